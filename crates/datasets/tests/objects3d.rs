//! The `objects-3d` family: drawn ranges respected over 200 scenes and
//! actually spanned, every pair of motions distinct, exact ground truth
//! without noise, determinism, errors.

mod family_checks;

use datasets::synthetic::{
    generate_objects3d_scene, MotionKind, Objects3dParams, Preset, PresetParams, SyntheticScene,
};
use datasets::DatasetError;
use family_checks::{check_noise_free, check_same_bytes, checked_record, distances};

/// Scenes `0/first..0/first+count` of `params` from `seed`.
fn scenes(params: &Objects3dParams, seed: u64, first: u32, count: u32) -> Vec<SyntheticScene> {
    (first..first + count)
        .map(|i| generate_objects3d_scene(params, seed, 0, i).unwrap())
        .collect()
}

/// Index of the background motion (0-based) of a scene, if it has one.
fn background(s: &SyntheticScene) -> Option<usize> {
    let r = s.record.as_ref().unwrap();
    r.motions
        .iter()
        .position(|m| m.kind == MotionKind::Background)
}

#[test]
fn preset_is_registered_with_one_category_and_the_hopef_splits() {
    let p = Preset::from_name("objects-3d").unwrap();
    assert_eq!(p, Preset::Objects3d);
    assert_eq!(p.categories(), vec![0]);
    assert_eq!(p.indices(), 0..=999);
    let params = p.params();
    params.validate().unwrap();
    let table = toml::Value::try_from(&params).unwrap();
    assert_eq!(p.params_from_toml(table).unwrap(), params);
    let PresetParams::Objects3d(o) = &params else {
        panic!("objects-3d parameters expected");
    };
    assert_eq!(
        params.generate_scene(3, 0, 850).unwrap(),
        generate_objects3d_scene(o, 3, 0, 850).unwrap()
    );
}

#[test]
fn drawn_ranges_hold_and_are_spanned_over_200_scenes() {
    let p = Objects3dParams::default();
    let all = scenes(&p, 11, 800, 200);
    let (mut n_min, mut n_max, mut smallest) = (usize::MAX, 0, usize::MAX);
    let (mut f_lo, mut f_hi) = (f64::INFINITY, 0.0_f64);
    let mut objects_seen = [0usize; 6];
    let mut with_background = 0;
    for s in &all {
        let r = checked_record(s);
        let name = &s.scene.name;
        let (w, h) = r.image_size;
        assert!(
            (400..=1600).contains(&w) && (300..=1200).contains(&h),
            "{name}: {w} x {h}"
        );
        let factor = r.focal / f64::from(w.max(h));
        assert!(
            (0.6..=2.5).contains(&factor),
            "{name}: focal factor {factor}"
        );
        assert!((100..=3000).contains(&r.n), "{name}: N {}", r.n);
        assert!(
            r.outlier_share <= 0.4 + 0.5 / r.n as f64,
            "{name}: outliers {}",
            r.outlier_share
        );
        assert!(
            (0.3..=1.2).contains(&r.noise_sigma),
            "{name}: sigma {}",
            r.noise_sigma
        );
        let bg = background(s);
        assert!(
            bg.is_none() || bg == Some(0),
            "{name}: the background is label 1"
        );
        with_background += usize::from(bg.is_some());
        let objects = r.motions.len() - usize::from(bg.is_some());
        assert!((1..=5).contains(&objects), "{name}: {objects} objects");
        objects_seen[objects] += 1;
        for m in &r.motions {
            assert!(
                m.points >= 15,
                "{name}: motion {} has {} matches",
                m.label,
                m.points
            );
            smallest = smallest.min(m.points);
            if m.kind == MotionKind::Object {
                assert!(
                    (5.0..=40.0).contains(&m.rotation_deg),
                    "{name}: turn {}",
                    m.rotation_deg
                );
            }
        }
        n_min = n_min.min(r.n);
        n_max = n_max.max(r.n);
        f_lo = f_lo.min(factor);
        f_hi = f_hi.max(factor);
    }
    assert!(n_min < 200 && n_max > 2000, "N spans {n_min}..{n_max}");
    assert!(smallest <= 20, "the smallest motion has {smallest} matches");
    assert!(
        f_lo < 0.8 && f_hi > 2.2,
        "focal factors span {f_lo}..{f_hi}"
    );
    assert!(
        (60..=140).contains(&with_background),
        "{with_background} of 200 with a background"
    );
    assert!(
        objects_seen[1..].iter().all(|&c| c >= 20),
        "object counts {objects_seen:?}"
    );
}

#[test]
fn without_noise_truth_is_exact_and_motions_are_distinct() {
    let p = Objects3dParams {
        noise_sigma: [0.0, 0.0],
        ..Objects3dParams::default()
    };
    for s in scenes(&p, 5, 800, 40) {
        check_noise_free(&s, background(&s));
        let scene = &s.scene;
        let fs = &scene.gt_fundamentals;
        // At most half of a motion's matches lie within 2.5 px of another's F.
        for i in 1..=fs.len() as i32 {
            for (j, f) in fs.iter().enumerate() {
                if j as i32 + 1 == i {
                    continue;
                }
                let d = distances(scene, i, f);
                let close = d.iter().filter(|&&x| x < 2.5).count();
                assert!(
                    2 * close <= d.len(),
                    "{}: {close} of {} matches of motion {i} within 2.5 px of F{}",
                    scene.name,
                    d.len(),
                    j + 1
                );
            }
        }
    }
}

#[test]
fn same_seed_same_bytes_other_seed_other_scene() {
    let p = Objects3dParams::default();
    let a = scenes(&p, 7, 850, 6);
    check_same_bytes(&a, &scenes(&p, 7, 850, 6));
    assert_ne!(a[0], scenes(&p, 8, 850, 1)[0]);
}

#[test]
fn bad_parameters_name_their_field() {
    let cases: [(Objects3dParams, &str); 4] = [
        (
            Objects3dParams {
                objects: [0, 3],
                ..Default::default()
            },
            "objects",
        ),
        (
            Objects3dParams {
                small_object_points: [10, 30],
                ..Default::default()
            },
            "small_object_points",
        ),
        (
            Objects3dParams {
                size_range: [100.0, 120.0],
                ..Default::default()
            },
            "size_range",
        ),
        (
            Objects3dParams {
                max_shared_share: 1.0,
                ..Default::default()
            },
            "max_shared_share",
        ),
    ];
    for (params, field) in cases {
        match generate_objects3d_scene(&params, 1, 0, 800) {
            Err(DatasetError::InvalidParams { field: f, .. }) => assert_eq!(f, field),
            other => panic!("{field}: expected InvalidParams, got {other:?}"),
        }
    }
}
