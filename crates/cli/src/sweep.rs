//! Sweep expansion: the `[sweep]` lists of an experiment become the
//! cartesian product of parameter combinations, in a fixed order.
//!
//! Order: the swept keys in [`PIPELINE_KEYS`] order, the first one varying
//! slowest, each key's values in the order the file lists them. The reported
//! parameter columns are the swept keys, with `method` always present (first).

use crate::config::{ConfigError, ExperimentConfig, PipelineConfig, PIPELINE_KEYS};
use std::path::Path;

/// One point of the sweep: its parameter values as reported in the output
/// files and the resolved pipeline configuration.
#[derive(Debug, Clone, PartialEq)]
pub struct Combination {
    /// Position in [`SweepPlan::combinations`].
    pub index: usize,
    /// One canonical value string per [`SweepPlan::columns`] entry.
    pub values: Vec<String>,
    /// Every parameter of this combination.
    pub pipeline: PipelineConfig,
}

/// The expanded sweep of an experiment.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepPlan {
    /// The parameter columns of every output file: `method`, then the other
    /// swept keys, in [`PIPELINE_KEYS`] order.
    pub columns: Vec<String>,
    /// Every combination, in run order.
    pub combinations: Vec<Combination>,
}

/// A problem in `[sweep]` or `[compare]`.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepError {
    /// Dotted key, e.g. `sweep.num_samples[2]`.
    pub key: String,
    /// What is wrong.
    pub message: String,
}

impl SweepError {
    /// As a [`ConfigError`] naming `file`.
    pub fn into_config_error(self, file: &Path) -> ConfigError {
        ConfigError::Invalid {
            file: file.to_path_buf(),
            line: None,
            key: self.key,
            message: self.message,
        }
    }
}

/// Canonical text of a parameter value in the output files: strings as they
/// are, numbers in Rust's shortest round-trip form, lists as `[a; b]`.
pub fn format_value(value: &toml::Value) -> String {
    match value {
        toml::Value::String(s) => s.clone(),
        toml::Value::Integer(i) => i.to_string(),
        toml::Value::Float(f) => f.to_string(),
        toml::Value::Boolean(b) => b.to_string(),
        toml::Value::Datetime(d) => d.to_string(),
        toml::Value::Array(items) => {
            let inner: Vec<String> = items.iter().map(format_value).collect();
            format!("[{}]", inner.join("; "))
        }
        toml::Value::Table(t) => {
            let inner: Vec<String> = t
                .iter()
                .map(|(k, v)| format!("{k}={}", format_value(v)))
                .collect();
            format!("{{{}}}", inner.join("; "))
        }
    }
}

/// `base` with `overrides` applied, checked as a [`PipelineConfig`].
fn pipeline_with(
    base: &toml::Table,
    overrides: &[(&str, &toml::Value)],
) -> Result<PipelineConfig, String> {
    let mut table = base.clone();
    for (key, value) in overrides {
        table.insert((*key).to_string(), (*value).clone());
    }
    let config: PipelineConfig = toml::Value::Table(table)
        .try_into()
        .map_err(|e: toml::de::Error| e.message().trim().replace('\n', "; "))?;
    config
        .validate()
        .map_err(|e| format!("{} {}", e.key, e.message))?;
    Ok(config)
}

impl SweepPlan {
    /// Expands the `[sweep]` lists of `config` over its `[pipeline]` table and
    /// checks `[compare] against`.
    pub fn expand(config: &ExperimentConfig) -> Result<SweepPlan, SweepError> {
        let base = config.pipeline_table();
        let swept = swept_lists(config, &base)?;
        let method_swept = swept.first().is_some_and(|(k, _)| *k == "method");
        let mut columns: Vec<String> = Vec::new();
        if !method_swept {
            columns.push("method".into());
        }
        columns.extend(swept.iter().map(|(k, _)| (*k).to_string()));

        let points = cartesian_product(&swept);
        let mut combinations = Vec::with_capacity(points.len());
        for (index, point) in points.into_iter().enumerate() {
            let overrides: Vec<(&str, &toml::Value)> = swept
                .iter()
                .map(|(k, _)| *k)
                .zip(point.iter().copied())
                .collect();
            let pipeline = pipeline_with(&base, &overrides).map_err(|message| SweepError {
                key: "sweep".into(),
                message: format!("combination {index}: {message}"),
            })?;
            let mut values: Vec<String> = Vec::with_capacity(columns.len());
            if !method_swept {
                values.push(method_name(&pipeline));
            }
            values.extend(point.iter().map(|v| format_value(v)));
            combinations.push(Combination {
                index,
                values,
                pipeline,
            });
        }
        let plan = SweepPlan {
            columns,
            combinations,
        };
        plan.check_against(&config.compare.against, &base)?;
        Ok(plan)
    }

    fn check_against(&self, against: &toml::Table, base: &toml::Table) -> Result<(), SweepError> {
        refuse_profile("compare.against", against)?;
        for (key, value) in against {
            if !PIPELINE_KEYS.contains(&key.as_str()) {
                return Err(SweepError {
                    key: format!("compare.against.{key}"),
                    message: format!("unknown pipeline parameter `{key}`"),
                });
            }
            pipeline_with(base, &[(key.as_str(), value)]).map_err(|message| SweepError {
                key: format!("compare.against.{key}"),
                message,
            })?;
        }
        Ok(())
    }

    /// The index of the reference combination of `combination`: the one
    /// whose parameters equal `combination`'s with `against` applied. `None`
    /// when that is `combination` itself or is not part of the run.
    pub fn reference_of(&self, combination: usize, against: &toml::Table) -> Option<usize> {
        let own = &self.combinations[combination].pipeline;
        let mut table = toml::Table::try_from(own).ok()?;
        for (key, value) in against {
            table.insert(key.clone(), value.clone());
        }
        let reference: PipelineConfig = toml::Value::Table(table).try_into().ok()?;
        if &reference == own {
            return None;
        }
        self.combinations
            .iter()
            .position(|c| c.pipeline == reference)
    }

    /// The `(column, value)` pairs of a combination, without the `skip` columns.
    pub fn params_of(&self, combination: usize, skip: &[&str]) -> Vec<(&str, &str)> {
        self.columns
            .iter()
            .zip(&self.combinations[combination].values)
            .filter(|(k, _)| !skip.contains(&k.as_str()))
            .map(|(k, v)| (k.as_str(), v.as_str()))
            .collect()
    }

    /// Human-readable label of a combination: `key=value` pairs.
    pub fn label(&self, combination: usize) -> String {
        self.columns
            .iter()
            .zip(&self.combinations[combination].values)
            .map(|(k, v)| format!("{k}={v}"))
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// The combination whose column values are `values`.
    pub fn find(&self, values: &[String]) -> Option<usize> {
        self.combinations.iter().position(|c| c.values == values)
    }
}

fn method_name(pipeline: &PipelineConfig) -> String {
    format_value(&toml::Value::try_from(pipeline.params.focal.method).expect("method serializes"))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn plan(extra: &str) -> Result<SweepPlan, ConfigError> {
        let text = format!("name = \"t\"\n[dataset]\nkind = \"synthetic\"\n{extra}");
        let config = ExperimentConfig::parse(&text, Path::new("s.toml"))?;
        Ok(SweepPlan::expand(&config).unwrap())
    }

    #[test]
    fn nothing_swept_still_reports_method() {
        let p = plan("[pipeline]\nmethod = \"baseline\"\n").unwrap();
        assert_eq!(p.columns, ["method"]);
        assert_eq!(p.combinations.len(), 1);
        assert_eq!(p.combinations[0].values, ["baseline"]);
    }

    #[test]
    fn product_order_follows_pipeline_keys_not_file_order() {
        let p = plan(
            "[sweep]\nrefine = [true, false]\ntau_range = [0.1, 0.25]\nmethod = [\"semical\"]\n",
        )
        .unwrap();
        assert_eq!(p.columns, ["method", "tau_range", "refine"]);
        let got: Vec<String> = p.combinations.iter().map(|c| c.values.join(",")).collect();
        assert_eq!(
            got,
            [
                "semical,0.1,true",
                "semical,0.1,false",
                "semical,0.25,true",
                "semical,0.25,false"
            ]
        );
        assert_eq!(p.combinations[3].pipeline.params.focal.tau_range, 0.25);
        assert!(!p.combinations[3].pipeline.params.refinement.refine);
    }

    #[test]
    fn method_not_swept_comes_first() {
        let p = plan("[sweep]\nnum_samples = [100, 200]\n").unwrap();
        assert_eq!(p.columns, ["method", "num_samples"]);
        assert_eq!(p.combinations[1].values, ["baseline", "200"]);
        assert_eq!(p.combinations[1].pipeline.params.sampling.num_samples, 200);
    }

    #[test]
    fn bad_sweep_entries_name_the_element() {
        let err = plan("[sweep]\nnum_samples = [100, -3]\n")
            .unwrap_err()
            .to_string();
        assert!(err.starts_with("s.toml:5: sweep.num_samples[1]: "), "{err}");
        let err = plan("[sweep]\nnum_sample = [100]\n")
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("sweep.num_sample: unknown pipeline parameter"),
            "{err}"
        );
        let err = plan("[sweep]\nmethod = \"semical\"\n")
            .unwrap_err()
            .to_string();
        assert!(err.contains("sweep.method: must be a list"), "{err}");
        let err = plan("[sweep]\nseed = [1, 1]\n").unwrap_err().to_string();
        assert!(err.contains("sweep.seed: lists `1` twice"), "{err}");
        let err = plan("[sweep]\ntau_diff = [0.1, 0.0]\n")
            .unwrap_err()
            .to_string();
        assert!(err.contains("sweep.tau_diff[1]: tau_diff must be"), "{err}");
        let err = plan("[compare]\nagainst = { methd = \"baseline\" }\n")
            .unwrap_err()
            .to_string();
        assert!(err.contains("compare.against.methd"), "{err}");
    }

    #[test]
    fn profile_is_the_base_of_the_run_not_a_swept_key() {
        let err = plan("[sweep]\nprofile = [\"default\", \"fast\"]\n")
            .unwrap_err()
            .to_string();
        assert!(
            err.starts_with("s.toml:5: sweep.profile: `profile` applies to the whole run"),
            "{err}"
        );
        let err = plan("[compare]\nagainst = { profile = \"thesis\" }\n")
            .unwrap_err()
            .to_string();
        assert!(err.contains("compare.against.profile: `profile`"), "{err}");
        // Swept keys override the profile's values; `profile` is no column.
        let p =
            plan("[pipeline]\nprofile = \"thesis\"\n[sweep]\nnum_samples = [100, 200]\n").unwrap();
        assert_eq!(p.columns, ["method", "num_samples"]);
        assert_eq!(p.combinations[1].values, ["semical", "200"]);
        let thesis = segmentation::Params::thesis();
        for (c, m) in p.combinations.iter().zip([100, 200]) {
            assert_eq!(
                c.pipeline.params(),
                thesis.clone().with(|q| q.sampling.num_samples = m)
            );
        }
    }

    #[test]
    fn reference_combination_differs_only_in_against() {
        let p = plan("[sweep]\nmethod = [\"baseline\", \"semical\"]\nnum_samples = [100, 200]\n")
            .unwrap();
        let against = crate::config::CompareConfig::default().against;
        // semical,200 -> baseline,200
        assert_eq!(p.reference_of(3, &against), Some(1));
        assert_eq!(p.reference_of(2, &against), Some(0));
        assert_eq!(p.reference_of(0, &against), None);
        let single = plan("").unwrap();
        assert_eq!(single.reference_of(0, &against), None);
    }
}

/// A swept key and its values.
type Swept<'a> = (&'static str, &'a Vec<toml::Value>);

/// The lists of `[sweep]` in [`PIPELINE_KEYS`] order, each checked: a known
/// key, a non-empty list of distinct values each valid in `base`.
fn swept_lists<'a>(
    config: &'a ExperimentConfig,
    base: &toml::Table,
) -> Result<Vec<Swept<'a>>, SweepError> {
    refuse_profile("sweep", &config.sweep)?;
    if let Some(key) = config
        .sweep
        .keys()
        .find(|k| !PIPELINE_KEYS.contains(&k.as_str()))
    {
        return Err(SweepError {
            key: format!("sweep.{key}"),
            message: format!(
                "unknown pipeline parameter `{key}`, expected one of {}",
                PIPELINE_KEYS.join(", ")
            ),
        });
    }
    let mut swept: Vec<Swept<'_>> = Vec::new();
    for key in PIPELINE_KEYS {
        let Some(value) = config.sweep.get(key) else {
            continue;
        };
        let err = |message: String| SweepError {
            key: format!("sweep.{key}"),
            message,
        };
        let toml::Value::Array(values) = value else {
            return Err(err("must be a list of values".into()));
        };
        if values.is_empty() {
            return Err(err("must list at least one value".into()));
        }
        for (i, v) in values.iter().enumerate() {
            pipeline_with(base, &[(key, v)]).map_err(|message| SweepError {
                key: format!("sweep.{key}[{i}]"),
                message,
            })?;
            if values[..i].contains(v) {
                return Err(err(format!("lists `{}` twice", format_value(v))));
            }
        }
        swept.push((key, values));
    }
    Ok(swept)
}

/// Refuses `profile` in `table` (the table `section`): the profile is the
/// base of the whole run, read once with `[pipeline]`, not a parameter of a
/// combination.
fn refuse_profile(section: &str, table: &toml::Table) -> Result<(), SweepError> {
    if table.contains_key("profile") {
        return Err(SweepError {
            key: format!("{section}.profile"),
            message: "`profile` applies to the whole run and cannot vary between combinations: \
                      give it in [pipeline], then list here the keys whose values differ"
                .into(),
        });
    }
    Ok(())
}

/// Every combination of the swept values, the first swept key slowest.
fn cartesian_product<'a>(swept: &[Swept<'a>]) -> Vec<Vec<&'a toml::Value>> {
    let mut points: Vec<Vec<&toml::Value>> = vec![Vec::new()];
    for (_, values) in swept {
        points = points
            .into_iter()
            .flat_map(|prefix| {
                values.iter().map(move |v| {
                    let mut p = prefix.clone();
                    p.push(v);
                    p
                })
            })
            .collect();
    }
    points
}

/// The plan of a synthetic experiment whose `[sweep]` table holds the
/// lines `sweep` (for the tests of the modules that read plans).
#[cfg(test)]
pub(crate) fn plan_of_sweep(sweep: &str) -> SweepPlan {
    let text = format!("name = \"x\"\n[dataset]\nkind = \"synthetic\"\n[sweep]\n{sweep}");
    let config = ExperimentConfig::parse(&text, Path::new("x.toml")).unwrap();
    SweepPlan::expand(&config).unwrap()
}

/// The examples once in the documentation of this module's items.
#[cfg(test)]
mod examples {
    #[test]
    fn expand_example() {
        let plan = super::plan_of_sweep(
            "num_samples = [500, 1000]\nmethod = [\"baseline\", \"semical\"]\n",
        );
        assert_eq!(plan.columns, ["method", "num_samples"]);
        let rows: Vec<String> = plan
            .combinations
            .iter()
            .map(|c| c.values.join(" "))
            .collect();
        assert_eq!(
            rows,
            [
                "baseline 500",
                "baseline 1000",
                "semical 500",
                "semical 1000"
            ]
        );
    }
}
