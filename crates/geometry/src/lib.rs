//! Two-view epipolar geometry for Algorithm 1 of the thesis.
//!
//! * [`Correspondences`] and [`FundamentalMatrix`]: checked input types.
//! * [`sampson`]: the Sampson (Eq. 23) and symmetric epipolar (Eq. 24)
//!   distances, single-point and batch forms, and the FROB distance (Eq. 45).
//!
//! Convention everywhere: a match (x1 ↔ x2) satisfies `x2ᵀ F x1 = 0`, with
//! homogeneous pixel coordinates `x = (x, y, 1)`.

pub mod error;
pub mod sampson;
pub mod types;

pub use error::GeometryError;
pub use sampson::{
    frob_distance, sampson_distance, sampson_distance_signed, sampson_distance_squared,
    sampson_distances_squared, symmetric_epipolar_distance,
};
pub use types::{Correspondences, FundamentalMatrix};
