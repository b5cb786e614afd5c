//! What a finished run derives from its `per_scene.csv`: `summary.csv`
//! (mean ± std per combination), `wilcoxon.csv` (each combination against
//! its reference) and `report.md` (tables in the style of the thesis's
//! Tables 2–4) and the run-level figures under `plots/`
//! ([`write_run_plots`]).
//!
//! Everything here reads the per-scene values back from the CSV text, so a
//! resumed or merged run derives exactly the bytes of an uninterrupted one.

use crate::config::{Method, PlotFormat};
use crate::output::{params_file_name, CsvTable, StageTimings, PLOTS_DIR};
use crate::plots::{self, PlotError, ScenePair, Series};
use crate::sweep::SweepPlan;
use crate::wilcoxon::{wilcoxon, Alternative, Mode, WilcoxonError};
use anyhow::{bail, Context, Result};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// The metrics summarised per combination, in column order.
pub const SUMMARY_METRICS: [&str; 7] = ["me", "acc", "fnr", "pur", "ari", "nmi", "frob"];

/// The metrics tested with Wilcoxon (errors: lower is better).
pub const TESTED_METRICS: [&str; 2] = ["me", "fnr"];

/// Scale from the per-scene value to the summary: percent for the label
/// metrics (as the thesis reports them), 1 for FROB (a distance).
pub fn summary_scale(metric: &str) -> f64 {
    if metric == "frob" {
        1.0
    } else {
        100.0
    }
}

/// True for the metrics where lower is better.
pub fn lower_is_better(metric: &str) -> bool {
    matches!(metric, "me" | "fnr" | "frob")
}

/// Mean and population standard deviation (ddof 0) of a sample.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeanStd {
    /// Arithmetic mean.
    pub mean: f64,
    /// Standard deviation with ddof 0 (method.md "Metrics").
    pub std: f64,
    /// Sample size.
    pub count: usize,
}

impl MeanStd {
    /// Mean and std of `values`; None when empty.
    pub fn of(values: &[f64]) -> Option<Self> {
        if values.is_empty() {
            return None;
        }
        let n = values.len() as f64;
        let mean = values.iter().sum::<f64>() / n;
        let var = values.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / n;
        Some(Self {
            mean,
            std: var.sqrt(),
            count: values.len(),
        })
    }
}

/// The per-scene values of one run, indexed by combination.
#[derive(Debug, Clone)]
pub struct RunValues {
    /// For each combination: the scenes it has rows for, in row order.
    pub scenes: Vec<Vec<String>>,
    /// For each combination and each of [`SUMMARY_METRICS`]: (scene, value).
    pub metrics: Vec<Vec<Vec<(String, f64)>>>,
    /// For each combination: generated hypotheses per scene.
    pub generated: Vec<Vec<f64>>,
    /// For each combination: kept hypotheses per scene.
    pub kept: Vec<Vec<f64>>,
}

fn parse_cell(cell: &str, file: &Path, row: usize, column: &str) -> Result<Option<f64>> {
    if cell.is_empty() {
        return Ok(None);
    }
    cell.parse::<f64>().map(Some).with_context(|| {
        format!(
            "{}: row {}: column `{column}`: `{cell}` is not a number",
            file.display(),
            row + 2
        )
    })
}

impl RunValues {
    /// Collects the values of `table` (a `per_scene.csv`) by combination.
    pub fn collect(plan: &SweepPlan, table: &CsvTable, file: &Path) -> Result<Self> {
        let k = plan.columns.len();
        let scene_col = table.require_column("scene", file)?;
        let metric_cols: Vec<usize> = SUMMARY_METRICS
            .iter()
            .map(|m| table.require_column(m, file))
            .collect::<Result<_>>()?;
        let generated_col = table.require_column("hypotheses_generated", file)?;
        let kept_col = table.require_column("hypotheses_kept", file)?;
        let c = plan.combinations.len();
        let mut out = Self {
            scenes: vec![Vec::new(); c],
            metrics: vec![vec![Vec::new(); SUMMARY_METRICS.len()]; c],
            generated: vec![Vec::new(); c],
            kept: vec![Vec::new(); c],
        };
        for (r, row) in table.rows.iter().enumerate() {
            let combo = plan.find(&row[..k]).with_context(|| {
                format!(
                    "{}: row {}: parameters ({}) are not a combination of this run",
                    file.display(),
                    r + 2,
                    row[..k].join(", ")
                )
            })?;
            let scene = row[scene_col].clone();
            for (m, &col) in metric_cols.iter().enumerate() {
                if let Some(v) = parse_cell(&row[col], file, r, SUMMARY_METRICS[m])? {
                    out.metrics[combo][m].push((scene.clone(), v));
                }
            }
            if let Some(v) = parse_cell(&row[generated_col], file, r, "hypotheses_generated")? {
                out.generated[combo].push(v);
            }
            if let Some(v) = parse_cell(&row[kept_col], file, r, "hypotheses_kept")? {
                out.kept[combo].push(v);
            }
            out.scenes[combo].push(scene);
        }
        Ok(out)
    }

    /// Mean ± std of metric `m` (index into [`SUMMARY_METRICS`]) of a
    /// combination, in summary units (see [`summary_scale`]).
    pub fn stats(&self, combo: usize, m: usize) -> Option<MeanStd> {
        let scale = summary_scale(SUMMARY_METRICS[m]);
        let values: Vec<f64> = self.metrics[combo][m]
            .iter()
            .map(|(_, v)| v * scale)
            .collect();
        MeanStd::of(&values)
    }
}

fn mean(values: &[f64]) -> Option<f64> {
    MeanStd::of(values).map(|s| s.mean)
}

fn cell(v: Option<f64>, decimals: usize) -> String {
    v.map(|x| format!("{x:.decimals$}")).unwrap_or_default()
}

/// `summary.csv`: per combination, the parameter columns, `scenes`, then
/// `<metric>_mean, <metric>_std` for ME, ACC, FNR, PUR, ARI, NMI (percent, 4
/// decimals) and FROB (as is, 6 decimals), `frob_scenes` (scenes where FROB
/// is defined), and the mean hypothesis counts `hypotheses_generated_mean`,
/// `hypotheses_kept_mean` (2 decimals).
pub fn summary_table(plan: &SweepPlan, values: &RunValues) -> CsvTable {
    let mut header = plan.columns.clone();
    header.push("scenes".into());
    for m in SUMMARY_METRICS {
        header.push(format!("{m}_mean"));
        header.push(format!("{m}_std"));
    }
    header.extend(
        [
            "frob_scenes",
            "hypotheses_generated_mean",
            "hypotheses_kept_mean",
        ]
        .iter()
        .map(|s| s.to_string()),
    );
    let mut rows = Vec::new();
    for combo in &plan.combinations {
        let c = combo.index;
        let mut row = combo.values.clone();
        row.push(values.scenes[c].len().to_string());
        for (m, name) in SUMMARY_METRICS.iter().enumerate() {
            let decimals = if *name == "frob" { 6 } else { 4 };
            let s = values.stats(c, m);
            row.push(cell(s.map(|s| s.mean), decimals));
            row.push(cell(s.map(|s| s.std), decimals));
        }
        row.push(
            values.metrics[c][SUMMARY_METRICS.len() - 1]
                .len()
                .to_string(),
        );
        row.push(cell(mean(&values.generated[c]), 2));
        row.push(cell(mean(&values.kept[c]), 2));
        rows.push(row);
    }
    CsvTable { header, rows }
}

/// One Wilcoxon test of a combination against its reference.
#[derive(Debug, Clone, PartialEq)]
pub struct WilcoxonRow {
    /// The tested combination.
    pub combination: usize,
    /// Its reference combination.
    pub reference: usize,
    /// `me` or `fnr`.
    pub metric: &'static str,
    /// Scenes present in both.
    pub pairs: usize,
    /// The test, or why it is undefined.
    pub result: std::result::Result<crate::wilcoxon::WilcoxonResult, WilcoxonError>,
}

/// Paired values of two combinations on their common scenes, in the scene
/// order of `a`: `(a values, b values)`.
pub fn paired(a: &[(String, f64)], b: &[(String, f64)]) -> (Vec<f64>, Vec<f64>) {
    let mut x = Vec::new();
    let mut y = Vec::new();
    for (scene, va) in a {
        if let Some((_, vb)) = b.iter().find(|(s, _)| s == scene) {
            x.push(*va);
            y.push(*vb);
        }
    }
    (x, y)
}

/// The one-tailed tests of every combination against its reference
/// (`[compare] against`) on ME and FNR: H1: the reference's error is larger
/// (scipy's `wilcoxon(reference, combination, alternative='greater')`).
pub fn wilcoxon_rows(
    plan: &SweepPlan,
    values: &RunValues,
    against: &toml::Table,
) -> Vec<WilcoxonRow> {
    let mut rows = Vec::new();
    for combo in &plan.combinations {
        let Some(reference) = plan.reference_of(combo.index, against) else {
            continue;
        };
        for metric in TESTED_METRICS {
            let m = SUMMARY_METRICS
                .iter()
                .position(|x| *x == metric)
                .expect("tested metric is summarised");
            let (x, y) = paired(
                &values.metrics[reference][m],
                &values.metrics[combo.index][m],
            );
            rows.push(WilcoxonRow {
                combination: combo.index,
                reference,
                metric,
                pairs: x.len(),
                result: wilcoxon(&x, &y, Alternative::Greater, Mode::Auto),
            });
        }
    }
    rows
}

/// A combination as `key=value` pairs separated by spaces.
pub fn short_label(plan: &SweepPlan, combination: usize) -> String {
    plan.columns
        .iter()
        .zip(&plan.combinations[combination].values)
        .map(|(k, v)| format!("{k}={v}"))
        .collect::<Vec<_>>()
        .join(" ")
}

/// `wilcoxon.csv`: the parameter columns of the tested combination,
/// `against` (the reference as `key=value` pairs), `metric`, `n` (non-zero
/// differences), `statistic` (T+), `p_value`, `mode_used` (`exact`,
/// `permutation`, `approx`; `undefined` with empty statistic and p when no
/// difference is non-zero).
pub fn wilcoxon_table(plan: &SweepPlan, rows: &[WilcoxonRow]) -> CsvTable {
    let mut header = plan.columns.clone();
    header.extend(
        [
            "against",
            "metric",
            "n",
            "statistic",
            "p_value",
            "mode_used",
        ]
        .iter()
        .map(|s| s.to_string()),
    );
    let rows = rows
        .iter()
        .map(|w| {
            let mut row = plan.combinations[w.combination].values.clone();
            row.push(short_label(plan, w.reference));
            row.push(w.metric.to_string());
            match &w.result {
                Ok(r) => {
                    row.push(r.n.to_string());
                    row.push(format!("{:.1}", r.statistic));
                    row.push(format!("{:.6e}", r.p_value));
                    row.push(r.mode_used.to_string());
                }
                Err(_) => {
                    row.push("0".into());
                    row.push(String::new());
                    row.push(String::new());
                    row.push("undefined".into());
                }
            }
            row
        })
        .collect();
    CsvTable { header, rows }
}

fn pm(s: Option<MeanStd>, decimals: usize) -> String {
    match s {
        Some(s) => format!("{:.decimals$} ± {:.decimals$}", s.mean, s.std),
        None => "–".into(),
    }
}

/// What `report.md` shows besides the tables: the run's name and dataset.
pub struct ReportContext<'a> {
    /// Experiment name.
    pub name: &'a str,
    /// Free text from the config.
    pub description: Option<&'a str>,
    /// Dataset kind.
    pub dataset: &'a str,
    /// Scene names in run order.
    pub scenes: &'a [String],
}

/// `report.md`: the metrics table (thesis Tables 2 and 4), the Wilcoxon
/// tests (Table 3) and ME per scene.
pub fn render_report(
    ctx: &ReportContext,
    plan: &SweepPlan,
    values: &RunValues,
    tests: &[WilcoxonRow],
) -> String {
    let mut md = String::new();
    let _ = writeln!(md, "# {}\n", ctx.name);
    if let Some(d) = ctx.description {
        let _ = writeln!(md, "{}\n", d.trim());
    }
    let _ = writeln!(
        md,
        "Dataset `{}`, {} scenes, {} parameter combination(s). The resolved configuration is `config.toml`; \
         per-scene values are in `per_scene.csv`.\n",
        ctx.dataset,
        ctx.scenes.len(),
        plan.combinations.len()
    );

    let _ = writeln!(md, "## Metrics (mean ± std over scenes)\n");
    let _ = writeln!(
        md,
        "ME, ACC, FNR, PUR, ARI and NMI in percent, FROB (Eq. 45) as a distance; std with ddof 0.\n"
    );
    let mut header: Vec<String> = plan.columns.clone();
    header.extend(
        [
            "scenes",
            "ME",
            "ACC",
            "FNR",
            "PUR",
            "ARI",
            "NMI",
            "FROB",
            "kept / generated",
        ]
        .iter()
        .map(|s| s.to_string()),
    );
    table_header(&mut md, &header);
    for combo in &plan.combinations {
        let c = combo.index;
        let mut cells = combo.values.clone();
        cells.push(values.scenes[c].len().to_string());
        for (m, name) in SUMMARY_METRICS.iter().enumerate() {
            cells.push(pm(values.stats(c, m), if *name == "frob" { 4 } else { 2 }));
        }
        cells.push(format!(
            "{} / {}",
            cell(mean(&values.kept[c]), 0),
            cell(mean(&values.generated[c]), 0)
        ));
        table_row(&mut md, &cells);
    }

    let _ = writeln!(md, "\n## Wilcoxon signed-rank tests\n");
    if tests.is_empty() {
        let _ = writeln!(
            md,
            "No combination of this run has its reference (`[compare] against`) in the run.\n"
        );
    } else {
        let _ = writeln!(
            md,
            "One-tailed, paired per scene, H1: the reference's error is larger (scipy's \
             `wilcoxon(reference, combination, alternative='greater')`, method `auto`).\n"
        );
        table_header(
            &mut md,
            &[
                "combination",
                "against",
                "metric",
                "pairs",
                "non-zero",
                "T+",
                "p",
                "mode",
            ]
            .map(String::from),
        );
        for t in tests {
            let (n, stat, p, mode) = match &t.result {
                Ok(r) => (
                    r.n.to_string(),
                    format!("{:.1}", r.statistic),
                    format!("{:.3e}", r.p_value),
                    r.mode_used.to_string(),
                ),
                Err(e) => ("0".into(), "–".into(), "–".into(), e.to_string()),
            };
            table_row(
                &mut md,
                &[
                    short_label(plan, t.combination),
                    short_label(plan, t.reference),
                    t.metric.to_uppercase(),
                    t.pairs.to_string(),
                    n,
                    stat,
                    p,
                    mode,
                ],
            );
        }
    }

    let _ = writeln!(md, "\n## ME per scene (%)\n");
    let me = 0;
    let mut header = vec!["scene".to_string()];
    header.extend((0..plan.combinations.len()).map(|c| short_label(plan, c)));
    table_header(&mut md, &header);
    for scene in ctx.scenes {
        let mut cells = vec![scene.clone()];
        for c in 0..plan.combinations.len() {
            let v = values.metrics[c][me].iter().find(|(s, _)| s == scene);
            cells.push(
                v.map(|(_, v)| format!("{:.2}", v * 100.0))
                    .unwrap_or_else(|| "–".into()),
            );
        }
        table_row(&mut md, &cells);
    }
    md
}

fn table_header(md: &mut String, cells: &[String]) {
    table_row(md, cells);
    let _ = writeln!(md, "|{}", "---|".repeat(cells.len()));
}

fn table_row(md: &mut String, cells: &[String]) {
    let escaped: Vec<String> = cells.iter().map(|c| c.replace('|', "\\|")).collect();
    let _ = writeln!(md, "| {} |", escaped.join(" | "));
}

/// Mean per-stage wall times of each combination, from `timings.csv`.
pub fn mean_timings(
    plan: &SweepPlan,
    table: &CsvTable,
    file: &Path,
) -> Result<Vec<Option<StageTimings>>> {
    let k = plan.columns.len();
    let mut sums = vec![[0.0f64; 8]; plan.combinations.len()];
    let mut counts = vec![0usize; plan.combinations.len()];
    let first = k + 2;
    if table.header.len() != first + 8 {
        bail!("{}: unexpected columns", file.display());
    }
    for (r, row) in table.rows.iter().enumerate() {
        let Some(c) = plan.find(&row[..k]) else {
            bail!(
                "{}: row {}: not a combination of this run",
                file.display(),
                r + 2
            );
        };
        for (s, sum) in sums[c].iter_mut().enumerate() {
            *sum += parse_cell(&row[first + s], file, r, &table.header[first + s])?.unwrap_or(0.0);
        }
        counts[c] += 1;
    }
    Ok(sums
        .iter()
        .zip(&counts)
        .map(|(s, &n)| {
            (n > 0).then(|| {
                let m = s.map(|v| v / n as f64);
                StageTimings {
                    sampling: m[0],
                    refine: m[1],
                    focal: m[2],
                    consensus: m[3],
                    preferences: m[4],
                    clustering: m[5],
                    cluster_fit: m[6],
                    total: m[7],
                }
            })
        })
        .collect())
}

/// The plain-text table `sctl run` and `sctl merge` print at the end.
pub fn console_summary(
    plan: &SweepPlan,
    values: &RunValues,
    tests: &[WilcoxonRow],
    timings: &[Option<StageTimings>],
) -> String {
    let mut rows: Vec<Vec<String>> = vec![[
        "combination",
        "scenes",
        "ME %",
        "FNR %",
        "kept/generated",
        "s/scene",
        "p(ME)",
    ]
    .map(String::from)
    .to_vec()];
    for combo in &plan.combinations {
        let c = combo.index;
        let p_me = tests
            .iter()
            .find(|t| t.combination == c && t.metric == "me")
            .and_then(|t| t.result.as_ref().ok())
            .map(|r| format!("{:.3e}", r.p_value))
            .unwrap_or_else(|| "–".into());
        rows.push(vec![
            short_label(plan, c),
            values.scenes[c].len().to_string(),
            pm(values.stats(c, 0), 2),
            pm(values.stats(c, 2), 2),
            format!(
                "{}/{}",
                cell(mean(&values.kept[c]), 0),
                cell(mean(&values.generated[c]), 0)
            ),
            timings
                .get(c)
                .copied()
                .flatten()
                .map(|t| format!("{:.3}", t.total))
                .unwrap_or_else(|| "–".into()),
            p_me,
        ]);
    }
    let mut out = aligned(&rows);
    let mut stages: Vec<Vec<String>> = vec![std::iter::once("mean s/scene by stage")
        .chain(StageTimings::NAMES)
        .map(String::from)
        .collect()];
    for combo in &plan.combinations {
        if let Some(t) = timings.get(combo.index).copied().flatten() {
            stages.push(
                std::iter::once(short_label(plan, combo.index))
                    .chain(t.values().iter().map(|v| format!("{v:.3}")))
                    .collect(),
            );
        }
    }
    if stages.len() > 1 {
        out.push('\n');
        out.push_str(&aligned(&stages));
    }
    out
}

/// Rows as left-aligned columns separated by two spaces.
fn aligned(rows: &[Vec<String>]) -> String {
    let widths: Vec<usize> = (0..rows[0].len())
        .map(|i| rows.iter().map(|r| r[i].chars().count()).max().unwrap_or(0))
        .collect();
    let mut out = String::new();
    for row in rows {
        let line: Vec<String> = row
            .iter()
            .zip(&widths)
            .map(|(c, w)| format!("{c:<w$}"))
            .collect();
        let _ = writeln!(out, "{}", line.join("  ").trim_end());
    }
    out
}

// ---------------------------------------------------------------------------
// Run-level figures.

/// File stem of the ME-against-M figure (Fig. 10).
pub const ME_VS_SAMPLES_PLOT: &str = "me_vs_num_samples";
/// File stem of the relative focal error histograms (Fig. 9).
pub const FOCAL_ERROR_PLOT: &str = "focal_error";
/// File stem of the ME-per-scene scatters, baseline against semical.
pub const ME_SCATTER_PLOT: &str = "me_scatter";

/// The `(column, value)` pairs of a combination, without the `skip` columns.
fn combination_params<'a>(
    plan: &'a SweepPlan,
    combination: usize,
    skip: &[&str],
) -> Vec<(&'a str, &'a str)> {
    plan.columns
        .iter()
        .zip(&plan.combinations[combination].values)
        .filter(|(k, _)| !skip.contains(&k.as_str()))
        .map(|(k, v)| (k.as_str(), v.as_str()))
        .collect()
}

/// `stem`, then `__` and the combination's parameters other than `method`
/// when there are any (see [`params_file_name`]).
fn run_plot_stem(stem: &str, plan: &SweepPlan, combination: usize) -> String {
    let params = combination_params(plan, combination, &["method"]);
    if params.is_empty() {
        stem.to_string()
    } else {
        format!("{stem}__{}", params_file_name(&params))
    }
}

/// The lines of Fig. 10 when `num_samples` is swept (None otherwise): one
/// series per combination of the other swept parameters (`method` and any
/// other), in run order, labelled by them (`semical`, or `method=semical,
/// tau_range=0.1`). Without a `seed` sweep each point is `(M, mean ME %, std
/// ME %)` over the scenes of one combination (ddof 0, as `summary.csv`).
/// When `seed` is swept too, the seeds of a line are pooled: each point is
/// the mean over the seeds of their mean ME and the standard deviation of
/// those means (ddof 0), i.e. the seed-to-seed spread. The label says which.
/// Combinations without any ME value are left out.
///
/// ```
/// let config = bench::config::ExperimentConfig::parse(
///     "name = \"x\"\n[dataset]\nkind = \"synthetic\"\n\
///      [sweep]\nmethod = [\"baseline\", \"semical\"]\nnum_samples = [100, 200]\n",
///     std::path::Path::new("x.toml"),
/// ).unwrap();
/// let plan = bench::sweep::SweepPlan::expand(&config).unwrap();
/// let table = bench::output::CsvTable::parse(
///     &format!("{}\n", bench::output::per_scene_header(&plan.columns).join(",")),
///     "p.csv".as_ref(),
/// ).unwrap();
/// let values = bench::report::RunValues::collect(&plan, &table, "p.csv".as_ref()).unwrap();
/// // No rows: nothing to draw, but num_samples is swept.
/// assert_eq!(bench::report::me_vs_samples_series(&plan, &values), Some(vec![]));
/// ```
pub fn me_vs_samples_series(plan: &SweepPlan, values: &RunValues) -> Option<Vec<Series>> {
    if !plan.columns.iter().any(|c| c == "num_samples") {
        return None;
    }
    let pooled = plan.columns.iter().any(|c| c == "seed");
    let me = SUMMARY_METRICS
        .iter()
        .position(|m| *m == "me")
        .expect("ME is summarised");
    // Per line: its key and, per M in run order, the mean ME of each
    // combination (one per seed when pooled) and the scenes' std.
    type Points = Vec<(usize, Vec<(f64, f64)>)>;
    let mut groups: Vec<(Vec<(&str, &str)>, Points)> = Vec::new();
    for combo in &plan.combinations {
        let Some(stats) = values.stats(combo.index, me) else {
            continue;
        };
        let key = combination_params(plan, combo.index, &["num_samples", "seed"]);
        let m = combo.pipeline.num_samples;
        let index = match groups.iter().position(|(k, _)| *k == key) {
            Some(i) => i,
            None => {
                groups.push((key, Vec::new()));
                groups.len() - 1
            }
        };
        let points = &mut groups[index].1;
        match points.iter_mut().find(|(pm, _)| *pm == m) {
            Some((_, v)) => v.push((stats.mean, stats.std)),
            None => points.push((m, vec![(stats.mean, stats.std)])),
        }
    }
    let series = groups
        .into_iter()
        .map(|(key, points)| {
            let name = match key.as_slice() {
                [("method", method)] => method.to_string(),
                _ => key
                    .iter()
                    .map(|(k, v)| format!("{k}={v}"))
                    .collect::<Vec<_>>()
                    .join(", "),
            };
            let seeds = points.iter().map(|(_, v)| v.len()).max().unwrap_or(0);
            let label = if pooled {
                format!("{name} (mean of {seeds} seeds ± std across seeds)")
            } else {
                format!("{name} (mean ± std over scenes)")
            };
            let points = points
                .into_iter()
                .map(|(m, v)| {
                    if pooled {
                        let n = v.len() as f64;
                        let mean = v.iter().map(|p| p.0).sum::<f64>() / n;
                        let var = v.iter().map(|p| (p.0 - mean).powi(2)).sum::<f64>() / n;
                        (m, mean, var.sqrt())
                    } else {
                        (m, v[0].0, v[0].1)
                    }
                })
                .collect();
            Series { label, points }
        })
        .collect();
    Some(series)
}

/// The `f_peak_error` column of `table` (a `per_scene.csv`) by combination:
/// `|f_peak − f_true| / f_true` of every scene where both are known.
pub fn focal_errors(plan: &SweepPlan, table: &CsvTable, file: &Path) -> Result<Vec<Vec<f64>>> {
    let k = plan.columns.len();
    let col = table.require_column("f_peak_error", file)?;
    let mut errors = vec![Vec::new(); plan.combinations.len()];
    for (r, row) in table.rows.iter().enumerate() {
        let combo = plan.find(&row[..k]).with_context(|| {
            format!(
                "{}: row {}: not a combination of this run",
                file.display(),
                r + 2
            )
        })?;
        if let Some(e) = parse_cell(&row[col], file, r, "f_peak_error")? {
            errors[combo].push(e);
        }
    }
    Ok(errors)
}

/// ME (%) per scene of a semical combination and of its baseline (the
/// combination with `method = "baseline"` and every other parameter equal),
/// on the scenes both have an ME for, in the semical combination's scene
/// order. None when `combination` is not semical or its baseline is not
/// part of the run.
pub fn me_scene_pairs(
    plan: &SweepPlan,
    values: &RunValues,
    combination: usize,
) -> Option<Vec<ScenePair>> {
    if plan.combinations[combination].pipeline.method != Method::Semical {
        return None;
    }
    let mut against = toml::Table::new();
    against.insert("method".into(), toml::Value::String("baseline".into()));
    let baseline = plan.reference_of(combination, &against)?;
    let me = SUMMARY_METRICS
        .iter()
        .position(|m| *m == "me")
        .expect("ME is summarised");
    let scale = summary_scale("me");
    let baseline_values = &values.metrics[baseline][me];
    Some(
        values.metrics[combination][me]
            .iter()
            .filter_map(|(scene, method_me)| {
                let (_, baseline_me) = baseline_values.iter().find(|(s, _)| s == scene)?;
                Some(ScenePair {
                    scene: scene.clone(),
                    baseline_me: baseline_me * scale,
                    method_me: method_me * scale,
                })
            })
            .collect(),
    )
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

/// Draws the run-level figures of a finished run from its `per_scene.csv`
/// (`table`, read from `file`) into `<dir>/plots/`, once per format, and
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
/// ([`params_file_name`]). The figures depend only on the table's content,
/// so a resumed, merged or multi-threaded run draws the same ones.
pub fn write_run_plots(
    dir: &Path,
    plan: &SweepPlan,
    values: &RunValues,
    table: &CsvTable,
    file: &Path,
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
    let errors = focal_errors(plan, table, file)?;
    for combo in &plan.combinations {
        let c = combo.index;
        if combo.pipeline.method == Method::Semical && !errors[c].is_empty() {
            let tau_range = combo.pipeline.tau_range;
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::ExperimentConfig;

    fn plan() -> SweepPlan {
        let config = ExperimentConfig::parse(
            "name = \"r\"\n[dataset]\nkind = \"synthetic\"\n[sweep]\nmethod = [\"baseline\", \"semical\"]\n",
            Path::new("r.toml"),
        )
        .unwrap();
        SweepPlan::expand(&config).unwrap()
    }

    fn table(rows: &[(&str, &str, &str, &str)]) -> CsvTable {
        let header = crate::output::per_scene_header(&["method".to_string()]);
        let rows = rows
            .iter()
            .map(|(method, scene, me, frob)| {
                let mut row = vec![String::new(); header.len()];
                row[0] = method.to_string();
                row[1] = scene.to_string();
                for (name, v) in [
                    ("me", *me),
                    ("fnr", *me),
                    ("frob", *frob),
                    ("hypotheses_generated", "10"),
                    ("hypotheses_kept", "4"),
                ] {
                    let i = header.iter().position(|h| h == name).unwrap();
                    row[i] = v.to_string();
                }
                row
            })
            .collect();
        CsvTable { header, rows }
    }

    #[test]
    fn mean_and_population_std() {
        let s = MeanStd::of(&[1.0, 2.0, 3.0, 4.0]).unwrap();
        assert_eq!(s.mean, 2.5);
        assert!((s.std - 1.25f64.sqrt()).abs() < 1e-15);
        assert!(MeanStd::of(&[]).is_none());
    }

    #[test]
    fn summary_is_in_percent_and_tests_pair_by_scene() {
        let p = plan();
        let t = table(&[
            ("baseline", "a", "0.300000", "0.01"),
            ("baseline", "b", "0.200000", ""),
            ("baseline", "c", "0.100000", "0.03"),
            ("semical", "c", "0.050000", "0.02"),
            ("semical", "a", "0.100000", ""),
            ("semical", "b", "0.100000", ""),
        ]);
        let values = RunValues::collect(&p, &t, Path::new("p.csv")).unwrap();
        let s = summary_table(&p, &values);
        let me_mean = s.header.iter().position(|h| h == "me_mean").unwrap();
        assert_eq!(s.rows[0][me_mean], "20.0000");
        let frob_n = s.header.iter().position(|h| h == "frob_scenes").unwrap();
        assert_eq!(s.rows[0][frob_n], "2");
        assert_eq!(s.rows[1][frob_n], "1");
        let against = crate::config::CompareConfig::default().against;
        let tests = wilcoxon_rows(&p, &values, &against);
        assert_eq!(tests.len(), 2);
        assert_eq!(tests[0].combination, 1);
        assert_eq!(tests[0].reference, 0);
        let r = tests[0].result.as_ref().unwrap();
        // Differences baseline - semical, paired by scene: 0.2, 0.1, 0.05: all positive.
        assert_eq!((r.n, r.statistic), (3, 6.0));
        assert!((r.p_value - 0.125).abs() < 1e-12);
        let w = wilcoxon_table(&p, &tests);
        assert_eq!(
            w.rows[0],
            [
                "semical",
                "method=baseline",
                "me",
                "3",
                "6.0",
                "1.250000e-1",
                "exact"
            ]
        );
    }

    #[test]
    fn unknown_combination_is_an_error() {
        let p = plan();
        let t = table(&[("bogus", "a", "0.1", "")]);
        let err = RunValues::collect(&p, &t, Path::new("p.csv"))
            .unwrap_err()
            .to_string();
        assert!(err.contains("p.csv: row 2: parameters (bogus)"), "{err}");
    }

    /// A per_scene table for a sweep of method × num_samples × tau_range:
    /// rows `(method, M, tau_range, scene, me, f_peak_error)`.
    fn swept() -> (SweepPlan, CsvTable) {
        swept_with("tau_range = [0.1, 0.3]", "0.3", 0.0)
    }

    /// As [`swept`] with `third` (a TOML sweep line) as the third swept
    /// parameter; ME is `bump` higher where it takes the value `bumped`.
    fn swept_with(third: &str, bumped: &str, bump: f64) -> (SweepPlan, CsvTable) {
        let config = ExperimentConfig::parse(
            &format!(
                "name = \"r\"\n[dataset]\nkind = \"synthetic\"\n[sweep]\n\
                 method = [\"baseline\", \"semical\"]\nnum_samples = [500, 100]\n{third}\n"
            ),
            Path::new("r.toml"),
        )
        .unwrap();
        let plan = SweepPlan::expand(&config).unwrap();
        let header = crate::output::per_scene_header(&plan.columns);
        let col = |name: &str| header.iter().position(|h| h == name).unwrap();
        let mut rows = Vec::new();
        for combo in &plan.combinations {
            let semical = combo.pipeline.method == Method::Semical;
            for (s, scene) in ["a", "b"].iter().enumerate() {
                // ME: baseline 0.2 / 0.4 on scenes a / b, semical half of it,
                // and 0.1 lower at M = 500.
                let mut me = 0.2 * (s + 1) as f64;
                if semical {
                    me /= 2.0;
                }
                if combo.pipeline.num_samples == 500 {
                    me -= 0.1;
                }
                if combo.values[2] == bumped {
                    me += bump;
                }
                let mut row = vec![String::new(); header.len()];
                row[..3].clone_from_slice(&combo.values);
                row[3] = scene.to_string();
                row[col("me")] = format!("{me:.6}");
                row[col("hypotheses_generated")] = "10".into();
                row[col("hypotheses_kept")] = "4".into();
                if semical && s == 0 {
                    row[col("f_peak_error")] = "0.250000".into();
                }
                rows.push(row);
            }
        }
        (plan, CsvTable { header, rows })
    }

    /// The Fig. 10 series of a table and their labels.
    fn series_of(plan_and_table: (SweepPlan, CsvTable)) -> (Vec<Series>, Vec<String>) {
        let (swept_plan, table) = plan_and_table;
        let values = RunValues::collect(&swept_plan, &table, Path::new("p.csv")).unwrap();
        let series = me_vs_samples_series(&swept_plan, &values).unwrap();
        let labels = series.iter().map(|s| s.label.clone()).collect();
        (series, labels)
    }

    #[test]
    fn me_against_m_has_one_series_per_other_combination() {
        let (series, labels) = series_of(swept());
        assert_eq!(
            labels,
            [
                "method=baseline, tau_range=0.1 (mean ± std over scenes)",
                "method=baseline, tau_range=0.3 (mean ± std over scenes)",
                "method=semical, tau_range=0.1 (mean ± std over scenes)",
                "method=semical, tau_range=0.3 (mean ± std over scenes)"
            ]
        );
        // Semical, tau_range 0.3: M = 500 first (sweep order), ME 0, 10 %
        // (mean 5, std 5), then M = 100: 10, 20 % (mean 15, std 5).
        let points = &series[3].points;
        assert_eq!(points.len(), 2);
        assert_eq!(points[0].0, 500);
        assert!((points[0].1 - 5.0).abs() < 1e-9 && (points[0].2 - 5.0).abs() < 1e-9);
        assert_eq!(points[1].0, 100);
        assert!((points[1].1 - 15.0).abs() < 1e-9 && (points[1].2 - 5.0).abs() < 1e-9);
        // Without num_samples in the sweep there is no such figure.
        assert_eq!(me_vs_samples_series(&plan(), &values_of_plan()), None);
    }

    #[test]
    fn me_against_m_pools_the_seeds_of_a_line() {
        let (series, labels) = series_of(swept_with("seed = [1, 2]", "2", 0.1));
        assert_eq!(
            labels,
            [
                "baseline (mean of 2 seeds ± std across seeds)",
                "semical (mean of 2 seeds ± std across seeds)"
            ]
        );
        // Semical at M = 500: seed 1 has ME 0, 10 % (mean 5), seed 2 10,
        // 20 % (mean 15): pooled mean 10, spread 5.
        let points = &series[1].points;
        assert_eq!(points.len(), 2);
        assert_eq!(points[0].0, 500);
        assert!((points[0].1 - 10.0).abs() < 1e-9, "{points:?}");
        assert!((points[0].2 - 5.0).abs() < 1e-9, "{points:?}");
    }

    fn values_of_plan() -> RunValues {
        RunValues::collect(&plan(), &table(&[]), Path::new("p.csv")).unwrap()
    }

    #[test]
    fn scatter_pairs_semical_with_its_baseline_and_errors_by_combination() {
        let (plan, table) = swept();
        let values = RunValues::collect(&plan, &table, Path::new("p.csv")).unwrap();
        // Combination 0 is baseline: no pairs.
        assert!(me_scene_pairs(&plan, &values, 0).is_none());
        let semical = plan
            .find(&["semical".into(), "100".into(), "0.3".into()])
            .unwrap();
        let pairs = me_scene_pairs(&plan, &values, semical).unwrap();
        let got: Vec<(&str, f64, f64)> = pairs
            .iter()
            .map(|p| (p.scene.as_str(), p.baseline_me, p.method_me))
            .collect();
        assert_eq!(got.len(), 2);
        for ((scene, b, m), (want_scene, want_b, want_m)) in
            got.iter().zip([("a", 20.0, 10.0), ("b", 40.0, 20.0)])
        {
            assert_eq!(*scene, want_scene);
            assert!((b - want_b).abs() < 1e-9 && (m - want_m).abs() < 1e-9);
        }
        let errors = focal_errors(&plan, &table, Path::new("p.csv")).unwrap();
        let with_errors: Vec<usize> = (0..errors.len())
            .filter(|&c| !errors[c].is_empty())
            .collect();
        assert_eq!(with_errors, [4, 5, 6, 7]);
        assert_eq!(errors[semical], [0.25]);
        assert_eq!(
            run_plot_stem(FOCAL_ERROR_PLOT, &plan, semical),
            "focal_error__num_samples-100__tau_range-0.3"
        );
    }

    #[test]
    fn run_plots_are_written_and_replace_earlier_ones() {
        let (plan, table) = swept();
        let values = RunValues::collect(&plan, &table, Path::new("p.csv")).unwrap();
        let dir = tempfile::tempdir().unwrap();
        let stale = dir.path().join(PLOTS_DIR).join("me_scatter__old.svg");
        std::fs::create_dir_all(stale.parent().unwrap()).unwrap();
        std::fs::write(&stale, "<svg/>").unwrap();
        clear_run_plots(dir.path()).unwrap();
        assert!(!stale.exists());
        let written = write_run_plots(
            dir.path(),
            &plan,
            &values,
            &table,
            Path::new("p.csv"),
            &[PlotFormat::Svg],
        )
        .unwrap();
        let mut names: Vec<String> = written
            .iter()
            .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
            .collect();
        names.sort();
        let mut expected = vec!["me_vs_num_samples.svg".to_string()];
        for m in [100, 500] {
            for tau in ["0.1", "0.3"] {
                for stem in [FOCAL_ERROR_PLOT, ME_SCATTER_PLOT] {
                    expected.push(format!("{stem}__num_samples-{m}__tau_range-{tau}.svg"));
                }
            }
        }
        expected.sort();
        assert_eq!(names, expected);
        let histogram = std::fs::read_to_string(
            dir.path()
                .join(PLOTS_DIR)
                .join("focal_error__num_samples-500__tau_range-0.1.svg"),
        )
        .unwrap();
        assert!(histogram.contains("within τ_range = 0.1: 0 of 1 scenes"));
    }
}
