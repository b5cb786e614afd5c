//! The parameters of the driving-scene generator (the `kitti-real` preset,
//! [`super::driving`]) and their checks.

use serde::{Deserialize, Serialize};

use super::{bad, range};
use crate::DatasetError;

/// The most moving cars a driving scene may have.
pub const MAX_CARS: usize = 4;

/// Parameters of the driving-scene generator ([`super::generate_driving_scene`]).
/// Ranges `[min, max]` are sampled uniformly; lengths are in metres, the
/// camera frame has x right, y down, z forward. Every field has a serde
/// default (the `kitti-real` preset), so a TOML file needs only the fields it
/// changes.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct DrivingParams {
    /// Image width W in pixels. Default 1242 (KITTI).
    pub image_width: u32,
    /// Image height H in pixels. Default 375 (KITTI).
    pub image_height: u32,
    /// Focal length range in pixels; the principal point is the image centre
    /// ((W−1)/2, (H−1)/2). Default `[720, 740]`.
    pub focal_range: [f64; 2],
    /// Total numbers of matches N: scene index i has `sizes[i % len]`, so
    /// every size appears in every split. Default `[1000, 2000, 3000, 5000]`.
    pub sizes: Vec<usize>,
    /// Share of the N matches on the static background. Default `[0.60, 0.75]`.
    pub background_share: [f64; 2],
    /// Share of the N matches that are gross outliers (a uniform pixel in
    /// each image). Default `[0.10, 0.15]`.
    pub outlier_share: [f64; 2],
    /// Fewest matches on each car, as a share of N. Default 0.05.
    pub min_car_share: f64,
    /// Height of the camera above the road. Default 1.65.
    pub camera_height: f64,
    /// Depth of background structure; below the horizon a point is on the
    /// road when that is nearer. Default `[8, 60]`.
    pub background_depth: [f64; 2],
    /// Forward distance the camera drives between the views. Default `[0.8, 1.5]`.
    pub ego_forward: [f64; 2],
    /// Heading change of the camera between the views, degrees, either
    /// sign (the camera moves along the chord of its arc). Default `[0, 2]`.
    pub ego_yaw_deg: [f64; 2],
    /// Car box: width, height, length. Default `[1.8, 1.5, 4.2]`.
    pub car_size: [f64; 3],
    /// Depth of a car's centre in view 1. Default `[10, 30]`.
    pub car_depth: [f64; 2],
    /// Lateral position of a car's centre in view 1. Default `[-6, 6]`.
    pub car_lateral: [f64; 2],
    /// Heading of a car relative to the optical axis, degrees. Default `[-15, 15]`.
    pub car_heading_deg: [f64; 2],
    /// Turn of a car between the views (about the vertical through its
    /// centre), degrees, either sign. Default `[4, 15]`.
    pub car_yaw_deg: [f64; 2],
    /// Tilt of a car's turn axis from the vertical, degrees, towards a
    /// uniform direction (road camber, pitching under braking; a turn about
    /// the exact vertical keeps every motion planar, and planar motions of
    /// points near the horizon are nearly indistinguishable by F).
    /// Default `[0, 30]`.
    pub car_axis_tilt_deg: [f64; 2],
    /// Sideways move of a car between the views (along its own x axis),
    /// either sign. Default `[0.3, 1.5]`.
    pub car_sideways: [f64; 2],
    /// Forward move of a car between the views (along its heading). Default `[-1, 2]`.
    pub car_forward: [f64; 2],
    /// Pixel noise σ per coordinate. Default 0.7.
    pub noise_sigma: f64,
    /// Noise 4-vectors longer than this many σ are redrawn (≥ 1); noise-free
    /// points keep this far from the image border, so no match leaves the
    /// image. Default 3.
    pub noise_truncation: f64,
    /// Least median Sampson distance (px, noise-free points) of a car's
    /// points to the background's true F and to every other car's, and of
    /// the other car's points to its F; a car failing it is redrawn.
    /// Default 8.
    pub min_separation_px: f64,
}

impl Default for DrivingParams {
    fn default() -> Self {
        Self {
            image_width: 1242,
            image_height: 375,
            focal_range: [720.0, 740.0],
            sizes: vec![1000, 2000, 3000, 5000],
            background_share: [0.60, 0.75],
            outlier_share: [0.10, 0.15],
            min_car_share: 0.05,
            camera_height: 1.65,
            background_depth: [8.0, 60.0],
            ego_forward: [0.8, 1.5],
            ego_yaw_deg: [0.0, 2.0],
            car_size: [1.8, 1.5, 4.2],
            car_depth: [10.0, 30.0],
            car_lateral: [-6.0, 6.0],
            car_heading_deg: [-15.0, 15.0],
            car_yaw_deg: [4.0, 15.0],
            car_axis_tilt_deg: [0.0, 30.0],
            car_sideways: [0.3, 1.5],
            car_forward: [-1.0, 2.0],
            noise_sigma: 0.7,
            noise_truncation: 3.0,
            min_separation_px: 8.0,
        }
    }
}

impl DrivingParams {
    /// Checks every range and value; [`DatasetError::InvalidParams`] names
    /// the first offending field.
    pub fn validate(&self) -> Result<(), DatasetError> {
        self.validate_camera()?;
        self.validate_counts()?;
        self.validate_motions()?;
        self.validate_noise()
    }

    /// The image, the focal length, the camera height and its motion.
    fn validate_camera(&self) -> Result<(), DatasetError> {
        if self.image_width < 64 || self.image_height < 64 {
            return bad(
                "image_width",
                format!(
                    "{} x {} is too small (64 x 64 at least)",
                    self.image_width, self.image_height
                ),
            );
        }
        range("focal_range", self.focal_range, f64::MIN_POSITIVE)?;
        positive("camera_height", self.camera_height)?;
        range("background_depth", self.background_depth, f64::MIN_POSITIVE)?;
        range("ego_forward", self.ego_forward, f64::MIN_POSITIVE)?;
        range("ego_yaw_deg", self.ego_yaw_deg, 0.0)
    }

    /// The sizes and the shares of background, outliers and cars.
    fn validate_counts(&self) -> Result<(), DatasetError> {
        if self.sizes.is_empty() || self.sizes.iter().any(|&n| n < 100) {
            return bad(
                "sizes",
                format!("{:?} must be a non-empty list of sizes >= 100", self.sizes),
            );
        }
        range("background_share", self.background_share, 0.0)?;
        range("outlier_share", self.outlier_share, 0.0)?;
        positive("min_car_share", self.min_car_share)?;
        let fixed = self.background_share[1] + self.outlier_share[1];
        if fixed + self.min_car_share > 1.0 {
            return bad(
                "min_car_share",
                format!(
                    "{} with background and outlier shares up to {fixed} leaves no room for one car",
                    self.min_car_share
                ),
            );
        }
        Ok(())
    }

    /// The cars' size, placement and motion.
    fn validate_motions(&self) -> Result<(), DatasetError> {
        for (i, &side) in self.car_size.iter().enumerate() {
            if !(side.is_finite() && side > 0.0) {
                return bad("car_size", format!("side {i} = {side} must be > 0"));
            }
        }
        range("car_depth", self.car_depth, f64::MIN_POSITIVE)?;
        range("car_lateral", self.car_lateral, f64::MIN)?;
        range("car_heading_deg", self.car_heading_deg, f64::MIN)?;
        range("car_yaw_deg", self.car_yaw_deg, 0.0)?;
        if self.car_yaw_deg[1] >= 90.0 {
            return bad(
                "car_yaw_deg",
                format!("{} must be below 90", self.car_yaw_deg[1]),
            );
        }
        range("car_axis_tilt_deg", self.car_axis_tilt_deg, 0.0)?;
        range("car_sideways", self.car_sideways, 0.0)?;
        range("car_forward", self.car_forward, f64::MIN)
    }

    /// The pixel noise and the separation threshold.
    fn validate_noise(&self) -> Result<(), DatasetError> {
        if !(self.noise_sigma.is_finite() && self.noise_sigma >= 0.0) {
            return bad(
                "noise_sigma",
                format!("{} must be finite and >= 0", self.noise_sigma),
            );
        }
        if !(self.noise_truncation.is_finite() && self.noise_truncation >= 1.0) {
            return bad(
                "noise_truncation",
                format!("{} must be finite and >= 1", self.noise_truncation),
            );
        }
        if !(self.min_separation_px.is_finite() && self.min_separation_px >= 0.0) {
            return bad(
                "min_separation_px",
                format!("{} must be finite and >= 0", self.min_separation_px),
            );
        }
        Ok(())
    }
}

/// A finite value > 0.
fn positive(field: &'static str, v: f64) -> Result<(), DatasetError> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        bad(field, format!("{v} must be finite and > 0"))
    }
}
