//! The text of every key of an experiment file, for `sctl run --help`,
//! tested against the keys of the tables it documents.

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
  method = \"baseline\"          baseline (no focal filter) | semical (Algorithm 1)
  num_samples = 3000           M, minimal samples per scene (at most, adaptive)
  adaptive_batch = 0           > 0: draw M in batches of this many until a batch
                               gives fewer than adaptive_tolerance N points a
                               better-supported hypothesis (0: fixed M)
  adaptive_tolerance = 0.01    the adaptive stop rule's fraction of the points
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
  minimal_solver = \"five-point\"   five-point (E at the focal prior) | eight-point
                               | seven-point | six-point-focal (shared unknown f)
  minimal_solutions = \"best\"   best (most matches within thr_px) | all
                               | best-then-polish (best, five-point roots
                               scored before their polish: faster)
                               | best-unpolished (as best-then-polish,
                               the winner left unpolished)
  min_consensus = 0            solutions with fewer matches within thr_px are
                               dropped before refinement (not eight-point)
  preselect_matches = 0        K > 0: a sample's solutions scored on K random
                               matches first, the top ones on all (best*)
  sampling = \"uniform\"        uniform | localized (the others among the first
                               match's nearest in image 1: NAPSAC) | mixed
                               (the two in turn) | guided (mixed, then the
                               uniform turns drawn by the co-inlier counts
                               of the hypotheses so far: Multi-GS)
  guided_batch = 100           samples per batch of guided (the first: mixed)
  focal_solver = \"kocur\"       kocur | bougnoux | external (read from focal_file)
  focal_file = \"f{seed}.csv\"   focal_solver = \"external\": CSV of scene,hypothesis,f1,f2
  weight_sets = \"adelaidermf\"  adelaidermf | hopef | [[w_f1, w_pp1, w_f2, w_pp2], ...]
  max_iters = 100              robust focal solver iterations
  focal_failure = \"report\"     report | prior (reference code)
  truncate_focals = false      truncate f1, f2 to integers (reference code)
  local_test = \"algorithm1\"    algorithm1 | reference-code
  implausible_focal = \"filter\"   f_peak outside 0.3-3 x prior: filter | abstain
                               (keep every hypothesis: the baseline's labels)
  linkage = \"t-linkage\"        t-linkage | j-linkage
  min_cluster_size = 8         smaller clusters become outliers
  size_rule = \"min-size\"       min-size | largest-gap (cut the sorted sizes at the
                               largest ratio) | { relative-min = 0.01 } (>= f N points)
  final_assignment = \"merge\"  none (the thesis) | refit (IRLS refit of each cluster, then
                               each match to its nearest model within thr_px)
                               | merge (a cluster joins a larger one whose best
                               hypothesis explains 80 % of its matches)
                               | merge-refit (merge, then a cluster joins a larger
                               one when the F refitted on both explains 80 % of each)
                               | merge-anchored (the same, the refit started from the
                               larger cluster's model)
  duplicate_filter = \"none\"   none | same-inliers (one hypothesis per distinct
                               inlier set enters the preferences)
  cluster_subset = 0           > 0: steps 1-9 on this many random matches, the others
                               then join the nearest cluster
  subset_extension = \"preference-explained\"   how: preference-explained (nearest mean
                               preference vector, within thr_px of its cluster's model)
                               | preference | model (nearest cluster model)
                               | preference-refit | model-refit (the cluster models
                               refitted by IRLS on the clustered matches)
                               | neighbours (the label of most of its 5 nearest
                               clustered matches, within thr_px of its model)
  recover_outliers = \"none\"   none | refit (each cluster's F refitted by IRLS; an
                               outlier joins the cluster that explains it best)
  max_memory_mb = 0            > 0: refuse (at once) a scene whose clustering
                               would need more memory (MB); 0: refuse a
                               run needing more than the available memory
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
                profile: Profile::Fast,
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
