//! `report.md`: the metrics table (thesis Tables 2 and 4), the Wilcoxon
//! tests (Table 3) and ME per scene.

use super::stats::{mean, MeanStd, RunValues, SUMMARY_METRICS};
use super::tables::{cell, short_label, WilcoxonRow};
use crate::sweep::SweepPlan;
use std::fmt::Write as _;

pub(super) fn pm(s: Option<MeanStd>, decimals: usize) -> String {
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
    write_intro(&mut md, ctx, plan);
    write_metrics(&mut md, plan, values);
    write_wilcoxon(&mut md, plan, tests);
    write_me_per_scene(&mut md, ctx, plan, values);
    write_failures(&mut md, plan, values);
    md
}

/// The scenes that could not be segmented, per combination, with why
/// (they are left out of every mean above).
fn write_failures(md: &mut String, plan: &SweepPlan, values: &RunValues) {
    let total: usize = values.failed.iter().map(Vec::len).sum();
    if total == 0 {
        return;
    }
    let _ = writeln!(
        md,
        "## Failed scenes\n\n{total} (scene, combination) unit(s) could not be segmented; \
         they are left out of every mean and test above.\n"
    );
    for combo in &plan.combinations {
        for (scene, reason) in &values.failed[combo.index] {
            let _ = writeln!(md, "- `{scene}` ({}): {reason}", plan.label(combo.index));
        }
    }
    md.push('\n');
}

/// The title, the description and what the run covers.
fn write_intro(md: &mut String, ctx: &ReportContext, plan: &SweepPlan) {
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
}

/// The metrics table: mean ± std of each summary metric per combination.
fn write_metrics(md: &mut String, plan: &SweepPlan, values: &RunValues) {
    let _ = writeln!(md, "## Metrics (mean ± std over scenes)\n");
    let _ = writeln!(
        md,
        "ME, ME_ALL, ACC, FNR, PUR, ARI and NMI in percent, FROB (Eq. 45) as a distance; std with ddof 0. \
         ME is the thesis's (ground-truth outliers excluded, a predicted outlier wrong), ME_ALL the \
         multi-model fitting literature's (all points, outliers a class of their own).\n"
    );
    let mut header: Vec<String> = plan.columns.clone();
    header.push("scenes".into());
    header.extend(SUMMARY_METRICS.iter().map(|m| m.to_uppercase()));
    header.push("kept / generated".into());
    table_header(md, &header);
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
        table_row(md, &cells);
    }
    let notes: Vec<String> = plan
        .combinations
        .iter()
        .filter_map(|combo| {
            let note = values.focal_verdicts[combo.index].note()?;
            Some(format!("- {}: {note}.", combo.values.join(", ")))
        })
        .collect();
    if !notes.is_empty() {
        let _ = writeln!(md, "\n{}", notes.join("\n"));
    }
}

/// The Wilcoxon tests of each combination against its reference.
fn write_wilcoxon(md: &mut String, plan: &SweepPlan, tests: &[WilcoxonRow]) {
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
            md,
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
                md,
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
}

/// ME (%) of every scene under every combination.
fn write_me_per_scene(md: &mut String, ctx: &ReportContext, plan: &SweepPlan, values: &RunValues) {
    let _ = writeln!(md, "\n## ME per scene (%)\n");
    let me = 0;
    let mut header = vec!["scene".to_string()];
    header.extend((0..plan.combinations.len()).map(|c| short_label(plan, c)));
    table_header(md, &header);
    for scene in ctx.scenes {
        let mut cells = vec![scene.clone()];
        for c in 0..plan.combinations.len() {
            let v = values.metrics[c][me].iter().find(|(s, _)| s == scene);
            cells.push(
                v.map(|(_, v)| format!("{:.2}", v * 100.0))
                    .unwrap_or_else(|| "–".into()),
            );
        }
        table_row(md, &cells);
    }
}

fn table_header(md: &mut String, cells: &[String]) {
    table_row(md, cells);
    let _ = writeln!(md, "|{}", "---|".repeat(cells.len()));
}

fn table_row(md: &mut String, cells: &[String]) {
    let escaped: Vec<String> = cells.iter().map(|c| c.replace('|', "\\|")).collect();
    let _ = writeln!(md, "| {} |", escaped.join(" | "));
}
