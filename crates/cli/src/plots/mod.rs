//! The figures of an experiment run (docs/method.md, "Published numbers"; the
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
//! One file per figure, each with the data it is drawn from:
//! `me_vs_samples.rs` (Fig. 10), `focal_kde.rs` (Fig. 8), `clusters.rs`
//! (Figs. 11–12), `focal_error.rs` (Fig. 9), `me_scatter.rs`; the shared
//! canvas code in `canvas.rs` and the colours in `colour.rs`.

mod canvas;
mod clusters;
mod colour;
mod focal_error;
mod focal_kde;
mod me_scatter;
mod me_vs_samples;
#[cfg(test)]
#[path = "../../tests/support/png.rs"]
mod test_png;
#[cfg(test)]
mod tests;

use canvas::*;
pub use clusters::clusters_over_images;
use colour::*;
pub use colour::{cluster_colour, OUTLIER_COLOUR, PEAK_COLOUR, TRUE_FOCAL_COLOUR};
pub use focal_error::focal_error_histogram;
pub use focal_kde::{focal_kde, FocalKdePlot};
pub use me_scatter::{me_scatter, me_scene_pairs};
#[cfg(test)]
pub use me_vs_samples::Series;
pub use me_vs_samples::{me_vs_samples, me_vs_samples_series};
use std::path::{Path, PathBuf};
use thiserror::Error;

/// Pixel size of the chart figures (Figs. 8, 9, 10 and the ME scatter).
pub const CHART_SIZE: (u32, u32) = (960, 640);

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
    /// The figure file could not be written.
    #[error("{}: cannot write the figure: {cause}", path.display())]
    Write {
        /// The output path.
        path: PathBuf,
        /// The I/O error.
        cause: std::io::Error,
    },
    /// The PNG could not be encoded, or an image read for it decoded.
    #[error("{}: cannot make the image: {cause}", path.display())]
    Png {
        /// The output path.
        path: PathBuf,
        /// The encoder's error.
        cause: image::ImageError,
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
    /// case); anything else is `PlotError::UnsupportedFormat`.
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

/// Largest magnitude of a value drawn: beyond it the axis arithmetic
/// (ranges, their widths and tick positions) overflows or loses precision.
pub const MAX_MAGNITUDE: f64 = 1e12;

/// The examples once in the documentation of this module's items.
#[cfg(test)]
mod examples {
    #[test]
    fn module_example() {
        use crate::plots::{me_vs_samples, Series};
        let dir = tempfile::tempdir().unwrap();
        let series = [
            Series {
                label: "baseline".into(),
                points: vec![(500, 16.0, 12.0), (3000, 15.6, 12.2)],
            },
            Series {
                label: "semical".into(),
                points: vec![(500, 13.0, 12.5), (3000, 10.5, 12.4)],
            },
        ];
        let path = dir.path().join("me_vs_m.svg");
        me_vs_samples(&series, &path).unwrap();
        let svg = std::fs::read_to_string(&path).unwrap();
        assert!(svg.starts_with("<svg") && svg.contains("ME (%)"));
    }

    #[test]
    fn from_path_example() {
        use crate::plots::PlotFormat;
        assert_eq!(
            PlotFormat::from_path("a/fig8.PNG".as_ref()).unwrap(),
            PlotFormat::Png
        );
        assert_eq!(
            PlotFormat::from_path("fig8.svg".as_ref()).unwrap(),
            PlotFormat::Svg
        );
        assert!(PlotFormat::from_path("fig8.pdf".as_ref()).is_err());
    }
}
