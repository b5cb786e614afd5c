//! The metrics over the points whose ground truth is known: a benchmark whose
//! labels were transferred from a sparser annotation marks the others
//! [`GROUND_TRUTH_UNKNOWN`] (docs/method.md, "Metrics").

use crate::{ClusteringMetrics, MetricsError, GROUND_TRUTH_UNKNOWN};

/// [`ClusteringMetrics`] over the known points, with the counts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KnownMetrics {
    /// The metrics of the known points; `None` when no point is known.
    pub metrics: Option<ClusteringMetrics>,
    /// Points whose ground truth is known (scored).
    pub known: usize,
    /// Points whose ground truth is [`GROUND_TRUTH_UNKNOWN`] (not scored).
    pub unknown: usize,
}

impl KnownMetrics {
    /// [`ClusteringMetrics::compute`] on the points whose ground truth is not
    /// [`GROUND_TRUTH_UNKNOWN`], both protocols included (ME with
    /// ground-truth outliers excluded, ME over all known points with
    /// outliers a class). An unknown point's prediction is neither right nor
    /// wrong: the result equals that of the vectors with those points
    /// removed.
    ///
    /// # Errors
    /// [`MetricsError`] when the lengths differ or a known or predicted
    /// label is out of range.
    ///
    /// ```
    /// use metrics::{ClusteringMetrics, KnownMetrics, GROUND_TRUTH_UNKNOWN as U};
    ///
    /// let k = KnownMetrics::compute(&[0, 0, -1, 1, 1], &[1, 1, U, 2, U]).unwrap();
    /// assert_eq!((k.known, k.unknown), (3, 2));
    /// assert_eq!(k.metrics, Some(ClusteringMetrics::compute(&[0, 0, 1], &[1, 1, 2]).unwrap()));
    /// ```
    pub fn compute(pred: &[i32], gt: &[i32]) -> Result<Self, MetricsError> {
        if pred.len() != gt.len() {
            return Err(MetricsError::LengthMismatch {
                predicted: pred.len(),
                ground_truth: gt.len(),
            });
        }
        let (known_pred, known_gt): (Vec<i32>, Vec<i32>) = pred
            .iter()
            .zip(gt)
            .filter(|(_, &g)| g != GROUND_TRUTH_UNKNOWN)
            .map(|(&p, &g)| (p, g))
            .unzip();
        let metrics = if known_gt.is_empty() {
            None
        } else {
            Some(ClusteringMetrics::compute(&known_pred, &known_gt)?)
        };
        Ok(Self {
            metrics,
            known: known_gt.len(),
            unknown: gt.len() - known_gt.len(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{misclassification_error, misclassification_error_all, MetricsError};

    const U: i32 = GROUND_TRUTH_UNKNOWN;

    /// Inserting unknown points, whatever their predictions, changes no
    /// metric; scoring them as outliers or as a motion would.
    #[test]
    fn unknown_points_change_nothing() {
        let pred = [3, 3, 3, -1, 5, 5, 5, -1, 3];
        let gt = [1, 1, 1, 1, 2, 2, 2, 0, 0];
        let base = ClusteringMetrics::compute(&pred, &gt).unwrap();
        for extra_pred in [-1, 3, 5, 9] {
            let mut p = pred.to_vec();
            let mut g = gt.to_vec();
            for at in [0, 4, 9, 11] {
                p.insert(at, extra_pred);
                g.insert(at, U);
            }
            let k = KnownMetrics::compute(&p, &g).unwrap();
            assert_eq!(k.metrics, Some(base), "unknowns predicted {extra_pred}");
            assert_eq!((k.known, k.unknown), (9, 4));
            // Counted as outliers, the same predictions would move ME over
            // all points; counted as motion 1, the thesis's ME.
            let as_outliers: Vec<i32> = g.iter().map(|&l| if l == U { 0 } else { l }).collect();
            let as_motion: Vec<i32> = g.iter().map(|&l| if l == U { 1 } else { l }).collect();
            let moved = misclassification_error_all(&p, &as_outliers).unwrap() != base.me_all
                || misclassification_error(&p, &as_motion).unwrap() != base.me;
            assert!(moved, "unknowns predicted {extra_pred}");
        }
    }

    #[test]
    fn all_unknown_scores_nothing_and_bad_labels_are_errors() {
        let k = KnownMetrics::compute(&[0, -1], &[U, U]).unwrap();
        assert_eq!((k.metrics, k.known, k.unknown), (None, 0, 2));
        assert_eq!(
            KnownMetrics::compute(&[0], &[U, 1]),
            Err(MetricsError::LengthMismatch {
                predicted: 1,
                ground_truth: 2
            })
        );
        // -1 is not "unknown" in the ground truth: still refused.
        assert!(matches!(
            KnownMetrics::compute(&[0, 0], &[1, -1]),
            Err(MetricsError::InvalidGroundTruthLabel { label: -1, .. })
        ));
    }
}
