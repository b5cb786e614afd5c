//! `sctl`: the command-line front end of the semi-calibrated T-Linkage
//! pipeline ([`main`]). One module per subcommand: its clap `Args` and its
//! `run` function.

mod compare;
mod filter_quality;
mod focal;
mod gt_focals;
mod hypotheses;
mod inspect;
mod merge;
mod metrics;
mod run;
mod segment;
mod synth;
mod tlinkage;
mod wilcoxon;

use crate::config::ExperimentConfig;
use anyhow::{Context, Result};
use clap::{Parser, Subcommand};
use datasets::Scene;
use std::path::PathBuf;

/// The peak resident memory of this process so far, in MB (`VmHWM` of
/// /proc/self/status); `None` where it cannot be read (not Linux).
pub(crate) fn peak_memory_mb() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb.div_ceil(1000))
}

/// `", peak memory N MB"`, or nothing where it cannot be read.
pub(crate) fn peak_memory_text() -> String {
    peak_memory_mb().map_or_else(String::new, |mb| format!(", peak memory {mb} MB"))
}

/// The arguments of the subcommands that work on a config's scenes
/// (`gt-focals`, `filter-quality`, `hypotheses`).
#[derive(clap::Args)]
pub struct ConfigScenes {
    /// The experiment file whose dataset and `[pipeline]` parameters to use.
    pub config: PathBuf,
    /// Data root [default: $SCTL_DATA_ROOT, else the config's data_root, else datasets/].
    #[arg(long, value_name = "DIR")]
    pub data_root: Option<PathBuf>,
}

impl ConfigScenes {
    /// The experiment file and its scenes (without images).
    pub fn load(&self) -> Result<LoadedConfig> {
        let config = ExperimentConfig::load(&self.config)?;
        let scenes = crate::dataset::load_scenes(&config.dataset, self.data_root.as_deref(), false)
            .with_context(|| format!("{}: [dataset]", self.config.display()))?;
        Ok(LoadedConfig { config, scenes })
    }
}

/// An experiment file read with the scenes of its `[dataset]` table.
pub struct LoadedConfig {
    /// The experiment file.
    pub config: ExperimentConfig,
    /// Its scenes, in dataset order.
    pub scenes: Vec<Scene>,
}

/// Two-view motion segmentation with semi-calibrated cameras.
#[derive(Parser)]
#[command(name = "sctl", version, about, propagate_version = true)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Run an experiment: every scene x every sweep combination, into results/NAME/.
    Run(run::Args),
    /// Segment one pair of your own matches and write one label per match.
    Segment(segment::Args),
    /// Paired comparison of two runs on their common scenes (means, wins, Wilcoxon).
    Compare(compare::Args),
    /// Combine the directories of `sctl run --shard` into one run directory.
    Merge(merge::Args),
    /// Focal lengths from fundamental matrices (Bougnoux and the robust iterative solver).
    Focal(focal::Args),
    /// Focal lengths of the F fitted to each ground-truth motion of a config's dataset (CSV).
    GtFocals(gt_focals::Args),
    /// The refined hypotheses of a config's scenes (CSV), for an external focal solver.
    Hypotheses(hypotheses::Args),
    /// Good models kept and discarded by the focal filter, per scene of a config's dataset (CSV).
    FilterQuality(filter_quality::Args),
    /// T-Linkage (or J-Linkage) clustering of a preference matrix read from CSV.
    Tlinkage(tlinkage::Args),
    /// Print a one-line JSON summary of each scene of a dataset.
    Inspect(inspect::Args),
    /// Write a synthetic HOPE-F-like dataset in the HOPE-F on-disk layout.
    Synth(synth::Args),
    /// Clustering metrics (ME, ACC, FNR, PUR, ARI, NMI) of predicted labels against ground truth.
    Metrics(metrics::Args),
    /// One-tailed Wilcoxon signed-rank test on paired per-scene values.
    Wilcoxon(wilcoxon::Args),
}

/// Parses the command line, runs the subcommand and prints its error, if
/// any, on one line: the whole of the `sctl` binary.
pub fn main() -> std::process::ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Run(args) => run::run(args),
        Command::Segment(args) => segment::run(args),
        Command::Compare(args) => compare::run(args),
        Command::Merge(args) => merge::run(args),
        Command::Focal(args) => focal::run(args),
        Command::GtFocals(args) => gt_focals::run(args),
        Command::Hypotheses(args) => hypotheses::run(args),
        Command::FilterQuality(args) => filter_quality::run(args),
        Command::Tlinkage(args) => tlinkage::run(args),
        Command::Inspect(args) => inspect::run(args),
        Command::Synth(args) => synth::run(args),
        Command::Metrics(args) => metrics::run(args),
        Command::Wilcoxon(args) => wilcoxon::run(args),
    };
    match result {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(err) => {
            eprintln!("error: {err:#}");
            std::process::ExitCode::FAILURE
        }
    }
}
