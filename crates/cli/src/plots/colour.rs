//! The colours of the figures: the cluster palette (Tableau-10, then
//! golden-angle hues) and the fixed colours of each figure's marks.

use plotters::style::RGBColor;

/// Colour of outliers (label −1) in [`clusters_over_images`].
pub const OUTLIER_COLOUR: RGBColor = RGBColor(128, 128, 128);

/// The first cluster colours: the Tableau-10 palette without its grey.
pub(super) const BASE_PALETTE: [RGBColor; 9] = [
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

pub(super) const KDE_COLOUR: RGBColor = RGBColor(31, 119, 180);
pub(super) const HISTOGRAM_COLOUR: RGBColor = RGBColor(158, 188, 218);
/// Colour of the f_peak line in [`focal_kde`] (used for nothing else there).
pub const PEAK_COLOUR: RGBColor = RGBColor(214, 39, 40);
pub(super) const BAND_COLOUR: RGBColor = RGBColor(255, 127, 14);
/// Colour of the true-focal line in [`focal_kde`] (used for nothing else
/// there).
pub const TRUE_FOCAL_COLOUR: RGBColor = RGBColor(44, 160, 44);
pub(super) const BLANK_PANEL_COLOUR: RGBColor = RGBColor(236, 236, 236);

/// The colour of cluster `label` (0, 1, …) in the cluster figures (Figs.
/// 11–12) and of the `k`-th series in Fig. 10: the nine Tableau-10 colours
/// other than grey, then hues spaced by the golden angle (137.5°) at
/// saturation 0.7 and lightness 0.45. A pure function of `label`; never the
/// outlier grey.
pub fn cluster_colour(label: usize) -> RGBColor {
    if let Some(&colour) = BASE_PALETTE.get(label) {
        return colour;
    }
    let k = (label - BASE_PALETTE.len()) as f64;
    let hue = (0.13 + k * 0.381_966_011_250_105).fract();
    hsl_to_rgb(hue, 0.7, 0.45)
}

/// HSL (all in [0, 1]) to 8-bit RGB.
pub(super) fn hsl_to_rgb(hue: f64, saturation: f64, lightness: f64) -> RGBColor {
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hsl_primaries() {
        assert_eq!(hsl_to_rgb(0.0, 1.0, 0.5), RGBColor(255, 0, 0));
        assert_eq!(hsl_to_rgb(1.0 / 3.0, 1.0, 0.5), RGBColor(0, 255, 0));
        assert_eq!(hsl_to_rgb(2.0 / 3.0, 1.0, 0.5), RGBColor(0, 0, 255));
        assert_eq!(hsl_to_rgb(0.5, 0.0, 0.5), RGBColor(128, 128, 128));
    }
}

/// The examples once in the documentation of this module's items.
#[cfg(test)]
mod examples {
    #[test]
    fn cluster_colour_example() {
        use crate::plots::cluster_colour;
        assert_eq!(cluster_colour(0), cluster_colour(0));
        assert_ne!(cluster_colour(0), cluster_colour(1));
    }
}
