//! The per-scene evaluation of `sctl run`: [`crate::pipeline::segment`] followed by the
//! metrics of docs/method.md ("Metrics") against the scene's ground truth, and
//! the per-scene figures ([`draw_scene_plots`]).

use crate::config::{Method, PipelineConfig};
use crate::experiment::{Evaluator, ScenePlots};
use crate::output::{file_safe, SceneResult, StageTimings};
use crate::pipeline::{
    estimate_hypothesis_focals, fit_cluster, generate_hypotheses, segment_with,
    GeneratedHypotheses, HypothesisFocals, PipelineError, Segmentation,
};
use crate::plots::{clusters_over_images, focal_kde, FocalKdePlot};
use anyhow::Result;
use datasets::Scene;
use geometry::Correspondences;
use metrics::{frob_score, KnownMetrics};
use nalgebra::Matrix3;
use segmentation::{FocalKey, HypothesisKey};
use std::collections::{BTreeMap, VecDeque};
use std::path::PathBuf;
use std::sync::{Arc, Mutex};

// A scene's unknown label is the one the metrics leave out.
const _: () = assert!(datasets::UNKNOWN_LABEL == metrics::GROUND_TRUTH_UNKNOWN);

/// File-name suffix of the focal KDE figure of a scene.
pub const FOCAL_KDE_SUFFIX: &str = "focal_kde";
/// File-name suffix of the clusters figure of a scene.
pub const CLUSTERS_SUFFIX: &str = "clusters";

/// Draws the figures of one segmented scene into `plots.dir`, once per
/// format, and returns the files written:
///
/// - `<scene>_clusters`: the segmentation's clusters over both images
///   (Figs. 11–12), or over blank canvases of the image size when the scene
///   has no images;
/// - `<scene>_focal_kde`: for the semical method when a consensus was
///   computed, the KDE of the [`Segmentation::kde_values`] with f_peak, the band
///   `f_peak (1 ± τ_range)` (Eq. 37) and the true focal when known (Fig. 8).
///
/// `<scene>` is the scene name made [`file_safe`] (`2/0900` → `2_0900`).
pub fn draw_scene_plots(
    scene: &Scene,
    segmentation: &Segmentation,
    pipeline: &PipelineConfig,
    plots: &ScenePlots,
) -> Result<Vec<PathBuf>> {
    let stem = file_safe(&scene.name);
    let mut written = Vec::new();
    let outliers = segmentation.labels.iter().filter(|&&l| l < 0).count();
    let clusters_title = format!(
        "{} ({}): {} motion(s), {} outliers",
        scene.name,
        plots.label,
        segmentation.clusters.len(),
        outliers
    );
    let kde_title = format!("{} ({})", scene.name, plots.label);
    let values = segmentation.kde_values(pipeline.params.focal.tau_diff);
    for format in &plots.formats {
        let ext = format.extension();
        let path = plots.dir.join(format!("{stem}_{CLUSTERS_SUFFIX}.{ext}"));
        clusters_over_images(
            scene.image_size,
            scene.images.as_ref().map(|(a, b)| (a, b)),
            &scene.points1,
            &scene.points2,
            &segmentation.labels,
            &clusters_title,
            &path,
        )?;
        written.push(path);
        if pipeline.params.focal.method != Method::Semical {
            continue;
        }
        if let Some(consensus) = &segmentation.consensus {
            let path = plots.dir.join(format!("{stem}_{FOCAL_KDE_SUFFIX}.{ext}"));
            let plot = FocalKdePlot::from_consensus(
                &values,
                consensus,
                pipeline.params.focal.tau_range,
                scene.true_focal,
                &kde_title,
            );
            focal_kde(&plot, &path)?;
            written.push(path);
        }
    }
    Ok(written)
}

/// The 8-point F of each ground-truth motion with at least 8 points, in
/// label order, in principal-point-centred coordinates (the FROB side of
/// the truth, Eq. 45).
pub fn ground_truth_models(scene: &Scene) -> Vec<Matrix3<f64>> {
    let Some(labels) = &scene.labels else {
        return Vec::new();
    };
    let Ok(points) = Correspondences::new(&scene.points1, &scene.points2) else {
        return Vec::new();
    };
    let points = points.shifted(scene.principal_point, scene.principal_point);
    motion_indices(labels)
        .values()
        .filter_map(|idx| fit_cluster(&points, idx))
        .collect()
}

/// The indices of the points of each ground-truth motion (labels > 0), by
/// label in increasing order.
pub fn motion_indices(labels: &[i32]) -> BTreeMap<i32, Vec<usize>> {
    let mut motions: BTreeMap<i32, Vec<usize>> = BTreeMap::new();
    for (i, &l) in labels.iter().enumerate() {
        if l > 0 {
            motions.entry(l).or_default().push(i);
        }
    }
    motions
}

/// The `per_scene.csv` record of a segmentation of `scene`. The metrics are
/// those of the matches whose label is known ([`KnownMetrics`]); when some
/// are `unknown`, the status says how many were not scored.
pub fn scene_result(
    scene: &Scene,
    segmentation: &Segmentation,
    gt_models: &[Matrix3<f64>],
) -> Result<SceneResult> {
    let known = match &scene.labels {
        Some(gt) => Some(KnownMetrics::compute(&segmentation.labels, gt)?),
        None => None,
    };
    let metrics = known.and_then(|k| k.metrics);
    let mut status = match &segmentation.degenerate {
        Some(reason) => reason.clone(),
        None if segmentation.consensus_fallback => "ok (focal filter kept all)".to_string(),
        None => "ok".to_string(),
    };
    if let Some(k) = known.filter(|k| k.unknown > 0) {
        status += &format!(
            "; {} of {} labels unknown, not scored",
            k.unknown,
            scene.len()
        );
    }
    let mut row = SceneResult {
        scene: scene.name.clone(),
        n: scene.len(),
        frob: frob_score(&segmentation.cluster_fundamentals(), gt_models),
        gt_motions: scene.labels.as_ref().map(|_| scene.num_motions()),
        gt_outliers: scene.labels.as_ref().map(|_| scene.num_outliers()),
        motions: segmentation.clusters.len(),
        outliers: segmentation.labels.iter().filter(|&&l| l < 0).count(),
        focal_verdict: segmentation.focal_verdict.name().to_string(),
        status,
        ..SceneResult::default()
    };
    if let Some(m) = &metrics {
        row.set_metrics(m);
    }
    row.set_hypotheses(&segmentation.counts);
    row.set_focal(segmentation.f_peak(), scene.true_focal);
    Ok(row)
}

/// Runs Algorithm 1 on in-memory scenes and scores each segmentation.
///
/// Steps 1–3 (the hypotheses) and step 4 (their focal lengths) of a scene
/// are computed once for every combination that shares their parameters
/// (e.g. both methods, or every `tau_range` of a sweep) and reused from a
/// small cache of the most recent ones; the reused stages keep the times
/// they took when computed in `timings.csv`. The results are those of
/// [`crate::pipeline::segment`].
pub struct PipelineEvaluator {
    scenes: Vec<Scene>,
    gt_models: Vec<Vec<Matrix3<f64>>>,
    hypotheses: StageCache<HypothesesOf, GeneratedHypotheses>,
    focals: StageCache<FocalsOf, HypothesisFocals>,
}

/// How many results of a stage [`PipelineEvaluator`] keeps.
const STAGE_CACHE_ENTRIES: usize = 8;

/// Steps 1–3 of scene `.0` with parameters `.1`.
type HypothesesOf = (usize, HypothesisKey);
/// Step 4 on those hypotheses with the solver parameters and focal file.
type FocalsOf = (HypothesesOf, FocalKey, String);

/// The most recent results of a pipeline stage by key (scene and
/// parameters), oldest dropped first.
struct StageCache<K, T> {
    entries: Mutex<VecDeque<(K, Arc<T>)>>,
}

impl<K: PartialEq, T> StageCache<K, T> {
    fn new() -> Self {
        Self {
            entries: Mutex::new(VecDeque::new()),
        }
    }

    /// The cached value of `key`, or `compute`'s (then cached). Two callers
    /// may compute the same key at once; both get equal values.
    fn get_or_compute<E>(
        &self,
        key: K,
        compute: impl FnOnce() -> Result<T, E>,
    ) -> Result<Arc<T>, E> {
        let cached = {
            let entries = self.entries.lock().expect("stage cache lock");
            entries
                .iter()
                .find(|(k, _)| *k == key)
                .map(|(_, v)| Arc::clone(v))
        };
        if let Some(value) = cached {
            return Ok(value);
        }
        let value = Arc::new(compute()?);
        let mut entries = self.entries.lock().expect("stage cache lock");
        if !entries.iter().any(|(k, _)| *k == key) {
            if entries.len() == STAGE_CACHE_ENTRIES {
                entries.pop_front();
            }
            entries.push_back((key, Arc::clone(&value)));
        }
        Ok(value)
    }
}

impl PipelineEvaluator {
    /// Prepares the scenes (and the ground-truth fits FROB compares with),
    /// and prints the library's warnings about each scene's input once
    /// ([`segmentation::check_matches`]: points far outside the image, a
    /// transposed image size); a scene it refuses fails when segmented,
    /// with the same message.
    pub fn new(scenes: Vec<Scene>) -> Self {
        for scene in &scenes {
            if let Ok(warnings) = segmentation::check_matches(&crate::pipeline::matches(scene)) {
                for warning in warnings {
                    eprintln!("warning: scene {}: {warning}", scene.name);
                }
            }
        }
        let gt_models = scenes.iter().map(ground_truth_models).collect();
        Self {
            scenes,
            gt_models,
            hypotheses: StageCache::new(),
            focals: StageCache::new(),
        }
    }

    /// [`crate::pipeline::segment`] of scene `index`, with steps 1–4 from
    /// the cache when another combination already computed them.
    pub fn segment(
        &self,
        index: usize,
        pipeline: &PipelineConfig,
    ) -> Result<Segmentation, PipelineError> {
        let scene = &self.scenes[index];
        let key = (index, pipeline.params().hypothesis_key());
        let generated = self
            .hypotheses
            .get_or_compute(key.clone(), || generate_hypotheses(scene, pipeline))?;
        let focals = match pipeline.params.focal.method {
            Method::Semical => Some(self.focals.get_or_compute::<PipelineError>(
                (
                    key,
                    pipeline.params().focal_key(),
                    pipeline.focal_file.clone(),
                ),
                || estimate_hypothesis_focals(scene, pipeline, &generated),
            )?),
            Method::Baseline => None,
        };
        segment_with(scene, pipeline, &generated, focals.as_deref())
    }

    /// The scenes.
    pub fn scenes(&self) -> &[Scene] {
        &self.scenes
    }
}

impl Evaluator for PipelineEvaluator {
    fn scene_names(&self) -> Vec<String> {
        self.scenes.iter().map(|s| s.name.clone()).collect()
    }

    fn evaluate(
        &self,
        index: usize,
        pipeline: &PipelineConfig,
        plots: Option<&ScenePlots>,
    ) -> Result<(SceneResult, StageTimings)> {
        let scene = &self.scenes[index];
        let segmentation = match self.segment(index, pipeline) {
            Ok(s) => s,
            // Refused (memory bound, bad coordinates, focal file): a row
            // without metrics that says why, left out of the means.
            Err(err) => {
                return Ok((
                    SceneResult::failed(scene, &err.reason()),
                    StageTimings::default(),
                ))
            }
        };
        let result = scene_result(scene, &segmentation, &self.gt_models[index])?;
        if let Some(plots) = plots {
            draw_scene_plots(scene, &segmentation, pipeline, plots)?;
        }
        Ok((result, segmentation.timings))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pipeline::segment;

    /// Everything but the timings.
    fn without_timings(mut s: Segmentation) -> Segmentation {
        s.timings = StageTimings::default();
        s
    }

    /// The cached stages give exactly the segmentation of a fresh run, for
    /// every combination sharing them, in any order, and after eviction.
    #[test]
    fn shared_stages_give_the_segmentation_of_a_fresh_run() {
        let params = datasets::synthetic::SyntheticParams::default();
        let scenes: Vec<Scene> = (0..2)
            .map(|k| {
                datasets::synthetic::generate_scene(&params, 7 + k, 2, &format!("s{k}")).unwrap()
            })
            .collect();
        let evaluator = PipelineEvaluator::new(scenes.clone());
        let mut configs = Vec::new();
        for method in [Method::Semical, Method::Baseline] {
            let variants = [
                (0.1, focal::OnFailure::Report),
                (0.3, focal::OnFailure::Report),
                (0.3, focal::OnFailure::Prior),
            ];
            for (tau_range, focal_failure) in variants {
                for num_samples in [150, 200] {
                    configs.push(PipelineConfig::from_params(
                        segmentation::Params::default().with(|q| {
                            q.focal.method = method;
                            q.focal.tau_range = tau_range;
                            q.reference_code.focal_failure = focal_failure;
                            q.sampling.num_samples = num_samples;
                        }),
                    ));
                }
            }
        }
        // More keys than the cache holds: some are evicted and recomputed.
        for round in 0..2 {
            for (index, scene) in scenes.iter().enumerate() {
                for config in &configs {
                    let cached = evaluator.segment(index, config).unwrap();
                    let fresh = segment(scene, config).unwrap();
                    assert_eq!(
                        without_timings(cached),
                        without_timings(fresh),
                        "round {round}, scene {index}, {config:?}"
                    );
                }
            }
        }
        // The semical units of a scene shared their focal lengths: the cache
        // holds a value computed once per (scene, M).
        assert!(evaluator.focals.entries.lock().unwrap().len() <= STAGE_CACHE_ENTRIES);
    }
}

/// Scoring a file with `unknown` labels.
#[cfg(test)]
mod unknown_labels {
    use super::*;
    use segmentation::Segmentation;

    /// A segmentation of `n` points that calls every point an outlier.
    fn all_outliers(n: usize) -> Segmentation {
        Segmentation {
            labels: vec![-1; n],
            counts: Default::default(),
            hypotheses: Vec::new(),
            consensus: None,
            consensus_fallback: false,
            focal_verdict: Default::default(),
            clusters: Vec::new(),
            clusters_before_filter: 0,
            timings: segmentation::StageTimings::default(),
            degenerate: Some("no hypothesis".into()),
            warnings: Vec::new(),
        }
    }

    fn write_scene(dir: &std::path::Path, name: &str, rows: &[(usize, &str)]) -> Scene {
        let mut text = String::from("x1,y1,x2,y2,label\n");
        for &(i, label) in rows {
            let x = i as f64;
            text += &format!("{x},{},{},{},{label}\n", 2.0 * x, x + 3.0, 7.0 - x);
        }
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        datasets::user::load_csv(&path, Some((64, 48))).unwrap()
    }

    /// A file with unknown rows gives the metrics of the same file with
    /// those rows removed, for any prediction of the unknown rows, and the
    /// status counts them.
    #[test]
    fn unknown_rows_score_as_if_removed() {
        let dir = tempfile::tempdir().unwrap();
        let labels = [
            "1", "1", "unknown", "1", "2", "unknown", "2", "2", "0", "1", "unknown", "0",
        ];
        let predicted = [0, 0, 1, -1, 1, -1, 1, 0, -1, 0, 0, 1];
        let all: Vec<(usize, &str)> = labels.iter().copied().enumerate().collect();
        let known: Vec<(usize, &str)> = all.iter().copied().filter(|r| r.1 != "unknown").collect();
        let with_unknown = write_scene(dir.path(), "with.csv", &all);
        let without = write_scene(dir.path(), "without.csv", &known);
        let mut seg = all_outliers(all.len());
        seg.degenerate = None;
        seg.labels = predicted.to_vec();
        let mut seg_known = all_outliers(known.len());
        seg_known.degenerate = None;
        seg_known.labels = known.iter().map(|r| predicted[r.0]).collect();

        let a = scene_result(&with_unknown, &seg, &[]).unwrap();
        let b = scene_result(&without, &seg_known, &[]).unwrap();
        let scores = |r: &SceneResult| (r.me, r.me_all, r.acc, r.fnr, r.pur, r.ari, r.nmi);
        assert!(b.me.is_some_and(|me| me > 0.0) && b.me_all.is_some());
        assert_eq!(scores(&a), scores(&b));
        assert_eq!((a.gt_motions, a.gt_outliers), (b.gt_motions, b.gt_outliers));
        assert_eq!(a.status, "ok; 3 of 12 labels unknown, not scored");
        assert_eq!(b.status, "ok");
        // Every unknown row predicted otherwise: the same scores.
        seg.labels = predicted
            .iter()
            .enumerate()
            .map(|(i, &p)| if labels[i] == "unknown" { 7 - p } else { p })
            .collect();
        assert_eq!(
            scores(&scene_result(&with_unknown, &seg, &[]).unwrap()),
            scores(&b)
        );
    }
}

/// The examples once in the documentation of this module's items.
#[cfg(test)]
mod examples {
    #[test]
    fn motion_indices_example() {
        let motions = crate::evaluate::motion_indices(&[1, 0, 2, 1]);
        assert_eq!(motions[&1], vec![0, 3]);
        assert_eq!(motions[&2], vec![2]);
        assert_eq!(motions.len(), 2);
    }
}
