use super::*;

/// The default with uniform sampling, each five-point root polished and
/// every match clustered ([`base`]), and one change made by `edit`.
fn with(edit: impl FnOnce(&mut Params)) -> Params {
    let mut p = base();
    edit(&mut p);
    p
}

/// The default with the stage switches that the tests below change set to
/// their other value (uniform sampling, `best`, every match clustered).
fn base() -> Params {
    Params::default().with(|p| {
        p.sampling.sampling = Sampling::Uniform;
        p.sampling.minimal_solutions = MinimalSolutions::Best;
        p.sampling.cluster_subset = 0;
    })
}

#[test]
fn every_range_check_names_its_key() {
    let cases: [(&str, Params); 9] = [
        ("num_samples", with(|p| p.sampling.num_samples = 0)),
        ("mss_size", with(|p| p.sampling.mss_size = 7)),
        ("cluster_subset", with(|p| p.sampling.cluster_subset = 5)),
        ("thr_px", with(|p| p.refinement.thr_px = f64::NAN)),
        ("tau_diff", with(|p| p.focal.tau_diff = 0.0)),
        ("tau_range", with(|p| p.focal.tau_range = -0.1)),
        ("irls_iters", with(|p| p.refinement.irls_iters = 0)),
        (
            "weight_sets",
            with(|p| p.focal.weight_sets = WeightSets::Explicit(vec![[1.0, 0.0, 1.0, 1.0]])),
        ),
        (
            "irls_sigma_offset_px",
            with(|p| p.reference_code.irls_sigma_offset_px = -1.0),
        ),
    ];
    for (key, params) in cases {
        assert_eq!(params.validate().unwrap_err().key, key);
        assert!(KEYS.iter().any(|k| k.name == key), "{key} is a key");
    }
    assert!(Params::default().validate().is_ok());
    let no_refine = with(|p| {
        p.refinement.refine = false;
        p.refinement.irls_iters = 0;
    });
    assert!(no_refine.validate().is_ok());
}

#[test]
fn keys_separate_what_changes_the_stage() {
    let a = base();
    let b = with(|p| {
        p.focal.method = Method::Baseline;
        p.focal.tau_range = 0.3;
        p.reference_code.local_test = LocalTest::ReferenceCode;
    });
    assert_eq!(a.hypothesis_key(), b.hypothesis_key());
    assert_eq!(a.focal_key(), b.focal_key());
    for changed in [
        with(|p| p.refinement.thr_px = 3.0),
        with(|p| p.sampling.sampling = Sampling::Localized),
        with(|p| p.sampling.cluster_subset = 1000),
        with(|p| p.sampling.minimal_solutions = MinimalSolutions::BestUnpolished),
        with(|p| p.sampling.sampling = Sampling::Guided),
        with(|p| p.reference_code.irls_sigma_offset_px = 1e-12),
        with(|p| p.reference_code.eight_point = EightPoint::Plain),
    ] {
        assert_ne!(a.hypothesis_key(), changed.hypothesis_key(), "{changed:?}");
        assert_eq!(a.focal_key(), changed.focal_key(), "{changed:?}");
    }
    // The batch of guided sampling matters to guided sampling only.
    let batch = with(|p| p.sampling.guided_batch = 100);
    assert_eq!(a.hypothesis_key(), batch.hypothesis_key());
    let guided = with(|p| p.sampling.sampling = Sampling::Guided);
    let guided_batch = Params {
        sampling: SamplingParams {
            guided_batch: 100,
            ..guided.sampling.clone()
        },
        ..guided.clone()
    };
    assert_ne!(guided.hypothesis_key(), guided_batch.hypothesis_key());
    let unmerged = with(|p| p.selection.final_assignment = FinalAssignment::None);
    assert_eq!(a.hypothesis_key(), unmerged.hypothesis_key());
    for changed in [
        with(|p| p.focal.weight_sets = WeightSets::Preset(WeightPreset::Hopef)),
        with(|p| p.focal.max_iters = 120),
        with(|p| p.reference_code.focal_failure = OnFailure::Prior),
        with(|p| p.reference_code.truncate_focals = true),
    ] {
        assert_ne!(a.focal_key(), changed.focal_key(), "{changed:?}");
        assert_eq!(a.hypothesis_key(), changed.hypothesis_key(), "{changed:?}");
    }
    // The same weights named or listed are the same solver.
    let listed = with(|p| {
        let sets = p.focal.weight_sets.sets();
        p.focal.weight_sets =
            WeightSets::Explicit(sets.iter().map(|w| [w.f1, w.pp1, w.f2, w.pp2]).collect());
    });
    assert_eq!(a.focal_key(), listed.focal_key());
}

#[test]
fn the_key_list_is_unique_and_each_stage_has_its_keys() {
    let mut names: Vec<&str> = PARAM_KEYS.to_vec();
    names.sort_unstable();
    names.dedup();
    assert_eq!(names.len(), KEYS.len());
    assert_eq!(key("seed").map(|k| k.stage), Some(Stage::Sampling));
    assert_eq!(key("max_memory_mb").map(|k| k.stage), Some(Stage::Limits));
    assert!(key("adaptive_batch").is_none());
    let reference = KEYS.iter().filter(|k| k.stage == Stage::ReferenceCode);
    assert_eq!(reference.count(), 8);
    assert!(KEYS.iter().all(|k| !k.doc.is_empty()));
    assert!(KEYS
        .iter()
        .filter(|k| k.ty == KeyType::Choice)
        .all(|k| k.allowed.contains(" | ")));
}
