//! Matches that several detected Fs explain, labelled by their neighbours.
//!
//! A match within `thr_px` of two detected Fs cannot be placed by its
//! residuals: their difference is noise. On the validation families 9-13 %
//! of the correct matches lie within `thr_px` of another motion's true F
//! (results/notes/fast-profile.md, `"neighbours"`). Its neighbours in
//! (x₁, y₁, x₂, y₂) mostly belong to its object, so the label most of them
//! have, among the Fs that explain it, is the better guess: iterated
//! conditional modes (Besag, "On the statistical analysis of dirty
//! pictures", JRSS B 1986) of a Potts term on the k-nearest-neighbour graph
//! (the smoothness term of PEARL, Isack & Boykov, IJCV 2012, and of
//! Multi-X, Barath & Matas, ICCV 2019), with the data term reduced to the
//! constraint that the match's F explains it.
//!
//! Only the matches labelled by the nearest F alone are voted on: those of
//! no cluster, and those of a cluster that the F it joined does not
//! explain. A detected cluster's matches, and those a cluster brought to
//! the F it joined, were put together by T-Linkage's preferences over all
//! hypotheses, which say more than a few neighbours; voting on them too
//! lowered ME on the validation families a little more but gave a motion's
//! fragments to a denser motion whose matches are spread among them
//! (results/notes/selection.md, "Neighbours").

use geometry::Correspondences;
use rstar::primitives::GeomWithData;
use rstar::RTree;

/// Neighbours of each voted match (on the validation families 4, 8 and 16
/// give ME within 0.01 points of each other on every family).
pub const VOTE_NEIGHBOURS: usize = 8;

/// Sweeps at most; each updates every voted match at once, so the result
/// does not depend on an order.
const MAX_SWEEPS: usize = 10;

/// `labels` (a detection per match, or −1) after the vote: each match not
/// `held` and within `thr_px` of at least two detections (`residuals[d][m]`)
/// takes, among those detections, the one that most of its
/// [`VOTE_NEIGHBOURS`] nearest matches in (x₁, y₁, x₂, y₂) have (ties: its
/// label when among them, else the nearest F), every such match at once,
/// until no label changes or after [`MAX_SWEEPS`] sweeps.
pub fn vote_ambiguous(
    points: &Correspondences,
    residuals: &[&Vec<f64>],
    held: &[bool],
    thr_px: f64,
    labels: &mut [i32],
) {
    let explaining = |m: usize| -> Vec<usize> {
        (0..residuals.len())
            .filter(|&d| residuals[d][m] <= thr_px)
            .collect()
    };
    let voters: Vec<(usize, Vec<usize>)> = (0..labels.len())
        .filter(|&m| !held[m])
        .map(|m| (m, explaining(m)))
        .filter(|(_, c)| c.len() >= 2)
        .collect();
    if voters.is_empty() {
        return;
    }
    let neighbours = nearest_neighbours(points, &voters, VOTE_NEIGHBOURS);
    for _ in 0..MAX_SWEEPS {
        let next: Vec<i32> = voters
            .iter()
            .zip(&neighbours)
            .map(|((m, c), nb)| vote(*m, c, nb, labels, residuals))
            .collect();
        let mut changed = false;
        for ((m, _), l) in voters.iter().zip(next) {
            changed |= labels[*m] != l;
            labels[*m] = l;
        }
        if !changed {
            break;
        }
    }
}

/// The candidate (`c`, detections that explain match `m`) that most of the
/// neighbours `nb` have; ties: `labels[m]` when among them, else the
/// candidate of smallest residual, then of smallest index.
fn vote(m: usize, c: &[usize], nb: &[u32], labels: &[i32], residuals: &[&Vec<f64>]) -> i32 {
    let count = |d: usize| {
        nb.iter()
            .filter(|&&j| labels[j as usize] == d as i32)
            .count()
    };
    let most = c.iter().map(|&d| count(d)).max().unwrap_or(0);
    let tied: Vec<usize> = c.iter().copied().filter(|&d| count(d) == most).collect();
    if tied.iter().any(|&d| d as i32 == labels[m]) {
        return labels[m];
    }
    tied.into_iter()
        .min_by(|&a, &b| residuals[a][m].total_cmp(&residuals[b][m]).then(a.cmp(&b)))
        .map_or(labels[m], |d| d as i32)
}

/// The `k` nearest other matches in (x₁, y₁, x₂, y₂) of each voter,
/// nearest first, ties by index (an R*-tree, `rstar`, over every match).
fn nearest_neighbours(
    points: &Correspondences,
    voters: &[(usize, Vec<usize>)],
    k: usize,
) -> Vec<Vec<u32>> {
    let coords = |m: usize| {
        let (p, q) = (points.point1(m), points.point2(m));
        [p[0], p[1], q[0], q[1]]
    };
    let tree = RTree::bulk_load(
        (0..points.len())
            .map(|m| GeomWithData::new(coords(m), m as u32))
            .collect(),
    );
    voters
        .iter()
        .map(|(m, _)| crate::sampling::nearest(&tree, coords(*m), *m, k))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// Two objects, left and right, 100 matches each: the even matches
    /// explained by their object's F alone, the odd ones by both Fs with
    /// the other's residual as small as their own's half the time.
    struct TwoObjects {
        points: Correspondences,
        residuals: [Vec<f64>; 2],
        truth: Vec<i32>,
    }

    fn two_objects() -> TwoObjects {
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        let (mut p1, mut p2, mut truth) = (Vec::new(), Vec::new(), Vec::new());
        let mut residuals = [Vec::new(), Vec::new()];
        for i in 0..200 {
            let object = i32::from(i >= 100);
            let x = rng.gen_range(10.0..150.0) + 200.0 * f64::from(object);
            let y = rng.gen_range(0.0..200.0);
            p1.push([x, y]);
            p2.push([x + 5.0, y]);
            truth.push(object);
            let own = rng.gen_range(0.0..2.0);
            let other = if i % 2 == 0 {
                rng.gen_range(3.0..9.0)
            } else {
                rng.gen_range(0.0..2.0)
            };
            residuals[object as usize].push(own);
            residuals[1 - object as usize].push(other);
        }
        TwoObjects {
            points: Correspondences::new(&p1, &p2).unwrap(),
            residuals,
            truth,
        }
    }

    /// The nearest F within `thr_px` per match, as `by_nfa` labels first.
    fn nearest(r: &[&Vec<f64>], n: usize, thr_px: f64) -> Vec<i32> {
        super::super::by_nearest_f(r, n, thr_px)
    }

    #[test]
    fn matches_two_fs_explain_take_their_neighbours_label() {
        let s = two_objects();
        let r: Vec<&Vec<f64>> = s.residuals.iter().collect();
        let mut labels = nearest(&r, 200, 2.5);
        let wrong_before = labels.iter().zip(&s.truth).filter(|(l, t)| l != t).count();
        vote_ambiguous(&s.points, &r, &[false; 200], 2.5, &mut labels);
        // The nearest F gets about a quarter of the matches wrong (half of
        // the odd ones); the neighbours, mostly of the same object, get
        // every one right.
        assert!(wrong_before > 30, "{wrong_before}");
        assert_eq!(labels, s.truth);
    }

    #[test]
    fn held_matches_and_single_explanations_are_not_voted_on() {
        let s = two_objects();
        let r: Vec<&Vec<f64>> = s.residuals.iter().collect();
        let start = nearest(&r, 200, 2.5);
        // Every match held: nothing changes.
        let mut labels = start.clone();
        vote_ambiguous(&s.points, &r, &[true; 200], 2.5, &mut labels);
        assert_eq!(labels, start);
        // A label changes only where both Fs explain the match.
        let mut labels = start.clone();
        vote_ambiguous(&s.points, &r, &[false; 200], 2.5, &mut labels);
        for m in 0..200 {
            if labels[m] != start[m] {
                assert!(r[0][m] <= 2.5 && r[1][m] <= 2.5, "match {m}");
            }
        }
        // One detection: no vote.
        let mut one = nearest(&r[..1], 200, 2.5);
        let before = one.clone();
        vote_ambiguous(&s.points, &r[..1], &[false; 200], 2.5, &mut one);
        assert_eq!(one, before);
    }
}
