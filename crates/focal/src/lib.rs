#![warn(missing_docs)]
//! Focal lengths of two views from their fundamental matrix, and the
//! scene-level focal consensus that filters fundamental-matrix hypotheses
//! (docs/method.md steps 4–6).
//!
//! - [`bougnoux`]: Bougnoux's closed form (Bougnoux 1998), which can give
//!   `f^2 < 0` ([`FocalFailure::NoRealFocal`]).
//! - [`robust_focals`]: the robust iterative solver of Kocur, Kyselica and
//!   Kukelova (CVPR 2024). Each step solves the two Kruppa constraints on a
//!   2-D plane of unknowns exactly: on the plane (parametrised by an
//!   orthonormal basis) the constraints are two bivariate quartics, whose
//!   real solutions are all found by eliminating one variable (the Bezout
//!   resultant, a degree-16 polynomial, interpolated at the 32nd roots of
//!   unity), finding its roots by the Aberth–Ehrlich iteration, completing
//!   each near-real root with the common root of the two quartics (the null
//!   vector of their Bezout matrix) and polishing every candidate pair with
//!   Newton's method on the 2x2 system; the
//!   solution with the smallest `|l1| + |l2|` in the step multipliers is
//!   taken.
//!   [`robust_focals_multi_start`] is the reference's multi-start rule;
//!   [`OnFailure`] chooses between reporting failures and the reference's
//!   prior-returning behaviour.
//! - [`passes_local_test`] (Eq. 36), [`focal_consensus`] (the KDE of
//!   Eq. 37, with scipy-compatible [`find_peaks`]) and [`band_indices`]
//!   (the band of Eq. 37).
//!
//! All pixel coordinates have the principal point at the origin
//! (`x2^T F x1 = 0`); `f1` belongs to image 1 (the `x1` side), `f2` to
//! image 2.

#![deny(unsafe_code)]

mod aberth;
mod bezout;
mod bivariate;
mod bougnoux;
mod consensus;
mod error;
mod kruppa;
mod multi_start;
mod params;
mod peaks;
mod resultant;
mod robust;
mod simd;
#[cfg(test)]
mod test_support;

pub use bougnoux::{bougnoux, bougnoux_per_image};
pub use consensus::{
    band_indices, focal_consensus, gaussian_kde, kde_bandwidth, linspace, median_sorted,
    passes_local_test, percentile_sorted, within_band, ConsensusParams, FocalConsensus,
};
pub use error::FocalFailure;
pub use kruppa::{kruppa_residuals, relative_kruppa_residual, KRUPPA_TOLERANCE};
pub use multi_start::robust_focals_multi_start;
pub use params::{
    FocalEstimate, FocalWeights, OnFailure, RobustFocalParams, ADELAIDE_MAX_ITERS,
    ADELAIDE_WEIGHT_SETS, HOPEF_MAX_ITERS, HOPEF_WEIGHT_SETS,
};
pub use peaks::{find_peaks, Peaks};
pub use robust::{apply_on_failure, robust_focals, robust_focals_or};
