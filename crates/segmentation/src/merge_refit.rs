//! Merging the clusters that one F refitted on their union explains
//! (`final_assignment = "merge-refit"` and `"merge-anchored"`, after
//! [`crate::merge_explained`]): at small M no sampled hypothesis may span
//! a motion that T-Linkage split, so the merge refits one.

use crate::assignment::cluster_refit_irls;
use crate::merge::{apply_merges, largest_first};
use crate::{Params, MERGE_SHARE};
use geometry::{sampson_distances_squared, Correspondences, IrlsParams, IrlsWorkspace};
use nalgebra::Matrix3;

/// New labels for `labels` (clusters `0..clusters`, −1 outliers) after
/// merging clusters that one *refitted* model explains
/// (`final_assignment = "merge-refit"`, run after
/// [`crate::merge_explained`]):
///
/// 1. clusters are visited from the largest (the lower label on ties);
///    each earlier kept group `A` and the cluster `B` are refitted
///    together: the F of IRLS-Tukey (Eqs. 33–34, [`crate::CLUSTER_REFIT_ITERS`]
///    iterations, `params`' other IRLS settings) started from the 8-point
///    of `A ∪ B`;
/// 2. its share of `A` and its share of `B` explained (squared Sampson
///    distance, Eq. 23, `≤ thr_px²`) are taken, and the smaller of the two
///    is the pair's score; `B` joins the group of best score when it is
///    `≥ MERGE_SHARE`, the group then holding `A ∪ B`; else `B` starts a
///    group;
/// 3. labels are renumbered 0, 1, … by first appearance; outliers stay −1.
///
/// Where [`crate::merge_explained`] needs one sampled hypothesis to explain a
/// fragment, this needs one F to explain both: at small M no single
/// sampled hypothesis may span a motion that T-Linkage split.
/// `points` are the principal-point-centred matches the labels index.
pub fn merge_refitted(
    points: &Correspondences,
    labels: &[i32],
    clusters: usize,
    params: &Params,
) -> Vec<i32> {
    merge_by_union_fit(points, labels, clusters, &[], false, params)
}

/// New labels for `labels` (clusters `0..clusters`, −1 outliers) after
/// merging clusters that a model grown from the larger one's explains
/// (`final_assignment = "merge-anchored"`, run after
/// [`crate::merge_explained`]): as [`merge_refitted`], but the IRLS-Tukey
/// refit of `A ∪ B` starts from `A`'s model, not from the 8-point of the
/// union. A group's model is at first its largest cluster's `anchors`
/// entry (its best-supported hypothesis), then the refit that last grew
/// it; a group without one starts from the 8-point.
///
/// Started from one motion's F, the robust refit keeps that motion and
/// weighs another motion's matches down, so `B` joins only when the
/// motion of `A`, refitted, explains it: a fragment of the motion does,
/// a second motion that one compromise F could also explain does not.
pub fn merge_anchored(
    points: &Correspondences,
    labels: &[i32],
    clusters: usize,
    anchors: &[Option<Matrix3<f64>>],
    params: &Params,
) -> Vec<i32> {
    merge_by_union_fit(points, labels, clusters, anchors, true, params)
}

/// The merge of [`merge_refitted`] (no `anchors`, `grow_anchor = false`:
/// every refit from the union's 8-point) and of [`merge_anchored`]
/// (`grow_anchor = true`). A cluster past the end of `anchors` has none.
fn merge_by_union_fit(
    points: &Correspondences,
    labels: &[i32],
    clusters: usize,
    anchors: &[Option<Matrix3<f64>>],
    grow_anchor: bool,
    params: &Params,
) -> Vec<i32> {
    let members = crate::assignment::members(labels, clusters);
    let order = largest_first(&members);
    let mut union_fit = UnionFit::new(points, params);

    let mut target = vec![0usize; clusters];
    let mut groups: Vec<Group> = Vec::new();
    for &b in &order {
        let best = groups
            .iter()
            .enumerate()
            .map(|(g, group)| (g, union_fit.score(group, &members[b])))
            .fold(
                None,
                |best: Option<(usize, UnionScore)>, (g, s)| match best {
                    Some((_, ref bs)) if bs.share >= s.share => best,
                    _ => Some((g, s)),
                },
            );
        match best {
            Some((g, s)) if s.share >= MERGE_SHARE => {
                target[b] = g;
                let group = &mut groups[g];
                group.members.extend_from_slice(&members[b]);
                group.members.sort_unstable();
                if grow_anchor {
                    group.anchor = s.model;
                }
            }
            _ => {
                target[b] = groups.len();
                groups.push(Group {
                    members: members[b].clone(),
                    anchor: anchors.get(b).copied().flatten(),
                });
            }
        }
    }
    apply_merges(labels, &target)
}

/// A group of merged clusters: its matches, increasing, and the model its
/// refits start from (None: the 8-point of the union).
struct Group {
    members: Vec<usize>,
    anchor: Option<Matrix3<f64>>,
}

/// A union refit: the smaller of the shares of the two sides it explains
/// (0 when the refit fails) and the refitted F.
struct UnionScore {
    share: f64,
    model: Option<Matrix3<f64>>,
}

/// The union refit of [`merge_refitted`] and [`merge_anchored`], and its
/// buffers.
struct UnionFit<'a> {
    points: &'a Correspondences,
    irls: IrlsParams,
    thr2: f64,
    workspace: IrlsWorkspace,
    residuals: Vec<f64>,
}

impl<'a> UnionFit<'a> {
    fn new(points: &'a Correspondences, params: &Params) -> Self {
        Self {
            points,
            irls: cluster_refit_irls(params),
            thr2: params.thr_px * params.thr_px,
            workspace: IrlsWorkspace::new(),
            residuals: vec![0.0; points.len()],
        }
    }

    /// The F refitted on `a ∪ b` (from `a`'s anchor, else the union's
    /// 8-point) and the smaller of the shares of `a` and of `b` it explains.
    fn score(&mut self, a: &Group, b: &[usize]) -> UnionScore {
        let mut union: Vec<usize> = a.members.iter().chain(b).copied().collect();
        union.sort_unstable();
        let start = a.anchor.as_ref();
        let Ok(fit) = self.workspace.run(self.points, &union, start, &self.irls) else {
            return UnionScore {
                share: 0.0,
                model: None,
            };
        };
        sampson_distances_squared(&fit.f, self.points, &mut self.residuals);
        let share = |set: &[usize]| {
            let explained = set
                .iter()
                .filter(|&&i| self.residuals[i] <= self.thr2)
                .count();
            explained as f64 / set.len().max(1) as f64
        };
        UnionScore {
            share: share(&a.members).min(share(b)),
            model: Some(fit.f),
        }
    }
}
