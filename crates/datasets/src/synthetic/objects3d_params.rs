//! The parameters of the `objects-3d` family ([`super::objects3d`]) and
//! their checks.

use serde::{Deserialize, Serialize};

use super::{bad, range};
use crate::DatasetError;

/// The most objects an `objects-3d` scene may have.
pub const MAX_OBJECTS_3D: usize = 8;

/// Relative frequencies of the objects' surfaces (need not sum to 1).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SurfaceMix {
    /// Points on the surface of an ellipsoid. Default 1.
    pub ellipsoids: f64,
    /// Points on a rectangular patch with a sinusoidal relief. Default 1.
    pub relief_planes: f64,
    /// Points on the six faces of a box. Default 1.
    pub boxes: f64,
}

impl Default for SurfaceMix {
    fn default() -> Self {
        Self {
            ellipsoids: 1.0,
            relief_planes: 1.0,
            boxes: 1.0,
        }
    }
}

/// Parameters of the `objects-3d` family
/// ([`super::generate_objects3d_scene`]). Ranges `[min, max]` are drawn
/// uniformly per scene (or per object) unless said otherwise; lengths are in
/// scene units. Every field has a serde default (the preset), so a TOML file
/// needs only the fields it changes.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Objects3dParams {
    /// Image width W, px. Default `[400, 1600]`.
    pub image_width: [u32; 2],
    /// Image height H, px. Default `[300, 1200]`.
    pub image_height: [u32; 2],
    /// Focal length as a multiple of max(W, H); the principal point is the
    /// image centre. Default `[0.6, 2.5]`.
    pub focal_factor: [f64; 2],
    /// Number of moving objects. Default `[1, 5]`.
    pub objects: [usize; 2],
    /// Probability that the scene has a static background (seen under the
    /// camera's motion). Default 0.5.
    pub background_probability: f64,
    /// Number of matches N, drawn log-uniformly (its lower end raised so
    /// that every motion can have `min_points`). Default `[100, 3000]`.
    pub size_range: [f64; 2],
    /// Share of N that is gross outliers. Default `[0, 0.4]`.
    pub outlier_share: [f64; 2],
    /// Fewest matches of a motion. Default 15.
    pub min_points: usize,
    /// Probability that an object other than the first is small: it gets a
    /// count drawn from `small_object_points` instead of a share of the
    /// rest. Default 0.3.
    pub small_object_probability: f64,
    /// Matches of a small object. Default `[15, 30]`.
    pub small_object_points: [usize; 2],
    /// The other motions share the remaining inliers in proportion to
    /// weights `exp(u)`, u uniform in `[−spread, spread]`, on top of
    /// `min_points` each. Default 2.
    pub weight_spread: f64,
    /// Mix of the objects' surfaces. Default ellipsoids, relief planes and
    /// boxes equally.
    pub surfaces: SurfaceMix,
    /// Depth of an object's centre in camera 1. Default `[3, 15]`.
    pub object_depth: [f64; 2],
    /// Projected diameter of an object's bounding sphere in image 1 as a
    /// fraction of min(W, H), drawn log-uniformly. Default `[0.05, 0.5]`.
    pub object_extent: [f64; 2],
    /// Rotation of an object between the views about an axis of uniform
    /// direction through its centre, degrees. Default `[5, 40]`.
    pub rotation_deg: [f64; 2],
    /// Translation of an object between the views (uniform direction) as a
    /// fraction of its depth. Default `[0.02, 0.2]`.
    pub translation: [f64; 2],
    /// Rotation of the camera between the views (uniform axis), degrees.
    /// Default `[0, 5]`.
    pub ego_rotation_deg: [f64; 2],
    /// Translation of the camera between the views (uniform direction).
    /// Default `[0.2, 1.0]`.
    pub ego_translation: [f64; 2],
    /// Depth of the background plane on the optical axis. Default `[20, 60]`.
    pub background_depth: [f64; 2],
    /// Tilt of the background plane's normal from the optical axis, degrees.
    /// Default `[0, 40]`.
    pub background_tilt_deg: [f64; 2],
    /// Amplitude of the background's relief as a fraction of its depth.
    /// Default `[0, 0.1]`.
    pub background_relief: [f64; 2],
    /// Pixel noise σ per coordinate. Default `[0.3, 1.2]`.
    pub noise_sigma: [f64; 2],
    /// Noise 4-vectors longer than this many σ are redrawn (≥ 1); noise-free
    /// points keep this far from the image border. Default 3.
    pub noise_truncation: f64,
    /// Distinct motions: at most `max_shared_share` of one motion's
    /// noise-free matches may lie within this Sampson distance (px) of
    /// another motion's true F. Default 2.5 (the default pipeline's inlier
    /// threshold).
    pub distinct_threshold_px: f64,
    /// See `distinct_threshold_px`. Default 0.5 (the median of the
    /// distances is at least the threshold).
    pub max_shared_share: f64,
}

impl Default for Objects3dParams {
    fn default() -> Self {
        Self {
            image_width: [400, 1600],
            image_height: [300, 1200],
            focal_factor: [0.6, 2.5],
            objects: [1, 5],
            background_probability: 0.5,
            size_range: [100.0, 3000.0],
            outlier_share: [0.0, 0.4],
            min_points: 15,
            small_object_probability: 0.3,
            small_object_points: [15, 30],
            weight_spread: 2.0,
            surfaces: SurfaceMix::default(),
            object_depth: [3.0, 15.0],
            object_extent: [0.05, 0.5],
            rotation_deg: [5.0, 40.0],
            translation: [0.02, 0.2],
            ego_rotation_deg: [0.0, 5.0],
            ego_translation: [0.2, 1.0],
            background_depth: [20.0, 60.0],
            background_tilt_deg: [0.0, 40.0],
            background_relief: [0.0, 0.1],
            noise_sigma: [0.3, 1.2],
            noise_truncation: 3.0,
            distinct_threshold_px: 2.5,
            max_shared_share: 0.5,
        }
    }
}

impl Objects3dParams {
    /// Checks every range and value; [`DatasetError::InvalidParams`] names
    /// the first offending field.
    pub fn validate(&self) -> Result<(), DatasetError> {
        self.validate_camera()?;
        self.validate_counts()?;
        self.validate_geometry()?;
        self.validate_noise()
    }

    /// The image sizes and the focal factor.
    fn validate_camera(&self) -> Result<(), DatasetError> {
        for (field, [lo, hi]) in [
            ("image_width", self.image_width),
            ("image_height", self.image_height),
        ] {
            if lo < 64 || lo > hi {
                return bad(field, format!("[{lo}, {hi}] needs 64 <= min <= max"));
            }
        }
        range("focal_factor", self.focal_factor, f64::MIN_POSITIVE)
    }

    /// Objects, N, outliers and the counts per motion.
    fn validate_counts(&self) -> Result<(), DatasetError> {
        let [lo, hi] = self.objects;
        if lo < 1 || lo > hi || hi > MAX_OBJECTS_3D {
            return bad(
                "objects",
                format!("[{lo}, {hi}] needs 1 <= min <= max <= {MAX_OBJECTS_3D}"),
            );
        }
        for (field, p) in [
            ("background_probability", self.background_probability),
            ("small_object_probability", self.small_object_probability),
        ] {
            if !(0.0..=1.0).contains(&p) {
                return bad(field, format!("{p} must be in [0, 1]"));
            }
        }
        range("size_range", self.size_range, 16.0)?;
        range("outlier_share", self.outlier_share, 0.0)?;
        if self.outlier_share[1] >= 0.9 {
            return bad(
                "outlier_share",
                format!("{} must be below 0.9", self.outlier_share[1]),
            );
        }
        if self.min_points < 8 {
            return bad("min_points", format!("{} must be >= 8", self.min_points));
        }
        let [s_lo, s_hi] = self.small_object_points;
        if s_lo < self.min_points || s_lo > s_hi {
            return bad(
                "small_object_points",
                format!("[{s_lo}, {s_hi}] needs min_points <= min <= max"),
            );
        }
        let most = self.min_points as f64 * (hi + 1) as f64 / (1.0 - self.outlier_share[1]);
        if most > self.size_range[1] {
            return bad(
                "size_range",
                format!(
                    "max {} leaves no room for {} motions of {} matches",
                    self.size_range[1],
                    hi + 1,
                    self.min_points
                ),
            );
        }
        if !(self.weight_spread.is_finite() && self.weight_spread >= 0.0) {
            return bad(
                "weight_spread",
                format!("{} must be finite and >= 0", self.weight_spread),
            );
        }
        Ok(())
    }

    /// The surfaces, the objects' and the camera's motions, the background.
    fn validate_geometry(&self) -> Result<(), DatasetError> {
        let w = [
            self.surfaces.ellipsoids,
            self.surfaces.relief_planes,
            self.surfaces.boxes,
        ];
        if w.iter().any(|v| !(v.is_finite() && *v >= 0.0)) || w.iter().sum::<f64>() <= 0.0 {
            return bad(
                "surfaces",
                format!("{w:?} must be >= 0 with a positive sum"),
            );
        }
        range("object_depth", self.object_depth, f64::MIN_POSITIVE)?;
        range("object_extent", self.object_extent, f64::MIN_POSITIVE)?;
        if self.object_extent[1] > 0.9 {
            return bad(
                "object_extent",
                format!("{} must be at most 0.9", self.object_extent[1]),
            );
        }
        range("rotation_deg", self.rotation_deg, 0.0)?;
        range("translation", self.translation, 0.0)?;
        range("ego_rotation_deg", self.ego_rotation_deg, 0.0)?;
        range("ego_translation", self.ego_translation, f64::MIN_POSITIVE)?;
        range("background_depth", self.background_depth, f64::MIN_POSITIVE)?;
        range("background_tilt_deg", self.background_tilt_deg, 0.0)?;
        if self.background_tilt_deg[1] > 60.0 {
            return bad(
                "background_tilt_deg",
                format!("{} must be at most 60", self.background_tilt_deg[1]),
            );
        }
        range("background_relief", self.background_relief, 0.0)?;
        if self.background_relief[1] >= 0.5 {
            return bad(
                "background_relief",
                format!("{} must be below 0.5", self.background_relief[1]),
            );
        }
        Ok(())
    }

    /// Noise and the distinctness rule.
    fn validate_noise(&self) -> Result<(), DatasetError> {
        range("noise_sigma", self.noise_sigma, 0.0)?;
        if !(self.noise_truncation.is_finite() && self.noise_truncation >= 1.0) {
            return bad(
                "noise_truncation",
                format!("{} must be finite and >= 1", self.noise_truncation),
            );
        }
        if !(self.distinct_threshold_px.is_finite() && self.distinct_threshold_px > 0.0) {
            return bad(
                "distinct_threshold_px",
                format!("{} must be finite and > 0", self.distinct_threshold_px),
            );
        }
        if !(self.max_shared_share > 0.0 && self.max_shared_share < 1.0) {
            return bad(
                "max_shared_share",
                format!("{} must be in (0, 1)", self.max_shared_share),
            );
        }
        Ok(())
    }
}
