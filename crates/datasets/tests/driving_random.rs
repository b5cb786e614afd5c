//! The `driving-random` family: drawn ranges respected over 200 scenes and
//! actually spanned, separations at their drawn values, exact ground truth
//! without noise, movers distinct from each other, determinism, errors.

mod family_checks;

use datasets::synthetic::{
    generate_driving_random_scene, DrivingRandomParams, MotionKind, Preset, PresetParams,
    SyntheticScene,
};
use datasets::DatasetError;
use family_checks::{check_noise_free, check_same_bytes, checked_record, distances, median};

/// Scenes `0/first..0/first+count` of `params` from `seed`.
fn scenes(params: &DrivingRandomParams, seed: u64, first: u32, count: u32) -> Vec<SyntheticScene> {
    (first..first + count)
        .map(|i| generate_driving_random_scene(params, seed, 0, i).unwrap())
        .collect()
}

#[test]
fn preset_is_registered_with_one_category_and_the_hopef_splits() {
    let p = Preset::from_name("driving-random").unwrap();
    assert_eq!(p, Preset::DrivingRandom);
    assert_eq!(p.categories(), vec![0]);
    assert_eq!(p.indices(), 0..=999);
    let params = p.params();
    params.validate().unwrap();
    let table = toml::Value::try_from(&params).unwrap();
    assert_eq!(p.params_from_toml(table).unwrap(), params);
    let PresetParams::DrivingRandom(d) = &params else {
        panic!("driving-random parameters expected");
    };
    assert_eq!(
        params.generate_scene(3, 0, 850).unwrap(),
        generate_driving_random_scene(d, 3, 0, 850).unwrap()
    );
}

#[test]
fn drawn_ranges_hold_and_are_spanned_over_200_scenes() {
    let p = DrivingRandomParams::default();
    let all = scenes(&p, 11, 800, 200);
    let (mut n_min, mut n_max) = (usize::MAX, 0);
    let (mut sep_min, mut sep_max) = (f64::INFINITY, 0.0_f64);
    let mut movers_seen = [0usize; 4];
    for s in &all {
        let r = checked_record(s);
        let name = &s.scene.name;
        assert!((200..=20_000).contains(&r.n), "{name}: N {}", r.n);
        assert!(
            (0.3..=1.5).contains(&r.noise_sigma),
            "{name}: sigma {}",
            r.noise_sigma
        );
        assert!(
            r.outlier_share <= 0.30 + 0.5 / r.n as f64,
            "{name}: outliers {}",
            r.outlier_share
        );
        assert_eq!(r.image_size, (1242, 375));
        assert!(
            (720.0..=740.0).contains(&r.focal),
            "{name}: focal {}",
            r.focal
        );
        assert_eq!(r.motions[0].kind, MotionKind::Background);
        assert!(
            r.motions[0].share >= 0.2,
            "{name}: background share {}",
            r.motions[0].share
        );
        let movers = &r.motions[1..];
        assert!(movers.len() <= 3);
        movers_seen[movers.len()] += 1;
        for m in movers {
            assert_eq!(m.kind, MotionKind::Object);
            assert!(m.points >= 10, "{name}: mover of {} points", m.points);
            let lo = (0.02_f64).max(10.0 / r.n as f64) - 0.5 / r.n as f64;
            assert!(
                (lo..=0.30 + 0.5 / r.n as f64).contains(&m.share),
                "{name}: share {}",
                m.share
            );
            let target = m.target_separation_px.unwrap();
            assert!((0.5..=20.0).contains(&target), "{name}: target {target}");
            let got = m.background_separation_px.unwrap();
            assert!(
                (got - target).abs() <= 0.01 * target,
                "{name}: separation {got} for {target}"
            );
            sep_min = sep_min.min(got);
            sep_max = sep_max.max(got);
        }
        n_min = n_min.min(r.n);
        n_max = n_max.max(r.n);
    }
    // Log-uniform N over 200 scenes: below 400 and above 10 000 both occur
    // (each with probability 1 - (1 - 0.15)^200), as does every mover count.
    assert!(n_min < 400 && n_max > 10_000, "N spans {n_min}..{n_max}");
    assert!(
        sep_min < 1.0 && sep_max > 10.0,
        "separations span {sep_min}..{sep_max}"
    );
    assert!(
        movers_seen.iter().all(|&c| c >= 20),
        "mover counts {movers_seen:?}"
    );
}

#[test]
fn without_noise_truth_is_exact_and_separations_are_measured() {
    let p = DrivingRandomParams {
        noise_sigma: [0.0, 0.0],
        ..DrivingRandomParams::default()
    };
    for s in scenes(&p, 5, 800, 30) {
        check_noise_free(&s, Some(0));
        let scene = &s.scene;
        let r = s.record.as_ref().unwrap();
        let fs = &scene.gt_fundamentals;
        // The drawn separation is the median distance to the background's F.
        for m in &r.motions[1..] {
            let got = median(distances(scene, m.label, &fs[0]));
            let target = m.target_separation_px.unwrap();
            assert!(
                (got - target).abs() <= 0.01 * target,
                "{}: {got} for {target}",
                scene.name
            );
        }
        // Movers are at least as distinct from each other as the less
        // separated of the two is from the background.
        for a in &r.motions[1..] {
            for b in &r.motions[1..] {
                if a.label == b.label {
                    continue;
                }
                let least = a
                    .background_separation_px
                    .unwrap()
                    .min(b.background_separation_px.unwrap());
                let d = median(distances(scene, a.label, &fs[b.label as usize - 1]));
                assert!(
                    d >= least,
                    "{}: movers {} and {}: {d} < {least}",
                    scene.name,
                    a.label,
                    b.label
                );
            }
        }
    }
}

#[test]
fn same_seed_same_bytes_other_seed_other_scene() {
    let p = DrivingRandomParams::default();
    let a = scenes(&p, 7, 850, 4);
    check_same_bytes(&a, &scenes(&p, 7, 850, 4));
    assert_ne!(a[0], scenes(&p, 8, 850, 1)[0]);
}

#[test]
fn bad_parameters_name_their_field() {
    let cases: [(DrivingRandomParams, &str); 4] = [
        (
            DrivingRandomParams {
                movers: [0, 4],
                ..Default::default()
            },
            "movers",
        ),
        (
            DrivingRandomParams {
                size_range: [50.0, 1000.0],
                ..Default::default()
            },
            "size_range",
        ),
        (
            DrivingRandomParams {
                separation_px: [0.0, 20.0],
                ..Default::default()
            },
            "separation_px",
        ),
        (
            DrivingRandomParams {
                outlier_share: [0.0, 0.7],
                ..Default::default()
            },
            "min_background_share",
        ),
    ];
    for (params, field) in cases {
        match generate_driving_random_scene(&params, 1, 0, 800) {
            Err(DatasetError::InvalidParams { field: f, .. }) => assert_eq!(f, field),
            other => panic!("{field}: expected InvalidParams, got {other:?}"),
        }
    }
}
