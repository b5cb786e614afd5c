//! `sctl metrics` end to end: JSON output on label files, and one-line
//! errors naming the file and token on bad input.

use std::path::{Path, PathBuf};

use assert_cmd::Command;
use predicates::prelude::*;
use serde_json::Value;
use tempfile::TempDir;

fn write(dir: &TempDir, name: &str, text: &str) -> PathBuf {
    let path = dir.path().join(name);
    std::fs::write(&path, text).unwrap();
    path
}

fn sctl_metrics(gt: &Path, pred: &Path) -> assert_cmd::assert::Assert {
    Command::cargo_bin("sctl")
        .unwrap()
        .arg("metrics")
        .arg("--gt")
        .arg(gt)
        .arg("--pred")
        .arg(pred)
        .assert()
}

fn json_of(assert: assert_cmd::assert::Assert) -> Value {
    let out = assert.success().get_output().stdout.clone();
    let text = String::from_utf8(out).unwrap();
    assert_eq!(text.lines().count(), 1, "one JSON line expected: {text}");
    serde_json::from_str(&text).unwrap()
}

#[test]
fn prints_every_metric_as_one_json_object() {
    let dir = TempDir::new().unwrap();
    // Newlines, tabs and repeated spaces all separate labels.
    let gt = write(&dir, "gt.txt", "1 1 1\n2\t2 2\n  0 0\n");
    let pred = write(&dir, "pred.txt", "7 7 7 3 3 -1 -1 3\n");
    let v = json_of(sctl_metrics(&gt, &pred));
    let keys: Vec<&str> = v.as_object().unwrap().keys().map(String::as_str).collect();
    for key in ["me", "acc", "fnr", "pur", "ari", "nmi"] {
        assert!(keys.contains(&key), "missing {key} in {v}");
    }
    // 6 inliers; clusters 7 -> motion 1 (3 points) and 3 -> motion 2 (2 points).
    let me = v["me"].as_f64().unwrap();
    assert!((me - 1.0 / 6.0).abs() < 1e-12, "{v}");
    assert!((v["acc"].as_f64().unwrap() - 5.0 / 6.0).abs() < 1e-12);
    // Cluster 3 = {2, 2, 0}: purity (3 + 2) / 6.
    assert!((v["pur"].as_f64().unwrap() - 5.0 / 6.0).abs() < 1e-12);
    // All 8 points: the rejected outlier is right, the rejected motion-2
    // point and the outlier in cluster 3 are wrong.
    assert!(
        (v["me_all"].as_f64().unwrap() - 2.0 / 8.0).abs() < 1e-12,
        "{v}"
    );
    let lib =
        metrics::ClusteringMetrics::compute(&[7, 7, 7, 3, 3, -1, -1, 3], &[1, 1, 1, 2, 2, 2, 0, 0])
            .unwrap();
    assert_eq!(v["ari"].as_f64().unwrap(), lib.ari);
    assert_eq!(v["nmi"].as_f64().unwrap(), lib.nmi);
    assert_eq!(v["fnr"].as_f64().unwrap(), lib.fnr);
}

#[test]
fn a_perfect_relabelled_prediction_scores_zero_error() {
    let dir = TempDir::new().unwrap();
    let gt = write(&dir, "gt.txt", "1 1 2 2 0");
    let pred = write(&dir, "pred.txt", "4 4 9 9 -1");
    let v = json_of(sctl_metrics(&gt, &pred));
    assert_eq!(v["me"].as_f64(), Some(0.0));
    assert_eq!(v["ari"].as_f64(), Some(1.0));
}

#[test]
fn a_non_integer_token_names_file_position_and_token() {
    let dir = TempDir::new().unwrap();
    let gt = write(&dir, "gt.txt", "1 1 2 2 0");
    let pred = write(&dir, "pred.txt", "4 4\n9 x9 -1");
    sctl_metrics(&gt, &pred)
        .failure()
        .stdout(predicate::str::is_empty())
        .stderr(predicate::str::contains(
            "pred.txt: token 4 (line 2) is \"x9\", not an integer label",
        ))
        .stderr(predicate::function(|s: &str| s.lines().count() == 1));
}

#[test]
fn a_length_mismatch_names_both_files() {
    let dir = TempDir::new().unwrap();
    let gt = write(&dir, "gt.txt", "1 1 2 2 0");
    let pred = write(&dir, "pred.txt", "4 4 9 9");
    sctl_metrics(&gt, &pred)
        .failure()
        .stderr(predicate::str::contains("gt.txt has 5 labels but"))
        .stderr(predicate::str::contains("pred.txt has 4"));
}

#[test]
fn an_empty_file_is_rejected() {
    let dir = TempDir::new().unwrap();
    let gt = write(&dir, "gt.txt", " \n\n");
    let pred = write(&dir, "pred.txt", "4 4 9 9");
    sctl_metrics(&gt, &pred)
        .failure()
        .stderr(predicate::str::contains("gt.txt: empty"));
}

#[test]
fn out_of_range_labels_are_rejected_with_their_position() {
    let dir = TempDir::new().unwrap();
    let gt = write(&dir, "gt.txt", "1 1 2 2 0");
    let pred = write(&dir, "pred.txt", "4 4 9 -3 -1");
    sctl_metrics(&gt, &pred)
        .failure()
        .stderr(predicate::str::contains("pred.txt: token 4 is -3"));
    let bad_gt = write(&dir, "bad_gt.txt", "1 -1 2 2 0");
    let good_pred = write(&dir, "good.txt", "4 4 9 9 -1");
    sctl_metrics(&bad_gt, &good_pred)
        .failure()
        .stderr(predicate::str::contains("bad_gt.txt: token 2 is -1"));
}

#[test]
fn a_missing_file_is_named() {
    let dir = TempDir::new().unwrap();
    let pred = write(&dir, "pred.txt", "4 4 9 9");
    sctl_metrics(&dir.path().join("nope.txt"), &pred)
        .failure()
        .stderr(predicate::str::contains("cannot read").and(predicate::str::contains("nope.txt")));
}

#[test]
fn help_documents_every_option() {
    Command::cargo_bin("sctl")
        .unwrap()
        .args(["metrics", "--help"])
        .assert()
        .success()
        .stdout(predicate::str::contains("--gt <GT.txt>"))
        .stdout(predicate::str::contains("--pred <PRED.txt>"))
        .stdout(predicate::str::contains("0 = gross outlier"))
        .stdout(predicate::str::contains("-1 = rejected as outlier"))
        .stdout(predicate::str::contains("nmi"));
}
