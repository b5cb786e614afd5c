//! [`Scene`]: the one input type of the pipeline (docs/method.md, "Input").

use crate::DatasetError;
use nalgebra::Matrix3;
use std::collections::BTreeSet;

/// Ground-truth label of a match whose truth is not known (the word
/// `unknown` in a user match file, see [`crate::user`]): neither the outlier
/// label 0 nor a motion, and far from the predicted outlier −1. Such matches
/// are segmented but not scored (docs/method.md, "Metrics").
pub const UNKNOWN_LABEL: i32 = i32::MIN;

/// Fewest correspondences a scene may have: one minimal sample of the
/// 8-point algorithm (Algorithm 1, step 1).
pub const MIN_POINTS: usize = 8;

/// One two-view scene: N point correspondences `points1[i] ↔ points2[i]` in
/// pixels, with optional ground truth.
///
/// Conventions: pixel coordinates as stored by the dataset (x right, y
/// down); a ground-truth fundamental matrix satisfies `x2ᵀ F x1 = 0` for
/// homogeneous pixel coordinates `x = (x, y, 1)`; labels are 0 for a gross
/// outlier and 1..k for the k rigid motions.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// Scene name (AdelaideRMF: file stem; HOPE-F: `<k>/<NNNN>`).
    pub name: String,
    /// Points in image 1, pixels.
    pub points1: Vec<[f64; 2]>,
    /// Points in image 2, pixels.
    pub points2: Vec<[f64; 2]>,
    /// Ground-truth labels: 0 = outlier, 1..k = motion, [`UNKNOWN_LABEL`]
    /// = not known.
    pub labels: Option<Vec<i32>>,
    /// Image size `(W, H)` in pixels.
    pub image_size: (u32, u32),
    /// Principal point in pixels: HOPE-F `(K[0,2], K[1,2])`; AdelaideRMF and
    /// user data `((W-1)/2, (H-1)/2)` (docs/method.md, "Input").
    pub principal_point: [f64; 2],
    /// Ground-truth focal length in pixels, when known (HOPE-F `K[0,0]`).
    pub true_focal: Option<f64>,
    /// Ground-truth fundamental matrix of each motion, in label order
    /// (`gt_fundamentals[j - 1]` belongs to label `j`); empty when unknown.
    pub gt_fundamentals: Vec<Matrix3<f64>>,
    /// The two images, when the dataset ships them.
    pub images: Option<(image::RgbImage, image::RgbImage)>,
}

/// The principal point assumed when no calibration is known: the image
/// centre `((W-1)/2, (H-1)/2)` in pixel-centre coordinates (docs/method.md,
/// "Input").
///
/// ```
/// assert_eq!(datasets::centre_principal_point((640, 480)), [319.5, 239.5]);
/// ```
pub fn centre_principal_point(image_size: (u32, u32)) -> [f64; 2] {
    [
        (f64::from(image_size.0) - 1.0) / 2.0,
        (f64::from(image_size.1) - 1.0) / 2.0,
    ]
}

impl Scene {
    /// Number of correspondences N.
    pub fn len(&self) -> usize {
        self.points1.len()
    }

    /// True when the scene has no correspondences.
    pub fn is_empty(&self) -> bool {
        self.points1.is_empty()
    }

    /// The focal prior `f_prior = max(W, H)` in pixels (docs/method.md, "Input";
    /// the prior of the focal solvers in Algorithm 1, step 4).
    ///
    /// ```
    /// # let scene = datasets::synthetic::generate_scene(
    /// #     &datasets::synthetic::SyntheticParams::default(), 7, 1, "s").unwrap();
    /// assert_eq!(scene.image_size, (1024, 768));
    /// assert_eq!(scene.focal_prior(), 1024.0);
    /// ```
    pub fn focal_prior(&self) -> f64 {
        f64::from(self.image_size.0.max(self.image_size.1))
    }

    /// Number of motions: the distinct labels > 0 (0 when unlabelled).
    pub fn num_motions(&self) -> usize {
        self.labels
            .as_ref()
            .map(|l| l.iter().filter(|&&x| x > 0).collect::<BTreeSet<_>>().len())
            .unwrap_or(0)
    }

    /// Number of gross outliers: labels equal to 0 (0 when unlabelled).
    pub fn num_outliers(&self) -> usize {
        self.labels
            .as_ref()
            .map(|l| l.iter().filter(|&&x| x == 0).count())
            .unwrap_or(0)
    }

    /// Number of matches whose ground truth is [`UNKNOWN_LABEL`] (0 when
    /// unlabelled).
    pub fn num_unknown(&self) -> usize {
        self.labels
            .as_ref()
            .map(|l| l.iter().filter(|&&x| x == UNKNOWN_LABEL).count())
            .unwrap_or(0)
    }

    /// Checks the invariants every loader guarantees: equal lengths of
    /// `points1`, `points2` and `labels`; N ≥ [`MIN_POINTS`]; finite
    /// coordinates; labels ≥ 0 or [`UNKNOWN_LABEL`] and, when ground-truth
    /// matrices are given, no label above their count; a non-zero image
    /// size; finite principal point and matrices; a positive finite true
    /// focal; images, if any, of the stated size.
    ///
    /// The error is [`DatasetError::InvalidScene`] naming the scene, the
    /// field and the index (loaders add the file with
    /// [`DatasetError::in_file`]).
    ///
    /// ```
    /// use datasets::Scene;
    /// let mut scene = Scene {
    ///     name: "tiny".into(),
    ///     points1: vec![[1.0, 2.0]; 8],
    ///     points2: vec![[3.0, 4.0]; 8],
    ///     labels: Some(vec![1; 8]),
    ///     image_size: (640, 480),
    ///     principal_point: datasets::centre_principal_point((640, 480)),
    ///     true_focal: None,
    ///     gt_fundamentals: vec![],
    ///     images: None,
    /// };
    /// assert!(scene.validate().is_ok());
    /// scene.points2[3][1] = f64::NAN;
    /// let err = scene.validate().unwrap_err().to_string();
    /// assert_eq!(err, "scene `tiny`: field `points2` at index 3: non-finite coordinate");
    /// ```
    pub fn validate(&self) -> Result<(), DatasetError> {
        self.validate_lengths()?;
        self.validate_coordinates()?;
        self.validate_labels()?;
        self.validate_camera()?;
        self.validate_images()
    }

    /// The [`DatasetError::InvalidScene`] of this scene.
    fn invalid(&self, field: &'static str, index: Option<usize>, problem: String) -> DatasetError {
        DatasetError::InvalidScene {
            path: None,
            scene: self.name.clone(),
            field,
            index,
            problem,
        }
    }

    /// Equal lengths of `points1`, `points2`, `labels`; N ≥ [`MIN_POINTS`].
    fn validate_lengths(&self) -> Result<(), DatasetError> {
        let err = |field, index, problem| self.invalid(field, index, problem);
        let n = self.points1.len();
        if self.points2.len() != n {
            return Err(err(
                "points2",
                None,
                format!("{} points, points1 has {n}", self.points2.len()),
            ));
        }
        if let Some(labels) = &self.labels {
            if labels.len() != n {
                return Err(err(
                    "labels",
                    None,
                    format!("{} labels for {n} points", labels.len()),
                ));
            }
        }
        if n < MIN_POINTS {
            return Err(err(
                "points1",
                None,
                format!("{n} correspondences, at least {MIN_POINTS} needed"),
            ));
        }
        Ok(())
    }

    /// Finite coordinates in both images.
    fn validate_coordinates(&self) -> Result<(), DatasetError> {
        for (field, points) in [("points1", &self.points1), ("points2", &self.points2)] {
            if let Some(i) = points
                .iter()
                .position(|p| !p[0].is_finite() || !p[1].is_finite())
            {
                return Err(self.invalid(field, Some(i), "non-finite coordinate".to_string()));
            }
        }
        Ok(())
    }

    /// Labels ≥ 0 or [`UNKNOWN_LABEL`] and, with ground-truth matrices, none
    /// above their count.
    fn validate_labels(&self) -> Result<(), DatasetError> {
        let err = |field, index, problem| self.invalid(field, index, problem);
        if let Some(labels) = &self.labels {
            if let Some(i) = labels.iter().position(|&l| l < 0 && l != UNKNOWN_LABEL) {
                return Err(err(
                    "labels",
                    Some(i),
                    format!("negative label {}", labels[i]),
                ));
            }
            let k = self.gt_fundamentals.len();
            if k > 0 {
                if let Some(i) = labels
                    .iter()
                    .position(|&l| l != UNKNOWN_LABEL && l as usize > k)
                {
                    return Err(err(
                        "labels",
                        Some(i),
                        format!("label {} but only {k} ground-truth matrices", labels[i]),
                    ));
                }
            }
        }
        Ok(())
    }

    /// A non-empty image, a finite principal point, a positive finite true
    /// focal and finite ground-truth matrices.
    fn validate_camera(&self) -> Result<(), DatasetError> {
        let err = |field, index, problem| self.invalid(field, index, problem);
        if self.image_size.0 == 0 || self.image_size.1 == 0 {
            return Err(err(
                "image_size",
                None,
                format!("{} x {} is empty", self.image_size.0, self.image_size.1),
            ));
        }
        if !self.principal_point.iter().all(|c| c.is_finite()) {
            return Err(err("principal_point", None, "non-finite".to_string()));
        }
        if let Some(f) = self.true_focal {
            if !(f.is_finite() && f > 0.0) {
                return Err(err(
                    "true_focal",
                    None,
                    format!("{f} is not a positive number"),
                ));
            }
        }
        if let Some(j) = self
            .gt_fundamentals
            .iter()
            .position(|f| !f.iter().all(|v| v.is_finite()))
        {
            return Err(err(
                "gt_fundamentals",
                Some(j),
                "non-finite entry".to_string(),
            ));
        }
        Ok(())
    }

    /// Images, if any, of the stated size.
    fn validate_images(&self) -> Result<(), DatasetError> {
        if let Some((a, b)) = &self.images {
            for (i, img) in [a, b].into_iter().enumerate() {
                if img.dimensions() != self.image_size {
                    return Err(self.invalid(
                        "images",
                        Some(i),
                        format!(
                            "image is {:?}, scene says {:?}",
                            img.dimensions(),
                            self.image_size
                        ),
                    ));
                }
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scene() -> Scene {
        Scene {
            name: "t".into(),
            points1: (0..10).map(|i| [i as f64, 1.0]).collect(),
            points2: (0..10).map(|i| [i as f64, 2.0]).collect(),
            labels: Some(vec![0, 1, 1, 2, 2, 2, 0, 1, 2, 1]),
            image_size: (100, 50),
            principal_point: centre_principal_point((100, 50)),
            true_focal: Some(80.0),
            gt_fundamentals: vec![Matrix3::identity(); 2],
            images: None,
        }
    }

    #[test]
    fn counts() {
        let s = scene();
        assert_eq!(s.len(), 10);
        assert_eq!(s.num_motions(), 2);
        assert_eq!(s.num_outliers(), 2);
        assert_eq!(s.focal_prior(), 100.0);
        assert!(s.validate().is_ok());
    }

    /// An unknown label is valid and counted apart; the label next to it,
    /// -1, is not a spelling of it.
    #[test]
    fn unknown_labels_are_valid_and_counted() {
        let mut s = scene();
        s.labels.as_mut().unwrap()[7] = UNKNOWN_LABEL;
        assert!(s.validate().is_ok());
        assert_eq!(s.num_unknown(), 1);
        assert_eq!((s.num_motions(), s.num_outliers()), (2, 2));
        s.labels.as_mut().unwrap()[7] = UNKNOWN_LABEL + 1;
        assert!(s.validate().is_err());
    }

    #[test]
    fn each_invariant_is_checked() {
        type Mutation = Box<dyn Fn(&mut Scene)>;
        let cases: Vec<(Mutation, &str)> = vec![
            (
                Box::new(|s| s.points2.pop().map(|_| ()).unwrap()),
                "field `points2`: 9 points, points1 has 10",
            ),
            (
                Box::new(|s| s.labels.as_mut().unwrap().push(1)),
                "field `labels`: 11 labels for 10 points",
            ),
            (
                Box::new(|s| {
                    s.points1.truncate(7);
                    s.points2.truncate(7);
                    s.labels = None;
                }),
                "field `points1`: 7 correspondences, at least 8 needed",
            ),
            (
                Box::new(|s| s.points1[4][0] = f64::INFINITY),
                "field `points1` at index 4: non-finite coordinate",
            ),
            (
                Box::new(|s| s.labels.as_mut().unwrap()[6] = -1),
                "field `labels` at index 6: negative label -1",
            ),
            (
                Box::new(|s| s.labels.as_mut().unwrap()[2] = 3),
                "field `labels` at index 2: label 3 but only 2 ground-truth matrices",
            ),
            (
                Box::new(|s| s.image_size = (0, 5)),
                "field `image_size`: 0 x 5 is empty",
            ),
            (
                Box::new(|s| s.principal_point[1] = f64::NAN),
                "field `principal_point`: non-finite",
            ),
            (
                Box::new(|s| s.true_focal = Some(-3.0)),
                "field `true_focal`: -3 is not a positive number",
            ),
            (
                Box::new(|s| s.gt_fundamentals[1][(0, 0)] = f64::NAN),
                "field `gt_fundamentals` at index 1: non-finite entry",
            ),
            (
                Box::new(|s| {
                    s.images = Some((image::RgbImage::new(100, 50), image::RgbImage::new(99, 50)))
                }),
                "field `images` at index 1: image is (99, 50), scene says (100, 50)",
            ),
        ];
        for (mutate, expected) in cases {
            let mut s = scene();
            mutate(&mut s);
            let msg = s.validate().unwrap_err().to_string();
            assert_eq!(msg, format!("scene `t`: {expected}"));
        }
    }

    #[test]
    fn in_file_names_the_file() {
        let mut s = scene();
        s.points1[0][1] = f64::NAN;
        let msg = s
            .validate()
            .unwrap_err()
            .in_file(std::path::Path::new("/data/x.mat"))
            .to_string();
        assert_eq!(
            msg,
            "/data/x.mat: scene `t`: field `points1` at index 0: non-finite coordinate"
        );
    }
}

/// What a loader reads besides the correspondences (shared by every loader
/// that can find images next to the matches).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LoadOptions {
    /// Decode the image pair into [`Scene::images`] when the source has one
    /// (AdelaideRMF's `img1`/`img2`, HOPE-F's `render0.png`/`render1.png`).
    /// The image size is read either way.
    pub images: bool,
}

impl Default for LoadOptions {
    /// Images included when present.
    fn default() -> Self {
        Self { images: true }
    }
}
