//! Steps 1–3 of Algorithm 1: minimal samples, their fits (8-point, or
//! another minimal solver) and the IRLS-Tukey refinement of each.

use crate::adaptive::{stop_after, SupportTracker};
use crate::minimal::{solve_and_choose, ScoringSet};
use crate::subset::sorted_draw;
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
    /// them unless [`Params::cluster_subset`] is smaller than N
    /// ([`crate::subset_indices`]).
    pub subset: Vec<usize>,
    /// Whether hypothesis `j`'s minimal sample gave a fit. With the
    /// 8-point (or one solution per sample) hypothesis `j` is sample `j`;
    /// with `minimal_solutions = "all"` a sample gives one hypothesis per
    /// solution, or one unfitted hypothesis when it has none.
    pub fitted: Vec<bool>,
    /// The model of hypothesis `j` (refined, or the raw fit when `refine`
    /// is off), centred coordinates; None when the fit or the refinement
    /// failed, or the fit explained fewer than [`Params::min_consensus`]
    /// matches.
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
    if points.len() < params.mss_size {
        return Err(SegmentationError::TooFewPoints {
            n: points.len(),
            needed: params.mss_size,
        });
    }
    Ok(points)
}

/// Steps 1–3 of Algorithm 1 (see [`GeneratedHypotheses`]): samples drawn
/// by a [`MinimalSampler`] built once for the scene, hypotheses in
/// parallel in the caller's rayon pool; the result does not depend on the
/// number of threads. With [`Params::adaptive_batch`] the samples come in
/// batches until the stop rule of [`SupportTracker`] holds (its cost is
/// counted in the refinement time).
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
    let subset = subset_indices(params.seed, all.len(), params.cluster_subset);
    let (points, pixels1) = if subset.len() == all.len() {
        (all, Cow::Borrowed(matches.points1))
    } else {
        let pixels1 = subset.iter().map(|&i| matches.points1[i]).collect();
        let points = all
            .subset(&subset)
            .map_err(SegmentationError::InvalidPoints)?;
        (points, Cow::Owned(pixels1))
    };
    let sampler = MinimalSampler::new(&pixels1, params.sampling, params.sample_size());
    let preselect = preselect_subset(&points, params)?;
    let scoring = ScoringSet {
        points: &points,
        preselect: preselect.as_ref(),
    };
    let guided = params.sampling == Sampling::Guided;
    let batch = match params.adaptive_batch {
        0 if guided => params.guided_batch,
        0 => params.num_samples,
        b => b,
    };
    let mut co_inliers = guided.then(|| CoInliers::new(points.len(), params.num_samples));
    let mut tracker =
        (params.adaptive_batch > 0).then(|| SupportTracker::new(points.len(), params.thr_px));
    let (mut fitted, mut models) = (Vec::new(), Vec::new());
    let (mut sampling_seconds, mut refine_seconds) = (0.0, 0.0);
    for (b, start) in (0..params.num_samples).step_by(batch).enumerate() {
        let samples = start..(start + batch).min(params.num_samples);
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
        let fits = match params.minimal_solver {
            MinimalSolver::EightPoint => fit_minimal_samples(&points, draw, samples, params),
            _ => solve_minimal_samples(scoring, draw, samples, params, matches.focal_prior),
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
        let gained = tracker.as_mut().map(|t| t.add_batch(&points, &refined));
        refine_seconds += t.elapsed().as_secs_f64();
        fitted.extend(fits.iter().map(Option::is_some));
        models.extend(refined);
        if gained.is_some_and(|g| stop_after(b, g, points.len(), params.adaptive_tolerance)) {
            break;
        }
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

/// The matches of [`Params::preselect_matches`]: that many of `points`,
/// drawn uniformly from stream 2⁶⁴ − 2 of [`crate::hypothesis_rng`] (no hypothesis
/// draws from it, nor does [`subset_indices`]); `None` when the key is 0 or
/// not below the number of points.
fn preselect_subset(
    points: &Correspondences,
    params: &Params,
) -> Result<Option<Correspondences>, SegmentationError> {
    let (n, size) = (points.len(), params.preselect_matches);
    if size == 0 || size >= n {
        return Ok(None);
    }
    points
        .subset(&sorted_draw(params.seed, usize::MAX - 1, n, size))
        .map(Some)
        .map_err(SegmentationError::InvalidPoints)
}

/// A minimal sample's fit and the matches its refinement starts from: the
/// sample itself for the 8-point, the matches within `thr_px` of the fit
/// for the smaller minimal solvers (a weighted 8-point needs 8).
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
            let sample = draw.sample(params.seed, j, params.mss_size);
            let subset = points.subset(&sample).ok()?;
            let f = match params.eight_point {
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

/// Steps 1–2 with a minimal solver other than the 8-point: each sample's
/// solutions, chosen by [`Params::minimal_solutions`]; a sample without a
/// solution gives one unfitted hypothesis. `focal` is the five-point's
/// `K(f)`.
fn solve_minimal_samples(
    scoring: ScoringSet,
    draw: Draw,
    samples: Range<usize>,
    params: &Params,
    focal: f64,
) -> Vec<Option<SampleFit>> {
    let size = params.sample_size();
    let per_sample: Vec<Vec<Option<SampleFit>>> = samples
        .into_par_iter()
        .map(|j| {
            if draw.cancel.is_cancelled() {
                return vec![None];
            }
            let sample = draw.sample(params.seed, j, size);
            let chosen = match scoring.points.subset(&sample) {
                Ok(subset) => solve_and_choose(
                    params.minimal_solver,
                    params.minimal_solutions,
                    &subset,
                    scoring,
                    focal,
                    params.thr_px,
                ),
                Err(_) => Vec::new(),
            };
            if chosen.is_empty() {
                return vec![None];
            }
            chosen
                .into_iter()
                .map(|c| {
                    Some(SampleFit {
                        start: c.consensus,
                        f: c.f,
                    })
                })
                .collect()
        })
        .collect();
    per_sample.into_iter().flatten().collect()
}

/// The fit, unless its consensus set is smaller than
/// [`Params::min_consensus`] (which the 8-point's fits, started from their
/// sample, ignore).
fn kept<'a>(fit: &'a Option<SampleFit>, params: &Params) -> Option<&'a SampleFit> {
    fit.as_ref().filter(|fit| {
        params.minimal_solver == MinimalSolver::EightPoint
            || fit.start.len() >= params.min_consensus
    })
}

/// Step 3: IRLS-Tukey from each fit (or the raw fit when `refine` is off);
/// a minimal solution whose consensus set is smaller than
/// [`Params::min_consensus`] is dropped first.
fn refine_fits(
    points: &Correspondences,
    fits: &[Option<SampleFit>],
    params: &Params,
    cancel: &Cancel,
) -> Vec<Option<Matrix3<f64>>> {
    if !params.refine {
        return fits
            .iter()
            .map(|fit| kept(fit, params).map(|s| s.f))
            .collect();
    }
    let irls = params.irls();
    fits.par_iter()
        .map_init(IrlsWorkspace::new, |ws, fit| {
            let fit = kept(fit, params).filter(|_| !cancel.is_cancelled())?;
            let refined = ws.run(points, &fit.start, Some(&fit.f), &irls).ok()?;
            Some(refined.f)
        })
        .collect()
}
