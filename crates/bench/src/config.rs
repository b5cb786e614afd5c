//! Configuration: the parameters of Algorithm 1 ([`PipelineConfig`]) and the
//! experiment files read by `sctl run` ([`ExperimentConfig`]).
//!
//! Every parameter of method.md's Parameters table is a field of
//! [`PipelineConfig`]; its serde default is the thesis's Table 1 value (or the
//! text's, where Table 1 has none). Unknown keys are errors, and every error
//! names the file, the key path (e.g. `pipeline.method`) and the line.

use serde::de::{self, Deserializer};
use serde::{Deserialize, Serialize, Serializer};

pub use segmentation::{
    EightPoint, FocalSolver, IrlsFit, Linkage, LocalTest, Method, MinimalSolutions, MinimalSolver,
    OnFailure, ParamError, Params, WeightPreset, WeightSets,
};
use std::path::{Path, PathBuf};
use thiserror::Error;

/// The `[pipeline]` table of an experiment file: every parameter of
/// [`segmentation::Params`] under the same name, with the same default (see
/// the field docs there), and `focal_file`, the harness's source of the
/// answers of `focal_solver = "external"`.
///
/// ```
/// let p: bench::config::PipelineConfig = toml::from_str("num_samples = 500").unwrap();
/// assert_eq!(p.num_samples, 500);
/// assert_eq!(p.thr_px, 2.5); // Table 1
/// assert!(toml::from_str::<bench::config::PipelineConfig>("num_sample = 5").is_err());
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
#[allow(missing_docs)] // each field is documented on segmentation::Params
pub struct PipelineConfig {
    pub method: Method,
    pub num_samples: usize,
    pub mss_size: usize,
    pub thr_px: f64,
    pub tau_diff: f64,
    pub tau_range: f64,
    pub irls_iters: usize,
    pub irls_fit: IrlsFit,
    pub irls_unit_weight_fallback: bool,
    pub irls_sigma_offset_px: f64,
    pub irls_polish: bool,
    pub refine: bool,
    pub eight_point: EightPoint,
    pub minimal_solver: MinimalSolver,
    pub minimal_solutions: MinimalSolutions,
    pub focal_solver: FocalSolver,
    /// The CSV of `focal_solver = "external"` (see [`crate::focal_file`]),
    /// relative to the working directory; `{seed}` is replaced by the seed.
    /// Answers are used as given (truncated when `truncate_focals`); a
    /// non-finite one leaves the hypothesis without focals. Default empty
    /// (not serialised when empty).
    #[serde(skip_serializing_if = "String::is_empty")]
    pub focal_file: String,
    pub weight_sets: WeightSets,
    pub max_iters: usize,
    pub focal_failure: OnFailure,
    pub truncate_focals: bool,
    pub local_test: LocalTest,
    pub linkage: Linkage,
    pub min_cluster_size: usize,
    /// The run's seed; scene `s` is segmented with the seed
    /// [`crate::pipeline::scene_seed`]`(seed, s)`, as in every committed result.
    pub seed: u64,
}

impl Default for PipelineConfig {
    fn default() -> Self {
        Self::from_params(Params::default())
    }
}

/// The keys of [`PipelineConfig`] in declaration order: the order of the
/// swept-parameter columns in every output file.
pub const PIPELINE_KEYS: [&str; 25] = [
    "method",
    "num_samples",
    "mss_size",
    "thr_px",
    "tau_diff",
    "tau_range",
    "irls_iters",
    "irls_fit",
    "irls_unit_weight_fallback",
    "irls_sigma_offset_px",
    "irls_polish",
    "refine",
    "eight_point",
    "minimal_solver",
    "minimal_solutions",
    "focal_solver",
    "focal_file",
    "weight_sets",
    "max_iters",
    "focal_failure",
    "truncate_focals",
    "local_test",
    "linkage",
    "min_cluster_size",
    "seed",
];

impl PipelineConfig {
    /// The table of `params`, without a focal file.
    pub fn from_params(p: Params) -> Self {
        Self {
            method: p.method,
            num_samples: p.num_samples,
            mss_size: p.mss_size,
            thr_px: p.thr_px,
            tau_diff: p.tau_diff,
            tau_range: p.tau_range,
            irls_iters: p.irls_iters,
            irls_fit: p.irls_fit,
            irls_unit_weight_fallback: p.irls_unit_weight_fallback,
            irls_sigma_offset_px: p.irls_sigma_offset_px,
            irls_polish: p.irls_polish,
            refine: p.refine,
            eight_point: p.eight_point,
            minimal_solver: p.minimal_solver,
            minimal_solutions: p.minimal_solutions,
            focal_solver: p.focal_solver,
            focal_file: String::new(),
            weight_sets: p.weight_sets,
            max_iters: p.max_iters,
            focal_failure: p.focal_failure,
            truncate_focals: p.truncate_focals,
            local_test: p.local_test,
            linkage: p.linkage,
            min_cluster_size: p.min_cluster_size,
            seed: p.seed,
        }
    }

    /// The method's parameters, with the run's seed.
    pub fn params(&self) -> Params {
        Params {
            method: self.method,
            num_samples: self.num_samples,
            mss_size: self.mss_size,
            thr_px: self.thr_px,
            tau_diff: self.tau_diff,
            tau_range: self.tau_range,
            irls_iters: self.irls_iters,
            irls_fit: self.irls_fit,
            irls_unit_weight_fallback: self.irls_unit_weight_fallback,
            irls_sigma_offset_px: self.irls_sigma_offset_px,
            irls_polish: self.irls_polish,
            refine: self.refine,
            eight_point: self.eight_point,
            minimal_solver: self.minimal_solver,
            minimal_solutions: self.minimal_solutions,
            focal_solver: self.focal_solver,
            weight_sets: self.weight_sets.clone(),
            max_iters: self.max_iters,
            focal_failure: self.focal_failure,
            truncate_focals: self.truncate_focals,
            local_test: self.local_test,
            linkage: self.linkage,
            min_cluster_size: self.min_cluster_size,
            seed: self.seed,
        }
    }

    /// The method's parameters for the scene named `scene`: the seed is
    /// [`crate::pipeline::scene_seed`]`(seed, scene)`.
    pub fn scene_params(&self, scene: &str) -> Params {
        Params {
            seed: crate::pipeline::scene_seed(self.seed, scene),
            ..self.params()
        }
    }

    /// Checks the ranges serde cannot ([`Params::validate`]) and that
    /// `focal_file` is given with `focal_solver = "external"`.
    pub fn validate(&self) -> Result<(), ParamError> {
        self.params().validate()?;
        if self.focal_solver == FocalSolver::External && self.focal_file.is_empty() {
            return Err(ParamError {
                key: "focal_file",
                message: "must name the CSV of focal lengths when focal_solver = \"external\""
                    .into(),
            });
        }
        Ok(())
    }
}

/// The dataset an experiment runs on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum DatasetKind {
    /// The 19 AdelaideRMF fundamental-matrix sequences (`<root>/adelaidermf/F/*.mat`).
    Adelaidermf,
    /// HOPE-F in its on-disk layout (`<root>/hopef/<k>/<NNNN>/`).
    Hopef,
    /// Scenes generated in memory by the seeded synthetic generator.
    Synthetic,
    /// The user's own match files (`x1,y1,x2,y2[,label]` CSV).
    Csv,
}

/// HOPE-F split by scene index: train 0000–0799, val 0800–0899, test 0900–0999.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Split {
    /// Scenes 0000–0799.
    Train,
    /// Scenes 0800–0899.
    Val,
    /// Scenes 0900–0999.
    Test,
}

/// `[dataset]`: which scenes an experiment runs on.
///
/// Selection keys combine (a scene must pass all that are given):
/// `scenes` (names), `split` and `categories` (HOPE-F and synthetic),
/// `index_range` (inclusive `[first, last]` scene index: HOPE-F's folder
/// number, else the position in the dataset's scene list).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DatasetConfig {
    /// `adelaidermf`, `hopef`, `synthetic` or `csv`.
    pub kind: DatasetKind,
    /// Data root (below it: `adelaidermf/F`, `hopef/`); overridden by
    /// `--data-root` and by `SCTL_DATA_ROOT`; default `datasets`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub data_root: Option<PathBuf>,
    /// Scene names to run, in the dataset's order. Default: every scene.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scenes: Option<Vec<String>>,
    /// HOPE-F split (`train`, `val`, `test`). Default: every split.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub split: Option<Split>,
    /// Number of moving objects (1–4) to keep (HOPE-F, synthetic). Default: all.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub categories: Option<Vec<u32>>,
    /// Inclusive scene-index range `[first, last]`. Default: all.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub index_range: Option<[u32; 2]>,
    /// Synthetic generator preset, one of [`datasets::synthetic::Preset::ALL`] by
    /// name (`quick`, `hopef-like`, `kitti-like`, `hopef`). Default `quick`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub preset: Option<String>,
    /// Synthetic generator seed. Default 1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub generator_seed: Option<u64>,
    /// `csv`: the match files, relative to the data root unless absolute:
    /// `.csv` (`x1,y1,x2,y2[,label]` with a header) or AdelaideRMF-style
    /// `.txt` (`x1 y1 x2 y2 [label]`), each with an optional sidecar
    /// `<file>.toml` (width, height, name, focal, principal point).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub files: Option<Vec<PathBuf>>,
    /// `csv`: image width in pixels of every file (else from each sidecar).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub width: Option<u32>,
    /// `csv`: image height in pixels of every file (else from each sidecar).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub height: Option<u32>,
}

/// `[compare]`: the reference combination of the Wilcoxon tests.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CompareConfig {
    /// Pipeline parameters that turn a combination into its reference (every
    /// other parameter equal). Default `{ method = "baseline" }`.
    #[serde(default = "default_against")]
    pub against: toml::Table,
}

fn default_against() -> toml::Table {
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
    /// assert_eq!(bench::config::PlotFormat::Svg.extension(), "svg");
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
/// [`crate::report::write_run_plots`] and
/// [`crate::evaluate::draw_scene_plots`] for the files).
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
    /// The base parameters of every combination.
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

/// Every key of an experiment file, for `sctl run --help`.
pub const CONFIG_KEYS_HELP: &str = "\
EXPERIMENT FILE (TOML)
  name = \"quickstart\"          run name; output goes to results/<name>/
  description = \"...\"          optional text for report.md

  [dataset]
  kind = \"adelaidermf\"         adelaidermf | hopef | synthetic | csv
  data_root = \"datasets\"       overridden by --data-root and SCTL_DATA_ROOT
  scenes = [\"biscuit\", ...]    scene names (default: all)
  split = \"test\"               hopef, synthetic: train | val | test
  categories = [1, 2]          hopef, synthetic: numbers of moving objects
  index_range = [900, 909]     inclusive scene indices (hopef folder number,
                               else position in the scene list)
  preset = \"quick\"             synthetic: quick | hopef-like | kitti-like | hopef
  generator_seed = 1           synthetic generator seed
  files = [\"pair.csv\"]         csv: match files (x1,y1,x2,y2[,label]; .txt:
                               x1 y1 x2 y2 [label]), relative to the data root
  width = 640                  csv: image size for every file (else each
  height = 480                 file's sidecar <file>.toml)

  [pipeline]                   (defaults: thesis Table 1 and text)
  method = \"semical\"           semical | baseline
  num_samples = 3000           M, minimal samples per scene
  mss_size = 8                 points per minimal sample
  thr_px = 2.5                 inlier threshold (px); tau = thr_px^2 (Eq. 38)
  tau_diff = 0.05              local test |f1-f2|/f_avg < tau_diff (Eq. 36)
  tau_range = 0.2              band |f_avg-f_peak|/f_peak <= tau_range (Eq. 37)
  irls_iters = 5               IRLS-Tukey outer iterations
  irls_fit = \"normalized\"      IRLS refit: normalized | plain (reference code)
  irls_unit_weight_fallback = true   false: < 8 positive weights drop the hypothesis
  irls_sigma_offset_px = 0.0   sigma = 1.4826 MAD + offset (reference code: 1e-12)
  irls_polish = false          LM polish of each sample's F first (reference code)
  refine = true                false: raw minimal-sample F (ablation)
  eight_point = \"normalized\"   normalized | plain
  minimal_solver = \"eight-point\"   eight-point | seven-point | five-point (E at the
                               focal prior) | six-point-focal (shared unknown f)
  minimal_solutions = \"best\"   best (most matches within thr_px) | all
  focal_solver = \"kocur\"       kocur | bougnoux | external (read from focal_file)
  focal_file = \"f{seed}.csv\"   focal_solver = \"external\": CSV of scene,hypothesis,f1,f2
  weight_sets = \"adelaidermf\"  adelaidermf | hopef | [[w_f1, w_pp1, w_f2, w_pp2], ...]
  max_iters = 100              robust focal solver iterations
  focal_failure = \"report\"     report | prior (reference code)
  truncate_focals = false      truncate f1, f2 to integers (reference code)
  local_test = \"algorithm1\"    algorithm1 | reference-code
  linkage = \"t-linkage\"        t-linkage | j-linkage
  min_cluster_size = 8         smaller clusters become outliers
  seed = 12345                 sampling seed

  [sweep]                      any [pipeline] key as a list; the run is the
  method = [\"baseline\", \"semical\"]   cartesian product, in the order above

  [compare]
  against = { method = \"baseline\" }   reference of each Wilcoxon test

  [plots]                      figures, written under <run>/plots/
  enabled = true               run-level figures from per_scene.csv:
                               me_vs_num_samples (when num_samples is swept),
                               focal_error[__<params>] (semical with a known
                               focal), me_scatter[__<params>] (baseline and
                               semical both run)
  per_scene = false            <combination>/<scene>_clusters and (semical)
                               <scene>_focal_kde for every scene
  formats = [\"png\", \"svg\"]   png | svg
";

/// A configuration error: one line naming the file, the key and the line.
#[derive(Debug, Error)]
pub enum ConfigError {
    /// The file could not be read.
    #[error("{file}: cannot read: {source}")]
    Read {
        /// The file.
        file: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// TOML syntax error, unknown key or wrongly typed value.
    #[error("{file}{}: {key}: {message}", line.map(|l| format!(":{l}")).unwrap_or_default())]
    Invalid {
        /// The file.
        file: PathBuf,
        /// 1-based line of the offending text, when known.
        line: Option<usize>,
        /// Dotted key path, e.g. `pipeline.method`.
        key: String,
        /// What is wrong.
        message: String,
    },
}

impl ConfigError {
    fn invalid(file: &Path, key: impl Into<String>, message: impl Into<String>) -> Self {
        ConfigError::Invalid {
            file: file.to_path_buf(),
            line: None,
            key: key.into(),
            message: message.into(),
        }
    }

    fn with_line(self, text: &str, key_path: &str) -> Self {
        match self {
            ConfigError::Invalid {
                file,
                line: None,
                key,
                message,
            } => ConfigError::Invalid {
                file,
                line: find_key_line(text, key_path),
                key,
                message,
            },
            other => other,
        }
    }
}

/// 1-based line of the byte offset `pos` in `text`.
fn line_of(text: &str, pos: usize) -> usize {
    text[..pos.min(text.len())].matches('\n').count() + 1
}

/// Best-effort line of `section.key` in a TOML text: the first `key =` line
/// after the `[section]` header.
fn find_key_line(text: &str, key_path: &str) -> Option<usize> {
    let (section, key) = key_path.rsplit_once('.')?;
    let key = key.split('[').next()?;
    let mut in_section = false;
    for (i, line) in text.lines().enumerate() {
        let t = line.trim();
        if t.starts_with('[') {
            in_section = t.trim_start_matches('[').trim_end_matches(']').trim() == section;
            continue;
        }
        if in_section {
            if let Some((k, _)) = t.split_once('=') {
                if k.trim().trim_matches('"') == key {
                    return Some(i + 1);
                }
            }
        }
    }
    None
}

/// `text`'s non-empty lines, trimmed and joined by `; `.
fn one_line(text: &str) -> String {
    text.lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect::<Vec<_>>()
        .join("; ")
}

/// Deserializes `text` as `T`, reporting the key path and line of the first error.
pub fn parse_toml<T: serde::de::DeserializeOwned>(
    text: &str,
    file: &Path,
) -> Result<T, ConfigError> {
    let deserializer = toml::Deserializer::new(text);
    serde_path_to_error::deserialize(deserializer).map_err(|err| {
        let path = err.path().to_string();
        let inner = err.inner();
        let key = if path == "." || path.is_empty() {
            "(top level)".to_string()
        } else {
            path
        };
        ConfigError::Invalid {
            file: file.to_path_buf(),
            line: inner.span().map(|s| line_of(text, s.start)),
            key,
            message: one_line(inner.message()),
        }
    })
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
        let config: ExperimentConfig = parse_toml(text, file)?;
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

/// A file that gives `[pipeline]` parameters: an experiment file (its other
/// tables are ignored) or a file holding only a `[pipeline]` table.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct PipelineFile {
    #[serde(default)]
    pipeline: PipelineConfig,
    #[serde(default, rename = "name")]
    _name: Option<toml::Value>,
    #[serde(default, rename = "description")]
    _description: Option<toml::Value>,
    #[serde(default, rename = "dataset")]
    _dataset: Option<toml::Value>,
    #[serde(default, rename = "sweep")]
    _sweep: Option<toml::Value>,
    #[serde(default, rename = "compare")]
    _compare: Option<toml::Value>,
    #[serde(default, rename = "plots")]
    _plots: Option<toml::Value>,
}

impl PipelineConfig {
    /// Reads the `[pipeline]` table of a file (missing keys take their
    /// defaults) and checks it.
    pub fn load(path: &Path) -> Result<Self, ConfigError> {
        let text = std::fs::read_to_string(path).map_err(|source| ConfigError::Read {
            file: path.to_path_buf(),
            source,
        })?;
        let file: PipelineFile = parse_toml(&text, path)?;
        file.pipeline.validate().map_err(|e| {
            let key = format!("pipeline.{}", e.key);
            ConfigError::invalid(path, key.clone(), e.message).with_line(&text, &key)
        })?;
        Ok(file.pipeline)
    }
}

impl DatasetConfig {
    fn check(&self, file: &Path) -> Result<(), ConfigError> {
        let only_for = |key: &str, present: bool, kinds: &[DatasetKind]| {
            if present && !kinds.contains(&self.kind) {
                Err(ConfigError::invalid(
                    file,
                    format!("dataset.{key}"),
                    format!("does not apply to kind = \"{}\"", self.kind.name()),
                ))
            } else {
                Ok(())
            }
        };
        use DatasetKind::*;
        only_for("split", self.split.is_some(), &[Hopef, Synthetic])?;
        only_for("categories", self.categories.is_some(), &[Hopef, Synthetic])?;
        only_for("preset", self.preset.is_some(), &[Synthetic])?;
        only_for(
            "generator_seed",
            self.generator_seed.is_some(),
            &[Synthetic],
        )?;
        only_for("files", self.files.is_some(), &[Csv])?;
        only_for("width", self.width.is_some(), &[Csv])?;
        only_for("height", self.height.is_some(), &[Csv])?;
        if let Some([a, b]) = self.index_range {
            if a > b {
                return Err(ConfigError::invalid(
                    file,
                    "dataset.index_range",
                    format!("first index {a} is after last index {b}"),
                ));
            }
        }
        if let Some(cats) = &self.categories {
            if let Some(c) = cats.iter().find(|c| !(1..=4).contains(*c)) {
                return Err(ConfigError::invalid(
                    file,
                    "dataset.categories",
                    format!("category {c} is not a number of motions in 1..=4"),
                ));
            }
        }
        if self.kind == Csv {
            if self.files.as_ref().map_or(0, Vec::len) == 0 {
                return Err(ConfigError::invalid(
                    file,
                    "dataset.files",
                    "kind = \"csv\" needs a non-empty list of match files",
                ));
            }
            if self.width.is_some() != self.height.is_some() {
                return Err(ConfigError::invalid(
                    file,
                    if self.width.is_some() {
                        "dataset.height"
                    } else {
                        "dataset.width"
                    },
                    "give both width and height (or neither, and a sidecar TOML per file)",
                ));
            }
            if self.width == Some(0) || self.height == Some(0) {
                return Err(ConfigError::invalid(
                    file,
                    if self.width == Some(0) {
                        "dataset.width"
                    } else {
                        "dataset.height"
                    },
                    "must be > 0 pixels",
                ));
            }
        }
        Ok(())
    }
}

impl DatasetKind {
    /// The name used in configs.
    pub fn name(self) -> &'static str {
        match self {
            DatasetKind::Adelaidermf => "adelaidermf",
            DatasetKind::Hopef => "hopef",
            DatasetKind::Synthetic => "synthetic",
            DatasetKind::Csv => "csv",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<ExperimentConfig, ConfigError> {
        ExperimentConfig::parse(text, Path::new("exp.toml"))
    }

    const BASE: &str = "name = \"t\"\n[dataset]\nkind = \"synthetic\"\n";

    #[test]
    fn pipeline_keys_follow_the_declaration_order() {
        // focal_file is left out when empty: give it a value.
        let config = PipelineConfig {
            focal_file: "f.csv".into(),
            ..Default::default()
        };
        let table = toml::Table::try_from(config.clone()).unwrap();
        let mut keys: Vec<&str> = table.keys().map(String::as_str).collect();
        let mut expected = PIPELINE_KEYS.to_vec();
        keys.sort();
        expected.sort();
        assert_eq!(keys, expected);
        // serde serializes in declaration order; toml's Table sorts, so check
        // the declaration order through the serialized text instead.
        let text = toml::to_string(&config).unwrap();
        let order: Vec<&str> = text
            .lines()
            .filter_map(|l| l.split_once(" = ").map(|(k, _)| k))
            .collect();
        assert_eq!(order, PIPELINE_KEYS.to_vec());
    }

    #[test]
    fn defaults_are_table_1() {
        let c = parse(BASE).unwrap();
        let p = &c.pipeline;
        assert_eq!(
            (
                p.num_samples,
                p.mss_size,
                p.thr_px,
                p.tau_diff,
                p.tau_range,
                p.irls_iters
            ),
            (3000, 8, 2.5, 0.05, 0.20, 5)
        );
        assert_eq!(p.method, Method::Semical);
        assert_eq!(c.compare.against, default_against());
        assert!(c.plots.enabled && !c.plots.per_scene);
    }

    #[test]
    fn unknown_pipeline_key_names_file_key_and_line() {
        let err = parse(&format!("{BASE}[pipeline]\nnum_samples = 10\nthr = 3\n")).unwrap_err();
        let msg = err.to_string();
        assert!(
            msg.starts_with("exp.toml:6: pipeline.thr: unknown field `thr`"),
            "{msg}"
        );
        assert!(!msg.contains('\n'), "{msg}");
    }

    #[test]
    fn bad_enum_value_names_the_key() {
        let err = parse(&format!("{BASE}[pipeline]\nmethod = \"semcal\"\n")).unwrap_err();
        let msg = err.to_string();
        assert!(
            msg.starts_with("exp.toml:5: pipeline.method: unknown variant `semcal`"),
            "{msg}"
        );
    }

    #[test]
    fn out_of_range_value_names_the_key_and_line() {
        let err = parse(&format!("{BASE}[pipeline]\n\ntau_range = -0.1\n")).unwrap_err();
        assert_eq!(
            err.to_string(),
            "exp.toml:6: pipeline.tau_range: must be a finite number > 0, got -0.1"
        );
    }

    #[test]
    fn weight_sets_accept_presets_and_lists() {
        let c = parse(&format!("{BASE}[pipeline]\nweight_sets = \"hopef\"\n")).unwrap();
        assert_eq!(c.pipeline.weight_sets.sets().len(), 6);
        let c = parse(&format!(
            "{BASE}[pipeline]\nweight_sets = [[1e-3, 1, 1e-3, 1]]\n"
        ))
        .unwrap();
        assert_eq!(
            c.pipeline.weight_sets.sets(),
            vec![focal::FocalWeights::new(1e-3, 1.0, 1e-3, 1.0)]
        );
        let err = parse(&format!("{BASE}[pipeline]\nweight_sets = \"kitti\"\n")).unwrap_err();
        assert!(err.to_string().contains("pipeline.weight_sets"), "{err}");
        let err = parse(&format!("{BASE}[pipeline]\nweight_sets = [[0, 1, 1, 1]]\n")).unwrap_err();
        assert!(err.to_string().contains("every weight must be"), "{err}");
    }

    #[test]
    fn dataset_keys_are_checked_against_the_kind() {
        let err = parse("name = \"t\"\n[dataset]\nkind = \"adelaidermf\"\nsplit = \"test\"\n")
            .unwrap_err();
        assert_eq!(
            err.to_string(),
            "exp.toml:4: dataset.split: does not apply to kind = \"adelaidermf\""
        );
        let err =
            parse("name = \"t\"\n[dataset]\nkind = \"csv\"\nfiles = [\"a.csv\"]\nwidth = 5\n")
                .unwrap_err();
        assert!(
            err.to_string().contains("dataset.height: give both"),
            "{err}"
        );
        let err = parse("name = \"t\"\n[dataset]\nkind = \"csv\"\n").unwrap_err();
        assert!(err.to_string().contains("dataset.files"), "{err}");
    }

    #[test]
    fn bad_name_and_missing_dataset_are_errors() {
        let err = parse("name = \"a/b\"\n[dataset]\nkind = \"synthetic\"\n").unwrap_err();
        assert!(
            err.to_string()
                .contains("name: `a/b` is not a valid run name"),
            "{err}"
        );
        let err = parse("name = \"a\"\n").unwrap_err();
        assert!(err.to_string().contains("missing field `dataset`"), "{err}");
    }

    #[test]
    fn help_lists_every_key() {
        let dataset = toml::Table::try_from(DatasetConfig {
            kind: DatasetKind::Csv,
            data_root: Some("r".into()),
            scenes: Some(vec![]),
            split: Some(Split::Test),
            categories: Some(vec![1]),
            index_range: Some([0, 1]),
            preset: Some("quick".into()),
            generator_seed: Some(1),
            files: Some(vec![]),
            width: Some(1),
            height: Some(1),
        })
        .unwrap();
        let plots = toml::Table::try_from(PlotsConfig::default()).unwrap();
        let keys = PIPELINE_KEYS
            .iter()
            .map(|k| k.to_string())
            .chain(dataset.keys().cloned())
            .chain(plots.keys().cloned());
        for key in keys {
            assert!(
                CONFIG_KEYS_HELP.contains(&format!("\n  {key} = ")),
                "{key} is not documented"
            );
        }
    }

    #[test]
    fn help_lists_every_synthetic_preset_and_no_other() {
        let line = CONFIG_KEYS_HELP
            .lines()
            .find(|l| l.trim_start().starts_with("preset = "))
            .expect("the preset line");
        let listed: Vec<&str> = line
            .split_once("synthetic:")
            .expect("the preset line names its choices")
            .1
            .split('|')
            .map(str::trim)
            .collect();
        let mut known: Vec<&str> = datasets::synthetic::Preset::ALL
            .iter()
            .map(|p| p.name())
            .collect();
        let mut sorted = listed.clone();
        sorted.sort_unstable();
        known.sort_unstable();
        assert_eq!(sorted, known, "help lists {listed:?}");
    }

    #[test]
    fn pipeline_file_reads_the_pipeline_table_of_any_config() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("p.toml");
        std::fs::write(
            &path,
            format!("{BASE}[pipeline]\nthr_px = 4.5\n[sweep]\nseed = [1, 2]\n"),
        )
        .unwrap();
        assert_eq!(PipelineConfig::load(&path).unwrap().thr_px, 4.5);
        std::fs::write(&path, "[pipeline]\nmethod = \"baseline\"\n").unwrap();
        assert_eq!(
            PipelineConfig::load(&path).unwrap().method,
            Method::Baseline
        );
        std::fs::write(&path, "[pipline]\nmethod = \"baseline\"\n").unwrap();
        let err = PipelineConfig::load(&path).unwrap_err().to_string();
        assert!(
            err.contains("p.toml:1: pipline: unknown field `pipline`"),
            "{err}"
        );
        std::fs::write(&path, "[pipeline]\n\nthr_px = 0\n").unwrap();
        let err = PipelineConfig::load(&path).unwrap_err().to_string();
        assert!(
            err.ends_with("p.toml:3: pipeline.thr_px: must be a finite number > 0, got 0"),
            "{err}"
        );
    }

    #[test]
    fn resolved_config_round_trips() {
        let c = parse(&format!(
            "{BASE}[pipeline]\nnum_samples = 100\n[sweep]\nmethod = [\"baseline\", \"semical\"]\n"
        ))
        .unwrap();
        let again = parse(&c.to_toml()).unwrap();
        assert_eq!(c, again);
    }
}
