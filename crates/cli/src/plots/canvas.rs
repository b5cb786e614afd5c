//! What every figure shares: the [`Figure`] trait and [`render`] to PNG or
//! SVG, the chart layout, the legend, the "no data" frame and the range
//! helpers.

use super::*;
use crate::output::write_bytes_atomic;
use image::{ImageFormat, RgbImage};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::path::Path;

pub(super) const FONT: &str = "sans-serif";

pub(super) type DrawResult<DB> =
    Result<(), DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>>;

/// The chart layout shared by every figure: the title as caption, a
/// 16-pixel margin, room for the x labels and `y_label_area` pixels for the
/// y labels.
pub(super) fn chart_builder<'a, 'b, DB: DrawingBackend>(
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
pub(super) fn draw_legend<'a, DB: DrawingBackend + 'a, CT: CoordTranslate>(
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
pub(super) trait Figure {
    /// Pixel size of the figure: [`CHART_SIZE`] unless the figure says.
    fn size(&self) -> (u32, u32) {
        CHART_SIZE
    }
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
pub(super) fn render(figure: &impl Figure, path: &Path) -> Result<(), PlotError> {
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
            let mut png = std::io::Cursor::new(Vec::new());
            image
                .write_to(&mut png, ImageFormat::Png)
                .map_err(|cause| PlotError::Png {
                    path: path.to_path_buf(),
                    cause,
                })?;
            write_file(path, png.get_ref())
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
            let underlay = figure.svg_underlay().map_err(|cause| PlotError::Png {
                path: path.to_path_buf(),
                cause,
            })?;
            if let Some(underlay) = underlay {
                let end_of_open_tag = svg
                    .find('>')
                    .ok_or_else(|| drawing("the SVG document has no root element".into()))?;
                svg.insert_str(end_of_open_tag + 1, &format!("\n{underlay}"));
            }
            write_file(path, svg.as_bytes())
        }
    }
}

/// Writes a figure's bytes through a temporary file and a rename
/// ([`write_bytes_atomic`]): a full disk leaves no partial figure.
fn write_file(path: &Path, bytes: &[u8]) -> Result<(), PlotError> {
    write_bytes_atomic(path, bytes).map_err(|cause| PlotError::Write {
        path: path.to_path_buf(),
        cause,
    })
}

pub(super) fn invalid(path: &Path, message: String) -> PlotError {
    PlotError::InvalidInput {
        path: path.to_path_buf(),
        message,
    }
}

pub(super) fn text_style(size: u32, colour: RGBColor) -> TextStyle<'static> {
    (FONT, size).into_font().color(&colour)
}

pub(super) fn centred(style: TextStyle<'static>) -> TextStyle<'static> {
    style.pos(Pos::new(HPos::Center, VPos::Center))
}

/// The empty frame of a chart: title, border and a centred note.
pub(super) fn draw_no_data<DB: DrawingBackend>(
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
pub(super) fn padded((lo, hi): (f64, f64), fraction: f64) -> (f64, f64) {
    let width = hi - lo;
    if width > 1e-9 * lo.abs().max(hi.abs()).max(1.0) {
        (lo - fraction * width, hi + fraction * width)
    } else {
        let half = (0.05 * lo.abs()).max(1.0);
        (lo - half, hi + half)
    }
}

/// A value that is drawn: finite and at most [`MAX_MAGNITUDE`] in magnitude.
pub(super) fn drawable(v: f64) -> bool {
    v.is_finite() && v.abs() <= MAX_MAGNITUDE
}

/// Smallest and largest of the drawable values, None when there are none.
pub(super) fn finite_range(values: impl IntoIterator<Item = f64>) -> Option<(f64, f64)> {
    values
        .into_iter()
        .filter(|&v| drawable(v))
        .fold(None, |range, v| match range {
            None => Some((v, v)),
            Some((lo, hi)) => Some((f64::min(lo, v), f64::max(hi, v))),
        })
}

#[cfg(test)]
mod tests {
    use super::*;

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
