//! `sctl tlinkage` from the outside: labels of known matrices, agreement with
//! the library, and one clear error line on bad input.

mod support;
use support::sctl;

use predicates::prelude::*;
use std::io::Write;
use tempfile::NamedTempFile;

fn csv_file(text: &str) -> NamedTempFile {
    let mut file = NamedTempFile::new().unwrap();
    file.write_all(text.as_bytes()).unwrap();
    file
}

/// Two blocks of preferences, interleaved: points 0, 2, 4 prefer hypotheses
/// 0-1, points 1, 3 prefer hypotheses 2-3, point 5 prefers nothing.
const TWO_BLOCKS: &str = "\
1,0.9,0,0
0,0,1,0.8
0.9,1,0,0
0,0,0.7,1
0.8,0.8,0,0
0,0,0,0
";

fn labels(output: &[u8]) -> Vec<i32> {
    String::from_utf8(output.to_vec())
        .unwrap()
        .lines()
        .map(|l| l.parse().unwrap())
        .collect()
}

#[test]
fn t_linkage_prints_one_label_per_point() {
    let file = csv_file(TWO_BLOCKS);
    let out = sctl()
        .args(["tlinkage", "--input"])
        .arg(file.path())
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    // No filter by default: the empty row is its own cluster.
    assert_eq!(labels(&out), vec![0, 1, 0, 1, 0, 2]);
}

#[test]
fn min_cluster_size_marks_small_clusters() {
    let file = csv_file(TWO_BLOCKS);
    sctl()
        .args(["tlinkage", "--min-cluster-size", "3", "--input"])
        .arg(file.path())
        .assert()
        .success()
        .stdout("0\n-1\n0\n-1\n0\n-1\n");
}

#[test]
fn j_linkage_thresholds_residuals() {
    // Residuals: points 0-2 fit hypotheses 0-1 (r <= 2), points 3-4 fit hypothesis 2.
    let file = csv_file("0,1,9\n2,0.5,9\n1,1,50\n9,9,0\n30,9,2\n");
    sctl()
        .args(["tlinkage", "--jlinkage", "--tau", "2", "--input"])
        .arg(file.path())
        .assert()
        .success()
        .stdout("0\n0\n0\n1\n1\n");
    // With tau = 0.1 only r = 0 counts: point 0 prefers {0}, point 3 {2},
    // the others nothing; no two points share a hypothesis.
    sctl()
        .args(["tlinkage", "--jlinkage", "--tau", "0.1", "--input"])
        .arg(file.path())
        .assert()
        .success()
        .stdout("0\n1\n2\n3\n4\n");
}

#[test]
fn labels_match_the_library_on_a_random_matrix() {
    // A deterministic pseudo-random 60 x 40 matrix with a block structure.
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let rows: Vec<Vec<f64>> = (0..60)
        .map(|i| {
            (0..40)
                .map(|j| {
                    let p = if i % 3 == j % 3 { 0.7 } else { 0.1 };
                    if next() < p {
                        (-5.0 * next()).exp()
                    } else {
                        0.0
                    }
                })
                .collect()
        })
        .collect();
    let text: String = rows
        .iter()
        .map(|r| {
            r.iter()
                .map(|v| format!("{v:e}"))
                .collect::<Vec<_>>()
                .join(",")
                + "\n"
        })
        .collect();
    let file = csv_file(&text);
    let out = sctl()
        .args(["tlinkage", "--min-cluster-size", "4", "--input"])
        .arg(file.path())
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let p = clustering::PreferenceMatrix::from_rows(&rows).unwrap();
    assert_eq!(labels(&out), clustering::t_linkage(&p, 4).labels);
    assert_eq!(labels(&out), clustering::reference::t_linkage(&p, 4).labels);
}

/// Runs `sctl tlinkage` on `text` and checks that it fails with exactly one
/// stderr line naming the file and containing `expected`.
fn fails_with(text: &str, extra: &[&str], expected: &str) {
    let file = csv_file(text);
    let name = file.path().display().to_string();
    let assert = sctl()
        .arg("tlinkage")
        .args(extra)
        .arg("--input")
        .arg(file.path())
        .assert()
        .failure()
        .stdout("")
        .stderr(predicate::str::contains(expected))
        .stderr(predicate::str::contains(name));
    let stderr = String::from_utf8(assert.get_output().stderr.clone()).unwrap();
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
}

#[test]
fn ragged_rows_are_rejected() {
    fails_with(
        "1,0,0\n0,1\n",
        &[],
        "row 2 (line 2) has 2 values, expected 3 as in row 1",
    );
}

#[test]
fn non_numeric_values_are_rejected() {
    fails_with(
        "1,0\n0,abc\n",
        &[],
        "row 2 (line 2), column 2: 'abc' is not a number",
    );
}

#[test]
fn nan_is_rejected() {
    fails_with(
        "1,NaN\n",
        &[],
        "row 1 (line 1), column 2: NaN is not allowed",
    );
    fails_with(
        "1,NaN\n",
        &["--jlinkage", "--tau", "1"],
        "column 2: NaN is not allowed",
    );
}

#[test]
fn negative_preferences_are_rejected() {
    fails_with(
        "1,0\n\n0.5,-0.25\n",
        &[],
        "row 2 (line 3), column 2: negative preference -0.25",
    );
    fails_with("1,1.5\n", &[], "column 2: preference 1.5 is above 1");
    fails_with(
        "1,-3\n",
        &["--jlinkage", "--tau", "1"],
        "column 2: negative residual -3",
    );
}

#[test]
fn empty_file_is_rejected() {
    fails_with("", &[], "no rows (the file is empty)");
    fails_with("\n  \n", &[], "no rows (the file is empty)");
}

#[test]
fn missing_file_is_rejected() {
    sctl()
        .args(["tlinkage", "--input", "/nonexistent/p.csv"])
        .assert()
        .failure()
        .stderr(predicate::str::contains("cannot read /nonexistent/p.csv"));
}

#[test]
fn tau_and_jlinkage_go_together() {
    let file = csv_file("1,0\n");
    sctl()
        .args(["tlinkage", "--jlinkage", "--input"])
        .arg(file.path())
        .assert()
        .failure()
        .stderr(predicate::str::contains("--tau"));
    sctl()
        .args(["tlinkage", "--tau", "2", "--input"])
        .arg(file.path())
        .assert()
        .failure()
        .stderr(predicate::str::contains("--jlinkage"));
    for tau in ["-1", "0", "NaN", "inf"] {
        sctl()
            .args(["tlinkage", "--jlinkage", "--tau", tau, "--input"])
            .arg(file.path())
            .assert()
            .failure()
            .stderr(predicate::str::contains("must be finite and > 0"));
    }
}

#[test]
fn help_documents_the_input() {
    sctl()
        .args(["tlinkage", "--help"])
        .assert()
        .success()
        .stdout(predicate::str::contains("preferences phi_ij in [0, 1]"))
        .stdout(predicate::str::contains("residuals r_ij >= 0"));
}
