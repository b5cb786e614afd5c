//! `sctl filter-quality CONFIG.toml`: per scene, how many good models
//! (`crate::quality::is_good_model`) the focal filter of semical kept and
//! discarded, with the config's `[pipeline]` (method forced to semical),
//! as a CSV on stdout.

use super::LoadedConfig;
use crate::experiment::thread_pool;
use crate::quality::filter_quality;
use anyhow::{Context, Result};
use std::io::Write;

/// Options of `sctl filter-quality`.
#[derive(clap::Args)]
pub struct Args {
    /// The config and its scenes.
    #[command(flatten)]
    pub input: super::ConfigScenes,
}

/// The CSV header.
pub const HEADER: &str = "scene,refined,good_refined,kept,good_kept,discarded,good_discarded";

/// Prints one row per scene with ground truth.
pub fn run(args: Args) -> Result<()> {
    let LoadedConfig { config, scenes } = args.input.load()?;
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let pool = thread_pool(threads)?;
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
