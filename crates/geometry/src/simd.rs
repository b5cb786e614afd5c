//! The instruction-set dispatch of the crate's batch loops: each hot loop
//! is an `#[inline(always)]` kernel, compiled twice, for the target's
//! baseline (SSE2 on x86-64) and for AVX2, and [`avx2`] says which one a
//! call runs. Both builds perform the same IEEE operations in the same
//! order (Rust fuses no multiply-add and reorders no sum), so the choice
//! changes no bit of any answer: AVX2 only holds four lanes per
//! instruction instead of two. The tests of each kernel run both builds
//! and compare the bits.
//!
//! The kernels: [`crate::sampson_consensus`], the batch Sampson
//! distances ([`crate::sampson_distances_squared`],
//! [`crate::sampson_residuals_signed`], [`crate::SampsonModels`]), the weighted moments of the
//! normalised 8-point and the evaluation of the ten 5-point constraints
//! with their Jacobian (the root polish).
#![allow(unsafe_code)]

/// Whether the AVX2 builds of the kernels can run on this CPU (the
/// detection is cached by the standard library). Always `false` off
/// x86-64, and in tests that force the portable build.
#[inline]
pub(crate) fn avx2() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        !portable_forced() && std::arch::is_x86_feature_detected!("avx2")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

#[cfg(test)]
thread_local! {
    /// Set by [`with_portable`]: this thread runs the baseline builds.
    static PORTABLE: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

#[cfg(test)]
fn portable_forced() -> bool {
    PORTABLE.with(|p| p.get())
}

#[cfg(not(test))]
#[inline(always)]
fn portable_forced() -> bool {
    false
}

/// `run()` on this thread with the baseline builds of every kernel: the
/// reference the tests compare the AVX2 builds with.
#[cfg(test)]
pub(crate) fn with_portable<T>(run: impl FnOnce() -> T) -> T {
    PORTABLE.with(|p| p.set(true));
    let out = run();
    PORTABLE.with(|p| p.set(false));
    out
}

/// Defines `$name`, which runs `$kernel` (an `#[inline(always)]` function
/// with the same parameters) compiled for AVX2 when [`avx2`] says the CPU
/// has it, and its baseline build otherwise. Type parameters and their
/// bounds go in `<…>` and `where […]`.
macro_rules! dispatch {
    (
        $(#[$meta:meta])*
        $vis:vis fn $name:ident $(<$($generic:ident),*>)? ($($arg:ident: $ty:ty),* $(,)?)
            $(-> $ret:ty)? $(where [$($bound:tt)*])? => $kernel:path
    ) => {
        $(#[$meta])*
        $vis fn $name $(<$($generic),*>)? ($($arg: $ty),*) $(-> $ret)? $(where $($bound)*)? {
            /// The kernel compiled for AVX2.
            ///
            /// # Safety
            /// The CPU must support AVX2.
            #[cfg(target_arch = "x86_64")]
            #[target_feature(enable = "avx2")]
            unsafe fn build_avx2 $(<$($generic),*>)? ($($arg: $ty),*) $(-> $ret)?
                $(where $($bound)*)?
            {
                $kernel($($arg),*)
            }
            #[cfg(target_arch = "x86_64")]
            if $crate::simd::avx2() {
                // SAFETY: `avx2()` checked that the CPU supports AVX2.
                return unsafe { build_avx2($($arg),*) };
            }
            $kernel($($arg),*)
        }
    };
}
pub(crate) use dispatch;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{
        eight_point_weighted, sampson_consensus, sampson_distances_squared,
        sampson_residuals_signed, Correspondences, FivePointRoots, SampsonModels,
    };
    use nalgebra::{Matrix3, Vector3};
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// `n` random matches over ±500 px, the second image a noisy copy of
    /// the first moved by a few pixels (so that thresholds split them).
    fn random_matches(rng: &mut ChaCha8Rng, n: usize) -> Correspondences {
        let p1: Vec<[f64; 2]> = (0..n)
            .map(|_| [rng.gen_range(-500.0..500.0), rng.gen_range(-400.0..400.0)])
            .collect();
        let p2: Vec<[f64; 2]> = p1
            .iter()
            .map(|p| {
                [
                    p[0] + 7.0 + rng.gen_range(-3.0..3.0),
                    p[1] + rng.gen_range(-3.0..3.0),
                ]
            })
            .collect();
        Correspondences::new(&p1, &p2).unwrap()
    }

    fn bits(values: impl IntoIterator<Item = f64>) -> Vec<u64> {
        values.into_iter().map(f64::to_bits).collect()
    }

    /// Every kernel's answer in this thread's build and in the portable
    /// one, as bits.
    fn answers(rng: &mut ChaCha8Rng, n: usize) -> (Vec<u64>, usize) {
        let points = random_matches(rng, n);
        // A translation along x, perturbed: some matches within the
        // thresholds, some beyond.
        let f = Matrix3::new(0.0, 0.0, 0.0, 0.0, 0.0, -1.0, 0.0, 1.0, 0.0)
            + Matrix3::from_fn(|_, _| rng.gen_range(-1e-4..1e-4));
        let mut out = Vec::new();
        let mut consensus = Vec::new();
        for (thr2, at_least) in [(2.0, 0), (4.0, n / 2), (9.0, n)] {
            let kept = sampson_consensus(&f, &points, thr2, at_least, &mut consensus);
            out.push(u64::from(kept));
            if kept {
                out.extend(consensus.iter().map(|&i| i as u64));
            }
        }
        let mut d = vec![0.0; n];
        sampson_distances_squared(&f, &points, &mut d);
        out.extend(bits(d.iter().copied()));
        sampson_residuals_signed(&f, &points, &mut d);
        out.extend(bits(d.iter().copied()));
        let models = SampsonModels::new(&[f, f.transpose(), f * 3.0 + Matrix3::identity()]);
        let mut row = [0.0; 3];
        for i in 0..n {
            models.distances_squared(points.point1(i), points.point2(i), &mut row);
            out.extend(bits(row));
        }
        let weights: Vec<f64> = (0..n).map(|_| rng.gen_range(0.0..1.0)).collect();
        out.extend(bits(
            eight_point_weighted(&points, &weights)
                .unwrap()
                .iter()
                .copied(),
        ));
        let bearing = |rng: &mut ChaCha8Rng| {
            Vector3::new(rng.gen_range(-0.5..0.5), rng.gen_range(-0.5..0.5), 1.0)
        };
        let q1: Vec<_> = (0..5).map(|_| bearing(rng)).collect();
        let q2: Vec<_> = q1.iter().map(|q| q + 0.05 * bearing(rng)).collect();
        let roots = FivePointRoots::new(&q1, &q2).unwrap();
        for k in 0..roots.len() {
            out.extend(bits(roots.unpolished(k).unwrap().iter().copied()));
            out.extend(bits(roots.polished(k).unwrap().iter().copied()));
        }
        (out, roots.len())
    }

    /// The AVX2 builds (where this CPU has AVX2) give the portable
    /// builds' bits: consensus sets with and without giving up, the batch
    /// distances, the weighted 8-point and the 5-point roots with their
    /// polish, on 40 random draws of sizes that leave partial blocks.
    #[test]
    fn every_build_gives_the_same_bits() {
        let mut roots = 0;
        for draw in 0..40 {
            let n = 8 + 37 * draw;
            let chosen = answers(&mut ChaCha8Rng::seed_from_u64(draw as u64), n);
            let portable = with_portable(|| {
                assert!(!avx2());
                answers(&mut ChaCha8Rng::seed_from_u64(draw as u64), n)
            });
            assert_eq!(chosen, portable, "draw {draw}, n {n}");
            roots += chosen.1;
        }
        assert!(roots >= 40, "the draws exercise the 5-point roots: {roots}");
    }
}
