//! Checks shared by the tests of the randomised families (`driving-random`,
//! `objects-3d`): the record against the scene, exact ground truth without
//! noise, byte-identical output.

use datasets::synthetic::{write_hopef_layout, SceneRecord, SyntheticScene, RECORDS_FILE};
use datasets::Scene;
use geometry::sampson_distance;
use nalgebra::Matrix3;
use std::path::Path;

/// The Sampson distances (px) of the matches labelled `label` to `f`.
pub fn distances(scene: &Scene, label: i32, f: &Matrix3<f64>) -> Vec<f64> {
    let labels = scene.labels.as_ref().unwrap();
    (0..scene.len())
        .filter(|&i| labels[i] == label)
        .map(|i| sampson_distance(f, scene.points1[i], scene.points2[i]))
        .collect()
}

/// The median of `v` (upper median for an even length, as the generators).
pub fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// The record of `s`, checked against its scene: N, the counts and shares
/// per label, the outlier share, the focal, the image size, one true F per
/// motion.
pub fn checked_record(s: &SyntheticScene) -> &SceneRecord {
    let r = s
        .record
        .as_ref()
        .expect("a randomised family's scene has a record");
    let scene = &s.scene;
    let labels = scene.labels.as_ref().unwrap();
    let name = &scene.name;
    assert_eq!(scene.len(), r.n, "{name}: N");
    assert_eq!(scene.num_motions(), r.motions.len(), "{name}: motions");
    assert_eq!(
        scene.gt_fundamentals.len(),
        r.motions.len(),
        "{name}: one F per motion"
    );
    let outliers = scene.num_outliers();
    assert_eq!(
        outliers as f64 / r.n as f64,
        r.outlier_share,
        "{name}: outlier share"
    );
    for (j, m) in r.motions.iter().enumerate() {
        assert_eq!(m.label, j as i32 + 1, "{name}: labels in order");
        let count = labels.iter().filter(|&&l| l == m.label).count();
        assert_eq!(count, m.points, "{name}: points of motion {}", m.label);
        assert_eq!(
            m.share,
            count as f64 / r.n as f64,
            "{name}: share of motion {}",
            m.label
        );
    }
    assert_eq!(scene.true_focal, Some(r.focal), "{name}: true focal");
    assert_eq!(s.intrinsics[(0, 0)], r.focal, "{name}: K's focal");
    assert_eq!(scene.image_size, r.image_size, "{name}: image size");
    r
}

/// For a scene generated without noise: every inlier satisfies its motion's
/// true F to 1e-9 px, and each recorded separation is the median Sampson
/// distance of the motion's matches to the other motions' F, recomputed.
pub fn check_noise_free(s: &SyntheticScene, background: Option<usize>) {
    let r = checked_record(s);
    let scene = &s.scene;
    let fs = &scene.gt_fundamentals;
    for m in &r.motions {
        let own = distances(scene, m.label, &fs[m.label as usize - 1]);
        let worst = own.iter().copied().fold(0.0, f64::max);
        assert!(
            worst < 1e-9,
            "{}: motion {} has a match {worst} px from its F",
            scene.name,
            m.label
        );
        let to = |j: usize| median(distances(scene, m.label, &fs[j]));
        let nearest = (0..fs.len())
            .filter(|&j| j + 1 != m.label as usize)
            .map(to)
            .min_by(f64::total_cmp);
        assert_close(m.nearest_separation_px, nearest, &scene.name);
        let to_background = background.filter(|&b| b + 1 != m.label as usize).map(to);
        assert_close(m.background_separation_px, to_background, &scene.name);
    }
}

/// Two optional separations equal to 1e-9 relative.
fn assert_close(recorded: Option<f64>, measured: Option<f64>, name: &str) {
    match (recorded, measured) {
        (Some(a), Some(b)) => assert!((a - b).abs() <= 1e-9 * b.max(1.0), "{name}: {a} != {b}"),
        (a, b) => assert_eq!(a, b, "{name}: separation present in one only"),
    }
}

/// Every file below `dir`, relative path and bytes, sorted.
fn files(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                stack.push(path);
            } else {
                let rel = path.strip_prefix(dir).unwrap().display().to_string();
                out.push((rel, std::fs::read(&path).unwrap()));
            }
        }
    }
    out.sort();
    out
}

/// The HOPE-F layout written from `scenes` twice, once from `again`, is
/// byte-identical, and includes the records file.
pub fn check_same_bytes(scenes: &[SyntheticScene], again: &[SyntheticScene]) {
    let (a, b) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
    write_hopef_layout(a.path(), scenes).unwrap();
    write_hopef_layout(b.path(), again).unwrap();
    let (fa, fb) = (files(a.path()), files(b.path()));
    assert!(
        fa.iter().any(|(name, _)| name == RECORDS_FILE),
        "no {RECORDS_FILE}"
    );
    assert_eq!(
        fa.len(),
        1 + 2 * scenes.len(),
        "two .npz per scene and the records"
    );
    assert!(fa == fb, "the same seed gave different bytes");
}
