//! Which hypotheses the focal filter keeps and discards, judged against the
//! ground truth: a hypothesis is a *good model* of a motion when its
//! inliers (squared Sampson distance below `thr_px²`, Eq. 38's preference
//! rule) are mostly that motion's points and cover most of them.

use crate::config::{Method, PipelineConfig};
use crate::pipeline::{
    estimate_hypothesis_focals, generate_hypotheses, segment_with, HypothesisStatus, PipelineError,
};
use datasets::Scene;
use geometry::sampson_distances_squared;

/// A hypothesis is a good model when at least this fraction of its inliers
/// belong to one ground-truth motion …
pub const GOOD_PRECISION: f64 = 0.8;
/// … and its inliers include at least this fraction of that motion's points.
pub const GOOD_RECALL: f64 = 0.5;

/// Whether the inlier set `inliers` (indices) is a good model of a motion of
/// `labels` (ground truth: 0 = outlier, k > 0 = motion k): its majority
/// motion holds at least [`GOOD_PRECISION`] of the inliers and the inliers
/// cover at least [`GOOD_RECALL`] of that motion.
pub fn is_good_model(inliers: &[usize], labels: &[i32]) -> bool {
    let motions = labels.iter().copied().max().unwrap_or(0).max(0) as usize;
    let mut counts = vec![0usize; motions + 1];
    for &i in inliers {
        if labels[i] > 0 {
            counts[labels[i] as usize] += 1;
        }
    }
    let Some((motion, &hits)) = counts.iter().enumerate().skip(1).max_by_key(|(_, &c)| c) else {
        return false;
    };
    let size = labels.iter().filter(|&&l| l == motion as i32).count();
    hits > 0
        && hits as f64 >= GOOD_PRECISION * inliers.len() as f64
        && hits as f64 >= GOOD_RECALL * size as f64
}

/// What the focal filter of one scene did, in hypothesis counts.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct FilterQuality {
    /// Hypotheses with a model after step 3.
    pub refined: usize,
    /// Of those, good models.
    pub good_refined: usize,
    /// Hypotheses the filter kept.
    pub kept: usize,
    /// Good models among them.
    pub good_kept: usize,
    /// Hypotheses the filter discarded (failed solve, local test, band).
    pub discarded: usize,
    /// Good models among them.
    pub good_discarded: usize,
}

/// Runs steps 1–6 of semical with `config` on a scene with ground truth and
/// counts the good models the focal filter kept and discarded. `None` when
/// the scene has no ground-truth labels.
pub fn filter_quality(
    scene: &Scene,
    config: &PipelineConfig,
) -> Result<Option<FilterQuality>, PipelineError> {
    let Some(labels) = &scene.labels else {
        return Ok(None);
    };
    let mut config = config.clone();
    config.params.focal.method = Method::Semical;
    let generated = generate_hypotheses(scene, &config)?;
    let focals = estimate_hypothesis_focals(scene, &config, &generated)?;
    let segmentation = segment_with(scene, &config, &generated, Some(&focals))?;
    let tau = config.params.refinement.thr_px * config.params.refinement.thr_px;
    let mut residuals = vec![0.0; scene.len()];
    let mut inliers = Vec::new();
    let mut q = FilterQuality::default();
    for (model, hypothesis) in generated.models.iter().zip(&segmentation.hypotheses) {
        let Some(f) = model else { continue };
        sampson_distances_squared(f, &generated.points, &mut residuals);
        inliers.clear();
        inliers.extend((0..residuals.len()).filter(|&i| residuals[i] < tau));
        let good = usize::from(is_good_model(&inliers, labels));
        q.refined += 1;
        q.good_refined += good;
        if hypothesis.status == HypothesisStatus::Kept {
            q.kept += 1;
            q.good_kept += good;
        } else {
            q.discarded += 1;
            q.good_discarded += good;
        }
    }
    Ok(Some(q))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_add_up_and_ground_truth_models_are_good() {
        let params = datasets::synthetic::SyntheticParams::default();
        let scene = datasets::synthetic::generate_scene(&params, 3, 2, "q").unwrap();
        let config = PipelineConfig::from_params(
            segmentation::Params::thesis().with(|q| q.sampling.num_samples = 300),
        );
        let q = filter_quality(&scene, &config).unwrap().unwrap();
        assert_eq!(q.kept + q.discarded, q.refined);
        assert_eq!(q.good_kept + q.good_discarded, q.good_refined);
        assert!(q.good_refined > 0 && q.good_refined < q.refined, "{q:?}");
        // The F fitted to all of a motion's points is a good model of it.
        let labels = scene.labels.as_ref().unwrap();
        let points = geometry::Correspondences::new(&scene.points1, &scene.points2)
            .unwrap()
            .shifted(scene.principal_point, scene.principal_point);
        for motion in 1..=2 {
            let idx: Vec<usize> = (0..labels.len()).filter(|&i| labels[i] == motion).collect();
            let f = crate::pipeline::fit_cluster(&points, &idx).unwrap();
            let mut r = vec![0.0; scene.len()];
            sampson_distances_squared(&f, &points, &mut r);
            let tau = config.params.refinement.thr_px * config.params.refinement.thr_px;
            let inliers: Vec<usize> = (0..r.len()).filter(|&i| r[i] < tau).collect();
            assert!(is_good_model(&inliers, labels), "motion {motion}");
        }
    }
}

/// The examples once in the documentation of this module's items.
#[cfg(test)]
mod examples {
    #[test]
    fn is_good_model_example() {
        use crate::quality::is_good_model;
        let labels = [1, 1, 1, 1, 2, 2, 0, 0];
        assert!(is_good_model(&[0, 1, 2], &labels)); // 3 of motion 1's 4 points
        assert!(!is_good_model(&[0, 4, 5, 6], &labels)); // a mix
        assert!(!is_good_model(&[6, 7], &labels)); // outliers only
    }
}
