//! Fig. 10: ME against the number of sampled hypotheses M.

use super::canvas::DrawResult;
use super::*;
use crate::report::{RunValues, SUMMARY_METRICS};
use crate::sweep::SweepPlan;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

/// One line of [`me_vs_samples`]: its legend entry and, per number of
/// sampled hypotheses M, the mean ME and the half-width of its band, in
/// percent: `(M, mean, std)` (the std over scenes, or across seeds; the
/// label says which).
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// The legend entry (e.g. `semical (mean ± std over scenes)`).
    pub label: String,
    /// `(M, mean ME %, std ME %)`, in any order.
    pub points: Vec<(usize, f64, f64)>,
}

struct MeVsSamples {
    series: Vec<Series>,
}

impl Figure for MeVsSamples {
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        _: PlotFormat,
    ) -> DrawResult<DB> {
        let title = "ME against the number of sampled hypotheses M";
        let points = || self.series.iter().flat_map(|s| s.points.iter());
        let (Some(m_range), Some(y_range)) = (
            finite_range(points().map(|p| p.0 as f64)),
            finite_range(points().map(|p| p.1 + p.2.abs())),
        ) else {
            return draw_no_data(root, title, "no data");
        };
        root.fill(&WHITE)?;
        let (m_lo, m_hi) = padded(m_range, 0.04);
        let y_hi = (y_range.1 * 1.1).max(1.0);
        let mut chart = chart_builder(root, title, 64).build_cartesian_2d(m_lo..m_hi, 0.0..y_hi)?;
        chart
            .configure_mesh()
            .x_desc("M (sampled hypotheses)")
            .y_desc("ME (%)")
            .axis_desc_style((FONT, 18))
            .label_style((FONT, 14))
            .x_label_formatter(&|m| format!("{m:.0}"))
            .draw()?;
        for (k, series) in self.series.iter().enumerate() {
            if series.points.is_empty() {
                continue;
            }
            let colour = cluster_colour(k);
            let points = &series.points;
            // The ±std band, clamped at 0 (ME is not negative).
            let mut band: Vec<(f64, f64)> = points
                .iter()
                .map(|&(m, mean, std)| (m as f64, mean + std.abs()))
                .collect();
            band.extend(
                points
                    .iter()
                    .rev()
                    .map(|&(m, mean, std)| (m as f64, (mean - std.abs()).max(0.0))),
            );
            chart.draw_series(std::iter::once(Polygon::new(band, colour.mix(0.18))))?;
            let line: Vec<(f64, f64)> = points
                .iter()
                .map(|&(m, mean, _)| (m as f64, mean))
                .collect();
            chart
                .draw_series(LineSeries::new(line.clone(), colour.stroke_width(2)))?
                .label(series.label.clone())
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 24, y)], colour.stroke_width(2))
                });
            chart.draw_series(line.into_iter().map(|p| Circle::new(p, 4, colour.filled())))?;
        }
        draw_legend(&mut chart, SeriesLabelPosition::UpperRight)
    }
}

/// ME (%) against the number of sampled hypotheses M, one line per method
/// with its ±std band (clamped at 0) — the thesis's Fig. 10.
///
/// Points whose M, mean or std is not drawable (see [`MAX_MAGNITUDE`]) are
/// left out; each series is drawn
/// in order of increasing M.
pub fn me_vs_samples(series: &[Series], path: impl AsRef<Path>) -> Result<(), PlotError> {
    let series = series
        .iter()
        .map(|s| {
            let mut points: Vec<(usize, f64, f64)> = s
                .points
                .iter()
                .copied()
                .filter(|p| drawable(p.0 as f64) && drawable(p.1) && drawable(p.2))
                .collect();
            points.sort_by_key(|p| p.0);
            Series {
                label: s.label.clone(),
                points,
            }
        })
        .collect();
    render(&MeVsSamples { series }, path.as_ref())
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
        let key = plan.params_of(combo.index, &["num_samples", "seed"]);
        let m = combo.pipeline.params.sampling.num_samples;
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

/// The examples once in the documentation of this module's items.
#[cfg(test)]
mod examples {
    #[test]
    fn me_vs_samples_series_example() {
        let plan = crate::sweep::plan_of_sweep(
            "method = [\"baseline\", \"semical\"]\nnum_samples = [100, 200]\n",
        );
        let table = crate::output::CsvTable::parse(
            &format!(
                "{}\n",
                crate::output::per_scene_header(&plan.columns).join(",")
            ),
            "p.csv".as_ref(),
        )
        .unwrap();
        let values = crate::report::RunValues::collect(&plan, &table, "p.csv".as_ref()).unwrap();
        // No rows: nothing to draw, but num_samples is swept.
        assert_eq!(
            crate::plots::me_vs_samples_series(&plan, &values),
            Some(vec![])
        );
    }
}
