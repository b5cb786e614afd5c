//! The experiment harness with a stand-in evaluator (values computed from the
//! scene and the parameters, finishing in scrambled order): output bytes do
//! not depend on the thread count, on interruption + `--resume`, or on
//! sharding + merge.

use super::{merge, run_experiment, Evaluator, Merged, RunOptions, ScenePlots, Shard};
use crate::config::{ExperimentConfig, Method, PipelineConfig};
use crate::output::{SceneResult, StageTimings};
use anyhow::{bail, Result};
use metrics::ClusteringMetrics;
use segmentation::HypothesisCounts;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Duration;

struct Stand {
    scenes: Vec<String>,
    /// Fail every call after this many (simulates a run killed midway).
    fail_after: Option<usize>,
    calls: AtomicUsize,
}

impl Stand {
    fn new(fail_after: Option<usize>) -> Self {
        Self {
            scenes: (0..7).map(|i| format!("scene{i}")).collect(),
            fail_after,
            calls: AtomicUsize::new(0),
        }
    }
}

impl Evaluator for Stand {
    fn scene_names(&self) -> Vec<String> {
        self.scenes.clone()
    }

    fn evaluate(
        &self,
        scene: usize,
        p: &PipelineConfig,
        plots: Option<&ScenePlots>,
    ) -> Result<(SceneResult, StageTimings)> {
        let call = self.calls.fetch_add(1, Ordering::SeqCst);
        if self.fail_after.is_some_and(|k| call >= k) {
            bail!("stopped");
        }
        if let Some(plots) = plots {
            // A stand-in figure: which unit drew it, into which directory.
            let text = format!("{} {}\n", plots.label, self.scenes[scene]);
            std::fs::write(plots.dir.join(format!("{}.txt", self.scenes[scene])), text)?;
        }
        // Scramble completion order across threads.
        std::thread::sleep(Duration::from_millis(
            ((scene * 7 + p.params.sampling.num_samples) % 5) as u64,
        ));
        let base = ((scene * 37 + p.params.sampling.num_samples / 100) % 23) as f64 / 100.0;
        let me = if p.params.focal.method == Method::Semical {
            base * 0.7
        } else {
            base
        } + 1.0 / 3.0 / 100.0;
        let mut result = SceneResult {
            n: 100 + scene,
            frob: (scene % 3 != 0).then_some(0.01 * scene as f64),
            gt_motions: Some(2),
            gt_outliers: Some(10),
            motions: 2,
            outliers: 12,
            status: "ok".into(),
            ..SceneResult::default()
        };
        result.set_metrics(&ClusteringMetrics {
            me,
            me_all: me * 1.5,
            acc: 1.0 - me,
            fnr: me / 2.0,
            pur: 1.0 - me / 3.0,
            ari: 0.5,
            nmi: 0.6,
        });
        result.set_hypotheses(&HypothesisCounts {
            generated: p.params.sampling.num_samples,
            refined: p.params.sampling.num_samples - 1,
            local_ok: p.params.sampling.num_samples / 2,
            kept: p.params.sampling.num_samples / 3,
            focal_failures: 1,
            focal_priors: 0,
        });
        result.set_focal(Some(1000.0 + scene as f64), None);
        let timings = StageTimings {
            total: call as f64, // differs between runs: kept out of every compared file
            ..Default::default()
        };
        Ok((result, timings))
    }
}

fn config() -> ExperimentConfig {
    ExperimentConfig::parse(
        "name = \"h\"\n[dataset]\nkind = \"synthetic\"\n\
         [sweep]\nmethod = [\"baseline\", \"semical\"]\nnum_samples = [100, 200]\n\
         [plots]\nper_scene = true\n",
        Path::new("h.toml"),
    )
    .unwrap()
}

fn options(dir: &Path, threads: usize, shard: Option<Shard>, resume: bool) -> RunOptions {
    RunOptions {
        out_dir: dir.to_path_buf(),
        threads,
        shard,
        resume,
        force: false,
        progress: false,
    }
}

const COMPARED: [&str; 5] = [
    "per_scene.csv",
    "summary.csv",
    "wilcoxon.csv",
    "report.md",
    "config.toml",
];

/// Every file under `dir/plots` (relative path, bytes), sorted by path.
fn plot_files(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut files = Vec::new();
    let mut stack = vec![dir.join("plots")];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                stack.push(path);
            } else {
                let rel = path
                    .strip_prefix(dir)
                    .unwrap()
                    .to_string_lossy()
                    .into_owned();
                files.push((rel, std::fs::read(&path).unwrap()));
            }
        }
    }
    files.sort();
    files
}

fn assert_same_files(a: &Path, b: &Path) {
    for name in COMPARED {
        let x = std::fs::read_to_string(a.join(name)).unwrap();
        let y = std::fs::read_to_string(b.join(name)).unwrap();
        assert_eq!(x, y, "{name} differs");
    }
    let (x, y) = (plot_files(a), plot_files(b));
    let names = |f: &[(String, Vec<u8>)]| f.iter().map(|(n, _)| n.clone()).collect::<Vec<_>>();
    assert_eq!(names(&x), names(&y), "different figures");
    for ((name, x), (_, y)) in x.iter().zip(&y) {
        assert!(x == y, "{name} differs");
    }
}

fn reference_run(root: &Path) -> PathBuf {
    let dir = root.join("one");
    run_experiment(&config(), &Stand::new(None), &options(&dir, 1, None, false)).unwrap();
    dir
}

#[test]
fn outputs_do_not_depend_on_threads() {
    let root = tempfile::tempdir().unwrap();
    let one = reference_run(root.path());
    let two = root.path().join("two");
    let outcome =
        run_experiment(&config(), &Stand::new(None), &options(&two, 2, None, false)).unwrap();
    assert_eq!(outcome.evaluated, 28);
    assert_same_files(&one, &two);
    let per_scene = std::fs::read_to_string(one.join("per_scene.csv")).unwrap();
    assert_eq!(per_scene.lines().count(), 1 + 28);
    assert!(per_scene.starts_with("method,num_samples,scene,n,me,"));
    // Unit order: combination-major, scenes in dataset order.
    let second = per_scene.lines().nth(2).unwrap();
    assert!(second.starts_with("baseline,100,scene1,101,"), "{second}");
    let wilcoxon = std::fs::read_to_string(one.join("wilcoxon.csv")).unwrap();
    // Two semical combinations, each tested on ME, ME over all points and FNR.
    assert_eq!(wilcoxon.lines().count(), 1 + 6, "{wilcoxon}");
    // Run-level figures (no known focal: no histogram) and one stand-in
    // figure per unit in its combination's directory.
    let figures: Vec<String> = plot_files(&one).into_iter().map(|(n, _)| n).collect();
    assert_eq!(figures.len(), 6 + 28, "{figures:?}");
    for name in [
        "plots/me_vs_num_samples.png",
        "plots/me_vs_num_samples.svg",
        "plots/me_scatter__num_samples-100.svg",
        "plots/me_scatter__num_samples-200.png",
        "plots/method-semical__num_samples-200/scene6.txt",
    ] {
        assert!(
            figures.iter().any(|f| f == name),
            "{name} missing: {figures:?}"
        );
    }
    let svg = std::fs::read_to_string(one.join("plots/me_vs_num_samples.svg")).unwrap();
    assert!(
        svg.contains("baseline (mean ± std over scenes)")
            && svg.contains("semical (mean ± std over scenes)")
    );
    let stand_in =
        std::fs::read_to_string(one.join("plots/method-baseline__num_samples-100/scene3.txt"))
            .unwrap();
    assert_eq!(stand_in, "method=baseline, num_samples=100 scene3\n");
    assert!(
        wilcoxon.contains("semical,200,method=baseline num_samples=200,me,"),
        "{wilcoxon}"
    );
}

#[test]
fn resume_after_interruption_equals_one_run() {
    let root = tempfile::tempdir().unwrap();
    let one = reference_run(root.path());
    let dir = root.path().join("resumed");
    let err = run_experiment(
        &config(),
        &Stand::new(Some(9)),
        &options(&dir, 2, None, false),
    )
    .unwrap_err();
    assert!(format!("{err:#}").contains("stopped"), "{err:#}");
    // A kill can also leave half a line behind.
    let path = dir.join("per_scene.csv");
    let mut text = std::fs::read_to_string(&path).unwrap();
    let partial_rows = text.lines().count() - 1;
    assert!((1..28).contains(&partial_rows), "{partial_rows}");
    text.push_str("semical,200,scene3,10");
    std::fs::write(&path, text).unwrap();

    let outcome =
        run_experiment(&config(), &Stand::new(None), &options(&dir, 2, None, true)).unwrap();
    assert_eq!(outcome.skipped, partial_rows);
    assert_eq!(outcome.evaluated, 28 - partial_rows);
    assert_same_files(&one, &dir);
    let timings = std::fs::read_to_string(dir.join("timings.csv")).unwrap();
    assert_eq!(timings.lines().count(), 1 + 28);

    // Resuming a directory written by another configuration is refused.
    let mut other = config();
    other.pipeline.params.refinement.thr_px = 3.0;
    let err = run_experiment(&other, &Stand::new(None), &options(&dir, 1, None, true)).unwrap_err();
    assert!(
        err.to_string()
            .contains("holds the results of another configuration (pipeline.thr_px: "),
        "{err}"
    );
}

#[test]
fn shards_merge_into_one_run() {
    let root = tempfile::tempdir().unwrap();
    let one = reference_run(root.path());
    let shards: Vec<PathBuf> = (1..=3)
        .map(|k| {
            let dir = root.path().join(format!("shard{k}"));
            let shard = Shard { index: k, count: 3 };
            let outcome = run_experiment(
                &config(),
                &Stand::new(None),
                &options(&dir, 2, Some(shard), false),
            )
            .unwrap();
            assert!(outcome.evaluated == 9 || outcome.evaluated == 10);
            assert!(!dir.join("summary.csv").exists());
            dir
        })
        .collect();
    let out = root.path().join("merged");
    let err = merge(&shards[..2], Some(&out)).unwrap_err().to_string();
    assert!(err.contains("units are missing"), "{err}");
    let Merged { out: dir, summary } = merge(&shards, Some(&out)).unwrap();
    assert_eq!(dir, out);
    assert!(
        summary.contains("method=semical num_samples=200"),
        "{summary}"
    );
    assert_same_files(&one, &out);
}

#[test]
fn shard_parsing_and_membership() {
    let s: Shard = "2/3".parse().unwrap();
    assert_eq!(s, Shard { index: 2, count: 3 });
    let units: Vec<usize> = (0..9).filter(|&u| s.contains(u)).collect();
    assert_eq!(units, [1, 4, 7]);
    for bad in ["0/3", "4/3", "3", "a/b", "1/0"] {
        assert!(bad.parse::<Shard>().is_err(), "{bad}");
    }
}
