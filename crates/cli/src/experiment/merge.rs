//! `sctl merge`: the run directories of the shards of one experiment
//! combined into one.

use super::default_out_dir;
use super::finalize;
use super::units::UnitIndex;
use crate::config::ExperimentConfig;
use crate::output::{
    per_scene_header, timings_header, write_atomic, CsvTable, CONFIG_FILE, PER_SCENE_FILE,
    PLOTS_DIR, TIMINGS_FILE,
};
use crate::sweep::SweepPlan;
use anyhow::{bail, Context, Result};
use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};

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

/// What `sctl merge` wrote.
#[derive(Debug, Clone)]
pub struct Merged {
    /// The merged run directory.
    pub out: PathBuf,
    /// The end-of-run table.
    pub summary: String,
}

/// The `config.toml` every directory holds (an error unless they all hold
/// the same one): its path in the first directory and its text.
fn common_config(dirs: &[PathBuf]) -> Result<(PathBuf, String)> {
    let Some(first) = dirs.first() else {
        bail!("merge: no run directory given");
    };
    let read = |dir: &Path| {
        let path = dir.join(CONFIG_FILE);
        let text = std::fs::read_to_string(&path).with_context(|| {
            format!(
                "{}: cannot read (is {} a run directory?)",
                path.display(),
                dir.display()
            )
        })?;
        Ok::<_, anyhow::Error>((path, text))
    };
    let (config_path, text) = read(first)?;
    for dir in &dirs[1..] {
        let (other, t) = read(dir)?;
        if t != text {
            bail!(
                "{}: differs from {}: the directories are not parts of one experiment",
                other.display(),
                config_path.display()
            );
        }
    }
    Ok((config_path, text))
}

/// The output directory: `out`, default `results/<name>`, never one of `dirs`.
fn output_dir(dirs: &[PathBuf], out: Option<&Path>, name: &str) -> Result<PathBuf> {
    let out = out
        .map(Path::to_path_buf)
        .unwrap_or_else(|| default_out_dir(name, None));
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
    Ok(out)
}

/// The rows of file `name` (with columns `header`) of every directory, one
/// per unit; two `per_scene.csv` rows of one unit must be equal.
fn merged_table(
    dirs: &[PathBuf],
    name: &str,
    header: Vec<String>,
    index: &UnitIndex,
    scenes: &[String],
) -> Result<CsvTable> {
    let mut all = CsvTable {
        header,
        rows: Vec::new(),
    };
    let mut origin: HashMap<(usize, usize), (PathBuf, Vec<String>)> = HashMap::new();
    for dir in dirs {
        let path = dir.join(name);
        let table = CsvTable::read(&path)?;
        if table.header != all.header {
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
                    index.plan().label(key.0),
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
    Ok(all)
}

/// An error naming a missing unit unless `per_scene` has every one.
fn check_complete(per_scene: &CsvTable, index: &UnitIndex, scenes: &[String]) -> Result<()> {
    let plan = index.plan();
    let expected = plan.combinations.len() * scenes.len();
    let have: HashSet<(usize, usize)> = per_scene
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
    Ok(())
}

/// Combines the run directories of the shards of one experiment into `out`
/// (default `results/<name>`): the same files a single run writes.
///
/// Every directory must hold the same `config.toml`; together they must
/// cover every (combination, scene) unit. Per-scene figures of the shards
/// are copied; the run-level figures are drawn from the merged rows.
pub fn merge(dirs: &[PathBuf], out: Option<&Path>) -> Result<Merged> {
    let (config_path, text) = common_config(dirs)?;
    let config = ExperimentConfig::parse(&text, &config_path)?;
    let plan = SweepPlan::expand(&config)
        .map_err(|e| anyhow::anyhow!("{}: {}: {}", config_path.display(), e.key, e.message))?;
    let scenes = config.dataset.scenes.clone().with_context(|| {
        format!(
            "{}: no resolved scene list (not written by sctl run)",
            config_path.display()
        )
    })?;
    let out = output_dir(dirs, out, &config.name)?;

    let index = UnitIndex::new(&plan, &scenes);
    let per_scene = merged_table(
        dirs,
        PER_SCENE_FILE,
        per_scene_header(&plan.columns),
        &index,
        &scenes,
    )?;
    let timings = merged_table(
        dirs,
        TIMINGS_FILE,
        timings_header(&plan.columns),
        &index,
        &scenes,
    )?;
    check_complete(&per_scene, &index, &scenes)?;

    std::fs::create_dir_all(&out).with_context(|| format!("{}: cannot create", out.display()))?;
    write_atomic(&out.join(CONFIG_FILE), &text)?;
    per_scene.write_atomic(&out.join(PER_SCENE_FILE))?;
    timings.write_atomic(&out.join(TIMINGS_FILE))?;
    for dir in dirs {
        copy_scene_plots(dir, &out)?;
    }
    let summary = finalize(&out, &config, &plan, &scenes, true)?.summary;
    Ok(Merged { out, summary })
}
