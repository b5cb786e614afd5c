//! Sampson and symmetric epipolar distances: invariances, agreement between
//! the single-point and batch forms, and known values.

mod common;

use geometry::{
    frob_distance, sampson_consensus, sampson_distance, sampson_distance_signed,
    sampson_distance_squared, sampson_distances_squared, sampson_residuals_signed,
    symmetric_epipolar_distance, Correspondences, SampsonModels,
};
use nalgebra::{Matrix3, Vector3};
use proptest::prelude::*;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

fn matrix() -> impl Strategy<Value = Matrix3<f64>> {
    prop::array::uniform9(-1.0..1.0f64)
        .prop_filter("non-zero", |a| a.iter().any(|v| v.abs() > 1e-3))
        .prop_map(|a| Matrix3::from_row_slice(&a))
}

fn pixel() -> impl Strategy<Value = [f64; 2]> {
    [-500.0..500.0f64, -400.0..400.0f64]
}

/// Any non-zero factor: sign times 10^e, e in [-250, 250].
fn factor() -> impl Strategy<Value = f64> {
    (any::<bool>(), -250.0..250.0f64, 1.0..10.0f64).prop_map(|(neg, e, m)| {
        if neg {
            -m * 10f64.powf(e)
        } else {
            m * 10f64.powf(e)
        }
    })
}

/// Equal up to rounding: 1e-12 relative, or 1e-9 px on the square root of a
/// squared distance (`e = x2ᵀ F x1` cancels, so its absolute rounding error
/// scales with the coordinates, not with the distance), or both infinite.
fn close(a: f64, b: f64) -> bool {
    a == b
        || (a - b).abs() <= 1e-12 * a.abs().max(b.abs())
        || (a.abs().sqrt() - b.abs().sqrt()).abs() <= 1e-9
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn distances_are_invariant_to_scaling_and_negating_f(
        f in matrix(), k in factor(), p1 in pixel(), p2 in pixel(),
    ) {
        let g = f * k;
        let d = sampson_distance_squared(&f, p1, p2);
        prop_assert!(!d.is_nan() && d >= 0.0);
        prop_assert!(close(d, sampson_distance_squared(&g, p1, p2)), "{} vs {}", d, sampson_distance_squared(&g, p1, p2));
        prop_assert!(close(d, sampson_distance_squared(&-f, p1, p2)));
        prop_assert!(close(sampson_distance(&f, p1, p2), sampson_distance(&g, p1, p2)));
        let s = sampson_distance_signed(&f, p1, p2);
        let sg = sampson_distance_signed(&g, p1, p2);
        prop_assert!(close(s, k.signum() * sg), "{} vs {}", s, sg);
        prop_assert!(close(s, -sampson_distance_signed(&-f, p1, p2)));
        prop_assert!(close(s * s, d));
        let e = symmetric_epipolar_distance(&f, p1, p2);
        prop_assert!(close(e, symmetric_epipolar_distance(&g, p1, p2)));
        prop_assert!(close(e, symmetric_epipolar_distance(&-f, p1, p2)));
        // Sampson is a first-order approximation of the geometric error and
        // never exceeds the symmetric epipolar distance.
        prop_assert!(d <= e * (1.0 + 1e-12));
        prop_assert!(frob_distance(&f, &g) < 1e-12);
    }

    #[test]
    fn batch_forms_equal_the_single_point_forms(
        f in matrix(), k in factor(), pts in prop::collection::vec((pixel(), pixel()), 0..40),
    ) {
        let (p1, p2): (Vec<_>, Vec<_>) = pts.into_iter().unzip();
        let c = Correspondences::new(&p1, &p2).unwrap();
        let g = f * k;
        let mut squared = vec![f64::NAN; p1.len()];
        let mut signed = vec![f64::NAN; p1.len()];
        sampson_distances_squared(&g, &c, &mut squared);
        sampson_residuals_signed(&g, &c, &mut signed);
        for i in 0..p1.len() {
            let expected = sampson_distance_squared(&f, p1[i], p2[i]);
            prop_assert!(close(squared[i], expected), "{}: {} vs {}", i, squared[i], expected);
            prop_assert!(close(signed[i].abs(), expected.sqrt()));
            prop_assert!(close(signed[i], sampson_distance_signed(&g, p1[i], p2[i])));
        }
    }

    /// The point-major form gives the column form's distances bit for bit,
    /// whatever the models' scales (the preference matrix depends on it).
    #[test]
    fn models_form_equals_the_column_form_bit_for_bit(
        fs in prop::collection::vec((matrix(), factor()), 1..6),
        pts in prop::collection::vec((pixel(), pixel()), 1..30),
    ) {
        let fs: Vec<Matrix3<f64>> = fs.into_iter().map(|(f, k)| f * k).collect();
        let (p1, p2): (Vec<_>, Vec<_>) = pts.into_iter().unzip();
        let c = Correspondences::new(&p1, &p2).unwrap();
        let models = SampsonModels::new(&fs);
        prop_assert_eq!(models.len(), fs.len());
        let mut columns = vec![vec![0.0; p1.len()]; fs.len()];
        for (f, column) in fs.iter().zip(&mut columns) {
            sampson_distances_squared(f, &c, column);
        }
        let mut row = vec![f64::NAN; fs.len()];
        for i in 0..p1.len() {
            models.distances_squared(p1[i], p2[i], &mut row);
            for (j, column) in columns.iter().enumerate() {
                prop_assert_eq!(row[j].to_bits(), column[i].to_bits(), "point {}, model {}", i, j);
            }
        }
    }

    #[test]
    fn consensus_equals_filtering_the_single_point_distances(
        f in matrix(), k in factor(), thr in 0.0..400.0f64, at_least in 0usize..40,
        pts in prop::collection::vec((pixel(), pixel()), 0..40),
    ) {
        let (p1, p2): (Vec<_>, Vec<_>) = pts.into_iter().unzip();
        let c = Correspondences::new(&p1, &p2).unwrap();
        let g = f * k;
        let naive: Vec<usize> = (0..p1.len())
            .filter(|&i| sampson_distance_squared(&g, p1[i], p2[i]) <= thr)
            .collect();
        let mut all = vec![99];
        prop_assert!(sampson_consensus(&g, &c, thr, 0, &mut all));
        prop_assert_eq!(&all, &naive);
        let mut part = Vec::new();
        let reached = sampson_consensus(&g, &c, thr, at_least, &mut part);
        prop_assert_eq!(reached, naive.len() >= at_least);
        if reached {
            prop_assert_eq!(&part, &naive);
        }
    }
}

/// Thresholds at a match's own distance and up to two floats either side
/// (where a test that rounds differently from the division would flip),
/// zero, tiny, huge, infinite and NaN thresholds, and an F whose gradient
/// vanishes: the consensus set is the naive filter of the single-point
/// distances.
#[test]
fn consensus_equals_the_naive_filter_at_the_threshold_and_its_limits() {
    use rand::Rng;
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let n = 300;
    let p1: Vec<[f64; 2]> = (0..n).map(|_| common::random_pixel(&mut rng)).collect();
    let p2: Vec<[f64; 2]> = p1
        .iter()
        .map(|p| {
            [
                p[0] + 9.0 + rng.gen_range(-4.0..4.0),
                p[1] + rng.gen_range(-4.0..4.0),
            ]
        })
        .collect();
    let c = Correspondences::new(&p1, &p2).unwrap();
    let translation = Matrix3::new(0.0, 0.0, 0.0, 0.0, 0.0, -1.0, 0.0, 1.0, 0.0)
        + Matrix3::from_fn(|_, _| rng.gen_range(-1e-4..1e-4));
    // Gradient zero wherever x1 and x2 sit at the origin of this F's lines.
    let degenerate = Matrix3::new(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0);
    let mut thresholds = vec![
        0.0,
        f64::MIN_POSITIVE,
        1e-200,
        1e200,
        f64::INFINITY,
        f64::NAN,
    ];
    for i in 0..n {
        let d = sampson_distance_squared(&translation, p1[i], p2[i]);
        thresholds.extend((-2..=2).map(|ulps| f64::from_bits((d.to_bits() as i64 + ulps) as u64)));
    }
    for f in [translation, degenerate] {
        for &thr in &thresholds {
            let naive: Vec<usize> = (0..n)
                .filter(|&i| sampson_distance_squared(&f, p1[i], p2[i]) <= thr)
                .collect();
            let mut got = Vec::new();
            sampson_consensus(&f, &c, thr, 0, &mut got);
            assert_eq!(got, naive, "thr {thr:e}");
        }
    }
}

#[test]
fn sampson_distance_is_the_distance_to_the_epipolar_line_for_a_translation() {
    // F = [t]x, t = (1, 0, 0): x2ᵀ F x1 = y1 - y2, a² + b² = 1, c² + d² = 1.
    let f = Matrix3::new(0.0, 0.0, 0.0, 0.0, 0.0, -1.0, 0.0, 1.0, 0.0);
    for (dy, x) in [(0.0, 3.0), (1.0, -50.0), (-3.5, 200.0)] {
        let p1 = [x, 10.0];
        let p2 = [x + 17.0, 10.0 + dy];
        assert!((sampson_distance_squared(&f, p1, p2) - dy * dy / 2.0).abs() < 1e-12);
        assert!((sampson_distance_signed(&f, p1, p2) - (-dy / 2f64.sqrt())).abs() < 1e-12);
        assert!((symmetric_epipolar_distance(&f, p1, p2) - 2.0 * dy * dy).abs() < 1e-12);
    }
}

#[test]
fn zero_gradient_matches_are_at_distance_zero_or_infinity() {
    // F = [e]x: image-1 epipole at the origin, F x1 = 0 there.
    let f = common::skew(&Vector3::new(0.0, 0.0, 1.0));
    let d = sampson_distance_squared(&f, [0.0, 0.0], [0.0, 0.0]);
    assert_eq!(d, 0.0);
    let d = symmetric_epipolar_distance(&f, [0.0, 0.0], [5.0, 5.0]);
    assert!(!d.is_nan());
    // A rank-1 F with a zero gradient at the origin: e = F22 there.
    let mut g = Matrix3::zeros();
    g[(2, 2)] = 0.9;
    assert_eq!(
        sampson_distance_squared(&g, [0.0, 0.0], [0.0, 0.0]),
        f64::INFINITY
    );
    assert_eq!(
        sampson_distance_signed(&-g, [0.0, 0.0], [0.0, 0.0]),
        f64::NEG_INFINITY
    );
    assert_eq!(
        symmetric_epipolar_distance(&g, [0.0, 0.0], [0.0, 0.0]),
        f64::INFINITY
    );
    let c = Correspondences::new(&[[0.0, 0.0]], &[[3.0, 0.0]]).unwrap();
    let mut out = [0.0; 1];
    sampson_distances_squared(&g, &c, &mut out);
    assert_eq!(out[0], f64::INFINITY);
    sampson_residuals_signed(&g, &c, &mut out);
    assert_eq!(out[0], f64::INFINITY);
}

#[test]
fn batch_writes_only_the_common_prefix() {
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let scene = common::random_scene(&mut rng, 10, 0, 0.0);
    let mut short = vec![-1.0; 4];
    sampson_distances_squared(&scene.f_true, &scene.points, &mut short);
    assert!(short.iter().all(|&d| (0.0..1e-18).contains(&d)));
    let mut long = vec![-1.0; 12];
    sampson_residuals_signed(&scene.f_true, &scene.points, &mut long);
    assert!(long[..10].iter().all(|&r| r.abs() < 1e-9));
    assert_eq!(&long[10..], &[-1.0, -1.0]);
}

#[test]
fn frob_distance_is_zero_only_up_to_scale_and_sign() {
    let f = Matrix3::new(1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 0.0);
    let g = Matrix3::new(1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 0.5);
    assert!(frob_distance(&f, &(-1e-7 * f)) < 1e-15);
    let d = frob_distance(&f, &g);
    let expected = (f / f.norm() - g / g.norm()).norm();
    assert!((d - expected).abs() < 1e-15 && d > 1e-3);
    assert!(frob_distance(&f, &Matrix3::zeros()).is_nan());
}
