//! Fig. 8: the KDE of the focal estimates of one scene.

use super::canvas::DrawResult;
use super::*;
use focal::FocalConsensus;
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

/// The data of [`focal_kde`] (thesis Fig. 8).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FocalKdePlot<'a> {
    /// The `f_avg` estimates that fed the KDE (px).
    pub values: &'a [f64],
    /// KDE grid (px), as [`FocalConsensus::grid`].
    pub grid: &'a [f64],
    /// KDE density at each grid point, as [`FocalConsensus::density`].
    pub density: &'a [f64],
    /// The consensus focal f_peak (Eq. 37).
    pub f_peak: Option<f64>,
    /// The band kept around f_peak, `(lo, hi)` in px (see [`tau_band`]).
    pub band: Option<(f64, f64)>,
    /// The ground-truth focal length, when known.
    pub true_focal: Option<f64>,
    /// The figure title (e.g. the scene name).
    pub title: &'a str,
}

impl<'a> FocalKdePlot<'a> {
    /// The plot of a pipeline's consensus: its grid, density and f_peak,
    /// and the band `f_peak · (1 ± tau_range)`.
    pub fn from_consensus(
        values: &'a [f64],
        consensus: &'a FocalConsensus,
        tau_range: f64,
        true_focal: Option<f64>,
        title: &'a str,
    ) -> Self {
        Self {
            values,
            grid: &consensus.grid,
            density: &consensus.density,
            f_peak: Some(consensus.f_peak),
            band: Some(tau_band(consensus.f_peak, tau_range)),
            true_focal,
            title,
        }
    }
}

/// The focal band of Eq. 37: the `f` with `|f − f_peak| / f_peak ≤ τ_range`,
/// i.e. `[f_peak (1 − τ_range), f_peak (1 + τ_range)]` for `f_peak > 0`.
pub fn tau_band(f_peak: f64, tau_range: f64) -> (f64, f64) {
    let half = (f_peak * tau_range).abs();
    (f_peak - half, f_peak + half)
}

struct FocalKde<'a> {
    plot: FocalKdePlot<'a>,
}

impl Figure for FocalKde<'_> {
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        _: PlotFormat,
    ) -> DrawResult<DB> {
        let title = self.plot.title;
        let data = KdeData::of(&self.plot);
        if data.values.is_empty() && data.curve.is_empty() {
            return draw_no_data(root, title, "no focal estimates");
        }
        let Some((x_lo, x_hi)) = data.x_range() else {
            return draw_no_data(root, title, "no focal estimates");
        };
        let histogram = Histogram::of(&data.values, (x_lo, x_hi));
        let kde_max = data.curve.iter().map(|c| c.1).fold(0.0, f64::max);
        let y_hi = histogram.max_density().max(kde_max) * 1.12;
        let y_hi = if y_hi > 0.0 { y_hi } else { 1.0 };

        root.fill(&WHITE)?;
        let mut chart = chart_builder(root, title, 80).build_cartesian_2d(x_lo..x_hi, 0.0..y_hi)?;
        chart
            .configure_mesh()
            .x_desc("focal length f_avg (px)")
            .y_desc("density")
            .axis_desc_style((FONT, 18))
            .label_style((FONT, 14))
            .x_label_formatter(&|x| format!("{x:.0}"))
            .y_label_formatter(&|y| format!("{y:.1e}"))
            .draw()?;
        if let Some((lo, hi)) = data.band {
            chart
                .draw_series(std::iter::once(Rectangle::new(
                    [(lo, 0.0), (hi, y_hi)],
                    BAND_COLOUR.mix(0.15).filled(),
                )))?
                .label(format!("τ_range band [{lo:.0}, {hi:.0}]"))
                .legend(|(x, y)| {
                    Rectangle::new([(x, y - 6), (x + 24, y + 6)], BAND_COLOUR.mix(0.3).filled())
                });
        }
        draw_histogram(&mut chart, &histogram, data.values.len())?;
        if data.values.len() <= 500 {
            let tick = y_hi * 0.025;
            chart.draw_series(data.values.iter().filter(|&&v| v >= x_lo && v <= x_hi).map(
                |&v| PathElement::new(vec![(v, 0.0), (v, tick)], BLACK.mix(0.6).stroke_width(1)),
            ))?;
        }
        if !data.curve.is_empty() {
            chart
                .draw_series(LineSeries::new(data.curve, KDE_COLOUR.stroke_width(2)))?
                .label("Gaussian KDE")
                .legend(|(x, y)| {
                    PathElement::new(vec![(x, y), (x + 24, y)], KDE_COLOUR.stroke_width(2))
                });
        }
        draw_focal_lines(&mut chart, data.f_peak, data.true_focal, y_hi)?;
        draw_legend(&mut chart, SeriesLabelPosition::UpperRight)
    }
}

/// The drawable part of a [`FocalKdePlot`]: values and markers that are
/// finite and within [`MAX_MAGNITUDE`].
struct KdeData {
    f_peak: Option<f64>,
    true_focal: Option<f64>,
    band: Option<(f64, f64)>,
    values: Vec<f64>,
    curve: Vec<(f64, f64)>,
}

impl KdeData {
    fn of(p: &FocalKdePlot<'_>) -> Self {
        let finite = |v: &Option<f64>| v.filter(|&x| drawable(x));
        Self {
            f_peak: finite(&p.f_peak),
            true_focal: finite(&p.true_focal),
            band: p.band.filter(|b| drawable(b.0) && drawable(b.1)),
            values: p.values.iter().copied().filter(|&v| drawable(v)).collect(),
            curve: p
                .grid
                .iter()
                .zip(p.density)
                .map(|(&x, &d)| (x, d))
                .filter(|&(x, d)| drawable(x) && drawable(d))
                .collect(),
        }
    }

    /// The horizontal axis: the KDE grid (1st–99th percentile of the
    /// values) and every marker; without a grid, all the values. Padded.
    fn x_range(&self) -> Option<(f64, f64)> {
        let markers = self
            .f_peak
            .into_iter()
            .chain(self.true_focal)
            .chain(self.band.into_iter().flat_map(|b| [b.0, b.1]));
        let base = if self.curve.is_empty() {
            finite_range(self.values.iter().copied())
        } else {
            finite_range(self.curve.iter().map(|c| c.0))
        };
        let range = finite_range(base.into_iter().flat_map(|b| [b.0, b.1]).chain(markers))?;
        Some(padded(range, 0.03))
    }
}

/// Bins of the histogram of [`focal_kde`].
const BINS: usize = 60;

/// The histogram of the values over the axis, normalised as a density over
/// all values so that it shares the axis with the KDE.
struct Histogram {
    x_lo: f64,
    bin_width: f64,
    counts: [usize; BINS],
    /// Values outside the axis.
    off_axis: usize,
    /// From a count to a density.
    scale: f64,
}

impl Histogram {
    fn of(values: &[f64], (x_lo, x_hi): (f64, f64)) -> Self {
        let bin_width = (x_hi - x_lo) / BINS as f64;
        let mut counts = [0usize; BINS];
        let mut off_axis = 0;
        for &v in values {
            let bin = ((v - x_lo) / bin_width).floor();
            if bin >= 0.0 && bin < BINS as f64 {
                counts[bin as usize] += 1;
            } else {
                off_axis += 1;
            }
        }
        let scale = 1.0 / (values.len().max(1) as f64 * bin_width);
        Self {
            x_lo,
            bin_width,
            counts,
            off_axis,
            scale,
        }
    }

    fn max_density(&self) -> f64 {
        self.counts.iter().max().copied().unwrap_or(0) as f64 * self.scale
    }
}

type KdeChart<'a, DB> = ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// The histogram bars, with the number of values (and of those off the
/// axis) in the legend.
fn draw_histogram<DB: DrawingBackend>(
    chart: &mut KdeChart<'_, DB>,
    h: &Histogram,
    n_values: usize,
) -> DrawResult<DB> {
    let mut off_axis_note = String::new();
    if h.off_axis > 0 {
        off_axis_note = format!(", {} off the axis", h.off_axis);
    }
    chart
        .draw_series(
            h.counts
                .iter()
                .enumerate()
                .filter(|(_, &c)| c > 0)
                .map(|(i, &c)| {
                    let x0 = h.x_lo + i as f64 * h.bin_width;
                    Rectangle::new(
                        [(x0, 0.0), (x0 + h.bin_width, c as f64 * h.scale)],
                        HISTOGRAM_COLOUR.filled(),
                    )
                }),
        )?
        .label(format!("f_avg estimates (n = {n_values}{off_axis_note})"))
        .legend(|(x, y)| Rectangle::new([(x, y - 6), (x + 24, y + 6)], HISTOGRAM_COLOUR.filled()));
    Ok(())
}

/// The f_peak line and the dashed true-focal line, when known.
fn draw_focal_lines<DB: DrawingBackend>(
    chart: &mut KdeChart<'_, DB>,
    f_peak: Option<f64>,
    true_focal: Option<f64>,
    y_hi: f64,
) -> DrawResult<DB> {
    if let Some(f) = f_peak {
        chart
            .draw_series(std::iter::once(PathElement::new(
                vec![(f, 0.0), (f, y_hi)],
                PEAK_COLOUR.stroke_width(2),
            )))?
            .label(format!("f_peak = {f:.1}"))
            .legend(|(x, y)| {
                PathElement::new(vec![(x, y), (x + 24, y)], PEAK_COLOUR.stroke_width(2))
            });
    }
    if let Some(f) = true_focal {
        chart
            .draw_series(DashedLineSeries::new(
                vec![(f, 0.0), (f, y_hi)],
                8,
                5,
                TRUE_FOCAL_COLOUR.stroke_width(2),
            ))?
            .label(format!("true focal = {f:.1}"))
            .legend(|(x, y)| {
                PathElement::new(vec![(x, y), (x + 24, y)], TRUE_FOCAL_COLOUR.stroke_width(2))
            });
    }
    Ok(())
}

/// The focal estimates of one scene — the thesis's Fig. 8: a histogram of
/// the `f_avg` values (normalised as a density), a rug of them when there
/// are at most 500, the Gaussian KDE curve (Eq. 37), the f_peak line, the
/// τ_range band shaded and the true focal as a dashed line.
///
/// The horizontal axis spans the KDE grid (the 1st–99th percentiles of the
/// values) and every marker; the legend counts the values off the axis.
/// `grid` and `density` must have the same length.
pub fn focal_kde(plot: &FocalKdePlot<'_>, path: impl AsRef<Path>) -> Result<(), PlotError> {
    let path = path.as_ref();
    if plot.grid.len() != plot.density.len() {
        return Err(invalid(
            path,
            format!(
                "`grid` has {} points but `density` has {}",
                plot.grid.len(),
                plot.density.len()
            ),
        ));
    }
    render(&FocalKde { plot: *plot }, path)
}

/// The examples once in the documentation of this module's items.
#[cfg(test)]
mod examples {
    #[test]
    fn tau_band_example() {
        assert_eq!(super::tau_band(1000.0, 0.25), (750.0, 1250.0));
    }
}
