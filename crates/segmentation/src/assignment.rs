//! The final assignment after the clustering (`final_assignment = "refit"`):
//! each cluster's model refitted on its points, then every match given the
//! model that explains it best, as Progressive-X (Barath & Matas, ICCV 2019)
//! and consensus-space clustering (Barath, Rozumnyi, Eichhardt, Hajder, Matas, CVPR 2023)
//! end their multi-model fitting.

use crate::Params;
use geometry::{sampson_distances_squared, Correspondences, IrlsParams, IrlsWorkspace};
use nalgebra::Matrix3;

/// IRLS-Tukey iterations of the cluster refits that follow the clustering
/// ([`crate::merge_refitted`], [`crate::merge_anchored`],
/// [`recover_outliers`], the refitted [`crate::SubsetExtension`]s): the default's
/// `irls_iters`, whatever the profile's (the fast profile's one iteration
/// leaves a cluster's 8-point, which its wrong matches pull off).
pub const CLUSTER_REFIT_ITERS: usize = 5;

/// `params`' IRLS settings with [`CLUSTER_REFIT_ITERS`] iterations: the
/// refits that follow the clustering.
pub(crate) fn cluster_refit_irls(params: &Params) -> IrlsParams {
    IrlsParams {
        max_iters: CLUSTER_REFIT_ITERS,
        ..params.irls()
    }
}

/// New labels for `labels` (clusters `0..clusters`, −1 outliers):
///
/// 1. the F of each cluster refitted by IRLS-Tukey (step 3, Eqs. 33–34,
///    [`Params::irls`]) started from the 8-point of its points; a cluster
///    whose refit fails (fewer than 8 inliers, degenerate) has no model;
/// 2. every match goes to the model of smallest squared Sampson distance
///    (Eq. 23; the lower label on ties) when it is `≤ thr_px²`, else −1;
/// 3. clusters left with fewer than `min_cluster_size` matches become
///    outliers, and the others are numbered 0, 1, … by first appearance
///    (smallest match index), as the clustering numbers them.
///
/// Labels out of `0..clusters` count as outliers. `points` are the
/// principal-point-centred matches. [`crate::segment`] calls it when `final_assignment = "refit"`; the synthetic
/// scenes of `tests/segment.rs` check it recovers the true labels.
pub fn reassign(
    points: &Correspondences,
    labels: &[i32],
    clusters: usize,
    params: &Params,
) -> Vec<i32> {
    let models = refit_clusters(points, &members(labels, clusters), &params.irls());
    let nearest = nearest_model(points, &models, params.thr_px * params.thr_px);
    drop_small_and_renumber(&nearest, models.len(), params.min_cluster_size)
}

/// `labels` (clusters `0..clusters`, −1 outliers) with the outliers
/// recovered (`recover_outliers = "refit"`):
///
/// 1. the F of each cluster refitted by IRLS-Tukey (Eqs. 33–34,
///    [`CLUSTER_REFIT_ITERS`] iterations, `params`' other IRLS settings)
///    started from the 8-point of its matches;
/// 2. every outlier joins the cluster whose refitted F has the smallest
///    squared Sampson distance to it (Eq. 23; the lower label on ties)
///    when it is `≤ thr_px²`; every other match keeps its cluster;
/// 3. labels are renumbered 0, 1, … by first appearance.
///
/// A match with no hypothesis of the M within `thr_px` has an empty
/// preference set and ends an outlier, however well its motion's F would
/// explain it: at small M this happens to many correct matches.
pub fn recover_outliers(
    points: &Correspondences,
    labels: &[i32],
    clusters: usize,
    params: &Params,
) -> Vec<i32> {
    let irls = cluster_refit_irls(params);
    let models = refit_clusters(points, &members(labels, clusters), &irls);
    let nearest = nearest_model(points, &models, params.thr_px * params.thr_px);
    let recovered: Vec<i32> = labels
        .iter()
        .zip(nearest)
        .map(|(&label, nearest)| if label >= 0 { label } else { nearest })
        .collect();
    drop_small_and_renumber(&recovered, clusters, 0)
}

/// The matches of each label `0..clusters`, increasing.
pub(crate) fn members(labels: &[i32], clusters: usize) -> Vec<Vec<usize>> {
    let mut members = vec![Vec::new(); clusters];
    for (i, &label) in labels.iter().enumerate() {
        if let Some(m) = usize::try_from(label).ok().and_then(|l| members.get_mut(l)) {
            m.push(i);
        }
    }
    members
}

/// IRLS-Tukey F of each cluster from its matches (None when it fails).
pub(crate) fn refit_clusters(
    points: &Correspondences,
    members: &[Vec<usize>],
    irls: &IrlsParams,
) -> Vec<Option<Matrix3<f64>>> {
    let mut ws = IrlsWorkspace::new();
    members
        .iter()
        .map(|idx| ws.run(points, idx, None, irls).ok().map(|s| s.f))
        .collect()
}

/// The model (by position) of smallest squared Sampson distance for each
/// match when `≤ thr2`, the first on ties; −1 otherwise.
pub(crate) fn nearest_model(
    points: &Correspondences,
    models: &[Option<Matrix3<f64>>],
    thr2: f64,
) -> Vec<i32> {
    let n = points.len();
    let mut best = vec![(-1_i32, f64::INFINITY); n];
    let mut residuals = vec![0.0; n];
    for (label, model) in models.iter().enumerate() {
        let Some(f) = model else { continue };
        sampson_distances_squared(f, points, &mut residuals);
        for (b, &r) in best.iter_mut().zip(&residuals) {
            if r <= thr2 && r < b.1 {
                *b = (label as i32, r);
            }
        }
    }
    best.into_iter().map(|(label, _)| label).collect()
}

/// Labels `0..clusters` with fewer than `min_size` matches become −1; the
/// others are renumbered by first appearance.
pub(crate) fn drop_small_and_renumber(
    labels: &[i32],
    clusters: usize,
    min_size: usize,
) -> Vec<i32> {
    let mut sizes = vec![0usize; clusters];
    for &l in labels.iter().filter(|&&l| l >= 0) {
        sizes[l as usize] += 1;
    }
    let mut renumbered = vec![-1_i32; clusters];
    let mut next = 0;
    labels
        .iter()
        .map(|&l| {
            let Ok(l) = usize::try_from(l) else { return -1 };
            if sizes[l] < min_size {
                return -1;
            }
            if renumbered[l] < 0 {
                renumbered[l] = next;
                next += 1;
            }
            renumbered[l]
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_clusters_drop_and_labels_follow_first_appearance() {
        let labels = [2, 2, 0, -1, 1, 2, 0, 0, 1];
        assert_eq!(
            drop_small_and_renumber(&labels, 3, 3),
            [0, 0, 1, -1, -1, 0, 1, 1, -1]
        );
        assert_eq!(
            drop_small_and_renumber(&labels, 3, 1),
            [0, 0, 1, -1, 2, 0, 1, 1, 2]
        );
        assert_eq!(drop_small_and_renumber(&labels, 3, 4), [-1; 9]);
    }

    #[test]
    fn members_ignore_outliers_and_unknown_labels() {
        assert_eq!(members(&[1, -1, 0, 7, 1], 2), vec![vec![2], vec![0, 4]]);
    }
}
