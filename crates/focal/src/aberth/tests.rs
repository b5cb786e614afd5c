use super::*;
use crate::test_support::poly_from_roots;

#[test]
fn packed_sweeps_equal_wide_sweeps_bit_for_bit() {
    use rand::{Rng, SeedableRng};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(5);
    let mut packed_sweeps = 0;
    for _ in 0..300 {
        let deg = rng.gen_range(5..=MAX_DEGREE);
        let c: Vec<f64> = (0..=deg)
            .map(|_| rng.gen_range(-1.0..1.0) * 10f64.powi(rng.gen_range(-3..3)))
            .collect();
        let mut start = [C64::new(0.0, 0.0); MAX_DEGREE];
        init_newton_polygon(&c, &mut start[..deg]);
        let mut packed = AberthState::new(&c, &start[..deg]);
        let mut wide = AberthState::new(&c, &start[..deg]);
        for _ in 0..100 {
            packed_sweeps += usize::from(packed.converged.iter().filter(|&&v| !v).count() <= 8);
            let moving = packed.jacobi_sweep();
            assert_eq!(moving, wide.jacobi_sweep_wide());
            assert_eq!(packed.converged, wide.converged);
            for i in 0..deg {
                assert_eq!(packed.re[i].to_bits(), wide.re[i].to_bits());
                assert_eq!(packed.im[i].to_bits(), wide.im[i].to_bits());
            }
            if moving == 0 {
                break;
            }
        }
    }
    assert!(packed_sweeps > 100, "only {packed_sweeps} packed sweeps");
}

#[test]
fn aberth_finds_known_roots() {
    // (z - 1)(z + 2)(z - 0.5)(z^2 + 1)(z - 30) expanded.
    let roots_true = [1.0, -2.0, 0.5, 30.0];
    let poly = poly_from_roots(&roots_true, &[(0.0, 1.0)]);
    let mut out = [C64::new(0.0, 0.0); MAX_DEGREE];
    let n = aberth_roots(&poly, &mut out, None, Simd::detect());
    assert_eq!(n, 6);
    for r in roots_true {
        assert!(
            out[..n]
                .iter()
                .any(|z| (z - C64::new(r, 0.0)).norm() < 1e-9),
            "missing root {r}: {:?}",
            &out[..n]
        );
    }
    for im in [1.0, -1.0] {
        assert!(out[..n]
            .iter()
            .any(|z| (z - C64::new(0.0, im)).norm() < 1e-9));
    }
}

#[test]
fn aberth_finds_all_sixteen_roots_cold_and_warm() {
    let real = [-3.0, -1.5, -0.7, -0.2, 0.3, 0.9, 1.6, 2.5];
    let pairs = [(0.5, 1.0), (-1.0, 0.4), (2.0, 0.8), (-0.3, 2.2)];
    let poly = poly_from_roots(&real, &pairs);
    let mut want: Vec<C64> = real.iter().map(|&r| C64::new(r, 0.0)).collect();
    for &(a, b) in &pairs {
        want.push(C64::new(a, b));
        want.push(C64::new(a, -b));
    }
    let check = |out: &[C64]| {
        for w in &want {
            assert!(
                out.iter().any(|z| (z - w).norm() < 1e-8),
                "missing root {w}: {out:?}"
            );
        }
    };
    let mut cold = [C64::new(0.0, 0.0); MAX_DEGREE];
    assert_eq!(aberth_roots(&poly, &mut cold, None, Simd::detect()), 16);
    check(&cold);
    // Warm start from the roots of a nearby polynomial.
    let nearby: Vec<f64> = poly
        .iter()
        .enumerate()
        .map(|(k, c)| c * (1.0 + 1e-3 * ((k as f64) * 0.9).sin()))
        .collect();
    let mut warm_start = [C64::new(0.0, 0.0); MAX_DEGREE];
    aberth_roots(&nearby, &mut warm_start, None, Simd::detect());
    let mut warm = [C64::new(0.0, 0.0); MAX_DEGREE];
    assert_eq!(
        aberth_roots(&poly, &mut warm, Some(&warm_start[..16]), Simd::detect()),
        16
    );
    check(&warm);
}

/// Every build of the sweeps and of the resultant that this CPU can run

#[test]
fn aberth_deflates_zero_roots_and_trims_leading_zeros() {
    // z^2 (z - 3), written with two trailing zero coefficients.
    let poly = [0.0, 0.0, -3.0, 1.0, 0.0, 0.0];
    let mut out = [C64::new(0.0, 0.0); MAX_DEGREE];
    let n = aberth_roots(&poly, &mut out, None, Simd::detect());
    assert_eq!(n, 3);
    assert_eq!(out[0], C64::new(0.0, 0.0));
    assert_eq!(out[1], C64::new(0.0, 0.0));
    assert!((out[2] - C64::new(3.0, 0.0)).norm() < 1e-12);
}
