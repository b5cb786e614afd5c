//! The metrics that match predicted clusters to ground-truth motions one to
//! one (Hungarian): ME, the literature's ME over all points, FNR, and purity.

use std::collections::BTreeMap;

use crate::labels::{agreement_counts, optimal_assignment, sorted_ids, validate};
use crate::{MetricsError, GROUND_TRUTH_OUTLIER, PREDICTED_OUTLIER};

/// Misclassification error (docs/method.md "Metrics", ME).
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
    checked(pred, gt, me_unchecked)
}

/// Misclassification error over all points, as the multi-model fitting
/// literature reports it on AdelaideRMF (the `me_all` column; the tables of
/// Progressive-X, MLink and consensus-space clustering).
///
/// Every point counts, ground-truth outliers included. The outliers are a
/// class of their own: a point is right when it is predicted −1 and its
/// ground truth is 0, or when its predicted cluster is the one matched to
/// its motion. Predicted clusters (ids ≥ 0) are matched one-to-one to the
/// ground-truth motions (ids ≥ 1) by the Hungarian algorithm maximising the
/// number of agreeing points; the outlier classes are matched to each other.
/// `ME_all = 1 − (outliers predicted −1 + matched) / N`. Returns 0.0 for no
/// points. Unlike [`misclassification_error`] (the thesis's ME), a
/// ground-truth outlier put into a cluster is an error, and rejecting it is
/// a success.
///
/// # Errors
/// [`MetricsError`] when the lengths differ or a label is out of range.
///
/// ```
/// use metrics::misclassification_error_all;
///
/// // The outlier (gt 0) predicted -1 is right; the one put in cluster 4 is wrong,
/// // and so is the motion-2 point rejected as an outlier.
/// let me = misclassification_error_all(&[4, 4, 7, -1, -1, 4], &[1, 1, 2, 2, 0, 0]).unwrap();
/// assert!((me - 2.0 / 6.0).abs() < 1e-15);
/// ```
pub fn misclassification_error_all(pred: &[i32], gt: &[i32]) -> Result<f64, MetricsError> {
    checked(pred, gt, me_all_unchecked)
}

/// False-negative rate (docs/method.md "Metrics", FNR).
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
    checked(pred, gt, fnr_unchecked)
}

/// Purity (docs/method.md "Metrics", PUR).
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
    checked(pred, gt, purity_unchecked)
}

/// `metric(pred, gt)` once [`validate`] accepts the labels.
fn checked(
    pred: &[i32],
    gt: &[i32],
    metric: fn(&[i32], &[i32]) -> f64,
) -> Result<f64, MetricsError> {
    validate(pred, gt)?;
    Ok(metric(pred, gt))
}

pub(crate) fn me_unchecked(pred: &[i32], gt: &[i32]) -> f64 {
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

pub(crate) fn me_all_unchecked(pred: &[i32], gt: &[i32]) -> f64 {
    if pred.is_empty() {
        return 0.0;
    }
    let rejected_outliers = pred
        .iter()
        .zip(gt)
        .filter(|&(&p, &g)| p == PREDICTED_OUTLIER && g == GROUND_TRUTH_OUTLIER)
        .count();
    let clustered_inliers: Vec<(i32, i32)> = pred
        .iter()
        .zip(gt)
        .filter(|&(&p, &g)| p != PREDICTED_OUTLIER && g != GROUND_TRUTH_OUTLIER)
        .map(|(&p, &g)| (p, g))
        .collect();
    let pids = sorted_ids(clustered_inliers.iter().map(|&(p, _)| p));
    let gids = sorted_ids(clustered_inliers.iter().map(|&(_, g)| g));
    if pids.is_empty() {
        return 1.0 - rejected_outliers as f64 / pred.len() as f64;
    }
    let counts = agreement_counts(&clustered_inliers, &pids, &gids);
    let matched: f64 = optimal_assignment(pids.len(), gids.len(), &counts, true)
        .iter()
        .map(|&(i, j)| counts[i * gids.len() + j])
        .sum();
    1.0 - (rejected_outliers as f64 + matched) / pred.len() as f64
}

pub(crate) fn fnr_unchecked(pred: &[i32], gt: &[i32]) -> f64 {
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

pub(crate) fn purity_unchecked(pred: &[i32], gt: &[i32]) -> f64 {
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A deterministic stream of small labels: `next(m)` is in `0..m`
    /// (a 64-bit LCG, its high bits).
    fn lcg(seed: u64) -> impl FnMut(u64) -> i32 {
        let mut state = seed;
        move |m| {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            ((state >> 33) % m) as i32
        }
    }

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
        let mut next = lcg(0x2545_f491_4f6c_dd1d);
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

    /// ME over all points by brute force: outliers right only when
    /// predicted −1; every injective map from the clusters to the motions.
    fn me_all_brute_force(pred: &[i32], gt: &[i32]) -> f64 {
        if pred.is_empty() {
            return 0.0;
        }
        let pids = sorted_ids(pred.iter().copied().filter(|&p| p >= 0));
        let gids = sorted_ids(gt.iter().copied().filter(|&g| g >= 1));
        let mut best = 0usize;
        let mut assignment = vec![None; pids.len()];
        fn visit(
            i: usize,
            pids: &[i32],
            gids: &[i32],
            assignment: &mut Vec<Option<i32>>,
            pred: &[i32],
            gt: &[i32],
            best: &mut usize,
        ) {
            if i == pids.len() {
                let right = pred
                    .iter()
                    .zip(gt)
                    .filter(|&(&p, &g)| match p {
                        -1 => g == 0,
                        _ => {
                            let k = pids.binary_search(&p).unwrap();
                            assignment[k] == Some(g)
                        }
                    })
                    .count();
                *best = (*best).max(right);
                return;
            }
            assignment[i] = None;
            visit(i + 1, pids, gids, assignment, pred, gt, best);
            for &g in gids {
                if !assignment[..i].contains(&Some(g)) {
                    assignment[i] = Some(g);
                    visit(i + 1, pids, gids, assignment, pred, gt, best);
                }
            }
            assignment[i] = None;
        }
        visit(0, &pids, &gids, &mut assignment, pred, gt, &mut best);
        1.0 - best as f64 / pred.len() as f64
    }

    #[test]
    fn me_all_equals_brute_force_on_small_labellings() {
        let mut next = lcg(0x9e37_79b9_7f4a_7c15);
        for _ in 0..300 {
            let n = next(25) as usize;
            let gt: Vec<i32> = (0..n).map(|_| next(4)).collect();
            let pred: Vec<i32> = (0..n).map(|_| next(6) - 1).collect();
            let fast = misclassification_error_all(&pred, &gt).unwrap();
            assert!(
                (fast - me_all_brute_force(&pred, &gt)).abs() < 1e-12,
                "{pred:?} {gt:?}"
            );
        }
    }

    #[test]
    fn me_all_counts_outliers_and_equals_me_without_them() {
        // No ground-truth outliers and no rejections: both definitions agree.
        let (pred, gt) = ([3, 3, 5, 5, 5, 3], [1, 1, 2, 2, 1, 1]);
        assert_eq!(
            misclassification_error_all(&pred, &gt).unwrap(),
            misclassification_error(&pred, &gt).unwrap()
        );
        // Every point rejected: only the ground-truth outliers are right.
        let me_all = misclassification_error_all(&[-1, -1, -1, -1], &[0, 1, 1, 0]).unwrap();
        assert_eq!(me_all, 0.5);
        // An outlier absorbed into a cluster costs ME_all but not ME.
        assert_eq!(
            misclassification_error(&[2, 2, 2], &[1, 1, 0]).unwrap(),
            0.0
        );
        let me_all = misclassification_error_all(&[2, 2, 2], &[1, 1, 0]).unwrap();
        assert!((me_all - 1.0 / 3.0).abs() < 1e-15);
    }
}
