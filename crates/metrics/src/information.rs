//! The information-theoretic metrics over all points: ARI and NMI.

use std::collections::BTreeMap;

use crate::labels::{sorted_ids, validate};
use crate::MetricsError;

/// Adjusted Rand index over all points, −1 and 0 taken as ordinary classes
/// (docs/method.md "Metrics", ARI; Hubert–Arabie adjustment as scikit-learn's
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
/// classes, with arithmetic-mean normalisation (docs/method.md "Metrics", NMI;
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

pub(crate) fn ari_unchecked(pred: &[i32], gt: &[i32]) -> f64 {
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

pub(crate) fn nmi_unchecked(pred: &[i32], gt: &[i32]) -> f64 {
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
