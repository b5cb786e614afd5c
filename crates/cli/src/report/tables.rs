//! The CSV tables of a run: `summary.csv` and the Wilcoxon tests of
//! `wilcoxon.csv`.

use super::stats::{mean, RunValues, SUMMARY_METRICS, TESTED_METRICS};
use crate::output::CsvTable;
use crate::sweep::SweepPlan;
use crate::wilcoxon::{wilcoxon, Alternative, Mode, WilcoxonError};

pub(super) fn cell(v: Option<f64>, decimals: usize) -> String {
    v.map(|x| format!("{x:.decimals$}")).unwrap_or_default()
}

/// `summary.csv`: per combination, the parameter columns, `scenes`, then
/// `<metric>_mean, <metric>_std` for ME, ME_ALL, ACC, FNR, PUR, ARI, NMI (percent, 4
/// decimals) and FROB (as is, 6 decimals), `frob_scenes` (scenes where FROB
/// is defined), the mean hypothesis counts `hypotheses_generated_mean`,
/// `hypotheses_kept_mean` (2 decimals), and the scenes whose focal
/// consensus was judged, implausible and absent (`focal_judged_scenes`,
/// `focal_implausible_scenes`, `focal_none_scenes`).
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
            "focal_judged_scenes",
            "focal_implausible_scenes",
            "focal_none_scenes",
            "failed_scenes",
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
        let verdicts = values.focal_verdicts[c];
        row.extend(
            [
                verdicts.judged,
                verdicts.implausible,
                verdicts.none,
                values.failed[c].len(),
            ]
            .map(|v| v.to_string()),
        );
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
