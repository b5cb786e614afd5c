//! Completing a run directory: rows in unit order, then the files derived
//! from them.

use super::units::{sort_rows, UnitIndex};
use crate::config::ExperimentConfig;
use crate::output::{
    write_atomic, CsvTable, SceneResult, PER_SCENE_FILE, REPORT_FILE, SUMMARY_FILE, TIMINGS_FILE,
    WILCOXON_FILE,
};
use crate::report::{
    clear_run_plots, console_summary, mean_timings, render_report, summary_table, wilcoxon_rows,
    wilcoxon_table, write_run_plots, ReportContext, RunValues,
};
use crate::sweep::SweepPlan;
use anyhow::Result;
use std::path::Path;

/// Completes a run directory: sorts `per_scene.csv` and `timings.csv` into
/// unit order and, unless this is a shard, writes `summary.csv`,
/// `wilcoxon.csv`, `report.md` and (with `[plots] enabled`) the run-level
/// figures of [`write_run_plots`], replacing any earlier ones. Returns the
/// end-of-run table and the failed units.
pub fn finalize(
    dir: &Path,
    config: &ExperimentConfig,
    plan: &SweepPlan,
    scenes: &[String],
    derive: bool,
) -> Result<Finalized> {
    let index = UnitIndex::new(plan, scenes);
    let per_scene_path = dir.join(PER_SCENE_FILE);
    let timings_path = dir.join(TIMINGS_FILE);
    let mut per_scene = CsvTable::read(&per_scene_path)?;
    let units = sort_rows(&mut per_scene, &index, &per_scene_path, None)?;
    per_scene.write_atomic(&per_scene_path)?;
    let mut timings = CsvTable::read(&timings_path)?;
    sort_rows(&mut timings, &index, &timings_path, Some(&units))?;
    timings.write_atomic(&timings_path)?;
    let failed = failed_units(plan, &per_scene, &per_scene_path)?;
    if !derive {
        return Ok(Finalized {
            summary: String::new(),
            failed,
        });
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
        write_run_plots(dir, plan, &values, &config.plots.formats)?;
    }
    let mean_times = mean_timings(plan, &timings, &timings_path)?;
    Ok(Finalized {
        summary: console_summary(plan, &values, &tests, &mean_times),
        failed,
    })
}

/// What [`finalize`] reports.
#[derive(Debug, Clone, Default)]
pub struct Finalized {
    /// The end-of-run table (empty for a shard).
    pub summary: String,
    /// The units that could not be segmented, in unit order.
    pub failed: Vec<FailedUnit>,
}

/// A (combination, scene) unit that could not be segmented.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FailedUnit {
    /// The scene name.
    pub scene: String,
    /// The combination as `key=value` pairs.
    pub combination: String,
    /// Why ([`SceneResult::failure`]).
    pub reason: String,
}

impl std::fmt::Display for FailedUnit {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "scene `{}` ({}): {}",
            self.scene, self.combination, self.reason
        )
    }
}

/// The failed units among the rows of `per_scene.csv`.
fn failed_units(plan: &SweepPlan, per_scene: &CsvTable, file: &Path) -> Result<Vec<FailedUnit>> {
    let k = plan.columns.len();
    let mut failed = Vec::new();
    for (r, row) in per_scene.rows.iter().enumerate() {
        let result = SceneResult::from_cells(&per_scene.header[k..], &row[k..], file, r + 2)?;
        if let (Some(reason), Some(c)) = (result.failure(), plan.find(&row[..k])) {
            failed.push(FailedUnit {
                scene: result.scene.clone(),
                combination: plan.label(c),
                reason: reason.to_string(),
            });
        }
    }
    Ok(failed)
}
