//! Issue 40 for `sctl run`: a run directory holding another run is refused
//! (never wiped), shards are not mixed on resume, scenes refused for memory
//! are reported and left out of the means, and output errors are reported
//! without panics.

mod support;
use support::sctl;

use predicates::prelude::*;
use std::path::Path;

const CONFIG: &str = r#"
name = "guard"
[dataset]
kind = "synthetic"
preset = "quick"
scenes = ["1/0900", "2/0900"]
[pipeline]
num_samples = 100
"#;

fn write(path: &Path, text: &str) {
    std::fs::write(path, text).unwrap();
}

fn run(config: &Path, out: &Path) -> assert_cmd::Command {
    let mut cmd = sctl();
    cmd.args(["run", "--quiet", "--threads", "1", "--out"])
        .arg(out)
        .arg(config);
    cmd
}

#[test]
fn a_directory_holding_a_run_is_refused_unless_resumed_or_forced() {
    let dir = tempfile::tempdir().unwrap();
    let (a, b) = (dir.path().join("a.toml"), dir.path().join("b.toml"));
    write(&a, CONFIG);
    write(
        &b,
        &CONFIG.replace("num_samples = 100", "num_samples = 120"),
    );
    let out = dir.path().join("D");
    run(&a, &out).assert().success();
    let before = std::fs::read(out.join("per_scene.csv")).unwrap();

    // Another configuration: refused, naming the directory and the key.
    run(&b, &out)
        .assert()
        .failure()
        .stderr(predicate::str::contains(out.display().to_string()))
        .stderr(predicate::str::contains(
            "pipeline.num_samples: 100 there, 120 here",
        ))
        .stderr(predicate::str::contains("--force"));
    assert_eq!(std::fs::read(out.join("per_scene.csv")).unwrap(), before);

    // The same configuration without --resume: refused too.
    run(&a, &out)
        .assert()
        .failure()
        .stderr(predicate::str::contains("--resume completes them"));
    assert_eq!(std::fs::read(out.join("per_scene.csv")).unwrap(), before);

    // --resume completes (nothing to do), --force replaces.
    run(&a, &out)
        .arg("--resume")
        .assert()
        .success()
        .stdout(predicate::str::contains(
            "0 units evaluated, 2 already done",
        ));
    run(&b, &out)
        .arg("--force")
        .assert()
        .success()
        .stdout(predicate::str::contains(
            "2 units evaluated, 0 already done",
        ));
    let config = std::fs::read_to_string(out.join("config.toml")).unwrap();
    assert!(config.contains("num_samples = 120"), "{config}");
}

#[test]
fn resuming_into_another_shards_directory_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let config = dir.path().join("a.toml");
    write(&config, CONFIG);
    let shard2 = dir.path().join("shard2");
    run(&config, &shard2)
        .args(["--shard", "2/2"])
        .assert()
        .success();
    let before = std::fs::read(shard2.join("per_scene.csv")).unwrap();
    run(&config, &shard2)
        .args(["--shard", "1/2", "--resume"])
        .assert()
        .failure()
        .stderr(predicate::str::contains("is not a unit of shard 1/2"));
    assert_eq!(std::fs::read(shard2.join("per_scene.csv")).unwrap(), before);
}

/// `num_samples = 10^8` under `max_memory_mb = 100`: refused before
/// sampling (which alone would take gigabytes and minutes), reported,
/// left out of the means, counted, and a failure unless allowed.
#[test]
fn scenes_refused_for_memory_are_reported_and_left_out_of_the_means() {
    let dir = tempfile::tempdir().unwrap();
    let config = dir.path().join("m.toml");
    let text = CONFIG.replace(
        "num_samples = 100",
        "num_samples = 100000000\nmax_memory_mb = 100",
    );
    write(&config, &text);
    let out = dir.path().join("M");
    run(&config, &out)
        .timeout(std::time::Duration::from_secs(60))
        .assert()
        .code(1)
        .stderr(predicate::str::contains(
            "failed: scene `1/0900` (method=baseline): 51 matches x 100000000 hypotheses",
        ))
        .stderr(predicate::str::contains("max_memory_mb = 100"))
        .stderr(predicate::str::contains("2 unit(s) could not be segmented"))
        .stderr(predicate::str::contains("--allow-failures"));
    let summary = std::fs::read_to_string(out.join("summary.csv")).unwrap();
    let header: Vec<&str> = summary.lines().next().unwrap().split(',').collect();
    let row: Vec<&str> = summary.lines().nth(1).unwrap().split(',').collect();
    let cell = |name: &str| row[header.iter().position(|h| *h == name).unwrap()];
    assert_eq!(cell("failed_scenes"), "2");
    assert_eq!(cell("scenes"), "0");
    assert_eq!(cell("me_mean"), "", "a refused scene is no 100 % ME");
    let report = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(report.contains("## Failed scenes"), "{report}");
    let per_scene = std::fs::read_to_string(out.join("per_scene.csv")).unwrap();
    assert_eq!(per_scene.matches("failed: ").count(), 2, "{per_scene}");

    run(&config, &dir.path().join("M2"))
        .arg("--allow-failures")
        .timeout(std::time::Duration::from_secs(60))
        .assert()
        .success()
        .stderr(predicate::str::contains("warning: 2 unit(s)"));
}

#[test]
fn thread_counts_are_bounded_with_a_clear_error() {
    let dir = tempfile::tempdir().unwrap();
    let config = dir.path().join("a.toml");
    write(&config, CONFIG);
    for (value, message) in [
        ("65535", "65535 threads: give 1 to 1024"),
        ("-3", "-3 threads: give 1 to 1024"),
        ("0", "0 threads: give 1 to 1024"),
    ] {
        sctl()
            .args(["run", "--threads", value])
            .arg(&config)
            .assert()
            .code(2)
            .stderr(predicate::str::contains(message));
    }
}

#[test]
fn a_full_standard_output_is_an_error_not_a_panic() {
    let dir = tempfile::tempdir().unwrap();
    let config = dir.path().join("a.toml");
    write(&config, CONFIG);
    let full = std::fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .unwrap();
    let output = std::process::Command::new(assert_cmd::cargo::cargo_bin("sctl"))
        .args(["run", "--quiet", "--out"])
        .arg(dir.path().join("D"))
        .arg(&config)
        .stdout(full)
        .output()
        .unwrap();
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("error: cannot write to standard output: No space left on device"),
        "{stderr}"
    );
    assert!(!stderr.contains("panicked"), "{stderr}");
}

#[test]
fn errors_do_not_repeat_their_cause() {
    let output = sctl()
        .args(["run", "/nonexistent/exp.toml"])
        .output()
        .unwrap();
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert_eq!(
        stderr.matches("No such file or directory").count(),
        1,
        "{stderr}"
    );
}

#[test]
fn help_says_what_the_tool_does_and_lists_the_product_commands_first() {
    let output = sctl().arg("--help").output().unwrap();
    let help = String::from_utf8(output.stdout).unwrap();
    assert!(
        help.starts_with("Finds the independently moving objects"),
        "{help}"
    );
    let at = |name: &str| help.find(&format!("\n  {name} ")).unwrap_or(usize::MAX);
    for product in ["segment", "run", "compare", "merge", "synth"] {
        assert!(at(product) < at("lab"), "{product} after lab:\n{help}");
    }
    for lab in ["gt-focals", "metrics", "wilcoxon", "focal", "inspect"] {
        assert_eq!(
            at(lab),
            usize::MAX,
            "{lab} listed at the top level:\n{help}"
        );
    }
    // The old invocations and the new ones are the same command.
    for args in [
        &["metrics", "--help"][..],
        &["lab", "metrics", "--help"][..],
    ] {
        sctl()
            .args(args)
            .assert()
            .success()
            .stdout(predicate::str::contains("Usage: sctl lab metrics"));
    }
}
