//! Algorithm 1 of the thesis end to end for one scene (method.md steps 1–9):
//! sampling → 8-point → IRLS-Tukey → focal estimation → local test (Eq. 36)
//! → KDE focal consensus and band (Eq. 37) → preferences (Eq. 38) →
//! T-Linkage (Eqs. 39–40) or J-Linkage → size filter.
//!
//! Hypotheses are generated in parallel (rayon, in the caller's thread pool);
//! hypothesis `j` of scene `s` draws its sample from its own ChaCha8 stream
//! `j` under a key derived from `(seed, s)` ([`hypothesis_rng`]), so the
//! labels are the same for any number of threads and any scene order.
//!
//! All geometry runs in principal-point-centred pixel coordinates (method.md
//! "Input"): every F of a [`Segmentation`] satisfies `x2ᵀ F x1 = 0` for
//! `x = (x − pp, y − pp_y, 1)`.

use crate::config::{EightPoint, FocalSolver, LocalTest, Method, PipelineConfig};
use crate::focal_file;
use crate::output::{HypothesisCounts, StageTimings};
use clustering::{ClusteringError, ClusteringParams};
use datasets::Scene;
use focal::{ConsensusParams, FocalConsensus, FocalWeights, OnFailure};
use geometry::{
    eight_point_normalized, eight_point_plain, sampson_distances_squared, Correspondences,
    GeometryError, IrlsParams, IrlsWorkspace,
};
use nalgebra::Matrix3;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use std::time::Instant;
use thiserror::Error;

/// Why a scene could not be segmented at all.
#[derive(Debug, Error)]
pub enum PipelineError {
    /// A parameter is out of range.
    #[error("invalid parameter `{key}`: {message}")]
    InvalidConfig {
        /// The [`PipelineConfig`] field.
        key: &'static str,
        /// What is wrong.
        message: String,
    },
    /// Fewer correspondences than one minimal sample.
    #[error("scene `{scene}`: {n} correspondences, a minimal sample needs {needed}")]
    TooFewPoints {
        /// Scene name.
        scene: String,
        /// Correspondences in the scene.
        n: usize,
        /// `mss_size`.
        needed: usize,
    },
    /// The correspondences are unusable (length mismatch, NaN).
    #[error("scene `{scene}`: {source}")]
    InvalidInput {
        /// Scene name.
        scene: String,
        /// The geometry error.
        source: GeometryError,
    },
    /// The focal file of `focal_solver = "external"` is unusable or was made
    /// for other hypotheses.
    #[error("scene `{scene}`: focal file: {message}")]
    FocalFile {
        /// Scene name.
        scene: String,
        /// What is wrong, naming the file, the line and the field.
        message: String,
    },
    /// The clustering rejected its input.
    #[error("scene `{scene}`: clustering: {source}")]
    Clustering {
        /// Scene name.
        scene: String,
        /// The clustering error.
        source: ClusteringError,
    },
}

/// What happened to one hypothesis (Algorithm 1 steps 2–6).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum HypothesisStatus {
    /// The 8-point fit of the minimal sample failed (degenerate sample).
    Degenerate,
    /// IRLS-Tukey dropped it: fewer than 8 inliers or a non-finite F (step 3).
    RefineFailed,
    /// The focal solver gave no answer (step 4).
    FocalFailed,
    /// It failed the local test (Eq. 36, or `f_avg <= 0` for the
    /// reference-code variant).
    LocalTestFailed,
    /// Its `f_avg` lies outside the band around f_peak (Eq. 37).
    OutsideBand,
    /// It reached the clustering.
    Kept,
}

impl HypothesisStatus {
    /// A short lowercase name.
    pub fn name(self) -> &'static str {
        match self {
            Self::Degenerate => "degenerate",
            Self::RefineFailed => "refine-failed",
            Self::FocalFailed => "focal-failed",
            Self::LocalTestFailed => "local-test-failed",
            Self::OutsideBand => "outside-band",
            Self::Kept => "kept",
        }
    }
}

/// One hypothesis of a segmentation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hypothesis {
    /// Its fate.
    pub status: HypothesisStatus,
    /// Focal lengths of image 1 and image 2 (px) when estimated (step 4).
    pub focals: Option<(f64, f64)>,
}

/// A final cluster: its label, its size and the 8-point F of its points.
#[derive(Debug, Clone, PartialEq)]
pub struct ClusterModel {
    /// The label (0, 1, …) in [`Segmentation::labels`].
    pub label: i32,
    /// Number of points.
    pub size: usize,
    /// Hartley-normalised 8-point F of its points (centred coordinates);
    /// None when the fit is degenerate.
    pub f: Option<Matrix3<f64>>,
}

/// The output of [`segment`]: labels and what the reports and plots need.
#[derive(Debug, Clone, PartialEq)]
pub struct Segmentation {
    /// One label per correspondence: 0, 1, … for the clusters, −1 for outliers.
    pub labels: Vec<i32>,
    /// Hypotheses generated / refined / passing the local test / kept.
    pub counts: HypothesisCounts,
    /// Every generated hypothesis in index order.
    pub hypotheses: Vec<Hypothesis>,
    /// The KDE focal consensus (Eq. 37) when it was computed.
    pub consensus: Option<FocalConsensus>,
    /// True when the focal filter kept every refined hypothesis because
    /// nothing passed the local test or nothing fell in the band (step 6).
    pub consensus_fallback: bool,
    /// The clusters kept after the size filter, by label.
    pub clusters: Vec<ClusterModel>,
    /// Clusters before the size filter (step 9).
    pub clusters_before_filter: usize,
    /// Wall time of each stage.
    pub timings: StageTimings,
    /// `None`, or why every point is an outlier.
    pub degenerate: Option<String>,
}

impl Segmentation {
    /// f_peak of the focal consensus, when computed.
    pub fn f_peak(&self) -> Option<f64> {
        self.consensus.as_ref().map(|c| c.f_peak)
    }

    /// The 8-point F of each final cluster that has one (centred coordinates).
    pub fn cluster_fundamentals(&self) -> Vec<Matrix3<f64>> {
        self.clusters.iter().filter_map(|c| c.f).collect()
    }
}

/// FNV-1a, 64 bit: a hash of the scene name that is the same on every
/// platform and Rust version.
pub fn fnv1a64(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

/// SplitMix64's output function: a bijective mix of 64 bits.
pub fn splitmix64(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// The RNG of hypothesis `index` of scene `scene` (Algorithm 1 step 1): a
/// ChaCha8 key from SplitMix64 over `seed` and the FNV-1a hash of the scene
/// name, and stream number `index`.
///
/// ```
/// use rand::Rng;
/// let mut a = bench::pipeline::hypothesis_rng(12345, "biscuit", 7);
/// let mut b = bench::pipeline::hypothesis_rng(12345, "biscuit", 7);
/// let mut c = bench::pipeline::hypothesis_rng(12345, "biscuit", 8);
/// let (x, y, z): (u64, u64, u64) = (a.gen(), b.gen(), c.gen());
/// assert_eq!(x, y);
/// assert_ne!(x, z);
/// ```
pub fn hypothesis_rng(seed: u64, scene: &str, index: usize) -> ChaCha8Rng {
    let mut state = splitmix64(seed) ^ fnv1a64(scene.as_bytes());
    let mut key = [0u8; 32];
    for chunk in key.chunks_exact_mut(8) {
        state = splitmix64(state);
        chunk.copy_from_slice(&state.to_le_bytes());
    }
    let mut rng = ChaCha8Rng::from_seed(key);
    rng.set_stream(index as u64);
    rng
}

/// The minimal sample of hypothesis `index`: `mss_size` distinct indices
/// drawn uniformly from `0..n` (Algorithm 1 step 1).
pub fn minimal_sample(
    seed: u64,
    scene: &str,
    index: usize,
    n: usize,
    mss_size: usize,
) -> Vec<usize> {
    let mut rng = hypothesis_rng(seed, scene, index);
    rand::seq::index::sample(&mut rng, n, mss_size).into_vec()
}

/// `f_avg = (f1 + f2) / 2` (Eq. 36).
fn f_avg((f1, f2): (f64, f64)) -> f64 {
    0.5 * (f1 + f2)
}

/// `(f1, f2)` of one hypothesis and whether they are the prior.
type FocalAnswer = ((f64, f64), bool);

/// `(f1, f2)` as the pipeline uses them: truncated to integers when
/// `truncate_focals` (the reference code), else unchanged.
fn focals_as_used(focals: (f64, f64), config: &PipelineConfig) -> (f64, f64) {
    if config.truncate_focals {
        (focals.0.trunc(), focals.1.trunc())
    } else {
        focals
    }
}

/// Focal lengths of one hypothesis (step 4), principal points at the origin;
/// `weight_sets` are the multi-start weights of the robust solver. The flag
/// is true when the focals are the prior standing in for a failed solve.
fn estimate_focals(
    f: &Matrix3<f64>,
    config: &PipelineConfig,
    weight_sets: &[FocalWeights],
    f_prior: f64,
) -> Option<FocalAnswer> {
    let (focals, from_prior) = match config.focal_solver {
        FocalSolver::Kocur => focal::robust_focals_multi_start(
            f,
            f_prior,
            weight_sets,
            config.max_iters,
            config.focal_failure,
        )
        .ok()
        .map(|e| ((e.f1, e.f2), e.from_prior)),
        FocalSolver::Bougnoux => match focal::bougnoux(f, [0.0, 0.0], [0.0, 0.0]) {
            Ok(pair) => Some((pair, false)),
            Err(_) if config.focal_failure == OnFailure::Prior => Some(((f_prior, f_prior), true)),
            Err(_) => None,
        },
        // Read for all hypotheses at once by `external_focals`.
        FocalSolver::External => None,
    }?;
    Some((focals_as_used(focals, config), from_prior))
}

/// The focal filter of steps 5–6 over the refined hypotheses (`refined[k]`
/// indexes `hypotheses`): sets every refined hypothesis's status and returns
/// the consensus, whether the filter fell back to keeping all, and the
/// number that passed the local test.
fn focal_filter(
    hypotheses: &mut [Hypothesis],
    refined: &[usize],
    config: &PipelineConfig,
) -> (Option<FocalConsensus>, bool, usize) {
    let reference = config.local_test == LocalTest::ReferenceCode;
    let mut local_ok = Vec::new();
    let mut pool = Vec::new();
    for &j in refined {
        let h = &mut hypotheses[j];
        let Some(focals) = h.focals else {
            h.status = HypothesisStatus::FocalFailed;
            continue;
        };
        let passes = focal::passes_local_test(focals.0, focals.1, config.tau_diff);
        if passes {
            local_ok.push(j);
        }
        if passes || (reference && f_avg(focals) > 0.0) {
            pool.push(j);
        } else {
            h.status = HypothesisStatus::LocalTestFailed;
        }
    }
    let values: Vec<f64> = local_ok
        .iter()
        .map(|&j| f_avg(hypotheses[j].focals.expect("local test passed")))
        .collect();
    let consensus = focal::focal_consensus(&values, &ConsensusParams::default());
    let mut kept = 0;
    if let Some(c) = &consensus {
        for &j in &pool {
            let inside = focal::within_band(
                f_avg(hypotheses[j].focals.expect("pooled")),
                c.f_peak,
                config.tau_range,
            );
            hypotheses[j].status = if inside {
                kept += 1;
                HypothesisStatus::Kept
            } else {
                HypothesisStatus::OutsideBand
            };
        }
    }
    let fallback = kept == 0;
    if fallback {
        for &j in refined {
            hypotheses[j].status = HypothesisStatus::Kept;
        }
    }
    (consensus, fallback, local_ok.len())
}

fn seconds_since(t: Instant) -> f64 {
    t.elapsed().as_secs_f64()
}

/// Steps 1–3 of Algorithm 1 for one scene: every minimal sample, its
/// 8-point fit and (unless `refine` is off) its IRLS-Tukey refinement. These
/// depend only on the scene and on `seed`, `num_samples`, `mss_size`,
/// `eight_point`, `refine`, `thr_px` and `irls_iters`
/// ([`hypothesis_key`]), so one set serves every combination of a sweep
/// that shares them.
#[derive(Debug, Clone, PartialEq)]
pub struct GeneratedHypotheses {
    /// The correspondences in principal-point-centred coordinates.
    pub points: Correspondences,
    /// Whether hypothesis `j`'s minimal sample gave an 8-point fit.
    pub fitted: Vec<bool>,
    /// The model of hypothesis `j` (refined, or the raw fit when `refine`
    /// is off); None when the fit or the refinement failed.
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

/// The parameters [`generate_hypotheses`] depends on, as a string: two
/// configurations with the same key give the same hypotheses on a scene.
pub fn hypothesis_key(config: &PipelineConfig) -> String {
    format!(
        "seed={} M={} mss={} eight_point={:?} refine={} thr_px={:e} irls_iters={}",
        config.seed,
        config.num_samples,
        config.mss_size,
        config.eight_point,
        config.refine,
        config.thr_px,
        config.irls_iters
    )
}

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

/// The parameters [`estimate_hypothesis_focals`] depends on besides the
/// hypotheses ([`hypothesis_key`]) and the scene's focal prior.
pub fn focal_key(config: &PipelineConfig) -> String {
    format!(
        "solver={:?} file={:?} weights={:?} max_iters={} failure={:?} truncate={}",
        config.focal_solver,
        config.focal_file,
        config.weight_sets.sets(),
        config.max_iters,
        config.focal_failure,
        config.truncate_focals
    )
}

/// Steps 1–3 of Algorithm 1 (see [`GeneratedHypotheses`]).
///
/// Errors on invalid parameters, fewer points than `mss_size` and
/// non-finite coordinates.
pub fn generate_hypotheses(
    scene: &Scene,
    config: &PipelineConfig,
) -> Result<GeneratedHypotheses, PipelineError> {
    config
        .validate()
        .map_err(|(key, message)| PipelineError::InvalidConfig { key, message })?;
    let name = scene.name.as_str();
    let points = Correspondences::new(&scene.points1, &scene.points2)
        .map_err(|source| PipelineError::InvalidInput {
            scene: name.to_string(),
            source,
        })?
        .shifted(scene.principal_point, scene.principal_point);
    let n = points.len();
    if n < config.mss_size {
        return Err(PipelineError::TooFewPoints {
            scene: name.to_string(),
            n,
            needed: config.mss_size,
        });
    }
    let m = config.num_samples;

    // Steps 1–2: minimal samples and their 8-point fits.
    let t = Instant::now();
    let fits: Vec<Option<(Vec<usize>, Matrix3<f64>)>> = (0..m)
        .into_par_iter()
        .map(|j| {
            let sample = minimal_sample(config.seed, name, j, n, config.mss_size);
            let subset = points.subset(&sample).ok()?;
            let f = match config.eight_point {
                EightPoint::Normalized => eight_point_normalized(&subset),
                EightPoint::Plain => eight_point_plain(&subset),
            }
            .ok()?;
            f.iter().all(|v| v.is_finite()).then_some((sample, f))
        })
        .collect();
    let sampling_seconds = seconds_since(t);

    // Step 3: IRLS-Tukey (or the raw minimal-sample F).
    let t = Instant::now();
    let irls = IrlsParams {
        thr_px: config.thr_px,
        max_iters: config.irls_iters,
        ..IrlsParams::default()
    };
    let models: Vec<Option<Matrix3<f64>>> = if config.refine {
        fits.par_iter()
            .map_init(IrlsWorkspace::new, |ws, fit| {
                let (sample, f) = fit.as_ref()?;
                let refined = ws.run(&points, sample, Some(f), &irls).ok()?;
                Some(refined.f)
            })
            .collect()
    } else {
        fits.iter()
            .map(|fit| fit.as_ref().map(|(_, f)| *f))
            .collect()
    };
    let refine_seconds = seconds_since(t);
    Ok(GeneratedHypotheses {
        points,
        fitted: fits.iter().map(Option::is_some).collect(),
        models,
        sampling_seconds,
        refine_seconds,
    })
}

/// Step 4 of Algorithm 1: the focal lengths of every hypothesis with a
/// model, in parallel, with the scene's focal prior and `config`'s solver
/// ([`focal_key`]).
///
/// Errors only for `focal_solver = "external"`: an unusable focal file, a
/// hypothesis missing from it, or one whose F differs from the file's
/// ([`PipelineError::FocalFile`]).
pub fn estimate_hypothesis_focals(
    scene: &Scene,
    config: &PipelineConfig,
    hypotheses: &GeneratedHypotheses,
) -> Result<HypothesisFocals, PipelineError> {
    let t = Instant::now();
    let f_prior = scene.focal_prior();
    let estimates: Vec<Option<FocalAnswer>> = match config.focal_solver {
        FocalSolver::External => external_focals(scene, config, hypotheses)?,
        _ => {
            let weight_sets = config.weight_sets.sets();
            hypotheses
                .models
                .par_iter()
                .map(|model| {
                    let f = model.as_ref()?;
                    estimate_focals(f, config, &weight_sets, f_prior)
                })
                .collect()
        }
    };
    Ok(HypothesisFocals {
        focals: estimates.iter().map(|e| e.map(|(f, _)| f)).collect(),
        from_prior: estimates
            .iter()
            .map(|e| e.is_some_and(|(_, p)| p))
            .collect(),
        seconds: seconds_since(t),
    })
}

/// The focals of every hypothesis with a model from `config.focal_file`
/// (see [`crate::focal_file`]): as given, truncated when `truncate_focals`,
/// none when not finite; an answer equal to the prior counts as a prior
/// answer. Each hypothesis must be in the file and, when the file holds F,
/// match it.
fn external_focals(
    scene: &Scene,
    config: &PipelineConfig,
    hypotheses: &GeneratedHypotheses,
) -> Result<Vec<Option<FocalAnswer>>, PipelineError> {
    let path = focal_file::focal_file_path(&config.focal_file, config.seed);
    let error = |message: String| PipelineError::FocalFile {
        scene: scene.name.clone(),
        message,
    };
    let rows = focal_file::read_scene_focals(&path, &scene.name).map_err(error)?;
    let f_prior = scene.focal_prior();
    let mut estimates = Vec::with_capacity(hypotheses.models.len());
    for (j, model) in hypotheses.models.iter().enumerate() {
        let Some(f) = model else {
            estimates.push(None);
            continue;
        };
        let row = rows.get(&j).ok_or_else(|| {
            error(format!(
                "{}: no row for hypothesis {j} (write the hypotheses of this config with `sctl hypotheses`)",
                path.display()
            ))
        })?;
        if let Some(theirs) = &row.model {
            if !focal_file::same_model(f, theirs, 1e-6) {
                return Err(error(format!(
                    "{}: hypothesis {j} has another F than this config generates \
                     (the file was made for other hypotheses: seed, M, thr_px, ...?)",
                    path.display()
                )));
            }
        }
        let focals = focals_as_used(row.focals, config);
        let finite = focals.0.is_finite() && focals.1.is_finite();
        estimates.push(finite.then_some((focals, focals == (f_prior, f_prior))));
    }
    Ok(estimates)
}

/// Segments one scene by Algorithm 1 (method.md steps 1–9) with `config`.
///
/// Errors only on input that admits no hypothesis at all (invalid
/// parameters, fewer points than `mss_size`, non-finite coordinates). When
/// every hypothesis is rejected the result is an all-outlier segmentation
/// whose [`Segmentation::degenerate`] says why.
///
/// ```
/// use bench::config::{Method, PipelineConfig};
/// let scene = datasets::synthetic::generate_scene(
///     &datasets::synthetic::SyntheticParams::default(), 3, 2, "demo").unwrap();
/// let config = PipelineConfig { num_samples: 300, method: Method::Baseline, ..Default::default() };
/// let seg = bench::pipeline::segment(&scene, &config).unwrap();
/// assert_eq!(seg.labels.len(), scene.len());
/// assert_eq!(seg.counts.generated, 300);
/// assert!(seg.clusters.len() >= 1);
/// ```
pub fn segment(scene: &Scene, config: &PipelineConfig) -> Result<Segmentation, PipelineError> {
    let started = Instant::now();
    let hypotheses = generate_hypotheses(scene, config)?;
    let focals = (config.method == Method::Semical)
        .then(|| estimate_hypothesis_focals(scene, config, &hypotheses))
        .transpose()?;
    let mut segmentation = segment_with(scene, config, &hypotheses, focals.as_ref())?;
    segmentation.timings.total = seconds_since(started);
    Ok(segmentation)
}

/// Steps 5–9 of Algorithm 1 on hypotheses generated for this scene with
/// this `config` ([`generate_hypotheses`]) and, for semical, their focal
/// lengths ([`estimate_hypothesis_focals`]); the stage timings of those
/// steps are copied from them. The result is that of [`segment`].
///
/// Errors when `focals` is missing for semical or the hypotheses do not
/// belong to the scene, and as [`segment`].
pub fn segment_with(
    scene: &Scene,
    config: &PipelineConfig,
    generated: &GeneratedHypotheses,
    focals: Option<&HypothesisFocals>,
) -> Result<Segmentation, PipelineError> {
    let started = Instant::now();
    config
        .validate()
        .map_err(|(key, message)| PipelineError::InvalidConfig { key, message })?;
    let name = scene.name.as_str();
    let points = &generated.points;
    let n = points.len();
    let m = generated.models.len();
    if n != scene.len() || m != config.num_samples {
        return Err(PipelineError::InvalidConfig {
            key: "num_samples",
            message: format!(
                "scene `{name}`: hypotheses generated for {n} points and M = {m}, not {} and {}",
                scene.len(),
                config.num_samples
            ),
        });
    }
    let models = &generated.models;
    let mut timings = StageTimings {
        sampling: generated.sampling_seconds,
        refine: generated.refine_seconds,
        ..StageTimings::default()
    };

    let mut hypotheses: Vec<Hypothesis> = generated
        .fitted
        .iter()
        .zip(models)
        .map(|(&fitted, model)| Hypothesis {
            status: match (fitted, model) {
                (false, _) => HypothesisStatus::Degenerate,
                (true, None) => HypothesisStatus::RefineFailed,
                (true, Some(_)) => HypothesisStatus::Kept,
            },
            focals: None,
        })
        .collect();
    let refined = generated.refined();

    // Steps 4–6: focal estimation, local test, consensus and band.
    let mut consensus = None;
    let mut consensus_fallback = false;
    let mut local_ok = refined.len();
    let mut focal_failures = 0;
    let mut focal_priors = 0;
    if config.method == Method::Semical {
        let Some(focals) = focals.filter(|f| f.focals.len() == m && f.from_prior.len() == m) else {
            return Err(PipelineError::InvalidConfig {
                key: "method",
                message: format!("scene `{name}`: semical needs the focal lengths of step 4"),
            });
        };
        for &j in &refined {
            hypotheses[j].focals = focals.focals[j];
            focal_failures += usize::from(focals.focals[j].is_none());
            focal_priors += usize::from(focals.from_prior[j]);
        }
        timings.focal = focals.seconds;

        let t = Instant::now();
        let filtered = focal_filter(&mut hypotheses, &refined, config);
        consensus = filtered.0;
        consensus_fallback = filtered.1;
        local_ok = filtered.2;
        timings.consensus = seconds_since(t);
    }
    // Steps 1–4 ran before this call (or were shared with another one).
    let shared_seconds = timings.sampling + timings.refine + timings.focal;
    let kept: Vec<usize> = refined
        .iter()
        .copied()
        .filter(|&j| hypotheses[j].status == HypothesisStatus::Kept)
        .collect();
    let counts = HypothesisCounts {
        generated: m,
        refined: refined.len(),
        local_ok,
        kept: kept.len(),
        focal_failures,
        focal_priors,
    };

    let mut segmentation = Segmentation {
        labels: vec![-1; n],
        counts,
        hypotheses,
        consensus,
        consensus_fallback,
        clusters: Vec::new(),
        clusters_before_filter: 0,
        timings,
        degenerate: None,
    };
    if kept.is_empty() {
        segmentation.degenerate = Some(if generated.fitted.iter().all(|&fitted| !fitted) {
            "every minimal sample is degenerate".to_string()
        } else {
            "no hypothesis survived the refinement".to_string()
        });
        segmentation.timings.total = seconds_since(started) + shared_seconds;
        return Ok(segmentation);
    }

    // Step 7: preferences, one hypothesis (column) at a time.
    let t = Instant::now();
    let clustering_error = |source| PipelineError::Clustering {
        scene: name.to_string(),
        source,
    };
    let params = ClusteringParams {
        linkage: config.linkage,
        min_cluster_size: config.min_cluster_size,
    };
    let tau = config.thr_px * config.thr_px;
    let mut builder = params
        .preference_builder(n, tau)
        .map_err(clustering_error)?;
    let mut residuals = vec![0.0; n];
    for &j in &kept {
        sampson_distances_squared(models[j].as_ref().expect("kept"), points, &mut residuals);
        builder
            .push_residuals(&residuals)
            .map_err(clustering_error)?;
    }
    let preferences = builder.finish();
    segmentation.timings.preferences = seconds_since(t);

    // Steps 8–9: linkage and size filter.
    let t = Instant::now();
    let clustering = params.cluster(&preferences);
    drop(preferences);
    segmentation.timings.clustering = seconds_since(t);

    // The 8-point F of each final cluster.
    let t = Instant::now();
    let mut members: Vec<Vec<usize>> = vec![Vec::new(); clustering.clusters_after_filter];
    for (i, &label) in clustering.labels.iter().enumerate() {
        if label >= 0 {
            members[label as usize].push(i);
        }
    }
    segmentation.clusters = members
        .iter()
        .enumerate()
        .map(|(label, idx)| ClusterModel {
            label: label as i32,
            size: idx.len(),
            f: fit_cluster(points, idx),
        })
        .collect();
    segmentation.timings.cluster_fit = seconds_since(t);
    segmentation.clusters_before_filter = clustering.clusters_before_filter;
    segmentation.labels = clustering.labels;
    segmentation.timings.total = seconds_since(started) + shared_seconds;
    Ok(segmentation)
}

/// Hartley-normalised 8-point F of the points `indices` (None with fewer
/// than 8 points or a degenerate configuration).
pub fn fit_cluster(points: &Correspondences, indices: &[usize]) -> Option<Matrix3<f64>> {
    if indices.len() < geometry::MIN_POINTS {
        return None;
    }
    eight_point_normalized(&points.subset(indices).ok()?).ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn samples_are_distinct_in_range_and_reproducible() {
        for j in 0..200 {
            let s = minimal_sample(1, "x", j, 30, 8);
            assert_eq!(s.len(), 8);
            let mut d = s.clone();
            d.sort_unstable();
            d.dedup();
            assert_eq!(d.len(), 8);
            assert!(s.iter().all(|&i| i < 30));
            assert_eq!(s, minimal_sample(1, "x", j, 30, 8));
        }
        assert_ne!(
            minimal_sample(1, "x", 0, 1000, 8),
            minimal_sample(1, "y", 0, 1000, 8)
        );
        assert_ne!(
            minimal_sample(1, "x", 0, 1000, 8),
            minimal_sample(2, "x", 0, 1000, 8)
        );
    }

    #[test]
    fn fnv_matches_the_published_test_vectors() {
        assert_eq!(fnv1a64(b""), 0xcbf29ce484222325);
        assert_eq!(fnv1a64(b"a"), 0xaf63dc4c8601ec8c);
        assert_eq!(fnv1a64(b"foobar"), 0x85944171f73967e8);
    }

    fn hyp(focals: Option<(f64, f64)>) -> Hypothesis {
        Hypothesis {
            status: HypothesisStatus::Kept,
            focals,
        }
    }

    #[test]
    fn focal_filter_variants() {
        // 0: no focal; 1..=5 agree near 1000; 6 fails |f1-f2| only; 7 negative.
        let mut hs = vec![
            hyp(None),
            hyp(Some((1000.0, 1010.0))),
            hyp(Some((990.0, 1000.0))),
            hyp(Some((1005.0, 1000.0))),
            hyp(Some((995.0, 1000.0))),
            hyp(Some((2000.0, 2010.0))),
            hyp(Some((900.0, 1100.0))),
            hyp(Some((-1000.0, -1000.0))),
        ];
        let refined: Vec<usize> = (0..hs.len()).collect();
        let config = PipelineConfig {
            tau_diff: 0.05,
            tau_range: 0.2,
            ..Default::default()
        };
        let mut a = hs.clone();
        let (c, fallback, local_ok) = focal_filter(&mut a, &refined, &config);
        assert!(!fallback);
        assert_eq!(local_ok, 5);
        let f_peak = c.unwrap().f_peak;
        assert!((f_peak - 1000.0).abs() < 100.0, "{f_peak}");
        use HypothesisStatus::*;
        let status: Vec<HypothesisStatus> = a.iter().map(|h| h.status).collect();
        assert_eq!(
            status,
            [
                FocalFailed,
                Kept,
                Kept,
                Kept,
                Kept,
                OutsideBand,
                LocalTestFailed,
                LocalTestFailed
            ]
        );
        // Reference code: 6 stays in the pool and the band keeps it (f_avg 1000).
        let reference = PipelineConfig {
            local_test: LocalTest::ReferenceCode,
            ..config.clone()
        };
        let (_, _, local_ok) = focal_filter(&mut hs, &refined, &reference);
        assert_eq!(local_ok, 5);
        assert_eq!(hs[6].status, Kept);
        assert_eq!(hs[7].status, LocalTestFailed);
        assert_eq!(hs[0].status, FocalFailed);
        // Nothing passes: everything refined is kept.
        let mut none = vec![hyp(None), hyp(Some((500.0, 1500.0)))];
        let (c, fallback, local_ok) = focal_filter(&mut none, &[0, 1], &config);
        assert!(c.is_none() && fallback && local_ok == 0);
        assert!(none.iter().all(|h| h.status == Kept));
    }
}
