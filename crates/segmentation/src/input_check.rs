//! The checks of the input's coordinates made before any hypothesis
//! (docs/method.md "Input"): a coordinate that is not finite or absurdly
//! large is refused, points far outside the image and an image size that
//! looks transposed are reported as [`InputWarning`]s in the result.

use crate::{Matches, SegmentationError};
use thiserror::Error;

/// The largest coordinate magnitude accepted, pixels: 10⁶ px, a thousand
/// times a 1000-pixel image and beyond any sensor. Beyond it a value is a
/// unit or parsing mistake (metres as micrometres, a sentinel such as
/// 1e200), and one such point would otherwise dominate the Hartley
/// normalisation of every sample that draws it.
pub const MAX_COORDINATE_PX: f64 = 1e6;

/// How far outside the image a point may lie before it counts as far
/// outside: one image width (height) left of (above) the image or right
/// of (below) it.
pub const OUTSIDE_MARGIN_IMAGES: f64 = 1.0;

/// Something suspicious about an input that is still segmented.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum InputWarning {
    /// Matches with a point more than [`OUTSIDE_MARGIN_IMAGES`] image
    /// sizes outside the image.
    #[error(
        "{count} of {total} matches lie more than one image size outside the {width} x {height} \
         image (first: row {row}, x1 = {x1}, y1 = {y1}, x2 = {x2}, y2 = {y2}): check the \
         image size and the coordinates' units"
    )]
    FarOutside {
        /// Matches far outside.
        count: usize,
        /// Matches in the input.
        total: usize,
        /// The first such match (0-based row).
        row: usize,
        /// Its coordinates.
        x1: f64,
        /// Its coordinates.
        y1: f64,
        /// Its coordinates.
        x2: f64,
        /// Its coordinates.
        y2: f64,
        /// The image size.
        width: u32,
        /// The image size.
        height: u32,
    },
    /// Every point fits in the image with width and height exchanged but
    /// not in the image as given.
    #[error(
        "every point fits an image of width {height} and height {width} but not image_size \
         = ({width}, {height}) (width, height): was it given as (height, width), as \
         img.shape[:2] is? Pass ({height}, {width})"
    )]
    TransposedImageSize {
        /// The width given.
        width: u32,
        /// The height given.
        height: u32,
    },
}

/// Refuses a non-finite coordinate or one beyond [`MAX_COORDINATE_PX`]
/// (naming the row, the column and the value), then lists the warnings
/// of the input (none for points inside their image).
pub fn check_matches(matches: &Matches) -> Result<Vec<InputWarning>, SegmentationError> {
    let rows = || {
        matches
            .points1
            .iter()
            .zip(matches.points2)
            .map(|(p, q)| [p[0], p[1], q[0], q[1]])
            .enumerate()
    };
    for (row, values) in rows() {
        let bad = values
            .iter()
            .position(|v| !(v.is_finite() && v.abs() <= MAX_COORDINATE_PX));
        if let Some(i) = bad {
            return Err(SegmentationError::InvalidCoordinate {
                row,
                column: ["x1", "y1", "x2", "y2"][i],
                value: values[i],
                bound: MAX_COORDINATE_PX,
            });
        }
    }
    let (w, h) = (
        f64::from(matches.image_size.0),
        f64::from(matches.image_size.1),
    );
    let mut warnings = Vec::new();
    let far = |v: &[f64; 4]| {
        let (mx, my) = (OUTSIDE_MARGIN_IMAGES * w, OUTSIDE_MARGIN_IMAGES * h);
        [v[0], v[2]].iter().any(|&x| x < -mx || x > w + mx)
            || [v[1], v[3]].iter().any(|&y| y < -my || y > h + my)
    };
    let mut outside = rows().filter(|(_, v)| far(v));
    if let Some((row, [x1, y1, x2, y2])) = outside.next() {
        warnings.push(InputWarning::FarOutside {
            count: 1 + outside.count(),
            total: matches.len(),
            row,
            x1,
            y1,
            x2,
            y2,
            width: matches.image_size.0,
            height: matches.image_size.1,
        });
    }
    let fits = |w: f64, h: f64| {
        let inside = |x: f64, y: f64| (-1.0..=w).contains(&x) && (-1.0..=h).contains(&y);
        rows().all(|(_, v)| inside(v[0], v[1]) && inside(v[2], v[3]))
    };
    if !matches.is_empty() && w != h && !fits(w, h) && fits(h, w) {
        warnings.push(InputWarning::TransposedImageSize {
            width: matches.image_size.0,
            height: matches.image_size.1,
        });
    }
    Ok(warnings)
}
