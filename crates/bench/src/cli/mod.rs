//! One module per `sctl` subcommand: its clap `Args` and its `run` function.

pub mod compare;
pub mod filter_quality;
pub mod focal;
pub mod gt_focals;
pub mod hypotheses;
pub mod inspect;
pub mod merge;
pub mod metrics;
pub mod run;
pub mod segment;
pub mod synth;
pub mod tlinkage;
pub mod wilcoxon;

use anyhow::{Context, Result};
use bench::config::ExperimentConfig;
use datasets::Scene;
use std::path::PathBuf;

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
    pub fn load(&self) -> Result<(ExperimentConfig, Vec<Scene>)> {
        let config = ExperimentConfig::load(&self.config)?;
        let scenes = bench::dataset::load_scenes(&config.dataset, self.data_root.as_deref(), false)
            .with_context(|| format!("{}: [dataset]", self.config.display()))?;
        Ok((config, scenes))
    }
}
