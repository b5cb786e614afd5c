//! The `hopef` preset against HOPE-F's own rules, recomputed here
//! independently: labels and acceptance by `prepare_features_and_gt.py`'s
//! Sampson formula, each F by its pose formula from the written files, the
//! matches on the objects' silhouettes (projected with HOPE-F's camera
//! convention), and the localisation noise against its documented law.

use datasets::hopef::{HopeF, LoadOptions, Selection, CATEGORIES};
use datasets::hopef_synth::layout::object_file;
use datasets::hopef_synth::stats::HopefStats;
use datasets::hopef_synth::{generate_scene, HopefParams, MatchSource, Shape};
use datasets::npz::NpzArchive;
use datasets::synthetic::{write_hopef_layout, Preset, PresetParams, SyntheticScene};
use nalgebra::{Matrix3, Rotation3, Vector3};

/// `prepare_features_and_gt.py`'s `sampson_distance` for one match:
/// `sqrt((x2ᵀ F x1)² / ((F x1)₀² + (F x1)₁² + (Fᵀ x2)₀² + (Fᵀ x2)₁²))`.
fn naive_sampson(f: &Matrix3<f64>, p1: [f64; 2], p2: [f64; 2]) -> f64 {
    let x1 = Vector3::new(p1[0], p1[1], 1.0);
    let x2 = Vector3::new(p2[0], p2[1], 1.0);
    let fx1 = f * x1;
    let ftx2 = f.transpose() * x2;
    let e = x2.dot(&fx1);
    (e * e / (fx1.x.powi(2) + fx1.y.powi(2) + ftx2.x.powi(2) + ftx2.y.powi(2))).sqrt()
}

/// Test-split scenes `0900..0900+per_category` of every category.
fn scenes(params: &HopefParams, seed: u64, per_category: u32) -> Vec<SyntheticScene> {
    CATEGORIES
        .flat_map(|c| (900..900 + per_category).map(move |i| (c, i)))
        .map(|(c, i)| generate_scene(params, seed, c, i).unwrap())
        .collect()
}

/// Noise-free keypoints: no localisation error, no half-pixel offset.
fn noiseless() -> HopefParams {
    HopefParams {
        localisation: 0.0,
        keypoint_offset_px: 0.0,
        ..HopefParams::default()
    }
}

#[test]
fn deterministic_per_seed_and_folder() {
    let params = HopefParams::default();
    let a = generate_scene(&params, 7, 2, 905).unwrap();
    assert_eq!(a, generate_scene(&params, 7, 2, 905).unwrap());
    assert_ne!(
        a.scene.points1,
        generate_scene(&params, 8, 2, 905).unwrap().scene.points1
    );
    assert_ne!(
        a.scene.points1,
        generate_scene(&params, 7, 2, 906).unwrap().scene.points1
    );
    // The preset's scene is the generator's, whatever else is generated.
    let PresetParams::Hopef(preset) = Preset::Hopef.params() else {
        panic!("the hopef preset has HOPE-F parameters");
    };
    assert_eq!(preset, params);
    assert_eq!(Preset::Hopef.params().generate_scene(7, 2, 905).unwrap(), a);
}

#[test]
fn labels_follow_hopef_rule_exactly() {
    let params = HopefParams::default();
    let (mut checked, mut ties) = (0, 0);
    for s in scenes(&params, 3, 8) {
        let scene = &s.scene;
        let labels = scene.labels.as_ref().unwrap();
        for (i, &label) in labels.iter().enumerate() {
            let d: Vec<f64> = scene
                .gt_fundamentals
                .iter()
                .map(|f| naive_sampson(f, scene.points1[i], scene.points2[i]))
                .collect();
            // NumPy's argmin: the first smallest.
            let (best, &min) = d
                .iter()
                .enumerate()
                .fold(
                    (0, &f64::INFINITY),
                    |acc, (j, v)| if v < acc.1 { (j, v) } else { acc },
                );
            let near_tie = (min - 2.0).abs() < 1e-9
                || d.iter()
                    .enumerate()
                    .any(|(j, v)| j != best && (v - min).abs() < 1e-9);
            if near_tie {
                ties += 1;
                continue;
            }
            let expected = if min < 2.0 { best as i32 + 1 } else { 0 };
            assert_eq!(label, expected, "{} match {i}: distances {d:?}", scene.name);
            checked += 1;
        }
    }
    assert!(
        checked > 5000 && ties * 1000 < checked,
        "{checked} checked, {ties} ties"
    );
}

#[test]
fn every_scene_meets_the_acceptance_rule() {
    let params = HopefParams::default();
    let mut redrawn = 0;
    let mut all = scenes(&params, 5, 10);
    all.extend((800..810).map(|i| generate_scene(&params, 5, 4, i).unwrap()));
    for s in &all {
        let scene = &s.scene;
        for (j, f) in scene.gt_fundamentals.iter().enumerate() {
            let within = (0..scene.len())
                .filter(|&i| naive_sampson(f, scene.points1[i], scene.points2[i]) < 2.0)
                .count();
            assert!(
                within > 7,
                "{} object {}: {within} matches within 2 px",
                scene.name,
                j + 1
            );
        }
        redrawn += usize::from(s.hopef.as_ref().unwrap().attempts > 1);
    }
    // The rule is not vacuous: some draws fail it and are redrawn.
    assert!(redrawn > 0, "no scene needed a second draw");
}

#[test]
fn an_impossible_acceptance_rule_is_a_clear_error() {
    let params = HopefParams {
        texture_density: [0.01, 0.02],
        max_attempts: 5,
        ..HopefParams::default()
    };
    let err = generate_scene(&params, 1, 3, 912).unwrap_err().to_string();
    assert!(
        err.contains("3/0912") && err.contains("acceptance rule"),
        "{err}"
    );
    let err = generate_scene(&HopefParams::default(), 1, 5, 900)
        .unwrap_err()
        .to_string();
    assert!(err.contains("category") && err.contains('5'), "{err}");
    let err = toml::from_str::<HopefParams>("mismatch = 0.2")
        .unwrap_err()
        .to_string();
    assert!(err.contains("mismatch"), "{err}");
}

/// HOPE-F's projection: `X_c = (R R_swap)ᵀ X + t`, `x = K' X_c` with `K'`
/// = K with its (1, 1) entry negated (`prepare_features_and_gt.py`).
struct HopefCamera {
    k: Matrix3<f64>,
    r: Matrix3<f64>,
    t: Vector3<f64>,
}

impl HopefCamera {
    fn of(s: &SyntheticScene) -> Self {
        let truth = s.hopef.as_ref().unwrap();
        let mut k = s.intrinsics;
        k[(1, 1)] *= -1.0;
        let swap = Matrix3::from_diagonal(&Vector3::new(-1.0, -1.0, 1.0));
        Self {
            k,
            r: (truth.camera_rotation * swap).transpose(),
            t: Vector3::new(0.0, 0.0, -truth.camera_distance),
        }
    }

    fn project(&self, x: &Vector3<f64>) -> [f64; 2] {
        let p = self.k * (self.r * x + self.t);
        [p.x / p.z, p.y / p.z]
    }
}

/// Points on the boundary of an object's solid whose convex hull is the
/// solid (boxes: the corners; cylinders: 128 points on each rim).
fn outline(shape: &Shape) -> Vec<Vector3<f64>> {
    match *shape {
        Shape::Box { extents: [x, y, z] } => (0..8)
            .map(|c| {
                let pick = |bit: usize, v: f64| if c & bit == 0 { -v / 2.0 } else { v / 2.0 };
                Vector3::new(pick(1, x), pick(2, y), if c & 4 == 0 { 0.0 } else { z })
            })
            .collect(),
        Shape::Cylinder { radius, height } => (0..256)
            .map(|i| {
                let a = std::f64::consts::TAU * (i % 128) as f64 / 128.0;
                let z = if i < 128 { 0.0 } else { height };
                Vector3::new(radius * a.cos(), radius * a.sin(), z)
            })
            .collect(),
    }
}

/// Convex hull (Andrew's monotone chain), counter-clockwise.
fn hull(mut p: Vec<[f64; 2]>) -> Vec<[f64; 2]> {
    p.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    let cross = |o: [f64; 2], a: [f64; 2], b: [f64; 2]| {
        (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    };
    let chain = |points: &mut dyn Iterator<Item = [f64; 2]>| {
        let mut h: Vec<[f64; 2]> = Vec::new();
        for q in points {
            while h.len() >= 2 && cross(h[h.len() - 2], h[h.len() - 1], q) <= 0.0 {
                h.pop();
            }
            h.push(q);
        }
        h.pop();
        h
    };
    let mut lower = chain(&mut p.clone().into_iter());
    lower.extend(chain(&mut p.into_iter().rev()));
    lower
}

/// Signed distance of `q` inside the convex polygon `h` (negative outside).
fn inside_by(h: &[[f64; 2]], q: [f64; 2]) -> f64 {
    (0..h.len())
        .map(|i| {
            let (a, b) = (h[i], h[(i + 1) % h.len()]);
            let (ex, ey) = (b[0] - a[0], b[1] - a[1]);
            ((q[1] - a[1]) * ex - (q[0] - a[0]) * ey) / (ex * ex + ey * ey).sqrt()
        })
        .fold(f64::INFINITY, f64::min)
}

#[test]
fn every_match_lies_on_the_objects_it_claims() {
    let (mut mismatches, mut correct) = (0, 0);
    for s in scenes(&noiseless(), 11, 6) {
        let truth = s.hopef.as_ref().unwrap();
        let camera = HopefCamera::of(&s);
        // Silhouette of object j in view v, from the poses written to disk.
        let silhouette = |j: usize, v: usize| {
            let o = &truth.objects[j];
            let pose = &o.poses[v];
            let r = Rotation3::from_axis_angle(&Vector3::z_axis(), pose.yaw);
            let t = Vector3::new(pose.position.x, pose.position.y, 0.0);
            hull(
                outline(&o.shape)
                    .iter()
                    .map(|p| camera.project(&(r * p + t)))
                    .collect(),
            )
        };
        for (i, source) in truth.sources.iter().enumerate() {
            let (o1, o2) = match *source {
                MatchSource::Correct { object } => {
                    correct += 1;
                    (object, object)
                }
                MatchSource::Mismatch { object1, object2 } => {
                    mismatches += 1;
                    (object1, object2)
                }
            };
            let d1 = inside_by(&silhouette(o1, 0), s.scene.points1[i]);
            let d2 = inside_by(&silhouette(o2, 1), s.scene.points2[i]);
            assert!(
                d1 > -1e-6 && d2 > -1e-6,
                "{} match {i} ({source:?}): {d1} {d2}",
                s.scene.name
            );
        }
    }
    assert!(
        mismatches > 1000 && correct > 1000,
        "{mismatches} mismatches, {correct} correct"
    );
}

impl HopefCamera {
    /// The first object whose solid the ray through `pixel` enters, and
    /// where, by marching in steps of `step` units (a naive reference for
    /// the generator's ray tests).
    fn first_hit(
        &self,
        s: &SyntheticScene,
        view: usize,
        pixel: [f64; 2],
        step: f64,
    ) -> Option<(usize, Vector3<f64>)> {
        let truth = s.hopef.as_ref().unwrap();
        let centre = -(self.r.transpose() * self.t);
        let back = -(self.k.try_inverse().unwrap() * Vector3::new(pixel[0], pixel[1], 1.0));
        let dir = (self.r.transpose() * back).normalize();
        let near = truth.camera_distance - 3.0;
        let steps = (6.0 / step) as usize;
        (0..steps).find_map(|i| {
            let x = centre + dir * (near.max(0.0) + i as f64 * step);
            let inside = truth.objects.iter().position(|o| {
                let pose = &o.poses[view];
                let r = Rotation3::from_axis_angle(&Vector3::z_axis(), -pose.yaw);
                let local = r * (x - Vector3::new(pose.position.x, pose.position.y, 0.0));
                match o.shape {
                    Shape::Box { extents: [a, b, c] } => {
                        local.x.abs() <= a / 2.0
                            && local.y.abs() <= b / 2.0
                            && (0.0..=c).contains(&local.z)
                    }
                    Shape::Cylinder { radius, height } => {
                        local.x.hypot(local.y) <= radius && (0.0..=height).contains(&local.z)
                    }
                }
            });
            inside.map(|j| (j, x))
        })
    }
}

#[test]
fn correct_matches_are_front_surfaces_seen_in_both_views() {
    let (mut checked, mut missed) = (0, 0);
    for s in scenes(&noiseless(), 29, 4)
        .iter()
        .filter(|s| s.category >= 2)
    {
        let camera = HopefCamera::of(s);
        let truth = s.hopef.as_ref().unwrap();
        for (i, source) in truth.sources.iter().enumerate().step_by(7) {
            if let MatchSource::Correct { object } = *source {
                for (view, p) in [(0, s.scene.points1[i]), (1, s.scene.points2[i])] {
                    let hit = camera.first_hit(s, view, p, 2e-3);
                    missed += usize::from(hit.is_none());
                    let Some((first, x)) = hit else { continue };
                    assert_eq!(
                        first, object,
                        "{} match {i} of object {object}, view {view}: another object is in front",
                        s.scene.name
                    );
                    // The surface point seen in view 1, carried by the
                    // object's motion, is the point seen in view 2.
                    if view == 0 {
                        let (r, t) = truth.objects[object].motion();
                        let q = camera.project(&(r * x + t));
                        let p2 = s.scene.points2[i];
                        let err = (q[0] - p2[0]).hypot(q[1] - p2[1]);
                        assert!(
                            err < 1.0,
                            "{} match {i}: the front surface maps {err} px away",
                            s.scene.name
                        );
                    }
                }
                checked += 1;
            }
        }
    }
    // Grazing rays may slip between marching steps, rarely.
    assert!(
        checked > 300 && missed * 50 < checked,
        "{checked} checked, {missed} missed"
    );
}

/// Reads array `name` of `<dir>/<file>` as f64 values.
fn read(dir: &std::path::Path, file: &str, name: &str) -> Vec<f64> {
    let bytes = std::fs::read(dir.join(file)).unwrap();
    NpzArchive::new(&bytes)
        .unwrap()
        .array(name)
        .unwrap()
        .unwrap()
        .to_f64()
}

fn matrix(v: &[f64]) -> Matrix3<f64> {
    Matrix3::from_row_slice(v)
}

#[test]
fn each_f_is_the_static_camera_seeing_the_drawn_planar_motion() {
    let root = tempfile::tempdir().unwrap();
    let all = scenes(&noiseless(), 13, 5);
    write_hopef_layout(root.path(), &all).unwrap();
    for s in &all {
        let dir = root.path().join(&s.scene.name);
        // prepare_features_and_gt.py, line by line: one camera (K, R, t) for both renders.
        let mut k = matrix(&read(&dir, "camera_parameters.npz", "K"));
        k[(1, 1)] *= -1.0;
        let swap = Matrix3::from_diagonal(&Vector3::new(-1.0, -1.0, 1.0));
        let r_cam = (matrix(&read(&dir, "camera_parameters.npz", "R")) * swap).transpose();
        let t_cam = Vector3::from_column_slice(&read(&dir, "camera_parameters.npz", "t"));
        let k_inv = k.try_inverse().unwrap();
        for j in 0..s.category as usize {
            let file = object_file(j);
            let yaw = |name: &str| read(&dir, &file, name)[0];
            let rz = |a: f64| *Rotation3::from_axis_angle(&Vector3::z_axis(), a).matrix();
            let (r1, r2) = (rz(yaw("rot_euler_0")), rz(yaw("rot_euler_1")));
            let t1 = Vector3::from_column_slice(&read(&dir, &file, "t_0"));
            let t2 = Vector3::from_column_slice(&read(&dir, &file, "t_1"));
            // Planar motion: both locations on the ground, yaw within ±2 × 10°.
            assert!(t1.z == 0.0 && t2.z == 0.0);
            assert!((yaw("rot_euler_1") - yaw("rot_euler_0")).abs() <= 20f64.to_radians() + 1e-12);
            let r_obj = (r2 * r1.transpose()).transpose();
            let t_obj = t2 - r_obj * t1;
            let r = r_cam * r_obj * r_cam.transpose();
            let t = -r_cam * r_obj * r_cam.transpose() * t_cam + t_cam + r_cam * t_obj;
            let tx = Matrix3::new(0.0, -t.z, t.y, t.z, 0.0, -t.x, -t.y, t.x, 0.0);
            let f = k_inv.transpose() * tx * r * k_inv;
            let f = f / f.norm();
            let g = s.scene.gt_fundamentals[j];
            let diff = (f - g).norm().min((f + g).norm());
            assert!(
                diff < 1e-9,
                "{} object {j}: |F - F_hopef| = {diff}",
                s.scene.name
            );
        }
        // Noise-free correct matches satisfy their object's F exactly.
        let truth = s.hopef.as_ref().unwrap();
        for (i, source) in truth.sources.iter().enumerate() {
            if let MatchSource::Correct { object } = *source {
                let d = naive_sampson(
                    &s.scene.gt_fundamentals[object],
                    s.scene.points1[i],
                    s.scene.points2[i],
                );
                assert!(d < 1e-6, "{} match {i}: {d} px", s.scene.name);
            }
        }
    }
}

#[test]
fn layout_round_trip_keeps_scenes_and_ratios() {
    let root = tempfile::tempdir().unwrap();
    let all = scenes(&HopefParams::default(), 17, 2);
    write_hopef_layout(root.path(), &all).unwrap();
    let data = HopeF::open(root.path()).unwrap();
    let refs = data.select(&[], &Selection::All).unwrap();
    assert_eq!(refs.len(), all.len());
    for (r, s) in refs.iter().zip(&all) {
        assert_eq!(data.load(r, LoadOptions::default()).unwrap(), s.scene);
        let dir = root.path().join(&s.scene.name);
        let ratios = read(&dir, "features_and_ground_truth.npz", "ratios");
        assert_eq!(ratios, s.hopef.as_ref().unwrap().ratios);
        assert!(ratios.iter().all(|&x| (0.0..0.9).contains(&x)));
        assert_eq!(
            read(&dir, "camera_parameters.npz", "image_size"),
            [1024.0, 1024.0]
        );
    }
    assert_eq!(Preset::Hopef.len(), 4000);
    assert_eq!(Preset::Hopef.indices(), 0..=999);
    assert_eq!(Preset::Hopef.categories(), vec![1, 2, 3, 4]);
    assert_eq!(Preset::from_name("hopef"), Some(Preset::Hopef));
}

/// erf by Abramowitz & Stegun 7.1.26 (|error| < 1.5e-7).
fn erf(x: f64) -> f64 {
    let t = 1.0 / (1.0 + 0.327_591_1 * x.abs());
    let poly = t
        * (0.254_829_592
            + t * (-0.284_496_736
                + t * (1.421_413_741 + t * (-1.453_152_027 + t * 1.061_405_429))));
    (1.0 - poly * (-x * x).exp()).copysign(x)
}

/// P(Sampson < x) under the documented law: |N(0, σ²)|, σ = c · s_min ·
/// 2^u, u exponential of rate ln(decay) truncated to [0, U] (midpoint rule).
fn documented_cdf(p: &HopefParams, x: f64) -> f64 {
    let rate = p.octave_decay.ln();
    let norm = 1.0 - (-rate * p.max_octaves).exp();
    let steps = 20_000;
    let du = p.max_octaves / steps as f64;
    (0..steps)
        .map(|i| {
            let u = (i as f64 + 0.5) * du;
            let sigma = p.localisation * p.keypoint_scale_px * u.exp2();
            rate * (-rate * u).exp() / norm * erf(x / (sigma * 2f64.sqrt())) * du
        })
        .sum()
}

#[test]
fn localisation_error_follows_its_documented_law() {
    let params = HopefParams {
        keypoint_offset_px: 0.0,
        ..HopefParams::default()
    };
    let mut d: Vec<f64> = Vec::new();
    for s in scenes(&params, 19, 12) {
        let truth = s.hopef.as_ref().unwrap();
        for (i, source) in truth.sources.iter().enumerate() {
            if let MatchSource::Correct { object } = *source {
                d.push(naive_sampson(
                    &s.scene.gt_fundamentals[object],
                    s.scene.points1[i],
                    s.scene.points2[i],
                ));
            }
        }
    }
    assert!(d.len() > 10_000, "{} correct matches", d.len());
    for x in [0.1, 0.25, 0.5, 1.0, 2.0, 4.0] {
        let empirical = d.iter().filter(|&&v| v < x).count() as f64 / d.len() as f64;
        let expected = documented_cdf(&params, x);
        assert!(
            (empirical - expected).abs() < 0.015,
            "P(d < {x}) = {empirical}, documented {expected}"
        );
    }
}

#[test]
fn stats_agree_with_a_direct_count() {
    let all = scenes(&HopefParams::default(), 23, 3);
    let stats = HopefStats::compute(&all).unwrap();
    assert_eq!(stats.scenes, all.len());
    let mean_outliers = all
        .iter()
        .map(|s| s.scene.num_outliers() as f64 / s.scene.len() as f64)
        .sum::<f64>()
        / all.len() as f64;
    assert!((stats.outlier_share.mean - mean_outliers).abs() < 1e-12);
    let (mut correct, mut zero, mut wrong, mut given) = (0, 0, 0, 0);
    for s in &all {
        let labels = s.scene.labels.as_ref().unwrap();
        for (i, source) in s.hopef.as_ref().unwrap().sources.iter().enumerate() {
            match source {
                MatchSource::Correct { .. } => {
                    correct += 1;
                    zero += usize::from(labels[i] == 0);
                }
                MatchSource::Mismatch { .. } => {
                    wrong += 1;
                    given += usize::from(labels[i] > 0);
                }
            }
        }
    }
    assert_eq!(stats.correct_labelled_outlier, zero as f64 / correct as f64);
    assert_eq!(
        stats.mismatches_labelled_object,
        given as f64 / wrong as f64
    );
    assert_eq!(
        stats.matches_per_object.count,
        all.iter().map(|s| s.category as usize).sum::<usize>()
    );
    // Legacy scenes have no generator record: a clear error naming the scene.
    let legacy = Preset::Quick.generate(1).unwrap();
    let err = HopefStats::compute(&legacy).unwrap_err().to_string();
    assert!(err.contains("1/0900"), "{err}");
}
