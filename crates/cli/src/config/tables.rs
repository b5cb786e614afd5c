//! The `[compare]` and `[plots]` tables.

use serde::de::{self, Deserializer};
use serde::{Deserialize, Serialize, Serializer};

/// `[compare]`: the reference combination of the Wilcoxon tests.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CompareConfig {
    /// Pipeline parameters that turn a combination into its reference (every
    /// other parameter equal). Default `{ method = "baseline" }`.
    #[serde(default = "default_against")]
    pub against: toml::Table,
}

pub(super) fn default_against() -> toml::Table {
    let mut t = toml::Table::new();
    t.insert("method".into(), toml::Value::String("baseline".into()));
    t
}

impl Default for CompareConfig {
    fn default() -> Self {
        Self {
            against: default_against(),
        }
    }
}

pub use crate::plots::PlotFormat;

impl PlotFormat {
    /// The file extension of the format, also its name in `[plots] formats`:
    /// `png` or `svg`.
    ///
    /// ```
    /// assert_eq!(sctl::config::PlotFormat::Svg.extension(), "svg");
    /// ```
    pub fn extension(self) -> &'static str {
        match self {
            PlotFormat::Png => "png",
            PlotFormat::Svg => "svg",
        }
    }
}

impl Serialize for PlotFormat {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(self.extension())
    }
}

impl<'de> Deserialize<'de> for PlotFormat {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let name = String::deserialize(deserializer)?;
        match name.as_str() {
            "png" => Ok(PlotFormat::Png),
            "svg" => Ok(PlotFormat::Svg),
            other => Err(de::Error::unknown_variant(other, &["png", "svg"])),
        }
    }
}

/// `[plots]`: which figures a run writes into its directory (see
/// `report::write_run_plots` and
/// `evaluate::draw_scene_plots` for the files).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PlotsConfig {
    /// Write the run-level figures into `<run>/plots/`, drawn from
    /// `per_scene.csv` when the run (or `sctl merge`) finishes: ME against M
    /// (Fig. 10, when `num_samples` is swept), the histogram of
    /// `|f_peak − f_true| / f_true` (Fig. 9) and the ME-per-scene scatter
    /// of baseline against semical. Default `true`.
    pub enabled: bool,
    /// Also write per-scene figures into `<run>/plots/<combination>/`: the
    /// focal KDE (Fig. 8, semical only) and the clusters over both images
    /// (Figs. 11–12; a blank canvas without images). Default `false`.
    pub per_scene: bool,
    /// Image formats, each figure written once per format: `png`, `svg`.
    /// Default `["png", "svg"]`.
    pub formats: Vec<PlotFormat>,
}

impl Default for PlotsConfig {
    fn default() -> Self {
        Self {
            enabled: true,
            per_scene: false,
            formats: vec![PlotFormat::Png, PlotFormat::Svg],
        }
    }
}
