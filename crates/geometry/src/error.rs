//! Error values of the geometry crate: bad input is reported, never panicked on.

use thiserror::Error;

/// Everything that can go wrong when building geometry inputs or estimating `F`.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum GeometryError {
    /// The two point lists have different lengths.
    #[error("point count mismatch: {points1} points in image 1, {points2} in image 2")]
    LengthMismatch { points1: usize, points2: usize },
    /// A coordinate is NaN or infinite.
    #[error("non-finite coordinate in {field} at index {index}")]
    NonFinite { field: &'static str, index: usize },
    /// A matrix entry is NaN or infinite.
    #[error("non-finite fundamental matrix entry at ({row}, {col})")]
    NonFiniteMatrix { row: usize, col: usize },
    /// The matrix is zero (no direction, so no epipolar geometry).
    #[error("fundamental matrix is zero")]
    ZeroMatrix,
    /// An estimator was given fewer points than it needs.
    #[error("too few points: {got} given, at least {needed} needed")]
    TooFewPoints { got: usize, needed: usize },
    /// The linear system has no unique solution (e.g. duplicate or collinear points).
    #[error("degenerate configuration: {0}")]
    Degenerate(&'static str),
    /// An index passed to a subset operation is out of range.
    #[error("index {index} out of range for {len} correspondences")]
    IndexOutOfRange { index: usize, len: usize },
}
