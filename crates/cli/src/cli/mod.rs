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
use std::io::Write as _;
use std::path::PathBuf;

/// The most worker threads `--threads` accepts: far above any machine the
/// pipeline runs on (it scales to the cores), far below the count at which
/// starting the pool exhausts the process's memory for thread stacks
/// (65 535 threads abort the process).
pub(crate) const MAX_THREADS: i64 = 1024;

/// Parses `--threads N`: 1..=[`MAX_THREADS`]; any other value (negative
/// ones included) is an error naming it.
pub(crate) fn parse_threads(text: &str) -> Result<usize, String> {
    match text.trim().parse::<i64>() {
        Ok(n) if (1..=MAX_THREADS).contains(&n) => Ok(n as usize),
        Ok(n) => Err(format!("{n} threads: give 1 to {MAX_THREADS}")),
        Err(_) => Err(format!(
            "`{}` is not a whole number of threads",
            crate::output::echo(text)
        )),
    }
}

/// Writes `text` to standard output and flushes it. A closed pipe (`sctl
/// ... | head -1`) is [`StdoutClosed`], which [`main`] ends quietly with
/// status 0; any other failure (a full disk) is an error saying so.
pub(crate) fn print_out(text: &str) -> Result<()> {
    let mut out = std::io::stdout().lock();
    out.write_all(text.as_bytes())
        .and_then(|()| out.flush())
        .map_err(stdout_error)
}

/// An error writing to standard output, as [`print_out`] reports it.
pub(crate) fn stdout_error(err: std::io::Error) -> anyhow::Error {
    if err.kind() == std::io::ErrorKind::BrokenPipe {
        anyhow::Error::new(StdoutClosed)
    } else {
        anyhow::Error::new(err).context("cannot write to standard output")
    }
}

/// Standard output was closed by its reader before everything was written.
#[derive(Debug, thiserror::Error)]
#[error("standard output closed by its reader")]
pub(crate) struct StdoutClosed;

/// True when `err` comes from a closed standard output (or any closed pipe):
/// the reader wanted no more, which is not a failure.
fn is_closed_pipe(err: &anyhow::Error) -> bool {
    err.chain().any(|cause| {
        cause.is::<StdoutClosed>()
            || cause
                .downcast_ref::<std::io::Error>()
                .is_some_and(|e| e.kind() == std::io::ErrorKind::BrokenPipe)
    })
}

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

/// The top-level `about`: what the tool does, in one sentence.
const ABOUT: &str = "Finds the independently moving objects in a pair of photos: segments the \
point matches between two views into rigid motions (T-Linkage over fundamental matrices, with \
semi-calibrated cameras), and evaluates the method on datasets.";

/// After the top-level help: the exit statuses.
const EXIT_STATUS_HELP: &str = "Exit status: 0 on success, also when standard output is closed \
by its reader (`sctl ... | head -1`); 1 on an error (one line on stderr) or, for `sctl run` \
without --allow-failures, when scenes could not be segmented; 2 for a bad command line.";

#[derive(Parser)]
#[command(
    name = "sctl",
    version,
    about = ABOUT,
    after_help = EXIT_STATUS_HELP,
    propagate_version = true
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Segment one pair of your own matches into motions (summary; labels with --out).
    Segment(segment::Args),
    /// Run an experiment: every scene x every sweep combination, into results/NAME/.
    Run(run::Args),
    /// Paired comparison of two runs on their common scenes (means, wins, Wilcoxon).
    Compare(compare::Args),
    /// Combine the directories of `sctl run --shard` into one run directory.
    Merge(merge::Args),
    /// Write a synthetic HOPE-F-like dataset in the HOPE-F on-disk layout.
    Synth(synth::Args),
    /// Diagnostics: gt-focals, filter-quality, hypotheses, tlinkage, inspect,
    /// metrics, wilcoxon, focal (`sctl lab CMD`; `sctl CMD` works too).
    #[command(subcommand)]
    Lab(Lab),
}

/// The diagnostic subcommands, under `sctl lab`.
#[derive(Subcommand)]
enum Lab {
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
    /// Clustering metrics (ME, ACC, FNR, PUR, ARI, NMI) of predicted labels against ground truth.
    Metrics(metrics::Args),
    /// One-tailed Wilcoxon signed-rank test on paired per-scene values.
    Wilcoxon(wilcoxon::Args),
}

/// The names of the [`Lab`] subcommands, which also work without `lab`.
const LAB_COMMANDS: [&str; 8] = [
    "focal",
    "gt-focals",
    "hypotheses",
    "filter-quality",
    "tlinkage",
    "inspect",
    "metrics",
    "wilcoxon",
];

/// The command line with `lab` inserted before a diagnostic subcommand
/// given at the top level (`sctl metrics ...` is `sctl lab metrics ...`).
fn with_lab(mut args: Vec<std::ffi::OsString>) -> Vec<std::ffi::OsString> {
    if args
        .get(1)
        .and_then(|a| a.to_str())
        .is_some_and(|a| LAB_COMMANDS.contains(&a))
    {
        args.insert(1, "lab".into());
    }
    args
}

/// Parses the command line, runs the subcommand and prints its error, if
/// any, on one line: the whole of the `sctl` binary.
pub fn main() -> std::process::ExitCode {
    let cli = Cli::parse_from(with_lab(std::env::args_os().collect()));
    let result = match cli.command {
        Command::Run(args) => run::run(args),
        Command::Segment(args) => segment::run(args),
        Command::Compare(args) => compare::run(args),
        Command::Merge(args) => merge::run(args),
        Command::Synth(args) => synth::run(args),
        Command::Lab(lab) => match lab {
            Lab::Focal(args) => focal::run(args),
            Lab::GtFocals(args) => gt_focals::run(args),
            Lab::Hypotheses(args) => hypotheses::run(args),
            Lab::FilterQuality(args) => filter_quality::run(args),
            Lab::Tlinkage(args) => tlinkage::run(args),
            Lab::Inspect(args) => inspect::run(args),
            Lab::Metrics(args) => metrics::run(args),
            Lab::Wilcoxon(args) => wilcoxon::run(args),
        },
    };
    match result {
        Ok(()) => std::process::ExitCode::SUCCESS,
        // `sctl segment --out - | head -1`: the reader has what it wanted.
        Err(err) if is_closed_pipe(&err) => std::process::ExitCode::SUCCESS,
        Err(err) => {
            // Not eprintln!: a closed or full stderr must not panic.
            let _ = writeln!(std::io::stderr(), "error: {err:#}");
            std::process::ExitCode::FAILURE
        }
    }
}
