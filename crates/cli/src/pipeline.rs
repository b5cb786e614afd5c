//! Algorithm 1 on a dataset scene: the harness's glue to the
//! [`segmentation`] crate. A scene becomes [`segmentation::Matches`] (its
//! principal point and `max(W, H)` focal prior), each scene is sampled with
//! the seed [`scene_seed`]`(seed, name)`, and `focal_solver = "external"`
//! reads its answers from the config's focal file (the `focal_file` module).

use crate::config::{FocalSolver, Method, PipelineConfig};
use crate::focal_file;
pub use crate::focal_file::FocalFileError;
use datasets::Scene;
pub use segmentation::{
    fit_cluster, ClusterModel, GeneratedHypotheses, Hypothesis, HypothesisCounts, HypothesisFocals,
    HypothesisStatus, Matches, Segmentation, SegmentationError, StageTimings,
};
use std::time::Instant;
use thiserror::Error;

/// Why a scene could not be segmented at all.
#[derive(Debug, Error)]
pub enum PipelineError {
    /// The method refused the scene (parameters, too few or non-finite points).
    #[error("scene `{scene}`: {cause}")]
    Segmentation {
        /// Scene name.
        scene: String,
        /// Why.
        cause: SegmentationError,
    },
    /// The focal file of `focal_solver = "external"` is unusable or was made
    /// for other hypotheses.
    #[error("scene `{scene}`: focal file: {cause}")]
    FocalFile {
        /// Scene name.
        scene: String,
        /// What is wrong, naming the file, the line and the field.
        cause: FocalFileError,
    },
}

impl PipelineError {
    /// Why, without the scene name (the rows and lines that show it name
    /// the scene already).
    pub fn reason(&self) -> String {
        match self {
            Self::Segmentation { cause, .. } => cause.to_string(),
            Self::FocalFile { cause, .. } => format!("focal file: {cause}"),
        }
    }
}

/// FNV-1a, 64 bit: a hash of the scene name that is the same on every
/// platform and Rust version.
pub fn fnv1a64(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

/// The sampling seed of scene `scene` in a run with seed `seed`:
/// SplitMix64 of the seed xor the FNV-1a hash of the name, so that the
/// scenes of a run draw independent samples.
pub fn scene_seed(seed: u64, scene: &str) -> u64 {
    segmentation::splitmix64(seed) ^ fnv1a64(scene.as_bytes())
}

/// The scene as the method's input.
pub fn matches(scene: &Scene) -> Matches<'_> {
    Matches::new(&scene.points1, &scene.points2, scene.image_size)
        .with_principal_point(scene.principal_point)
        .with_focal_prior(scene.focal_prior())
}

fn scene_error(scene: &Scene) -> impl Fn(SegmentationError) -> PipelineError + '_ {
    |cause| PipelineError::Segmentation {
        scene: scene.name.clone(),
        cause,
    }
}

/// Steps 1–3 of Algorithm 1 on a scene ([`segmentation::generate_hypotheses`]),
/// after checking the whole config ([`PipelineConfig::validate`]), the
/// coordinates ([`segmentation::check_matches`]: one bound, the library's)
/// and the memory bound ([`segmentation::check_memory`]).
pub fn generate_hypotheses(
    scene: &Scene,
    config: &PipelineConfig,
) -> Result<GeneratedHypotheses, PipelineError> {
    config
        .validate()
        .map_err(|e| scene_error(scene)(SegmentationError::InvalidParam(e)))?;
    segmentation::check_matches(&matches(scene)).map_err(scene_error(scene))?;
    let params = config.scene_params(&scene.name);
    // Before sampling, as `segmentation::segment` does: a bound too small
    // for num_samples refuses the scene before any memory is taken.
    segmentation::check_memory(scene.len(), &params).map_err(scene_error(scene))?;
    segmentation::generate_hypotheses(&matches(scene), &params).map_err(scene_error(scene))
}

/// Step 4 of Algorithm 1 on a scene's hypotheses: the config's solver, or
/// for `focal_solver = "external"` the answers of its focal file.
pub fn estimate_hypothesis_focals(
    scene: &Scene,
    config: &PipelineConfig,
    hypotheses: &GeneratedHypotheses,
) -> Result<HypothesisFocals, PipelineError> {
    let params = config.scene_params(&scene.name);
    if config.params.focal.focal_solver != FocalSolver::External {
        return segmentation::estimate_hypothesis_focals(hypotheses, &params, scene.focal_prior())
            .map_err(scene_error(scene));
    }
    let t = Instant::now();
    let answers = external_answers(scene, config, hypotheses)?;
    let mut focals =
        HypothesisFocals::from_answers(&answers, hypotheses, &params, scene.focal_prior())
            .map_err(scene_error(scene))?;
    focals.seconds = t.elapsed().as_secs_f64();
    Ok(focals)
}

/// The answers of `config.focal_file` for every hypothesis with a model
/// (None for the others). Each such hypothesis must be in the file and,
/// when the file holds F, match it.
fn external_answers(
    scene: &Scene,
    config: &PipelineConfig,
    hypotheses: &GeneratedHypotheses,
) -> Result<Vec<Option<(f64, f64)>>, PipelineError> {
    let path = focal_file::focal_file_path(&config.focal_file, config.params.sampling.seed);
    let error = |cause: FocalFileError| PipelineError::FocalFile {
        scene: scene.name.clone(),
        cause,
    };
    let rows = focal_file::read_scene_focals(&path, &scene.name).map_err(error)?;
    let mut answers = Vec::with_capacity(hypotheses.models.len());
    for (j, model) in hypotheses.models.iter().enumerate() {
        let Some(f) = model else {
            answers.push(None);
            continue;
        };
        let row = rows.get(&j).ok_or_else(|| {
            error(FocalFileError::MissingHypothesis {
                file: path.clone(),
                hypothesis: j,
            })
        })?;
        if let Some(theirs) = &row.model {
            if !focal_file::same_model(f, theirs, 1e-6) {
                return Err(error(FocalFileError::OtherModel {
                    file: path.clone(),
                    hypothesis: j,
                }));
            }
        }
        answers.push(Some(row.focals));
    }
    Ok(answers)
}

/// Segments one scene by Algorithm 1 with `config`
/// ([`segmentation::segment`], external focals read from the focal file).
pub fn segment(scene: &Scene, config: &PipelineConfig) -> Result<Segmentation, PipelineError> {
    let started = Instant::now();
    let hypotheses = generate_hypotheses(scene, config)?;
    let focals = (config.params.focal.method == Method::Semical)
        .then(|| estimate_hypothesis_focals(scene, config, &hypotheses))
        .transpose()?;
    let mut segmentation = segment_with(scene, config, &hypotheses, focals.as_ref())?;
    segmentation.timings.total = started.elapsed().as_secs_f64();
    Ok(segmentation)
}

/// Steps 5–9 of Algorithm 1 on a scene's hypotheses and focals
/// ([`segmentation::segment_with`]).
pub fn segment_with(
    scene: &Scene,
    config: &PipelineConfig,
    generated: &GeneratedHypotheses,
    focals: Option<&HypothesisFocals>,
) -> Result<Segmentation, PipelineError> {
    let params = config.scene_params(&scene.name);
    segmentation::segment_with(&matches(scene), &params, generated, focals)
        .map_err(scene_error(scene))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fnv_matches_the_published_test_vectors() {
        assert_eq!(fnv1a64(b""), 0xcbf29ce484222325);
        assert_eq!(fnv1a64(b"a"), 0xaf63dc4c8601ec8c);
        assert_eq!(fnv1a64(b"foobar"), 0x85944171f73967e8);
    }

    fn scene_with(points1: Vec<[f64; 2]>) -> Scene {
        let points2 = points1.clone();
        Scene {
            name: "s".into(),
            points1,
            points2,
            image_size: (100, 50),
            principal_point: [49.5, 24.5],
            labels: None,
            true_focal: None,
            gt_fundamentals: Vec::new(),
            images: None,
        }
    }

    #[test]
    fn coordinates_are_checked_by_the_library_before_sampling() {
        // The library's bound (segmentation::MAX_COORDINATE_PX), named with
        // the scene, the row and the column.
        let mut points = vec![[50.0, 20.0]; 20];
        points[3] = [50.0, 1e7];
        let err = generate_hypotheses(&scene_with(points), &PipelineConfig::default()).unwrap_err();
        assert!(
            matches!(
                &err,
                PipelineError::Segmentation {
                    cause: SegmentationError::InvalidCoordinate {
                        row: 3,
                        column: "y1",
                        ..
                    },
                    ..
                }
            ),
            "{err}"
        );
        assert!(
            err.to_string()
                .starts_with("scene `s`: match row 3, column y1"),
            "{err}"
        );
    }

    #[test]
    fn scenes_of_a_run_draw_different_samples() {
        assert_ne!(scene_seed(1, "x"), scene_seed(1, "y"));
        assert_ne!(scene_seed(1, "x"), scene_seed(2, "x"));
    }
}
