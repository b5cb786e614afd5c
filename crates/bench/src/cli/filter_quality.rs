//! `sctl filter-quality CONFIG.toml`: per scene, how many good models
//! (`bench::quality::is_good_model`) the focal filter of semical kept and
//! discarded, with the config's `[pipeline]` (method forced to semical),
//! as a CSV on stdout.

use anyhow::{Context, Result};
use bench::config::ExperimentConfig;
use bench::dataset::load_scenes;
use bench::experiment::thread_pool;
use bench::quality::filter_quality;
use std::io::Write;
use std::path::PathBuf;

/// Options of `sctl filter-quality`.
#[derive(clap::Args)]
pub struct Args {
    /// The experiment file whose dataset and `[pipeline]` to use.
    pub config: PathBuf,
    /// Data root [default: $SCTL_DATA_ROOT, else the config's data_root, else datasets/].
    #[arg(long, value_name = "DIR")]
    pub data_root: Option<PathBuf>,
}

/// The CSV header.
pub const HEADER: &str = "scene,refined,good_refined,kept,good_kept,discarded,good_discarded";

/// Prints one row per scene with ground truth.
pub fn run(args: Args) -> Result<()> {
    let config = ExperimentConfig::load(&args.config)?;
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let pool = thread_pool(threads)?;
    let scenes = pool
        .install(|| load_scenes(&config.dataset, args.data_root.as_deref(), false))
        .with_context(|| format!("{}: [dataset]", args.config.display()))?;
    let mut out = std::io::stdout().lock();
    writeln!(out, "{HEADER}")?;
    for scene in &scenes {
        let quality = pool
            .install(|| filter_quality(scene, &config.pipeline))
            .with_context(|| format!("scene `{}`", scene.name))?;
        if let Some(q) = quality {
            writeln!(
                out,
                "{},{},{},{},{},{},{}",
                scene.name,
                q.refined,
                q.good_refined,
                q.kept,
                q.good_kept,
                q.discarded,
                q.good_discarded
            )?;
        }
    }
    Ok(())
}
