//! The experiment harness behind `sctl run` and `sctl merge`: every
//! (combination, scene) unit of a sweep evaluated in parallel, each appended
//! to `per_scene.csv` and `timings.csv` as soon as it finishes, then the run
//! directory completed with `summary.csv`, `wilcoxon.csv`, `report.md` and
//! the run-level figures under `plots/` (when `[plots] enabled`). With
//! `[plots] per_scene`, each unit also draws its own figures into
//! `plots/<combination>/` as it finishes (see [`ScenePlots`]).
//!
//! Units are numbered `combination × scenes + scene`; `--shard K/N` keeps
//! the units whose number is `K − 1` modulo `N`. At the end of a run the two
//! CSV files are rewritten in unit order, so that their bytes do not depend
//! on the thread count, on interruptions or on sharding.
//!
//! One file per job: this file (the evaluator interface, options, shards),
//! `run.rs` ([`run_experiment`]), `units.rs` (unit order of the CSV rows),
//! `finalize.rs` (the derived files) and `merge.rs` ([`merge`]).

mod finalize;
mod merge;
mod run;
#[cfg(test)]
mod tests;
mod units;

pub use finalize::{finalize, FailedUnit};
pub use merge::{merge, Merged};
pub use run::run_experiment;

use crate::config::{ExperimentConfig, PipelineConfig, PlotFormat};
use crate::output::{params_file_name, SceneResult, StageTimings};
use crate::sweep::SweepPlan;
use anyhow::{Context, Result};
use std::path::{Path, PathBuf};
use std::str::FromStr;
use thiserror::Error;

/// Where the per-scene figures of one (combination, scene) unit go.
#[derive(Debug, Clone, PartialEq)]
pub struct ScenePlots {
    /// The combination's directory, `<run>/plots/<combination>` (see
    /// [`combination_dir_name`]); it exists.
    pub dir: PathBuf,
    /// The combination as `key=value` pairs, for the figure titles.
    pub label: String,
    /// Each figure is written once per format.
    pub formats: Vec<PlotFormat>,
}

/// Evaluates one combination on one scene: the pipeline and the metrics.
pub trait Evaluator: Sync {
    /// The scene names, in run order.
    fn scene_names(&self) -> Vec<String>;
    /// Runs `pipeline` on scene `scene` (an index into
    /// [`Evaluator::scene_names`]); draws the scene's figures into `plots`
    /// when given (an evaluator without figures may ignore it).
    fn evaluate(
        &self,
        scene: usize,
        pipeline: &PipelineConfig,
        plots: Option<&ScenePlots>,
    ) -> Result<(SceneResult, StageTimings)>;
}

/// The per-scene figure directory name of a combination: its swept
/// parameters (always `method` first) as [`params_file_name`], e.g.
/// `method-semical__num_samples-500`.
pub fn combination_dir_name(plan: &SweepPlan, combination: usize) -> String {
    params_file_name(&plan.params_of(combination, &[]))
}

/// One of `N` deterministic parts of a run (`--shard K/N`, `1 ≤ K ≤ N`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// K, 1-based.
    pub index: usize,
    /// N.
    pub count: usize,
}

/// A `--shard` argument that is not `K/N` with `1 ≤ K ≤ N`.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
#[error("`{0}` is not K/N with 1 <= K <= N (e.g. 2/4)")]
pub struct ShardError(String);

impl FromStr for Shard {
    type Err = ShardError;
    fn from_str(s: &str) -> std::result::Result<Self, ShardError> {
        let err = || ShardError(s.to_string());
        let (k, n) = s.split_once('/').ok_or_else(err)?;
        let index: usize = k.trim().parse().map_err(|_| err())?;
        let count: usize = n.trim().parse().map_err(|_| err())?;
        if index == 0 || index > count {
            return Err(err());
        }
        Ok(Self { index, count })
    }
}

impl Shard {
    /// True when unit number `unit` belongs to this shard.
    pub fn contains(&self, unit: usize) -> bool {
        unit % self.count == self.index - 1
    }
}

/// How to run an experiment.
#[derive(Debug, Clone)]
pub struct RunOptions {
    /// The run directory.
    pub out_dir: PathBuf,
    /// Worker threads (a local rayon pool).
    pub threads: usize,
    /// Run only this part of the units.
    pub shard: Option<Shard>,
    /// Keep the rows already in `per_scene.csv` and run only the others.
    pub resume: bool,
    /// Replace the results of an earlier run in `out_dir` (without it, and
    /// without `resume`, a directory holding a run is refused).
    pub force: bool,
    /// Draw a progress bar on stderr (when it is a terminal).
    pub progress: bool,
}

/// What a run did.
#[derive(Debug, Clone)]
pub struct RunOutcome {
    /// Units evaluated by this invocation.
    pub evaluated: usize,
    /// Units found done in `per_scene.csv` (`--resume`).
    pub skipped: usize,
    /// Wall time of this invocation, seconds.
    pub wall_seconds: f64,
    /// The end-of-run table (empty for a shard).
    pub summary: String,
    /// The units of the run directory that could not be segmented (this
    /// invocation's and, with `--resume`, earlier ones), in unit order.
    pub failed: Vec<FailedUnit>,
}

/// The default run directory: `results/<name>`, or
/// `results/<name>/shard-K-of-N` for a shard.
pub fn default_out_dir(name: &str, shard: Option<Shard>) -> PathBuf {
    let base = Path::new("results").join(name);
    match shard {
        Some(s) => base.join(format!("shard-{}-of-{}", s.index, s.count)),
        None => base,
    }
}

/// The configuration as written to `config.toml`: every default explicit
/// and the scene list resolved, so that `sctl merge` needs nothing else.
pub fn resolved_config(config: &ExperimentConfig, scenes: &[String]) -> ExperimentConfig {
    let mut resolved = config.clone();
    resolved.dataset.scenes = Some(scenes.to_vec());
    resolved
}

/// A rayon pool of `threads` workers (0: rayon's default), local to the
/// caller: nothing global is configured.
pub fn thread_pool(threads: usize) -> Result<rayon::ThreadPool> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .context("cannot start the worker threads")
}
