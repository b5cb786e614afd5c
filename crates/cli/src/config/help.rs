//! The text of every key of an experiment file, for `sctl run --help`,
//! tested against the keys of the tables it documents; the `[pipeline]`
//! keys come from the key table ([`super::keys::pipeline_help`]).

use std::sync::LazyLock;

/// Every key of an experiment file, for `sctl run --help`.
pub static CONFIG_KEYS_HELP: LazyLock<String> =
    LazyLock::new(|| format!("{HEAD}{}{TAIL}", super::keys::pipeline_help()));

/// The help before the `[pipeline]` keys.
const HEAD: &str = "\
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
  preset = \"quick\"             synthetic: quick | hopef-like | kitti-like | hopef | kitti-real | adelaide-like | driving-random | objects-3d
  generator_seed = 1           synthetic generator seed
  files = [\"pair.csv\"]         csv: match files (x1,y1,x2,y2[,label]; .txt:
                               x1 y1 x2 y2 [label]), relative to the data root
  width = 640                  csv: image size for every file (else each
  height = 480                 file's sidecar <file>.toml)

  [pipeline]                   (defaults: the best measured configuration, 5-point
                               hypotheses at the focal prior without the focal
                               filter; the thesis text: method = \"semical\",
                               minimal_solver = \"eight-point\"; Table 1 values)
  profile = \"default\"          default | thesis | fast | large: the values of every key
                               not given here (default: those below; thesis:
                               the thesis text's; fast: fewer samples and IRLS
                               iterations, guided sampling, 200 matches
                               clustered; large: localized sampling, clusters
                               under 2 % of N dropped). Not a [sweep] key
";

/// The help after the `[pipeline]` keys.
const TAIL: &str = "
  [sweep]                      any [pipeline] key as a list; the run is the
  method = [\"baseline\", \"semical\"]   cartesian product, in the key table's order

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

#[cfg(test)]
mod tests {
    use super::super::*;
    use std::collections::{BTreeMap, BTreeSet};

    /// The `key = ` lines of the help text by section (`""` for the top
    /// level): two spaces, the key, ` = `.
    fn documented_keys() -> BTreeMap<String, BTreeSet<String>> {
        let mut keys: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
        let mut section = String::new();
        for line in CONFIG_KEYS_HELP.lines() {
            if line.starts_with("   ") && !line.starts_with("    ") {
                continue; // the reference-code line's continuation
            }
            let Some(rest) = line.strip_prefix("  ") else {
                continue;
            };
            if rest.starts_with(' ') {
                continue; // a continuation line
            }
            if let Some(name) = rest.strip_prefix('[') {
                section = name.split(']').next().unwrap().to_string();
                keys.entry(section.clone()).or_default();
            } else if let Some((key, _)) = rest.split_once(" = ") {
                keys.entry(section.clone())
                    .or_default()
                    .insert(key.to_string());
            }
        }
        keys
    }

    /// An experiment file with every optional key given, serialised: the
    /// keys serde reads, by section.
    fn serde_keys() -> BTreeMap<String, BTreeSet<String>> {
        let config = ExperimentConfig {
            name: "n".into(),
            description: Some("d".into()),
            dataset: DatasetConfig {
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
            },
            pipeline: PipelineConfig {
                profile: Profile::Thesis,
                focal_file: "f.csv".into(),
                ..PipelineConfig::default()
            },
            sweep: toml::Table::new(),
            compare: CompareConfig::default(),
            plots: PlotsConfig::default(),
        };
        let mut keys: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
        for (key, value) in toml::Table::try_from(&config).unwrap() {
            match value {
                toml::Value::Table(table) => {
                    keys.entry(key).or_default().extend(table.keys().cloned())
                }
                _ => {
                    keys.entry(String::new()).or_default().insert(key);
                }
            }
        }
        keys
    }

    #[test]
    fn help_documents_exactly_the_keys_serde_reads() {
        let mut documented = documented_keys();
        let mut read = serde_keys();
        // The reference code's variants are named on one line.
        let reference = segmentation::KEYS
            .iter()
            .filter(|k| k.stage == segmentation::Stage::ReferenceCode);
        for key in reference {
            assert!(CONFIG_KEYS_HELP.contains(key.name), "{}", key.name);
            documented
                .get_mut("pipeline")
                .unwrap()
                .insert(key.name.to_string());
        }
        // `[sweep]` takes any [pipeline] key: the help shows one example.
        let sweep = documented.remove("sweep").expect("a [sweep] section");
        assert!(!sweep.is_empty(), "no [sweep] example");
        for key in &sweep {
            assert!(PIPELINE_KEYS.contains(&key.as_str()), "[sweep] {key}");
        }
        assert_eq!(read.remove("sweep"), Some(BTreeSet::new()));
        assert_eq!(documented, read, "help (left) against serde (right)");
    }

    #[test]
    fn pipeline_keys_are_the_method_parameters_and_the_focal_file() {
        let mut expected: Vec<&str> = segmentation::PARAM_KEYS.to_vec();
        let solver = expected.iter().position(|k| *k == "focal_solver").unwrap();
        expected.insert(solver + 1, "focal_file");
        assert_eq!(PIPELINE_KEYS.to_vec(), expected);
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
}
