//! The `[pipeline]` table: the parameters of Algorithm 1 ([`PipelineConfig`],
//! mirroring [`segmentation::Params`]) and the files that give only them.

use super::{parse_toml, ConfigError};
use segmentation::{
    DuplicateFilter, EightPoint, FinalAssignment, FocalSolver, ImplausibleFocal, IrlsFit, Linkage,
    LocalTest, Method, MinimalSolutions, MinimalSolver, OnFailure, ParamError, Params, Profile,
    Sampling, SizeRule, WeightSets,
};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// The `[pipeline]` table of an experiment file: every parameter of
/// [`segmentation::Params`] under the same name, with the same default (see
/// the field docs there), `focal_file`, the harness's source of the
/// answers of `focal_solver = "external"`, and `profile`, the named set of
/// parameters ([`segmentation::Profile`]) that gives every key the table
/// does not ([`PipelineConfig::on_profile`]).
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
    /// The named parameter set whose values the keys this table does not
    /// give take: `default` ([`Params::default`]), `thesis`
    /// ([`Params::thesis`]), `fast` ([`Params::fast`]) or `large`
    /// ([`Params::large`]). Applied when a
    /// file is read ([`PipelineConfig::load`],
    /// [`super::ExperimentConfig::parse`]): the other fields hold the
    /// resolved values. Not one of [`PIPELINE_KEYS`] (it cannot be swept).
    /// Default `default` (not serialised then).
    #[serde(skip_serializing_if = "is_default_profile")]
    pub profile: Profile,
    pub method: Method,
    pub num_samples: usize,
    pub adaptive_batch: usize,
    pub adaptive_tolerance: f64,
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
    pub sampling: Sampling,
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
    pub implausible_focal: ImplausibleFocal,
    pub linkage: Linkage,
    pub min_cluster_size: usize,
    pub size_rule: SizeRule,
    pub final_assignment: FinalAssignment,
    pub duplicate_filter: DuplicateFilter,
    pub max_memory_mb: u64,
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
pub const PIPELINE_KEYS: [&str; 33] = [
    "method",
    "num_samples",
    "adaptive_batch",
    "adaptive_tolerance",
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
    "sampling",
    "focal_solver",
    "focal_file",
    "weight_sets",
    "max_iters",
    "focal_failure",
    "truncate_focals",
    "local_test",
    "implausible_focal",
    "linkage",
    "min_cluster_size",
    "size_rule",
    "final_assignment",
    "duplicate_filter",
    "max_memory_mb",
    "seed",
];

fn is_default_profile(profile: &Profile) -> bool {
    *profile == Profile::Default
}

impl PipelineConfig {
    /// The table of `params`, without a focal file, on the `default` profile.
    pub fn from_params(p: Params) -> Self {
        Self {
            profile: Profile::Default,
            method: p.method,
            num_samples: p.num_samples,
            adaptive_batch: p.adaptive_batch,
            adaptive_tolerance: p.adaptive_tolerance,
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
            sampling: p.sampling,
            focal_solver: p.focal_solver,
            focal_file: String::new(),
            weight_sets: p.weight_sets,
            max_iters: p.max_iters,
            focal_failure: p.focal_failure,
            truncate_focals: p.truncate_focals,
            local_test: p.local_test,
            implausible_focal: p.implausible_focal,
            linkage: p.linkage,
            min_cluster_size: p.min_cluster_size,
            size_rule: p.size_rule,
            final_assignment: p.final_assignment,
            duplicate_filter: p.duplicate_filter,
            max_memory_mb: p.max_memory_mb,
            seed: p.seed,
        }
    }

    /// The method's parameters, with the run's seed.
    pub fn params(&self) -> Params {
        Params {
            method: self.method,
            num_samples: self.num_samples,
            adaptive_batch: self.adaptive_batch,
            adaptive_tolerance: self.adaptive_tolerance,
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
            sampling: self.sampling,
            focal_solver: self.focal_solver,
            weight_sets: self.weight_sets.clone(),
            max_iters: self.max_iters,
            focal_failure: self.focal_failure,
            truncate_focals: self.truncate_focals,
            local_test: self.local_test,
            implausible_focal: self.implausible_focal,
            linkage: self.linkage,
            min_cluster_size: self.min_cluster_size,
            size_rule: self.size_rule,
            final_assignment: self.final_assignment,
            duplicate_filter: self.duplicate_filter,
            max_memory_mb: self.max_memory_mb,
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

impl PipelineConfig {
    /// The table of a profile: its parameters, on that profile.
    pub fn of_profile(profile: Profile) -> Self {
        Self {
            profile,
            ..Self::from_params(profile.params())
        }
    }

    /// `self`, as read from a `[pipeline]` table that gives the keys of
    /// `given`, on the base `profile` instead of [`Params::default`]: the
    /// keys of `given` keep their values in `self`, every other key takes
    /// `profile`'s ([`Profile::params`]). The error is serde's message.
    ///
    /// ```
    /// use bench::config::PipelineConfig;
    /// use segmentation::{Params, Profile};
    /// let given: toml::Table = toml::from_str("thr_px = 4.0").unwrap();
    /// let read: PipelineConfig = toml::from_str("thr_px = 4.0").unwrap();
    /// let p = read.on_profile(Profile::Thesis, &given).unwrap();
    /// assert_eq!(p.params(), Params { thr_px: 4.0, ..Params::thesis() });
    /// assert_eq!(p.profile, Profile::Thesis);
    /// ```
    pub fn on_profile(&self, profile: Profile, given: &toml::Table) -> Result<Self, String> {
        let own = toml::Table::try_from(self).map_err(|e| e.to_string())?;
        let mut table =
            toml::Table::try_from(Self::of_profile(profile)).map_err(|e| e.to_string())?;
        for key in given.keys() {
            match own.get(key) {
                Some(value) => table.insert(key.clone(), value.clone()),
                None => table.remove(key),
            };
        }
        let resolved: Self = toml::Value::Table(table)
            .try_into()
            .map_err(|e: toml::de::Error| e.message().trim().replace('\n', "; "))?;
        Ok(Self {
            profile,
            ..resolved
        })
    }

    /// `self`, read from the `[pipeline]` table of `text` (the file `file`),
    /// on its profile: `profile` when given (e.g. by the command line), else
    /// the table's own `profile` key.
    pub(super) fn resolve_profile(
        self,
        profile: Option<Profile>,
        text: &str,
        file: &Path,
    ) -> Result<Self, ConfigError> {
        let profile = profile.unwrap_or(self.profile);
        if profile == Profile::Default {
            // The serde defaults are the default profile's.
            return Ok(Self { profile, ..self });
        }
        let table: toml::Table = text.parse().map_err(|e: toml::de::Error| {
            ConfigError::invalid(file, "(top level)", e.message().trim())
        })?;
        let empty = toml::Table::new();
        let given = table
            .get("pipeline")
            .and_then(toml::Value::as_table)
            .unwrap_or(&empty);
        self.on_profile(profile, given).map_err(|message| {
            ConfigError::invalid(file, "pipeline.profile", message)
                .with_line(text, "pipeline.profile")
        })
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
    /// Reads the `[pipeline]` table of a file (missing keys take the values
    /// of its `profile`) and checks it.
    pub fn load(path: &Path) -> Result<Self, ConfigError> {
        Self::load_with_profile(path, None)
    }

    /// As [`PipelineConfig::load`], on `profile` instead of the file's own
    /// `profile` key when given: the keys the file gives still override it.
    pub fn load_with_profile(path: &Path, profile: Option<Profile>) -> Result<Self, ConfigError> {
        let text = std::fs::read_to_string(path).map_err(|source| ConfigError::Read {
            file: path.to_path_buf(),
            source,
        })?;
        let file: PipelineFile = parse_toml(&text, path)?;
        let pipeline = file.pipeline.resolve_profile(profile, &text, path)?;
        pipeline.validate().map_err(|e| {
            let key = format!("pipeline.{}", e.key);
            ConfigError::invalid(path, key.clone(), e.message).with_line(&text, &key)
        })?;
        Ok(pipeline)
    }
}
