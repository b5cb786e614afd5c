//! The robust iterative focal solver of Kocur, Kyselica and Kukelova
//! (CVPR 2024), as docs/method.md step 4 specifies it: the iteration from the
//! prior, one step's plane and quartics, the stopping rule and the failure
//! policy.

use nalgebra::Matrix3;

use crate::bezout::{min_l1_real_solution, RootCache};
use crate::error::FocalFailure;
use crate::kruppa::{relative_residual, KruppaSvd};
use crate::params::{FocalEstimate, OnFailure, RobustFocalParams};
use crate::simd::{self, Simd};
use crate::KRUPPA_TOLERANCE;

/// Focal lengths and principal points of both images from F (principal
/// points at the origin, `x2^T F x1 = 0`) by the robust iterative solver of
/// Kocur, Kyselica and Kukelova (CVPR 2024), docs/method.md step 4.
///
/// Unknowns `x = (f1, u1, v1, f2, u2, v2)`, prior
/// `p = (f_prior, 0, 0, f_prior, 0, 0)`, objective
/// `sum_i w_i (x_i - p_i)^2` subject to the Kruppa constraints
/// `g1(x) = g2(x) = 0` (see [`kruppa_residuals`](crate::kruppa_residuals)). Starting from `x_0 = p`,
/// step k takes the gradients of g1, g2 at `x_k` scaled by `1/w_i` as the
/// directions `c1, c2` and sets `x_{k+1} = p + l1 c1 + l2 c2`, where
/// `(l1, l2)` is the real solution of `g1 = g2 = 0` on that plane (two
/// quartics in (l1, l2)) with the smallest `|l1| + |l2|`, found among all
/// real solutions (hidden-variable resultant, see the crate docs). It stops
/// when `e_k = |x_{k+1} - p|^2` changes by less than `1e-4` relative to
/// `e_{k-1}` or `e_k < 1e-8` (checked from k = 1), or after step
/// `k = max_iters`.
///
/// Every success satisfies both constraints to [`KRUPPA_TOLERANCE`]
/// relative to their value at the prior ([`relative_kruppa_residual`](crate::relative_kruppa_residual)).
/// Failures: [`FocalFailure::NoRealSolution`] when a step's plane holds no
/// real solution, [`FocalFailure::NonFinite`],
/// [`FocalFailure::NoConvergence`] when the final check fails, and
/// [`FocalFailure::InvalidMatrix`] / [`FocalFailure::InvalidParameter`] for
/// invalid input.
///
/// ```
/// use nalgebra::{Matrix3, Rotation3, Vector3};
/// use focal::{robust_focals, RobustFocalParams};
/// let r = Rotation3::from_euler_angles(0.1, -0.25, 0.05).into_inner();
/// let t = Vector3::new(0.4, -0.2, 1.0);
/// let k_inv = Matrix3::from_diagonal(&Vector3::new(1.0 / 900.0, 1.0 / 900.0, 1.0));
/// let f = k_inv.transpose() * t.cross_matrix() * r * k_inv;
/// let est = robust_focals(&f, &RobustFocalParams { f_prior: 1000.0, ..Default::default() }).unwrap();
/// // The weighted projection of the prior onto the constraints moves the
/// // focal lengths from the prior towards the truth.
/// assert!((est.f1 - 900.0).abs() < 100.0 && (est.f2 - 900.0).abs() < 100.0);
/// let residual = focal::relative_kruppa_residual(&f, &est, 1000.0).unwrap();
/// assert!(residual <= 1e-6);
/// ```
pub fn robust_focals(
    f: &Matrix3<f64>,
    params: &RobustFocalParams,
) -> Result<FocalEstimate, FocalFailure> {
    robust_focals_with(Simd::detect(), f, params)
}

/// [`robust_focals`] with the kernels (and, for [`Simd::Avx512`], the whole
/// solve) compiled for `simd`, a level the CPU supports: every level gives
/// the same bits ([`crate::simd`]).
pub(crate) fn robust_focals_with(
    simd: Simd,
    f: &Matrix3<f64>,
    params: &RobustFocalParams,
) -> Result<FocalEstimate, FocalFailure> {
    simd::robust_focals(simd, f, params)
}

/// [`robust_focals`]: the steps from the prior to the end, with the kernels
/// compiled for `simd`.
#[inline(always)]
pub(crate) fn solve_to_end(
    simd: Simd,
    f: &Matrix3<f64>,
    params: &RobustFocalParams,
) -> Result<FocalEstimate, FocalFailure> {
    let k = KruppaSvd::new(f);
    let mut solve = Solve::start(k.as_ref(), params, simd)?;
    loop {
        if let Some(result) = solve.next_step() {
            return result;
        }
    }
}

/// A robust focal solve in progress, advanced one step at a time (the
/// iteration of [`robust_focals`]).
pub(crate) struct Solve<'a> {
    k: &'a KruppaSvd,
    /// The instruction set of the step's kernels.
    simd: Simd,
    f_prior: f64,
    max_iters: usize,
    p: [f64; 6],
    w: [f64; 6],
    x: [f64; 6],
    cache: RootCache,
    e_prev: f64,
    /// The index of the next step. The solve's final iteration count (success
    /// or failure) is at least this: a step k that stops or fails reports k.
    pub(crate) step: usize,
    /// The iterates `x_{k+1}` of the last [`CYCLE_HISTORY`] steps, step k at
    /// `k % CYCLE_HISTORY`, for [`Solve::cycle_end`].
    history: [[f64; 6]; CYCLE_HISTORY],
    /// Whether [`Solve::cycle_end`] may end the solve early (always, except
    /// in the test that compares both ways).
    detect_cycles: bool,
}

/// The longest cycle [`Solve::cycle_end`] looks for, plus one.
const CYCLE_HISTORY: usize = 9;

/// Two iterates closer than this times `f_prior` in every unknown count as
/// the same point of a cycle.
const CYCLE_TOLERANCE: f64 = 1e-9;

impl<'a> Solve<'a> {
    /// Validates the parameters and F (given by its SVD, `None` when F is
    /// invalid) in [`robust_focals`]'s order and starts at `x_0 = p`; the
    /// steps run the kernels compiled for `simd`.
    pub(crate) fn start(
        k: Option<&'a KruppaSvd>,
        params: &RobustFocalParams,
        simd: Simd,
    ) -> Result<Self, FocalFailure> {
        let f_prior = params.f_prior;
        if !(f_prior.is_finite() && f_prior > 0.0) {
            return Err(FocalFailure::InvalidParameter {
                name: "f_prior",
                value: f_prior,
                requirement: "must be finite and > 0",
            });
        }
        params.weights.validate()?;
        let k = k.ok_or(FocalFailure::InvalidMatrix)?;
        let p = [f_prior, 0.0, 0.0, f_prior, 0.0, 0.0];
        Ok(Self {
            k,
            simd,
            f_prior,
            max_iters: params.max_iters,
            p,
            w: params.weights.per_unknown(),
            x: p,
            cache: RootCache::default(),
            e_prev: f64::NAN,
            step: 0,
            history: [[f64::NAN; 6]; CYCLE_HISTORY],
            detect_cycles: true,
        })
    }

    /// Takes the next step; returns the solve's answer once it has ended.
    #[inline(always)]
    pub(crate) fn next_step(&mut self) -> Option<Result<FocalEstimate, FocalFailure>> {
        let step = self.step;
        let Some(d) = solve_step(
            self.k,
            &self.p,
            &self.x,
            &self.w,
            &mut self.cache,
            self.simd,
        ) else {
            return Some(Err(FocalFailure::NoRealSolution { iteration: step }));
        };
        let e: f64 = d.iter().map(|v| v * v).sum();
        for ((xi, pi), di) in self.x.iter_mut().zip(&self.p).zip(&d) {
            *xi = pi + di;
        }
        if !(e.is_finite() && self.x.iter().all(|v| v.is_finite())) {
            return Some(Err(FocalFailure::NonFinite { iteration: step }));
        }
        if step > 0 && ((self.e_prev - e).abs() / self.e_prev.abs() < 1e-4 || e < 1e-8) {
            return Some(self.finish(step));
        }
        self.e_prev = e;
        self.history[step % CYCLE_HISTORY] = self.x;
        if let Some(x_last) = self.cycle_end(step) {
            self.x = x_last;
            return Some(self.finish(self.max_iters + 1));
        }
        self.step += 1;
        (self.step > self.max_iters).then(|| self.finish(self.max_iters + 1))
    }

    /// After step k (which did not stop): when the iterate has returned to
    /// within [`CYCLE_TOLERANCE`]` * f_prior` of the iterate of step k − p
    /// for some period p < [`CYCLE_HISTORY`], the iteration is caught in a
    /// cycle. A step is a function of the previous iterate (the root
    /// finder's warm start only moves its answer at rounding level), so the
    /// steps k − p + 1 … k repeat until `max_iters`; the stopping rule was
    /// checked on every transition of the cycle and did not fire, so it
    /// will not. Returns the iterate that step `max_iters` would reach, so
    /// that the solve ends at once with the answer of running every step.
    ///
    /// Most solves that run out of steps on real hypotheses are such cycles
    /// (period 2 in 80 % of them on AdelaideRMF), so this halves the solver's
    /// time there. The answer is the same as running every step except
    /// when the cycle is not exact and the iterates drift apart over the
    /// remaining steps: 2 of 1600 noisy synthetic solves, all of them solves
    /// that ran out of steps either way (`robust_focals_skips_cycles_...`
    /// test).
    fn cycle_end(&self, step: usize) -> Option<[f64; 6]> {
        if !self.detect_cycles || step >= self.max_iters {
            return None;
        }
        let tol = CYCLE_TOLERANCE * self.f_prior;
        let x = &self.x;
        let period = (1..CYCLE_HISTORY.min(step + 1)).find(|&p| {
            let earlier = &self.history[(step - p) % CYCLE_HISTORY];
            x.iter().zip(earlier).all(|(a, b)| (a - b).abs() <= tol)
        })?;
        let last = step - period + (self.max_iters - (step - period)) % period;
        Some(self.history[last % CYCLE_HISTORY])
    }

    /// The final Kruppa check of the current iterate.
    fn finish(&self, iterations: usize) -> Result<FocalEstimate, FocalFailure> {
        let x = &self.x;
        let residual = relative_residual(self.k, x, self.f_prior);
        if residual.is_nan() || residual > KRUPPA_TOLERANCE {
            return Err(FocalFailure::NoConvergence {
                iterations,
                residual,
            });
        }
        Ok(FocalEstimate {
            f1: x[0],
            f2: x[3],
            pp1: [x[1], x[2]],
            pp2: [x[4], x[5]],
            iterations,
            from_prior: false,
        })
    }
}

/// One step: the displacement `d = l1 c1 + l2 c2` from the prior, with
/// `c_i = W^{-1} grad g_i(x)` and `(l1, l2)` the minimum-`|l1| + |l2|` real
/// solution of `g(p + d) = 0`. `cache` carries the previous step's
/// resultant roots as the starting point of this step's root-finding.
///
/// The plane is parametrised by an orthonormal basis `(b1, b2)` of
/// `span(c1, c2)` (Gram–Schmidt, `[c1 c2] = [b1 b2] R`) scaled by `f_prior`:
/// `d = f_prior (s1 b1 + s2 b2)`. The two directions are often nearly
/// parallel, which makes the `(l1, l2)` parametrisation ill-conditioned; the
/// solution set is the same, and `l = f_prior R^{-1} s` recovers the
/// multipliers for the `|l1| + |l2|` criterion.
#[inline(always)]
fn solve_step(
    k: &KruppaSvd,
    p: &[f64; 6],
    x: &[f64; 6],
    w: &[f64; 6],
    cache: &mut RootCache,
    simd: Simd,
) -> Option<[f64; 6]> {
    let (_, j) = k.eval_with_grad(x);
    let mut c = [[0.0; 6]; 2];
    for r in 0..2 {
        for i in 0..6 {
            c[r][i] = j[r][i] / w[i];
        }
    }
    let dot = |a: &[f64; 6], b: &[f64; 6]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    let r11 = dot(&c[0], &c[0]).sqrt();
    if !(r11 > 0.0 && r11.is_finite()) {
        return None;
    }
    let mut b1 = [0.0; 6];
    for i in 0..6 {
        b1[i] = c[0][i] / r11;
    }
    let r12 = dot(&b1, &c[1]);
    let mut b2 = [0.0; 6];
    for i in 0..6 {
        b2[i] = c[1][i] - r12 * b1[i];
    }
    let r22 = dot(&b2, &b2).sqrt();
    if !(r22 > 1e-12 * r11.max(r12.abs()) && r22.is_finite()) {
        // c1 and c2 are parallel: the plane degenerates to a line.
        return None;
    }
    let scale = p[0];
    let mut e1 = [0.0; 6];
    let mut e2 = [0.0; 6];
    for i in 0..6 {
        b2[i] /= r22;
        e1[i] = scale * b1[i];
        e2[i] = scale * b2[i];
    }
    let (q1, q2) = k.along_plane(p, &e1, &e2);
    let (m1, m2) = (q1.max_abs_coef(), q2.max_abs_coef());
    if !(m1 > 0.0 && m2 > 0.0 && m1.is_finite() && m2.is_finite()) {
        return None;
    }
    let (q1, q2) = (q1.scaled(m1), q2.scaled(m2));
    // l = scale R^{-1} s with R = [[r11, r12], [0, r22]]; the common factor
    // `scale / r22` does not change the argmin, so it is left out.
    let m = [[r22 / r11, -r12 / r11], [0.0, 1.0]];
    let s = min_l1_real_solution(&q1, &q2, m, cache, simd)?;
    let mut d = [0.0; 6];
    for (i, di) in d.iter_mut().enumerate() {
        *di = s[0] * e1[i] + s[1] * e2[i];
    }
    Some(d)
}

/// Applies an [`OnFailure`] policy to a solver result: with
/// [`OnFailure::Prior`], a failed solve ([`FocalFailure::is_solve_failure`])
/// becomes [`FocalEstimate::prior`] with the iteration count the solver had
/// used ([`FocalFailure::iterations`]); invalid input stays an error. With
/// [`OnFailure::Report`] the result is returned unchanged.
pub fn apply_on_failure(
    result: Result<FocalEstimate, FocalFailure>,
    f_prior: f64,
    on_failure: OnFailure,
) -> Result<FocalEstimate, FocalFailure> {
    match (result, on_failure) {
        (Err(e), OnFailure::Prior) if e.is_solve_failure() => {
            Ok(FocalEstimate::prior(f_prior, e.iterations()))
        }
        (r, _) => r,
    }
}

/// [`robust_focals`] followed by [`apply_on_failure`].
pub fn robust_focals_or(
    f: &Matrix3<f64>,
    params: &RobustFocalParams,
    on_failure: OnFailure,
) -> Result<FocalEstimate, FocalFailure> {
    apply_on_failure(robust_focals(f, params), params.f_prior, on_failure)
}
#[cfg(test)]
mod tests {
    use super::*;
    use crate::params::{ADELAIDE_WEIGHT_SETS, HOPEF_WEIGHT_SETS};
    use crate::test_support::sample_f;

    /// The pruning of the multi-start rule relies on this: a solve that ends
    /// while taking step k reports exactly k iterations (success or failure),
    /// or `max_iters + 1` when it ran out of steps (or will: a cycle).
    #[test]
    fn a_solve_ending_at_step_k_reports_k_iterations() {
        let matrices = [
            sample_f([0.1, -0.25, 0.05], [0.4, -0.2, 1.0], 900.0, 900.0, 0.0),
            sample_f([0.3, 0.4, -0.1], [1.0, 0.1, 0.2], 700.0, 1500.0, 1e-4),
            sample_f([-0.2, 0.6, 0.3], [0.2, 1.0, -0.3], 1200.0, 1000.0, 1e-3),
            sample_f([0.05, 0.02, 0.01], [1.0, 0.0, 0.0], 1000.0, 1000.0, 3e-2),
        ];
        let mut kinds = std::collections::BTreeSet::new();
        for f in &matrices {
            let svd = KruppaSvd::new(f);
            for weights in HOPEF_WEIGHT_SETS {
                for max_iters in [1, 2, 100] {
                    let params = RobustFocalParams {
                        f_prior: 1024.0,
                        weights,
                        max_iters,
                    };
                    let mut solve = Solve::start(svd.as_ref(), &params, Simd::detect()).unwrap();
                    let (last_step, result) = loop {
                        let step = solve.step;
                        assert!(step <= max_iters);
                        if let Some(result) = solve.next_step() {
                            break (step, result);
                        }
                    };
                    assert_eq!(result, robust_focals(f, &params));
                    let count = match &result {
                        Ok(est) => est.iterations,
                        Err(e) => e.iterations(),
                    };
                    // Out of steps: at step max_iters, or earlier once caught
                    // in a cycle (Solve::cycle_end); either way the count is
                    // at least the step.
                    let ran_out = count == max_iters + 1;
                    assert!(
                        count == last_step || ran_out,
                        "{result:?} at step {last_step}"
                    );
                    kinds.insert((result.is_ok(), ran_out));
                }
            }
        }
        // Successes, failures and exhausted budgets were all exercised.
        assert!(kinds.len() >= 3, "{kinds:?}");
    }

    /// Ending a solve caught in a cycle gives the answer of running every
    /// step: on noisy synthetic F (where many solves cycle) the outcome,
    /// iteration count and focal lengths agree, and any disagreement is
    /// between solves that ran out of steps.
    #[test]
    fn robust_focals_skips_cycles_with_the_answer_of_every_step() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(2024);
        let (mut cycles, mut agree, mut total) = (0, 0, 0);
        for _ in 0..400 {
            let angles = [
                rng.gen_range(-0.4..0.4),
                rng.gen_range(-0.4..0.4),
                rng.gen_range(-0.2..0.2),
            ];
            let t = [
                rng.gen_range(-1.0..1.0),
                rng.gen_range(-1.0..1.0),
                rng.gen_range(-1.0..1.0),
            ];
            let noise = 10f64.powf(rng.gen_range(-4.0..-1.5));
            let f = sample_f(
                angles,
                t,
                rng.gen_range(300.0..2000.0),
                rng.gen_range(300.0..2000.0),
                noise,
            );
            let svd = KruppaSvd::new(&f);
            for weights in ADELAIDE_WEIGHT_SETS {
                let params = RobustFocalParams {
                    f_prior: 640.0,
                    weights,
                    max_iters: 100,
                };
                let run = |detect: bool| {
                    let mut solve = Solve::start(svd.as_ref(), &params, Simd::detect()).unwrap();
                    solve.detect_cycles = detect;
                    loop {
                        let step = solve.step;
                        if let Some(result) = solve.next_step() {
                            return (result, step);
                        }
                    }
                };
                let (fast, fast_step) = run(true);
                let (slow, _) = run(false);
                // Out of steps: an answer, or a failed final check, after max_iters.
                let ran_out = |r: &Result<FocalEstimate, FocalFailure>| match r {
                    Ok(e) => e.iterations > params.max_iters,
                    Err(e) => e.iterations() > params.max_iters,
                };
                if ran_out(&fast) && fast_step < params.max_iters {
                    cycles += 1;
                }
                total += 1;
                let same = match (&fast, &slow) {
                    (Ok(a), Ok(b)) => {
                        a.iterations == b.iterations
                            && (a.f1 - b.f1).abs() <= 1e-6 * 640.0
                            && (a.f2 - b.f2).abs() <= 1e-6 * 640.0
                    }
                    (Err(a), Err(b)) => a == b,
                    _ => false,
                };
                if same {
                    agree += 1;
                } else {
                    assert!(
                        ran_out(&fast) || ran_out(&slow),
                        "{fast:?} against {slow:?}"
                    );
                }
            }
        }
        assert!(cycles >= 20, "only {cycles} cycles in {total} solves");
        assert!(agree as f64 >= 0.99 * total as f64, "{agree}/{total} agree");
        println!("{cycles} cycles skipped, {agree}/{total} answers as running every step");
    }
}
