//! `sctl merge DIR...`: combines the run directories of `sctl run --shard`
//! into the files a single run writes.

use anyhow::Result;
use std::path::PathBuf;

/// Options of `sctl merge`.
#[derive(clap::Args)]
pub struct Args {
    /// Shard run directories (each with config.toml, per_scene.csv, timings.csv).
    #[arg(required = true, value_name = "DIR")]
    pub dirs: Vec<PathBuf>,
    /// Output directory [default: results/NAME].
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
}

/// Merges and prints the summary table.
pub fn run(args: Args) -> Result<()> {
    let crate::experiment::Merged { out, summary } =
        crate::experiment::merge(&args.dirs, args.out.as_deref())?;
    super::print_out(&format!(
        "{summary}merged {} directories into {}\n",
        args.dirs.len(),
        out.display()
    ))
}
