#![warn(missing_docs)]
//! Per-scene evaluation metrics of a segmentation (method.md, "Metrics").
//!
//! Label conventions follow the evaluation protocol:
//! - predicted labels: [`PREDICTED_OUTLIER`] (−1) marks a point rejected as an
//!   outlier, any id `>= 0` names a predicted cluster (ids are arbitrary);
//! - ground-truth labels: [`GROUND_TRUTH_OUTLIER`] (0) marks a gross outlier,
//!   ids `>= 1` name rigid motions.
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

use std::collections::BTreeMap;

use geometry::frob_distance;
use nalgebra::Matrix3;
use serde::{Deserialize, Serialize};
use thiserror::Error;

/// Predicted label of a point rejected as an outlier.
pub const PREDICTED_OUTLIER: i32 = -1;

/// Ground-truth label of a gross outlier.
pub const GROUND_TRUTH_OUTLIER: i32 = 0;

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

/// Every label-based metric of method.md "Metrics" for one scene, as
/// fractions in [0, 1] (ARI may be negative).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ClusteringMetrics {
    /// Misclassification error, see [`misclassification_error`].
    pub me: f64,
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
    /// Computes ME, ACC = 1 − ME, FNR, PUR, ARI and NMI of `pred` against
    /// `gt` (method.md "Metrics").
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
            acc: 1.0 - me,
            fnr: fnr_unchecked(pred, gt),
            pur: purity_unchecked(pred, gt),
            ari: ari_unchecked(pred, gt),
            nmi: nmi_unchecked(pred, gt),
        })
    }
}

/// Misclassification error (method.md "Metrics", ME).
///
/// Over the points whose ground truth is not 0 (count `N_in`), predicted
/// clusters (ids ≠ −1) are matched one-to-one to ground-truth motions by the
/// Hungarian algorithm maximising the number of agreeing points; a point
/// predicted −1 is always wrong. `ME = 1 − matched / N_in`.
/// Returns 0.0 when no point is a ground-truth inlier and 1.0 when every
/// inlier is predicted −1.
///
/// # Errors
/// [`MetricsError`] when the lengths differ or a label is out of range.
///
/// ```
/// use metrics::misclassification_error;
///
/// // Cluster 4 covers motion 1 and motion 2 in part; one point of motion 2 is rejected.
/// let me = misclassification_error(&[4, 4, 4, 4, -1], &[1, 1, 2, 2, 2]).unwrap();
/// assert!((me - 3.0 / 5.0).abs() < 1e-15);
/// ```
pub fn misclassification_error(pred: &[i32], gt: &[i32]) -> Result<f64, MetricsError> {
    validate(pred, gt)?;
    Ok(me_unchecked(pred, gt))
}

/// False-negative rate (method.md "Metrics", FNR).
///
/// Predicted clusters are matched one-to-one to ground-truth ids (0
/// included) by the Hungarian algorithm maximising agreement over the points
/// whose prediction is `>= 0`. `FNR = 1 − (ground-truth inliers whose
/// predicted cluster is matched to their own id) / (ground-truth inliers)`.
/// Returns 0.0 without ground-truth inliers and 1.0 when every point is
/// predicted −1.
///
/// # Errors
/// [`MetricsError`] when the lengths differ or a label is out of range.
///
/// ```
/// use metrics::false_negative_rate;
///
/// // Cluster 3 is matched to the outliers (id 0), so the motion-1 point in it is missed.
/// let fnr = false_negative_rate(&[3, 3, 3, 8, 8], &[0, 0, 1, 1, 1]).unwrap();
/// assert!((fnr - 1.0 / 3.0).abs() < 1e-15);
/// ```
pub fn false_negative_rate(pred: &[i32], gt: &[i32]) -> Result<f64, MetricsError> {
    validate(pred, gt)?;
    Ok(fnr_unchecked(pred, gt))
}

/// Purity (method.md "Metrics", PUR).
///
/// Over the points whose prediction is `>= 0`: the sum over predicted
/// clusters of the largest ground-truth class count in the cluster (class 0
/// included), divided by the number of such points. Returns 0.0 when every
/// point is predicted −1.
///
/// # Errors
/// [`MetricsError`] when the lengths differ or a label is out of range.
///
/// ```
/// use metrics::purity;
///
/// let pur = purity(&[0, 0, 0, 1, -1], &[1, 1, 2, 2, 2]).unwrap();
/// assert!((pur - 3.0 / 4.0).abs() < 1e-15);
/// ```
pub fn purity(pred: &[i32], gt: &[i32]) -> Result<f64, MetricsError> {
    validate(pred, gt)?;
    Ok(purity_unchecked(pred, gt))
}

/// Adjusted Rand index over all points, −1 and 0 taken as ordinary classes
/// (method.md "Metrics", ARI; Hubert–Arabie adjustment as scikit-learn's
/// `adjusted_rand_score`).
///
/// With the pair-confusion counts `tp` (pairs together in both labellings),
/// `fp`, `fn` (together in only one) and `tn` (apart in both):
/// `ARI = 2 (tp·tn − fn·fp) / ((tp + fn)(fn + tn) + (tp + fp)(fp + tn))`,
/// and 1.0 when `fn = fp = 0` (identical partitions, or fewer than two points).
///
/// # Errors
/// [`MetricsError`] when the lengths differ or a label is out of range.
///
/// ```
/// use metrics::adjusted_rand_index;
///
/// assert_eq!(adjusted_rand_index(&[0, 0, 1, 1], &[1, 1, 2, 2]).unwrap(), 1.0);
/// assert_eq!(adjusted_rand_index(&[0, 1, 0, 1], &[1, 1, 2, 2]).unwrap(), -0.5);
/// ```
pub fn adjusted_rand_index(pred: &[i32], gt: &[i32]) -> Result<f64, MetricsError> {
    validate(pred, gt)?;
    Ok(ari_unchecked(pred, gt))
}

/// Normalised mutual information over all points, −1 and 0 taken as ordinary
/// classes, with arithmetic-mean normalisation (method.md "Metrics", NMI;
/// as scikit-learn's `normalized_mutual_info_score`).
///
/// `NMI = I(U; V) / ((H(U) + H(V)) / 2)` with natural logarithms. As in
/// scikit-learn: 1.0 when both labellings have a single class (or no
/// points), 0.0 when the mutual information is 0 (in particular when exactly
/// one side has a single class).
///
/// # Errors
/// [`MetricsError`] when the lengths differ or a label is out of range.
///
/// ```
/// use metrics::normalized_mutual_info;
///
/// assert!((normalized_mutual_info(&[3, 3, 4, 4], &[1, 1, 2, 2]).unwrap() - 1.0).abs() < 1e-15);
/// assert_eq!(normalized_mutual_info(&[3, 3, 3, 3], &[1, 1, 2, 2]).unwrap(), 0.0);
/// assert_eq!(normalized_mutual_info(&[3, 3, 3], &[1, 1, 1]).unwrap(), 1.0);
/// ```
pub fn normalized_mutual_info(pred: &[i32], gt: &[i32]) -> Result<f64, MetricsError> {
    validate(pred, gt)?;
    Ok(nmi_unchecked(pred, gt))
}

/// FROB score (Eq. 45): the mean Frobenius distance between matched
/// fundamental matrices.
///
/// Each cost is `min(‖Fa/‖Fa‖ − Fb/‖Fb‖‖, ‖Fa/‖Fa‖ + Fb/‖Fb‖‖)`
/// ([`geometry::frob_distance`]); predicted and ground-truth matrices are
/// assigned one-to-one by the Hungarian algorithm minimising the total cost
/// (rectangular: `min(P, G)` pairs), and the score is the mean of the
/// assigned costs. The caller fits the matrices (8-point on each predicted
/// cluster and on each ground-truth motion with at least 8 points).
///
/// Returns `None` when FROB is undefined: either side empty, or a matrix
/// with zero norm or non-finite entries (its distance is not a number).
///
/// ```
/// use metrics::frob_score;
/// use nalgebra::Matrix3;
///
/// let a = Matrix3::new(0.0, -1.0, 0.5, 1.0, 0.0, -0.2, -0.5, 0.2, 0.0);
/// let b = Matrix3::new(0.3, 0.0, 1.0, 0.0, 0.0, 2.0, -1.0, -2.0, 0.0);
/// // Scale and sign are irrelevant, the order of the matrices too.
/// let score = frob_score(&[-2.0 * b, 5.0 * a], &[a, b]).unwrap();
/// assert!(score < 1e-12);
/// assert_eq!(frob_score(&[], &[a]), None);
/// ```
pub fn frob_score(predicted: &[Matrix3<f64>], ground_truth: &[Matrix3<f64>]) -> Option<f64> {
    if predicted.is_empty() || ground_truth.is_empty() {
        return None;
    }
    let costs: Vec<f64> = predicted
        .iter()
        .flat_map(|fa| ground_truth.iter().map(move |fb| frob_distance(fa, fb)))
        .collect();
    if costs.iter().any(|c| !c.is_finite()) {
        return None;
    }
    let pairs = optimal_assignment(predicted.len(), ground_truth.len(), &costs, false);
    let total: f64 = pairs
        .iter()
        .map(|&(r, c)| costs[r * ground_truth.len() + c])
        .sum();
    Some(total / pairs.len() as f64)
}

fn validate(pred: &[i32], gt: &[i32]) -> Result<(), MetricsError> {
    if pred.len() != gt.len() {
        return Err(MetricsError::LengthMismatch {
            predicted: pred.len(),
            ground_truth: gt.len(),
        });
    }
    if let Some((index, &label)) = pred
        .iter()
        .enumerate()
        .find(|(_, &l)| l < PREDICTED_OUTLIER)
    {
        return Err(MetricsError::InvalidPredictedLabel { index, label });
    }
    if let Some((index, &label)) = gt
        .iter()
        .enumerate()
        .find(|(_, &l)| l < GROUND_TRUTH_OUTLIER)
    {
        return Err(MetricsError::InvalidGroundTruthLabel { index, label });
    }
    Ok(())
}

/// Sorted distinct values.
fn sorted_ids(labels: impl Iterator<Item = i32>) -> Vec<i32> {
    let mut ids: Vec<i32> = labels.collect();
    ids.sort_unstable();
    ids.dedup();
    ids
}

/// Agreement counts `C[i][j] = #{(p, g) : p = rows[i], g = cols[j]}` over
/// `pairs`, flattened row-major; pairs whose ids are absent are skipped.
fn agreement_counts(pairs: &[(i32, i32)], rows: &[i32], cols: &[i32]) -> Vec<f64> {
    let mut counts = vec![0.0; rows.len() * cols.len()];
    for &(p, g) in pairs {
        if let (Ok(i), Ok(j)) = (rows.binary_search(&p), cols.binary_search(&g)) {
            counts[i * cols.len() + j] += 1.0;
        }
    }
    counts
}

/// Hungarian assignment on a row-major `rows x cols` matrix of finite
/// costs, as `(row, column)` pairs.
fn optimal_assignment(
    rows: usize,
    cols: usize,
    costs: &[f64],
    maximize: bool,
) -> Vec<(usize, usize)> {
    let (r, c) = lsap::solve(rows, cols, &costs.to_vec(), maximize)
        .expect("a finite rectangular cost matrix always has a complete assignment");
    r.into_iter().zip(c).collect()
}

fn me_unchecked(pred: &[i32], gt: &[i32]) -> f64 {
    let inliers: Vec<(i32, i32)> = pred
        .iter()
        .zip(gt)
        .filter(|(_, &g)| g != GROUND_TRUTH_OUTLIER)
        .map(|(&p, &g)| (p, g))
        .collect();
    if inliers.is_empty() {
        return 0.0;
    }
    let pids = sorted_ids(
        inliers
            .iter()
            .map(|&(p, _)| p)
            .filter(|&p| p != PREDICTED_OUTLIER),
    );
    if pids.is_empty() {
        return 1.0;
    }
    let gids = sorted_ids(inliers.iter().map(|&(_, g)| g));
    let counts = agreement_counts(&inliers, &pids, &gids);
    let matched: f64 = optimal_assignment(pids.len(), gids.len(), &counts, true)
        .iter()
        .map(|&(i, j)| counts[i * gids.len() + j])
        .sum();
    1.0 - matched / inliers.len() as f64
}

fn fnr_unchecked(pred: &[i32], gt: &[i32]) -> f64 {
    let inlier_count = gt.iter().filter(|&&g| g != GROUND_TRUTH_OUTLIER).count();
    if inlier_count == 0 {
        return 0.0;
    }
    let clustered: Vec<(i32, i32)> = pred
        .iter()
        .zip(gt)
        .filter(|(&p, _)| p >= 0)
        .map(|(&p, &g)| (p, g))
        .collect();
    if clustered.is_empty() {
        return 1.0;
    }
    let pids = sorted_ids(clustered.iter().map(|&(p, _)| p));
    let gids = sorted_ids(clustered.iter().map(|&(_, g)| g));
    let counts = agreement_counts(&clustered, &pids, &gids);
    let matched_id: BTreeMap<i32, i32> = optimal_assignment(pids.len(), gids.len(), &counts, true)
        .into_iter()
        .map(|(i, j)| (pids[i], gids[j]))
        .collect();
    let recovered = clustered
        .iter()
        .filter(|&&(p, g)| g != GROUND_TRUTH_OUTLIER && matched_id.get(&p) == Some(&g))
        .count();
    1.0 - recovered as f64 / inlier_count as f64
}

fn purity_unchecked(pred: &[i32], gt: &[i32]) -> f64 {
    let mut cells: BTreeMap<(i32, i32), usize> = BTreeMap::new();
    let mut clustered = 0usize;
    for (&p, &g) in pred.iter().zip(gt) {
        if p >= 0 {
            *cells.entry((p, g)).or_default() += 1;
            clustered += 1;
        }
    }
    if clustered == 0 {
        return 0.0;
    }
    let mut largest: BTreeMap<i32, usize> = BTreeMap::new();
    for (&(p, _), &count) in &cells {
        let best = largest.entry(p).or_default();
        *best = (*best).max(count);
    }
    largest.values().sum::<usize>() as f64 / clustered as f64
}

/// Non-zero cells of the contingency table between `gt` (rows) and `pred`
/// (columns), keyed by (row index, column index) into the sorted ids.
struct Contingency {
    cells: BTreeMap<(usize, usize), u64>,
    row_sums: Vec<u64>,
    col_sums: Vec<u64>,
}

impl Contingency {
    fn new(pred: &[i32], gt: &[i32]) -> Self {
        let classes = sorted_ids(gt.iter().copied());
        let clusters = sorted_ids(pred.iter().copied());
        let mut cells: BTreeMap<(usize, usize), u64> = BTreeMap::new();
        let mut row_sums = vec![0u64; classes.len()];
        let mut col_sums = vec![0u64; clusters.len()];
        for (p, g) in pred.iter().zip(gt) {
            let (Ok(i), Ok(j)) = (classes.binary_search(g), clusters.binary_search(p)) else {
                continue;
            };
            *cells.entry((i, j)).or_default() += 1;
            row_sums[i] += 1;
            col_sums[j] += 1;
        }
        Self {
            cells,
            row_sums,
            col_sums,
        }
    }
}

fn ari_unchecked(pred: &[i32], gt: &[i32]) -> f64 {
    let table = Contingency::new(pred, gt);
    let n = pred.len() as i128;
    let sum_squares: i128 = table
        .cells
        .values()
        .map(|&c| (c as i128) * (c as i128))
        .sum();
    let together_in_pred: i128 = table
        .cells
        .iter()
        .map(|(&(_, j), &c)| c as i128 * table.col_sums[j] as i128)
        .sum();
    let together_in_gt: i128 = table
        .cells
        .iter()
        .map(|(&(i, _), &c)| c as i128 * table.row_sums[i] as i128)
        .sum();
    let tp = sum_squares - n;
    let fp = together_in_pred - sum_squares;
    let fn_ = together_in_gt - sum_squares;
    let tn = n * n - fp - fn_ - sum_squares;
    if fn_ == 0 && fp == 0 {
        return 1.0;
    }
    let numerator = tp * tn - fn_ * fp;
    let denominator = (tp + fn_) * (fn_ + tn) + (tp + fp) * (fp + tn);
    2.0 * numerator as f64 / denominator as f64
}

/// Entropy (natural log) of a labelling given its class sizes; 0.0 for a
/// single class.
fn entropy(class_sizes: &[u64]) -> f64 {
    if class_sizes.len() <= 1 {
        return 0.0;
    }
    let total = class_sizes.iter().sum::<u64>() as f64;
    let log_total = total.ln();
    -class_sizes
        .iter()
        .map(|&c| (c as f64 / total) * ((c as f64).ln() - log_total))
        .sum::<f64>()
}

fn nmi_unchecked(pred: &[i32], gt: &[i32]) -> f64 {
    let table = Contingency::new(pred, gt);
    let (classes, clusters) = (table.row_sums.len(), table.col_sums.len());
    if (classes == 1 && clusters == 1) || (classes == 0 && clusters == 0) {
        return 1.0;
    }
    if classes == 1 || clusters == 1 {
        return 0.0;
    }
    let total = pred.len() as f64;
    let log_total = total.ln();
    let log_row_total = (table.row_sums.iter().sum::<u64>() as f64).ln();
    let log_col_total = (table.col_sums.iter().sum::<u64>() as f64).ln();
    let mi: f64 = table
        .cells
        .iter()
        .map(|(&(i, j), &c)| {
            let c = c as f64;
            let p_ij = c / total;
            let outer = (table.row_sums[i] * table.col_sums[j]) as f64;
            let log_outer = -outer.ln() + log_row_total + log_col_total;
            let term = p_ij * (c.ln() - log_total) + p_ij * log_outer;
            if term.abs() < f64::EPSILON {
                0.0
            } else {
                term
            }
        })
        .sum::<f64>()
        .max(0.0);
    if mi == 0.0 {
        return 0.0;
    }
    let normalizer = (entropy(&table.row_sums) + entropy(&table.col_sums)) / 2.0;
    mi / normalizer
}

#[cfg(test)]
mod tests {
    use super::*;

    /// ME by brute force: the best agreement over every injective map from
    /// predicted clusters to ground-truth motions.
    fn me_brute_force(pred: &[i32], gt: &[i32]) -> f64 {
        let inliers: Vec<(i32, i32)> = pred
            .iter()
            .zip(gt)
            .filter(|(_, &g)| g != 0)
            .map(|(&p, &g)| (p, g))
            .collect();
        if inliers.is_empty() {
            return 0.0;
        }
        let pids = sorted_ids(inliers.iter().map(|&(p, _)| p).filter(|&p| p != -1));
        let gids = sorted_ids(inliers.iter().map(|&(_, g)| g));
        fn best(
            i: usize,
            pids: &[i32],
            gids: &[i32],
            used: &mut Vec<bool>,
            inl: &[(i32, i32)],
        ) -> usize {
            if i == pids.len() {
                return 0;
            }
            let mut top = best(i + 1, pids, gids, used, inl); // cluster i unmatched
            for j in 0..gids.len() {
                if !used[j] {
                    used[j] = true;
                    let agree = inl
                        .iter()
                        .filter(|&&(p, g)| p == pids[i] && g == gids[j])
                        .count();
                    top = top.max(agree + best(i + 1, pids, gids, used, inl));
                    used[j] = false;
                }
            }
            top
        }
        let matched = best(0, &pids, &gids, &mut vec![false; gids.len()], &inliers);
        1.0 - matched as f64 / inliers.len() as f64
    }

    #[test]
    fn me_equals_brute_force_on_small_labellings() {
        // A deterministic family of small labellings (LCG), exhaustive matching.
        let mut state: u64 = 0x2545_f491_4f6c_dd1d;
        let mut next = |m: u64| {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            ((state >> 33) % m) as i32
        };
        for _ in 0..300 {
            let n = 1 + next(25) as usize;
            let gt: Vec<i32> = (0..n).map(|_| next(4)).collect();
            let pred: Vec<i32> = (0..n).map(|_| next(6) - 1).collect();
            let fast = misclassification_error(&pred, &gt).unwrap();
            assert!(
                (fast - me_brute_force(&pred, &gt)).abs() < 1e-12,
                "{pred:?} {gt:?}"
            );
        }
    }

    #[test]
    fn fnr_matches_clusters_to_outlier_class_too() {
        // Cluster 3 holds two outliers and one motion-1 point: it is matched
        // to id 0, so its motion-1 point is a false negative.
        let fnr = false_negative_rate(&[3, 3, 3, 8, 8], &[0, 0, 1, 1, 1]).unwrap();
        assert!((fnr - 1.0 / 3.0).abs() < 1e-15);
        // ME ignores the outliers: cluster 3 then covers 1 point, cluster 8 two.
        let me = misclassification_error(&[3, 3, 3, 8, 8], &[0, 0, 1, 1, 1]).unwrap();
        assert!((me - 1.0 / 3.0).abs() < 1e-15);
    }

    #[test]
    fn ari_of_independent_halves_is_negative() {
        assert_eq!(
            adjusted_rand_index(&[0, 1, 0, 1], &[1, 1, 2, 2]).unwrap(),
            -0.5
        );
    }

    #[test]
    fn entropy_of_uniform_classes_is_log_k() {
        assert!((entropy(&[5, 5, 5, 5]) - 4f64.ln()).abs() < 1e-15);
        assert_eq!(entropy(&[9]), 0.0);
    }
}
