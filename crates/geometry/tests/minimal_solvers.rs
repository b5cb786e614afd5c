//! The minimal solvers (5-point E, 6-point shared focal, 7-point F):
//! exact recovery on noiseless scenes, agreement with PoseLib 2.0.5 and a
//! direct 7-point transcription (fixture made by
//! scripts/make_minimal_solver_fixtures.py), constraint residuals of every
//! returned solution, determinism, and errors on bad input.

mod common;

use common::{intrinsics, json_matrix, json_rows, random_scene, sample_indices};
use geometry::{
    five_point, seven_point, six_point_focal, Correspondences, FivePointRoots, FocalSolution,
    GeometryError,
};
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

fn correspondences(case: &Value) -> Correspondences {
    Correspondences::new(
        &json_rows::<2>(&case["points1"]),
        &json_rows::<2>(&case["points2"]),
    )
    .unwrap()
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

/// The focal and `E` of the solution whose focal is closest to `focal`.
fn nearest_focal(solutions: &[FocalSolution], focal: f64) -> Option<&FocalSolution> {
    solutions
        .iter()
        .min_by(|a, b| (a.focal - focal).abs().total_cmp(&(b.focal - focal).abs()))
}

fn check_focal_solution(s: &FocalSolution, points: &Correspondences) -> f64 {
    let (p1, p2) = homogeneous(points);
    let k = intrinsics(s.focal);
    let e = k * s.fundamental * k;
    assert!(s.focal > 0.0);
    assert!(projective_distance(&e, &s.essential) < 1e-12);
    epipolar_residual(&s.fundamental, &p1, &p2)
        .max(trace_residual(&s.essential))
        .max(s.fundamental.determinant().abs())
}

#[test]
fn six_point_matches_poselib_and_satisfies_its_constraints() {
    let json = fixture();
    let (mut worst_focal, mut worst_e, mut worst_residual) = (0.0_f64, 0.0_f64, 0.0_f64);
    let mut counts = Vec::new();
    let (mut accurate, mut inaccurate) = (0, 0);
    for (k, case) in json["six_point"].as_array().unwrap().iter().enumerate() {
        let points = correspondences(case);
        let ours = six_point_focal(&points).unwrap();
        counts.push(ours.len());
        let theirs = case["poselib"].as_array().unwrap();
        assert!(
            ours.len() >= theirs.len(),
            "case {k}: fewer solutions than PoseLib"
        );
        for t in theirs {
            let focal = t["focal"].as_f64().unwrap();
            let essential = json_matrix(&t["essential"]);
            // PoseLib's own error: its F = K⁻¹ E K⁻¹ on the six matches.
            let k_inv = intrinsics(1.0 / focal);
            let (p1, p2) = homogeneous(&points);
            let theirs_residual = epipolar_residual(&(k_inv * essential * k_inv), &p1, &p2);
            let Some(s) = nearest_focal(&ours, focal) else {
                assert!(
                    theirs_residual > 1e-6,
                    "case {k}: PoseLib's f = {focal} missed"
                );
                continue;
            };
            let (df, de) = (
                (s.focal - focal).abs() / focal,
                projective_distance(&s.essential, &essential),
            );
            if theirs_residual < 1e-12 {
                worst_focal = worst_focal.max(df);
                worst_e = worst_e.max(de);
                accurate += 1;
            } else {
                // An inaccurate PoseLib root: close to ours, or no root.
                assert!(
                    df < 1e-2 || theirs_residual > 1e-6,
                    "case {k}: f {focal} vs {}",
                    s.focal
                );
                inaccurate += 1;
            }
        }
        for s in &ours {
            worst_residual = worst_residual.max(check_focal_solution(s, &points));
        }
    }
    println!("6-point: {accurate} accurate PoseLib roots: max relative focal difference {worst_focal:e}, E distance {worst_e:e}; {inaccurate} inaccurate ones; our residual {worst_residual:e}, counts {counts:?}");
    assert!(worst_focal < 1e-6, "focal {worst_focal:e}");
    assert!(worst_e < 1e-6, "E {worst_e:e}");
    assert!(worst_residual < 1e-12, "residual {worst_residual:e}");
}

#[test]
fn six_point_recovers_the_true_focal_on_noiseless_scenes() {
    let json = fixture();
    let mut worst = (0.0_f64, 0.0_f64);
    let mut check = |points: &Correspondences, focal: f64, e_true: &Matrix3<f64>| {
        let ours = six_point_focal(points).unwrap();
        assert!(ours.len() <= 15);
        let s = nearest_focal(&ours, focal).unwrap();
        worst.0 = worst.0.max((s.focal - focal).abs() / focal);
        worst.1 = worst.1.max(projective_distance(&s.essential, e_true));
    };
    for case in json["six_point"].as_array().unwrap() {
        if case["noise_px"].as_f64().unwrap() == 0.0 {
            let focal = case["focal_true"].as_f64().unwrap();
            check(
                &correspondences(case),
                focal,
                &json_matrix(&case["essential_true"]),
            );
        }
    }
    let mut rng = ChaCha8Rng::seed_from_u64(61);
    let mut done = 0;
    while done < 200 {
        let scene = random_scene(&mut rng, 6, 0, 0.0);
        // One camera: re-project image 2 with the focal of image 1.
        let ratio = scene.focal1 / scene.focal2;
        let p1: Vec<[f64; 2]> = (0..6).map(|i| scene.points.point1(i)).collect();
        let p2: Vec<[f64; 2]> = (0..6)
            .map(|i| scene.points.point2(i).map(|v| v * ratio))
            .collect();
        let k = intrinsics(scene.focal1);
        let k2 = intrinsics(scene.focal2);
        let e_true = k2.transpose() * scene.f_true * k;
        check(
            &Correspondences::new(&p1, &p2).unwrap(),
            scene.focal1,
            &e_true,
        );
        done += 1;
    }
    println!(
        "6-point: worst relative focal error {:e}, E distance {:e}",
        worst.0, worst.1
    );
    assert!(worst.0 < 1e-8 && worst.1 < 1e-8, "{worst:?}");
}

#[test]
fn seven_point_matches_the_direct_reference() {
    let c = compare_with_oracle(
        "seven_point",
        "reference",
        "fundamental_true",
        |case| seven_point(&correspondences(case)).unwrap(),
        |case, f| {
            let (p1, p2) = homogeneous(&correspondences(case));
            epipolar_residual(f, &p1, &p2).max(f.determinant().abs())
        },
        |_, _, _| {},
    );
    println!("7-point vs reference: {c:?}");
    assert!(c.counts.iter().all(|&n| n == 1 || n == 3), "{c:?}");
    assert!(c.worst_match < 1e-9, "{c:?}");
    assert!(c.worst_truth < 1e-9, "{c:?}");
    assert!(c.worst_residual < 1e-12, "{c:?}");
}

#[test]
fn seven_point_recovers_the_true_fundamental_matrix_on_noiseless_scenes() {
    let mut rng = ChaCha8Rng::seed_from_u64(71);
    let mut worst = 0.0_f64;
    for _ in 0..200 {
        let scene = random_scene(&mut rng, 30, 0, 0.0);
        let sample = scene
            .points
            .subset(&sample_indices(&mut rng, 30, 7))
            .unwrap();
        worst = worst.max(closest(&seven_point(&sample).unwrap(), &scene.f_true));
    }
    println!("7-point: worst distance to the truth over 200 scenes {worst:e}");
    assert!(worst < 1e-8, "{worst:e}");
}

#[test]
fn solvers_are_deterministic() {
    let json = fixture();
    for case in json["five_point"].as_array().unwrap().iter().take(5) {
        let (q1, q2) = (bearings(&case["bearings1"]), bearings(&case["bearings2"]));
        assert_eq!(five_point(&q1, &q2).unwrap(), five_point(&q1, &q2).unwrap());
    }
    for case in json["six_point"].as_array().unwrap().iter().take(5) {
        let p = correspondences(case);
        assert_eq!(six_point_focal(&p).unwrap(), six_point_focal(&p).unwrap());
    }
    for case in json["seven_point"].as_array().unwrap().iter().take(5) {
        let p = correspondences(case);
        assert_eq!(seven_point(&p).unwrap(), seven_point(&p).unwrap());
    }
}

#[test]
fn wrong_sample_sizes_and_bad_bearings_are_typed_errors() {
    let p = |n: usize| {
        let pts: Vec<[f64; 2]> = (0..n).map(|i| [i as f64 * 10.0, (i * i) as f64]).collect();
        Correspondences::new(&pts, &pts).unwrap()
    };
    assert_eq!(
        seven_point(&p(8)),
        Err(GeometryError::SampleSize { got: 8, needed: 7 })
    );
    assert_eq!(
        six_point_focal(&p(5)),
        Err(GeometryError::SampleSize { got: 5, needed: 6 })
    );
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
    let repeated = scene.points.subset(&[0, 1, 2, 3, 4, 5, 5]).unwrap();
    assert!(matches!(
        seven_point(&repeated),
        Err(GeometryError::Degenerate(_))
    ));
    let repeated = scene.points.subset(&[0, 1, 2, 3, 3, 4]).unwrap();
    assert!(matches!(
        six_point_focal(&repeated),
        Err(GeometryError::Degenerate(_))
    ));
    let (p1, p2) = homogeneous(&scene.points);
    let (q1, q2) = (
        [p1[0], p1[1], p1[2], p1[2], p1[3]],
        [p2[0], p2[1], p2[2], p2[2], p2[3]],
    );
    assert!(matches!(
        five_point(&q1, &q2),
        Err(GeometryError::Degenerate(_))
    ));
    // All points of image 1 at one place.
    let same = Correspondences::new(
        &[[5.0, 5.0]; 7],
        &(0..7).map(|i| scene.points.point2(i)).collect::<Vec<_>>(),
    )
    .unwrap();
    assert!(matches!(
        seven_point(&same),
        Err(GeometryError::Degenerate(_))
    ));
    let origin = Correspondences::new(&[[0.0, 0.0]; 6], &[[0.0, 0.0]; 6]).unwrap();
    assert!(matches!(
        six_point_focal(&origin),
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
        let pts: Vec<[f64; 2]> = values.chunks(2).map(|c| [c[0], c[1]]).collect();
        for n in [6, 7] {
            let Ok(points) = Correspondences::new(&pts[..n], &pts[n..2 * n]) else { continue };
            if n == 6 {
                if let Ok(sols) = six_point_focal(&points) {
                    prop_assert!(sols.iter().all(|s| s.focal > 0.0 && s.fundamental.iter().all(|v| v.is_finite())));
                }
            } else if let Ok(fs) = seven_point(&points) {
                prop_assert!(fs.iter().all(|f| f.iter().all(|v| v.is_finite())));
            }
        }
    }
}
