//! Parameters and answers of the robust focal solver (docs/method.md step 4):
//! the prior weights, the reference's weight sets, the failure policy and
//! the estimate.

use serde::{Deserialize, Serialize};

use crate::error::FocalFailure;

/// Weights of the deviation from the priors, `(w_f1, w_pp1, w_f2, w_pp2)`:
/// the objective is `w_f1 (f1 - f_prior)^2 + w_pp1 |pp1|^2 + w_f2 (f2 -
/// f_prior)^2 + w_pp2 |pp2|^2`, so each enters the step directions as `1/w`
/// (docs/method.md step 4).
///
/// Defaults (serde and [`Default`]): `(5e-4, 1, 5e-4, 1)`, PoseLib's.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct FocalWeights {
    /// Weight of the focal length of image 1. Default `5e-4`.
    pub f1: f64,
    /// Weight of the principal point of image 1 (both coordinates). Default `1`.
    pub pp1: f64,
    /// Weight of the focal length of image 2. Default `5e-4`.
    pub f2: f64,
    /// Weight of the principal point of image 2 (both coordinates). Default `1`.
    pub pp2: f64,
}

impl FocalWeights {
    /// The weight set `(w_f1, w_pp1, w_f2, w_pp2)`.
    pub const fn new(f1: f64, pp1: f64, f2: f64, pp2: f64) -> Self {
        Self { f1, pp1, f2, pp2 }
    }

    /// Per-unknown weights for `x = (f1, u1, v1, f2, u2, v2)`.
    pub(crate) fn per_unknown(&self) -> [f64; 6] {
        [self.f1, self.pp1, self.pp1, self.f2, self.pp2, self.pp2]
    }

    /// Every weight must be finite and positive.
    pub(crate) fn validate(&self) -> Result<(), FocalFailure> {
        for (name, value) in [
            ("w_f1", self.f1),
            ("w_pp1", self.pp1),
            ("w_f2", self.f2),
            ("w_pp2", self.pp2),
        ] {
            if !(value.is_finite() && value > 0.0) {
                return Err(FocalFailure::InvalidParameter {
                    name,
                    value,
                    requirement: "must be finite and > 0",
                });
            }
        }
        Ok(())
    }
}

impl Default for FocalWeights {
    fn default() -> Self {
        Self::new(5e-4, 1.0, 5e-4, 1.0)
    }
}

/// The weight sets the reference implementation tries on AdelaideRMF
/// (docs/method.md step 4, with `max_iters` 100).
pub const ADELAIDE_WEIGHT_SETS: [FocalWeights; 4] = [
    FocalWeights::new(1e-3, 1.0, 1e-3, 1.0),
    FocalWeights::new(5e-4, 1.0, 5e-4, 1.0),
    FocalWeights::new(1e-4, 1.0, 1e-4, 1.0),
    FocalWeights::new(5e-4, 2.0, 5e-4, 2.0),
];

/// The reference's `max_iters` with [`ADELAIDE_WEIGHT_SETS`].
pub const ADELAIDE_MAX_ITERS: usize = 100;

/// The weight sets the reference implementation tries on HOPE-F (docs/method.md
/// step 4, with `max_iters` 120): the AdelaideRMF four plus
/// `(1e-3, 2, 1e-3, 2)` and `(1e-4, 3, 1e-4, 3)`.
pub const HOPEF_WEIGHT_SETS: [FocalWeights; 6] = [
    FocalWeights::new(1e-3, 1.0, 1e-3, 1.0),
    FocalWeights::new(5e-4, 1.0, 5e-4, 1.0),
    FocalWeights::new(1e-4, 1.0, 1e-4, 1.0),
    FocalWeights::new(5e-4, 2.0, 5e-4, 2.0),
    FocalWeights::new(1e-3, 2.0, 1e-3, 2.0),
    FocalWeights::new(1e-4, 3.0, 1e-4, 3.0),
];

/// The reference's `max_iters` with [`HOPEF_WEIGHT_SETS`].
pub const HOPEF_MAX_ITERS: usize = 120;

/// Parameters of [`robust_focals`](crate::robust_focals).
///
/// Defaults (serde and [`Default`]): `f_prior` 1000 px, weights
/// `(5e-4, 1, 5e-4, 1)`, `max_iters` 50. In the pipeline `f_prior` is
/// `max(W, H)` of the images (docs/method.md, Input).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RobustFocalParams {
    /// Prior focal length of both images, px. Default 1000.
    pub f_prior: f64,
    /// Weights of the deviation from the priors. Default `(5e-4, 1, 5e-4, 1)`.
    pub weights: FocalWeights,
    /// The iteration stops after at most `max_iters + 1` steps. Default 50.
    pub max_iters: usize,
}

impl Default for RobustFocalParams {
    fn default() -> Self {
        Self {
            f_prior: 1000.0,
            weights: FocalWeights::default(),
            max_iters: 50,
        }
    }
}

/// What to do when the robust solver fails (docs/method.md step 4).
///
/// Serialised in lowercase: `"report"` or `"prior"`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum OnFailure {
    /// Report the failure as an error (the project's default).
    #[default]
    Report,
    /// Return the priors `f1 = f2 = f_prior`, `pp1 = pp2 = (0, 0)` with the
    /// iteration count used, as the reference implementation does.
    Prior,
}

/// An answer of the robust focal solver.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct FocalEstimate {
    /// Focal length of image 1, px. Only `f1^2` enters the model, so the sign
    /// carries no geometric meaning; it is reported as the iteration found it.
    pub f1: f64,
    /// Focal length of image 2, px (sign as for `f1`).
    pub f2: f64,
    /// Principal point of image 1 relative to the prior (0, 0), px.
    pub pp1: [f64; 2],
    /// Principal point of image 2 relative to the prior (0, 0), px.
    pub pp2: [f64; 2],
    /// The index k of the step at which the stopping rule fired (the first
    /// step is k = 0, and the rule is first checked at k = 1), or
    /// `max_iters + 1` when it never fired: PoseLib's reported count.
    pub iterations: usize,
    /// True when this is the prior returned for a failed solve
    /// ([`OnFailure::Prior`]).
    pub from_prior: bool,
}

impl FocalEstimate {
    /// `x = (f1, u1, v1, f2, u2, v2)`.
    pub fn unknowns(&self) -> [f64; 6] {
        [
            self.f1,
            self.pp1[0],
            self.pp1[1],
            self.f2,
            self.pp2[0],
            self.pp2[1],
        ]
    }

    /// The prior answer `f1 = f2 = f_prior`, principal points at the origin.
    pub fn prior(f_prior: f64, iterations: usize) -> Self {
        Self {
            f1: f_prior,
            f2: f_prior,
            pp1: [0.0; 2],
            pp2: [0.0; 2],
            iterations,
            from_prior: true,
        }
    }
}
