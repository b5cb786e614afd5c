//! The parameters of the `driving-random` family ([`super::driving_random`])
//! and their checks.

use serde::{Deserialize, Serialize};

use super::{bad, range, DrivingParams};
use crate::DatasetError;

/// The most movers a `driving-random` scene may have.
pub const MAX_MOVERS: usize = 3;

/// Parameters of the `driving-random` family
/// ([`super::generate_driving_random_scene`]). Every difficulty is drawn
/// per scene from its range; the camera, background and car geometry are
/// the `kitti-real` preset's ([`DrivingParams`], field `geometry`). Lengths in metres; every
/// field has a serde default (the preset), so a TOML file needs only the
/// fields it changes.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct DrivingRandomParams {
    /// Number of matches N, drawn log-uniformly. Default `[200, 20000]`.
    pub size_range: [f64; 2],
    /// Number of independently moving cars, drawn uniformly. Default `[0, 3]`.
    pub movers: [usize; 2],
    /// Share of N of each mover, drawn uniformly (its lower end raised to
    /// `min_mover_points / N` when that is larger). Default `[0.02, 0.30]`.
    pub mover_share: [f64; 2],
    /// Fewest matches a mover may have (a minimal sample of the 8-point
    /// algorithm and a few more). Default 10.
    pub min_mover_points: usize,
    /// The movers' shares are redrawn, all together, while the background
    /// would keep less than this share of N. Default 0.2.
    pub min_background_share: f64,
    /// Share of N that is gross outliers, drawn uniformly. Default `[0, 0.30]`.
    pub outlier_share: [f64; 2],
    /// Pixel noise σ per coordinate, drawn uniformly. Default `[0.3, 1.5]`.
    pub noise_sigma: [f64; 2],
    /// Noise 4-vectors longer than this many σ are redrawn (≥ 1). Default 3.
    pub noise_truncation: f64,
    /// A mover's separation: the median Sampson distance (px) of its
    /// noise-free matches to the background's true F, drawn log-uniformly.
    /// Default `[0.5, 20]`.
    pub separation_px: [f64; 2],
    /// Relative tolerance within which a mover's separation meets the drawn
    /// one. Default 0.01.
    pub separation_tolerance: f64,
    /// The camera (image 1242 × 375, focal 720–740 px, principal point at
    /// the centre), its height, the background's depth, the ego-motion and
    /// the cars' size, pose and motion direction: the `kitti-real` preset's
    /// fields of the same names (a `[geometry]` table in TOML). Default
    /// [`DrivingParams::default`]; its `sizes`, shares, noise and
    /// `min_separation_px` are not used.
    pub geometry: DrivingParams,
}

impl Default for DrivingRandomParams {
    fn default() -> Self {
        Self {
            size_range: [200.0, 20_000.0],
            movers: [0, MAX_MOVERS],
            mover_share: [0.02, 0.30],
            min_mover_points: 10,
            min_background_share: 0.2,
            outlier_share: [0.0, 0.30],
            noise_sigma: [0.3, 1.5],
            noise_truncation: 3.0,
            separation_px: [0.5, 20.0],
            separation_tolerance: 0.01,
            geometry: DrivingParams::default(),
        }
    }
}

impl DrivingRandomParams {
    /// Checks every range and value; [`DatasetError::InvalidParams`] names
    /// the first offending field.
    pub fn validate(&self) -> Result<(), DatasetError> {
        self.validate_counts()?;
        self.validate_difficulty()?;
        self.geometry_for(self.noise_sigma[1]).validate()
    }

    /// N, the movers and the shares.
    fn validate_counts(&self) -> Result<(), DatasetError> {
        range("size_range", self.size_range, 100.0)?;
        let [lo, hi] = self.movers;
        if lo > hi || hi > MAX_MOVERS {
            return bad(
                "movers",
                format!("[{lo}, {hi}] needs min <= max <= {MAX_MOVERS}"),
            );
        }
        range("mover_share", self.mover_share, f64::MIN_POSITIVE)?;
        range("outlier_share", self.outlier_share, 0.0)?;
        if self.min_mover_points < 8 {
            return bad(
                "min_mover_points",
                format!("{} must be >= 8", self.min_mover_points),
            );
        }
        let floor = (self.min_mover_points as f64 / self.size_range[0]).max(self.mover_share[0]);
        let worst = self.outlier_share[1] + hi as f64 * floor + self.min_background_share;
        if !(0.0..1.0).contains(&self.min_background_share) || worst > 1.0 {
            return bad(
                "min_background_share",
                format!(
                    "{} with {hi} movers of at least {floor} and outliers up to {} exceeds N",
                    self.min_background_share, self.outlier_share[1]
                ),
            );
        }
        Ok(())
    }

    /// Noise and separation.
    fn validate_difficulty(&self) -> Result<(), DatasetError> {
        range("noise_sigma", self.noise_sigma, 0.0)?;
        if !(self.noise_truncation.is_finite() && self.noise_truncation >= 1.0) {
            return bad(
                "noise_truncation",
                format!("{} must be finite and >= 1", self.noise_truncation),
            );
        }
        range("separation_px", self.separation_px, f64::MIN_POSITIVE)?;
        if !(self.separation_tolerance > 0.0 && self.separation_tolerance < 0.5) {
            return bad(
                "separation_tolerance",
                format!("{} must be in (0, 0.5)", self.separation_tolerance),
            );
        }
        Ok(())
    }

    /// The `kitti-real` generator's parameters for the camera, the
    /// background and the cars of a scene with noise `sigma` (which sets the
    /// margin noise-free points keep from the image border).
    pub(super) fn geometry_for(&self, sigma: f64) -> DrivingParams {
        DrivingParams {
            noise_sigma: sigma,
            noise_truncation: self.noise_truncation,
            ..self.geometry.clone()
        }
    }
}
