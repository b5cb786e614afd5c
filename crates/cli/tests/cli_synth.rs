//! `sctl synth`: writes a preset in the HOPE-F layout that the HOPE-F loader
//! and `sctl inspect` read back, refuses to overwrite, takes parameter
//! overrides.

mod support;
use support::sctl;

use datasets::hopef::{HopeF, LoadOptions, Selection};
use datasets::synthetic::Preset;
use predicates::prelude::*;

#[test]
fn quick_preset_round_trips_and_inspects() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("quick");
    sctl()
        .args(["synth", "--preset", "quick", "--seed", "3", "--out"])
        .arg(&out)
        .assert()
        .success()
        .stderr(predicate::str::contains("synth: generating 4 scenes"))
        .stderr(predicate::str::contains("4/4 scenes written"));
    assert!(out.join("2/0901/features_and_ground_truth.npz").is_file());
    assert!(out.join("2/0901/camera_parameters.npz").is_file());
    let metadata: toml::Value =
        toml::from_str(&std::fs::read_to_string(out.join("synthetic.toml")).unwrap()).unwrap();
    assert_eq!(metadata["preset"].as_str(), Some("quick"));
    assert_eq!(metadata["seed"].as_integer(), Some(3));

    // The files hold exactly what the library generates for that seed.
    let expected = Preset::Quick.generate(3).unwrap();
    let data = HopeF::open(&out).unwrap();
    let refs = data.select(&[], &Selection::All).unwrap();
    assert_eq!(refs.len(), expected.len());
    for (r, e) in refs.iter().zip(&expected) {
        assert_eq!(data.load(r, LoadOptions::default()).unwrap(), e.scene);
    }

    let stdout = sctl()
        .args(["inspect", "--dataset", "hopef", "--dir"])
        .arg(&out)
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let motions: Vec<u64> = String::from_utf8(stdout)
        .unwrap()
        .lines()
        .map(|l| {
            serde_json::from_str::<serde_json::Value>(l).unwrap()["motions"]
                .as_u64()
                .unwrap()
        })
        .collect();
    assert_eq!(motions, [1, 1, 2, 2]);
}

#[test]
fn refuses_a_non_empty_directory_unless_forced() {
    let tmp = tempfile::tempdir().unwrap();
    std::fs::write(tmp.path().join("keep.txt"), "x").unwrap();
    sctl()
        .args(["synth", "--preset", "quick", "--out"])
        .arg(tmp.path())
        .assert()
        .failure()
        .stderr(predicate::str::contains("is not empty (use --force"));
    assert!(!tmp.path().join("1").exists());
    sctl()
        .args(["synth", "--preset", "quick", "--force", "--out"])
        .arg(tmp.path())
        .assert()
        .success();
    assert!(tmp
        .path()
        .join("1/0900/features_and_ground_truth.npz")
        .is_file());
    assert!(tmp.path().join("keep.txt").is_file());
}

#[test]
fn parameter_overrides_and_bad_input() {
    let tmp = tempfile::tempdir().unwrap();
    let params = tmp.path().join("params.toml");
    std::fs::write(&params, "image_width = 800\nimage_height = 600\n").unwrap();
    let out = tmp.path().join("small");
    sctl()
        .args(["synth", "--preset", "quick", "--params"])
        .arg(&params)
        .arg("--out")
        .arg(&out)
        .assert()
        .success();
    sctl()
        .args([
            "inspect",
            "--dataset",
            "hopef",
            "--scene",
            "1/0900",
            "--dir",
        ])
        .arg(&out)
        .assert()
        .success()
        .stdout(predicate::str::contains("\"width\":800,\"height\":600"));
    // The preset's own values survive where the file is silent.
    let meta = std::fs::read_to_string(out.join("synthetic.toml")).unwrap();
    assert!(meta.contains("min_points_per_object = 20"), "{meta}");

    std::fs::write(&params, "outlier_fraction = 2.0\n").unwrap();
    sctl()
        .args(["synth", "--preset", "quick", "--params"])
        .arg(&params)
        .arg("--out")
        .arg(tmp.path().join("x"))
        .assert()
        .failure()
        .stderr(predicate::str::contains("params.toml"))
        .stderr(predicate::str::contains("outlier_fraction"));
    std::fs::write(&params, "no_such_field = 1\n").unwrap();
    sctl()
        .args(["synth", "--preset", "quick", "--params"])
        .arg(&params)
        .arg("--out")
        .arg(tmp.path().join("y"))
        .assert()
        .failure()
        .stderr(predicate::str::contains("no_such_field"));
    sctl()
        .args(["synth", "--preset", "huge", "--out"])
        .arg(tmp.path().join("z"))
        .assert()
        .failure()
        .stderr(predicate::str::contains(
            "unknown preset `huge` (available: hopef-like, quick, kitti-like, hopef, kitti-real, adelaide-like, driving-random, objects-3d)",
        ));
}
