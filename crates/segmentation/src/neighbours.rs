//! Joining the unclustered matches by their neighbours
//! (`subset_extension = "neighbours"`): a left-out match takes the label
//! that most of its nearest clustered matches have.
//!
//! A match near the epipolar lines of two motions is explained by both
//! motions' F, and its preference vector (Eq. 38) is a mix of theirs; on
//! the `adelaide-like` validation scenes 11.4 % of the correct matches lie
//! within `thr_px` of another motion's true F (`cargo run --release -p
//! bench --example cluster_anatomy`). Rigid objects are compact, so a
//! match's neighbours in both images, (x₁, y₁, x₂, y₂), mostly belong to its
//! own motion: the neighbourhood prior of PEARL's smoothness term (Isack &
//! Boykov, IJCV 2012) and of Multi-X (Barath & Matas, ECCV 2018), here as
//! a vote.

use crate::ClusteredSubset;
use geometry::Correspondences;
use rayon::prelude::*;

/// The clustered matches that vote on a left-out match's label.
pub const EXTENSION_NEIGHBOURS: usize = 5;

/// The label of each match outside `subset` (−1 inside it) voted by its
/// [`EXTENSION_NEIGHBOURS`] nearest matches of the subset in the joint
/// image space (x₁, y₁, x₂, y₂) (Euclidean distance in px; the lower
/// subset position on ties): the class with most votes among them, the
/// subset's outliers a class of their own, and of classes with as many
/// votes the one of the nearest voter. Labels out of `0..subset.clusters`
/// vote as outliers. In parallel; independent of the thread count.
pub(crate) fn neighbour_vote(points: &Correspondences, subset: ClusteredSubset) -> Vec<i32> {
    let class = |l: i32| {
        if (0..subset.clusters as i32).contains(&l) {
            l
        } else {
            -1
        }
    };
    let voters: Vec<([f64; 4], i32)> = subset
        .indices
        .iter()
        .zip(subset.labels)
        .map(|(&i, &l)| (joint(points, i), class(l)))
        .collect();
    let in_subset = subset.membership(points.len());
    (0..points.len())
        .into_par_iter()
        .map(|i| {
            if in_subset[i] {
                return -1;
            }
            let nearest = nearest_voters(&voters, joint(points, i), EXTENSION_NEIGHBOURS);
            majority(&nearest)
        })
        .collect()
}

/// Match `i` as a point of the joint image space (x₁, y₁, x₂, y₂).
fn joint(points: &Correspondences, i: usize) -> [f64; 4] {
    let ([x1, y1], [x2, y2]) = (points.point1(i), points.point2(i));
    [x1, y1, x2, y2]
}

/// The labels of the `k` voters nearest to `q`, nearest first (the
/// earlier voter on equal distances).
fn nearest_voters(voters: &[([f64; 4], i32)], q: [f64; 4], k: usize) -> Vec<i32> {
    // (squared distance, label), sorted; a voter enters only when strictly
    // nearer than the k-th, so earlier voters win ties.
    let mut best: Vec<(f64, i32)> = Vec::with_capacity(k + 1);
    for (p, label) in voters {
        let d2: f64 = p.iter().zip(&q).map(|(a, b)| (a - b) * (a - b)).sum();
        if best.len() == k && d2 >= best[k - 1].0 {
            continue;
        }
        let at = best.partition_point(|&(d, _)| d <= d2);
        best.insert(at, (d2, *label));
        best.truncate(k);
    }
    best.into_iter().map(|(_, label)| label).collect()
}

/// The label with most entries in `labels` (nearest first); of labels
/// with as many, the one that comes first. −1 for none.
fn majority(labels: &[i32]) -> i32 {
    let mut best = (0, -1);
    for &l in labels {
        let votes = labels.iter().filter(|&&m| m == l).count();
        if votes > best.0 {
            best = (votes, l);
        }
    }
    best.1
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_most_frequent_label_wins_and_the_nearest_breaks_ties() {
        assert_eq!(majority(&[1, 0, 0, 1, 2]), 1);
        assert_eq!(majority(&[2, 0, 0, -1, -1]), 0);
        assert_eq!(majority(&[-1, -1, 0, 0, 3]), -1);
        assert_eq!(majority(&[]), -1);
    }

    #[test]
    fn the_nearest_voters_equal_a_full_sort() {
        let voters: Vec<([f64; 4], i32)> = (0..40_i32)
            .map(|i| {
                let v = (i * 37 % 41) as f64;
                ([v, (i * 13 % 7) as f64, 0.5 * v, 1.0], i)
            })
            .collect();
        let q = [20.0, 3.0, 9.0, 1.0];
        let d2 = |p: &[f64; 4]| {
            p.iter()
                .zip(&q)
                .map(|(a, b)| (a - b) * (a - b))
                .sum::<f64>()
        };
        let mut sorted: Vec<(f64, i32)> = voters.iter().map(|(p, l)| (d2(p), *l)).collect();
        sorted.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        for k in [1, 5, 9, 40] {
            let want: Vec<i32> = sorted[..k].iter().map(|&(_, l)| l).collect();
            assert_eq!(nearest_voters(&voters, q, k), want, "k = {k}");
        }
    }
}
