//! The reference implementation's multi-start rule over weight sets
//! (docs/method.md step 4): fewest iterations, ties by the smallest `|f1 - f2|`.

use nalgebra::Matrix3;

use crate::error::FocalFailure;
use crate::kruppa::KruppaSvd;
use crate::params::{FocalEstimate, FocalWeights, OnFailure, RobustFocalParams};
use crate::robust::{apply_on_failure, Solve};
use crate::simd::Simd;

/// The reference's multi-start rule (docs/method.md step 4): run
/// [`robust_focals`](crate::robust_focals) with each weight set and keep the answer with the
/// fewest iterations, ties broken by the smallest `|f1 - f2|`, remaining
/// ties by the earlier weight set.
///
/// Failures: with [`OnFailure::Prior`] a failed solve is replaced by the
/// prior answer (`f1 = f2 = f_prior`, its iteration count) and competes like
/// any other candidate, as in the reference implementation; with
/// [`OnFailure::Report`] failed solves are skipped, and the call fails only
/// when every weight set fails, with the first weight set's failure. An empty
/// `weight_sets` is [`FocalFailure::NoWeightSets`].
///
/// The answer is exactly that of running every solve to its end, but the
/// solves advance in lockstep and one whose iteration count is certain to
/// exceed the fewest found so far is abandoned, since it can no longer win;
/// the SVD of F is computed once for all weight sets.
///
/// ```
/// use nalgebra::{Matrix3, Rotation3, Vector3};
/// use focal::{robust_focals_multi_start, OnFailure, ADELAIDE_WEIGHT_SETS, ADELAIDE_MAX_ITERS};
/// let r = Rotation3::from_euler_angles(0.1, -0.25, 0.05).into_inner();
/// let t = Vector3::new(0.4, -0.2, 1.0);
/// let k_inv = Matrix3::from_diagonal(&Vector3::new(1.0 / 900.0, 1.0 / 900.0, 1.0));
/// let f = k_inv.transpose() * t.cross_matrix() * r * k_inv;
/// let best = robust_focals_multi_start(
///     &f, 1000.0, &ADELAIDE_WEIGHT_SETS, ADELAIDE_MAX_ITERS, OnFailure::Report,
/// ).unwrap();
/// assert!(!best.from_prior);
/// ```
pub fn robust_focals_multi_start(
    f: &Matrix3<f64>,
    f_prior: f64,
    weight_sets: &[FocalWeights],
    max_iters: usize,
    on_failure: OnFailure,
) -> Result<FocalEstimate, FocalFailure> {
    let starts = MultiStart {
        f_prior,
        weight_sets,
        max_iters,
        on_failure,
    };
    multi_start_with(Simd::detect(), f, &starts)
}

/// The arguments of [`robust_focals_multi_start`] after F.
pub(crate) struct MultiStart<'w> {
    /// Prior focal length of both images, px.
    pub(crate) f_prior: f64,
    /// The weight sets, in the order that breaks the last ties.
    pub(crate) weight_sets: &'w [FocalWeights],
    /// `max_iters` of every solve.
    pub(crate) max_iters: usize,
    /// The failure policy of every solve.
    pub(crate) on_failure: OnFailure,
}

/// [`robust_focals_multi_start`] with the kernels compiled for `simd`, a
/// level the CPU supports.
pub(crate) fn multi_start_with(
    simd: Simd,
    f: &Matrix3<f64>,
    starts: &MultiStart,
) -> Result<FocalEstimate, FocalFailure> {
    let svd = KruppaSvd::new(f);
    fewest_iterations(run_in_lockstep(svd.as_ref(), starts, simd))
}

/// The answer of every weight set that ran to its end (`None` for the
/// abandoned ones), in set order.
type Outcomes = Vec<Option<Result<FocalEstimate, FocalFailure>>>;

/// Starts one solve per weight set and advances them in lockstep until each
/// has ended or can no longer win.
fn run_in_lockstep(svd: Option<&KruppaSvd>, starts: &MultiStart, simd: Simd) -> Outcomes {
    let mut outcomes: Outcomes = vec![None; starts.weight_sets.len()];
    let mut live = Vec::with_capacity(starts.weight_sets.len());
    for (i, weights) in starts.weight_sets.iter().enumerate() {
        let params = RobustFocalParams {
            f_prior: starts.f_prior,
            weights: *weights,
            max_iters: starts.max_iters,
        };
        match Solve::start(svd, &params, simd) {
            Ok(solve) => live.push((i, solve)),
            Err(e) => outcomes[i] = Some(Err(e)),
        }
    }
    // All solves advance in lockstep. Once a candidate with `n` iterations
    // exists, a solve about to take a step k > n can only end with more
    // iterations and can never win, so it is dropped; the candidates with the
    // fewest iterations all run to their end, and the rule below picks among
    // them exactly as among all answers. While no candidate exists nothing
    // is dropped, so an all-failed `Report` call still sees every failure.
    let mut cap = usize::MAX;
    while !live.is_empty() {
        live.retain_mut(|(i, solve)| {
            if solve.step > cap {
                return false;
            }
            match solve.next_step() {
                None => true,
                Some(result) => {
                    let result = apply_on_failure(result, starts.f_prior, starts.on_failure);
                    if let Ok(est) = &result {
                        cap = cap.min(est.iterations);
                    }
                    outcomes[*i] = Some(result);
                    false
                }
            }
        });
    }
    outcomes
}

/// The reference's choice among the outcomes: the fewest iterations, ties
/// by the smallest `|f1 - f2|`, then the earlier weight set; else the first
/// failure.
fn fewest_iterations(outcomes: Outcomes) -> Result<FocalEstimate, FocalFailure> {
    let mut best: Option<FocalEstimate> = None;
    let mut first_failure: Option<FocalFailure> = None;
    for result in outcomes.into_iter().flatten() {
        match result {
            Ok(est) => {
                let better = match &best {
                    None => true,
                    Some(b) => {
                        (est.iterations, (est.f1 - est.f2).abs())
                            < (b.iterations, (b.f1 - b.f2).abs())
                    }
                };
                if better {
                    best = Some(est);
                }
            }
            Err(e) => {
                first_failure.get_or_insert(e);
            }
        }
    }
    match (best, first_failure) {
        (Some(b), _) => Ok(b),
        (None, Some(e)) => Err(e),
        (None, None) => Err(FocalFailure::NoWeightSets),
    }
}
