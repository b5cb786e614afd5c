//! Step 2 with the five-point solver ([`crate::MinimalSolver::FivePoint`]):
//! a sample's candidate fundamental matrices, the choice among them, and
//! the matches refinement starts from.

use crate::MinimalSolutions;
use geometry::{five_point, sampson_consensus, Correspondences, FivePointRoots};
use nalgebra::{Matrix3, Vector3};

/// The fundamental matrices (centred pixel coordinates) of one five-point
/// sample `subset`; empty when the sample is degenerate or has no real
/// solution. `focal` is the focal of `K(f) = diag(f, f, 1)`: the solver's
/// E become `F = K⁻ᵀ E K⁻¹`.
pub(crate) fn candidates(subset: &Correspondences, focal: f64) -> Vec<Matrix3<f64>> {
    essential_candidates(subset, focal)
        .into_iter()
        .filter(|f| f.iter().all(|v| v.is_finite()))
        .collect()
}

/// Five-point E from the bearings `K⁻¹ (x, y, 1)ᵀ` of the centred points,
/// each converted to `F = K⁻ᵀ E K⁻¹` (Hartley & Zisserman Eq. 9.12).
fn essential_candidates(subset: &Correspondences, focal: f64) -> Vec<Matrix3<f64>> {
    let (q1, q2) = bearings(subset, focal);
    five_point(&q1, &q2)
        .unwrap_or_default()
        .into_iter()
        .map(|e| essential_to_fundamental(&e, focal))
        .collect()
}

/// The bearings `K⁻¹ (x, y, 1)ᵀ` of a sample's centred points, image 1 and 2.
fn bearings(subset: &Correspondences, focal: f64) -> (Vec<Vector3<f64>>, Vec<Vector3<f64>>) {
    let bearing = |p: [f64; 2]| Vector3::new(p[0] / focal, p[1] / focal, 1.0);
    (0..subset.len())
        .map(|i| (bearing(subset.point1(i)), bearing(subset.point2(i))))
        .unzip()
}

/// `F = K⁻ᵀ E K⁻¹` with `K = diag(f, f, 1)` (Hartley & Zisserman Eq. 9.12).
fn essential_to_fundamental(e: &Matrix3<f64>, focal: f64) -> Matrix3<f64> {
    let k_inv = Matrix3::from_diagonal(&Vector3::new(1.0 / focal, 1.0 / focal, 1.0));
    k_inv * e * k_inv
}

/// One five-point sample's hypothesis: the candidate with the largest
/// consensus among `points` ([`MinimalSolutions::Best`]), or, with
/// [`MinimalSolutions::BestUnpolished`], the unpolished root with the
/// largest consensus ([`best_unpolished`]); `None` when the sample has no
/// usable solution.
pub(crate) fn solve_and_choose(
    choice: MinimalSolutions,
    subset: &Correspondences,
    points: &Correspondences,
    focal: f64,
    thr_px: f64,
) -> Option<Chosen> {
    match choice {
        MinimalSolutions::BestUnpolished => best_unpolished(subset, points, focal, thr_px),
        MinimalSolutions::Best => {
            let candidates = candidates(subset, focal).into_iter().enumerate();
            most_consensus(points, candidates, thr_px * thr_px).map(|(_, chosen)| chosen)
        }
    }
}

/// The five-point root of a sample whose unpolished F has the largest
/// consensus (the first on ties), unpolished, with that consensus set;
/// `None` when the sample has no usable root.
fn best_unpolished(
    subset: &Correspondences,
    points: &Correspondences,
    focal: f64,
    thr_px: f64,
) -> Option<Chosen> {
    let (q1, q2) = bearings(subset, focal);
    let roots = FivePointRoots::new(&q1, &q2).ok()?;
    let unpolished = (0..roots.len())
        .filter_map(|k| {
            Some((
                k,
                essential_to_fundamental(&roots.unpolished(k).ok()?, focal),
            ))
        })
        .filter(|(_, f)| f.iter().all(|v| v.is_finite()));
    most_consensus(points, unpolished, thr_px * thr_px).map(|(_, chosen)| chosen)
}

/// A chosen solution and its consensus set: the matches within `thr_px`
/// (Sampson distance, Eq. 23), increasing, where its refinement starts.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Chosen {
    pub f: Matrix3<f64>,
    pub consensus: Vec<usize>,
}

/// The candidate `(key, F)` with the largest consensus within `thr2` px²,
/// the first on ties, with its key and consensus set; `None` without
/// candidates. A candidate is abandoned as soon as it can no longer beat
/// the best so far.
fn most_consensus<K>(
    points: &Correspondences,
    candidates: impl Iterator<Item = (K, Matrix3<f64>)>,
    thr2: f64,
) -> Option<(K, Chosen)> {
    let mut best: Option<(K, Chosen)> = None;
    let mut scratch = Vec::new();
    for (key, f) in candidates {
        let to_beat = best.as_ref().map_or(0, |(_, b)| b.consensus.len() + 1);
        if sampson_consensus(&f, points, thr2, to_beat, &mut scratch) {
            let chosen = Chosen {
                f,
                consensus: std::mem::take(&mut scratch),
            };
            if let Some((_, previous)) = best.replace((key, chosen)) {
                scratch = previous.consensus;
            }
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Rotation3, Vector3};

    /// Noise-free matches of 40 points seen by one camera of focal `focal`
    /// before and after a rigid motion (centred pixels), and the true F.
    fn rigid_scene(focal: f64) -> (Correspondences, Matrix3<f64>) {
        let r = Rotation3::from_euler_angles(0.05, -0.12, 0.08);
        let t = Vector3::new(0.6, -0.1, 0.15);
        let (mut p1, mut p2) = (Vec::new(), Vec::new());
        for i in 0..40 {
            let a = i as f64;
            let x = Vector3::new(
                (a * 0.37).sin() * 2.0,
                (a * 0.71).cos() * 1.5,
                6.0 + (a * 0.53).sin(),
            );
            let y = r * x + t;
            p1.push([focal * x.x / x.z, focal * x.y / x.z]);
            p2.push([focal * y.x / y.z, focal * y.y / y.z]);
        }
        let tx = t.cross_matrix();
        let k_inv = Matrix3::from_diagonal(&Vector3::new(1.0 / focal, 1.0 / focal, 1.0));
        let f = k_inv * tx * r.matrix() * k_inv;
        (Correspondences::new(&p1, &p2).unwrap(), f / f.norm())
    }

    fn same_up_to_scale(a: &Matrix3<f64>, b: &Matrix3<f64>) -> bool {
        let (a, b) = (a / a.norm(), b / b.norm());
        (a - b).norm().min((a + b).norm()) < 1e-8
    }

    /// The candidate of largest consensus within `thr_px`, by a naive
    /// count of each candidate's matches (the first on ties).
    fn naive_best(points: &Correspondences, candidates: &[Matrix3<f64>], thr_px: f64) -> usize {
        let support = |f: &Matrix3<f64>| {
            (0..points.len())
                .filter(|&i| {
                    geometry::sampson_distance_squared(f, points.point1(i), points.point2(i))
                        <= thr_px * thr_px
                })
                .count()
        };
        let mut best = (0, 0);
        for (k, f) in candidates.iter().enumerate() {
            if k == 0 || support(f) > best.1 {
                best = (k, support(f));
            }
        }
        best.0
    }

    #[test]
    fn five_point_recovers_the_true_f_on_noise_free_matches() {
        let focal = 900.0;
        let (points, truth) = rigid_scene(focal);
        let sample: Vec<usize> = (0..geometry::FIVE_POINT_SAMPLE)
            .map(|i| 3 * i + 1)
            .collect();
        let subset = points.subset(&sample).unwrap();
        let all = candidates(&subset, focal);
        assert!(all.iter().any(|f| same_up_to_scale(f, &truth)), "{all:?}");
        // The best solution is the one every match agrees with.
        let best = solve_and_choose(MinimalSolutions::Best, &subset, &points, focal, 0.5).unwrap();
        assert!(same_up_to_scale(&best.f, &truth));
        assert_eq!(best.consensus, (0..points.len()).collect::<Vec<_>>());
    }

    #[test]
    fn best_is_the_first_candidate_of_largest_consensus() {
        let (points, truth) = rigid_scene(900.0);
        let worse = truth.component_mul(&Matrix3::new(1.0, 1.1, 0.9, 1.2, 1.0, 0.8, 1.0, 1.3, 1.0));
        let scaled = truth * -3.0;
        let candidates = [worse, scaled, truth];
        assert_eq!(naive_best(&points, &candidates, 2.0), 1);
        let (k, chosen) = most_consensus(&points, candidates.into_iter().enumerate(), 4.0).unwrap();
        assert_eq!((k, chosen.f), (1, scaled), "ties keep the first");
        let mut recount = Vec::new();
        geometry::sampson_consensus(&truth, &points, 4.0, 0, &mut recount);
        assert_eq!(chosen.consensus, recount);
        assert!(!recount.is_empty());
    }

    /// Scoring the unpolished roots picks the root `best` picks, within
    /// 1e-5 of its polish and with its own consensus set: on noise-free
    /// matches and on 60 samples of the same matches with up to ±1 px of
    /// deterministic noise, at the focal prior and off it.
    #[test]
    fn best_unpolished_chooses_as_best_does() {
        let (exact, _) = rigid_scene(900.0);
        let noisy: Vec<([f64; 2], [f64; 2])> = (0..exact.len())
            .map(|i| {
                let (a, b) = (exact.point1(i), exact.point2(i));
                let jitter = ((i * 37 % 11) as f64 - 5.0) / 5.0;
                (a, [b[0] + jitter, b[1] - 0.5 * jitter])
            })
            .collect();
        let (p1, p2): (Vec<_>, Vec<_>) = noisy.into_iter().unzip();
        let noisy = Correspondences::new(&p1, &p2).unwrap();
        for (points, focal) in [(&exact, 900.0), (&noisy, 900.0), (&noisy, 1200.0)] {
            for start in 0..20 {
                let sample: Vec<usize> = (0..5).map(|k| (start + 7 * k) % points.len()).collect();
                let subset = points.subset(&sample).unwrap();
                let run = |choice| solve_and_choose(choice, &subset, points, focal, 2.0);
                let best = run(MinimalSolutions::Best).expect("a solution");
                let all = candidates(&subset, focal);
                assert_eq!(
                    best.f,
                    all[naive_best(points, &all, 2.0)],
                    "sample {sample:?}"
                );
                let unpolished = run(MinimalSolutions::BestUnpolished).expect("a root");
                let (f, polished) = (&unpolished.f, &best.f);
                let gap = (f / f.norm() - polished / polished.norm()).norm();
                assert!(gap < 1e-5, "sample {sample:?}: {gap:e}");
                let mut recount = Vec::new();
                geometry::sampson_consensus(f, points, 4.0, 0, &mut recount);
                assert_eq!(unpolished.consensus, recount, "sample {sample:?}");
            }
        }
    }

    #[test]
    fn five_point_at_a_wrong_focal_is_no_longer_exact() {
        let (points, truth) = rigid_scene(900.0);
        let subset = points.subset(&[0, 5, 10, 15, 20]).unwrap();
        let at_prior = candidates(&subset, 1200.0);
        assert!(!at_prior.iter().any(|f| same_up_to_scale(f, &truth)));
    }

    #[test]
    fn degenerate_samples_give_no_candidate() {
        let p = [[1.0, 2.0]; 5];
        let subset = Correspondences::new(&p, &p).unwrap();
        assert!(candidates(&subset, 800.0).is_empty());
        for choice in [MinimalSolutions::Best, MinimalSolutions::BestUnpolished] {
            assert!(solve_and_choose(choice, &subset, &subset, 800.0, 2.0).is_none());
        }
    }
}
