//! The minimal solver (5-point E): exact recovery on noiseless scenes,
//! agreement with PoseLib 2.0.5 (fixture made by
//! scripts/make_minimal_solver_fixtures.py), constraint residuals of every
//! returned solution, determinism, and errors on bad input.

mod common;

use common::{intrinsics, json_matrix, json_rows, random_scene};
use geometry::{five_point, Correspondences, FivePointRoots, GeometryError};
use nalgebra::{Matrix3, Vector3};
use proptest::prelude::*;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use serde_json::Value;

/// `min(‖â − b̂‖, ‖â + b̂‖)` of the unit-norm matrices: the distance up to
/// scale and sign.
fn projective_distance(a: &Matrix3<f64>, b: &Matrix3<f64>) -> f64 {
    let (a, b) = (a / a.norm(), b / b.norm());
    (a - b).norm().min((a + b).norm())
}

/// The smallest projective distance from `target` to any of `candidates`.
fn closest(candidates: &[Matrix3<f64>], target: &Matrix3<f64>) -> f64 {
    candidates
        .iter()
        .map(|c| projective_distance(c, target))
        .fold(f64::INFINITY, f64::min)
}

/// `‖2 E Eᵀ E − tr(E Eᵀ) E‖` for unit `E` (zero for an essential matrix).
fn trace_residual(e: &Matrix3<f64>) -> f64 {
    let e = e / e.norm();
    let eet = e * e.transpose();
    (2.0 * eet * e - eet.trace() * e).norm()
}

fn fixture() -> Value {
    serde_json::from_str(include_str!("fixtures/minimal_solvers.json")).unwrap()
}

fn bearings(v: &Value) -> Vec<Vector3<f64>> {
    json_rows::<3>(v).into_iter().map(Vector3::from).collect()
}

/// Largest `|q2ᵀ M q1| / (‖q1‖ ‖q2‖ ‖M‖)` over the matches.
fn epipolar_residual(m: &Matrix3<f64>, q1: &[Vector3<f64>], q2: &[Vector3<f64>]) -> f64 {
    q1.iter()
        .zip(q2)
        .map(|(a, b)| (b.transpose() * m * a)[0].abs() / (a.norm() * b.norm() * m.norm()))
        .fold(0.0, f64::max)
}

fn homogeneous(points: &Correspondences) -> (Vec<Vector3<f64>>, Vec<Vector3<f64>>) {
    (0..points.len())
        .map(|i| {
            let ([a, b], [c, d]) = (points.point1(i), points.point2(i));
            (Vector3::new(a, b, 1.0), Vector3::new(c, d, 1.0))
        })
        .unzip()
}

/// Worst-case figures of a solver's matrix sets against an oracle's.
#[derive(Debug, Default)]
struct SetComparison {
    /// Largest distance from an oracle matrix to the closest of ours.
    worst_match: f64,
    /// Largest distance from the truth to the closest of ours (noise-free cases).
    worst_truth: f64,
    /// Largest residual of our solutions.
    worst_residual: f64,
    /// Our solution count per case.
    counts: Vec<usize>,
}

/// Runs `solve` on every case of fixture section `section`, asserts the
/// same solution count as the oracle list `oracle`, passes each oracle
/// matrix and its distance to ours to `check_match`, and collects
/// `residual` of each of our solutions and the distance of the truth
/// (`truth` key, noise-free cases) to ours.
fn compare_with_oracle(
    section: &str,
    oracle: &str,
    truth: &str,
    solve: impl Fn(&Value) -> Vec<Matrix3<f64>>,
    residual: impl Fn(&Value, &Matrix3<f64>) -> f64,
    check_match: impl Fn(usize, &Matrix3<f64>, f64),
) -> SetComparison {
    let json = fixture();
    let mut out = SetComparison::default();
    for (k, case) in json[section].as_array().unwrap().iter().enumerate() {
        let ours = solve(case);
        let theirs: Vec<Matrix3<f64>> = case[oracle]
            .as_array()
            .unwrap()
            .iter()
            .map(json_matrix)
            .collect();
        assert_eq!(
            ours.len(),
            theirs.len(),
            "{section} case {k}: solution count"
        );
        out.counts.push(ours.len());
        for m in &theirs {
            let d = closest(&ours, m);
            check_match(k, m, d);
            out.worst_match = out.worst_match.max(d);
        }
        for m in &ours {
            out.worst_residual = out.worst_residual.max(residual(case, m));
        }
        if case["noise_px"].as_f64().unwrap() == 0.0 {
            out.worst_truth = out
                .worst_truth
                .max(closest(&ours, &json_matrix(&case[truth])));
        }
    }
    out
}

#[test]
fn five_point_matches_poselib_and_satisfies_its_constraints() {
    let bearing_pair = |case: &Value| (bearings(&case["bearings1"]), bearings(&case["bearings2"]));
    let c = compare_with_oracle(
        "five_point",
        "poselib",
        "essential_true",
        |case| {
            let (q1, q2) = bearing_pair(case);
            five_point(&q1, &q2).unwrap()
        },
        |case, e| {
            let (q1, q2) = bearing_pair(case);
            epipolar_residual(e, &q1, &q2)
                .max(trace_residual(e))
                .max(e.determinant().abs())
        },
        // PoseLib's roots (Sturm bisection) carry errors up to 1e-3 on
        // some samples; its own trace residual bounds them.
        |k, e, d| assert!(d < 1e-6 || d < 10.0 * trace_residual(e), "case {k}: {d:e}"),
    );
    println!("5-point vs PoseLib: {c:?}");
    assert!(c.worst_truth < 1e-8, "{c:?}");
    assert!(c.worst_residual < 1e-13, "{c:?}");
}

#[test]
fn five_point_recovers_the_true_essential_matrix_on_noiseless_scenes() {
    let mut rng = ChaCha8Rng::seed_from_u64(51);
    let mut worst = 0.0_f64;
    for _ in 0..200 {
        let scene = random_scene(&mut rng, 5, 0, 0.0);
        let (k1, k2) = (intrinsics(scene.focal1), intrinsics(scene.focal2));
        let (p1, p2) = homogeneous(&scene.points);
        let q1: Vec<_> = p1.iter().map(|p| k1.try_inverse().unwrap() * p).collect();
        let q2: Vec<_> = p2.iter().map(|p| k2.try_inverse().unwrap() * p).collect();
        let e_true = k2.transpose() * scene.f_true * k1;
        let ours = five_point(&q1, &q2).unwrap();
        assert!(
            ours.len() <= 10 && ours.len() % 2 == 0,
            "{} solutions",
            ours.len()
        );
        worst = worst.max(closest(&ours, &e_true));
    }
    println!("5-point: worst distance to the truth over 200 scenes {worst:e}");
    assert!(worst < 1e-8, "{worst:e}");
}

/// The unpolished roots are the polished solutions to about 1e-7, and
/// polishing any of them gives [`five_point`]'s matrix bit for bit, on
/// noisy samples (where the polish has work to do) and noiseless ones.
#[test]
fn five_point_roots_polish_to_the_solver_s_solutions() {
    let mut rng = ChaCha8Rng::seed_from_u64(52);
    let mut worst_unpolished = 0.0_f64;
    for case in 0..200 {
        let noise = if case % 2 == 0 { 0.0 } else { 0.5 };
        let scene = random_scene(&mut rng, 5, 0, noise);
        let (k1, k2) = (intrinsics(scene.focal1), intrinsics(scene.focal2));
        let (p1, p2) = homogeneous(&scene.points);
        let q1: Vec<_> = p1.iter().map(|p| k1.try_inverse().unwrap() * p).collect();
        let q2: Vec<_> = p2.iter().map(|p| k2.try_inverse().unwrap() * p).collect();
        let solutions = five_point(&q1, &q2).unwrap();
        let roots = FivePointRoots::new(&q1, &q2).unwrap();
        let polished: Vec<Matrix3<f64>> = (0..roots.len())
            .map(|k| roots.polished(k).unwrap())
            .collect();
        // Every solution is some root polished, bit for bit, and each
        // polished root is one of the solutions (duplicates merged there).
        for e in &solutions {
            assert!(polished.contains(e), "case {case}");
        }
        for (k, e) in polished.iter().enumerate() {
            assert!(solutions.iter().any(|s| projective_distance(s, e) < 1e-10));
            let unpolished = roots.unpolished(k).unwrap();
            worst_unpolished = worst_unpolished.max(projective_distance(e, &unpolished));
        }
    }
    println!("5-point: worst unpolished root against its polish {worst_unpolished:e}");
    assert!(worst_unpolished < 1e-5, "{worst_unpolished:e}");
}

#[test]
fn solvers_are_deterministic() {
    let json = fixture();
    for case in json["five_point"].as_array().unwrap().iter().take(5) {
        let (q1, q2) = (bearings(&case["bearings1"]), bearings(&case["bearings2"]));
        assert_eq!(five_point(&q1, &q2).unwrap(), five_point(&q1, &q2).unwrap());
    }
}

#[test]
fn wrong_sample_sizes_and_bad_bearings_are_typed_errors() {
    let q: Vec<Vector3<f64>> = (0..5).map(|i| Vector3::new(i as f64, 1.0, 2.0)).collect();
    assert_eq!(
        five_point(&q[..4], &q[..4]),
        Err(GeometryError::SampleSize { got: 4, needed: 5 })
    );
    assert!(matches!(
        five_point(&q, &q[..4]),
        Err(GeometryError::LengthMismatch { .. })
    ));
    let mut bad = q.clone();
    bad[3].y = f64::NAN;
    assert_eq!(
        five_point(&q, &bad),
        Err(GeometryError::NonFinite {
            field: "bearing2",
            index: 3
        })
    );
    bad[3] = Vector3::zeros();
    assert_eq!(
        five_point(&bad, &q),
        Err(GeometryError::ZeroBearing { image: 1, index: 3 })
    );
}

#[test]
fn degenerate_samples_are_reported() {
    let mut rng = ChaCha8Rng::seed_from_u64(81);
    let scene = random_scene(&mut rng, 7, 0, 0.0);
    // A repeated match: the system loses rank.
    let (p1, p2) = homogeneous(&scene.points);
    let (q1, q2) = (
        [p1[0], p1[1], p1[2], p1[2], p1[3]],
        [p2[0], p2[1], p2[2], p2[2], p2[3]],
    );
    assert!(matches!(
        five_point(&q1, &q2),
        Err(GeometryError::Degenerate(_))
    ));
}

fn coordinate() -> impl Strategy<Value = f64> {
    prop_oneof![
        -1e3..1e3f64,
        Just(0.0),
        Just(1e300),
        Just(-1e-300),
        Just(f64::NAN),
        Just(f64::INFINITY),
        -1e200..1e200f64,
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Garbage in: an error value or solutions, never a panic; any solution
    /// returned is finite.
    #[test]
    fn garbage_never_panics(values in prop::collection::vec(coordinate(), 30)) {
        let q: Vec<Vector3<f64>> = values.chunks(3).map(|c| Vector3::new(c[0], c[1], c[2])).collect();
        if let Ok(es) = five_point(&q[..5], &q[5..]) {
            prop_assert!(es.iter().all(|e| e.iter().all(|v| v.is_finite())));
        }
    }
}
