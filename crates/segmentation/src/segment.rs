//! Algorithm 1 end to end (docs/method.md steps 1–9), and steps 5–9 on
//! hypotheses and focals computed beforehand.

use crate::assignment::members;
use crate::memory_guard::{memory_limit, ASSUMED_PREFERENCE_DENSITY};
use crate::merge::inlier_words;
use crate::selection::nfa::FITTED_MATCHES;
use crate::selection::{select_clustered, select_groups, Camera, GroupOrigin, ImageRect};
use crate::{
    available_memory, centred_points, check_available_memory, check_matches,
    estimate_hypothesis_focals, extend_labels, focal_filter, generate_hypotheses_cancellable,
    merge_explained, Cancel, ClusterModel, ClusteredSubset, FinalAssignment, FocalVerdict,
    GeneratedHypotheses, Hypothesis, HypothesisCounts, HypothesisFocals, HypothesisStatus,
    InlierBits, Matches, Method, Params, Segmentation, SegmentationError, StageTimings,
    SubsetExtension,
};
use clustering::dendrogram::last_sides;
use clustering::{ClusteringParams, Preferences};
use geometry::{eight_point_normalized, sampson_distances_squared, Correspondences, SampsonModels};
use nalgebra::Matrix3;
use std::borrow::Cow;
use std::time::Instant;

/// Segments `matches` by Algorithm 1 (docs/method.md steps 1–9) with `params`.
///
/// Errors only on input that admits no hypothesis at all (invalid
/// parameters or camera fields, fewer points than `mss_size`, non-finite
/// coordinates) and for `focal_solver = "external"` (use
/// [`segment_with`]). When every hypothesis is rejected the result is an
/// all-outlier segmentation whose [`Segmentation::degenerate`] says why.
///
/// ```
/// use segmentation::{segment, Matches, Method, Params};
/// // Two rigid motions seen by one camera: the second moves sideways.
/// let mut p1 = Vec::new();
/// let mut p2 = Vec::new();
/// for i in 0..60 {
///     let (x, y, z) = ((i % 10) as f64 - 4.5, (i / 10) as f64 - 2.5, 8.0 + (i % 7) as f64);
///     let shift = if i < 30 { [0.4, 0.0] } else { [-0.3, 0.2] };
///     p1.push([500.0 * x / z + 320.0, 500.0 * y / z + 240.0]);
///     p2.push([500.0 * (x + shift[0]) / z + 320.0, 500.0 * (y + shift[1]) / z + 240.0]);
/// }
/// let params = Params::default().with(|q| { q.focal.method = Method::Baseline; q.sampling.num_samples = 300; });
/// let seg = segment(&Matches::new(&p1, &p2, (640, 480)), &params).unwrap();
/// assert_eq!(seg.labels.len(), 60);
/// assert_eq!(seg.counts.generated, 300);
/// ```
pub fn segment(matches: &Matches, params: &Params) -> Result<Segmentation, SegmentationError> {
    segment_cancellable(matches, params, &Cancel::new())
}

/// [`segment`], stopped by `cancel` (set from another thread): it is
/// checked between the stages, before each minimal sample and refinement
/// and before each preference row, and once set the call returns
/// [`SegmentationError::Interrupted`] (the work so far is dropped).
///
/// Before sampling, the coordinates are checked ([`check_matches`]) and
/// the memory of the run is bounded: by [`Params::max_memory_mb`] when
/// set, else by the machine's available memory
/// ([`check_available_memory`] with [`available_memory`]).
pub fn segment_cancellable(
    matches: &Matches,
    params: &Params,
    cancel: &Cancel,
) -> Result<Segmentation, SegmentationError> {
    let started = Instant::now();
    params.validate()?;
    check_matches(matches)?;
    check_memory(matches.len(), params)?;
    cancel.check()?;
    let hypotheses = generate_hypotheses_cancellable(matches, params, cancel)?;
    let focals = (params.focal.method == Method::Semical)
        .then(|| estimate_hypothesis_focals(&hypotheses, params, matches.focal_prior))
        .transpose()?;
    cancel.check()?;
    let mut segmentation =
        segment_with_cancellable(matches, params, &hypotheses, focals.as_ref(), cancel)?;
    segmentation.timings.total = started.elapsed().as_secs_f64();
    Ok(segmentation)
}

/// Steps 5–9 of Algorithm 1 on hypotheses generated for these matches with
/// these parameters ([`generate_hypotheses`](crate::generate_hypotheses)) and, for semical, their focal
/// lengths ([`estimate_hypothesis_focals`] or
/// [`HypothesisFocals::from_answers`]); the stage timings of those steps
/// are copied from them. The result is that of [`segment`].
///
/// Errors when `focals` is missing for semical or the stages do not belong
/// to these matches and parameters, and as [`segment`].
pub fn segment_with(
    matches: &Matches,
    params: &Params,
    generated: &GeneratedHypotheses,
    focals: Option<&HypothesisFocals>,
) -> Result<Segmentation, SegmentationError> {
    segment_with_cancellable(matches, params, generated, focals, &Cancel::new())
}

/// [`segment_with`], stopped by `cancel` as [`segment_cancellable`] is.
pub fn segment_with_cancellable(
    matches: &Matches,
    params: &Params,
    generated: &GeneratedHypotheses,
    focals: Option<&HypothesisFocals>,
    cancel: &Cancel,
) -> Result<Segmentation, SegmentationError> {
    let started = Instant::now();
    params.validate()?;
    let warnings = check_matches(matches)?;
    check_stages(matches, params, generated, focals)?;
    let mut timings = StageTimings {
        sampling: generated.sampling_seconds,
        refine: generated.refine_seconds,
        ..StageTimings::default()
    };
    let mut hypotheses = initial_statuses(generated);
    let refined = generated.refined();
    let mut counts = HypothesisCounts {
        generated: generated.models.len(),
        refined: refined.len(),
        local_ok: refined.len(),
        ..HypothesisCounts::default()
    };

    // Steps 4–6: focal lengths, local test, consensus and band.
    let mut consensus = None;
    let mut consensus_fallback = false;
    let mut focal_verdict = FocalVerdict::NotEstimated;
    if let Some(focals) = focals.filter(|_| params.focal.method == Method::Semical) {
        for &j in &refined {
            hypotheses[j].focals = focals.focals[j];
            counts.focal_failures += usize::from(focals.focals[j].is_none());
            counts.focal_priors += usize::from(focals.from_prior[j]);
        }
        timings.focal = focals.seconds;
        let t = Instant::now();
        let outcome = focal_filter(&mut hypotheses, &refined, params, matches.focal_prior);
        (consensus, consensus_fallback, counts.local_ok) =
            (outcome.consensus, outcome.fallback, outcome.local_ok);
        focal_verdict = outcome.verdict;
        timings.consensus = t.elapsed().as_secs_f64();
    }
    // Steps 1–4 ran before this call (or were shared with another one).
    let shared_seconds = timings.sampling + timings.refine + timings.focal;
    let kept: Vec<usize> = refined
        .iter()
        .copied()
        .filter(|&j| hypotheses[j].status == HypothesisStatus::Kept)
        .collect();
    counts.kept = kept.len();
    let mut segmentation = Segmentation {
        labels: vec![-1; matches.len()],
        counts,
        hypotheses,
        consensus,
        consensus_fallback,
        focal_verdict,
        clusters: Vec::new(),
        clusters_before_filter: 0,
        timings,
        degenerate: None,
        warnings,
    };
    cancel.check()?;
    if kept.is_empty() {
        segmentation.degenerate = Some(nothing_kept_reason(generated).to_string());
    } else {
        let stages = Stages {
            generated,
            kept: &kept,
            cancel,
        };
        cluster_kept(&mut segmentation, matches, stages, params)?;
    }
    segmentation.timings.total = started.elapsed().as_secs_f64() + shared_seconds;
    Ok(segmentation)
}

/// Checks that the stages were computed for these matches and parameters.
fn check_stages(
    matches: &Matches,
    params: &Params,
    generated: &GeneratedHypotheses,
    focals: Option<&HypothesisFocals>,
) -> Result<(), SegmentationError> {
    let (n, m) = (generated.subset.len(), generated.models.len());
    let subset_len = params.clustered_matches(matches.len());
    let subset_ok = generated.points.len() == n
        && n == subset_len
        && generated.subset.last().map_or(true, |&i| i < matches.len());
    // One hypothesis per minimal sample.
    if !subset_ok || m != params.sampling.num_samples {
        return Err(SegmentationError::StageMismatch(format!(
            "hypotheses generated for {n} points and M = {m}, not {subset_len} and {}",
            params.sampling.num_samples
        )));
    }
    if params.focal.method == Method::Semical
        && !focals.is_some_and(|f| f.focals.len() == m && f.from_prior.len() == m)
    {
        return Err(SegmentationError::StageMismatch(format!(
            "semical needs the focal lengths of step 4 for all {m} hypotheses"
        )));
    }
    Ok(())
}

/// Each hypothesis's status after steps 2–3 (kept unless it failed there).
fn initial_statuses(generated: &GeneratedHypotheses) -> Vec<Hypothesis> {
    generated
        .fitted
        .iter()
        .zip(&generated.models)
        .map(|(&fitted, model)| Hypothesis {
            status: match (fitted, model) {
                (false, _) => HypothesisStatus::Degenerate,
                (true, None) => HypothesisStatus::RefineFailed,
                (true, Some(_)) => HypothesisStatus::Kept,
            },
            focals: None,
        })
        .collect()
}

fn nothing_kept_reason(generated: &GeneratedHypotheses) -> &'static str {
    if generated.fitted.iter().all(|&fitted| !fitted) {
        "every minimal sample is degenerate"
    } else {
        "no hypothesis survived the refinement"
    }
}

/// Steps 7–9 on the kept hypotheses: preferences (Eq. 38), T-/J-Linkage,
/// the size filter, the final assignment ([`Params::final_assignment`],
/// timed with the cluster fits), the matches left out of a
/// [`Params::cluster_subset`] ([`extend_labels`], timed likewise) and the
/// 8-point F of each final cluster.
fn cluster_kept(
    segmentation: &mut Segmentation,
    matches: &Matches,
    stages: Stages,
    params: &Params,
) -> Result<(), SegmentationError> {
    let Stages {
        generated, cancel, ..
    } = stages;
    let points = &generated.points;
    let clustering_params = clustering_params(params, memory_limit(params));
    // Step 7: preferences, one point (row) at a time.
    let t = Instant::now();
    let subset_active = generated.subset.len() < matches.len();
    // The inlier sets of the entering hypotheses: the merge's models, and
    // the cluster models that the subset's extension may test against.
    let keep_inliers = params.selection.final_assignment == FinalAssignment::Merge
        || (subset_active && params.selection.subset_extension != SubsetExtension::Preference);
    let step7 = build_preferences(stages, params, keep_inliers)?;
    segmentation.timings.preferences = t.elapsed().as_secs_f64();
    cancel.check()?;

    // Steps 8–9: linkage and size filter.
    let t = Instant::now();
    let stop = || cancel.is_cancelled();
    let clustering = clustering_params
        .try_cluster_owned_until(step7.preferences, &stop)?
        .ok_or(SegmentationError::Interrupted)?;
    segmentation.timings.clustering = t.elapsed().as_secs_f64();
    cancel.check()?;

    let t = Instant::now();
    // Where every match was clustered, the two sides of each cluster's
    // last merge, which the selection may split it into.
    let sides = (params.selection.final_assignment == FinalAssignment::Nfa && !subset_active)
        .then(|| last_sides(&clustering, FITTED_MATCHES + 1));
    let (labels, clusters) = match params.selection.final_assignment {
        FinalAssignment::Merge => with_count(merge_explained(
            &clustering.labels,
            clustering.clusters_after_filter,
            &step7.inliers,
        )),
        FinalAssignment::None | FinalAssignment::Nfa => {
            (clustering.labels, clustering.clusters_after_filter)
        }
    };
    let (labels, all_points) = if subset_active {
        let all = centred_points(matches, params)?;
        let subset = ClusteredSubset {
            indices: &generated.subset,
            labels: &labels,
            clusters,
        };
        let tau = params.refinement.thr_px * params.refinement.thr_px;
        let how = params.selection.subset_extension;
        let (models, inliers) = (&step7.models, &step7.inliers);
        let labels = extend_labels(&all, subset, models, inliers, tau, how);
        (labels, Cow::Owned(all))
    } else {
        (labels, Cow::Borrowed(points))
    };
    let (labels, clusters) = if params.selection.final_assignment == FinalAssignment::Nfa {
        // The clusters, every match labelled, are the selection's groups.
        let groups = members(&labels, clusters);
        let thr = params.refinement.thr_px;
        let camera = Camera {
            image: ImageRect::new(matches.image_size, matches.principal_point),
            focal_px: matches.focal_prior,
        };
        let selected = match &sides {
            Some(sides) => select_clustered(&all_points, &groups, sides, camera, thr)?,
            None => select_groups(&all_points, &groups, GroupOrigin::Extended, camera, thr)?,
        };
        (selected.labels, selected.motions)
    } else {
        (labels, clusters)
    };
    segmentation.clusters = cluster_models(&all_points, &labels, clusters);
    segmentation.timings.cluster_fit = t.elapsed().as_secs_f64();
    segmentation.clusters_before_filter = clustering.clusters_before_filter;
    segmentation.labels = labels;
    Ok(())
}

/// What step 7 gives steps 8–9: the preferences, the inlier sets of the
/// entering hypotheses when `keep_inliers` (empty otherwise) and the
/// models that entered the preferences, in order.
struct PreferenceStage {
    preferences: Preferences,
    inliers: InlierBits,
    models: Vec<Matrix3<f64>>,
}

/// Step 7 on the kept hypotheses (Eq. 38, or J-Linkage's `r ≤ τ`): the
/// preference matrix, built one point at a time in parallel
/// ([`clustering::Preferences::from_residual_rows`], each row stored at
/// exactly its size), with `τ = thr_px²`. With `keep_inliers` (the merge's
/// and the subset extension's cluster models), each hypothesis's inlier set
/// (`r ≤ τ`) is computed first, one hypothesis at a time, and returned
/// (empty otherwise).
fn build_preferences(
    stages: Stages,
    params: &Params,
    keep_inliers: bool,
) -> Result<PreferenceStage, SegmentationError> {
    let Stages {
        generated,
        kept,
        cancel,
    } = stages;
    let points = &generated.points;
    let tau = params.refinement.thr_px * params.refinement.thr_px;
    let mut residuals = vec![0.0; points.len()];
    let mut inliers = InlierBits::new(points.len());
    let mut entering = Vec::with_capacity(kept.len());
    for &j in kept {
        let Some(model) = generated.models[j].as_ref() else {
            continue;
        };
        if keep_inliers {
            sampson_distances_squared(model, points, &mut residuals);
            inliers.push_words(inlier_words(&residuals, tau));
        }
        entering.push(*model);
    }
    let models = SampsonModels::new(&entering);
    let preferences = Preferences::from_residual_rows(
        params.clustering.linkage,
        points.len(),
        models.len(),
        tau,
        |i, out| {
            // Once cancelled, the rows left are not computed (every
            // residual above τ) and the caller returns Interrupted.
            if cancel.is_cancelled() {
                out.fill(f64::INFINITY);
            } else {
                models.distances_squared(points.point1(i), points.point2(i), out);
            }
        },
    )?;
    Ok(PreferenceStage {
        preferences,
        inliers,
        models: entering,
    })
}

/// Labels numbered 0, 1, … by first appearance (−1 outliers) with their
/// number of clusters.
fn with_count(labels: Vec<i32>) -> (Vec<i32>, usize) {
    let clusters = labels.iter().map(|&l| l + 1).max().unwrap_or(0) as usize;
    (labels, clusters)
}

/// What steps 7–9 take from the steps before: the hypotheses, the kept
/// ones and the caller's cancellation flag.
#[derive(Clone, Copy)]
struct Stages<'a> {
    generated: &'a GeneratedHypotheses,
    kept: &'a [usize],
    cancel: &'a Cancel,
}

/// The explicit bound [`Params::max_memory_mb`], bytes (`None` for 0).
fn explicit_limit(params: &Params) -> Option<u64> {
    (params.max_memory_mb > 0).then(|| params.max_memory_mb.saturating_mul(1_000_000))
}

/// The memory checks [`segment`] makes before sampling: the preference
/// matrix and linkage of `num_samples` hypotheses over the matches
/// clustered of `n_matches`, at `ASSUMED_PREFERENCE_DENSITY`, against
/// [`Params::max_memory_mb`] when set, and the whole run's need against the
/// machine's available memory when it is 0 ([`check_available_memory`]).
/// Callers that run the stages themselves ([`generate_hypotheses`](crate::generate_hypotheses) then
/// [`segment_with`]) call it first.
pub fn check_memory(n_matches: usize, params: &Params) -> Result<(), SegmentationError> {
    clustering_params(params, explicit_limit(params)).check_memory(
        params.clustered_matches(n_matches),
        params.sampling.num_samples,
        ASSUMED_PREFERENCE_DENSITY,
    )?;
    check_available_memory(n_matches, params, available_memory())
}

/// The clustering's parameters: linkage, size filter and the memory bound
/// `limit` (bytes).
fn clustering_params(params: &Params, limit: Option<u64>) -> ClusteringParams {
    ClusteringParams {
        linkage: params.clustering.linkage,
        min_cluster_size: params.clustering.min_cluster_size,
        size_rule: params.clustering.size_rule,
        max_memory_bytes: limit,
    }
}

/// The 8-point F of each cluster `0..clusters` of `labels`, by label.
fn cluster_models(points: &Correspondences, labels: &[i32], clusters: usize) -> Vec<ClusterModel> {
    members(labels, clusters)
        .iter()
        .enumerate()
        .map(|(label, idx)| ClusterModel {
            label: label as i32,
            size: idx.len(),
            f: fit_cluster(points, idx),
        })
        .collect()
}

/// Hartley-normalised 8-point F of the points `indices` (None with fewer
/// than 8 points or a degenerate configuration).
pub fn fit_cluster(points: &Correspondences, indices: &[usize]) -> Option<Matrix3<f64>> {
    if indices.len() < geometry::MIN_POINTS {
        return None;
    }
    eight_point_normalized(&points.subset(indices).ok()?).ok()
}
