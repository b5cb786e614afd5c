//! `sctl compare` on two hand-written `per_scene.csv` files.

mod support;
use support::{sctl, PER_SCENE_COLUMNS as PER_SCENE_FIELDS};

use predicates::prelude::*;
use std::path::Path;

/// A `per_scene.csv` with one parameter column `method` and the given
/// (method, scene, me) rows.
fn write_run(dir: &Path, rows: &[(&str, &str, f64)]) {
    std::fs::create_dir_all(dir).unwrap();
    let mut text = format!("method,{}\n", PER_SCENE_FIELDS.join(","));
    for (method, scene, me) in rows {
        let mut cells = vec![String::new(); PER_SCENE_FIELDS.len()];
        cells[0] = scene.to_string();
        cells[1] = "100".into();
        let column = |name: &str| PER_SCENE_FIELDS.iter().position(|f| *f == name).unwrap();
        cells[column("me")] = format!("{me:.6}");
        cells[column("me_all")] = format!("{:.6}", me / 2.0);
        cells[column("acc")] = format!("{:.6}", 1.0 - me);
        text += &format!("{method},{}\n", cells.join(","));
    }
    std::fs::write(dir.join("per_scene.csv"), text).unwrap();
}

#[test]
fn compares_two_runs_on_their_common_scenes() {
    let root = tempfile::tempdir().unwrap();
    let a = root.path().join("a");
    let b = root.path().join("b");
    // A is better on s1..s5, worse on s6; s7 only in A.
    write_run(
        &a,
        &[
            ("semical", "s1", 0.10),
            ("semical", "s2", 0.20),
            ("semical", "s3", 0.05),
            ("semical", "s4", 0.00),
            ("semical", "s5", 0.30),
            ("semical", "s6", 0.50),
            ("semical", "s7", 0.90),
        ],
    );
    write_run(
        &b,
        &[
            ("baseline", "s6", 0.40),
            ("baseline", "s1", 0.15),
            ("baseline", "s2", 0.40),
            ("baseline", "s3", 0.08),
            ("baseline", "s4", 0.30),
            ("baseline", "s5", 0.60),
        ],
    );
    // Differences A - B: -0.05, -0.2, -0.03, -0.3, -0.3, +0.1: ranks with a
    // tie at 0.3; T+ = rank of 0.1 = 3; H1 "A better" p = P(T+ <= 3) under
    // the permutation distribution of the tied ranks = 5/64.
    sctl()
        .arg("compare")
        .arg(&a)
        .arg(b.join("per_scene.csv"))
        .assert()
        .success()
        .stdout(predicate::str::contains("6 common scenes, metric ME"))
        .stdout(predicate::str::contains(
            "mean A 19.1667 %, mean B 32.1667 %",
        ))
        .stdout(predicate::str::contains(
            "A better on 5, B better on 1, ties 0",
        ))
        .stdout(predicate::str::contains(
            "H1 A better: 7.8125e-2 (permutation, n = 6)",
        ));
    sctl()
        .arg("compare")
        .arg(&a)
        .arg(&b)
        .args(["--metric", "acc"])
        .assert()
        .success()
        .stdout(predicate::str::contains("A better on 5, B better on 1"));
    sctl()
        .arg("compare")
        .arg(&a)
        .arg(&b)
        .args(["--metric", "me_all"])
        .assert()
        .success()
        .stdout(predicate::str::contains(
            "mean A 9.5833 %, mean B 16.0833 %",
        ));
}

#[test]
fn ambiguous_or_bad_requests_are_errors() {
    let root = tempfile::tempdir().unwrap();
    let both = root.path().join("both");
    write_run(&both, &[("baseline", "s1", 0.1), ("semical", "s1", 0.2)]);
    sctl()
        .arg("compare")
        .arg(&both)
        .arg(&both)
        .assert()
        .failure()
        .stderr(predicate::str::contains("2 combinations match"));
    sctl()
        .arg("compare")
        .arg(&both)
        .arg(&both)
        .args(["--a", "method=semical", "--b", "method=baseline"])
        .assert()
        .success()
        .stdout(predicate::str::contains("B better on 1"));
    sctl()
        .arg("compare")
        .arg(&both)
        .arg(&both)
        .args(["--a", "seed=1"])
        .assert()
        .failure()
        .stderr(predicate::str::contains("no parameter column `seed`"));
    sctl()
        .arg("compare")
        .arg(&both)
        .arg(&both)
        .args([
            "--a",
            "method=semical",
            "--b",
            "method=baseline",
            "--metric",
            "speed",
        ])
        .assert()
        .failure()
        .stderr(predicate::str::contains("no column `speed`"));
    sctl()
        .arg("compare")
        .arg(root.path().join("missing"))
        .arg(&both)
        .assert()
        .failure()
        .stderr(predicate::str::contains("missing: cannot read"));
}
