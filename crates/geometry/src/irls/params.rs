//! The parameters of IRLS-Tukey ([`IrlsParams`]): the text's defaults and
//! the reference code's variants (see the module above).

use crate::GeometryError;
use serde::{Deserialize, Serialize};

/// Consistency constant of the MAD for Gaussian noise, `1 / Φ⁻¹(3/4)`
/// (Eq. 34): `σ ≈ 1.4826 · MAD`.
pub const MAD_TO_SIGMA: f64 = 1.4826;

/// How step 4 of the IRLS iteration refits `F` from the weighted inliers.
/// Written `"normalized"` or `"plain"` in configuration files.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum IrlsFit {
    /// The weighted 8-point on Hartley-normalised coordinates (weighted
    /// centroids and mean distances, [`crate::eight_point_weighted`]): the
    /// thesis text's refit. The default.
    #[default]
    Normalized,
    /// The weighted 8-point in the given (principal-point-centred) pixel
    /// coordinates, no normalisation ([`crate::eight_point_weighted_plain`]),
    /// then rank 2: the reference code's refit.
    Plain,
}

/// Parameters of the IRLS-Tukey refinement. Missing fields take the
/// defaults of thesis Table 1 (and the text's variant, see the [module
/// documentation](crate::irls)) when deserialised.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct IrlsParams {
    /// Inlier threshold on the Sampson distance, in px (`thr_px`); a match
    /// is an inlier when its squared Sampson distance is `≤ thr_px²` (and
    /// within the MAD bound of step 5). Default 2.5 (Table 1; the reference
    /// code uses 4.5 on AdelaideRMF).
    pub thr_px: f64,
    /// Maximum number of outer iterations (`irls_iters` in the configs,
    /// which is accepted as an alias). Default 5.
    #[serde(alias = "irls_iters")]
    pub max_iters: usize,
    /// Tukey biweight constant `c` (Eq. 33), in units of σ. Default 4.685
    /// (95 % efficiency under Gaussian noise).
    pub tukey_c: f64,
    /// Convergence threshold on `|old Δ new| / |old ∪ new|` of the inlier
    /// sets. Default 0.01 (1 %).
    pub min_change: f64,
    /// The refit of step 4 (`irls_fit` in the configs, accepted as an
    /// alias): `"normalized"` (default, the text) or `"plain"` (the
    /// reference code; also the start from the sample when no initial `F`
    /// is given).
    #[serde(alias = "irls_fit")]
    pub fit: IrlsFit,
    /// When the Tukey weights leave fewer than 8 positive weights, or the
    /// weighted system has a null space of dimension > 1, refit with unit
    /// weights on the current inliers. Default true (the rule this crate
    /// adds to the text). False is the reference code's rule: the weighted
    /// system is solved as it is, and a degenerate one fails the hypothesis
    /// with [`GeometryError::TooFewWeightedPoints`] or
    /// [`GeometryError::Degenerate`]. (The reference takes LAPACK's smallest
    /// singular vector of the singular `XᵀWX`, an arbitrary member of a
    /// solution space of dimension ≥ 2 chosen by rounding; it fits at most
    /// 7 weighted points and is not reproducible, so it is dropped here.)
    pub unit_weight_fallback: bool,
    /// Added to the robust scale of step 2, in px:
    /// `σ = 1.4826 · MAD + sigma_offset_px`. Default 0 (the text); the
    /// reference code adds 1e-12, which keeps the weights of residuals at
    /// the rounding level of an exact fit (below ~1e-12 px) positive.
    pub sigma_offset_px: f64,
    /// Polish the starting `F` on the sample before the first iteration by
    /// [`crate::polish_fundamental`] (PoseLib's `refine_fundamental`, as
    /// the reference code does). Default false (the text).
    pub polish: bool,
}

impl Default for IrlsParams {
    fn default() -> Self {
        Self {
            thr_px: 2.5,
            max_iters: 5,
            tukey_c: 4.685,
            min_change: 0.01,
            fit: IrlsFit::Normalized,
            unit_weight_fallback: true,
            sigma_offset_px: 0.0,
            polish: false,
        }
    }
}

impl IrlsParams {
    /// The reference code's variant of the refinement (see the [module
    /// documentation](crate::irls)): `fit = Plain`, `unit_weight_fallback = false`,
    /// `sigma_offset_px = 1e-12`, `polish = true`, the other fields at their
    /// defaults.
    pub fn reference_code() -> Self {
        Self {
            fit: IrlsFit::Plain,
            unit_weight_fallback: false,
            sigma_offset_px: 1e-12,
            polish: true,
            ..Self::default()
        }
    }

    /// Checks the ranges: `thr_px` finite and `> 0`, `max_iters ≥ 1`,
    /// `tukey_c` finite and `> 0`, `min_change` and `sigma_offset_px` finite
    /// and `≥ 0`.
    pub fn validate(&self) -> Result<(), GeometryError> {
        let invalid = |name, value, requirement| {
            Err(GeometryError::InvalidParameter {
                name,
                value,
                requirement,
            })
        };
        if !(self.thr_px.is_finite() && self.thr_px > 0.0) {
            return invalid("thr_px", self.thr_px, "must be finite and > 0");
        }
        if self.max_iters == 0 {
            return invalid("max_iters", 0.0, "must be >= 1");
        }
        if !(self.tukey_c.is_finite() && self.tukey_c > 0.0) {
            return invalid("tukey_c", self.tukey_c, "must be finite and > 0");
        }
        if !(self.min_change.is_finite() && self.min_change >= 0.0) {
            return invalid("min_change", self.min_change, "must be finite and >= 0");
        }
        if !(self.sigma_offset_px.is_finite() && self.sigma_offset_px >= 0.0) {
            return invalid(
                "sigma_offset_px",
                self.sigma_offset_px,
                "must be finite and >= 0",
            );
        }
        Ok(())
    }
}
