//! `sctl run`: every (combination, scene) unit of a sweep evaluated in
//! parallel and appended to the CSV files as it finishes.

use super::units::UnitIndex;
use super::{
    combination_dir_name, finalize, resolved_config, thread_pool, Evaluator, RunOptions,
    RunOutcome, ScenePlots, Shard,
};
use crate::config::{ExperimentConfig, FocalSolver, Method};
use crate::focal_file;
use crate::output::{
    echo, per_scene_header, timing_fields, timings_header, write_atomic, CsvAppender, CsvTable,
    CONFIG_FILE, PER_SCENE_FILE, PLOTS_DIR, REPORT_FILE, SUMMARY_FILE, TIMINGS_FILE, WILCOXON_FILE,
};
use crate::sweep::SweepPlan;
use anyhow::{bail, Context, Result};
use indicatif::{ProgressBar, ProgressStyle};
use rayon::prelude::*;
use std::collections::HashSet;
use std::path::Path;
use std::sync::Mutex;
use std::time::Instant;

/// Fails before any unit runs when a semical combination reads its focal
/// lengths from a file (`focal_solver = "external"`) that is missing or
/// lacks a required column: otherwise every scene would fail alike.
fn check_focal_files(plan: &SweepPlan) -> Result<()> {
    for combination in &plan.combinations {
        let p = &combination.pipeline;
        if p.params.focal.method == Method::Semical
            && p.params.focal.focal_solver == FocalSolver::External
        {
            let path = focal_file::focal_file_path(&p.focal_file, p.params.sampling.seed);
            focal_file::check_focal_file(&path).map_err(|e| {
                anyhow::anyhow!(
                    "focal_file: {e} (make it for these hypotheses: `sctl hypotheses`, then the external solver)"
                )
            })?;
        }
    }
    Ok(())
}

/// The files a run writes into its directory (besides `plots/`).
const RUN_FILES: [&str; 6] = [
    CONFIG_FILE,
    PER_SCENE_FILE,
    TIMINGS_FILE,
    SUMMARY_FILE,
    WILCOXON_FILE,
    REPORT_FILE,
];

/// Writes `config.toml` into the run directory `dir`. A directory holding
/// a run already is refused unless `resume` (then its configuration must
/// be this one) or `force` (then its files are removed): results are never
/// lost silently.
fn prepare_run_dir(dir: &Path, resolved: &str, options: &RunOptions) -> Result<()> {
    std::fs::create_dir_all(dir).with_context(|| format!("{}: cannot create", dir.display()))?;
    let config_path = dir.join(CONFIG_FILE);
    let previous = std::fs::read_to_string(&config_path).ok();
    let holds_run = RUN_FILES.iter().any(|name| dir.join(name).exists());
    if options.force {
        for name in RUN_FILES {
            let path = dir.join(name);
            if path.exists() {
                std::fs::remove_file(&path)
                    .with_context(|| format!("{}: cannot remove", path.display()))?;
            }
        }
    } else if let Some(previous) = previous.as_deref().filter(|p| *p != resolved) {
        bail!(
            "{}: holds the results of another configuration ({}); choose another --out, \
             or --force to replace them",
            dir.display(),
            config_difference(previous, resolved)
        );
    } else if holds_run && !options.resume {
        bail!(
            "{}: holds the results of {}; --resume completes them, --force replaces them",
            dir.display(),
            if previous.is_some() {
                "this configuration"
            } else {
                "a run without config.toml"
            }
        );
    }
    write_atomic(&config_path, resolved)
}

/// The keys whose values differ between two `config.toml` texts, as
/// `key: A there, B here` (at most four, then how many more).
fn config_difference(there: &str, here: &str) -> String {
    let flat = |text: &str| {
        let mut keys = std::collections::BTreeMap::new();
        if let Ok(table) = text.parse::<toml::Table>() {
            flatten("", &toml::Value::Table(table), &mut keys);
        }
        keys
    };
    let (there, here) = (flat(there), flat(here));
    let missing = "(none)".to_string();
    let differing: Vec<String> = there
        .keys()
        .chain(here.keys())
        .collect::<std::collections::BTreeSet<_>>()
        .into_iter()
        .filter(|k| there.get(*k) != here.get(*k))
        .map(|k| {
            let a = there.get(k).unwrap_or(&missing);
            let b = here.get(k).unwrap_or(&missing);
            format!("{k}: {} there, {} here", echo(a), echo(b))
        })
        .collect();
    match differing.len() {
        0 => "the same keys, written differently".to_string(),
        n if n <= 4 => differing.join("; "),
        n => format!("{}; and {} more keys", differing[..4].join("; "), n - 4),
    }
}

/// `value`'s leaves as `dotted.key → TOML text`.
fn flatten(
    prefix: &str,
    value: &toml::Value,
    out: &mut std::collections::BTreeMap<String, String>,
) {
    match value {
        toml::Value::Table(table) => {
            for (k, v) in table {
                let key = if prefix.is_empty() {
                    k.clone()
                } else {
                    format!("{prefix}.{k}")
                };
                flatten(&key, v, out);
            }
        }
        leaf => {
            out.insert(prefix.to_string(), leaf.to_string());
        }
    }
}

/// The units of this invocation: those of its shard, and of them the ones
/// not already in `per_scene.csv` when resuming.
struct Units {
    /// Every `(combination, scene)` of the shard.
    mine: Vec<(usize, usize)>,
    /// Those to evaluate, scene by scene.
    todo: Vec<(usize, usize)>,
}

impl Units {
    fn select(
        plan: &SweepPlan,
        scenes: &[String],
        options: &RunOptions,
        per_scene_path: &Path,
    ) -> Result<Self> {
        let index = UnitIndex::new(plan, scenes);
        let mut done: HashSet<(usize, usize)> = HashSet::new();
        if options.resume && per_scene_path.exists() {
            let table = CsvTable::read(per_scene_path)?;
            for (r, row) in table.rows.iter().enumerate() {
                let unit = index.of(row, per_scene_path, r + 2)?;
                check_shard(options.shard, unit, scenes, per_scene_path, r + 2)?;
                done.insert(unit);
            }
        }
        let n_scenes = scenes.len();
        let mine: Vec<(usize, usize)> = (0..plan.combinations.len() * n_scenes)
            .filter(|&u| options.shard.map_or(true, |s| s.contains(u)))
            .map(|u| (u / n_scenes, u % n_scenes))
            .collect();
        // Scene by scene, so that the combinations of a scene run close together
        // and share its hypotheses (see `PipelineEvaluator`); the files are
        // written in unit order at the end whatever the order here.
        let mut todo: Vec<(usize, usize)> =
            mine.iter().copied().filter(|u| !done.contains(u)).collect();
        todo.sort_by_key(|&(c, s)| (s, c));
        Ok(Self { mine, todo })
    }

    fn skipped(&self) -> usize {
        self.mine.len() - self.todo.len()
    }
}

/// Refuses a unit found in `per_scene.csv` that is not part of this
/// invocation's shard: the directory holds another shard's units, and
/// resuming into it would mix two shards.
fn check_shard(
    shard: Option<Shard>,
    (combination, scene): (usize, usize),
    scenes: &[String],
    file: &Path,
    line: usize,
) -> Result<()> {
    let Some(shard) = shard else { return Ok(()) };
    if shard.contains(combination * scenes.len() + scene) {
        return Ok(());
    }
    bail!(
        "{}: row {line} (scene `{}`) is not a unit of shard {}/{}: the directory holds \
         another shard's results; resume it with its own --shard, or choose another --out",
        file.display(),
        scenes[scene],
        shard.index,
        shard.count
    )
}

/// The progress bar of a run (hidden unless `shown`).
fn progress_bar(units: &Units, shown: bool) -> ProgressBar {
    let bar = if shown {
        ProgressBar::new(units.mine.len() as u64)
    } else {
        ProgressBar::hidden()
    };
    bar.set_style(
        ProgressStyle::with_template("{bar:40} {pos}/{len} scenes x combinations  [{elapsed_precise} < {eta_precise}]  {msg}")
            .expect("valid template"),
    );
    bar.set_position(units.skipped() as u64);
    bar.reset_eta();
    bar
}

/// Per combination, where its per-scene figures go (`[plots] per_scene`),
/// for the combinations with units to evaluate; the directories are made.
fn scene_plot_targets(
    config: &ExperimentConfig,
    plan: &SweepPlan,
    dir: &Path,
    todo: &[(usize, usize)],
) -> Result<Vec<Option<ScenePlots>>> {
    let scene_plots = config.plots.enabled && config.plots.per_scene;
    (0..plan.combinations.len())
        .map(|c| {
            if !scene_plots || !todo.iter().any(|&(tc, _)| tc == c) {
                return Ok(None);
            }
            let dir = dir.join(PLOTS_DIR).join(combination_dir_name(plan, c));
            std::fs::create_dir_all(&dir)
                .with_context(|| format!("{}: cannot create", dir.display()))?;
            Ok(Some(ScenePlots {
                dir,
                label: plan.label(c),
                formats: config.plots.formats.clone(),
            }))
        })
        .collect()
}

/// The files the units append to, one row each as it finishes.
struct Appenders {
    per_scene: CsvAppender,
    timings: CsvAppender,
}

/// Evaluates `todo` on the worker threads, appending each unit's rows.
fn evaluate_units(
    evaluator: &dyn Evaluator,
    plan: &SweepPlan,
    scenes: &[String],
    todo: &[(usize, usize)],
    plot_targets: &[Option<ScenePlots>],
    appenders: &Mutex<Appenders>,
    bar: &ProgressBar,
) -> Result<()> {
    todo.par_iter().try_for_each(|&(c, s)| -> Result<()> {
        let combo = &plan.combinations[c];
        let (mut result, timings) = evaluator
            .evaluate(s, &combo.pipeline, plot_targets[c].as_ref())
            .with_context(|| format!("scene `{}` ({})", scenes[s], plan.label(c)))?;
        result.scene = scenes[s].clone();
        let per_scene_row: Vec<String> =
            combo.values.iter().cloned().chain(result.cells()).collect();
        let timing_row: Vec<String> = combo
            .values
            .iter()
            .cloned()
            .chain([scenes[s].clone()])
            .chain(timing_fields(result.n, &timings))
            .collect();
        {
            let mut w = appenders.lock().expect("writer lock");
            w.timings.append(&timing_row)?;
            w.per_scene.append(&per_scene_row)?;
        }
        bar.set_message(scenes[s].clone());
        bar.inc(1);
        Ok(())
    })
}

/// Runs `config` with `evaluator` into `options.out_dir`.
pub fn run_experiment(
    config: &ExperimentConfig,
    evaluator: &dyn Evaluator,
    options: &RunOptions,
) -> Result<RunOutcome> {
    let started = Instant::now();
    let plan =
        SweepPlan::expand(config).map_err(|e| anyhow::anyhow!("{}: {}", e.key, e.message))?;
    check_focal_files(&plan)?;
    let scenes = evaluator.scene_names();
    let dir = &options.out_dir;
    prepare_run_dir(dir, &resolved_config(config, &scenes).to_toml(), options)?;
    let per_scene_path = dir.join(PER_SCENE_FILE);
    let units = Units::select(&plan, &scenes, options, &per_scene_path)?;

    let appenders = Mutex::new(Appenders {
        per_scene: CsvAppender::open(&per_scene_path, &per_scene_header(&plan.columns))?,
        timings: CsvAppender::open(&dir.join(TIMINGS_FILE), &timings_header(&plan.columns))?,
    });
    let bar = progress_bar(&units, options.progress);
    let plot_targets = scene_plot_targets(config, &plan, dir, &units.todo)?;
    thread_pool(options.threads)?.install(|| {
        evaluate_units(
            evaluator,
            &plan,
            &scenes,
            &units.todo,
            &plot_targets,
            &appenders,
            &bar,
        )
    })?;
    bar.finish_and_clear();
    drop(appenders);

    let finalized = finalize(dir, config, &plan, &scenes, options.shard.is_none())?;
    Ok(RunOutcome {
        evaluated: units.todo.len(),
        skipped: units.skipped(),
        wall_seconds: started.elapsed().as_secs_f64(),
        summary: finalized.summary,
        failed: finalized.failed,
    })
}
