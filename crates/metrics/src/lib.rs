#![warn(missing_docs)]
//! Per-scene evaluation metrics of a segmentation (docs/method.md, "Metrics").
//!
//! Label conventions follow the evaluation protocol:
//! - predicted labels: [`PREDICTED_OUTLIER`] (−1) marks a point rejected as an
//!   outlier, any id `>= 0` names a predicted cluster (ids are arbitrary);
//! - ground-truth labels: [`GROUND_TRUTH_OUTLIER`] (0) marks a gross outlier,
//!   ids `>= 1` name rigid motions; [`GROUND_TRUTH_UNKNOWN`] marks a point
//!   whose truth is not known, which [`KnownMetrics`] leaves out (every
//!   other function refuses it as a negative label).
//!
//! The Hungarian matchings use the Jonker–Volgenant solver of the `lsap`
//! crate (a port of `scipy.optimize.linear_sum_assignment`), with cluster ids
//! sorted ascending on both sides, so that ties between equally good
//! matchings are broken exactly as the reference evaluation breaks them.
//!
//! ```
//! use metrics::ClusteringMetrics;
//!
//! let gt = [1, 1, 1, 2, 2, 2, 0];
//! let pred = [7, 7, 7, 3, 3, -1, -1];
//! let m = ClusteringMetrics::compute(&pred, &gt).unwrap();
//! assert!((m.me - 1.0 / 6.0).abs() < 1e-12); // one inlier rejected
//! assert!((m.acc - 5.0 / 6.0).abs() < 1e-12);
//! assert_eq!(m.pur, 1.0); // every predicted cluster is pure
//! ```

mod frob;
mod information;
mod known;
mod labels;
mod matching;

pub use frob::frob_score;
pub use information::{adjusted_rand_index, normalized_mutual_info};
pub use known::KnownMetrics;
pub use matching::{
    false_negative_rate, misclassification_error, misclassification_error_all, purity,
};

use serde::{Deserialize, Serialize};
use thiserror::Error;

use information::{ari_unchecked, nmi_unchecked};
use labels::validate;
use matching::{fnr_unchecked, me_all_unchecked, me_unchecked, purity_unchecked};

/// Predicted label of a point rejected as an outlier.
pub const PREDICTED_OUTLIER: i32 = -1;

/// Ground-truth label of a gross outlier.
pub const GROUND_TRUTH_OUTLIER: i32 = 0;

/// Ground-truth label of a point whose truth is not known (equal to
/// `datasets::UNKNOWN_LABEL`, the word `unknown` in a user match file):
/// scored by [`KnownMetrics`], which leaves such points out.
pub const GROUND_TRUTH_UNKNOWN: i32 = i32::MIN;

/// Why a pair of label vectors cannot be scored.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum MetricsError {
    /// The two label vectors do not label the same points.
    #[error("label vectors differ in length: {predicted} predicted labels, {ground_truth} ground-truth labels")]
    LengthMismatch {
        /// Number of predicted labels.
        predicted: usize,
        /// Number of ground-truth labels.
        ground_truth: usize,
    },
    /// A predicted label below −1.
    #[error("predicted label {label} at index {index} is invalid: predicted labels are -1 (outlier) or >= 0")]
    InvalidPredictedLabel {
        /// Position of the label (0-based).
        index: usize,
        /// The offending value.
        label: i32,
    },
    /// A negative ground-truth label.
    #[error("ground-truth label {label} at index {index} is invalid: ground-truth labels are 0 (outlier) or >= 1")]
    InvalidGroundTruthLabel {
        /// Position of the label (0-based).
        index: usize,
        /// The offending value.
        label: i32,
    },
}

/// Every label-based metric of docs/method.md "Metrics" for one scene, as
/// fractions in [0, 1] (ARI may be negative).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ClusteringMetrics {
    /// Misclassification error, see [`misclassification_error`].
    pub me: f64,
    /// Misclassification error over all points, outliers a class of their
    /// own, see [`misclassification_error_all`].
    pub me_all: f64,
    /// Accuracy, ACC = 1 − ME.
    pub acc: f64,
    /// False-negative rate, see [`false_negative_rate`].
    pub fnr: f64,
    /// Purity, see [`purity`].
    pub pur: f64,
    /// Adjusted Rand index, see [`adjusted_rand_index`].
    pub ari: f64,
    /// Normalised mutual information, see [`normalized_mutual_info`].
    pub nmi: f64,
}

impl ClusteringMetrics {
    /// Computes ME, ME over all points, ACC = 1 − ME, FNR, PUR, ARI and NMI of `pred` against
    /// `gt` (docs/method.md "Metrics").
    ///
    /// # Errors
    /// [`MetricsError`] when the lengths differ or a label is out of range.
    ///
    /// ```
    /// use metrics::ClusteringMetrics;
    ///
    /// // The same partition under other ids is a perfect segmentation.
    /// let m = ClusteringMetrics::compute(&[5, 5, 9, 9, -1], &[1, 1, 2, 2, 0]).unwrap();
    /// assert_eq!((m.me, m.acc, m.fnr, m.pur, m.ari), (0.0, 1.0, 0.0, 1.0, 1.0));
    /// assert!((m.nmi - 1.0).abs() < 1e-12);
    ///
    /// assert!(ClusteringMetrics::compute(&[1, 2], &[1]).is_err());
    /// ```
    pub fn compute(pred: &[i32], gt: &[i32]) -> Result<Self, MetricsError> {
        validate(pred, gt)?;
        let me = me_unchecked(pred, gt);
        Ok(Self {
            me,
            me_all: me_all_unchecked(pred, gt),
            acc: 1.0 - me,
            fnr: fnr_unchecked(pred, gt),
            pur: purity_unchecked(pred, gt),
            ari: ari_unchecked(pred, gt),
            nmi: nmi_unchecked(pred, gt),
        })
    }
}
