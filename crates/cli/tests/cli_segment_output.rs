//! Issue 40 for `sctl segment`: closed pipes, full disks and file-size
//! limits; absurd coordinates and command-line values (one check, the
//! library's, for `sctl segment` and `sctl run`); the focal prior; JPEG
//! backgrounds.

mod support;
use support::sctl;

use predicates::prelude::*;
use std::fmt::Write as _;
use std::path::Path;
use std::process::Stdio;

/// A synthetic two-motion 1024 x 768 scene as `x1,y1,x2,y2`, with row
/// `edit.0` (0-based) replaced by `edit.1` when given.
fn write_matches(path: &Path, edits: &[(usize, &str)]) {
    let scene = support::quick_scene(1, 900);
    let mut rows: Vec<String> = scene
        .points1
        .iter()
        .zip(&scene.points2)
        .map(|(p, q)| format!("{},{},{},{}", p[0], p[1], q[0], q[1]))
        .collect();
    for (row, text) in edits {
        rows[*row] = text.to_string();
    }
    let mut text = String::from("x1,y1,x2,y2\n");
    for row in rows {
        let _ = writeln!(text, "{row}");
    }
    std::fs::write(path, text).unwrap();
}

fn segment(matches: &Path) -> assert_cmd::Command {
    let mut cmd = sctl();
    cmd.arg("segment")
        .arg("--matches")
        .arg(matches)
        .args(["--width", "1024", "--height", "768"]);
    cmd
}

#[test]
fn a_closed_pipe_ends_quietly() {
    let dir = tempfile::tempdir().unwrap();
    let matches = dir.path().join("pair.csv");
    write_matches(&matches, &[]);
    for out in [&["--out", "-"][..], &[][..]] {
        let mut child = std::process::Command::new(assert_cmd::cargo::cargo_bin("sctl"))
            .arg("segment")
            .arg("--matches")
            .arg(&matches)
            .args(["--width", "1024", "--height", "768"])
            .args(out)
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        // The reader goes away before anything is written (`| head -0`).
        drop(child.stdout.take());
        let output = child.wait_with_output().unwrap();
        let stderr = String::from_utf8(output.stderr).unwrap();
        assert_eq!(output.status.code(), Some(0), "{out:?}: {stderr}");
        assert!(
            !stderr.contains("panicked") && !stderr.contains("error"),
            "{stderr}"
        );
    }
}

#[test]
fn a_file_size_limit_leaves_no_partial_file() {
    let dir = tempfile::tempdir().unwrap();
    let matches = dir.path().join("pair.csv");
    write_matches(&matches, &[]);
    let labels = dir.path().join("labels.txt");
    let plot = dir.path().join("clusters.png");
    std::fs::write(&labels, "earlier labels\n").unwrap();
    let sctl = assert_cmd::cargo::cargo_bin("sctl");
    // 1 block of 512 bytes: the labels (about 170 bytes) fit, the figure
    // does not; SIGXFSZ ignored so that the write fails with EFBIG.
    let script = format!(
        "trap '' XFSZ; ulimit -f 1; exec '{}' segment --matches '{}' --width 1024 --height 768 --out '{}' --plot '{}'",
        sctl.display(),
        matches.display(),
        labels.display(),
        plot.display()
    );
    let output = std::process::Command::new("sh")
        .args(["-c", &script])
        .output()
        .unwrap();
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("clusters.png: cannot write the figure: File too large"),
        "{stderr}"
    );
    assert!(!plot.exists(), "a partial figure was left");
    assert_eq!(
        std::fs::read_to_string(&labels).unwrap(),
        "earlier labels\n"
    );
    let mut names: Vec<String> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(names, ["labels.txt", "pair.csv"], "temporary files left");

    // Without the limit both are written whole.
    segment(&matches)
        .arg("--out")
        .arg(&labels)
        .arg("--plot")
        .arg(&plot)
        .assert()
        .success();
    let written = std::fs::read_to_string(&labels).unwrap();
    assert_eq!(written.lines().count(), support::quick_scene(1, 900).len());
    assert!(image::open(&plot).is_ok());
}

#[test]
fn absurd_coordinates_are_refused_and_far_ones_warned_about() {
    let dir = tempfile::tempdir().unwrap();
    let absurd = dir.path().join("absurd.csv");
    write_matches(&absurd, &[(4, "1e200,3,4,5")]);
    segment(&absurd)
        .assert()
        .code(1)
        .stderr(predicate::str::contains(
            "absurd.csv: match row 4, column x1: coordinate 1e200 is not a finite number within ±1e6 px",
        ));
    let far = dir.path().join("far.csv");
    write_matches(&far, &[(4, "-5000,3,4,5"), (6, "4,5,4000,5")]);
    let output = segment(&far).output().unwrap();
    assert!(output.status.success());
    let stderr = String::from_utf8(output.stderr).unwrap();
    let warning = "far.csv: 2 of 51 matches lie more than one image size outside the 1024 x 768 \
                   image (first: row 4, x1 = -5000";
    assert!(
        stderr.starts_with("warning: ") && stderr.contains(warning),
        "{stderr}"
    );
    // One check, the library's: the warning is printed once.
    assert_eq!(stderr.matches("lie more than").count(), 1, "{stderr}");
}

#[test]
fn sctl_run_prints_the_same_input_warning_once_per_scene() {
    let dir = tempfile::tempdir().unwrap();
    write_matches(&dir.path().join("far.csv"), &[(4, "-5000,3,4,5")]);
    // Not far.toml: that name is far.csv's sidecar.
    let config = dir.path().join("experiment.toml");
    std::fs::write(
        &config,
        "name = \"far\"\n[dataset]\nkind = \"csv\"\nfiles = [\"far.csv\"]\nwidth = 1024\nheight = 768\n\
         [pipeline]\nnum_samples = 100\n[sweep]\nseed = [1, 2]\n[plots]\nenabled = false\n",
    )
    .unwrap();
    let output = sctl()
        .arg("run")
        .arg(&config)
        .arg("--data-root")
        .arg(dir.path())
        .arg("--out")
        .arg(dir.path().join("out"))
        .arg("--quiet")
        .output()
        .unwrap();
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert!(output.status.success(), "{stderr}");
    // Two seeds, one scene: one warning, naming the scene.
    assert_eq!(
        stderr.matches("lie more than one image size").count(),
        1,
        "{stderr}"
    );
    assert!(
        stderr.contains("warning: scene far: 1 of 51 matches"),
        "{stderr}"
    );
}

#[test]
fn negative_and_long_values_are_named_by_the_range_check() {
    let dir = tempfile::tempdir().unwrap();
    let matches = dir.path().join("pair.csv");
    write_matches(&matches, &[]);
    let run = |args: &[&str], message: &str| {
        let mut cmd = sctl();
        cmd.arg("segment").arg("--matches").arg(&matches).args(args);
        cmd.assert()
            .code(2)
            .stderr(predicate::str::contains(message));
    };
    run(
        &["--width", "-1024", "--height", "768"],
        "-1024 pixels: give 1 to 200000",
    );
    run(
        &["--width", "1024", "--height", "-7"],
        "-7 pixels: give 1 to 200000",
    );
    run(
        &["--width", "1024", "--height", "768", "--focal", "-5"],
        "-5: give a focal length in pixels, > 0",
    );
    let long = "7x".repeat(5_000);
    let output = sctl()
        .arg("segment")
        .arg("--matches")
        .arg(&matches)
        .args(["--width", &long, "--height", "768"])
        .output()
        .unwrap();
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert!(
        stderr.contains("… (10000 characters)` is not a whole number"),
        "{stderr}"
    );
    // clap quotes the argument itself before the message; the message cuts it.
}

#[test]
fn the_focal_prior_is_the_one_given() {
    let dir = tempfile::tempdir().unwrap();
    let matches = dir.path().join("pair.csv");
    write_matches(&matches, &[]);
    segment(&matches)
        .args(["--focal", "700", "--threads", "1"])
        .assert()
        .success()
        .stdout(predicate::str::contains(
            "five-point hypotheses at the focal prior 700 px",
        ));
    // The prior reaches the five-point solver: other hypothesis counts
    // than at max(W, H) = 1024.
    let counts = |focal: &str| {
        let output = segment(&matches)
            .args(["--focal", focal, "--threads", "1"])
            .output()
            .unwrap();
        assert!(output.status.success());
        let stdout = String::from_utf8(output.stdout).unwrap();
        let at = stdout.find("hypotheses kept").unwrap();
        stdout[at..].lines().next().unwrap().to_string()
    };
    assert_ne!(counts("300"), counts("1024"));
}

#[test]
fn jpeg_backgrounds_are_drawn_under_the_clusters() {
    let dir = tempfile::tempdir().unwrap();
    let matches = dir.path().join("pair.csv");
    write_matches(&matches, &[]);
    let teal = [10u8, 200, 150];
    let (a, b) = (dir.path().join("a.jpg"), dir.path().join("b.jpeg"));
    for path in [&a, &b] {
        image::RgbImage::from_pixel(1024, 768, image::Rgb(teal))
            .save_with_format(path, image::ImageFormat::Jpeg)
            .unwrap();
    }
    let plot = dir.path().join("over.png");
    segment(&matches)
        .arg("--plot")
        .arg(&plot)
        .arg("--image1")
        .arg(&a)
        .arg("--image2")
        .arg(&b)
        .assert()
        .success();
    let figure = image::open(&plot).unwrap().to_rgb8();
    let near_teal = figure
        .pixels()
        .filter(|p| p.0.iter().zip(teal).all(|(&c, t)| c.abs_diff(t) <= 4))
        .count();
    assert!(
        near_teal > 2 * 800 * 600 * 8 / 10,
        "{near_teal} teal pixels"
    );
}
