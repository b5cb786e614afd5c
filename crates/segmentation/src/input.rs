//! The input of a segmentation: matches in pixels and the camera priors.

use crate::SegmentationError;

/// Point matches between two images of one camera, in pixels, with the
/// image size, the principal point and the focal prior (docs/method.md "Input").
///
/// ```
/// let p1 = [[10.0, 20.0]; 8];
/// let p2 = [[11.0, 20.5]; 8];
/// let m = segmentation::Matches::new(&p1, &p2, (640, 480));
/// assert_eq!(m.principal_point, [319.5, 239.5]);
/// assert_eq!(m.focal_prior, 640.0);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Matches<'a> {
    /// Points in image 1, pixels (`x` right, `y` down).
    pub points1: &'a [[f64; 2]],
    /// The matching points in image 2, pixels.
    pub points2: &'a [[f64; 2]],
    /// Image size `(W, H)` in pixels.
    pub image_size: (u32, u32),
    /// Principal point in pixels. Default: the image centre
    /// `((W − 1)/2, (H − 1)/2)` ([`image_centre`]).
    pub principal_point: [f64; 2],
    /// Focal prior of the focal solvers (step 4), pixels. Default
    /// `max(W, H)`.
    pub focal_prior: f64,
}

/// The principal point assumed when no calibration is known: the image
/// centre `((W − 1)/2, (H − 1)/2)` in pixel-centre coordinates (docs/method.md,
/// "Input").
pub fn image_centre(image_size: (u32, u32)) -> [f64; 2] {
    [
        (f64::from(image_size.0) - 1.0) / 2.0,
        (f64::from(image_size.1) - 1.0) / 2.0,
    ]
}

impl<'a> Matches<'a> {
    /// Matches with the default principal point (the image centre) and focal
    /// prior (`max(W, H)`).
    pub fn new(points1: &'a [[f64; 2]], points2: &'a [[f64; 2]], image_size: (u32, u32)) -> Self {
        Self {
            points1,
            points2,
            image_size,
            principal_point: image_centre(image_size),
            focal_prior: f64::from(image_size.0.max(image_size.1)),
        }
    }

    /// The same matches with another principal point.
    pub fn with_principal_point(self, principal_point: [f64; 2]) -> Self {
        Self {
            principal_point,
            ..self
        }
    }

    /// The same matches with another focal prior.
    pub fn with_focal_prior(self, focal_prior: f64) -> Self {
        Self {
            focal_prior,
            ..self
        }
    }

    /// Number of matches N.
    pub fn len(&self) -> usize {
        self.points1.len()
    }

    /// True when there are no matches.
    pub fn is_empty(&self) -> bool {
        self.points1.is_empty()
    }

    /// Checks the camera fields: a non-empty image, a finite principal
    /// point and a finite focal prior `> 0` (the points are checked when
    /// the hypotheses are generated).
    pub fn validate(&self) -> Result<(), SegmentationError> {
        let invalid = |field, message: String| SegmentationError::InvalidCamera { field, message };
        let (w, h) = self.image_size;
        if w == 0 || h == 0 {
            return Err(invalid(
                "image_size",
                format!("must be positive, got {w} × {h}"),
            ));
        }
        if !self.principal_point.iter().all(|v| v.is_finite()) {
            return Err(invalid(
                "principal_point",
                format!("must be finite, got {:?}", self.principal_point),
            ));
        }
        if !(self.focal_prior.is_finite() && self.focal_prior > 0.0) {
            return Err(invalid(
                "focal_prior",
                format!("must be a finite number > 0, got {}", self.focal_prior),
            ));
        }
        Ok(())
    }
}
