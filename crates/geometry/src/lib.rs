//! Two-view epipolar geometry for Algorithm 1 of the thesis.
//!
//! * [`Correspondences`] and [`FundamentalMatrix`]: checked input types.
//! * [`sampson`]: the Sampson (Eq. 23) and symmetric epipolar (Eq. 24)
//!   distances, single-point and batch forms, and the FROB distance (Eq. 45).
//! * [`eight_point`]: the 8-point algorithm (step 2) in pixel (plain) and
//!   Hartley-normalised coordinates, each unweighted or weighted, followed by
//!   rank-2 enforcement.
//! * [`irls`]: IRLS-Tukey refinement of a hypothesis (step 3, Section 5.2.1;
//!   Eqs. 33–34), with the reference code's variants as switches.
//! * [`polish`]: the reference code's nonlinear polish of a sample's F
//!   (PoseLib's `refine_fundamental`: Levenberg–Marquardt on the
//!   Cauchy-robust Sampson error).
//! * [`mod@five_point`]: the minimal relative-pose solver for hypothesis
//!   generation, returning every real essential matrix from 5 calibrated
//!   bearings (Nistér 2004).
//!
//! Convention everywhere: a match (x1 ↔ x2) satisfies `x2ᵀ F x1 = 0`, with
//! homogeneous pixel coordinates `x = (x, y, 1)`, `F` stored row-major in
//! the 8-point design rows.

#![warn(missing_docs)]

#[cfg(test)]
mod dense_poly;
pub mod eight_point;
pub mod error;
mod essential_system;
pub mod five_point;
pub mod irls;
mod linalg;
mod lu;
mod mad;
mod minimal;
pub mod polish;
mod poly;
pub mod sampson;
mod simd;
mod sturm;
pub mod types;

pub use eight_point::{
    eight_point_normalized, eight_point_plain, eight_point_weighted, eight_point_weighted_plain,
    enforce_rank2, MIN_POINTS, RANK_TOLERANCE,
};
pub use error::GeometryError;
pub use five_point::{five_point, FivePointRoots, FIVE_POINT_SAMPLE};
pub use irls::{
    median_absolute_deviation, median_in_place, refine_irls_tukey, tukey_weight, IrlsFit,
    IrlsParams, IrlsSummary, IrlsWorkspace, RefinedModel, MAD_TO_SIGMA,
};
pub use polish::{polish_fundamental, Polished, POLISH_LOSS_SCALE_PX, POLISH_MAX_ITERS};
pub use sampson::{
    frob_distance, sampson_consensus, sampson_distance, sampson_distance_signed,
    sampson_distance_squared, sampson_distances_squared, sampson_residuals_signed,
    symmetric_epipolar_distance, SampsonModels,
};
pub use types::{Correspondences, FundamentalMatrix};
