//! `sctl`: the command-line front end of the semi-calibrated T-Linkage
//! pipeline. Each subcommand lives in its own module under `cli/`.

use clap::{Parser, Subcommand};

mod cli;

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
    Run(cli::run::Args),
    /// Segment one pair of your own matches and write one label per match.
    Segment(cli::segment::Args),
    /// Paired comparison of two runs on their common scenes (means, wins, Wilcoxon).
    Compare(cli::compare::Args),
    /// Combine the directories of `sctl run --shard` into one run directory.
    Merge(cli::merge::Args),
    /// Focal lengths from fundamental matrices (Bougnoux and the robust iterative solver).
    Focal(cli::focal::Args),
    /// Focal lengths of the F fitted to each ground-truth motion of a config's dataset (CSV).
    GtFocals(cli::gt_focals::Args),
    /// The refined hypotheses of a config's scenes (CSV), for an external focal solver.
    Hypotheses(cli::hypotheses::Args),
    /// Good models kept and discarded by the focal filter, per scene of a config's dataset (CSV).
    FilterQuality(cli::filter_quality::Args),
    /// T-Linkage (or J-Linkage) clustering of a preference matrix read from CSV.
    Tlinkage(cli::tlinkage::Args),
    /// Print a one-line JSON summary of each scene of a dataset.
    Inspect(cli::inspect::Args),
    /// Write a synthetic HOPE-F-like dataset in the HOPE-F on-disk layout.
    Synth(cli::synth::Args),
    /// Clustering metrics (ME, ACC, FNR, PUR, ARI, NMI) of predicted labels against ground truth.
    Metrics(cli::metrics::Args),
    /// One-tailed Wilcoxon signed-rank test on paired per-scene values.
    Wilcoxon(cli::wilcoxon::Args),
}

fn main() -> std::process::ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Run(args) => cli::run::run(args),
        Command::Segment(args) => cli::segment::run(args),
        Command::Compare(args) => cli::compare::run(args),
        Command::Merge(args) => cli::merge::run(args),
        Command::Focal(args) => cli::focal::run(args),
        Command::GtFocals(args) => cli::gt_focals::run(args),
        Command::Hypotheses(args) => cli::hypotheses::run(args),
        Command::FilterQuality(args) => cli::filter_quality::run(args),
        Command::Tlinkage(args) => cli::tlinkage::run(args),
        Command::Inspect(args) => cli::inspect::run(args),
        Command::Synth(args) => cli::synth::run(args),
        Command::Metrics(args) => cli::metrics::run(args),
        Command::Wilcoxon(args) => cli::wilcoxon::run(args),
    };
    match result {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(err) => {
            eprintln!("error: {err:#}");
            std::process::ExitCode::FAILURE
        }
    }
}
