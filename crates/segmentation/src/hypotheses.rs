//! Steps 1–3 of Algorithm 1: minimal samples, their fits (8-point, or
//! another minimal solver) and the IRLS-Tukey refinement of each.

use crate::minimal::solve_and_choose;
use crate::Cancel;
use crate::{
    subset_indices, CoInlierKernel, CoInliers, EightPoint, Matches, MinimalSampler, MinimalSolver,
    Params, Sampling, SegmentationError,
};
use geometry::{eight_point_normalized, eight_point_plain, Correspondences, IrlsWorkspace};
use nalgebra::Matrix3;
use rayon::prelude::*;
use std::borrow::Cow;
use std::ops::Range;
use std::time::Instant;

/// The hypotheses of steps 1–3 for one input. They depend only on the
/// matches and on [`Params::hypothesis_key`], so one set serves every
/// parameter set that shares that key.
#[derive(Debug, Clone, PartialEq)]
pub struct GeneratedHypotheses {
    /// The correspondences the hypotheses were drawn from and steps 7–9
    /// cluster, in principal-point-centred coordinates: the matches of
    /// `subset`.
    pub points: Correspondences,
    /// The indices of those matches among the input's, increasing: all of
    /// them unless [`SamplingParams::cluster_subset`](crate::SamplingParams::cluster_subset) is smaller than N
    /// ([`crate::subset_indices`]).
    pub subset: Vec<usize>,
    /// Whether hypothesis `j`'s minimal sample (sample `j`) gave a fit.
    pub fitted: Vec<bool>,
    /// The model of hypothesis `j` (refined, or the raw fit when `refine`
    /// is off), centred coordinates; None when the fit or the refinement
    /// failed.
    pub models: Vec<Option<Matrix3<f64>>>,
    /// Wall time of steps 1–2, seconds.
    pub sampling_seconds: f64,
    /// Wall time of step 3, seconds.
    pub refine_seconds: f64,
}

impl GeneratedHypotheses {
    /// Indices of the hypotheses with a model, in order.
    pub fn refined(&self) -> Vec<usize> {
        (0..self.models.len())
            .filter(|&j| self.models[j].is_some())
            .collect()
    }
}

/// The matches in principal-point-centred coordinates, checked: the
/// parameters, the camera fields, finite points of equal count, at least
/// `mss_size` of them.
pub fn centred_points(
    matches: &Matches,
    params: &Params,
) -> Result<Correspondences, SegmentationError> {
    params.validate()?;
    matches.validate()?;
    let pp = matches.principal_point;
    let points = Correspondences::new(matches.points1, matches.points2)
        .map_err(SegmentationError::InvalidPoints)?
        .shifted(pp, pp);
    if points.len() < params.sampling.mss_size {
        return Err(SegmentationError::TooFewPoints {
            n: points.len(),
            needed: params.sampling.mss_size,
        });
    }
    Ok(points)
}

/// Steps 1–3 of Algorithm 1 (see [`GeneratedHypotheses`]): samples drawn
/// by a [`MinimalSampler`] built once for the scene, hypotheses in
/// parallel in the caller's rayon pool; the result does not depend on the
/// number of threads. Guided sampling draws in batches of
/// [`SamplingParams::guided_batch`](crate::SamplingParams::guided_batch), each guided by the hypotheses before it.
///
/// Errors on invalid parameters or camera fields, fewer points than
/// `mss_size` and non-finite coordinates.
pub fn generate_hypotheses(
    matches: &Matches,
    params: &Params,
) -> Result<GeneratedHypotheses, SegmentationError> {
    generate_hypotheses_cancellable(matches, params, &Cancel::new())
}

/// [`generate_hypotheses`], stopped by `cancel`: once it is set, the
/// samples and refinements not yet started are skipped and the call
/// returns [`SegmentationError::Interrupted`].
pub fn generate_hypotheses_cancellable(
    matches: &Matches,
    params: &Params,
    cancel: &Cancel,
) -> Result<GeneratedHypotheses, SegmentationError> {
    let all = centred_points(matches, params)?;
    let subset = subset_indices(
        params.sampling.seed,
        all.len(),
        params.sampling.cluster_subset,
    );
    let (points, pixels1) = if subset.len() == all.len() {
        (all, Cow::Borrowed(matches.points1))
    } else {
        let pixels1 = subset.iter().map(|&i| matches.points1[i]).collect();
        let points = all
            .subset(&subset)
            .map_err(SegmentationError::InvalidPoints)?;
        (points, Cow::Owned(pixels1))
    };
    let sampler = MinimalSampler::new(&pixels1, params.sampling.sampling, params.sample_size());
    let guided = params.sampling.sampling == Sampling::Guided;
    let batch = if guided {
        params.sampling.guided_batch
    } else {
        params.sampling.num_samples
    };
    let mut co_inliers = guided.then(|| CoInliers::new(points.len(), params.sampling.num_samples));
    let (mut fitted, mut models) = (Vec::new(), Vec::new());
    let (mut sampling_seconds, mut refine_seconds) = (0.0, 0.0);
    for start in (0..params.sampling.num_samples).step_by(batch) {
        let samples = start..(start + batch).min(params.sampling.num_samples);
        let t = Instant::now();
        let draw = Draw {
            sampler: &sampler,
            cancel,
            // Guided after the first batch, by the hypotheses before.
            guide: co_inliers
                .as_mut()
                .filter(|co| !co.is_empty())
                .map(|co| co.kernel()),
        };
        let fits = match params.sampling.minimal_solver {
            MinimalSolver::EightPoint => fit_minimal_samples(&points, draw, samples, params),
            MinimalSolver::FivePoint => {
                solve_minimal_samples(&points, draw, samples, params, matches.focal_prior)
            }
        };
        if let Some(co) = co_inliers.as_mut() {
            for fit in &fits {
                co.add(fit.as_ref().map_or(&[], |f| &f.start));
            }
        }
        sampling_seconds += t.elapsed().as_secs_f64();

        let t = Instant::now();
        cancel.check()?;
        let refined = refine_fits(&points, &fits, params, cancel);
        cancel.check()?;
        refine_seconds += t.elapsed().as_secs_f64();
        fitted.extend(fits.iter().map(Option::is_some));
        models.extend(refined);
    }
    Ok(GeneratedHypotheses {
        points,
        subset,
        fitted,
        models,
        sampling_seconds,
        refine_seconds,
    })
}

/// A minimal sample's fit and the matches its refinement starts from: the
/// sample itself for the 8-point, the matches within `thr_px` of the fit
/// for the five-point (a weighted 8-point needs 8).
struct SampleFit {
    start: Vec<usize>,
    f: Matrix3<f64>,
}

/// Where the samples come from: the scene's sampler and, for guided
/// sampling after its first batch, the co-inlier counts of the hypotheses
/// so far.
#[derive(Clone, Copy)]
struct Draw<'a> {
    sampler: &'a MinimalSampler,
    guide: Option<&'a CoInlierKernel>,
    /// Checked before each sample: once set, the sample is skipped.
    cancel: &'a Cancel,
}

impl Draw<'_> {
    fn sample(&self, seed: u64, index: usize, size: usize) -> Vec<usize> {
        self.sampler.sample_guided(self.guide, seed, index, size)
    }
}

/// Steps 1–2: each minimal sample and its 8-point fit (None when the sample
/// is degenerate or the fit not finite).
fn fit_minimal_samples(
    points: &Correspondences,
    draw: Draw,
    samples: Range<usize>,
    params: &Params,
) -> Vec<Option<SampleFit>> {
    samples
        .into_par_iter()
        .map(|j| {
            if draw.cancel.is_cancelled() {
                return None;
            }
            let sample = draw.sample(params.sampling.seed, j, params.sampling.mss_size);
            let subset = points.subset(&sample).ok()?;
            let f = match params.reference_code.eight_point {
                EightPoint::Normalized => eight_point_normalized(&subset),
                EightPoint::Plain => eight_point_plain(&subset),
            }
            .ok()?;
            f.iter()
                .all(|v| v.is_finite())
                .then_some(SampleFit { start: sample, f })
        })
        .collect()
}

/// Steps 1–2 with the five-point solver: each sample's solution, chosen by
/// [`Params::minimal_solutions`] (None when the sample has none). `focal`
/// is the five-point's `K(f)`.
fn solve_minimal_samples(
    points: &Correspondences,
    draw: Draw,
    samples: Range<usize>,
    params: &Params,
    focal: f64,
) -> Vec<Option<SampleFit>> {
    let size = params.sample_size();
    samples
        .into_par_iter()
        .map(|j| {
            if draw.cancel.is_cancelled() {
                return None;
            }
            let sample = draw.sample(params.sampling.seed, j, size);
            let subset = points.subset(&sample).ok()?;
            let chosen = solve_and_choose(
                params.sampling.minimal_solutions,
                &subset,
                points,
                focal,
                params.refinement.thr_px,
            )?;
            Some(SampleFit {
                start: chosen.consensus,
                f: chosen.f,
            })
        })
        .collect()
}

/// Step 3: IRLS-Tukey from each fit (or the raw fit when `refine` is off).
fn refine_fits(
    points: &Correspondences,
    fits: &[Option<SampleFit>],
    params: &Params,
    cancel: &Cancel,
) -> Vec<Option<Matrix3<f64>>> {
    if !params.refinement.refine {
        return fits.iter().map(|fit| fit.as_ref().map(|s| s.f)).collect();
    }
    let irls = params.irls();
    fits.par_iter()
        .map_init(IrlsWorkspace::new, |ws, fit| {
            let fit = fit.as_ref().filter(|_| !cancel.is_cancelled())?;
            let refined = ws.run(points, &fit.start, Some(&fit.f), &irls).ok()?;
            Some(refined.f)
        })
        .collect()
}
