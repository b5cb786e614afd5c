//! The plain-text table `sctl run` and `sctl merge` print at the end, with
//! the mean per-stage timings read from `timings.csv`.

use super::markdown::pm;
use super::stats::{mean, metric_index, RunValues};
use super::tables::{cell, short_label, WilcoxonRow};
use crate::output::{CsvTable, StageTimings};
use crate::sweep::SweepPlan;
use anyhow::{bail, Context, Result};
use std::fmt::Write as _;
use std::path::Path;

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
        "ME all %",
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
            pm(values.stats(c, metric_index("me")), 2),
            pm(values.stats(c, metric_index("me_all")), 2),
            pm(values.stats(c, metric_index("fnr")), 2),
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
    for combo in &plan.combinations {
        if let Some(note) = values.focal_verdicts[combo.index].note() {
            let _ = writeln!(out, "{}: {note}", short_label(plan, combo.index));
        }
    }
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
