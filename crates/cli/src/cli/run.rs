//! `sctl run CONFIG.toml`: runs an experiment (every scene × every sweep
//! combination) into a run directory.

use crate::config::{ExperimentConfig, CONFIG_KEYS_HELP};
use crate::dataset::load_scenes;
use crate::evaluate::PipelineEvaluator;
use crate::experiment::{
    default_out_dir, run_experiment, thread_pool, RunOptions, RunOutcome, Shard,
};
use anyhow::{Context, Result};
use std::fmt::Write as _;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};

/// Options of `sctl run`.
#[derive(clap::Args)]
#[command(after_long_help = CONFIG_KEYS_HELP.as_str())]
pub struct Args {
    /// The experiment file (TOML; every key is listed under --help).
    pub config: PathBuf,
    /// Run directory [default: results/NAME, or results/NAME/shard-K-of-N with --shard].
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Worker threads, 1 to 1024 [default: every core].
    #[arg(long, value_name = "N", allow_hyphen_values = true, value_parser = super::parse_threads)]
    pub threads: Option<usize>,
    /// Run only part K of N of the (scene, combination) units: those whose
    /// number is K-1 modulo N. Combine the parts with `sctl merge`.
    #[arg(long, value_name = "K/N")]
    pub shard: Option<Shard>,
    /// Keep the units already in the run directory's per_scene.csv and run
    /// the others (the configuration, and the shard, must be the same).
    #[arg(long, conflicts_with = "force")]
    pub resume: bool,
    /// Replace the results of an earlier run in the run directory. Without
    /// it (or --resume) a directory that holds a run is refused, naming the
    /// configuration keys that differ.
    #[arg(long)]
    pub force: bool,
    /// Exit with status 0 even when scenes could not be segmented (refused
    /// for memory, bad coordinates, a bad focal file). Either way they are
    /// listed on stderr, marked `failed: REASON` in per_scene.csv, left out
    /// of the means and counted (summary.csv `failed_scenes`, report.md);
    /// without this flag the exit status is then 1.
    #[arg(long)]
    pub allow_failures: bool,
    /// Data root [default: $SCTL_DATA_ROOT, else the config's data_root, else datasets/].
    #[arg(long, value_name = "DIR")]
    pub data_root: Option<PathBuf>,
    /// No progress bar.
    #[arg(long)]
    pub quiet: bool,
}

/// Runs the experiment and prints the summary table.
pub fn run(args: Args) -> Result<()> {
    let config = ExperimentConfig::load(&args.config)?;
    let threads = match args.threads {
        Some(t) => t,
        None => std::thread::available_parallelism().map_or(1, |n| n.get()),
    };
    let images = config.plots.enabled && config.plots.per_scene;
    let scenes = thread_pool(threads)?
        .install(|| load_scenes(&config.dataset, args.data_root.as_deref(), images))
        .with_context(|| format!("{}: [dataset]", args.config.display()))?;
    let out_dir = args
        .out
        .clone()
        .unwrap_or_else(|| default_out_dir(&config.name, args.shard));
    let evaluator = PipelineEvaluator::new(scenes);
    let options = RunOptions {
        out_dir: out_dir.clone(),
        threads,
        shard: args.shard,
        resume: args.resume,
        force: args.force,
        progress: !args.quiet && std::io::stderr().is_terminal(),
    };
    eprintln!(
        "sctl run: {} — {} scenes, {} thread(s), output in {}",
        config.name,
        evaluator.scenes().len(),
        threads,
        out_dir.display()
    );
    let outcome = run_experiment(&config, &evaluator, &options)?;
    super::print_out(&end_text(&config, &args, &outcome, &out_dir))?;
    let failed = outcome.failed.len();
    if failed > 0 {
        for unit in &outcome.failed {
            eprintln!("failed: {unit}");
        }
        let text = format!(
            "{failed} unit(s) could not be segmented (listed above; left out of the means, \
             counted in summary.csv and report.md)"
        );
        if !args.allow_failures {
            anyhow::bail!("{text}; --allow-failures accepts them");
        }
        eprintln!("warning: {text}");
    }
    Ok(())
}

/// What `sctl run` prints at the end: the summary table, the counts and
/// where the results are.
fn end_text(
    config: &ExperimentConfig,
    args: &Args,
    outcome: &RunOutcome,
    out_dir: &Path,
) -> String {
    let mut text = outcome.summary.clone();
    let _ = writeln!(
        text,
        "{} units evaluated, {} already done; {:.1} s wall{}; results in {}",
        outcome.evaluated,
        outcome.skipped,
        outcome.wall_seconds,
        super::peak_memory_text(),
        out_dir.display()
    );
    if config.plots.enabled && args.shard.is_none() {
        let _ = writeln!(
            text,
            "figures in {}",
            out_dir.join(crate::output::PLOTS_DIR).display()
        );
    }
    if let Some(shard) = args.shard {
        let _ = writeln!(
            text,
            "shard {}/{} done: combine the shard directories with `sctl merge`",
            shard.index, shard.count
        );
    }
    text
}
