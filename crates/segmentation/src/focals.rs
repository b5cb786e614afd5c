//! Step 4 of Algorithm 1: the focal lengths of every refined hypothesis.

use crate::{FocalSolver, GeneratedHypotheses, Params, SegmentationError};
use focal::{FocalWeights, OnFailure};
use nalgebra::Matrix3;
use rayon::prelude::*;
use std::time::Instant;

/// The focal lengths of step 4 for every hypothesis with a model (`None`
/// for the others and for failed solves), and the step's wall time.
#[derive(Debug, Clone, PartialEq)]
pub struct HypothesisFocals {
    /// `(f1, f2)` of hypothesis `j`, px.
    pub focals: Vec<Option<(f64, f64)>>,
    /// Whether hypothesis `j`'s focals are the prior standing in for a
    /// failed solve (`focal_failure = "prior"`).
    pub from_prior: Vec<bool>,
    /// Wall time of step 4, seconds.
    pub seconds: f64,
}

/// One hypothesis's focals and whether they are the prior standing in for a
/// failed solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FocalAnswer {
    /// `(f1, f2)`, px.
    pub focals: (f64, f64),
    /// True when the focals are the prior.
    pub from_prior: bool,
}

impl HypothesisFocals {
    /// Focals computed outside this crate (`focal_solver = "external"`),
    /// one entry per generated hypothesis: used as given (truncated when
    /// `truncate_focals`), none when missing or not finite, and an answer
    /// equal to `(focal_prior, focal_prior)` counts as the prior. Answers for
    /// hypotheses without a model are ignored.
    ///
    /// Errors when the number of answers is not the number of hypotheses.
    pub fn from_answers(
        answers: &[Option<(f64, f64)>],
        hypotheses: &GeneratedHypotheses,
        params: &Params,
        focal_prior: f64,
    ) -> Result<Self, SegmentationError> {
        if answers.len() != hypotheses.models.len() {
            return Err(SegmentationError::StageMismatch(format!(
                "{} focal answers for {} hypotheses",
                answers.len(),
                hypotheses.models.len()
            )));
        }
        let estimates: Vec<Option<FocalAnswer>> = answers
            .iter()
            .zip(&hypotheses.models)
            .map(|(answer, model)| {
                model.as_ref()?;
                let focals = focals_as_used((*answer)?, params);
                let finite = focals.0.is_finite() && focals.1.is_finite();
                finite.then_some(FocalAnswer {
                    focals,
                    from_prior: focals == (focal_prior, focal_prior),
                })
            })
            .collect();
        Ok(Self::from_estimates(&estimates, 0.0))
    }

    fn from_estimates(estimates: &[Option<FocalAnswer>], seconds: f64) -> Self {
        Self {
            focals: estimates.iter().map(|e| e.map(|a| a.focals)).collect(),
            from_prior: estimates
                .iter()
                .map(|e| e.is_some_and(|a| a.from_prior))
                .collect(),
            seconds,
        }
    }
}

/// `(f1, f2)` as the pipeline uses them: truncated to integers when
/// `truncate_focals` (the reference code), else unchanged.
pub fn focals_as_used(focals: (f64, f64), params: &Params) -> (f64, f64) {
    if params.reference_code.truncate_focals {
        (focals.0.trunc(), focals.1.trunc())
    } else {
        focals
    }
}

/// Focal lengths of one hypothesis `f` (step 4), principal points at the
/// origin, with `params`'s solver; `weight_sets` are the multi-start
/// weights of the robust solver. None for a failed solve (and always for
/// [`FocalSolver::External`]).
pub fn estimate_focals(
    f: &Matrix3<f64>,
    params: &Params,
    weight_sets: &[FocalWeights],
    focal_prior: f64,
) -> Option<FocalAnswer> {
    let (focals, from_prior) = match params.focal.focal_solver {
        FocalSolver::Kocur => focal::robust_focals_multi_start(
            f,
            focal_prior,
            weight_sets,
            params.focal.max_iters,
            params.reference_code.focal_failure,
        )
        .ok()
        .map(|e| ((e.f1, e.f2), e.from_prior)),
        FocalSolver::Bougnoux => match focal::bougnoux(f, [0.0, 0.0], [0.0, 0.0]) {
            Ok(pair) => Some((pair, false)),
            Err(_) if params.reference_code.focal_failure == OnFailure::Prior => {
                Some(((focal_prior, focal_prior), true))
            }
            Err(_) => None,
        },
        FocalSolver::External => None,
    }?;
    Some(FocalAnswer {
        focals: focals_as_used(focals, params),
        from_prior,
    })
}

/// Step 4 of Algorithm 1: the focal lengths of every hypothesis with a
/// model, in parallel, with `params`'s solver ([`Params::focal_key`]) and
/// the focal prior.
///
/// Errors for [`FocalSolver::External`], whose answers come as data
/// ([`HypothesisFocals::from_answers`]).
pub fn estimate_hypothesis_focals(
    hypotheses: &GeneratedHypotheses,
    params: &Params,
    focal_prior: f64,
) -> Result<HypothesisFocals, SegmentationError> {
    if params.focal.focal_solver == FocalSolver::External {
        return Err(SegmentationError::ExternalFocalsRequired);
    }
    let t = Instant::now();
    let weight_sets = params.focal.weight_sets.sets();
    let estimates: Vec<Option<FocalAnswer>> = hypotheses
        .models
        .par_iter()
        .map(|model| estimate_focals(model.as_ref()?, params, &weight_sets, focal_prior))
        .collect();
    Ok(HypothesisFocals::from_estimates(
        &estimates,
        t.elapsed().as_secs_f64(),
    ))
}
