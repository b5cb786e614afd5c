//! The data behind the run-level figures (Figs. 9 and 10, the ME scatter)
//! and their drawing into `<run>/plots/`.

use super::stats::RunValues;
use crate::config::{Method, PlotFormat};
use crate::output::{params_file_name, PLOTS_DIR};
use crate::plots::{self, me_scene_pairs, me_vs_samples_series, PlotError};
use crate::sweep::SweepPlan;
use anyhow::{Context, Result};
use std::path::{Path, PathBuf};

/// File stem of the ME-against-M figure (Fig. 10).
pub const ME_VS_SAMPLES_PLOT: &str = "me_vs_num_samples";
/// File stem of the relative focal error histograms (Fig. 9).
pub const FOCAL_ERROR_PLOT: &str = "focal_error";
/// File stem of the ME-per-scene scatters, baseline against semical.
pub const ME_SCATTER_PLOT: &str = "me_scatter";

/// `stem`, then `__` and the combination's parameters other than `method`
/// when there are any (see [`params_file_name`]).
pub(super) fn run_plot_stem(stem: &str, plan: &SweepPlan, combination: usize) -> String {
    let params = plan.params_of(combination, &["method"]);
    if params.is_empty() {
        stem.to_string()
    } else {
        format!("{stem}__{}", params_file_name(&params))
    }
}

/// Removes the run-level figures (the files directly in `<dir>/plots/`),
/// leaving the per-scene subdirectories.
pub fn clear_run_plots(dir: &Path) -> Result<()> {
    let plots = dir.join(PLOTS_DIR);
    let Ok(entries) = std::fs::read_dir(&plots) else {
        return Ok(());
    };
    for entry in entries {
        let path = entry
            .with_context(|| format!("{}: cannot list", plots.display()))?
            .path();
        if path.is_file() {
            std::fs::remove_file(&path)
                .with_context(|| format!("{}: cannot remove", path.display()))?;
        }
    }
    Ok(())
}

/// Draws the run-level figures of a finished run from the values of its
/// `per_scene.csv` into `<dir>/plots/`, once per format, and
/// returns the files written:
///
/// - `me_vs_num_samples`: ME against M (Fig. 10, [`me_vs_samples_series`]),
///   when `num_samples` is swept;
/// - `focal_error[__<params>]`: for each semical combination with at least
///   one scene of known focal, the histogram of `|f_peak − f_true| / f_true`
///   with its `τ_range` band (Fig. 9);
/// - `me_scatter[__<params>]`: for each semical combination whose baseline
///   ran too, ME per scene of the baseline against semical
///   ([`me_scene_pairs`]), when they share a scene with ME.
///
/// `<params>` are the combination's swept parameters other than `method`
/// ([`params_file_name`]). The figures depend only on the values of `per_scene.csv`,
/// so a resumed, merged or multi-threaded run draws the same ones.
pub fn write_run_plots(
    dir: &Path,
    plan: &SweepPlan,
    values: &RunValues,
    formats: &[PlotFormat],
) -> Result<Vec<PathBuf>> {
    let plots = dir.join(PLOTS_DIR);
    std::fs::create_dir_all(&plots)
        .with_context(|| format!("{}: cannot create", plots.display()))?;
    let mut written = Vec::new();
    let mut each_format = |stem: &str, draw: &dyn Fn(&Path) -> Result<(), PlotError>| {
        for format in formats {
            let path = plots.join(format!("{stem}.{}", format.extension()));
            draw(&path)?;
            written.push(path);
        }
        Ok::<(), anyhow::Error>(())
    };
    if let Some(series) = me_vs_samples_series(plan, values) {
        each_format(ME_VS_SAMPLES_PLOT, &|path| {
            plots::me_vs_samples(&series, path)
        })?;
    }
    let errors = &values.focal_errors;
    for combo in &plan.combinations {
        let c = combo.index;
        if combo.pipeline.params.focal.method == Method::Semical && !errors[c].is_empty() {
            let tau_range = combo.pipeline.params.focal.tau_range;
            each_format(&run_plot_stem(FOCAL_ERROR_PLOT, plan, c), &|path| {
                plots::focal_error_histogram(&errors[c], tau_range, path)
            })?;
        }
        if let Some(pairs) = me_scene_pairs(plan, values, c).filter(|p| !p.is_empty()) {
            each_format(&run_plot_stem(ME_SCATTER_PLOT, plan, c), &|path| {
                plots::me_scatter(&pairs, path)
            })?;
        }
    }
    Ok(written)
}
