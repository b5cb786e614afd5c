//! Label validation and the Hungarian matching shared by the metrics.

use crate::{MetricsError, GROUND_TRUTH_OUTLIER, PREDICTED_OUTLIER};

pub(crate) fn validate(pred: &[i32], gt: &[i32]) -> Result<(), MetricsError> {
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
pub(crate) fn sorted_ids(labels: impl Iterator<Item = i32>) -> Vec<i32> {
    let mut ids: Vec<i32> = labels.collect();
    ids.sort_unstable();
    ids.dedup();
    ids
}

/// Agreement counts `C[i][j] = #{(p, g) : p = rows[i], g = cols[j]}` over
/// `pairs`, flattened row-major; pairs whose ids are absent are skipped.
pub(crate) fn agreement_counts(pairs: &[(i32, i32)], rows: &[i32], cols: &[i32]) -> Vec<f64> {
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
pub(crate) fn optimal_assignment(
    rows: usize,
    cols: usize,
    costs: &[f64],
    maximize: bool,
) -> Vec<(usize, usize)> {
    let (r, c) = lsap::solve(rows, cols, &costs.to_vec(), maximize)
        .expect("a finite rectangular cost matrix always has a complete assignment");
    r.into_iter().zip(c).collect()
}
