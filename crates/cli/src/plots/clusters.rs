//! Figs. 11–12: the clusters over the image pair.

use super::canvas::DrawResult;
use super::*;
use base64::prelude::{Engine as _, BASE64_STANDARD};
use image::codecs::png::PngEncoder;
use image::{ImageEncoder, RgbImage};
use plotters::coord::Shift;
use plotters::element::BitMapElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::path::Path;

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
    pub fn to_canvas(self, view: usize, p: [f64; 2]) -> (i32, i32) {
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
        let (canvas_w, _) = self.layout.canvas_size;
        root.draw(&Text::new(
            self.title.to_string(),
            (canvas_w as i32 / 2, 20),
            centred(text_style(24, BLACK)),
        ))?;
        self.draw_panels(root, format)?;
        self.draw_points(root)?;
        self.draw_cluster_legend(root)
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
                BASE64_STANDARD.encode(&png)
            ));
        }
        Ok(Some(underlay))
    }
}

impl ClustersOverImages<'_> {
    /// Both panels: the image (PNG) or a blank canvas, a frame and a
    /// caption; a note when there is no correspondence.
    fn draw_panels<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        format: PlotFormat,
    ) -> DrawResult<DB> {
        let layout = &self.layout;
        let (pw, ph) = (layout.panel_size.0 as i32, layout.panel_size.1 as i32);
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
        Ok(())
    }

    /// Every drawable correspondence in both panels: outliers as crosses,
    /// then the clustered points in their colours.
    fn draw_points<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<DB> {
        let layout = &self.layout;
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
        Ok(())
    }

    /// The legend strip: one entry per cluster with its size, then the
    /// outliers.
    fn draw_cluster_legend<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
    ) -> DrawResult<DB> {
        let (canvas_w, _) = self.layout.canvas_size;
        let ph = self.layout.panel_size.1 as i32;
        let (clusters, outliers) = self.cluster_sizes();
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

/// The examples once in the documentation of this module's items.
#[cfg(test)]
mod examples {
    #[test]
    fn new_example() {
        let layout = super::ClustersLayout::new((640, 480)).unwrap();
        assert_eq!(layout.panel_size, (800, 600));
        assert_eq!(layout.to_canvas(0, [0.0, 0.0]), layout.origins[0]);
    }
}
