//! Noiseless synthetic two-view geometry: F = K2^-T [t]x R K1^-1 with known
//! focal lengths and principal points.

use focal::{
    bougnoux, bougnoux_per_image, kruppa_residuals, relative_kruppa_residual, robust_focals,
    FocalFailure, FocalWeights, RobustFocalParams, KRUPPA_TOLERANCE,
};
use nalgebra::{Matrix3, Rotation3, Unit, Vector3};
use proptest::prelude::*;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

struct Scene {
    f: Matrix3<f64>,
    f1: f64,
    f2: f64,
    pp1: [f64; 2],
    pp2: [f64; 2],
}

fn intrinsics(f: f64, pp: [f64; 2]) -> Matrix3<f64> {
    Matrix3::new(f, 0.0, pp[0], 0.0, f, pp[1], 0.0, 0.0, 1.0)
}

/// A generic relative pose (rotation 5-30 degrees about a random axis,
/// random translation direction) and random focal lengths / principal
/// points.
fn random_scene(rng: &mut ChaCha8Rng, with_pp: bool) -> Scene {
    let axis = Unit::new_normalize(Vector3::new(
        rng.gen_range(-1.0..1.0),
        rng.gen_range(-1.0..1.0),
        rng.gen_range(-1.0..1.0),
    ));
    let angle = rng.gen_range(5.0_f64..30.0).to_radians();
    let r = Rotation3::from_axis_angle(&axis, angle).into_inner();
    let t = Vector3::new(
        rng.gen_range(-1.0..1.0),
        rng.gen_range(-1.0..1.0),
        rng.gen_range(-1.0..1.0),
    )
    .normalize();
    let f1 = rng.gen_range(400.0..2000.0);
    let f2 = rng.gen_range(400.0..2000.0);
    let pp = |rng: &mut ChaCha8Rng| {
        if with_pp {
            [rng.gen_range(-40.0..40.0), rng.gen_range(-30.0..30.0)]
        } else {
            [0.0, 0.0]
        }
    };
    let pp1 = pp(rng);
    let pp2 = pp(rng);
    let k1_inv = intrinsics(f1, pp1).try_inverse().unwrap();
    let k2_inv = intrinsics(f2, pp2).try_inverse().unwrap();
    let f = k2_inv.transpose() * t.cross_matrix() * r * k1_inv;
    Scene {
        f: f / f.norm(),
        f1,
        f2,
        pp1,
        pp2,
    }
}

#[test]
fn bougnoux_recovers_the_focal_lengths_of_noiseless_scenes() {
    let mut rng = ChaCha8Rng::seed_from_u64(2024);
    for i in 0..200 {
        let s = random_scene(&mut rng, i % 2 == 1);
        let (f1, f2) = bougnoux(&s.f, s.pp1, s.pp2).unwrap_or_else(|e| panic!("scene {i}: {e}"));
        assert!(
            (f1 - s.f1).abs() <= 1e-6 * s.f1,
            "scene {i}: f1 {f1} vs {}",
            s.f1
        );
        assert!(
            (f2 - s.f2).abs() <= 1e-6 * s.f2,
            "scene {i}: f2 {f2} vs {}",
            s.f2
        );
    }
}

/// A scene whose image-1 denominator is small in absolute terms (5e-10 of
/// its Cauchy–Schwarz bound, with f1 = 1855 and the principal point 28 px
/// off centre) but far from rounding noise: an absolute threshold called it
/// singular; the closed form still recovers both focal lengths.
#[test]
fn bougnoux_accepts_a_small_but_well_defined_denominator() {
    let mut rng = ChaCha8Rng::seed_from_u64(7976);
    let s = random_scene(&mut rng, true);
    for scale in [1.0, -1e-3, 1e3] {
        let (f1, f2) = bougnoux(&(s.f * scale), s.pp1, s.pp2).unwrap();
        assert!((f1 - s.f1).abs() <= 1e-6 * s.f1, "f1 {f1} vs {}", s.f1);
        assert!((f2 - s.f2).abs() <= 1e-6 * s.f2, "f2 {f2} vs {}", s.f2);
    }
}

#[test]
fn bougnoux_reports_parallel_optical_axes_as_singular() {
    // Rotation about the optical axis, translation in the image plane: the
    // optical axes are parallel and the closed form is 0 / 0.
    let r = Rotation3::from_axis_angle(&Vector3::z_axis(), 0.2).into_inner();
    let t = Vector3::new(1.0, 0.1, 0.0);
    let k_inv = intrinsics(800.0, [0.0, 0.0]).try_inverse().unwrap();
    let f = k_inv.transpose() * t.cross_matrix() * r * k_inv;
    assert_eq!(
        bougnoux_per_image(&f, [0.0; 2], [0.0; 2]),
        [Err(FocalFailure::Singular), Err(FocalFailure::Singular)]
    );
}

#[test]
fn bougnoux_rejects_invalid_input() {
    let mut f = Matrix3::identity();
    f[(1, 2)] = f64::NAN;
    assert_eq!(
        bougnoux(&f, [0.0; 2], [0.0; 2]),
        Err(FocalFailure::InvalidMatrix)
    );
    assert_eq!(
        bougnoux(&Matrix3::zeros(), [0.0; 2], [0.0; 2]),
        Err(FocalFailure::InvalidMatrix)
    );
    assert!(matches!(
        bougnoux(&Matrix3::identity(), [f64::INFINITY, 0.0], [0.0; 2]),
        Err(FocalFailure::InvalidParameter { name: "pp1", .. })
    ));
}

#[test]
fn kruppa_constraints_vanish_at_the_true_cameras() {
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    for i in 0..50 {
        let s = random_scene(&mut rng, true);
        let g = kruppa_residuals(&s.f, s.f1, s.pp1, s.f2, s.pp2).unwrap();
        let g0 = kruppa_residuals(&s.f, 1000.0, [0.0; 2], 1000.0, [0.0; 2]).unwrap();
        let scale = g0[0].abs().max(g0[1].abs());
        assert!(
            g[0].abs().max(g[1].abs()) <= 1e-9 * scale,
            "scene {i}: {g:?} vs {g0:?}"
        );
    }
}

#[test]
fn prior_on_the_constraints_is_a_fixed_point() {
    // The prior already satisfies the Kruppa constraints: the minimum-norm
    // step is zero, e_1 = 0 < 1e-8 stops at k = 1, and the answer is the
    // prior itself.
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let s = random_scene(&mut rng, false);
    let s = {
        // Same focal length in both images.
        let k = intrinsics(s.f1, [0.0; 2]).try_inverse().unwrap();
        let r = Rotation3::from_euler_angles(0.05, 0.2, -0.1).into_inner();
        let t = Vector3::new(0.6, -0.3, 0.2);
        let f = k.transpose() * t.cross_matrix() * r * k;
        Scene { f, f2: s.f1, ..s }
    };
    let params = RobustFocalParams {
        f_prior: s.f1,
        ..Default::default()
    };
    let est = robust_focals(&s.f, &params).unwrap();
    assert_eq!(est.iterations, 1);
    assert!((est.f1 - s.f1).abs() <= 1e-6 * s.f1 && (est.f2 - s.f1).abs() <= 1e-6 * s.f1);
    assert!(est.pp1.iter().chain(est.pp2.iter()).all(|v| v.abs() < 1e-6));
}

#[test]
fn pinned_principal_points_recover_the_true_focal_lengths() {
    // With the principal points pinned by a large weight, the constraints
    // leave (f1^2, f2^2) determined: the solver must land on the truth.
    let mut rng = ChaCha8Rng::seed_from_u64(99);
    let params = RobustFocalParams {
        f_prior: 1000.0,
        weights: FocalWeights::new(5e-4, 1e8, 5e-4, 1e8),
        max_iters: 100,
    };
    let mut recovered = 0;
    let n = 40;
    for _ in 0..n {
        let s = random_scene(&mut rng, false);
        if let Ok(e) = robust_focals(&s.f, &params) {
            let r = relative_kruppa_residual(&s.f, &e, params.f_prior).unwrap();
            assert!(r <= KRUPPA_TOLERANCE);
            if (e.f1.abs() - s.f1).abs() <= 1e-4 * s.f1 && (e.f2.abs() - s.f2).abs() <= 1e-4 * s.f2
            {
                recovered += 1;
            }
        }
    }
    assert!(recovered >= n * 9 / 10, "recovered {recovered}/{n}");
}

#[test]
fn robust_solver_rejects_invalid_input() {
    let f = Matrix3::new(0.0, -1e-6, 1e-3, 1e-6, 0.0, -2e-3, -1e-3, 2e-3, 1.0);
    let mut bad = f;
    bad[(0, 0)] = f64::NAN;
    assert_eq!(
        robust_focals(&bad, &RobustFocalParams::default()),
        Err(FocalFailure::InvalidMatrix)
    );
    for f_prior in [0.0, -5.0, f64::NAN, f64::INFINITY] {
        let p = RobustFocalParams {
            f_prior,
            ..Default::default()
        };
        assert!(matches!(
            robust_focals(&f, &p),
            Err(FocalFailure::InvalidParameter {
                name: "f_prior",
                ..
            })
        ));
    }
    let p = RobustFocalParams {
        weights: FocalWeights::new(5e-4, 0.0, 5e-4, 1.0),
        ..Default::default()
    };
    assert!(matches!(
        robust_focals(&f, &p),
        Err(FocalFailure::InvalidParameter { name: "w_pp1", .. })
    ));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Bougnoux is invariant to the scale and sign of F, and transposing F
    /// swaps the images. Invariant up to rounding amplified by the
    /// denominator's cancellation, so the tolerance is relative to how well
    /// the scene determines the focal lengths: how far the unscaled answer is
    /// from the truth (a noiseless scene), floored at 1e-10.
    #[test]
    fn bougnoux_invariances(seed in 0u64..10_000, scale in prop_oneof![-1e3..-1e-3, 1e-3..1e3f64]) {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let s = random_scene(&mut rng, true);
        let (a1, a2) = bougnoux(&s.f, s.pp1, s.pp2).unwrap();
        let (b1, b2) = bougnoux(&(s.f * scale), s.pp1, s.pp2).unwrap();
        let (c2, c1) = bougnoux(&s.f.transpose(), s.pp2, s.pp1).unwrap();
        let tol1 = 100.0 * ((a1 - s.f1).abs() / s.f1).max(1e-12);
        let tol2 = 100.0 * ((a2 - s.f2).abs() / s.f2).max(1e-12);
        prop_assert!((a1 - b1).abs() <= tol1 * a1 && (a2 - b2).abs() <= tol2 * a2);
        prop_assert!((a1 - c1).abs() <= tol1 * a1 && (a2 - c2).abs() <= tol2 * a2);
    }

    /// The robust solver depends on F only up to scale and sign: scaling by
    /// a signed power of two leaves F / |F| exact up to sign, and the
    /// constraints are invariant to the sign of the singular vectors, so the
    /// answer must be identical. Every success satisfies the constraints.
    #[test]
    fn robust_solver_scale_invariance(seed in 0u64..10_000, exponent in -30i32..30, negative in any::<bool>()) {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let s = random_scene(&mut rng, true);
        let scale = if negative { -1.0 } else { 1.0 } * 2f64.powi(exponent);
        let params = RobustFocalParams { f_prior: 1000.0, ..Default::default() };
        let a = robust_focals(&s.f, &params);
        let b = robust_focals(&(s.f * scale), &params);
        prop_assert_eq!(a, b);
        if let Ok(a) = a {
            prop_assert!(relative_kruppa_residual(&s.f, &a, 1000.0).unwrap() <= KRUPPA_TOLERANCE);
        }
    }
}
