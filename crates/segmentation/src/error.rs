//! Why an input could not be segmented at all.

use crate::ParamError;
use clustering::ClusteringError;
use geometry::GeometryError;
use thiserror::Error;

/// Why [`crate::segment`] (or one of its stages) refused its input. An input
/// that admits hypotheses but whose hypotheses are all rejected is not an
/// error: it gives an all-outlier [`crate::Segmentation`] saying why.
#[derive(Debug, Error)]
pub enum SegmentationError {
    /// A parameter is out of range.
    #[error(transparent)]
    InvalidParam(#[from] ParamError),
    /// The image size, principal point or focal prior is unusable.
    #[error("invalid input `{field}`: {message}")]
    InvalidCamera {
        /// The [`crate::Matches`] field.
        field: &'static str,
        /// What is wrong.
        message: String,
    },
    /// Fewer correspondences than one minimal sample.
    #[error("{n} correspondences, a minimal sample needs {needed}")]
    TooFewPoints {
        /// Correspondences in the input.
        n: usize,
        /// `mss_size`.
        needed: usize,
    },
    /// The correspondences are unusable (length mismatch, NaN).
    #[error("invalid correspondences: {0}")]
    InvalidPoints(#[source] GeometryError),
    /// Stages computed for another input or other parameters were combined.
    #[error("stages do not match: {0}")]
    StageMismatch(String),
    /// `focal_solver = "external"` needs the answers as data.
    #[error(
        "focal_solver = \"external\": pass the focal lengths as data \
         (HypothesisFocals::from_answers, then segment_with)"
    )]
    ExternalFocalsRequired,
    /// The clustering rejected its input.
    #[error("clustering: {0}")]
    Clustering(#[source] ClusteringError),
    /// Clustering would need more memory than [`crate::Params::max_memory_mb`].
    #[error(
        "{n_points} matches x {n_hypotheses} hypotheses would need about {required_mb} MB \
         to cluster, above max_memory_mb = {limit_mb}: lower num_samples or raise max_memory_mb"
    )]
    MemoryBound {
        /// Matches N.
        n_points: usize,
        /// Hypotheses M.
        n_hypotheses: usize,
        /// The estimate of [`clustering::required_memory`], MB (rounded up).
        required_mb: u64,
        /// The bound, MB.
        limit_mb: u64,
    },
    /// With `max_memory_mb = 0`, the estimated need of the whole run
    /// ([`crate::memory_need`]) exceeds the memory the machine has
    /// available ([`crate::available_memory`]).
    #[error(
        "{n_matches} matches ({n_clustered} clustered) x {n_hypotheses} hypotheses would need \
         about {needed_mb} MB (hypotheses {hypotheses_mb} MB, preferences and clustering \
         {clustering_mb} MB), but only {available_mb} MB are available (MemAvailable): use \
         fewer matches, cluster a subset (cluster_subset), lower num_samples, or set an explicit \
         max_memory_mb"
    )]
    MemoryAvailable {
        /// Matches N.
        n_matches: usize,
        /// Matches clustered ([`crate::SamplingParams::cluster_subset`], or N).
        n_clustered: usize,
        /// Hypotheses M.
        n_hypotheses: usize,
        /// The whole estimate, MB (rounded up).
        needed_mb: u64,
        /// Its hypotheses' part, MB.
        hypotheses_mb: u64,
        /// Its preferences' and clustering's part, MB.
        clustering_mb: u64,
        /// The memory available, MB (rounded down).
        available_mb: u64,
    },
    /// A coordinate is not finite or beyond [`crate::MAX_COORDINATE_PX`].
    #[error(
        "match row {row}, column {column}: coordinate {value:e} is not a finite number within \
         ±{bound:e} px"
    )]
    InvalidCoordinate {
        /// The match (0-based row of the input).
        row: usize,
        /// `x1`, `y1`, `x2` or `y2`.
        column: &'static str,
        /// The value.
        value: f64,
        /// [`crate::MAX_COORDINATE_PX`].
        bound: f64,
    },
    /// The caller's [`crate::Cancel`] was set; the work done so far is
    /// dropped.
    #[error("interrupted")]
    Interrupted,
    /// The model selection refused the clusters (`final_assignment = "nfa"`).
    #[error(transparent)]
    Selection(#[from] crate::selection::SelectionError),
}

impl From<ClusteringError> for SegmentationError {
    fn from(e: ClusteringError) -> Self {
        match e {
            ClusteringError::MemoryBound {
                n_points,
                n_hypotheses,
                required,
                limit,
            } => SegmentationError::MemoryBound {
                n_points,
                n_hypotheses,
                required_mb: required.div_ceil(1_000_000),
                limit_mb: limit / 1_000_000,
            },
            other => SegmentationError::Clustering(other),
        }
    }
}
