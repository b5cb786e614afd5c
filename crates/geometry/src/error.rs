//! Error values of the geometry crate: bad input is reported, never panicked on.

use thiserror::Error;

/// Everything that can go wrong when building geometry inputs or estimating `F`.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum GeometryError {
    /// The two point lists have different lengths.
    #[error("point count mismatch: {points1} points in image 1, {points2} in image 2")]
    LengthMismatch {
        /// Number of points in image 1.
        points1: usize,
        /// Number of points in image 2.
        points2: usize,
    },
    /// A coordinate is NaN or infinite.
    #[error("non-finite coordinate in {field} at index {index}")]
    NonFinite {
        /// The coordinate column: `x1`, `y1`, `x2` or `y2`.
        field: &'static str,
        /// Index of the correspondence.
        index: usize,
    },
    /// A matrix entry is NaN or infinite.
    #[error("non-finite fundamental matrix entry at ({row}, {col})")]
    NonFiniteMatrix {
        /// Row of the entry.
        row: usize,
        /// Column of the entry.
        col: usize,
    },
    /// The matrix is zero (no direction, so no epipolar geometry).
    #[error("fundamental matrix is zero")]
    ZeroMatrix,
    /// An estimator was given fewer points than it needs.
    #[error("too few points: {got} given, at least {needed} needed")]
    TooFewPoints {
        /// Number of points given.
        got: usize,
        /// Number of points needed.
        needed: usize,
    },
    /// The linear system has no unique solution (e.g. duplicate or collinear points).
    #[error("degenerate configuration: {0}")]
    Degenerate(&'static str),
    /// An index passed to a subset operation is out of range.
    #[error("index {index} out of range for {len} correspondences")]
    IndexOutOfRange {
        /// The offending index.
        index: usize,
        /// Number of correspondences.
        len: usize,
    },
    /// The weight vector of the weighted 8-point does not have one weight per
    /// correspondence.
    #[error("weight count mismatch: {weights} weights for {points} correspondences")]
    WeightCountMismatch {
        /// Number of weights given.
        weights: usize,
        /// Number of correspondences.
        points: usize,
    },
    /// A weight is negative, NaN or infinite.
    #[error("invalid weight {value} at index {index}: weights must be finite and >= 0")]
    InvalidWeight {
        /// Index of the weight.
        index: usize,
        /// Its value.
        value: f64,
    },
    /// Fewer correspondences than the estimator needs carry a positive weight.
    #[error("too few positively weighted points: {got} given, at least {needed} needed")]
    TooFewWeightedPoints {
        /// Number of positive weights.
        got: usize,
        /// Number needed.
        needed: usize,
    },
    /// A refinement left fewer inliers than a fundamental matrix needs.
    #[error("too few inliers after IRLS iteration {iteration}: {got}, at least {needed} needed")]
    TooFewInliers {
        /// Number of inliers left.
        got: usize,
        /// Number needed.
        needed: usize,
        /// The iteration (1-based) after which they were counted.
        iteration: usize,
    },
    /// A parameter is outside its valid range.
    #[error("invalid parameter {name} = {value}: {requirement}")]
    InvalidParameter {
        /// Name of the parameter, as in the configuration files.
        name: &'static str,
        /// Its value.
        value: f64,
        /// The valid range, in words.
        requirement: &'static str,
    },
    /// A minimal solver was given a sample of the wrong size.
    #[error("minimal solver needs exactly {needed} correspondences, {got} given")]
    SampleSize {
        /// Number of correspondences given.
        got: usize,
        /// Number the solver needs.
        needed: usize,
    },
    /// A bearing vector of the 5-point solver is zero.
    #[error("zero bearing vector in image {image} at index {index}")]
    ZeroBearing {
        /// The image, 1 or 2.
        image: usize,
        /// Index of the correspondence.
        index: usize,
    },
    /// An intermediate quantity overflowed (coordinates too large for f64).
    #[error("non-finite value in {0} (coordinates too large)")]
    Overflow(&'static str),
}
