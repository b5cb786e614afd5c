//! The synthetic generator: determinism, ground truth consistent with the
//! points, well-separated objects, presets, and a lossless HOPE-F round trip.

use datasets::hopef::{HopeF, LoadOptions, Selection};
use datasets::synthetic::{
    generate_hopef_scene, generate_scene, scene_seed, write_hopef_layout, Preset, SyntheticParams,
    SyntheticScene,
};
use datasets::{DatasetError, Scene};
use geometry::sampson_distance;

fn inlier_sampson(scene: &Scene) -> Vec<f64> {
    let labels = scene.labels.as_ref().unwrap();
    (0..scene.len())
        .filter(|&i| labels[i] > 0)
        .map(|i| {
            sampson_distance(
                &scene.gt_fundamentals[labels[i] as usize - 1],
                scene.points1[i],
                scene.points2[i],
            )
        })
        .collect()
}

/// The presets of this generator (not `hopef`, tested in hopef_synth.rs)
/// with their parameters.
fn legacy_presets() -> Vec<(Preset, SyntheticParams)> {
    Preset::ALL
        .into_iter()
        .filter_map(|p| p.params().as_synthetic().map(|params| (p, params.clone())))
        .collect()
}

fn all_preset_scenes() -> Vec<(Preset, SyntheticParams, SyntheticScene)> {
    legacy_presets()
        .into_iter()
        .flat_map(|(p, params)| {
            p.generate(2024)
                .unwrap()
                .into_iter()
                .map(move |s| (p, params.clone(), s))
        })
        .collect()
}

#[test]
fn deterministic_per_seed() {
    let params = SyntheticParams::default();
    for k in 1..=4 {
        let a = generate_scene(&params, 99, k, "s").unwrap();
        let b = generate_scene(&params, 99, k, "s").unwrap();
        let c = generate_scene(&params, 100, k, "s").unwrap();
        assert_eq!(a, b);
        assert_ne!(a.points1, c.points1);
    }
    assert_eq!(
        Preset::Quick.generate(5).unwrap(),
        Preset::Quick.generate(5).unwrap()
    );
    assert_ne!(
        Preset::Quick.generate(5).unwrap(),
        Preset::Quick.generate(6).unwrap()
    );
    // A scene does not depend on the others generated with it.
    let all = Preset::HopefLike.generate(11).unwrap();
    let alone = Preset::HopefLike
        .params()
        .generate_scene(11, 3, 957)
        .unwrap();
    let position = all.iter().position(|s| s.scene.name == "3/0957").unwrap();
    assert_eq!(all[position], alone);
    assert_eq!(scene_seed(11, 3, 957), scene_seed(11, 3, 957));
}

#[test]
fn true_f_explains_at_least_99_percent_of_inliers_within_3_sigma_in_every_scene() {
    for (preset, params, s) in all_preset_scenes() {
        let sigma = params.noise_sigma;
        let d = inlier_sampson(&s.scene);
        let within = d.iter().filter(|&&x| x < 3.0 * sigma).count();
        assert!(
            within * 100 >= d.len() * 99,
            "{} {}: {within}/{} inliers within 3 sigma",
            preset.name(),
            s.scene.name,
            d.len()
        );
    }
}

#[test]
fn noise_has_the_requested_scale() {
    // The 4-D noise vector is Gaussian truncated at 3 sigma; its component
    // along any fixed direction then has RMS sqrt(E[chi2_4 | chi2_4 <= 9] / 4)
    // = 0.938 sigma, and the Sampson distance is that component to first order.
    let scenes = Preset::HopefLike.generate(3).unwrap();
    let all: Vec<f64> = scenes
        .iter()
        .flat_map(|s| inlier_sampson(&s.scene))
        .collect();
    let rms = (all.iter().map(|d| d * d).sum::<f64>() / all.len() as f64).sqrt();
    let ratio = rms / 0.5;
    assert!(
        (0.91..=0.965).contains(&ratio),
        "RMS Sampson / sigma = {ratio}"
    );
}

#[test]
fn noiseless_scenes_fit_their_f_exactly() {
    let params = SyntheticParams {
        noise_sigma: 0.0,
        ..SyntheticParams::default()
    };
    for seed in 0..40 {
        let k = 1 + (seed as usize % 4);
        let scene = generate_scene(&params, seed, k, "exact").unwrap();
        let worst = inlier_sampson(&scene).into_iter().fold(0.0, f64::max);
        assert!(worst < 1e-6, "seed {seed}: {worst} px");
        // Outliers are random pairs: far from every motion's epipolar geometry, mostly.
        let labels = scene.labels.as_ref().unwrap();
        let mut nearest: Vec<f64> = (0..scene.len())
            .filter(|&i| labels[i] == 0)
            .map(|i| {
                scene
                    .gt_fundamentals
                    .iter()
                    .map(|f| sampson_distance(f, scene.points1[i], scene.points2[i]))
                    .fold(f64::INFINITY, f64::min)
            })
            .collect();
        nearest.sort_by(f64::total_cmp);
        assert!(
            nearest[nearest.len() / 2] > 5.0,
            "seed {seed}: median outlier distance {}",
            nearest[nearest.len() / 2]
        );
    }
}

#[test]
fn scenes_have_the_promised_structure() {
    for (preset, params, s) in all_preset_scenes() {
        let scene = &s.scene;
        let name = format!("{} {}", preset.name(), scene.name);
        scene.validate().unwrap();
        let background = params.background.enabled;
        let motions = s.category as usize + usize::from(background);
        assert_eq!(scene.num_motions(), motions, "{name}");
        assert_eq!(scene.gt_fundamentals.len(), motions, "{name}");
        assert_eq!(scene.image_size, (1024, 768));
        // Principal point near the centre, focal in range, K consistent.
        assert!(
            (scene.principal_point[0] - 511.5).abs() <= 10.0
                && (scene.principal_point[1] - 383.5).abs() <= 10.0
        );
        let f = scene.true_focal.unwrap();
        assert!((500.0..=1500.0).contains(&f), "{name}: f = {f}");
        assert_eq!(s.intrinsics[(0, 0)], f);
        assert_eq!(
            [s.intrinsics[(0, 2)], s.intrinsics[(1, 2)]],
            scene.principal_point
        );
        // Every point is inside both images.
        for p in scene.points1.iter().chain(&scene.points2) {
            assert!(
                (0.0..=1023.0).contains(&p[0]) && (0.0..=767.0).contains(&p[1]),
                "{name}: {p:?}"
            );
        }
        // Objects keep enough points; outliers are the requested fraction.
        let labels = scene.labels.as_ref().unwrap();
        let first_object = if background { 2 } else { 1 };
        for label in first_object..=motions as i32 {
            let count = labels.iter().filter(|&&l| l == label).count();
            assert!(
                count >= params.min_points_per_object && count <= params.points_per_object[1],
                "{name}: object {label} has {count} points"
            );
        }
        let outliers = scene.num_outliers();
        let inliers = scene.len() - outliers;
        assert_eq!(
            outliers,
            (0.2 * inliers as f64 / 0.8).round() as usize,
            "{name}"
        );
    }
}

#[test]
fn objects_are_separated_in_image_1() {
    let params = SyntheticParams {
        noise_sigma: 0.0,
        ..SyntheticParams::default()
    };
    for seed in 0..100 {
        let k = 2 + (seed as usize % 3);
        let scene = generate_scene(&params, seed, k, "sep").unwrap();
        let labels = scene.labels.as_ref().unwrap();
        let boxes: Vec<[f64; 4]> = (1..=k as i32)
            .map(|l| {
                let pts = (0..scene.len())
                    .filter(|&i| labels[i] == l)
                    .map(|i| scene.points1[i]);
                pts.fold(
                    [
                        f64::INFINITY,
                        f64::INFINITY,
                        f64::NEG_INFINITY,
                        f64::NEG_INFINITY,
                    ],
                    |b, p| {
                        [
                            b[0].min(p[0]),
                            b[1].min(p[1]),
                            b[2].max(p[0]),
                            b[3].max(p[1]),
                        ]
                    },
                )
            })
            .collect();
        for a in 0..k {
            for b in a + 1..k {
                let (p, q) = (boxes[a], boxes[b]);
                let disjoint = p[2] < q[0] || q[2] < p[0] || p[3] < q[1] || q[3] < p[1];
                assert!(
                    disjoint,
                    "seed {seed}: objects {} and {} overlap: {p:?} {q:?}",
                    a + 1,
                    b + 1
                );
            }
        }
    }
}

#[test]
fn background_mode_labels_the_static_scene_1() {
    let preset = Preset::KittiLike;
    for s in preset.generate(8).unwrap() {
        let labels = s.scene.labels.as_ref().unwrap();
        let background = labels.iter().filter(|&&l| l == 1).count();
        assert!(
            background >= 50,
            "{}: {background} background points",
            s.scene.name
        );
        assert!(s.ego_translation.norm() >= 0.4 && s.ego_translation.z > 0.0);
        // The background F is the ego-motion's: K^-T [t]x R K^-1.
        let k_inv = s.intrinsics.try_inverse().unwrap();
        let t = s.ego_translation;
        let tx = nalgebra::Matrix3::new(0.0, -t.z, t.y, t.z, 0.0, -t.x, -t.y, t.x, 0.0);
        let f = k_inv.transpose() * tx * s.ego_rotation * k_inv;
        let f = f / f.norm();
        let diff = (f - s.scene.gt_fundamentals[0])
            .norm()
            .min((f + s.scene.gt_fundamentals[0]).norm());
        assert!(diff < 1e-12, "{}", s.scene.name);
    }
}

#[test]
fn hopef_layout_round_trip_is_lossless() {
    let root = tempfile::tempdir().unwrap();
    let mut scenes = Preset::Quick.generate(1).unwrap();
    scenes.extend(
        Preset::KittiLike
            .generate(1)
            .unwrap()
            .into_iter()
            .take(3)
            .map(|mut s| {
                s.index += 100; // 1000+: distinct folders from the quick preset
                s.scene.name = datasets::hopef::scene_name(s.category, s.index);
                s
            }),
    );
    // A non-default image size survives through the `image_size` array.
    let odd = SyntheticParams {
        image_width: 800,
        image_height: 600,
        ..SyntheticParams::default()
    };
    scenes.push(generate_hopef_scene(&odd, 3, 4, 905).unwrap());
    write_hopef_layout(root.path(), &scenes).unwrap();

    let data = HopeF::open(root.path()).unwrap();
    let refs = data.select(&[], &Selection::All).unwrap();
    assert_eq!(refs.len(), scenes.len());
    for r in refs {
        let loaded = data.load(&r, LoadOptions::default()).unwrap();
        let original = scenes.iter().find(|s| s.scene.name == loaded.name).unwrap();
        assert_eq!(loaded, original.scene, "{}", loaded.name);
    }
}

#[test]
fn params_from_toml_use_documented_defaults() {
    let params: SyntheticParams =
        toml::from_str("noise_sigma = 1.0\n[background]\nenabled = true\n").unwrap();
    assert_eq!(params.noise_sigma, 1.0);
    assert!(params.background.enabled);
    assert_eq!(params.background.points, [150, 250]);
    assert_eq!(
        SyntheticParams {
            noise_sigma: 0.5,
            background: Default::default(),
            ..params
        },
        SyntheticParams::default()
    );
    let d = SyntheticParams::default();
    assert_eq!((d.image_width, d.image_height), (1024, 768));
    assert_eq!(d.focal_range, [500.0, 1500.0]);
    assert_eq!(d.outlier_fraction, 0.2);
    assert_eq!(d.rotation_deg, [3.0, 20.0]);
    assert!(
        toml::from_str::<SyntheticParams>("noise = 1.0").is_err(),
        "unknown fields are rejected"
    );
}

#[test]
fn invalid_params_are_rejected_by_name() {
    let cases: Vec<(SyntheticParams, &str)> = vec![
        (
            SyntheticParams {
                focal_range: [900.0, 500.0],
                ..Default::default()
            },
            "focal_range",
        ),
        (
            SyntheticParams {
                outlier_fraction: 0.95,
                ..Default::default()
            },
            "outlier_fraction",
        ),
        (
            SyntheticParams {
                noise_sigma: f64::NAN,
                ..Default::default()
            },
            "noise_sigma",
        ),
        (
            SyntheticParams {
                points_per_object: [5, 10],
                ..Default::default()
            },
            "points_per_object",
        ),
        (
            SyntheticParams {
                object_extent: [0.5, 1.5],
                ..Default::default()
            },
            "object_extent",
        ),
        (
            SyntheticParams {
                rotation_deg: [0.0, 5.0],
                translation: [0.0, 0.1],
                ..Default::default()
            },
            "translation",
        ),
    ];
    for (params, field) in cases {
        let err = generate_scene(&params, 1, 2, "bad").unwrap_err();
        assert!(
            matches!(err, DatasetError::InvalidParams { field: f, .. } if f == field),
            "{field}: {err}"
        );
    }
    let err = generate_scene(&SyntheticParams::default(), 1, 0, "none").unwrap_err();
    assert!(err.to_string().contains("num_objects"), "{err}");
}

#[test]
fn presets_have_the_documented_shape() {
    assert_eq!(Preset::HopefLike.len(), 400);
    assert_eq!(Preset::HopefLike.categories(), vec![1, 2, 3, 4]);
    assert_eq!(Preset::HopefLike.indices(), 900..=999);
    assert_eq!(Preset::Quick.len(), 4);
    for p in Preset::ALL {
        assert_eq!(Preset::from_name(p.name()), Some(p));
        p.params().validate().unwrap();
    }
    let quick = Preset::Quick.generate(0).unwrap();
    assert!(
        quick.iter().all(|s| s.scene.len() <= 150),
        "quick scenes are small"
    );
}
