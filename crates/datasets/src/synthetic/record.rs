//! The drawn difficulty of a scene of the randomised families
//! (`driving-random`, `objects-3d`): what was drawn (N, noise, outlier
//! share, each motion's share and separation), kept beside the scene and
//! written by [`write_records_csv`] (`sctl synth` writes it as
//! [`RECORDS_FILE`] at the top of its output).

use std::path::Path;

use nalgebra::Matrix3;
use serde::Serialize;

use super::driving::{median_sampson, Tracks};
use super::SyntheticScene;
use crate::DatasetError;

/// The file [`super::write_hopef_layout_with`] writes at the top of its
/// output when its scenes carry a [`SceneRecord`].
pub const RECORDS_FILE: &str = "difficulty.csv";

/// What one motion of a scene is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum MotionKind {
    /// The static background under the camera's ego-motion.
    Background,
    /// An independently moving rigid object (a car, a 3-D object).
    Object,
}

/// The drawn difficulty of one motion.
#[derive(Debug, Clone, PartialEq)]
pub struct MotionRecord {
    /// Its label in the scene (1..k).
    pub label: i32,
    /// Background or object.
    pub kind: MotionKind,
    /// Its number of matches.
    pub points: usize,
    /// `points / N`.
    pub share: f64,
    /// The separation drawn for it, px (`driving-random` movers; `None`
    /// otherwise): the median Sampson distance its noise-free matches were
    /// made to have to the background's true F.
    pub target_separation_px: Option<f64>,
    /// Median Sampson distance (px) of its noise-free matches to the
    /// background's true F (`None` for the background itself, or when there
    /// is none).
    pub background_separation_px: Option<f64>,
    /// Smallest median Sampson distance (px) of its noise-free matches to
    /// any other motion's true F (`None` in a one-motion scene).
    pub nearest_separation_px: Option<f64>,
    /// Rotation angle of the object between the views, degrees, relative to
    /// the static world (0 for the background).
    pub rotation_deg: f64,
}

/// The drawn difficulty of one scene.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneRecord {
    /// The preset (`driving-random`, `objects-3d`).
    pub family: &'static str,
    /// Number of matches N.
    pub n: usize,
    /// Pixel noise σ per coordinate.
    pub noise_sigma: f64,
    /// Gross outliers / N.
    pub outlier_share: f64,
    /// The true focal length, px.
    pub focal: f64,
    /// Image size (W, H), px.
    pub image_size: (u32, u32),
    /// The motions in label order.
    pub motions: Vec<MotionRecord>,
}

/// The separations of motion `i` ([`MotionRecord::background_separation_px`],
/// [`MotionRecord::nearest_separation_px`]) from the noise-free `tracks` of
/// every motion and their true `fundamentals` (same order), the background
/// at `background` when there is one.
pub(super) fn separations(
    i: usize,
    tracks: &[&Tracks],
    fundamentals: &[Matrix3<f64>],
    background: Option<usize>,
) -> (Option<f64>, Option<f64>) {
    let to_background = background
        .filter(|&b| b != i)
        .map(|b| median_sampson(&fundamentals[b], tracks[i]));
    let nearest = (0..fundamentals.len())
        .filter(|&j| j != i)
        .map(|j| median_sampson(&fundamentals[j], tracks[i]))
        .min_by(f64::total_cmp);
    (to_background, nearest)
}

/// One row of [`RECORDS_FILE`]: a motion of a scene, with the scene's
/// values repeated.
#[derive(Serialize)]
struct Row<'a> {
    scene: &'a str,
    family: &'a str,
    n: usize,
    motions: usize,
    noise_sigma: f64,
    outlier_share: f64,
    focal: f64,
    width: u32,
    height: u32,
    label: i32,
    kind: MotionKind,
    points: usize,
    share: f64,
    target_separation_px: Option<f64>,
    background_separation_px: Option<f64>,
    nearest_separation_px: Option<f64>,
    rotation_deg: f64,
}

/// Writes the records of the `scenes` that have one to the CSV file `path`,
/// one row per motion (columns: `scene, family, n, motions, noise_sigma,
/// outlier_share, focal, width, height, label, kind, points, share,
/// target_separation_px, background_separation_px, nearest_separation_px,
/// rotation_deg`; an absent value is empty). Returns the number of scenes
/// written; no file is written when none has a record.
pub fn write_records_csv(path: &Path, scenes: &[SyntheticScene]) -> Result<usize, DatasetError> {
    let with_record: Vec<(&str, &SceneRecord)> = scenes
        .iter()
        .filter_map(|s| s.record.as_ref().map(|r| (s.scene.name.as_str(), r)))
        .collect();
    if with_record.is_empty() {
        return Ok(0);
    }
    let io = |e: csv::Error| DatasetError::io(path, std::io::Error::other(e));
    let mut out = csv::Writer::from_path(path).map_err(io)?;
    for (scene, r) in &with_record {
        for m in &r.motions {
            out.serialize(Row {
                scene,
                family: r.family,
                n: r.n,
                motions: r.motions.len(),
                noise_sigma: r.noise_sigma,
                outlier_share: r.outlier_share,
                focal: r.focal,
                width: r.image_size.0,
                height: r.image_size.1,
                label: m.label,
                kind: m.kind,
                points: m.points,
                share: m.share,
                target_separation_px: m.target_separation_px,
                background_separation_px: m.background_separation_px,
                nearest_separation_px: m.nearest_separation_px,
                rotation_deg: m.rotation_deg,
            })
            .map_err(io)?;
        }
    }
    out.flush().map_err(|e| DatasetError::io(path, e))?;
    Ok(with_record.len())
}
