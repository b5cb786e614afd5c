//! `sctl inspect`: JSON lines for AdelaideRMF and HOPE-F, the data-root
//! resolution, and non-zero exits naming the file on bad input.

use assert_cmd::Command;
use predicates::prelude::*;
use std::path::PathBuf;

fn shared() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared")
}

/// `../shared/datasets`, a data root holding `adelaidermf/F`.
fn shared_data_root() -> PathBuf {
    let root = shared().join("datasets");
    assert!(
        root.join("adelaidermf/F/biscuit.mat").is_file(),
        "AdelaideRMF not found under {}: {}",
        root.display(),
        datasets::DATASET_HINT
    );
    root
}

fn fixtures(sub: &str) -> PathBuf {
    let dir = shared().join("fixtures/hopef-layout").join(sub);
    assert!(
        dir.is_dir(),
        "HOPE-F layout fixtures not found at {}",
        dir.display()
    );
    dir
}

fn sctl() -> Command {
    let mut cmd = Command::cargo_bin("sctl").unwrap();
    cmd.env_remove("SCTL_DATA_ROOT");
    cmd
}

fn json_lines(stdout: &[u8]) -> Vec<serde_json::Value> {
    String::from_utf8(stdout.to_vec())
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect()
}

#[test]
fn adelaidermf_prints_one_line_per_scene() {
    let out = sctl()
        .args(["inspect", "--dataset", "adelaidermf", "--data-root"])
        .arg(shared_data_root())
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let lines = json_lines(&out);
    assert_eq!(lines.len(), 19);
    let names: Vec<&str> = lines.iter().map(|l| l["name"].as_str().unwrap()).collect();
    assert_eq!(names, datasets::adelaidermf::FUNDAMENTAL_SCENES.to_vec());
    let dinobooks = &lines[15];
    assert_eq!(
        *dinobooks,
        serde_json::json!({"name": "dinobooks", "n": 360, "motions": 3, "outliers": 155,
            "width": 640, "height": 480, "has_images": true, "true_focal": null})
    );
}

#[test]
fn scene_flag_and_environment_variable() {
    let out = sctl()
        .env("SCTL_DATA_ROOT", shared_data_root())
        .args([
            "inspect",
            "--dataset",
            "adelaidermf",
            "--scene",
            "breadtoycar",
        ])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let lines = json_lines(&out);
    assert_eq!(lines.len(), 1);
    assert_eq!(lines[0]["n"], 166);
    assert_eq!(lines[0]["motions"], 3);
    assert_eq!(lines[0]["outliers"], 56);

    // The flag wins over the environment variable.
    sctl()
        .env("SCTL_DATA_ROOT", "/nonexistent")
        .args([
            "inspect",
            "--dataset",
            "adelaidermf",
            "--scene",
            "book",
            "--data-root",
        ])
        .arg(shared_data_root())
        .assert()
        .success()
        .stdout(predicate::str::contains("\"n\":187"));
}

#[test]
fn unknown_scene_and_missing_dataset_fail_with_a_hint() {
    sctl()
        .args([
            "inspect",
            "--dataset",
            "adelaidermf",
            "--scene",
            "nosuch",
            "--data-root",
        ])
        .arg(shared_data_root())
        .assert()
        .failure()
        .stderr(predicate::str::contains("no scene named `nosuch`"));
    sctl()
        .args([
            "inspect",
            "--dataset",
            "hopef",
            "--data-root",
            "/nonexistent/root",
        ])
        .assert()
        .failure()
        .stderr(predicate::str::contains("/nonexistent/root/hopef"))
        .stderr(predicate::str::contains("scripts/link-datasets.sh"));
}

#[test]
fn hopef_fixtures_under_a_data_root() {
    // <root>/hopef -> the good fixtures.
    let root = tempfile::tempdir().unwrap();
    std::os::unix::fs::symlink(fixtures("good"), root.path().join("hopef")).unwrap();
    let out = sctl()
        .args(["inspect", "--dataset", "hopef", "--data-root"])
        .arg(root.path())
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let text = String::from_utf8(out).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), 12);
    // Exact text: field order, and the focal printed to full precision.
    assert_eq!(
        lines[4],
        r#"{"name":"2/0001","n":216,"motions":2,"outliers":21,"width":1024,"height":1024,"has_images":false,"true_focal":983.6376457777931}"#
    );
    sctl()
        .args([
            "inspect",
            "--dataset",
            "hopef",
            "--scene",
            "4/0002",
            "--dir",
        ])
        .arg(fixtures("good"))
        .assert()
        .success()
        .stdout(predicate::str::contains(
            "\"name\":\"4/0002\",\"n\":370,\"motions\":4,\"outliers\":33",
        ));
    sctl()
        .args(["inspect", "--dataset", "hopef", "--split", "test", "--dir"])
        .arg(fixtures("good"))
        .assert()
        .failure()
        .stderr(predicate::str::contains("no HOPE-F scene folders"));
}

#[test]
fn bad_files_exit_non_zero_naming_the_file() {
    for (case, problem) in [
        ("nan_points", "non-finite coordinate"),
        ("truncated", "not a readable .npz archive"),
        ("missing_labels", "missing array `labels`"),
        ("length_mismatch", "does not match points1"),
    ] {
        let dir = fixtures("bad").join(case);
        let file = dir.join("1/0000/features_and_ground_truth.npz");
        sctl()
            .args(["inspect", "--dataset", "hopef", "--dir"])
            .arg(&dir)
            .assert()
            .failure()
            .stdout(predicate::str::is_empty())
            .stderr(predicate::str::contains(file.display().to_string()))
            .stderr(predicate::str::contains(problem))
            .stderr(predicate::str::contains("1 of 1 scenes failed to load"));
    }
}

#[test]
fn a_corrupt_mat_file_is_named_and_the_others_still_print() {
    let dir = tempfile::tempdir().unwrap();
    let src = shared_data_root().join("adelaidermf/F");
    for name in datasets::adelaidermf::FUNDAMENTAL_SCENES {
        let from = src.join(format!("{name}.mat"));
        let to = dir.path().join(format!("{name}.mat"));
        if name == "cube" {
            let bytes = std::fs::read(&from).unwrap();
            std::fs::write(&to, &bytes[..bytes.len() / 3]).unwrap();
        } else {
            std::os::unix::fs::symlink(&from, &to).unwrap();
        }
    }
    let output = sctl()
        .args(["inspect", "--dataset", "adelaidermf", "--dir"])
        .arg(dir.path())
        .assert()
        .failure()
        .stderr(predicate::str::contains(format!(
            "{}: not a readable MAT v5 file",
            dir.path().join("cube.mat").display()
        )))
        .stderr(predicate::str::contains("1 of 19 scenes failed to load"))
        .get_output()
        .stdout
        .clone();
    assert_eq!(json_lines(&output).len(), 18);
}
