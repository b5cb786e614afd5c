//! The driving-scene generator and the `kitti-real` preset: sizes, shares,
//! exact ground truth without noise, separability, determinism, errors.

use datasets::hopef::Split;
use datasets::synthetic::{generate_driving_scene, DrivingParams, Preset, PresetParams};
use datasets::{DatasetError, Scene};
use geometry::sampson_distance;

/// The Sampson distances (px) of the matches labelled `label` to `f`.
fn distances(scene: &Scene, label: i32, f: &nalgebra::Matrix3<f64>) -> Vec<f64> {
    let labels = scene.labels.as_ref().unwrap();
    (0..scene.len())
        .filter(|&i| labels[i] == label)
        .map(|i| sampson_distance(f, scene.points1[i], scene.points2[i]))
        .collect()
}

/// The median of `v` (upper median for an even length, as the generator).
fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// The share of the matches labelled `label`.
fn share(scene: &Scene, label: i32) -> f64 {
    let labels = scene.labels.as_ref().unwrap();
    labels.iter().filter(|&&l| l == label).count() as f64 / labels.len() as f64
}

#[test]
fn preset_round_trips_and_spans_the_hopef_splits() {
    let p = Preset::from_name("kitti-real").unwrap();
    assert_eq!(p, Preset::KittiReal);
    assert_eq!(p.name(), "kitti-real");
    assert_eq!(p.categories(), vec![1, 2]);
    assert_eq!(p.indices(), 0..=999);
    assert_eq!(p.len(), 2000);
    let params = p.params();
    params.validate().unwrap();
    let table = toml::Value::try_from(&params).unwrap();
    assert_eq!(p.params_from_toml(table).unwrap(), params);
    let PresetParams::Driving(d) = params else {
        panic!("driving parameters expected");
    };
    // Every size is in every split (N depends on index mod the list length).
    for split in [Split::Train, Split::Val, Split::Test] {
        let mut seen: Vec<usize> = split
            .indices()
            .map(|i| d.sizes[i as usize % d.sizes.len()])
            .collect();
        seen.sort_unstable();
        seen.dedup();
        assert_eq!(seen, vec![1000, 2000, 3000, 5000], "{split:?}");
    }
}

#[test]
fn scenes_have_the_stated_size_shares_and_camera() {
    let params = DrivingParams::default();
    // One scene of each size, spread over the three splits.
    for (category, index, n) in [(1, 900, 1000), (2, 801, 2000), (1, 2, 3000), (2, 903, 5000)] {
        let s = generate_driving_scene(&params, 3, category, index).unwrap();
        let scene = &s.scene;
        let name = &scene.name;
        assert_eq!(scene.len(), n, "{name}");
        assert_eq!(scene.num_motions(), category as usize + 1, "{name}");
        assert_eq!(scene.gt_fundamentals.len(), category as usize + 1);
        assert_eq!(scene.image_size, (1242, 375));
        assert_eq!(scene.principal_point, [620.5, 187.0]);
        let f = scene.true_focal.unwrap();
        assert!((720.0..=740.0).contains(&f), "{name}: f {f}");
        let outliers = share(scene, 0);
        assert!(
            (0.10 - 5e-4..=0.15 + 5e-4).contains(&outliers),
            "{name}: {outliers}"
        );
        let background = share(scene, 1);
        assert!(
            (0.60 - 5e-4..=0.75 + 5e-4).contains(&background),
            "{name}: {background}"
        );
        for car in 2..=category as i32 + 1 {
            assert!(share(scene, car) >= 0.05, "{name}: car {car}");
        }
        // Noisy inliers stay within the truncation (3 σ = 2.1 px) of their F.
        for label in 1..=category as i32 + 1 {
            let d = distances(scene, label, &scene.gt_fundamentals[label as usize - 1]);
            assert!(d.iter().all(|&x| x <= 2.1 + 1e-6), "{name}: motion {label}");
        }
        let (w, h) = (1241.0, 374.0);
        for p in scene.points1.iter().chain(&scene.points2) {
            assert!(
                (0.0..=w).contains(&p[0]) && (0.0..=h).contains(&p[1]),
                "{name}"
            );
        }
    }
}

#[test]
fn noise_free_inliers_lie_on_their_motion_and_cars_are_separable() {
    let params = DrivingParams {
        noise_sigma: 0.0,
        outlier_share: [0.0, 0.0],
        ..DrivingParams::default()
    };
    for (category, index) in [(1, 4), (2, 800), (2, 905)] {
        let scene = generate_driving_scene(&params, 11, category, index)
            .unwrap()
            .scene;
        let name = &scene.name;
        assert_eq!(share(&scene, 0), 0.0, "{name}");
        let fs = &scene.gt_fundamentals;
        for label in 1..=category as i32 + 1 {
            let d = distances(&scene, label, &fs[label as usize - 1]);
            let worst = d.iter().cloned().fold(0.0, f64::max);
            assert!(worst < 1e-6, "{name}: motion {label} off its F by {worst}");
        }
        let min = params.min_separation_px;
        for car in 2..=category as i32 + 1 {
            assert!(
                median(distances(&scene, car, &fs[0])) >= min,
                "{name}: car {car}"
            );
            for other in 2..car {
                let (a, b) = (car as usize - 1, other as usize - 1);
                assert!(median(distances(&scene, car, &fs[b])) >= min, "{name}");
                assert!(median(distances(&scene, other, &fs[a])) >= min, "{name}");
            }
        }
    }
}

#[test]
fn scenes_are_deterministic_per_seed_category_and_index() {
    let params = DrivingParams::default();
    let a = generate_driving_scene(&params, 5, 1, 0).unwrap();
    assert_eq!(a, generate_driving_scene(&params, 5, 1, 0).unwrap());
    let other_index = generate_driving_scene(&params, 5, 1, 4).unwrap();
    assert_eq!(other_index.scene.len(), a.scene.len());
    assert_ne!(other_index.scene.points1, a.scene.points1);
    let other_seed = generate_driving_scene(&params, 6, 1, 0).unwrap();
    assert_ne!(other_seed.scene.points1, a.scene.points1);
    let via_preset = Preset::KittiReal.params().generate_scene(5, 1, 0).unwrap();
    assert_eq!(via_preset, a);
}

#[test]
fn bad_parameters_and_categories_are_typed_errors() {
    let field = |params: DrivingParams, category: u32| match generate_driving_scene(
        &params, 1, category, 0,
    )
    .unwrap_err()
    {
        DatasetError::InvalidParams { field, .. } => field,
        e => panic!("InvalidParams expected, got {e}"),
    };
    let d = DrivingParams::default;
    assert_eq!(field(d(), 0), "category");
    assert_eq!(field(d(), 5), "category");
    let empty = DrivingParams {
        sizes: vec![],
        ..d()
    };
    assert_eq!(field(empty, 1), "sizes");
    let crowded = DrivingParams {
        min_car_share: 0.2,
        ..d()
    };
    assert_eq!(field(crowded, 1), "min_car_share");
    let fat_cars = || DrivingParams {
        min_car_share: 0.08,
        ..d()
    };
    assert_eq!(field(fat_cars(), 2), "min_car_share");
    generate_driving_scene(&fat_cars(), 1, 1, 0).unwrap();
    let truncation = DrivingParams {
        noise_truncation: 0.0,
        ..d()
    };
    assert_eq!(field(truncation, 1), "noise_truncation");
    let unseparable = DrivingParams {
        min_separation_px: 1e4,
        ..d()
    };
    let err = generate_driving_scene(&unseparable, 1, 1, 0).unwrap_err();
    assert!(
        matches!(&err, DatasetError::Generation { scene, .. } if scene == "1/0000"),
        "{err}"
    );
}
