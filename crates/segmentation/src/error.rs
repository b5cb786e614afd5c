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
    Clustering(#[from] ClusteringError),
}
