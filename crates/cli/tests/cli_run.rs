//! `sctl run` and `sctl merge` from the outside: byte-identical outputs at 1
//! and 2 threads, after an interrupted run resumed, and after shards merged;
//! one-line errors naming the file and key for bad configs.

mod support;
use support::{decode_png, one_line_error as assert_one_line_error, sctl};

use predicates::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

const CONFIG: &str = r#"
name = "cli-run"
[dataset]
kind = "synthetic"
preset = "quick"
scenes = ["1/0900", "2/0900", "2/0901"]
[pipeline]
num_samples = 200
[sweep]
method = ["baseline", "semical"]
"#;

const COMPARED: [&str; 4] = [
    "per_scene.csv",
    "summary.csv",
    "wilcoxon.csv",
    "config.toml",
];

struct Fixture {
    _root: tempfile::TempDir,
    config: PathBuf,
    one_thread: PathBuf,
}

/// The config and its run at one thread, shared by the tests.
fn fixture() -> &'static Fixture {
    static FIXTURE: OnceLock<Fixture> = OnceLock::new();
    FIXTURE.get_or_init(|| {
        let root = tempfile::tempdir().unwrap();
        let config = root.path().join("exp.toml");
        std::fs::write(&config, CONFIG).unwrap();
        let one_thread = root.path().join("one");
        sctl()
            .args(["run", "--threads", "1", "--out"])
            .arg(&one_thread)
            .arg(&config)
            .assert()
            .success()
            .stdout(predicate::str::contains("method=semical"));
        Fixture {
            _root: root,
            config,
            one_thread,
        }
    })
}

fn assert_same(a: &Path, b: &Path) {
    for name in COMPARED {
        let x = std::fs::read(a.join(name)).unwrap();
        let y = std::fs::read(b.join(name)).unwrap();
        assert!(
            x == y,
            "{name} differs between {} and {}",
            a.display(),
            b.display()
        );
    }
}

#[test]
fn writes_every_file_with_the_documented_columns() {
    let f = fixture();
    let dir = &f.one_thread;
    for name in COMPARED.iter().chain(&["timings.csv", "report.md"]) {
        assert!(dir.join(name).is_file(), "{name} missing");
    }
    let per_scene = std::fs::read_to_string(dir.join("per_scene.csv")).unwrap();
    let header = per_scene.lines().next().unwrap();
    assert!(
        header.starts_with("method,scene,n,me,me_all,acc,fnr,pur,ari,nmi,frob,"),
        "{header}"
    );
    assert_eq!(per_scene.lines().count(), 1 + 6);
    let summary = std::fs::read_to_string(dir.join("summary.csv")).unwrap();
    assert!(
        summary.starts_with("method,scenes,me_mean,me_std,me_all_mean,me_all_std,acc_mean,"),
        "{summary}"
    );
    let wilcoxon = std::fs::read_to_string(dir.join("wilcoxon.csv")).unwrap();
    let mut lines = wilcoxon.lines();
    assert_eq!(
        lines.next().unwrap(),
        "method,against,metric,n,statistic,p_value,mode_used"
    );
    assert!(lines
        .next()
        .unwrap()
        .starts_with("semical,method=baseline,me,"));
    let report = std::fs::read_to_string(dir.join("report.md")).unwrap();
    assert!(report.contains("## Metrics (mean ± std over scenes)"));
    let timings = std::fs::read_to_string(dir.join("timings.csv")).unwrap();
    assert!(timings.starts_with("method,scene,n,sampling_s,refine_s,focal_s,"));
}

#[test]
fn two_threads_give_the_same_bytes() {
    let f = fixture();
    let dir = tempfile::tempdir().unwrap();
    sctl()
        .args(["run", "--threads", "2", "--out"])
        .arg(dir.path())
        .arg(&f.config)
        .assert()
        .success();
    assert_same(&f.one_thread, dir.path());
}

#[test]
fn resume_after_a_kill_gives_the_same_bytes() {
    let f = fixture();
    let dir = tempfile::tempdir().unwrap();
    // What a run killed after three units leaves: config, three rows in
    // completion order, and half of a fourth.
    for name in ["config.toml", "timings.csv"] {
        std::fs::copy(f.one_thread.join(name), dir.path().join(name)).unwrap();
    }
    let full = std::fs::read_to_string(f.one_thread.join("per_scene.csv")).unwrap();
    let lines: Vec<&str> = full.lines().collect();
    let partial = format!(
        "{}\n{}\n{}\n{}\n{}",
        lines[0],
        lines[5],
        lines[2],
        lines[3],
        &lines[4][..20]
    );
    std::fs::write(dir.path().join("per_scene.csv"), partial).unwrap();
    sctl()
        .args(["run", "--resume", "--out"])
        .arg(dir.path())
        .arg(&f.config)
        .assert()
        .success()
        .stdout(predicate::str::contains(
            "3 units evaluated, 3 already done",
        ));
    assert_same(&f.one_thread, dir.path());
}

#[test]
fn shards_merge_into_the_same_bytes() {
    let f = fixture();
    let root = tempfile::tempdir().unwrap();
    let mut shards = Vec::new();
    for k in 1..=2 {
        let dir = root.path().join(format!("s{k}"));
        sctl()
            .args(["run", "--shard", &format!("{k}/2"), "--out"])
            .arg(&dir)
            .arg(&f.config)
            .assert()
            .success()
            .stdout(predicate::str::contains(format!("shard {k}/2 done")));
        shards.push(dir);
    }
    let out = root.path().join("merged");
    sctl()
        .arg("merge")
        .args(&shards)
        .arg("--out")
        .arg(&out)
        .assert()
        .success()
        .stdout(predicate::str::contains("merged 2 directories"));
    assert_same(&f.one_thread, &out);

    // One shard alone is not a whole run.
    sctl()
        .arg("merge")
        .arg(&shards[0])
        .arg("--out")
        .arg(root.path().join("half"))
        .assert()
        .failure()
        .stderr(predicate::str::contains("units are missing"));
}

#[test]
fn merge_refuses_directories_of_different_experiments() {
    let f = fixture();
    let root = tempfile::tempdir().unwrap();
    let other = root.path().join("other");
    std::fs::create_dir_all(&other).unwrap();
    let text = std::fs::read_to_string(f.one_thread.join("config.toml"))
        .unwrap()
        .replace("num_samples = 200", "num_samples = 300");
    std::fs::write(other.join("config.toml"), text).unwrap();
    sctl()
        .arg("merge")
        .arg(&f.one_thread)
        .arg(&other)
        .assert()
        .failure()
        .stderr(predicate::str::contains("are not parts of one experiment"));
    sctl()
        .args(["merge", "/nonexistent/run"])
        .assert()
        .failure()
        .stderr(predicate::str::contains(
            "/nonexistent/run/config.toml: cannot read",
        ));
}

fn one_line_error(config_text: &str, expected: &str) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bad.toml");
    std::fs::write(&path, config_text).unwrap();
    let output = sctl()
        .arg("run")
        .arg(&path)
        .arg("--out")
        .arg(dir.path().join("out"))
        .output()
        .unwrap();
    let message = assert_one_line_error(&output, &[]);
    let expected = format!("{}{expected}", path.display());
    assert!(
        message.starts_with(&expected),
        "{message} does not start with {expected}"
    );
}

#[test]
fn bad_configs_fail_with_one_line_naming_file_and_key() {
    one_line_error(
        &CONFIG.replace("num_samples = 200", "num_samples = 200\nthr_pix = 3"),
        ":9: pipeline.thr_pix: unknown field `thr_pix`",
    );
    one_line_error(
        &CONFIG.replace(
            "[\"baseline\", \"semical\"]",
            "[\"baseline\", \"semicalibrated\"]",
        ),
        ":10: sweep.method[1]: unknown variant `semicalibrated`",
    );
    one_line_error(
        &CONFIG.replace("num_samples = 200", "num_samples = 0"),
        ":8: pipeline.num_samples: must be at least 1",
    );
    one_line_error(
        &CONFIG.replace("preset = \"quick\"", "preset = \"slow\""),
        ": [dataset]: dataset.preset: unknown preset `slow`",
    );
    one_line_error(
        "name = \"x\"\n[dataset\n",
        ":2: (top level): invalid table header",
    );
}

#[test]
fn command_line_errors_are_reported() {
    let f = fixture();
    sctl()
        .args(["run", "--shard", "3/2"])
        .arg(&f.config)
        .assert()
        .failure()
        .stderr(predicate::str::contains("is not K/N"));
    sctl()
        .args(["run", "--threads", "0"])
        .arg(&f.config)
        .assert()
        .failure();
    sctl()
        .args(["run", "/nonexistent/exp.toml"])
        .assert()
        .failure()
        .stderr(predicate::str::contains(
            "/nonexistent/exp.toml: cannot read",
        ));
    sctl()
        .args(["run", "--help"])
        .assert()
        .success()
        .stdout(predicate::str::contains("tau_range = 0.2"))
        .stdout(predicate::str::contains("[sweep]"));
}

const PLOTS_CONFIG: &str = r#"
name = "cli-plots"
[dataset]
kind = "synthetic"
preset = "quick"
scenes = ["1/0900", "2/0900"]
[sweep]
method = ["baseline", "semical"]
num_samples = [100, 200]
[plots]
per_scene = true
formats = ["png", "svg"]
"#;

/// The files under `dir`, relative to it, sorted.
fn files_under(dir: &Path) -> Vec<String> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                stack.push(path);
            } else {
                let rel = path.strip_prefix(dir).unwrap();
                out.push(rel.to_string_lossy().into_owned());
            }
        }
    }
    out.sort();
    out
}

#[test]
fn plots_are_written_per_run_and_per_scene() {
    let root = tempfile::tempdir().unwrap();
    let config = root.path().join("plots.toml");
    std::fs::write(&config, PLOTS_CONFIG).unwrap();
    let out = root.path().join("run");
    sctl()
        .args(["run", "--threads", "2", "--out"])
        .arg(&out)
        .arg(&config)
        .assert()
        .success();
    let plots = out.join("plots");
    let mut expected: Vec<String> = Vec::new();
    for stem in [
        "me_vs_num_samples",
        "focal_error__num_samples-100",
        "focal_error__num_samples-200",
        "me_scatter__num_samples-100",
        "me_scatter__num_samples-200",
    ] {
        for ext in ["png", "svg"] {
            expected.push(format!("{stem}.{ext}"));
        }
    }
    for method in ["baseline", "semical"] {
        for m in [100, 200] {
            for scene in ["1_0900", "2_0900"] {
                let mut kinds = vec!["clusters"];
                if method == "semical" {
                    kinds.push("focal_kde");
                }
                for kind in kinds {
                    for ext in ["png", "svg"] {
                        expected.push(format!(
                            "method-{method}__num_samples-{m}/{scene}_{kind}.{ext}"
                        ));
                    }
                }
            }
        }
    }
    expected.sort();
    assert_eq!(files_under(&plots), expected);
    for name in &expected {
        let path = plots.join(name);
        if name.ends_with(".png") {
            decode_png(&path);
        } else {
            let svg = std::fs::read_to_string(&path).unwrap();
            assert!(svg.starts_with("<svg"), "{name}");
        }
    }
    // The figures carry what they are about.
    let me_vs_m = std::fs::read_to_string(plots.join("me_vs_num_samples.svg")).unwrap();
    assert!(
        me_vs_m.contains("baseline (mean ± std over scenes)")
            && me_vs_m.contains("semical (mean ± std over scenes)")
    );
    let kde =
        std::fs::read_to_string(plots.join("method-semical__num_samples-200/2_0900_focal_kde.svg"))
            .unwrap();
    assert!(kde.contains("f_peak = ") && kde.contains("true focal = "));
    let clusters = decode_png(&plots.join("method-semical__num_samples-200/2_0900_clusters.png"));
    // Two side-by-side panels of the 1024 x 768 image scaled to 800 x 600.
    assert!(clusters.width() > 1600 && clusters.height() > 600);

    // The run-level figures come from per_scene.csv alone: a merge of the
    // shards of a one-thread run draws the same bytes, and brings the
    // per-scene figures along.
    let mut shards = Vec::new();
    for k in 1..=2 {
        let dir = root.path().join(format!("s{k}"));
        sctl()
            .args([
                "run",
                "--threads",
                "1",
                "--shard",
                &format!("{k}/2"),
                "--out",
            ])
            .arg(&dir)
            .arg(&config)
            .assert()
            .success();
        assert!(!dir.join("plots/me_vs_num_samples.png").exists());
        shards.push(dir);
    }
    let merged = root.path().join("merged");
    sctl()
        .arg("merge")
        .args(&shards)
        .arg("--out")
        .arg(&merged)
        .assert()
        .success();
    assert_eq!(files_under(&merged.join("plots")), expected);
    for name in expected.iter().filter(|n| !n.contains('/')) {
        assert!(
            std::fs::read(plots.join(name)).unwrap()
                == std::fs::read(merged.join("plots").join(name)).unwrap(),
            "{name} differs between the 2-thread run and the merged shards"
        );
    }

    // Run-level figures only, PNG only, and stale figures are replaced.
    let png_only = PLOTS_CONFIG
        .replace("per_scene = true", "per_scene = false")
        .replace("formats = [\"png\", \"svg\"]", "formats = [\"png\"]");
    std::fs::write(&config, png_only).unwrap();
    let out2 = root.path().join("run2");
    sctl()
        .args(["run", "--out"])
        .arg(&out2)
        .arg(&config)
        .assert()
        .success();
    let pngs: Vec<String> = expected
        .iter()
        .filter(|n| !n.contains('/') && n.ends_with(".png"))
        .cloned()
        .collect();
    assert_eq!(files_under(&out2.join("plots")), pngs);
}

#[test]
fn bad_plot_formats_are_config_errors() {
    one_line_error(
        &format!("{CONFIG}[plots]\nformats = [\"pdf\"]\n"),
        ":12: plots.formats[0]: unknown variant `pdf`, expected `png` or `svg`",
    );
    one_line_error(
        &format!("{CONFIG}[plots]\nformats = []\n"),
        ":12: plots.formats: must name at least one format when plots are enabled",
    );
}
