//! 8-point estimators: exact recovery on noiseless scenes, agreement with
//! naive SVD implementations, weights, and errors on degenerate input.

mod common;

use common::{naive_least_squares, naive_normalized, naive_rank2, point_lists, random_scene};
use geometry::{
    eight_point_normalized, eight_point_plain, eight_point_weighted, eight_point_weighted_plain,
    enforce_rank2, frob_distance, sampson_distance, Correspondences, GeometryError,
};
use nalgebra::Matrix3;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

type Estimator = fn(&Correspondences) -> Result<Matrix3<f64>, GeometryError>;

fn unit_weighted(points: &Correspondences) -> Result<Matrix3<f64>, GeometryError> {
    eight_point_weighted(points, &vec![1.0; points.len()])
}

fn random_weighted(points: &Correspondences) -> Result<Matrix3<f64>, GeometryError> {
    let mut rng = ChaCha8Rng::seed_from_u64(points.len() as u64);
    let w: Vec<f64> = (0..points.len()).map(|_| rng.gen_range(0.1..3.0)).collect();
    eight_point_weighted(points, &w)
}

fn random_weighted_plain(points: &Correspondences) -> Result<Matrix3<f64>, GeometryError> {
    let mut rng = ChaCha8Rng::seed_from_u64(points.len() as u64);
    let w: Vec<f64> = (0..points.len()).map(|_| rng.gen_range(0.1..3.0)).collect();
    eight_point_weighted_plain(points, &w)
}

const VARIANTS: [(&str, Estimator); 5] = [
    ("plain", eight_point_plain),
    ("normalized", eight_point_normalized),
    ("weighted (unit)", unit_weighted),
    ("weighted (random)", random_weighted),
    ("weighted plain (random)", random_weighted_plain),
];

#[test]
fn every_variant_recovers_f_exactly_from_noiseless_scenes() {
    for seed in 0..20 {
        for n in [8, 9, 15, 60, 300] {
            let mut rng = ChaCha8Rng::seed_from_u64(seed);
            let scene = random_scene(&mut rng, n, 0, 0.0);
            for (name, estimate) in VARIANTS {
                let f = estimate(&scene.points).unwrap();
                let d = frob_distance(&f, &scene.f_true);
                assert!(d < 1e-8, "{name}, seed {seed}, N {n}: FROB {d:e}");
                assert!((f.norm() - 1.0).abs() < 1e-12, "{name}: not unit norm");
                assert!(f.determinant().abs() < 1e-12, "{name}: not rank 2");
            }
        }
    }
}

#[test]
fn true_matches_have_zero_sampson_distance_to_the_true_f() {
    for seed in 0..20 {
        let mut rng = ChaCha8Rng::seed_from_u64(100 + seed);
        let scene = random_scene(&mut rng, 200, 0, 0.0);
        for i in 0..scene.points.len() {
            let d = sampson_distance(
                &scene.f_true,
                scene.points.point1(i),
                scene.points.point2(i),
            );
            assert!(d < 1e-9, "seed {seed}, match {i}: {d:e} px");
        }
    }
}

#[test]
fn true_f_satisfies_the_scene_construction() {
    // The oracle itself: F = K2⁻ᵀ [t]x R K1⁻¹ must map x1 to a line through x2
    // and be rank 2; noisy matches must not satisfy it exactly.
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let scene = random_scene(&mut rng, 50, 0, 1.0);
    assert!(scene.f_true.determinant().abs() < 1e-12 * scene.f_true.norm().powi(3));
    let mean = (0..50)
        .map(|i| {
            sampson_distance(
                &scene.f_true,
                scene.points.point1(i),
                scene.points.point2(i),
            )
        })
        .sum::<f64>()
        / 50.0;
    assert!(mean > 0.1 && mean < 3.0, "mean Sampson distance {mean}");
}

#[test]
fn plain_variant_equals_the_svd_of_the_unnormalised_design_matrix() {
    for seed in 0..10 {
        // N = 8 (exactly determined: the null-space path) and overdetermined.
        for (n, outliers) in [(8, 0), (6, 2), (9, 0), (12, 2), (100, 20)] {
            let mut rng = ChaCha8Rng::seed_from_u64(200 + seed);
            let scene = random_scene(&mut rng, n, outliers, 0.7);
            let (p1, p2) = point_lists(&scene.points);
            let expected = naive_rank2(&naive_least_squares(&p1, &p2, &vec![1.0; p1.len()]));
            let f = eight_point_plain(&scene.points).unwrap();
            let d = frob_distance(&f, &expected);
            assert!(d < 1e-9, "seed {seed}, N {}: FROB {d:e}", n + outliers);
        }
    }
}

#[test]
fn weighted_plain_variant_equals_the_svd_of_the_weighted_design_matrix() {
    for seed in 0..10 {
        // Exactly 8 positive weights (the null-space path), and more; zero
        // weights among them.
        for (n, outliers, zeros) in [(8, 0, 0), (9, 2, 3), (12, 2, 1), (100, 20, 30)] {
            let mut rng = ChaCha8Rng::seed_from_u64(600 + seed);
            let scene = random_scene(&mut rng, n, outliers, 0.7);
            let (p1, p2) = point_lists(&scene.points);
            let mut w: Vec<f64> = (0..p1.len()).map(|_| rng.gen_range(0.05..4.0)).collect();
            w.iter_mut().rev().take(zeros).for_each(|v| *v = 0.0);
            let expected = naive_rank2(&naive_least_squares(&p1, &p2, &w));
            let f = eight_point_weighted_plain(&scene.points, &w).unwrap();
            let d = frob_distance(&f, &expected);
            assert!(d < 1e-9, "seed {seed}, N {}: FROB {d:e}", n + outliers);
            // Scaling all weights does not move the minimiser.
            let scaled: Vec<f64> = w.iter().map(|v| v * 37.5).collect();
            let g = eight_point_weighted_plain(&scene.points, &scaled).unwrap();
            assert!(frob_distance(&f, &g) < 1e-12, "seed {seed}: scale");
        }
    }
}

#[test]
fn unit_weights_give_the_plain_estimate_bit_for_bit() {
    for seed in 0..10 {
        let mut rng = ChaCha8Rng::seed_from_u64(700 + seed);
        let scene = random_scene(&mut rng, [8, 30][seed as usize % 2], 5, 0.5);
        let unit = vec![1.0; scene.points.len()];
        assert_eq!(
            eight_point_weighted_plain(&scene.points, &unit),
            eight_point_plain(&scene.points)
        );
    }
}

#[test]
fn normalised_and_weighted_variants_equal_the_textbook_implementation() {
    for seed in 0..10 {
        let mut rng = ChaCha8Rng::seed_from_u64(300 + seed);
        let scene = random_scene(&mut rng, 80, 20, 0.7);
        let (p1, p2) = point_lists(&scene.points);
        let n = p1.len();
        let unit = vec![1.0; n];
        let d = frob_distance(
            &eight_point_normalized(&scene.points).unwrap(),
            &naive_normalized(&p1, &p2, &unit),
        );
        assert!(d < 1e-10, "normalized, seed {seed}: FROB {d:e}");
        let w: Vec<f64> = (0..n).map(|_| rng.gen_range(0.0..2.0)).collect();
        let d = frob_distance(
            &eight_point_weighted(&scene.points, &w).unwrap(),
            &naive_normalized(&p1, &p2, &w),
        );
        assert!(d < 1e-10, "weighted, seed {seed}: FROB {d:e}");
    }
}

#[test]
fn normalised_differs_from_plain_on_noisy_data() {
    // The two minimise different algebraic errors: equal answers here would
    // mean one variant silently calls the other.
    // With 8 matches they share the null vector and differ by the rank-2
    // step only (done in pixel versus normalised coordinates).
    for n in [8, 50] {
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        let scene = random_scene(&mut rng, n, 0, 1.0);
        let plain = eight_point_plain(&scene.points).unwrap();
        let normalized = eight_point_normalized(&scene.points).unwrap();
        assert!(frob_distance(&plain, &normalized) > 1e-9, "N {n}");
    }
}

#[test]
fn unit_weights_equal_the_normalised_estimate() {
    for seed in 0..10 {
        let mut rng = ChaCha8Rng::seed_from_u64(400 + seed);
        let scene = random_scene(&mut rng, 40, 10, 0.5);
        let normalized = eight_point_normalized(&scene.points).unwrap();
        for scale in [1.0, 0.01, 250.0] {
            let w = vec![scale; scene.points.len()];
            let weighted = eight_point_weighted(&scene.points, &w).unwrap();
            let d = frob_distance(&weighted, &normalized);
            assert!(d < 1e-12, "seed {seed}, weight {scale}: FROB {d:e}");
        }
    }
}

#[test]
fn zero_weights_remove_the_outliers() {
    for seed in 0..10 {
        let mut rng = ChaCha8Rng::seed_from_u64(500 + seed);
        let scene = random_scene(&mut rng, 30, 20, 0.5);
        let w: Vec<f64> = scene
            .is_inlier
            .iter()
            .map(|&b| f64::from(u8::from(b)))
            .collect();
        let weighted = eight_point_weighted(&scene.points, &w).unwrap();
        let inliers = scene.points.subset(&(0..30).collect::<Vec<_>>()).unwrap();
        let clean = eight_point_normalized(&inliers).unwrap();
        assert!(frob_distance(&weighted, &clean) < 1e-12, "seed {seed}");
        // ...and the outliers do matter when they are not removed.
        let all = eight_point_normalized(&scene.points).unwrap();
        assert!(frob_distance(&all, &clean) > 1e-3, "seed {seed}");
    }
}

#[test]
fn enforce_rank2_matches_the_naive_projection() {
    let mut rng = ChaCha8Rng::seed_from_u64(9);
    for _ in 0..50 {
        let f = Matrix3::from_fn(|_, _| rng.gen_range(-5.0..5.0));
        let g = enforce_rank2(f);
        assert!((g - naive_rank2(&f)).norm() < 1e-12 * f.norm());
        assert!(g.determinant().abs() < 1e-12 * f.norm().powi(3));
        // Idempotent.
        assert!((enforce_rank2(g) - g).norm() < 1e-12 * f.norm());
    }
    let mut nan = Matrix3::identity();
    nan[(0, 0)] = f64::NAN;
    assert!(enforce_rank2(nan)[(0, 0)].is_nan());
}

#[test]
fn fewer_than_eight_points_is_an_error() {
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let scene = random_scene(&mut rng, 7, 0, 0.0);
    let expected = GeometryError::TooFewPoints { got: 7, needed: 8 };
    for (name, estimate) in VARIANTS {
        assert_eq!(estimate(&scene.points), Err(expected.clone()), "{name}");
    }
    assert_eq!(
        eight_point_plain(&Correspondences::default()),
        Err(GeometryError::TooFewPoints { got: 0, needed: 8 })
    );
}

#[test]
fn weight_errors_name_the_problem() {
    type Weighted = fn(&Correspondences, &[f64]) -> Result<Matrix3<f64>, GeometryError>;
    let estimators: [Weighted; 2] = [eight_point_weighted, eight_point_weighted_plain];
    for estimate in estimators {
        weight_errors(estimate);
    }
}

fn weight_errors(estimate: fn(&Correspondences, &[f64]) -> Result<Matrix3<f64>, GeometryError>) {
    let mut rng = ChaCha8Rng::seed_from_u64(12);
    let scene = random_scene(&mut rng, 10, 0, 0.0);
    assert_eq!(
        estimate(&scene.points, &[1.0; 9]),
        Err(GeometryError::WeightCountMismatch {
            weights: 9,
            points: 10
        })
    );
    let mut w = vec![1.0; 10];
    w[4] = -0.5;
    assert_eq!(
        estimate(&scene.points, &w),
        Err(GeometryError::InvalidWeight {
            index: 4,
            value: -0.5
        })
    );
    w[4] = 1.0;
    w[6] = f64::INFINITY;
    assert!(matches!(
        estimate(&scene.points, &w),
        Err(GeometryError::InvalidWeight { index: 6, .. })
    ));
    w[6] = f64::NAN;
    assert!(matches!(
        estimate(&scene.points, &w),
        Err(GeometryError::InvalidWeight { index: 6, .. })
    ));
    let mut w = vec![1.0; 10];
    w[0] = 0.0;
    w[1] = 0.0;
    w[2] = 0.0;
    assert_eq!(
        estimate(&scene.points, &w),
        Err(GeometryError::TooFewWeightedPoints { got: 7, needed: 8 })
    );
    let message = GeometryError::InvalidWeight {
        index: 4,
        value: -0.5,
    }
    .to_string();
    assert!(
        message.contains("index 4") && message.contains("-0.5"),
        "{message}"
    );
}

#[test]
fn huge_coordinates_overflow_into_an_error() {
    let p1: Vec<[f64; 2]> = (0..8)
        .map(|i| [1e200 * (i as f64 + 1.0), 1e200 * ((i * i) as f64 - 3.0)])
        .collect();
    let p2: Vec<[f64; 2]> = (0..8)
        .map(|i| [1e200 * ((i * 3 % 5) as f64), -1e200 * (i as f64)])
        .collect();
    let c = Correspondences::new(&p1, &p2).unwrap();
    for (name, estimate) in VARIANTS {
        assert!(
            matches!(estimate(&c), Err(GeometryError::Overflow(_))),
            "{name}: {:?}",
            estimate(&c)
        );
    }
}
