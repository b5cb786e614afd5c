//! Summary statistics of a run: the per-scene values of `per_scene.csv` by
//! combination ([`RunValues`]) and their mean ± std ([`MeanStd`]).

use crate::output::{CsvTable, SceneResult};
use crate::sweep::SweepPlan;
use anyhow::{Context, Result};
use std::path::Path;

/// The metrics summarised per combination, in column order.
pub const SUMMARY_METRICS: [&str; 8] = ["me", "me_all", "acc", "fnr", "pur", "ari", "nmi", "frob"];

/// The metrics tested with Wilcoxon (errors: lower is better).
pub const TESTED_METRICS: [&str; 3] = ["me", "me_all", "fnr"];

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
    matches!(metric, "me" | "me_all" | "fnr" | "frob")
}

/// Mean and population standard deviation (ddof 0) of a sample.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeanStd {
    /// Arithmetic mean.
    pub mean: f64,
    /// Standard deviation with ddof 0 (docs/method.md "Metrics").
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
    /// For each combination: the scenes it has results for, in row order
    /// (the failed ones are in `failed`).
    pub scenes: Vec<Vec<String>>,
    /// For each combination: the scenes that failed ([`SceneResult::failure`]),
    /// with the reason, in row order; left out of every mean.
    pub failed: Vec<Vec<(String, String)>>,
    /// For each combination and each of [`SUMMARY_METRICS`]: (scene, value).
    pub metrics: Vec<Vec<Vec<(String, f64)>>>,
    /// For each combination: generated hypotheses per scene.
    pub generated: Vec<Vec<f64>>,
    /// For each combination: kept hypotheses per scene.
    pub kept: Vec<Vec<f64>>,
    /// For each combination: `f_peak_error` (`|f_peak − f_true| / f_true`)
    /// of every scene where both are known.
    pub focal_errors: Vec<Vec<f64>>,
    /// For each combination: scenes whose focal consensus was judged
    /// (`focal_verdict` not empty) and, of those, the ones not plausible
    /// (`implausible`, or `none`: no consensus).
    pub focal_verdicts: Vec<FocalVerdictCounts>,
}

/// How many scenes of a combination had a focal consensus judged, and how
/// many of them were implausible or had none.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct FocalVerdictCounts {
    /// Scenes with a focal stage (`focal_verdict` not empty).
    pub judged: usize,
    /// f_peak outside 0.3–3 × the focal prior.
    pub implausible: usize,
    /// No hypothesis passed the local test.
    pub none: usize,
}

impl FocalVerdictCounts {
    /// The one-line note for a combination whose consensus was not plausible
    /// on some scene; None when it was on all (or none was judged).
    pub fn note(&self) -> Option<String> {
        if self.implausible + self.none == 0 {
            return None;
        }
        let mut parts = Vec::new();
        if self.implausible > 0 {
            parts.push(format!(
                "implausible (f_peak outside 0.3-3 x the focal prior) on {} of {} scenes",
                self.implausible, self.judged
            ));
        }
        if self.none > 0 {
            parts.push(format!("absent on {} of {} scenes", self.none, self.judged));
        }
        Some(format!("focal consensus {}", parts.join(", ")))
    }
}

/// The index of summary metric `name` in [`SUMMARY_METRICS`].
pub fn metric_index(name: &str) -> usize {
    SUMMARY_METRICS
        .iter()
        .position(|m| *m == name)
        .unwrap_or_else(|| unreachable!("`{name}` is not a summary metric"))
}

/// The value of summary metric `name` (one of [`SUMMARY_METRICS`]) in a row.
fn metric(row: &SceneResult, name: &str) -> Option<f64> {
    match name {
        "me" => row.me,
        "me_all" => row.me_all,
        "acc" => row.acc,
        "fnr" => row.fnr,
        "pur" => row.pur,
        "ari" => row.ari,
        "nmi" => row.nmi,
        "frob" => row.frob,
        other => unreachable!("`{other}` is not a summary metric"),
    }
}

impl RunValues {
    /// Collects the values of `table` (a `per_scene.csv`, read from `file`)
    /// by combination, each row read as a [`SceneResult`].
    pub fn collect(plan: &SweepPlan, table: &CsvTable, file: &Path) -> Result<Self> {
        let k = plan.columns.len();
        let c = plan.combinations.len();
        let mut out = Self {
            scenes: vec![Vec::new(); c],
            failed: vec![Vec::new(); c],
            metrics: vec![vec![Vec::new(); SUMMARY_METRICS.len()]; c],
            generated: vec![Vec::new(); c],
            kept: vec![Vec::new(); c],
            focal_errors: vec![Vec::new(); c],
            focal_verdicts: vec![FocalVerdictCounts::default(); c],
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
            let result = SceneResult::from_cells(&table.header[k..], &row[k..], file, r + 2)?;
            if let Some(reason) = result.failure() {
                out.failed[combo].push((result.scene.clone(), reason.to_string()));
                continue;
            }
            for (m, name) in SUMMARY_METRICS.iter().enumerate() {
                if let Some(v) = metric(&result, name) {
                    out.metrics[combo][m].push((result.scene.clone(), v));
                }
            }
            out.generated[combo].push(result.hypotheses_generated as f64);
            out.kept[combo].push(result.hypotheses_kept as f64);
            if let Some(e) = result.f_peak_error {
                out.focal_errors[combo].push(e);
            }
            let verdicts = &mut out.focal_verdicts[combo];
            verdicts.judged += usize::from(!result.focal_verdict.is_empty());
            verdicts.implausible += usize::from(result.focal_verdict == "implausible");
            verdicts.none += usize::from(result.focal_verdict == "none");
            out.scenes[combo].push(result.scene);
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

pub(super) fn mean(values: &[f64]) -> Option<f64> {
    MeanStd::of(values).map(|s| s.mean)
}
