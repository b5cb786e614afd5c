//! The experiment harness behind `sctl run` and `sctl merge`: every
//! (combination, scene) unit of a sweep evaluated in parallel, each appended
//! to `per_scene.csv` and `timings.csv` as soon as it finishes, then the run
//! directory completed with `summary.csv`, `wilcoxon.csv`, `report.md` and
//! the run-level figures under `plots/` (when `[plots] enabled`). With
//! `[plots] per_scene`, each unit also draws its own figures into
//! `plots/<combination>/` as it finishes (see [`ScenePlots`]).
//!
//! Units are numbered `combination × scenes + scene`; `--shard K/N` keeps
//! the units whose number is `K − 1` modulo `N`. At the end of a run the two
//! CSV files are rewritten in unit order, so that their bytes do not depend
//! on the thread count, on interruptions or on sharding.

use crate::config::{ExperimentConfig, FocalSolver, Method, PipelineConfig, PlotFormat};
use crate::focal_file;
use crate::output::{
    params_file_name, per_scene_header, timing_fields, timings_header, write_atomic, CsvAppender,
    CsvTable, SceneResult, StageTimings, CONFIG_FILE, PER_SCENE_FILE, PLOTS_DIR, REPORT_FILE,
    SUMMARY_FILE, TIMINGS_FILE, WILCOXON_FILE,
};
use crate::report::{
    clear_run_plots, console_summary, mean_timings, render_report, summary_table, wilcoxon_rows,
    wilcoxon_table, write_run_plots, ReportContext, RunValues,
};
use crate::sweep::SweepPlan;
use anyhow::{bail, Context, Result};
use indicatif::{ProgressBar, ProgressStyle};
use rayon::prelude::*;
use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};
use std::str::FromStr;
use std::sync::Mutex;
use std::time::Instant;

/// Where the per-scene figures of one (combination, scene) unit go.
#[derive(Debug, Clone, PartialEq)]
pub struct ScenePlots {
    /// The combination's directory, `<run>/plots/<combination>` (see
    /// [`combination_dir_name`]); it exists.
    pub dir: PathBuf,
    /// The combination as `key=value` pairs, for the figure titles.
    pub label: String,
    /// Each figure is written once per format.
    pub formats: Vec<PlotFormat>,
}

/// Evaluates one combination on one scene: the pipeline and the metrics.
pub trait Evaluator: Sync {
    /// The scene names, in run order.
    fn scene_names(&self) -> Vec<String>;
    /// Runs `pipeline` on scene `scene` (an index into
    /// [`Evaluator::scene_names`]); draws the scene's figures into `plots`
    /// when given (an evaluator without figures may ignore it).
    fn evaluate(
        &self,
        scene: usize,
        pipeline: &PipelineConfig,
        plots: Option<&ScenePlots>,
    ) -> Result<(SceneResult, StageTimings)>;
}

/// The per-scene figure directory name of a combination: its swept
/// parameters (always `method` first) as [`params_file_name`], e.g.
/// `method-semical__num_samples-500`.
pub fn combination_dir_name(plan: &SweepPlan, combination: usize) -> String {
    let params: Vec<(&str, &str)> = plan
        .columns
        .iter()
        .zip(&plan.combinations[combination].values)
        .map(|(k, v)| (k.as_str(), v.as_str()))
        .collect();
    params_file_name(&params)
}

/// One of `N` deterministic parts of a run (`--shard K/N`, `1 ≤ K ≤ N`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// K, 1-based.
    pub index: usize,
    /// N.
    pub count: usize,
}

impl FromStr for Shard {
    type Err = String;
    fn from_str(s: &str) -> std::result::Result<Self, String> {
        let err = || format!("`{s}` is not K/N with 1 <= K <= N (e.g. 2/4)");
        let (k, n) = s.split_once('/').ok_or_else(err)?;
        let index: usize = k.trim().parse().map_err(|_| err())?;
        let count: usize = n.trim().parse().map_err(|_| err())?;
        if index == 0 || index > count {
            return Err(err());
        }
        Ok(Self { index, count })
    }
}

impl Shard {
    /// True when unit number `unit` belongs to this shard.
    pub fn contains(&self, unit: usize) -> bool {
        unit % self.count == self.index - 1
    }
}

/// How to run an experiment.
#[derive(Debug, Clone)]
pub struct RunOptions {
    /// The run directory.
    pub out_dir: PathBuf,
    /// Worker threads (a local rayon pool).
    pub threads: usize,
    /// Run only this part of the units.
    pub shard: Option<Shard>,
    /// Keep the rows already in `per_scene.csv` and run only the others.
    pub resume: bool,
    /// Draw a progress bar on stderr (when it is a terminal).
    pub progress: bool,
}

/// What a run did.
#[derive(Debug, Clone)]
pub struct RunOutcome {
    /// Units evaluated by this invocation.
    pub evaluated: usize,
    /// Units found done in `per_scene.csv` (`--resume`).
    pub skipped: usize,
    /// Wall time of this invocation, seconds.
    pub wall_seconds: f64,
    /// The end-of-run table (empty for a shard).
    pub summary: String,
}

/// The default run directory: `results/<name>`, or
/// `results/<name>/shard-K-of-N` for a shard.
pub fn default_out_dir(name: &str, shard: Option<Shard>) -> PathBuf {
    let base = Path::new("results").join(name);
    match shard {
        Some(s) => base.join(format!("shard-{}-of-{}", s.index, s.count)),
        None => base,
    }
}

/// The configuration as written to `config.toml`: every default explicit
/// and the scene list resolved, so that `sctl merge` needs nothing else.
pub fn resolved_config(config: &ExperimentConfig, scenes: &[String]) -> ExperimentConfig {
    let mut resolved = config.clone();
    resolved.dataset.scenes = Some(scenes.to_vec());
    resolved
}

/// A rayon pool of `threads` workers (0: rayon's default), local to the
/// caller: nothing global is configured.
pub fn thread_pool(threads: usize) -> Result<rayon::ThreadPool> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .context("cannot start the worker threads")
}

/// Unit order: `(combination, scene)` of each row's key, for sorting.
struct UnitIndex<'a> {
    plan: &'a SweepPlan,
    scenes: HashMap<&'a str, usize>,
}

impl<'a> UnitIndex<'a> {
    fn new(plan: &'a SweepPlan, scenes: &'a [String]) -> Self {
        Self {
            plan,
            scenes: scenes
                .iter()
                .enumerate()
                .map(|(i, s)| (s.as_str(), i))
                .collect(),
        }
    }

    fn of(&self, row: &[String], file: &Path, line: usize) -> Result<(usize, usize)> {
        let k = self.plan.columns.len();
        if row.len() <= k {
            bail!("{}: row {line}: too few columns", file.display());
        }
        let combo = self.plan.find(&row[..k]).with_context(|| {
            format!(
                "{}: row {line}: parameters ({}) are not a combination of this run",
                file.display(),
                row[..k].join(", ")
            )
        })?;
        let scene = *self.scenes.get(row[k].as_str()).with_context(|| {
            format!(
                "{}: row {line}: scene `{}` is not part of this run",
                file.display(),
                row[k]
            )
        })?;
        Ok((combo, scene))
    }
}

/// Fails before any unit runs when a semical combination reads its focal
/// lengths from a file (`focal_solver = "external"`) that is missing or
/// lacks a required column: otherwise every scene would fail alike.
fn check_focal_files(plan: &SweepPlan) -> Result<()> {
    for combination in &plan.combinations {
        let p = &combination.pipeline;
        if p.method == Method::Semical && p.focal_solver == FocalSolver::External {
            let path = focal_file::focal_file_path(&p.focal_file, p.seed);
            focal_file::check_focal_file(&path).map_err(|e| {
                anyhow::anyhow!(
                    "focal_file: {e} (make it for these hypotheses: `sctl hypotheses`, then the external solver)"
                )
            })?;
        }
    }
    Ok(())
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
    let resolved = resolved_config(config, &scenes).to_toml();
    let dir = &options.out_dir;
    std::fs::create_dir_all(dir).with_context(|| format!("{}: cannot create", dir.display()))?;
    let config_path = dir.join(CONFIG_FILE);
    let per_scene_path = dir.join(PER_SCENE_FILE);
    let timings_path = dir.join(TIMINGS_FILE);

    if options.resume {
        if let Ok(previous) = std::fs::read_to_string(&config_path) {
            if previous != resolved {
                bail!(
                    "{}: written by another configuration; --resume needs the same config and scenes (or use another --out)",
                    config_path.display()
                );
            }
        }
    } else {
        for name in [
            PER_SCENE_FILE,
            TIMINGS_FILE,
            SUMMARY_FILE,
            WILCOXON_FILE,
            REPORT_FILE,
        ] {
            let path = dir.join(name);
            if path.exists() {
                std::fs::remove_file(&path)
                    .with_context(|| format!("{}: cannot remove", path.display()))?;
            }
        }
    }
    write_atomic(&config_path, &resolved)?;

    let index = UnitIndex::new(&plan, &scenes);
    let mut done: HashSet<(usize, usize)> = HashSet::new();
    if options.resume && per_scene_path.exists() {
        let table = CsvTable::read(&per_scene_path)?;
        for (r, row) in table.rows.iter().enumerate() {
            done.insert(index.of(row, &per_scene_path, r + 2)?);
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
    let skipped = mine.len() - todo.len();

    let writers = Mutex::new((
        CsvAppender::open(&per_scene_path, &per_scene_header(&plan.columns))?,
        CsvAppender::open(&timings_path, &timings_header(&plan.columns))?,
    ));
    let bar = if options.progress {
        ProgressBar::new(mine.len() as u64)
    } else {
        ProgressBar::hidden()
    };
    bar.set_style(
        ProgressStyle::with_template("{bar:40} {pos}/{len} scenes x combinations  [{elapsed_precise} < {eta_precise}]  {msg}")
            .expect("valid template"),
    );
    bar.set_position(skipped as u64);
    bar.reset_eta();

    let scene_plots = config.plots.enabled && config.plots.per_scene;
    let plot_targets: Vec<Option<ScenePlots>> = (0..plan.combinations.len())
        .map(|c| {
            if !scene_plots || !todo.iter().any(|&(tc, _)| tc == c) {
                return Ok(None);
            }
            let dir = dir.join(PLOTS_DIR).join(combination_dir_name(&plan, c));
            std::fs::create_dir_all(&dir)
                .with_context(|| format!("{}: cannot create", dir.display()))?;
            Ok(Some(ScenePlots {
                dir,
                label: plan.label(c),
                formats: config.plots.formats.clone(),
            }))
        })
        .collect::<Result<_>>()?;

    thread_pool(options.threads)?.install(|| {
        todo.par_iter().try_for_each(|&(c, s)| -> Result<()> {
            let combo = &plan.combinations[c];
            let (result, timings) = evaluator
                .evaluate(s, &combo.pipeline, plot_targets[c].as_ref())
                .with_context(|| format!("scene `{}` ({})", scenes[s], plan.label(c)))?;
            let key: Vec<String> = combo
                .values
                .iter()
                .cloned()
                .chain([scenes[s].clone()])
                .collect();
            let per_scene_row: Vec<String> = key.iter().cloned().chain(result.fields()).collect();
            let timing_row: Vec<String> = key
                .into_iter()
                .chain(timing_fields(result.n, &timings))
                .collect();
            {
                let mut w = writers.lock().expect("writer lock");
                w.1.append(&timing_row)?;
                w.0.append(&per_scene_row)?;
            }
            bar.set_message(scenes[s].clone());
            bar.inc(1);
            Ok(())
        })
    })?;
    bar.finish_and_clear();
    drop(writers);

    let summary = finalize(dir, config, &plan, &scenes, options.shard.is_none())?;
    Ok(RunOutcome {
        evaluated: todo.len(),
        skipped,
        wall_seconds: started.elapsed().as_secs_f64(),
        summary,
    })
}

/// Rewrites a run's CSV rows in unit order (one row per unit, the first one
/// seen) and drops timing rows of units without a result.
fn sort_rows(
    table: &mut CsvTable,
    index: &UnitIndex,
    file: &Path,
    keep: Option<&HashSet<(usize, usize)>>,
) -> Result<HashSet<(usize, usize)>> {
    let mut keyed: Vec<((usize, usize), Vec<String>)> = Vec::with_capacity(table.rows.len());
    let mut seen = HashSet::new();
    for (r, row) in table.rows.drain(..).enumerate() {
        let key = index.of(&row, file, r + 2)?;
        if keep.is_some_and(|k| !k.contains(&key)) || !seen.insert(key) {
            continue;
        }
        keyed.push((key, row));
    }
    keyed.sort_by_key(|(key, _)| *key);
    table.rows = keyed.into_iter().map(|(_, row)| row).collect();
    Ok(seen)
}

/// Completes a run directory: sorts `per_scene.csv` and `timings.csv` into
/// unit order and, unless this is a shard, writes `summary.csv`,
/// `wilcoxon.csv`, `report.md` and (with `[plots] enabled`) the run-level
/// figures of [`write_run_plots`], replacing any earlier ones. Returns the
/// end-of-run table.
pub fn finalize(
    dir: &Path,
    config: &ExperimentConfig,
    plan: &SweepPlan,
    scenes: &[String],
    derive: bool,
) -> Result<String> {
    let index = UnitIndex::new(plan, scenes);
    let per_scene_path = dir.join(PER_SCENE_FILE);
    let timings_path = dir.join(TIMINGS_FILE);
    let mut per_scene = CsvTable::read(&per_scene_path)?;
    let units = sort_rows(&mut per_scene, &index, &per_scene_path, None)?;
    per_scene.write_atomic(&per_scene_path)?;
    let mut timings = CsvTable::read(&timings_path)?;
    sort_rows(&mut timings, &index, &timings_path, Some(&units))?;
    timings.write_atomic(&timings_path)?;
    if !derive {
        return Ok(String::new());
    }

    let values = RunValues::collect(plan, &per_scene, &per_scene_path)?;
    summary_table(plan, &values).write_atomic(&dir.join(SUMMARY_FILE))?;
    let tests = wilcoxon_rows(plan, &values, &config.compare.against);
    wilcoxon_table(plan, &tests).write_atomic(&dir.join(WILCOXON_FILE))?;
    let ctx = ReportContext {
        name: &config.name,
        description: config.description.as_deref(),
        dataset: config.dataset.kind.name(),
        scenes,
    };
    write_atomic(
        &dir.join(REPORT_FILE),
        &render_report(&ctx, plan, &values, &tests),
    )?;
    clear_run_plots(dir)?;
    if config.plots.enabled {
        write_run_plots(
            dir,
            plan,
            &values,
            &per_scene,
            &per_scene_path,
            &config.plots.formats,
        )?;
    }
    let mean_times = mean_timings(plan, &timings, &timings_path)?;
    Ok(console_summary(plan, &values, &tests, &mean_times))
}

/// Copies the per-scene figures of run directory `from` (the files in each
/// subdirectory of `from/plots/`) into the same places under `to`.
fn copy_scene_plots(from: &Path, to: &Path) -> Result<()> {
    let plots = from.join(PLOTS_DIR);
    if !plots.is_dir() {
        return Ok(());
    }
    let list = |dir: &Path| -> Result<Vec<PathBuf>> {
        let mut paths = Vec::new();
        for entry in
            std::fs::read_dir(dir).with_context(|| format!("{}: cannot list", dir.display()))?
        {
            paths.push(
                entry
                    .with_context(|| format!("{}: cannot list", dir.display()))?
                    .path(),
            );
        }
        paths.sort();
        Ok(paths)
    };
    for sub in list(&plots)?.into_iter().filter(|p| p.is_dir()) {
        let Some(name) = sub.file_name() else {
            continue;
        };
        let target = to.join(PLOTS_DIR).join(name);
        std::fs::create_dir_all(&target)
            .with_context(|| format!("{}: cannot create", target.display()))?;
        for file in list(&sub)?.into_iter().filter(|p| p.is_file()) {
            let Some(file_name) = file.file_name() else {
                continue;
            };
            let dest = target.join(file_name);
            std::fs::copy(&file, &dest).with_context(|| {
                format!("{}: cannot copy to {}", file.display(), dest.display())
            })?;
        }
    }
    Ok(())
}

/// Combines the run directories of the shards of one experiment into `out`
/// (default `results/<name>`): the same files a single run writes.
///
/// Every directory must hold the same `config.toml`; together they must
/// cover every (combination, scene) unit. Per-scene figures of the shards
/// are copied; the run-level figures are drawn from the merged rows.
pub fn merge(dirs: &[PathBuf], out: Option<&Path>) -> Result<(PathBuf, String)> {
    let Some(first) = dirs.first() else {
        bail!("merge: no run directory given");
    };
    let config_path = first.join(CONFIG_FILE);
    let text = std::fs::read_to_string(&config_path).with_context(|| {
        format!(
            "{}: cannot read (is {} a run directory?)",
            config_path.display(),
            first.display()
        )
    })?;
    for dir in &dirs[1..] {
        let other = dir.join(CONFIG_FILE);
        let t = std::fs::read_to_string(&other).with_context(|| {
            format!(
                "{}: cannot read (is {} a run directory?)",
                other.display(),
                dir.display()
            )
        })?;
        if t != text {
            bail!(
                "{}: differs from {}: the directories are not parts of one experiment",
                other.display(),
                config_path.display()
            );
        }
    }
    let config = ExperimentConfig::parse(&text, &config_path)?;
    let plan = SweepPlan::expand(&config)
        .map_err(|e| anyhow::anyhow!("{}: {}: {}", config_path.display(), e.key, e.message))?;
    let scenes = config.dataset.scenes.clone().with_context(|| {
        format!(
            "{}: no resolved scene list (not written by sctl run)",
            config_path.display()
        )
    })?;
    let out = out
        .map(Path::to_path_buf)
        .unwrap_or_else(|| default_out_dir(&config.name, None));
    let out_canonical = out.canonicalize().ok();
    if dirs.iter().any(|d| {
        d.canonicalize()
            .ok()
            .is_some_and(|d| Some(d) == out_canonical)
    }) {
        bail!(
            "{}: the output directory cannot be one of the merged directories",
            out.display()
        );
    }

    let index = UnitIndex::new(&plan, &scenes);
    let mut merged: Vec<CsvTable> = Vec::new();
    for (name, header) in [
        (PER_SCENE_FILE, per_scene_header(&plan.columns)),
        (TIMINGS_FILE, timings_header(&plan.columns)),
    ] {
        let mut all = CsvTable {
            header: header.clone(),
            rows: Vec::new(),
        };
        let mut origin: HashMap<(usize, usize), (PathBuf, Vec<String>)> = HashMap::new();
        for dir in dirs {
            let path = dir.join(name);
            let table = CsvTable::read(&path)?;
            if table.header != header {
                bail!(
                    "{}: its columns are not those of this experiment",
                    path.display()
                );
            }
            for (r, row) in table.rows.into_iter().enumerate() {
                let key = index.of(&row, &path, r + 2)?;
                match origin.get(&key) {
                    Some((other, previous)) if name == PER_SCENE_FILE && previous != &row => bail!(
                        "{}: row {} ({}, scene `{}`) differs from the same unit in {}",
                        path.display(),
                        r + 2,
                        plan.label(key.0),
                        scenes[key.1],
                        other.display()
                    ),
                    Some(_) => {}
                    None => {
                        origin.insert(key, (path.clone(), row.clone()));
                        all.rows.push(row);
                    }
                }
            }
        }
        merged.push(all);
    }
    let expected = plan.combinations.len() * scenes.len();
    let have: HashSet<(usize, usize)> = merged[0]
        .rows
        .iter()
        .enumerate()
        .map(|(r, row)| index.of(row, Path::new(PER_SCENE_FILE), r + 2))
        .collect::<Result<_>>()?;
    if have.len() < expected {
        let missing = (0..expected)
            .map(|u| (u / scenes.len(), u % scenes.len()))
            .find(|u| !have.contains(u))
            .expect("some unit is missing");
        bail!(
            "{} of {expected} (combination, scene) units are missing, e.g. scene `{}` with {}; run (or --resume) the missing shards first",
            expected - have.len(),
            scenes[missing.1],
            plan.label(missing.0)
        );
    }

    std::fs::create_dir_all(&out).with_context(|| format!("{}: cannot create", out.display()))?;
    write_atomic(&out.join(CONFIG_FILE), &text)?;
    merged[0].write_atomic(&out.join(PER_SCENE_FILE))?;
    merged[1].write_atomic(&out.join(TIMINGS_FILE))?;
    for dir in dirs {
        copy_scene_plots(dir, &out)?;
    }
    let summary = finalize(&out, &config, &plan, &scenes, true)?;
    Ok((out, summary))
}

#[cfg(test)]
mod tests {
    use super::*;

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
}
