//! Step 2 with the minimal solvers other than the 8-point
//! ([`MinimalSolver`]): a sample's candidate fundamental matrices, the
//! choice among them, and the matches refinement starts from.

use crate::{MinimalSolutions, MinimalSolver};
use geometry::{
    five_point, sampson_consensus, seven_point, six_point_focal, Correspondences, FivePointRoots,
};
use nalgebra::{Matrix3, Vector3};

/// The fundamental matrices (centred pixel coordinates) of one minimal
/// sample `subset` under `solver`; empty when the sample is degenerate or
/// has no real solution. `focal` is the focal of `K(f) = diag(f, f, 1)` for
/// the five-point solver: its E become `F = K⁻ᵀ E K⁻¹`.
pub(crate) fn candidates(
    solver: MinimalSolver,
    subset: &Correspondences,
    focal: f64,
) -> Vec<Matrix3<f64>> {
    let solutions = match solver {
        MinimalSolver::EightPoint => unreachable!("the 8-point path has its own step 2"),
        MinimalSolver::SevenPoint => seven_point(subset).unwrap_or_default(),
        MinimalSolver::FivePoint => essential_candidates(subset, focal),
        MinimalSolver::SixPointFocal => six_point_focal(subset)
            .map(|sols| sols.into_iter().map(|s| s.fundamental).collect())
            .unwrap_or_default(),
    };
    solutions
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

/// The matches a sample's solutions are scored on: all of them, and
/// optionally a few that pick the finalists first
/// ([`crate::Params::preselect_matches`]).
#[derive(Debug, Clone, Copy)]
pub(crate) struct ScoringSet<'a> {
    /// Every match (the consensus sets are over these).
    pub points: &'a Correspondences,
    /// A subset of `points`: only the solutions with the most matches of it
    /// within the threshold are scored on `points`.
    pub preselect: Option<&'a Correspondences>,
}

impl<'a> ScoringSet<'a> {
    /// Every solution scored on all of `points`.
    #[cfg(test)]
    pub fn all(points: &'a Correspondences) -> Self {
        Self {
            points,
            preselect: None,
        }
    }
}

/// One sample's hypotheses: its candidates under `solver`, chosen by
/// `choice` ([`choose`]); with the five-point solver and
/// [`MinimalSolutions::BestThenPolish`] or
/// [`MinimalSolutions::BestUnpolished`], scored before the root polish
/// ([`best_then_polish`], [`best_unpolished`]).
pub(crate) fn solve_and_choose(
    solver: MinimalSolver,
    choice: MinimalSolutions,
    subset: &Correspondences,
    scoring: ScoringSet,
    focal: f64,
    thr_px: f64,
) -> Vec<Chosen> {
    if solver == MinimalSolver::FivePoint {
        match choice {
            MinimalSolutions::BestThenPolish => {
                return best_then_polish(subset, scoring, focal, thr_px)
            }
            MinimalSolutions::BestUnpolished => {
                return best_unpolished(subset, scoring, focal, thr_px)
                    .map(|winner| winner.chosen)
                    .into_iter()
                    .collect()
            }
            MinimalSolutions::Best | MinimalSolutions::All => {}
        }
    }
    choose(choice, scoring, candidates(solver, subset, focal), thr_px)
}

/// A sample's five-point roots and the one chosen among them before any
/// polish.
struct UnpolishedWinner {
    roots: FivePointRoots,
    /// The winner's index in `roots`.
    index: usize,
    /// The winner's unpolished F and its consensus set.
    chosen: Chosen,
}

/// The five-point roots of a sample and the one whose unpolished F has the
/// largest consensus (the first on ties); `None` when the sample has no
/// usable root.
fn best_unpolished(
    subset: &Correspondences,
    scoring: ScoringSet,
    focal: f64,
    thr_px: f64,
) -> Option<UnpolishedWinner> {
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
    let (index, chosen) = best_consensus(scoring, unpolished, thr_px * thr_px)?;
    Some(UnpolishedWinner {
        roots,
        index,
        chosen,
    })
}

/// [`best_unpolished`]'s winner polished alone and its consensus set
/// recounted; empty when the sample has no root or the polish fails.
fn best_then_polish(
    subset: &Correspondences,
    scoring: ScoringSet,
    focal: f64,
    thr_px: f64,
) -> Vec<Chosen> {
    let Some(winner) = best_unpolished(subset, scoring, focal, thr_px) else {
        return Vec::new();
    };
    let Ok(e) = winner.roots.polished(winner.index) else {
        return Vec::new();
    };
    let f = essential_to_fundamental(&e, focal);
    if !f.iter().all(|v| v.is_finite()) {
        return Vec::new();
    }
    let mut consensus = Vec::new();
    sampson_consensus(&f, scoring.points, thr_px * thr_px, 0, &mut consensus);
    vec![Chosen { f, consensus }]
}

/// A chosen solution and its consensus set: the matches within `thr_px`
/// (Sampson distance, Eq. 23), increasing, where its refinement starts.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Chosen {
    pub f: Matrix3<f64>,
    pub consensus: Vec<usize>,
}

/// The candidates that become hypotheses, each with its consensus set: all
/// of them, or the one with the largest consensus (the first on ties,
/// among the preselected ones, [`best_consensus`]). A candidate is
/// abandoned as soon as it can no longer beat the best so far.
pub(crate) fn choose(
    choice: MinimalSolutions,
    scoring: ScoringSet,
    candidates: Vec<Matrix3<f64>>,
    thr_px: f64,
) -> Vec<Chosen> {
    let thr2 = thr_px * thr_px;
    match choice {
        MinimalSolutions::All => candidates
            .into_iter()
            .map(|f| {
                let mut consensus = Vec::new();
                sampson_consensus(&f, scoring.points, thr2, 0, &mut consensus);
                Chosen { f, consensus }
            })
            .collect(),
        MinimalSolutions::Best
        | MinimalSolutions::BestThenPolish
        | MinimalSolutions::BestUnpolished => {
            best_consensus(scoring, candidates.into_iter().enumerate(), thr2)
                .map(|(_, chosen)| chosen)
                .into_iter()
                .collect()
        }
    }
}

/// The candidate `(key, F)` with the largest consensus within `thr2` px²
/// on `scoring.points`, the first on ties, with its key and consensus set;
/// `None` without candidates. With `scoring.preselect`, only the
/// candidates with the most of its matches within `thr2` compete
/// ([`preselected`]): the preemptive scoring of RANSAC's hypotheses on a
/// few matches first (Nistér, "Preemptive RANSAC", ICCV 2003; Matas &
/// Chum's T(d,d) test, BMVC 2002), here among one sample's roots.
fn best_consensus<K>(
    scoring: ScoringSet,
    candidates: impl Iterator<Item = (K, Matrix3<f64>)>,
    thr2: f64,
) -> Option<(K, Chosen)> {
    match scoring.preselect {
        None => most_consensus(scoring.points, candidates, thr2),
        Some(few) => most_consensus(
            scoring.points,
            preselected(few, candidates, thr2).into_iter(),
            thr2,
        ),
    }
}

/// The candidates with the most matches of `few` within `thr2` px² (every
/// one of them on a tie), in their order.
fn preselected<K>(
    few: &Correspondences,
    candidates: impl Iterator<Item = (K, Matrix3<f64>)>,
    thr2: f64,
) -> Vec<(K, Matrix3<f64>)> {
    let mut scratch = Vec::new();
    let scored: Vec<(usize, K, Matrix3<f64>)> = candidates
        .map(|(key, f)| {
            sampson_consensus(&f, few, thr2, 0, &mut scratch);
            (scratch.len(), key, f)
        })
        .collect();
    let top = scored.iter().map(|(count, ..)| *count).max().unwrap_or(0);
    scored
        .into_iter()
        .filter(|(count, ..)| *count == top)
        .map(|(_, key, f)| (key, f))
        .collect()
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

    #[test]
    fn every_solver_recovers_the_true_f_on_noise_free_matches() {
        let focal = 900.0;
        let (points, truth) = rigid_scene(focal);
        for solver in [
            MinimalSolver::SevenPoint,
            MinimalSolver::FivePoint,
            MinimalSolver::SixPointFocal,
        ] {
            let sample: Vec<usize> = (0..solver.sample_size(8)).map(|i| 3 * i + 1).collect();
            let subset = points.subset(&sample).unwrap();
            let all = candidates(solver, &subset, focal);
            assert!(
                all.iter().any(|f| same_up_to_scale(f, &truth)),
                "{solver:?}: {all:?}"
            );
            // The best solution is the one every match agrees with.
            let best = choose(
                MinimalSolutions::Best,
                ScoringSet::all(&points),
                all.clone(),
                0.5,
            );
            assert_eq!(best.len(), 1);
            assert!(same_up_to_scale(&best[0].f, &truth), "{solver:?}");
            assert_eq!(best[0].consensus, (0..points.len()).collect::<Vec<_>>());
            let every = choose(
                MinimalSolutions::All,
                ScoringSet::all(&points),
                all.clone(),
                0.5,
            );
            assert_eq!(every.iter().map(|c| c.f).collect::<Vec<_>>(), all);
        }
    }

    #[test]
    fn best_is_the_first_candidate_of_largest_consensus() {
        let (points, truth) = rigid_scene(900.0);
        let worse = truth.component_mul(&Matrix3::new(1.0, 1.1, 0.9, 1.2, 1.0, 0.8, 1.0, 1.3, 1.0));
        let naive_support = |f: &Matrix3<f64>| {
            (0..points.len())
                .filter(|&i| {
                    geometry::sampson_distance_squared(f, points.point1(i), points.point2(i)) <= 4.0
                })
                .count()
        };
        assert!(naive_support(&worse) < naive_support(&truth));
        let scaled = truth * -3.0;
        let chosen = choose(
            MinimalSolutions::Best,
            ScoringSet::all(&points),
            vec![worse, scaled, truth],
            2.0,
        );
        assert_eq!(chosen.len(), 1);
        assert_eq!(chosen[0].f, scaled, "ties keep the first");
        assert_eq!(chosen[0].consensus.len(), naive_support(&truth));
    }

    /// Scoring the unpolished roots picks the solution `best` picks, and
    /// the winner's polish and consensus are `best`'s bit for bit (left
    /// unpolished: within 1e-5 of it, with its own consensus set): on
    /// noise-free matches and on 60 samples of the same matches with up to
    /// ±1 px of deterministic noise, at the focal prior and off it.
    #[test]
    fn best_then_polish_chooses_as_best_does() {
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
                let run = |choice| {
                    solve_and_choose(
                        MinimalSolver::FivePoint,
                        choice,
                        &subset,
                        ScoringSet::all(points),
                        focal,
                        2.0,
                    )
                };
                let best = run(MinimalSolutions::Best);
                assert_eq!(best.len(), 1, "sample {sample:?}");
                assert_eq!(
                    run(MinimalSolutions::BestThenPolish),
                    best,
                    "sample {sample:?}"
                );
                // Unpolished: the same root to the roots' accuracy, with
                // the consensus set of the F it returns.
                let unpolished = run(MinimalSolutions::BestUnpolished);
                assert_eq!(unpolished.len(), 1, "sample {sample:?}");
                let (f, consensus) = (&unpolished[0].f, &unpolished[0].consensus);
                let polished = &best[0].f;
                let gap = (f / f.norm() - polished / polished.norm()).norm();
                assert!(gap < 1e-5, "sample {sample:?}: {gap:e}");
                let mut recount = Vec::new();
                geometry::sampson_consensus(f, points, 4.0, 0, &mut recount);
                assert_eq!(consensus, &recount, "sample {sample:?}");
            }
        }
    }

    /// The naive reference of preselection: count every candidate on the
    /// few matches and on all of them by the distance of each match, keep
    /// those with the top count on the few, take the first of largest full
    /// count.
    fn naive_preselected_best(
        points: &Correspondences,
        few: &[usize],
        candidates: &[Matrix3<f64>],
        thr2: f64,
    ) -> Option<usize> {
        let within = |f: &Matrix3<f64>, i: usize| {
            geometry::sampson_distance_squared(f, points.point1(i), points.point2(i)) <= thr2
        };
        let on_few: Vec<usize> = candidates
            .iter()
            .map(|f| few.iter().filter(|&&i| within(f, i)).count())
            .collect();
        let top = *on_few.iter().max()?;
        let mut best: Option<(usize, usize)> = None;
        for (k, f) in candidates.iter().enumerate() {
            if on_few[k] != top {
                continue;
            }
            let full = (0..points.len()).filter(|&i| within(f, i)).count();
            if best.map_or(true, |(_, b)| full > b) {
                best = Some((k, full));
            }
        }
        best.map(|(k, _)| k)
    }

    /// Preselection on a few matches chooses what the naive reference does
    /// (five-point roots of noisy matches), with the full consensus set;
    /// with every match as the few, it chooses as `best`.
    #[test]
    fn preselection_chooses_as_the_naive_reference() {
        let (exact, _) = rigid_scene(900.0);
        let (p1, p2): (Vec<_>, Vec<_>) = (0..exact.len())
            .map(|i| {
                let (a, b) = (exact.point1(i), exact.point2(i));
                let jitter = ((i * 37 % 11) as f64 - 5.0) / 2.0;
                (a, [b[0] + jitter, b[1] - 0.5 * jitter])
            })
            .unzip();
        let points = Correspondences::new(&p1, &p2).unwrap();
        let few_indices = [1, 4, 9, 16, 25, 36];
        let few = points.subset(&few_indices).unwrap();
        let scoring = ScoringSet {
            points: &points,
            preselect: Some(&few),
        };
        let everything = ScoringSet {
            points: &points,
            preselect: Some(&points),
        };
        for start in 0..30 {
            let sample: Vec<usize> = (0..5).map(|k| (start + 7 * k) % points.len()).collect();
            let subset = points.subset(&sample).unwrap();
            let all = candidates(MinimalSolver::FivePoint, &subset, 1100.0);
            let chosen = choose(MinimalSolutions::Best, scoring, all.clone(), 2.0);
            let want = naive_preselected_best(&points, &few_indices, &all, 4.0);
            assert_eq!(
                chosen.first().map(|c| c.f),
                want.map(|k| all[k]),
                "sample {sample:?}"
            );
            if let Some(c) = chosen.first() {
                let mut recount = Vec::new();
                geometry::sampson_consensus(&c.f, &points, 4.0, 0, &mut recount);
                assert_eq!(c.consensus, recount);
            }
            let plain = choose(
                MinimalSolutions::Best,
                ScoringSet::all(&points),
                all.clone(),
                2.0,
            );
            assert_eq!(choose(MinimalSolutions::Best, everything, all, 2.0), plain);
        }
    }

    /// Two candidates, each exact for one half of the matches: the one that
    /// explains more of all matches wins without preselection, the one
    /// that explains more of the few wins with it (they are its matches).
    #[test]
    fn preselection_can_overrule_the_full_count() {
        let (points, truth) = rigid_scene(900.0);
        // The matches 0..25 moved by `truth`; 25..40 replaced by matches
        // that `other` explains exactly (a pure translation along x).
        let other = Matrix3::new(0.0, 0.0, 0.0, 0.0, 0.0, -1.0, 0.0, 1.0, 0.0);
        let (mut p1, mut p2): (Vec<_>, Vec<_>) = (0..25)
            .map(|i| (points.point1(i), points.point2(i)))
            .unzip();
        for i in 25..40 {
            let y = 30.0 * i as f64 - 900.0;
            p1.push([3.0 * i as f64, y]);
            p2.push([3.0 * i as f64 + 40.0, y]);
        }
        let points = Correspondences::new(&p1, &p2).unwrap();
        let candidates = vec![other, truth];
        let naive = ScoringSet::all(&points);
        let plain = choose(MinimalSolutions::Best, naive, candidates.clone(), 1.0);
        assert_eq!(plain[0].f, truth);
        assert_eq!(plain[0].consensus, (0..25).collect::<Vec<_>>());
        let few_indices = [3, 26, 30, 33, 37];
        let few = points.subset(&few_indices).unwrap();
        let scoring = ScoringSet {
            points: &points,
            preselect: Some(&few),
        };
        let chosen = choose(MinimalSolutions::Best, scoring, candidates.clone(), 1.0);
        assert_eq!(chosen[0].f, other);
        assert_eq!(chosen[0].consensus, (25..40).collect::<Vec<_>>());
        assert_eq!(
            naive_preselected_best(&points, &few_indices, &candidates, 1.0),
            Some(0)
        );
    }

    #[test]
    fn five_point_at_a_wrong_focal_is_no_longer_exact() {
        let (points, truth) = rigid_scene(900.0);
        let subset = points.subset(&[0, 5, 10, 15, 20]).unwrap();
        let at_prior = candidates(MinimalSolver::FivePoint, &subset, 1200.0);
        assert!(!at_prior.iter().any(|f| same_up_to_scale(f, &truth)));
    }

    #[test]
    fn degenerate_samples_give_no_candidate() {
        let p = [[1.0, 2.0]; 7];
        let subset = Correspondences::new(&p, &p).unwrap();
        for solver in [
            MinimalSolver::SevenPoint,
            MinimalSolver::FivePoint,
            MinimalSolver::SixPointFocal,
        ] {
            let size = solver.sample_size(8);
            let sub = subset.subset(&(0..size).collect::<Vec<_>>()).unwrap();
            assert!(candidates(solver, &sub, 800.0).is_empty(), "{solver:?}");
        }
    }
}
