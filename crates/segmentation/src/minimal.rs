//! Step 2 with the minimal solvers other than the 8-point
//! ([`MinimalSolver`]): a sample's candidate fundamental matrices, the
//! choice among them, and the matches refinement starts from.

use crate::{MinimalSolutions, MinimalSolver};
use geometry::{
    five_point, sampson_distance_squared, seven_point, six_point_focal, Correspondences,
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
    let bearing = |p: [f64; 2]| Vector3::new(p[0] / focal, p[1] / focal, 1.0);
    let q1: Vec<Vector3<f64>> = (0..subset.len())
        .map(|i| bearing(subset.point1(i)))
        .collect();
    let q2: Vec<Vector3<f64>> = (0..subset.len())
        .map(|i| bearing(subset.point2(i)))
        .collect();
    let k_inv = Matrix3::from_diagonal(&Vector3::new(1.0 / focal, 1.0 / focal, 1.0));
    five_point(&q1, &q2)
        .unwrap_or_default()
        .into_iter()
        .map(|e| k_inv * e * k_inv)
        .collect()
}

/// The indices of the matches within `thr_px` of `f` (Sampson distance,
/// Eq. 23), increasing.
pub(crate) fn consensus(points: &Correspondences, f: &Matrix3<f64>, thr_px: f64) -> Vec<usize> {
    let thr2 = thr_px * thr_px;
    (0..points.len())
        .filter(|&i| sampson_distance_squared(f, points.point1(i), points.point2(i)) <= thr2)
        .collect()
}

/// The candidates that become hypotheses: all of them, or the one with the
/// largest consensus (the first on ties).
pub(crate) fn choose(
    choice: MinimalSolutions,
    points: &Correspondences,
    candidates: Vec<Matrix3<f64>>,
    thr_px: f64,
) -> Vec<Matrix3<f64>> {
    match choice {
        MinimalSolutions::All => candidates,
        MinimalSolutions::Best => {
            let mut best: Option<(usize, Matrix3<f64>)> = None;
            for f in candidates {
                let support = consensus(points, &f, thr_px).len();
                match &best {
                    Some((s, _)) if *s >= support => {}
                    _ => best = Some((support, f)),
                }
            }
            best.map(|(_, f)| f).into_iter().collect()
        }
    }
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
            let best = choose(MinimalSolutions::Best, &points, all.clone(), 0.5);
            assert_eq!(best.len(), 1);
            assert!(same_up_to_scale(&best[0], &truth), "{solver:?}");
            assert_eq!(consensus(&points, &best[0], 0.5).len(), points.len());
            assert_eq!(
                choose(MinimalSolutions::All, &points, all.clone(), 0.5),
                all
            );
        }
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
