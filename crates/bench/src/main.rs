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
    /// Focal lengths from fundamental matrices (Bougnoux and the robust iterative solver).
    Focal(cli::focal::Args),
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
        Command::Focal(args) => cli::focal::run(args),
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
