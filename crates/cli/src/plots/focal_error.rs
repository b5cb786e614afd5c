//! Fig. 9: the relative focal error over the scenes of a run.

use super::canvas::DrawResult;
use super::*;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

struct FocalErrorHistogram {
    errors: Vec<f64>,
    tau_range: f64,
}

impl Figure for FocalErrorHistogram {
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        _: PlotFormat,
    ) -> DrawResult<DB> {
        let title = "Relative error of f_peak over scenes";
        if self.errors.is_empty() {
            return draw_no_data(root, title, "no scene with a known focal length");
        }
        let tau = self.tau_range;
        let max_error = self.errors.iter().copied().fold(0.0, f64::max);
        let x_hi = max_error.max(tau) * 1.1;
        // Bins of τ/5 so that the band ends on a bin edge, unless that makes
        // more than 100 bins.
        let mut bin_width = tau / 5.0;
        if x_hi / bin_width > 100.0 {
            bin_width = x_hi / 100.0;
        }
        let bins = ((x_hi / bin_width).ceil() as usize).max(1);
        let mut counts = vec![0u32; bins];
        for &e in &self.errors {
            let bin = ((e / bin_width).floor() as usize).min(bins - 1);
            counts[bin] += 1;
        }
        let within = self.errors.iter().filter(|&&e| e <= tau).count();
        let y_hi = counts.iter().max().copied().unwrap_or(0) + 1;
        let y_hi = y_hi + y_hi.div_ceil(5);

        root.fill(&WHITE)?;
        let mut chart = chart_builder(root, title, 64).build_cartesian_2d(0.0..x_hi, 0u32..y_hi)?;
        chart
            .configure_mesh()
            .x_desc("|f_peak − f_true| / f_true")
            .y_desc("scenes")
            .axis_desc_style((FONT, 18))
            .label_style((FONT, 14))
            .draw()?;
        chart
            .draw_series(std::iter::once(Rectangle::new(
                [(0.0, 0), (tau, y_hi)],
                TRUE_FOCAL_COLOUR.mix(0.15).filled(),
            )))?
            .label(format!(
                "within τ_range = {tau}: {within} of {} scenes",
                self.errors.len()
            ))
            .legend(|(x, y)| {
                Rectangle::new(
                    [(x, y - 6), (x + 24, y + 6)],
                    TRUE_FOCAL_COLOUR.mix(0.3).filled(),
                )
            });
        chart.draw_series(
            counts
                .iter()
                .enumerate()
                .filter(|(_, &c)| c > 0)
                .map(|(i, &c)| {
                    let x0 = i as f64 * bin_width;
                    Rectangle::new([(x0, 0), (x0 + bin_width, c)], KDE_COLOUR.mix(0.8).filled())
                }),
        )?;
        chart.draw_series(DashedLineSeries::new(
            vec![(tau, 0), (tau, y_hi)],
            8,
            5,
            TRUE_FOCAL_COLOUR.stroke_width(2),
        ))?;
        draw_legend(&mut chart, SeriesLabelPosition::UpperRight)
    }
}

/// Histogram over scenes of the relative focal error
/// `|f_peak − f_true| / f_true` (absolute values of `rel_errors` are taken;
/// undrawable ones are left out, see [`MAX_MAGNITUDE`]), with the band `[0, τ_range]` shaded, its
/// edge dashed and the share of scenes inside it in the legend — the
/// thesis's Fig. 9. `tau_range` must be positive and at most
/// [`MAX_MAGNITUDE`].
pub fn focal_error_histogram(
    rel_errors: &[f64],
    tau_range: f64,
    path: impl AsRef<Path>,
) -> Result<(), PlotError> {
    let path = path.as_ref();
    if !(drawable(tau_range) && tau_range > 0.0) {
        return Err(invalid(
            path,
            format!(
                "`tau_range` must be a positive number up to {MAX_MAGNITUDE:e}, got {tau_range}"
            ),
        ));
    }
    let errors = rel_errors
        .iter()
        .copied()
        .filter(|&e| drawable(e))
        .map(f64::abs)
        .collect();
    render(&FocalErrorHistogram { errors, tau_range }, path)
}
