//! Error values of the clustering crate: bad input is reported, never panicked on.

use thiserror::Error;

/// Everything that can go wrong when building a preference matrix.
///
/// Indices are 0-based: `point` is a row of the N × M preference matrix,
/// `hypothesis` a column.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ClusteringError {
    /// The inlier threshold τ of Eq. 38 (or of the J-Linkage test `r ≤ τ`) is
    /// not a finite positive number.
    #[error("invalid threshold tau = {0}: it must be finite and > 0")]
    InvalidTau(f64),
    /// A residual is NaN or negative (squared distances are `>= 0`; `+inf`
    /// is accepted and means "no preference").
    #[error("invalid residual {value} for point {point}, hypothesis {hypothesis}: residuals must be >= 0 and not NaN")]
    InvalidResidual {
        /// The point (row).
        point: usize,
        /// The hypothesis (column).
        hypothesis: usize,
        /// The offending value.
        value: f64,
    },
    /// A preference value given directly is NaN, infinite or outside `[0, 1]`.
    #[error("invalid preference {value} for point {point}, hypothesis {hypothesis}: preferences must lie in [0, 1]")]
    InvalidPreference {
        /// The point (row).
        point: usize,
        /// The hypothesis (column).
        hypothesis: usize,
        /// The offending value.
        value: f64,
    },
    /// One hypothesis's residual column does not have one value per point.
    #[error("hypothesis {hypothesis} has {got} residuals, expected one per point ({expected})")]
    ColumnLength {
        /// The hypothesis (column).
        hypothesis: usize,
        /// The length expected.
        expected: usize,
        /// The length given.
        got: usize,
    },
    /// A row of a row-major input does not have the length of the first row.
    #[error("point {point} has {got} values, expected {expected} (the length of the first row)")]
    RaggedRow {
        /// The point (row).
        point: usize,
        /// The length expected.
        expected: usize,
        /// The length given.
        got: usize,
    },
    /// More points than the clustering can index (cluster ids are `u32`, labels `i32`).
    #[error("{0} points: at most 2^31 - 1 points can be clustered")]
    TooManyPoints(usize),
    /// More hypotheses than a continuous preference matrix can index (`u32`).
    #[error("{0} hypotheses: at most 2^32 - 1 hypotheses are supported")]
    TooManyHypotheses(usize),
    /// The fraction of [`crate::SizeRule::RelativeMin`] is not in `[0, 1]`.
    #[error("invalid size_rule relative-min = {0}: the fraction of N must lie in [0, 1]")]
    InvalidRelativeMin(f64),
    /// The clustering would need more memory than `max_memory_bytes`.
    #[error("{n_points} points x {n_hypotheses} hypotheses would need about {} MB for the clustering, above max_memory_bytes = {} MB", required.div_ceil(1_000_000), limit / 1_000_000)]
    MemoryBound {
        /// Number of points N.
        n_points: usize,
        /// Number of hypotheses M.
        n_hypotheses: usize,
        /// The estimate of [`crate::required_memory`], bytes.
        required: u64,
        /// The bound, bytes.
        limit: u64,
    },
}
