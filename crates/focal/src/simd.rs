//! The one place of the crate with `unsafe` code: the instruction-set
//! levels ([`Simd`]), the builds of the lane-parallel kernels for each
//! level (`#[target_feature]` functions) and the dispatch to them.
//!
//! Every build runs the same source (an `#[inline(always)]` kernel of
//! [`crate::resultant`], [`crate::aberth`] or [`crate::robust`]) and
//! performs the same IEEE operations in the same order, so the level changes
//! no bit of any answer; the tests below run every level this CPU has,
//! the portable one included, and compare the bits.
#![allow(unsafe_code)]

use nalgebra::Matrix3;

use crate::aberth::AberthState;
use crate::bivariate::Quartic2;
use crate::error::FocalFailure;
use crate::params::{FocalEstimate, RobustFocalParams};
use crate::resultant::{resultant_in_t2_lanes, RES_DEGREE};
use crate::robust::solve_to_end;

/// The instruction sets the lane-parallel kernels (the resultant and the
/// Aberth sweeps) are compiled for, widest first. Each build performs
/// the same IEEE operations in the same order (the compiler fuses no
/// multiply-add and reorders no sum), so every level gives the same bits;
/// the wider ones only hold more lanes per instruction and, with AVX-512,
/// keep the 16 lanes' sums in 32 registers instead of spilling them. With
/// AVX-512 the whole robust solve is compiled for it ([`robust_focals`]);
/// the step's functions are `#[inline(always)]` so that they are
/// compiled into that build rather than called in their baseline one.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Simd {
    /// AVX-512 F, DQ and VL.
    Avx512,
    /// AVX2.
    Avx2,
    /// Whatever the target's baseline is (SSE2 on x86-64).
    Portable,
}

impl Simd {
    /// The widest level this CPU supports.
    pub(crate) fn detect() -> Self {
        Self::supported()[0]
    }

    /// The levels this CPU supports, widest first (`Portable` always, and
    /// repeated to fill the array).
    pub(crate) fn supported() -> [Self; 3] {
        let mut levels = [Self::Portable; 3];
        let mut n = 0;
        #[cfg(target_arch = "x86_64")]
        {
            use std::arch::is_x86_feature_detected as has;
            if has!("avx512f") && has!("avx512dq") && has!("avx512vl") {
                levels[n] = Self::Avx512;
                n += 1;
            }
            if has!("avx2") {
                levels[n] = Self::Avx2;
                n += 1;
            }
        }
        levels[n] = Self::Portable;
        levels
    }
}

/// The resultant of [`crate::resultant::resultant_in_t2`] computed by the
/// kernel compiled for `simd`, which the CPU must support (as
/// [`Simd::detect`] and [`Simd::supported`] ensure).
pub(crate) fn resultant_in_t2(simd: Simd, p: &Quartic2, q: &Quartic2) -> [f64; RES_DEGREE + 1] {
    match simd {
        // SAFETY: `simd` is a level the CPU supports.
        #[cfg(target_arch = "x86_64")]
        Simd::Avx512 => unsafe { resultant_in_t2_avx512(p, q) },
        // SAFETY: as above.
        #[cfg(target_arch = "x86_64")]
        Simd::Avx2 => unsafe { resultant_in_t2_avx2(p, q) },
        _ => resultant_in_t2_lanes(p, q),
    }
}

/// [`resultant_in_t2_lanes`] compiled for AVX-512.
///
/// # Safety
/// The CPU must support [`Simd::Avx512`].
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f,avx512dq,avx512vl")]
unsafe fn resultant_in_t2_avx512(p: &Quartic2, q: &Quartic2) -> [f64; RES_DEGREE + 1] {
    resultant_in_t2_lanes(p, q)
}

/// [`resultant_in_t2_lanes`] compiled for AVX2.
///
/// # Safety
/// The CPU must support AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn resultant_in_t2_avx2(p: &Quartic2, q: &Quartic2) -> [f64; RES_DEGREE + 1] {
    resultant_in_t2_lanes(p, q)
}

/// [`AberthState::jacobi_sweep`] compiled for `simd`, which the CPU must
/// support.
pub(crate) fn jacobi_sweep(simd: Simd, state: &mut AberthState) -> usize {
    match simd {
        // SAFETY: `simd` is a level the CPU supports.
        #[cfg(target_arch = "x86_64")]
        Simd::Avx512 => unsafe { jacobi_sweep_avx512(state) },
        // SAFETY: as above.
        #[cfg(target_arch = "x86_64")]
        Simd::Avx2 => unsafe { jacobi_sweep_avx2(state) },
        _ => state.jacobi_sweep(),
    }
}

/// [`AberthState::jacobi_sweep`] compiled for AVX-512.
///
/// # Safety
/// The CPU must support [`Simd::Avx512`].
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f,avx512dq,avx512vl")]
unsafe fn jacobi_sweep_avx512(state: &mut AberthState) -> usize {
    state.jacobi_sweep()
}

/// [`AberthState::jacobi_sweep`] compiled for AVX2.
///
/// # Safety
/// The CPU must support AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn jacobi_sweep_avx2(state: &mut AberthState) -> usize {
    state.jacobi_sweep()
}

/// The robust solve ([`crate::robust_focals`]) at the level `simd`, which
/// the CPU must support: with [`Simd::Avx512`] the whole solve is compiled
/// for it, otherwise the baseline build of the steps calls the kernels
/// compiled for `simd`.
pub(crate) fn robust_focals(
    simd: Simd,
    f: &Matrix3<f64>,
    params: &RobustFocalParams,
) -> Result<FocalEstimate, FocalFailure> {
    match simd {
        // SAFETY: `simd` is a level the CPU supports.
        #[cfg(target_arch = "x86_64")]
        Simd::Avx512 => unsafe { solve_avx512(f, params) },
        _ => solve_to_end(simd, f, params),
    }
}

/// [`solve_to_end`] compiled for AVX-512 as a whole, so that the scalar parts of a
/// step (the plane, the Kruppa quartics, the candidates' polish) also get its
/// 32 registers; the same operations in the same order, so the same bits.
///
/// # Safety
/// The CPU must support [`Simd::Avx512`].
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f,avx512dq,avx512vl")]
unsafe fn solve_avx512(
    f: &Matrix3<f64>,
    params: &RobustFocalParams,
) -> Result<FocalEstimate, FocalFailure> {
    solve_to_end(Simd::Avx512, f, params)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::aberth::{init_newton_polygon, MAX_DEGREE};
    use crate::multi_start::{multi_start_with, MultiStart};
    use crate::params::{OnFailure, ADELAIDE_MAX_ITERS, ADELAIDE_WEIGHT_SETS, HOPEF_WEIGHT_SETS};
    use crate::test_support::{poly_from_roots, product_of_lines, sample_f, LINES_P, LINES_Q};
    use nalgebra::Complex;
    use rand::{Rng, SeedableRng};

    /// Every level this CPU supports, each once, the portable one last.
    fn levels() -> Vec<Simd> {
        let mut levels = Simd::supported().to_vec();
        levels.dedup();
        assert_eq!(levels.last(), Some(&Simd::Portable));
        levels
    }

    /// A random bivariate quartic with coefficients over twelve decades.
    fn random_quartic(rng: &mut rand_chacha::ChaCha8Rng) -> Quartic2 {
        let mut c = [[0.0; 5]; 5];
        for (i, row) in c.iter_mut().enumerate() {
            for v in row.iter_mut().take(5 - i) {
                *v = rng.gen_range(-1.0..1.0) * 10f64.powi(rng.gen_range(-6..6));
            }
        }
        Quartic2(c)
    }

    /// The resultant kernel of every level, the portable one forced,
    /// computes the same bits: the line products and 200 random pairs.
    #[test]
    fn every_level_computes_the_same_resultant_bits() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(31);
        let mut pairs = vec![(product_of_lines(&LINES_P), product_of_lines(&LINES_Q))];
        pairs.extend((0..200).map(|_| (random_quartic(&mut rng), random_quartic(&mut rng))));
        for (p, q) in &pairs {
            let portable = resultant_in_t2(Simd::Portable, p, q).map(f64::to_bits);
            for simd in levels() {
                assert_eq!(
                    resultant_in_t2(simd, p, q).map(f64::to_bits),
                    portable,
                    "{simd:?}"
                );
            }
        }
    }

    /// The Aberth sweeps of every level give the same bits as the portable
    /// ones, sweep after sweep until every root has converged: a polynomial
    /// with known roots and 100 random ones of degree 5 to 16.
    #[test]
    fn every_level_computes_the_same_sweep_bits() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(8);
        let mut polys = vec![poly_from_roots(
            &[-2.0, -0.5, 0.1, 0.8, 1.7, 3.0],
            &[(0.4, 0.9), (-1.2, 0.3)],
        )];
        polys.extend((0..100).map(|_| {
            let deg = rng.gen_range(5..=MAX_DEGREE);
            (0..=deg)
                .map(|_| rng.gen_range(-1.0..1.0) * 10f64.powi(rng.gen_range(-3..3)))
                .collect()
        }));
        for poly in &polys {
            let deg = poly.len() - 1;
            let mut start = [Complex::new(0.0, 0.0); MAX_DEGREE];
            init_newton_polygon(poly, &mut start[..deg]);
            for simd in levels() {
                let mut portable = AberthState::new(poly, &start[..deg]);
                let mut vector = AberthState::new(poly, &start[..deg]);
                for _ in 0..100 {
                    let moving = jacobi_sweep(Simd::Portable, &mut portable);
                    assert_eq!(moving, jacobi_sweep(simd, &mut vector), "{simd:?}");
                    assert_eq!(portable.re.map(f64::to_bits), vector.re.map(f64::to_bits));
                    assert_eq!(portable.im.map(f64::to_bits), vector.im.map(f64::to_bits));
                    if moving == 0 {
                        break;
                    }
                }
            }
        }
    }

    /// The fundamental matrices of the whole-solve comparisons: exact,
    /// slightly and clearly perturbed.
    fn solve_matrices() -> Vec<Matrix3<f64>> {
        (0..60)
            .map(|i| {
                let x = i as f64;
                sample_f(
                    [0.1 + 0.01 * x, -0.2 + 0.007 * x, 0.05],
                    [0.4 - 0.02 * x, -0.2, 1.0],
                    600.0 + 20.0 * x,
                    1400.0 - 10.0 * x,
                    [0.0, 1e-6, 1e-4][i % 3],
                )
            })
            .collect()
    }

    /// `Ok` answers compared by the bits of the unknowns and the count,
    /// failures by their full description.
    fn same_answer(
        a: &Result<FocalEstimate, FocalFailure>,
        b: &Result<FocalEstimate, FocalFailure>,
    ) -> bool {
        match (a, b) {
            (Ok(a), Ok(b)) => {
                a.unknowns().map(f64::to_bits) == b.unknowns().map(f64::to_bits)
                    && a.iterations == b.iterations
                    && a.from_prior == b.from_prior
            }
            (a, b) => format!("{a:?}") == format!("{b:?}"),
        }
    }

    /// The whole robust solve at every level (AVX-512 compiles all of it;
    /// the portable level runs no vector kernel at all) gives the same bits,
    /// successes and failures alike; so does the multi-start rule.
    #[test]
    fn every_level_gives_the_same_solve() {
        for f in &solve_matrices() {
            for weights in ADELAIDE_WEIGHT_SETS {
                let params = RobustFocalParams {
                    f_prior: 1000.0,
                    weights,
                    max_iters: ADELAIDE_MAX_ITERS,
                };
                let portable = robust_focals(Simd::Portable, f, &params);
                for simd in levels() {
                    let answer = robust_focals(simd, f, &params);
                    assert!(
                        same_answer(&answer, &portable),
                        "{simd:?}: {answer:?} vs {portable:?}"
                    );
                }
            }
            for on_failure in [OnFailure::Report, OnFailure::Prior] {
                let starts = MultiStart {
                    f_prior: 1000.0,
                    weight_sets: &HOPEF_WEIGHT_SETS,
                    max_iters: ADELAIDE_MAX_ITERS,
                    on_failure,
                };
                let portable = multi_start_with(Simd::Portable, f, &starts);
                for simd in levels() {
                    let answer = multi_start_with(simd, f, &starts);
                    assert!(
                        same_answer(&answer, &portable),
                        "{simd:?}: {answer:?} vs {portable:?}"
                    );
                }
            }
        }
    }
}
