//! Configuration: the parameters of Algorithm 1 ([`PipelineConfig`]) and the
//! experiment files read by `sctl run` ([`ExperimentConfig`]).
//!
//! Every parameter of docs/method.md's Parameters table is a field of
//! [`PipelineConfig`]; its serde default is the thesis's Table 1 value (or the
//! text's, where Table 1 has none). Unknown keys are errors, and every error
//! names the file, the key path (e.g. `pipeline.method`) and the line.

//!
//! One file per job: `pipeline` (`[pipeline]`), `dataset` (`[dataset]`),
//! `tables` (`[compare]`, `[plots]`), `toml_error` (errors with file,
//! key and line), `help` (the `--help` text, tested against the keys),
//! [`keys`] (the texts made from the key table: help, README, Python stub).

mod dataset;
mod help;
pub mod keys;
mod pipeline;
mod tables;
#[cfg(test)]
mod tests;
mod toml_error;

pub use dataset::{DatasetConfig, DatasetKind, Split};
pub use help::CONFIG_KEYS_HELP;
pub use pipeline::{PipelineConfig, PIPELINE_KEYS};
pub use segmentation::{
    EightPoint, FocalSolver, IrlsFit, Linkage, LocalTest, Method, MinimalSolutions, MinimalSolver,
    OnFailure, ParamError, Params, Profile, WeightPreset, WeightSets,
};
pub use tables::{CompareConfig, PlotFormat, PlotsConfig};
pub use toml_error::{parse_toml, ConfigError};

use serde::{Deserialize, Serialize};
use std::path::Path;

/// An experiment file, as read: `name`, `[dataset]`, `[pipeline]`, `[sweep]`,
/// `[compare]`, `[plots]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ExperimentConfig {
    /// Name of the experiment: the output goes to `results/<name>/`.
    pub name: String,
    /// Free text shown at the top of `report.md`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub description: Option<String>,
    /// The scenes.
    pub dataset: DatasetConfig,
    /// The base parameters of every combination (resolved on its profile).
    #[serde(default)]
    pub pipeline: PipelineConfig,
    /// Parameters given as lists: the run is their cartesian product.
    #[serde(default)]
    pub sweep: toml::Table,
    /// The reference combination of the Wilcoxon tests.
    #[serde(default)]
    pub compare: CompareConfig,
    /// Figures.
    #[serde(default)]
    pub plots: PlotsConfig,
}

impl ExperimentConfig {
    /// Reads and checks an experiment file: syntax, unknown keys, value
    /// types and ranges, the `[sweep]` lists and `[compare] against`.
    pub fn load(path: &Path) -> Result<Self, ConfigError> {
        let text = std::fs::read_to_string(path).map_err(|source| ConfigError::Read {
            file: path.to_path_buf(),
            source,
        })?;
        Self::parse(&text, path)
    }

    /// As [`ExperimentConfig::load`], from text; `file` only names the source in errors.
    pub fn parse(text: &str, file: &Path) -> Result<Self, ConfigError> {
        let mut config: ExperimentConfig = parse_toml(text, file)?;
        config.pipeline = config.pipeline.resolve_profile(None, text, file)?;
        config.check(file).map_err(|e| {
            let key = match &e {
                ConfigError::Invalid { key, .. } => key.clone(),
                _ => String::new(),
            };
            e.with_line(text, &key)
        })?;
        Ok(config)
    }

    fn check(&self, file: &Path) -> Result<(), ConfigError> {
        if self.name.is_empty()
            || !self
                .name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || matches!(c, '-' | '_' | '.'))
            || self.name.starts_with('.')
        {
            return Err(ConfigError::invalid(
                file,
                "name",
                format!(
                    "`{}` is not a valid run name (letters, digits, `-`, `_`, `.`; it names the output directory)",
                    self.name
                ),
            ));
        }
        self.pipeline
            .validate()
            .map_err(|e| ConfigError::invalid(file, format!("pipeline.{}", e.key), e.message))?;
        if self.plots.formats.is_empty() && self.plots.enabled {
            return Err(ConfigError::invalid(
                file,
                "plots.formats",
                "must name at least one format when plots are enabled",
            ));
        }
        self.dataset.check(file)?;
        crate::sweep::SweepPlan::expand(self).map_err(|e| e.into_config_error(file))?;
        Ok(())
    }

    /// The `[pipeline]` table with every default written out.
    pub fn pipeline_table(&self) -> toml::Table {
        toml::Table::try_from(&self.pipeline).expect("PipelineConfig serializes to a table")
    }

    /// The resolved configuration as TOML text (every default explicit).
    pub fn to_toml(&self) -> String {
        toml::to_string(self).expect("ExperimentConfig serializes to TOML")
    }
}
