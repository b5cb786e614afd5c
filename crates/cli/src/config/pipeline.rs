//! The `[pipeline]` table: the parameters of Algorithm 1 ([`PipelineConfig`],
//! [`segmentation::Params`] with the harness's `profile` and `focal_file`)
//! and the files that give only them.

use super::{parse_toml, ConfigError};
use segmentation::{FocalSolver, ParamError, Params, Profile, PARAM_KEYS};
use serde::de::value::MapAccessDeserializer;
use serde::de::{DeserializeSeed, Deserializer, Error as _, IntoDeserializer, MapAccess, Visitor};
use serde::{Deserialize, Serialize};
use std::path::Path;
use std::sync::LazyLock;

/// The `[pipeline]` table of an experiment file: every parameter of
/// [`segmentation::Params`] under the same name, with the same default (see
/// the field docs there), `focal_file`, the harness's source of the
/// answers of `focal_solver = "external"`, and `profile`, the named set of
/// parameters ([`segmentation::Profile`]) that gives every key the table
/// does not ([`PipelineConfig::on_profile`]).
///
/// The table reads as one flat map: `profile` and `focal_file` are taken
/// out, an unknown key is refused with the list of every key of the table,
/// and every other key is read by `Params`'s own serde (its defaults, its
/// types), so the two cannot drift. Written back, it is `profile` (unless
/// default), `focal_file` (unless empty), then `Params`.
///
/// ```
/// let p: sctl::config::PipelineConfig = toml::from_str("num_samples = 500").unwrap();
/// assert_eq!(p.params.sampling.num_samples, 500);
/// assert_eq!(p.params.refinement.thr_px, 2.5); // Table 1
/// assert!(toml::from_str::<sctl::config::PipelineConfig>("num_sample = 5").is_err());
/// ```
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct PipelineConfig {
    /// The named parameter set whose values the keys this table does not
    /// give take: `default` ([`Params::default`]) or `thesis`
    /// ([`Params::thesis`]). Applied when a
    /// file is read ([`PipelineConfig::load`],
    /// [`super::ExperimentConfig::parse`]): `params` holds the resolved
    /// values. Not one of [`PIPELINE_KEYS`] (it cannot be swept).
    /// Default `default` (not serialised then).
    #[serde(skip_serializing_if = "is_default_profile")]
    pub profile: Profile,
    /// The CSV of `focal_solver = "external"` (see the `focal_file` module),
    /// relative to the working directory; `{seed}` is replaced by the seed.
    /// Answers are used as given (truncated when `truncate_focals`); a
    /// non-finite one leaves the hypothesis without focals. Default empty
    /// (not serialised when empty).
    #[serde(skip_serializing_if = "String::is_empty")]
    pub focal_file: String,
    /// The method's parameters; `seed` is the run's seed: scene `s` is
    /// segmented with the seed [`crate::pipeline::scene_seed`]`(seed, s)`,
    /// as in every committed result.
    #[serde(flatten)]
    pub params: Params,
}

impl<'de> Deserialize<'de> for PipelineConfig {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_map(PipelineVisitor)
    }
}

/// Reads a `[pipeline]` map: [`HarnessKeys`] takes `profile` and
/// `focal_file` out of it, `Params` reads the rest.
struct PipelineVisitor;

impl<'de> Visitor<'de> for PipelineVisitor {
    type Value = PipelineConfig;

    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str("a [pipeline] table")
    }

    fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<PipelineConfig, A::Error> {
        let mut keys = HarnessKeys {
            map,
            profile: Profile::Default,
            focal_file: String::new(),
        };
        let params = Params::deserialize(MapAccessDeserializer::new(&mut keys))?;
        Ok(PipelineConfig {
            profile: keys.profile,
            focal_file: keys.focal_file,
            params,
        })
    }
}

/// The map of a `[pipeline]` table as `Params` sees it: the harness's own
/// keys are read into their fields as they pass and never reach `Params`.
/// Every call goes through the underlying map, so a parse error keeps its
/// key path and line.
struct HarnessKeys<A> {
    map: A,
    profile: Profile,
    focal_file: String,
}

/// A key of a `[pipeline]` table: a harness key (the seed handed back,
/// unused) or a key of `Params`, read by `Params`'s seed.
enum PipelineKey<S, K> {
    Profile(S),
    FocalFile(S),
    Param(K),
}

/// Every key a `[pipeline]` table may hold, for the unknown-key error.
static TABLE_KEYS: LazyLock<Vec<&'static str>> =
    LazyLock::new(|| std::iter::once("profile").chain(PIPELINE_KEYS).collect());

/// Reads a key as a string, then either recognises a harness key, refuses
/// an unknown one (naming every key of the table), or hands it to
/// `Params`'s key seed.
struct PipelineKeySeed<S>(S);

impl<'de, S: DeserializeSeed<'de>> DeserializeSeed<'de> for PipelineKeySeed<S> {
    type Value = PipelineKey<S, S::Value>;

    fn deserialize<D: Deserializer<'de>>(self, deserializer: D) -> Result<Self::Value, D::Error> {
        let key = String::deserialize(deserializer)?;
        match key.as_str() {
            "profile" => Ok(PipelineKey::Profile(self.0)),
            "focal_file" => Ok(PipelineKey::FocalFile(self.0)),
            _ if !PIPELINE_KEYS.contains(&key.as_str()) => {
                Err(D::Error::unknown_field(&key, &TABLE_KEYS))
            }
            _ => self
                .0
                .deserialize(key.into_deserializer())
                .map(PipelineKey::Param),
        }
    }
}

impl<'de, A: MapAccess<'de>> MapAccess<'de> for &mut HarnessKeys<A> {
    type Error = A::Error;

    fn next_key_seed<K: DeserializeSeed<'de>>(
        &mut self,
        seed: K,
    ) -> Result<Option<K::Value>, A::Error> {
        let mut seed = seed;
        loop {
            match self.map.next_key_seed(PipelineKeySeed(seed))? {
                None => return Ok(None),
                Some(PipelineKey::Param(key)) => return Ok(Some(key)),
                Some(PipelineKey::Profile(unused)) => {
                    self.profile = self.map.next_value::<ProfileName>()?.0;
                    seed = unused;
                }
                Some(PipelineKey::FocalFile(unused)) => {
                    self.focal_file = self.map.next_value()?;
                    seed = unused;
                }
            }
        }
    }

    fn next_value_seed<V: DeserializeSeed<'de>>(&mut self, seed: V) -> Result<V::Value, A::Error> {
        self.map.next_value_seed(seed)
    }
}

/// The keys of [`PipelineConfig`] but `profile`: those of [`Params`] in
/// declaration order ([`segmentation::PARAM_KEYS`]), `focal_file` after
/// `focal_solver` — the order of the swept-parameter columns in every
/// output file.
pub const PIPELINE_KEYS: [&str; PARAM_KEYS.len() + 1] = with_focal_file(PARAM_KEYS);

/// `keys` with `"focal_file"` inserted after `"focal_solver"` (at the end
/// when there is none).
const fn with_focal_file<const N: usize, const M: usize>(
    keys: [&'static str; N],
) -> [&'static str; M] {
    let mut out = ["focal_file"; M];
    let (mut read, mut write) = (0, 0);
    while read < N {
        out[write] = keys[read];
        write += 1;
        if same_str(keys[read], "focal_solver") {
            write += 1; // out[write - 1] keeps "focal_file"
        }
        read += 1;
    }
    out
}

/// `a == b` at compile time.
const fn same_str(a: &str, b: &str) -> bool {
    let (a, b) = (a.as_bytes(), b.as_bytes());
    if a.len() != b.len() {
        return false;
    }
    let mut i = 0;
    while i < a.len() {
        if a[i] != b[i] {
            return false;
        }
        i += 1;
    }
    true
}

/// A profile read by name: an unknown or retired name is an error saying
/// so ([`Profile::unknown`]), located at the `profile` key.
struct ProfileName(Profile);

impl<'de> Deserialize<'de> for ProfileName {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let name = String::deserialize(deserializer)?;
        Profile::from_name(&name)
            .map(ProfileName)
            .ok_or_else(|| D::Error::custom(Profile::unknown(&name)))
    }
}

fn is_default_profile(profile: &Profile) -> bool {
    *profile == Profile::Default
}

impl PipelineConfig {
    /// The table of `params`, without a focal file, on the `default` profile.
    pub fn from_params(params: Params) -> Self {
        Self {
            params,
            ..Self::default()
        }
    }

    /// The method's parameters, with the run's seed.
    pub fn params(&self) -> Params {
        self.params.clone()
    }

    /// The method's parameters for the scene named `scene`: the seed is
    /// [`crate::pipeline::scene_seed`]`(seed, scene)`.
    pub fn scene_params(&self, scene: &str) -> Params {
        self.params().with(|q| {
            q.sampling.seed = crate::pipeline::scene_seed(self.params.sampling.seed, scene)
        })
    }

    /// Checks the ranges serde cannot ([`Params::validate`]) and that
    /// `focal_file` is given with `focal_solver = "external"`.
    pub fn validate(&self) -> Result<(), ParamError> {
        self.params().validate()?;
        if self.params.focal.focal_solver == FocalSolver::External && self.focal_file.is_empty() {
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
    /// use sctl::config::PipelineConfig;
    /// use segmentation::{Params, Profile};
    /// let given: toml::Table = toml::from_str("thr_px = 4.0").unwrap();
    /// let read: PipelineConfig = toml::from_str("thr_px = 4.0").unwrap();
    /// let p = read.on_profile(Profile::Thesis, &given).unwrap();
    /// assert_eq!(p.params(), Params::thesis().with(|q| q.refinement.thr_px = 4.0));
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
