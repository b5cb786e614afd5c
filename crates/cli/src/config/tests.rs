//! Tests of the experiment-file parsing: defaults, errors with line numbers.

use super::tables::default_against;
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
    // the declaration order through the serialized text instead: the
    // harness's focal_file first, then Params's keys in PIPELINE_KEYS order.
    let text = toml::to_string(&config).unwrap();
    let order: Vec<&str> = text
        .lines()
        .filter_map(|l| l.split_once(" = ").map(|(k, _)| k))
        .collect();
    let params_keys = PIPELINE_KEYS.iter().filter(|&&k| k != "focal_file");
    let expected: Vec<&str> = std::iter::once("focal_file")
        .chain(params_keys.copied())
        .collect();
    assert_eq!(order, expected);
}

#[test]
fn defaults_are_the_default_profile_and_table_1_the_thesis() {
    let c = parse(BASE).unwrap();
    let p = &c.pipeline;
    assert_eq!(
        (
            p.params.sampling.num_samples,
            p.params.sampling.mss_size,
            p.params.refinement.thr_px,
            p.params.focal.tau_diff,
            p.params.focal.tau_range,
            p.params.refinement.irls_iters
        ),
        (1000, 8, 2.5, 0.05, 0.20, 1)
    );
    // Table 1's M and IRLS iterations are the thesis profile's.
    let t = Params::thesis();
    assert_eq!((t.sampling.num_samples, t.refinement.irls_iters), (3000, 5));
    // The default: five-point hypotheses, no filter.
    assert_eq!(p.params.focal.method, Method::Baseline);
    assert_eq!(
        p.params.sampling.minimal_solver,
        segmentation::MinimalSolver::FivePoint
    );
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
fn sampling_and_final_assignment_read_and_reject_bad_values() {
    let c = parse(BASE).unwrap();
    assert_eq!(
        c.pipeline.params.sampling.sampling,
        segmentation::Sampling::Guided
    );
    assert_eq!(
        c.pipeline.params.selection.final_assignment,
        segmentation::FinalAssignment::Nfa
    );
    let c = parse(&format!(
        "{BASE}[pipeline]\nsampling = \"localized\"\nfinal_assignment = \"none\"\n"
    ))
    .unwrap();
    let p = c.pipeline.params();
    assert_eq!(p.sampling.sampling, segmentation::Sampling::Localized);
    assert_eq!(
        p.selection.final_assignment,
        segmentation::FinalAssignment::None
    );
    assert_eq!(PipelineConfig::from_params(p), c.pipeline);
    // Values and keys of variants that were measured and not adopted are
    // refused, named.
    for (line, key, what) in [
        (
            "final_assignment = \"merge-refit\"",
            "final_assignment",
            "unknown variant `merge-refit`",
        ),
        (
            "sampling = \"mixed\"",
            "sampling",
            "unknown variant `mixed`",
        ),
        (
            "minimal_solver = \"seven-point\"",
            "minimal_solver",
            "unknown variant `seven-point`",
        ),
        (
            "minimal_solutions = \"all\"",
            "minimal_solutions",
            "unknown variant `all`",
        ),
        (
            "subset_extension = \"model\"",
            "subset_extension",
            "unknown variant `model`",
        ),
    ] {
        let err = parse(&format!("{BASE}[pipeline]\n{line}\n")).unwrap_err();
        let msg = err.to_string();
        assert!(
            msg.starts_with(&format!("exp.toml:5: pipeline.{key}: {what}")),
            "{msg}"
        );
    }
    let err = parse(&format!("{BASE}[pipeline]\nadaptive_batch = 100\n")).unwrap_err();
    assert!(err.to_string().contains("adaptive_batch"), "{err}");
    let err = parse(&format!("{BASE}[pipeline]\nsampling = \"napsac\"\n")).unwrap_err();
    assert!(
        err.to_string()
            .starts_with("exp.toml:5: pipeline.sampling: unknown variant `napsac`"),
        "{err}"
    );
    let err = parse(&format!("{BASE}[pipeline]\nfinal_assignment = true\n")).unwrap_err();
    assert!(
        err.to_string()
            .starts_with("exp.toml:5: pipeline.final_assignment:"),
        "{err}"
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
    assert_eq!(c.pipeline.params.focal.weight_sets.sets().len(), 6);
    let c = parse(&format!(
        "{BASE}[pipeline]\nweight_sets = [[1e-3, 1, 1e-3, 1]]\n"
    ))
    .unwrap();
    assert_eq!(
        c.pipeline.params.focal.weight_sets.sets(),
        vec![focal::FocalWeights::new(1e-3, 1.0, 1e-3, 1.0)]
    );
    let err = parse(&format!("{BASE}[pipeline]\nweight_sets = \"kitti\"\n")).unwrap_err();
    assert!(err.to_string().contains("pipeline.weight_sets"), "{err}");
    let err = parse(&format!("{BASE}[pipeline]\nweight_sets = [[0, 1, 1, 1]]\n")).unwrap_err();
    assert!(err.to_string().contains("every weight must be"), "{err}");
}

#[test]
fn dataset_keys_are_checked_against_the_kind() {
    let err =
        parse("name = \"t\"\n[dataset]\nkind = \"adelaidermf\"\nsplit = \"test\"\n").unwrap_err();
    assert_eq!(
        err.to_string(),
        "exp.toml:4: dataset.split: does not apply to kind = \"adelaidermf\""
    );
    let err = parse("name = \"t\"\n[dataset]\nkind = \"csv\"\nfiles = [\"a.csv\"]\nwidth = 5\n")
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
fn pipeline_file_reads_the_pipeline_table_of_any_config() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("p.toml");
    std::fs::write(
        &path,
        format!("{BASE}[pipeline]\nthr_px = 4.5\n[sweep]\nseed = [1, 2]\n"),
    )
    .unwrap();
    assert_eq!(
        PipelineConfig::load(&path)
            .unwrap()
            .params
            .refinement
            .thr_px,
        4.5
    );
    std::fs::write(&path, "[pipeline]\nmethod = \"baseline\"\n").unwrap();
    assert_eq!(
        PipelineConfig::load(&path).unwrap().params.focal.method,
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

#[test]
fn size_rule_reads_each_rule_and_rejects_a_bad_fraction() {
    use segmentation::SizeRule;
    for (text, rule) in [
        ("\"min-size\"", SizeRule::MinSize),
        ("{ relative-min = 0.01 }", SizeRule::RelativeMin(0.01)),
    ] {
        let c = parse(&format!("{BASE}[pipeline]\nsize_rule = {text}\n")).unwrap();
        assert_eq!(c.pipeline.params.clustering.size_rule, rule, "{text}");
    }
    let err = parse(&format!(
        "{BASE}[pipeline]\nsize_rule = {{ relative-min = 2.0 }}\n"
    ))
    .unwrap_err()
    .to_string();
    assert!(err.contains("pipeline.size_rule"), "{err}");
    assert!(parse(&format!("{BASE}[pipeline]\nsize_rule = \"gap\"\n")).is_err());
}

#[test]
fn profile_gives_the_keys_the_table_does_not() {
    // No profile, or `default`: Params::default().
    let none = parse(BASE).unwrap();
    let default = parse(&format!("{BASE}[pipeline]\nprofile = \"default\"\n")).unwrap();
    assert_eq!(none, default);
    assert_eq!(none.pipeline.params(), Params::default());
    for profile in Profile::ALL {
        let c = parse(&format!(
            "{BASE}[pipeline]\nprofile = \"{}\"\n",
            profile.name()
        ))
        .unwrap();
        assert_eq!(c.pipeline.params(), profile.params(), "{profile:?}");
        assert_eq!(c.pipeline.profile, profile);
    }
    // The keys the table gives override the profile's, wherever they stand.
    let c = parse(&format!(
        "{BASE}[pipeline]\nthr_px = 4.0\nprofile = \"thesis\"\nmethod = \"baseline\"\n"
    ))
    .unwrap();
    assert_eq!(
        c.pipeline.params(),
        Params::thesis().with(|q| {
            q.refinement.thr_px = 4.0;
            q.focal.method = Method::Baseline;
        })
    );
    // A key given with the default's value still overrides the profile.
    let c = parse(&format!(
        "{BASE}[pipeline]\nprofile = \"thesis\"\nminimal_solver = \"five-point\"\n"
    ))
    .unwrap();
    assert_eq!(
        c.pipeline.params.sampling.minimal_solver,
        MinimalSolver::FivePoint
    );
    assert_eq!(c.pipeline.params.focal.method, Method::Semical);
}

#[test]
fn bad_profile_and_errors_beside_it_name_key_and_line() {
    let err = parse(&format!("{BASE}[pipeline]\n\nprofile = \"quick\"\n"))
        .unwrap_err()
        .to_string();
    assert!(
        err.starts_with("exp.toml:6: pipeline.profile: unknown profile `quick`"),
        "{err}"
    );
    assert!(err.contains("default, thesis"), "{err}");
    // A retired profile says what became of it.
    let err = parse(&format!("{BASE}[pipeline]\nprofile = \"large\"\n"))
        .unwrap_err()
        .to_string();
    assert!(
        err.starts_with(
            "exp.toml:5: pipeline.profile: profile `large` was folded into the default"
        ),
        "{err}"
    );
    let err = parse(&format!(
        "{BASE}[pipeline]\nprofile = \"thesis\"\nthr = 3\n"
    ))
    .unwrap_err()
    .to_string();
    assert!(
        err.starts_with("exp.toml:6: pipeline.thr: unknown field `thr`"),
        "{err}"
    );
    let err = parse(&format!(
        "{BASE}[pipeline]\nprofile = \"thesis\"\n\ntau_range = -0.1\n"
    ))
    .unwrap_err()
    .to_string();
    assert_eq!(
        err,
        "exp.toml:7: pipeline.tau_range: must be a finite number > 0, got -0.1"
    );
}

#[test]
fn resolved_config_on_a_profile_reads_back_the_same() {
    let c = parse(&format!(
        "{BASE}[pipeline]\nprofile = \"thesis\"\nthr_px = 3.5\n[sweep]\nseed = [1, 2]\n"
    ))
    .unwrap();
    assert_eq!(
        c.pipeline.params(),
        Params::thesis().with(|q| q.refinement.thr_px = 3.5)
    );
    let text = c.to_toml();
    assert!(text.contains("profile = \"thesis\""), "{text}");
    assert_eq!(parse(&text).unwrap(), c);
    // Without a profile the resolved file does not mention one.
    assert!(!parse(BASE).unwrap().to_toml().contains("profile"));
}

#[test]
fn pipeline_file_reads_its_profile_or_the_given_one() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("p.toml");
    std::fs::write(
        &path,
        "[pipeline]\nprofile = \"thesis\"\nnum_samples = 700\n",
    )
    .unwrap();
    let thesis = Params::thesis().with(|q| q.sampling.num_samples = 700);
    assert_eq!(PipelineConfig::load(&path).unwrap().params(), thesis);
    // A given profile replaces the file's; the file's keys still override.
    let default = PipelineConfig::load_with_profile(&path, Some(Profile::Default)).unwrap();
    assert_eq!(
        default.params(),
        Params::default().with(|q| q.sampling.num_samples = 700)
    );
    assert_eq!(default.profile, Profile::Default);
    // No [pipeline] table: the profile's values.
    std::fs::write(&path, "name = \"x\"\n").unwrap();
    let thesis = PipelineConfig::load_with_profile(&path, Some(Profile::Thesis)).unwrap();
    assert_eq!(thesis, PipelineConfig::of_profile(Profile::Thesis));
    assert_eq!(thesis.params(), Params::thesis());
}
