//! ME per scene, the baseline against semical.

use super::canvas::DrawResult;
use super::*;
use crate::config::Method;
use crate::report::{summary_scale, RunValues, SUMMARY_METRICS};
use crate::sweep::SweepPlan;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::path::Path;

/// ME of one scene under the uncalibrated baseline and under semical, in
/// percent.
#[derive(Debug, Clone, PartialEq)]
pub struct ScenePair {
    /// Scene name.
    pub scene: String,
    /// ME of the baseline (%).
    pub baseline_me: f64,
    /// ME of the semi-calibrated method (%).
    pub method_me: f64,
}

/// Membership of a group of [`ScenePair`]s in the scatter.
type ScenePredicate = fn(&ScenePair) -> bool;

struct MeScatter {
    pairs: Vec<ScenePair>,
}

impl Figure for MeScatter {
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        _: PlotFormat,
    ) -> DrawResult<DB> {
        let title = "ME per scene: baseline against semical";
        if self.pairs.is_empty() {
            return draw_no_data(root, title, "no data");
        }
        let top = self
            .pairs
            .iter()
            .map(|p| p.baseline_me.max(p.method_me))
            .fold(0.0, f64::max);
        let hi = (top * 1.08).max(1.0);

        root.fill(&WHITE)?;
        let (width, height) = root.dim_in_pixel();
        // A square plotting area: pad the sides.
        let side_pad = width.saturating_sub(height) as i32 / 2;
        let area = root.margin(0, 0, side_pad, side_pad);
        let mut chart = chart_builder(&area, title, 64).build_cartesian_2d(0.0..hi, 0.0..hi)?;
        chart
            .configure_mesh()
            .x_desc("baseline ME (%)")
            .y_desc("semical ME (%)")
            .axis_desc_style((FONT, 18))
            .label_style((FONT, 14))
            .draw()?;
        chart.draw_series(DashedLineSeries::new(
            vec![(0.0, 0.0), (hi, hi)],
            8,
            5,
            BLACK.mix(0.5).stroke_width(1),
        ))?;
        let groups: [(&str, RGBColor, ScenePredicate); 3] = [
            ("semical better", KDE_COLOUR, |p| {
                p.method_me < p.baseline_me
            }),
            ("semical worse", PEAK_COLOUR, |p| {
                p.method_me > p.baseline_me
            }),
            ("tied", OUTLIER_COLOUR, |p| p.method_me == p.baseline_me),
        ];
        for (name, colour, member) in groups {
            let count = self.pairs.iter().filter(|p| member(p)).count();
            chart
                .draw_series(
                    self.pairs
                        .iter()
                        .filter(|p| member(p))
                        .map(|p| Circle::new((p.baseline_me, p.method_me), 5, colour.filled())),
                )?
                .label(format!("{name}: {count}"))
                .legend(move |(x, y)| Circle::new((x + 12, y), 5, colour.filled()));
        }
        if self.pairs.len() <= 30 {
            chart.draw_series(self.pairs.iter().map(|p| {
                EmptyElement::at((p.baseline_me, p.method_me))
                    + Text::new(
                        p.scene.clone(),
                        (7, -4),
                        text_style(12, BLACK).pos(Pos::new(HPos::Left, VPos::Bottom)),
                    )
            }))?;
        }
        draw_legend(&mut chart, SeriesLabelPosition::UpperLeft)
    }
}

/// ME per scene, the uncalibrated baseline on the horizontal axis against
/// semical on the vertical, with the diagonal: points below it are scenes
/// where semical segments better (the per-scene view behind the Wilcoxon
/// test of Section 7.4.2 and Tables 2–3). Scene names are written next to
/// the points when there are at most 30; pairs with an undrawable ME are left
/// out.
pub fn me_scatter(pairs: &[ScenePair], path: impl AsRef<Path>) -> Result<(), PlotError> {
    let pairs = pairs
        .iter()
        .filter(|p| drawable(p.baseline_me) && drawable(p.method_me))
        .cloned()
        .collect();
    render(&MeScatter { pairs }, path.as_ref())
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
    if plan.combinations[combination].pipeline.params.focal.method != Method::Semical {
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
