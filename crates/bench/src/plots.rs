//! The figures of an experiment run (method.md, "Published numbers"; the
//! thesis's Figs. 8–12), drawn with plotters.
//!
//! Every function takes plain data and an output path and writes a PNG or an
//! SVG according to the path's extension (`.png` / `.svg`, any case). Empty
//! or entirely undrawable input draws the frame of the figure with a
//! "no data" note instead of failing; malformed input (slices of different
//! lengths, images of the wrong size, a non-positive τ_range) is a
//! [`PlotError`] naming the output file, and so is a failure to draw or to
//! write. Values that are not finite or exceed [`MAX_MAGNITUDE`] in
//! magnitude are left out of the figures.
//!
//! Text is rendered by plotters' TrueType path (font-kit over fontconfig)
//! for PNG output, which needs a system font for the family `sans-serif`
//! (Debian: `fonts-dejavu-core`); SVG output names the font family and lets
//! the viewer render it.
//!
//! ```
//! use bench::plots::{me_vs_samples, Series};
//! let dir = tempfile::tempdir().unwrap();
//! let series = [
//!     Series { label: "baseline".into(), points: vec![(500, 16.0, 12.0), (3000, 15.6, 12.2)] },
//!     Series { label: "semical".into(), points: vec![(500, 13.0, 12.5), (3000, 10.5, 12.4)] },
//! ];
//! let path = dir.path().join("me_vs_m.svg");
//! me_vs_samples(&series, &path).unwrap();
//! let svg = std::fs::read_to_string(&path).unwrap();
//! assert!(svg.starts_with("<svg") && svg.contains("ME (%)"));
//! ```

use focal::FocalConsensus;
use image::codecs::png::PngEncoder;
use image::{ImageEncoder, ImageFormat, RgbImage};
use plotters::coord::Shift;
use plotters::element::BitMapElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::path::{Path, PathBuf};
use thiserror::Error;

/// Pixel size of the chart figures (Figs. 8, 9, 10 and the ME scatter).
pub const CHART_SIZE: (u32, u32) = (960, 640);

/// Colour of outliers (label −1) in [`clusters_over_images`].
pub const OUTLIER_COLOUR: RGBColor = RGBColor(128, 128, 128);

/// The first cluster colours: the Tableau-10 palette without its grey.
const BASE_PALETTE: [RGBColor; 9] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];

const KDE_COLOUR: RGBColor = RGBColor(31, 119, 180);
const HISTOGRAM_COLOUR: RGBColor = RGBColor(158, 188, 218);
/// Colour of the f_peak line in [`focal_kde`] (used for nothing else there).
pub const PEAK_COLOUR: RGBColor = RGBColor(214, 39, 40);
const BAND_COLOUR: RGBColor = RGBColor(255, 127, 14);
/// Colour of the true-focal line in [`focal_kde`] (used for nothing else
/// there).
pub const TRUE_FOCAL_COLOUR: RGBColor = RGBColor(44, 160, 44);
const BLANK_PANEL_COLOUR: RGBColor = RGBColor(236, 236, 236);
const FONT: &str = "sans-serif";

/// Why a figure could not be written. Every variant names the output file.
#[derive(Debug, Error)]
pub enum PlotError {
    /// The file name ends neither in `.png` nor in `.svg`.
    #[error("{}: unsupported plot format: the file name must end in .png or .svg", path.display())]
    UnsupportedFormat {
        /// The output path.
        path: PathBuf,
    },
    /// The data cannot be drawn as given.
    #[error("{}: invalid plot input: {message}", path.display())]
    InvalidInput {
        /// The output path.
        path: PathBuf,
        /// What is wrong, naming the argument.
        message: String,
    },
    /// plotters failed (for PNG output, typically: no system font found).
    #[error("{}: drawing failed: {message}", path.display())]
    Drawing {
        /// The output path.
        path: PathBuf,
        /// plotters' error.
        message: String,
    },
    /// The SVG file could not be written.
    #[error("{}: cannot write the SVG file: {source}", path.display())]
    Write {
        /// The output path.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The PNG could not be encoded or written.
    #[error("{}: cannot write the PNG file: {source}", path.display())]
    Png {
        /// The output path.
        path: PathBuf,
        /// The encoder's error.
        source: image::ImageError,
    },
}

/// The output format, chosen by the file name's extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PlotFormat {
    /// A raster image (`.png`).
    Png,
    /// A vector image (`.svg`).
    Svg,
}

impl PlotFormat {
    /// `.png` → [`PlotFormat::Png`], `.svg` → [`PlotFormat::Svg`] (any
    /// case); anything else is [`PlotError::UnsupportedFormat`].
    ///
    /// ```
    /// use bench::plots::PlotFormat;
    /// assert_eq!(PlotFormat::from_path("a/fig8.PNG".as_ref()).unwrap(), PlotFormat::Png);
    /// assert_eq!(PlotFormat::from_path("fig8.svg".as_ref()).unwrap(), PlotFormat::Svg);
    /// assert!(PlotFormat::from_path("fig8.pdf".as_ref()).is_err());
    /// ```
    pub fn from_path(path: &Path) -> Result<Self, PlotError> {
        let extension = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        match extension.as_deref() {
            Some("png") => Ok(Self::Png),
            Some("svg") => Ok(Self::Svg),
            _ => Err(PlotError::UnsupportedFormat {
                path: path.to_path_buf(),
            }),
        }
    }
}

/// The colour of cluster `label` (0, 1, …) in the cluster figures (Figs.
/// 11–12) and of the `k`-th series in Fig. 10: the nine Tableau-10 colours
/// other than grey, then hues spaced by the golden angle (137.5°) at
/// saturation 0.7 and lightness 0.45. A pure function of `label`; never the
/// outlier grey.
///
/// ```
/// use bench::plots::cluster_colour;
/// assert_eq!(cluster_colour(0), cluster_colour(0));
/// assert_ne!(cluster_colour(0), cluster_colour(1));
/// ```
pub fn cluster_colour(label: usize) -> RGBColor {
    if let Some(&colour) = BASE_PALETTE.get(label) {
        return colour;
    }
    let k = (label - BASE_PALETTE.len()) as f64;
    let hue = (0.13 + k * 0.381_966_011_250_105).fract();
    hsl_to_rgb(hue, 0.7, 0.45)
}

/// HSL (all in [0, 1]) to 8-bit RGB.
fn hsl_to_rgb(hue: f64, saturation: f64, lightness: f64) -> RGBColor {
    let chroma = (1.0 - (2.0 * lightness - 1.0).abs()) * saturation;
    let sector = hue * 6.0;
    let x = chroma * (1.0 - (sector % 2.0 - 1.0).abs());
    let (r, g, b) = match sector as u32 {
        0 => (chroma, x, 0.0),
        1 => (x, chroma, 0.0),
        2 => (0.0, chroma, x),
        3 => (0.0, x, chroma),
        4 => (x, 0.0, chroma),
        _ => (chroma, 0.0, x),
    };
    let m = lightness - chroma / 2.0;
    let byte = |v: f64| ((v + m) * 255.0).round().clamp(0.0, 255.0) as u8;
    RGBColor(byte(r), byte(g), byte(b))
}

/// Ground-truth labels (0 = outlier, 1..k = motion) as plot labels (−1 =
/// outlier, 0..k−1 = cluster), so that [`clusters_over_images`] can draw the
/// ground truth: `j ↦ j − 1` for `j > 0`, anything else `↦ −1`.
///
/// ```
/// assert_eq!(bench::plots::ground_truth_plot_labels(&[0, 1, 2, 1]), vec![-1, 0, 1, 0]);
/// ```
pub fn ground_truth_plot_labels(ground_truth: &[i32]) -> Vec<i32> {
    ground_truth
        .iter()
        .map(|&j| if j > 0 { j - 1 } else { -1 })
        .collect()
}

type DrawResult<DB> = Result<(), DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>>;

/// The chart layout shared by every figure: the title as caption, a
/// 16-pixel margin, room for the x labels and `y_label_area` pixels for the
/// y labels.
fn chart_builder<'a, 'b, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    title: &str,
    y_label_area: u32,
) -> ChartBuilder<'a, 'b, DB> {
    let mut builder = ChartBuilder::on(area);
    builder
        .caption(title, (FONT, 24))
        .margin(16)
        .x_label_area_size(48)
        .y_label_area_size(y_label_area);
    builder
}

/// The legend box shared by every figure, at `position`.
fn draw_legend<'a, DB: DrawingBackend + 'a, CT: CoordTranslate>(
    chart: &mut ChartContext<'a, DB, CT>,
    position: SeriesLabelPosition,
) -> DrawResult<DB> {
    chart
        .configure_series_labels()
        .position(position)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font((FONT, 16))
        .draw()
}

/// One figure, drawable on any plotters backend.
trait Figure {
    fn size(&self) -> (u32, u32);
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        format: PlotFormat,
    ) -> DrawResult<DB>;
    /// SVG elements placed under everything `draw` produces.
    fn svg_underlay(&self) -> Result<Option<String>, image::ImageError> {
        Ok(None)
    }
}

/// Draws `figure` and writes it to `path` in the format its extension names.
fn render(figure: &impl Figure, path: &Path) -> Result<(), PlotError> {
    let format = PlotFormat::from_path(path)?;
    let (width, height) = figure.size();
    let drawing = |message: String| PlotError::Drawing {
        path: path.to_path_buf(),
        message,
    };
    match format {
        PlotFormat::Png => {
            let mut buffer = vec![255u8; width as usize * height as usize * 3];
            {
                let root =
                    BitMapBackend::with_buffer(&mut buffer, (width, height)).into_drawing_area();
                figure
                    .draw(&root, format)
                    .map_err(|e| drawing(e.to_string()))?;
                root.present().map_err(|e| drawing(e.to_string()))?;
            }
            let image = RgbImage::from_raw(width, height, buffer)
                .ok_or_else(|| drawing("the pixel buffer does not match the figure size".into()))?;
            image
                .save_with_format(path, ImageFormat::Png)
                .map_err(|source| PlotError::Png {
                    path: path.to_path_buf(),
                    source,
                })
        }
        PlotFormat::Svg => {
            let mut svg = String::new();
            {
                let root = SVGBackend::with_string(&mut svg, (width, height)).into_drawing_area();
                figure
                    .draw(&root, format)
                    .map_err(|e| drawing(e.to_string()))?;
                root.present().map_err(|e| drawing(e.to_string()))?;
            }
            let underlay = figure.svg_underlay().map_err(|source| PlotError::Png {
                path: path.to_path_buf(),
                source,
            })?;
            if let Some(underlay) = underlay {
                let end_of_open_tag = svg
                    .find('>')
                    .ok_or_else(|| drawing("the SVG document has no root element".into()))?;
                svg.insert_str(end_of_open_tag + 1, &format!("\n{underlay}"));
            }
            std::fs::write(path, svg).map_err(|source| PlotError::Write {
                path: path.to_path_buf(),
                source,
            })
        }
    }
}

fn invalid(path: &Path, message: String) -> PlotError {
    PlotError::InvalidInput {
        path: path.to_path_buf(),
        message,
    }
}

fn text_style(size: u32, colour: RGBColor) -> TextStyle<'static> {
    (FONT, size).into_font().color(&colour)
}

fn centred(style: TextStyle<'static>) -> TextStyle<'static> {
    style.pos(Pos::new(HPos::Center, VPos::Center))
}

/// The empty frame of a chart: title, border and a centred note.
fn draw_no_data<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    title: &str,
    note: &str,
) -> DrawResult<DB> {
    root.fill(&WHITE)?;
    let (width, height) = root.dim_in_pixel();
    let (w, h) = (width as i32, height as i32);
    root.draw(&Text::new(
        title.to_string(),
        (w / 2, 28),
        centred(text_style(24, BLACK)),
    ))?;
    root.draw(&Rectangle::new(
        [(40, 60), (w - 40, h - 40)],
        BLACK.stroke_width(1),
    ))?;
    root.draw(&Text::new(
        note.to_string(),
        (w / 2, h / 2),
        centred(text_style(22, BLACK)),
    ))
}

/// `[lo, hi]` widened by `fraction` of its width on each side; an interval
/// narrower than `1e-9` of its magnitude (or than `1e-9`) is widened to
/// `±max(1, 5 % of |lo|)`.
fn padded((lo, hi): (f64, f64), fraction: f64) -> (f64, f64) {
    let width = hi - lo;
    if width > 1e-9 * lo.abs().max(hi.abs()).max(1.0) {
        (lo - fraction * width, hi + fraction * width)
    } else {
        let half = (0.05 * lo.abs()).max(1.0);
        (lo - half, hi + half)
    }
}

/// Largest magnitude of a value drawn: beyond it the axis arithmetic
/// (ranges, their widths and tick positions) overflows or loses precision.
pub const MAX_MAGNITUDE: f64 = 1e12;

/// A value that is drawn: finite and at most [`MAX_MAGNITUDE`] in magnitude.
fn drawable(v: f64) -> bool {
    v.is_finite() && v.abs() <= MAX_MAGNITUDE
}

/// Smallest and largest of the drawable values, None when there are none.
fn finite_range(values: impl IntoIterator<Item = f64>) -> Option<(f64, f64)> {
    values
        .into_iter()
        .filter(|&v| drawable(v))
        .fold(None, |range, v| match range {
            None => Some((v, v)),
            Some((lo, hi)) => Some((f64::min(lo, v), f64::max(hi, v))),
        })
}

// ---------------------------------------------------------------------------
// Fig. 10: ME against M.

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
    fn size(&self) -> (u32, u32) {
        CHART_SIZE
    }

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

// ---------------------------------------------------------------------------
// Fig. 8: the KDE of the focal estimates.

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
///
/// ```
/// assert_eq!(bench::plots::tau_band(1000.0, 0.25), (750.0, 1250.0));
/// ```
pub fn tau_band(f_peak: f64, tau_range: f64) -> (f64, f64) {
    let half = (f_peak * tau_range).abs();
    (f_peak - half, f_peak + half)
}

struct FocalKde<'a> {
    plot: FocalKdePlot<'a>,
}

impl Figure for FocalKde<'_> {
    fn size(&self) -> (u32, u32) {
        CHART_SIZE
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        _: PlotFormat,
    ) -> DrawResult<DB> {
        let p = &self.plot;
        let finite = |v: &Option<f64>| v.filter(|&x| drawable(x));
        let (f_peak, true_focal) = (finite(&p.f_peak), finite(&p.true_focal));
        let band = p.band.filter(|b| drawable(b.0) && drawable(b.1));
        let values: Vec<f64> = p.values.iter().copied().filter(|&v| drawable(v)).collect();
        let curve: Vec<(f64, f64)> = p
            .grid
            .iter()
            .zip(p.density)
            .map(|(&x, &d)| (x, d))
            .filter(|&(x, d)| drawable(x) && drawable(d))
            .collect();
        if values.is_empty() && curve.is_empty() {
            return draw_no_data(root, p.title, "no focal estimates");
        }
        // The axis spans the KDE grid (1st–99th percentile of the values)
        // and every marker; without a grid, all the values.
        let markers = f_peak
            .into_iter()
            .chain(true_focal)
            .chain(band.into_iter().flat_map(|b| [b.0, b.1]));
        let base = if curve.is_empty() {
            finite_range(values.iter().copied())
        } else {
            finite_range(curve.iter().map(|c| c.0))
        };
        let Some(range) = finite_range(base.into_iter().flat_map(|b| [b.0, b.1]).chain(markers))
        else {
            return draw_no_data(root, p.title, "no focal estimates");
        };
        let (x_lo, x_hi) = padded(range, 0.03);

        // Histogram normalised as a density over all values, so that it
        // shares the axis with the KDE.
        const BINS: usize = 60;
        let bin_width = (x_hi - x_lo) / BINS as f64;
        let mut counts = [0usize; BINS];
        let mut off_axis = 0;
        for &v in &values {
            let bin = ((v - x_lo) / bin_width).floor();
            if bin >= 0.0 && bin < BINS as f64 {
                counts[bin as usize] += 1;
            } else {
                off_axis += 1;
            }
        }
        let scale = 1.0 / (values.len().max(1) as f64 * bin_width);
        let hist_max = counts.iter().max().copied().unwrap_or(0) as f64 * scale;
        let kde_max = curve.iter().map(|c| c.1).fold(0.0, f64::max);
        let y_hi = hist_max.max(kde_max) * 1.12;
        let y_hi = if y_hi > 0.0 { y_hi } else { 1.0 };

        root.fill(&WHITE)?;
        let mut chart =
            chart_builder(root, p.title, 80).build_cartesian_2d(x_lo..x_hi, 0.0..y_hi)?;
        chart
            .configure_mesh()
            .x_desc("focal length f_avg (px)")
            .y_desc("density")
            .axis_desc_style((FONT, 18))
            .label_style((FONT, 14))
            .x_label_formatter(&|x| format!("{x:.0}"))
            .y_label_formatter(&|y| format!("{y:.1e}"))
            .draw()?;
        if let Some((lo, hi)) = band {
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
        let mut off_axis_note = String::new();
        if off_axis > 0 {
            off_axis_note = format!(", {off_axis} off the axis");
        }
        chart
            .draw_series(
                counts
                    .iter()
                    .enumerate()
                    .filter(|(_, &c)| c > 0)
                    .map(|(i, &c)| {
                        let x0 = x_lo + i as f64 * bin_width;
                        Rectangle::new(
                            [(x0, 0.0), (x0 + bin_width, c as f64 * scale)],
                            HISTOGRAM_COLOUR.filled(),
                        )
                    }),
            )?
            .label(format!(
                "f_avg estimates (n = {}{off_axis_note})",
                values.len()
            ))
            .legend(|(x, y)| {
                Rectangle::new([(x, y - 6), (x + 24, y + 6)], HISTOGRAM_COLOUR.filled())
            });
        if values.len() <= 500 {
            let tick = y_hi * 0.025;
            chart.draw_series(
                values
                    .iter()
                    .filter(|&&v| v >= x_lo && v <= x_hi)
                    .map(|&v| {
                        PathElement::new(vec![(v, 0.0), (v, tick)], BLACK.mix(0.6).stroke_width(1))
                    }),
            )?;
        }
        if !curve.is_empty() {
            chart
                .draw_series(LineSeries::new(curve, KDE_COLOUR.stroke_width(2)))?
                .label("Gaussian KDE")
                .legend(|(x, y)| {
                    PathElement::new(vec![(x, y), (x + 24, y)], KDE_COLOUR.stroke_width(2))
                });
        }
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
        draw_legend(&mut chart, SeriesLabelPosition::UpperRight)
    }
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

// ---------------------------------------------------------------------------
// Figs. 11–12: clusters over the image pair.

/// Where [`clusters_over_images`] puts things: both images scaled by
/// [`Self::scale`] to fit a 800 × 600 panel, side by side under a title
/// strip, with a legend strip below.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClustersLayout {
    /// The image size `(W, H)` in pixels.
    pub image_size: (u32, u32),
    /// Canvas pixels per image pixel.
    pub scale: f64,
    /// Size of each panel on the canvas.
    pub panel_size: (u32, u32),
    /// Top-left canvas pixel of the panel of image 1 and of image 2.
    pub origins: [(i32, i32); 2],
    /// Size of the whole figure.
    pub canvas_size: (u32, u32),
}

const PANEL_MAX: (f64, f64) = (800.0, 600.0);
const MARGIN: i32 = 12;
const TITLE_HEIGHT: i32 = 64;
const LEGEND_HEIGHT: i32 = 40;
const PANEL_GAP: i32 = 16;

impl ClustersLayout {
    /// The layout for images of `image_size`; None when a side is 0.
    ///
    /// ```
    /// let layout = bench::plots::ClustersLayout::new((640, 480)).unwrap();
    /// assert_eq!(layout.panel_size, (800, 600));
    /// assert_eq!(layout.to_canvas(0, [0.0, 0.0]), layout.origins[0]);
    /// ```
    pub fn new(image_size: (u32, u32)) -> Option<Self> {
        let (w, h) = image_size;
        if w == 0 || h == 0 {
            return None;
        }
        let scale = (PANEL_MAX.0 / f64::from(w)).min(PANEL_MAX.1 / f64::from(h));
        let panel_size = (
            ((f64::from(w) * scale).round() as u32).max(1),
            ((f64::from(h) * scale).round() as u32).max(1),
        );
        let (pw, ph) = (panel_size.0 as i32, panel_size.1 as i32);
        let origins = [
            (MARGIN, TITLE_HEIGHT),
            (MARGIN + pw + PANEL_GAP, TITLE_HEIGHT),
        ];
        let canvas_size = (
            (2 * MARGIN + 2 * pw + PANEL_GAP) as u32,
            (TITLE_HEIGHT + ph + LEGEND_HEIGHT + MARGIN) as u32,
        );
        Some(Self {
            image_size,
            scale,
            panel_size,
            origins,
            canvas_size,
        })
    }

    /// The canvas pixel of image point `p` (pixel coordinates, pixel
    /// centres at integers) in image `view` (0 or 1):
    /// `origin + round((p + 0.5) · scale − 0.5)`.
    pub fn to_canvas(&self, view: usize, p: [f64; 2]) -> (i32, i32) {
        let (ox, oy) = self.origins[view.min(1)];
        let map = |v: f64| ((v + 0.5) * self.scale - 0.5).round() as i32;
        (ox + map(p[0]), oy + map(p[1]))
    }

    /// True when `p` lies on the image (within half a pixel of its border
    /// pixel centres).
    pub fn contains(&self, p: [f64; 2]) -> bool {
        let (w, h) = (f64::from(self.image_size.0), f64::from(self.image_size.1));
        p[0] >= -0.5 && p[0] < w - 0.5 && p[1] >= -0.5 && p[1] < h - 0.5
    }
}

struct ClustersOverImages<'a> {
    layout: ClustersLayout,
    images: Option<(&'a RgbImage, &'a RgbImage)>,
    points: [&'a [[f64; 2]]; 2],
    labels: &'a [i32],
    title: &'a str,
}

impl ClustersOverImages<'_> {
    /// Image `view` resized to its panel.
    fn panel_image(&self, view: usize) -> Option<RgbImage> {
        let (a, b) = self.images?;
        let image = if view == 0 { a } else { b };
        let (pw, ph) = self.layout.panel_size;
        Some(if image.dimensions() == (pw, ph) {
            image.clone()
        } else {
            image::imageops::resize(image, pw, ph, image::imageops::FilterType::Triangle)
        })
    }

    /// The clusters by label and their sizes, and the number of outliers.
    fn cluster_sizes(&self) -> (Vec<(i32, usize)>, usize) {
        let mut sizes = std::collections::BTreeMap::new();
        let mut outliers = 0;
        for &label in self.labels {
            if label >= 0 {
                *sizes.entry(label).or_insert(0) += 1;
            } else {
                outliers += 1;
            }
        }
        (sizes.into_iter().collect(), outliers)
    }
}

impl Figure for ClustersOverImages<'_> {
    fn size(&self) -> (u32, u32) {
        self.layout.canvas_size
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        format: PlotFormat,
    ) -> DrawResult<DB> {
        // The background is white already: the PNG buffer starts white and
        // the SVG underlay begins with a white rectangle.
        let layout = &self.layout;
        let (canvas_w, _) = layout.canvas_size;
        let (pw, ph) = (layout.panel_size.0 as i32, layout.panel_size.1 as i32);
        let (clusters, outliers) = self.cluster_sizes();
        root.draw(&Text::new(
            self.title.to_string(),
            (canvas_w as i32 / 2, 20),
            centred(text_style(24, BLACK)),
        ))?;
        for (view, &(ox, oy)) in layout.origins.iter().enumerate() {
            match (self.images.is_some(), format) {
                (true, PlotFormat::Png) => {
                    if let Some(image) = self.panel_image(view) {
                        let element = BitMapElement::with_owned_buffer(
                            (ox, oy),
                            layout.panel_size,
                            image.into_raw(),
                        );
                        if let Some(element) = element {
                            root.draw(&element)?;
                        }
                    }
                }
                (true, PlotFormat::Svg) => {}
                (false, _) => {
                    root.draw(&Rectangle::new(
                        [(ox, oy), (ox + pw, oy + ph)],
                        BLANK_PANEL_COLOUR.filled(),
                    ))?;
                }
            }
            root.draw(&Rectangle::new(
                [(ox - 1, oy - 1), (ox + pw, oy + ph)],
                BLACK.stroke_width(1),
            ))?;
            root.draw(&Text::new(
                format!("image {}", view + 1),
                (ox + pw / 2, oy - 14),
                centred(text_style(16, BLACK)),
            ))?;
        }
        if self.labels.is_empty() {
            let (ox, oy) = layout.origins[0];
            root.draw(&Text::new(
                "no correspondences".to_string(),
                (ox + pw + PANEL_GAP / 2, oy + ph / 2),
                centred(text_style(22, BLACK)),
            ))?;
        }
        // Outliers first, underneath the clusters.
        for outlier_pass in [true, false] {
            for (view, points) in self.points.iter().enumerate() {
                for (p, &label) in points.iter().zip(self.labels) {
                    if (label < 0) != outlier_pass
                        || !p.iter().all(|c| c.is_finite())
                        || !layout.contains(*p)
                    {
                        continue;
                    }
                    let at = layout.to_canvas(view, *p);
                    if label < 0 {
                        root.draw(&Cross::new(at, 3, OUTLIER_COLOUR.stroke_width(1)))?;
                    } else {
                        root.draw(&Circle::new(at, 4, cluster_colour(label as usize).filled()))?;
                        root.draw(&Circle::new(at, 4, BLACK.stroke_width(1)))?;
                    }
                }
            }
        }
        // Legend: one entry per cluster, then the outliers.
        let legend_y = TITLE_HEIGHT + ph + LEGEND_HEIGHT / 2;
        let mut x = MARGIN + 8;
        let right = canvas_w as i32 - MARGIN;
        const ENTRY_WIDTH: i32 = 150;
        for (shown, &(label, size)) in clusters.iter().enumerate() {
            if x + 2 * ENTRY_WIDTH > right {
                root.draw(&Text::new(
                    format!("+{} more clusters", clusters.len() - shown),
                    (x, legend_y),
                    text_style(15, BLACK).pos(Pos::new(HPos::Left, VPos::Center)),
                ))?;
                x += ENTRY_WIDTH;
                break;
            }
            root.draw(&Circle::new(
                (x, legend_y),
                5,
                cluster_colour(label as usize).filled(),
            ))?;
            root.draw(&Circle::new((x, legend_y), 5, BLACK.stroke_width(1)))?;
            root.draw(&Text::new(
                format!("cluster {label} ({size})"),
                (x + 10, legend_y),
                text_style(15, BLACK).pos(Pos::new(HPos::Left, VPos::Center)),
            ))?;
            x += ENTRY_WIDTH;
        }
        root.draw(&Cross::new(
            (x, legend_y),
            4,
            OUTLIER_COLOUR.stroke_width(2),
        ))?;
        root.draw(&Text::new(
            format!("outliers ({outliers})"),
            (x + 10, legend_y),
            text_style(15, BLACK).pos(Pos::new(HPos::Left, VPos::Center)),
        ))?;
        Ok(())
    }

    fn svg_underlay(&self) -> Result<Option<String>, image::ImageError> {
        let (w, h) = self.layout.canvas_size;
        let mut underlay =
            format!("<rect x=\"0\" y=\"0\" width=\"{w}\" height=\"{h}\" fill=\"#FFFFFF\"/>\n");
        for view in 0..2 {
            let Some(image) = self.panel_image(view) else {
                continue;
            };
            let mut png = Vec::new();
            PngEncoder::new(&mut png).write_image(
                image.as_raw(),
                image.width(),
                image.height(),
                image::ExtendedColorType::Rgb8,
            )?;
            let (ox, oy) = self.layout.origins[view];
            underlay.push_str(&format!(
                "<image x=\"{ox}\" y=\"{oy}\" width=\"{}\" height=\"{}\" \
                 xmlns:xlink=\"http://www.w3.org/1999/xlink\" \
                 xlink:href=\"data:image/png;base64,{}\"/>\n",
                image.width(),
                image.height(),
                base64(&png)
            ));
        }
        Ok(Some(underlay))
    }
}

/// Standard base64 (RFC 4648, with padding).
fn base64(bytes: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            chunk.get(1).copied().unwrap_or(0),
            chunk.get(2).copied().unwrap_or(0),
        ];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        let sextet = |shift: u32| char::from(ALPHABET[((n >> shift) & 63) as usize]);
        out.push(sextet(18));
        out.push(sextet(12));
        out.push(if chunk.len() > 1 { sextet(6) } else { '=' });
        out.push(if chunk.len() > 2 { sextet(0) } else { '=' });
    }
    out
}

/// Both images side by side with every correspondence drawn over them in
/// its cluster's colour ([`cluster_colour`]) and the outliers (any negative
/// label) as small grey crosses — the thesis's Figs. 11–12. Without images
/// the panels are blank canvases of the image size. A legend below counts
/// the points of each cluster and the outliers.
///
/// PNG output draws the images as bitmaps; SVG output embeds them as
/// base64 PNG `<image>` elements under the drawing. The geometry is
/// [`ClustersLayout::new`]`(image_size)`. Points that are not finite or lie
/// off the image are not drawn. `points1`, `points2` and `labels` must have
/// the same length and the images the size `image_size`; labels are those
/// of a segmentation (−1 = outlier; see [`ground_truth_plot_labels`] for
/// ground truth).
pub fn clusters_over_images(
    image_size: (u32, u32),
    images: Option<(&RgbImage, &RgbImage)>,
    points1: &[[f64; 2]],
    points2: &[[f64; 2]],
    labels: &[i32],
    title: &str,
    path: impl AsRef<Path>,
) -> Result<(), PlotError> {
    let path = path.as_ref();
    let layout = ClustersLayout::new(image_size).ok_or_else(|| {
        invalid(
            path,
            format!("`image_size` {} x {} is empty", image_size.0, image_size.1),
        )
    })?;
    if points2.len() != points1.len() || labels.len() != points1.len() {
        return Err(invalid(
            path,
            format!(
                "`points1` has {} points, `points2` {} and `labels` {}",
                points1.len(),
                points2.len(),
                labels.len()
            ),
        ));
    }
    if let Some((a, b)) = images {
        for (i, image) in [a, b].into_iter().enumerate() {
            if image.dimensions() != image_size {
                return Err(invalid(
                    path,
                    format!(
                        "image {} is {} x {}, `image_size` is {} x {}",
                        i + 1,
                        image.width(),
                        image.height(),
                        image_size.0,
                        image_size.1
                    ),
                ));
            }
        }
    }
    let figure = ClustersOverImages {
        layout,
        images,
        points: [points1, points2],
        labels,
        title,
    };
    render(&figure, path)
}

// ---------------------------------------------------------------------------
// Fig. 9: relative focal error over scenes.

struct FocalErrorHistogram {
    errors: Vec<f64>,
    tau_range: f64,
}

impl Figure for FocalErrorHistogram {
    fn size(&self) -> (u32, u32) {
        CHART_SIZE
    }

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

// ---------------------------------------------------------------------------
// ME per scene, baseline against semical.

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
    fn size(&self) -> (u32, u32) {
        CHART_SIZE
    }

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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_matches_rfc4648_vectors() {
        let cases = [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ];
        for (plain, encoded) in cases {
            assert_eq!(base64(plain.as_bytes()), encoded);
        }
        assert_eq!(base64(&[0xff, 0xfe, 0xfd]), "//79");
    }

    #[test]
    fn hsl_primaries() {
        assert_eq!(hsl_to_rgb(0.0, 1.0, 0.5), RGBColor(255, 0, 0));
        assert_eq!(hsl_to_rgb(1.0 / 3.0, 1.0, 0.5), RGBColor(0, 255, 0));
        assert_eq!(hsl_to_rgb(2.0 / 3.0, 1.0, 0.5), RGBColor(0, 0, 255));
        assert_eq!(hsl_to_rgb(0.5, 0.0, 0.5), RGBColor(128, 128, 128));
    }

    #[test]
    fn padded_widens_degenerate_ranges() {
        assert_eq!(padded((0.0, 10.0), 0.1), (-1.0, 11.0));
        assert_eq!(padded((1000.0, 1000.0), 0.1), (950.0, 1050.0));
        assert_eq!(padded((0.0, 0.0), 0.1), (-1.0, 1.0));
        assert_eq!(
            finite_range([f64::NAN, 3.0, -1.0, f64::INFINITY]),
            Some((-1.0, 3.0))
        );
        assert_eq!(finite_range([f64::NAN]), None);
    }
}
