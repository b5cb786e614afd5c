//! `sctl wilcoxon` end to end: JSON output on value files, options, and
//! one-line errors naming the file and token on bad input.

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

fn sctl_wilcoxon(a: &Path, b: &Path, extra: &[&str]) -> assert_cmd::assert::Assert {
    Command::cargo_bin("sctl")
        .unwrap()
        .arg("wilcoxon")
        .arg("--baseline")
        .arg(a)
        .arg("--method")
        .arg(b)
        .args(extra)
        .assert()
}

fn json_of(assert: assert_cmd::assert::Assert) -> Value {
    let out = assert.success().get_output().stdout.clone();
    let text = String::from_utf8(out).unwrap();
    assert_eq!(text.lines().count(), 1, "one JSON line expected: {text}");
    serde_json::from_str(&text).unwrap()
}

const BASELINE: &str = "0.30 0.12 0.25\n0.40 0.18 0.22 0.35 0.09\n";
const METHOD: &str = "0.20 0.10 0.28 0.15 0.12 0.21 0.30 0.02\n";

#[test]
fn default_is_one_tailed_greater_with_auto_mode() {
    let dir = TempDir::new().unwrap();
    let a = write(&dir, "a.txt", BASELINE);
    let b = write(&dir, "b.txt", METHOD);
    let v = json_of(sctl_wilcoxon(&a, &b, &[]));
    // Differences 0.10 0.02 -0.03 0.25 0.06 0.01 0.05 0.07: T+ = 36 - 3, and
    // T+ >= 33 in 5 of the 256 sign patterns (scipy: 0.01953125).
    assert_eq!(v["statistic"].as_f64(), Some(33.0));
    assert_eq!(v["p_value"].as_f64(), Some(5.0 / 256.0));
    assert_eq!(v["mode_used"].as_str(), Some("exact"));
    assert_eq!(v["n"].as_u64(), Some(8));
    assert_eq!(v["n_zero"].as_u64(), Some(0));
}

#[test]
fn alternative_and_mode_options_are_honoured() {
    let dir = TempDir::new().unwrap();
    let a = write(&dir, "a.txt", BASELINE);
    let b = write(&dir, "b.txt", METHOD);
    let less = json_of(sctl_wilcoxon(&a, &b, &["--alternative", "less"]));
    // P(T+ <= 33) = 1 - P(T+ >= 34) = 1 - 3/256.
    assert_eq!(less["p_value"].as_f64(), Some(253.0 / 256.0));
    let two = json_of(sctl_wilcoxon(&a, &b, &["--alternative", "two-sided"]));
    assert_eq!(two["statistic"].as_f64(), Some(3.0));
    assert_eq!(two["p_value"].as_f64(), Some(10.0 / 256.0));
    let approx = json_of(sctl_wilcoxon(&a, &b, &["--mode", "approx"]));
    assert_eq!(approx["mode_used"].as_str(), Some("approx"));
    // scipy.stats.wilcoxon(a, b, alternative='greater', method='approx').
    let p = approx["p_value"].as_f64().unwrap();
    assert!((p - 0.017845950058402206).abs() < 1e-9 * p, "{p}");
    let exact = json_of(sctl_wilcoxon(&a, &b, &["--mode", "exact"]));
    assert_eq!(exact["mode_used"].as_str(), Some("exact"));
}

#[test]
fn ties_and_zeros_in_a_small_sample_use_the_permutation_branch() {
    let dir = TempDir::new().unwrap();
    let a = write(&dir, "a.txt", "1 2 3 4 5 6");
    let b = write(&dir, "b.txt", "0 0 2 3 5 6");
    // Differences 1 2 1 1 0 0: zeros and ties.
    let v = json_of(sctl_wilcoxon(&a, &b, &[]));
    assert_eq!(v["mode_used"].as_str(), Some("permutation"));
    assert_eq!(v["n"].as_u64(), Some(4));
    assert_eq!(v["n_zero"].as_u64(), Some(2));
    // All four non-zero differences positive: only 1 of 16 sign patterns reaches T+ = 10.
    assert_eq!(v["statistic"].as_f64(), Some(10.0));
    assert_eq!(v["p_value"].as_f64(), Some(1.0 / 16.0));
}

#[test]
fn a_non_numeric_token_names_file_position_and_token() {
    let dir = TempDir::new().unwrap();
    let a = write(&dir, "a.txt", BASELINE);
    let b = write(&dir, "b.txt", "0.20 0.10\n0.28 0,15 0.12 0.21 0.30 0.02\n");
    sctl_wilcoxon(&a, &b, &[])
        .failure()
        .stdout(predicate::str::is_empty())
        .stderr(predicate::str::contains(
            "b.txt: token 4 (line 2) is \"0,15\", not a finite number",
        ))
        .stderr(predicate::function(|s: &str| s.lines().count() == 1));
}

#[test]
fn nan_and_infinity_are_rejected() {
    let dir = TempDir::new().unwrap();
    let a = write(&dir, "a.txt", "1 2 NaN");
    let b = write(&dir, "b.txt", "1 2 3");
    sctl_wilcoxon(&a, &b, &[])
        .failure()
        .stderr(predicate::str::contains(
            "a.txt: token 3 (line 1) is \"NaN\"",
        ));
    let c = write(&dir, "c.txt", "inf 2 3");
    sctl_wilcoxon(&c, &b, &[])
        .failure()
        .stderr(predicate::str::contains("c.txt: token 1"));
}

#[test]
fn a_length_mismatch_names_both_files() {
    let dir = TempDir::new().unwrap();
    let a = write(&dir, "a.txt", BASELINE);
    let b = write(&dir, "b.txt", "0.2 0.1");
    sctl_wilcoxon(&a, &b, &[])
        .failure()
        .stderr(predicate::str::contains("a.txt has 8 values but"))
        .stderr(predicate::str::contains("b.txt has 2"));
}

#[test]
fn empty_input_and_all_zero_differences_are_errors() {
    let dir = TempDir::new().unwrap();
    let empty = write(&dir, "empty.txt", "\n");
    let b = write(&dir, "b.txt", "1 2");
    sctl_wilcoxon(&empty, &b, &[])
        .failure()
        .stderr(predicate::str::contains("empty.txt: empty"));
    sctl_wilcoxon(&b, &b, &[])
        .failure()
        .stderr(predicate::str::contains("all 2 differences are zero"));
}

#[test]
fn bad_option_values_are_rejected() {
    let dir = TempDir::new().unwrap();
    let a = write(&dir, "a.txt", BASELINE);
    let b = write(&dir, "b.txt", METHOD);
    sctl_wilcoxon(&a, &b, &["--alternative", "bigger"])
        .failure()
        .stderr(predicate::str::contains("greater"));
    sctl_wilcoxon(&a, &b, &["--mode", "permutation"]).failure();
}

#[test]
fn help_documents_every_option() {
    Command::cargo_bin("sctl")
        .unwrap()
        .args(["wilcoxon", "--help"])
        .assert()
        .success()
        .stdout(predicate::str::contains("--baseline <A.txt>"))
        .stdout(predicate::str::contains("--method <B.txt>"))
        .stdout(predicate::str::contains("--alternative <ALTERNATIVE>"))
        .stdout(predicate::str::contains("two-sided"))
        .stdout(predicate::str::contains("--mode <MODE>"))
        .stdout(predicate::str::contains("approx"))
        .stdout(predicate::str::contains("[default: greater]"))
        .stdout(predicate::str::contains("[default: auto]"));
}
