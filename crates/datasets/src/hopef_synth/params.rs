//! The parameters of the HOPE-F process ([`HopefParams`]): the values the
//! dataset's scripts fix, and the values this generator chooses where they
//! are silent (marked "chosen" below; crates/datasets/README.md explains
//! each choice).

use crate::DatasetError;
use serde::{Deserialize, Serialize};

/// Parameters of the HOPE-F-faithful generator. Ranges `[min, max]` are
/// sampled uniformly unless a field says otherwise. Every field has a serde
/// default (the `hopef` preset), so a TOML file needs only the fields it
/// changes.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct HopefParams {
    /// Image size `[W, H]` in pixels. Default `[1024, 1024]` (HOPE-F's
    /// render resolution).
    pub image_size: [u32; 2],
    /// Sensor width in mm; the focal in pixels is `focal_mm / sensor_mm × W`
    /// and the principal point is `(W/2, H/2)` (Blender's K). Default 30.
    pub sensor_mm: f64,
    /// Lens focal length range in mm. Default `[24, 40]` (819.2–1365.3 px).
    pub focal_mm: [f64; 2],
    /// Camera distance from the world origin. Default `[3, 5]` units.
    pub camera_distance: [f64; 2],
    /// Camera tilt from the vertical, degrees (Blender rotation about x).
    /// Default `[25, 65]`.
    pub camera_tilt_deg: [f64; 2],
    /// Camera azimuth, degrees (Blender rotation about z). Default
    /// `[90, 270]`.
    pub camera_azimuth_deg: [f64; 2],
    /// The four base positions are `(±b, ±b)`; this is `b`. Default 0.5.
    pub base_offset: f64,
    /// Each object's position is its base position plus a uniform offset in
    /// `[−j, j]` per axis; this is `j`. Default 0.25.
    pub position_jitter: f64,
    /// Each object's yaw is uniform in `[−y, y]` degrees; this is `y`.
    /// Default 10.
    pub yaw_deg: f64,
    /// Probability that an object is a box (else a cylinder). Chosen;
    /// default 0.5.
    pub box_share: f64,
    /// Longest side of a box, units. Chosen; default `[0.4, 1.4]`.
    pub box_long_side: [f64; 2],
    /// Middle side of a box as a fraction of its longest. Chosen; default
    /// `[0.35, 1.0]`.
    pub box_middle_ratio: [f64; 2],
    /// Shortest side of a box as a fraction of its longest. Chosen; default
    /// `[0.2, 0.6]`.
    pub box_short_ratio: [f64; 2],
    /// Diameter of a cylinder, units. Chosen; default `[0.3, 0.7]`.
    pub cylinder_diameter: [f64; 2],
    /// Height of a cylinder, units. Chosen; default `[0.25, 1.4]`.
    pub cylinder_height: [f64; 2],
    /// Texture features per unit² of an object's surface, sampled
    /// log-uniformly per object. Chosen; default `[30, 1500]`.
    pub texture_density: [f64; 2],
    /// Per-face multiplier of the density (plain lids, printed sides).
    /// Chosen; default `[0.2, 1.0]`.
    pub face_texture: [f64; 2],
    /// Probability that a feature seen head-on is detected in a view.
    /// Chosen; default 0.8.
    pub repeatability: f64,
    /// Detection falls linearly from `repeatability` at `cos θ ≥ max` to 0
    /// at `cos θ ≤ min` (θ: angle between the surface normal and the line of
    /// sight). Chosen; default `[0.1, 0.4]`.
    pub grazing_cos: [f64; 2],
    /// Probability that a feature detected in both views is matched to
    /// itself and passes the ratio test. Chosen; default 0.85.
    pub match_rate: f64,
    /// Smallest keypoint scale in pixels (OpenCV's SIFT starts on the
    /// doubled image: 1.6 / 2). Chosen; default 0.8.
    pub keypoint_scale_px: f64,
    /// Keypoints per octave fall by this factor (an octave has a quarter of
    /// the pixels). Chosen; default 4.
    pub octave_decay: f64,
    /// Octaves above the smallest scale. Chosen; default 5.
    pub max_octaves: f64,
    /// Localisation error σ per coordinate and view, as a fraction of the
    /// keypoint's scale. Chosen; default 0.5.
    pub localisation: f64,
    /// Added to both coordinates of every keypoint: Blender's K puts the
    /// principal point at `W/2` in coordinates where pixel `i` spans
    /// `[i, i+1)`, OpenCV reports pixel centres at integers. Chosen;
    /// default −0.5.
    pub keypoint_offset_px: f64,
    /// Mismatches as a share of all matches, per scene. Chosen; default
    /// `[0.2, 0.55]`.
    pub mismatch_share: [f64; 2],
    /// Probability that a mismatch pairs a feature with one of the same
    /// object in image 2 (similar print); else with any object's. Chosen;
    /// default 0.5.
    pub same_object_mismatch: f64,
    /// Ratio-test threshold; `ratios` lie below it. Default 0.9.
    pub ratio_test: f64,
    /// Beta(a, b) of `ratio / ratio_test` for correct matches. Chosen;
    /// default `[2, 3]`.
    pub ratio_beta_correct: [f64; 2],
    /// Beta(a, b) of `ratio / ratio_test` for mismatches. Chosen; default
    /// `[5, 1.5]`.
    pub ratio_beta_mismatch: [f64; 2],
    /// Labelling band: a match gets the label of the object whose F has the
    /// smallest Sampson distance if that is below this, else 0. Default 2.0
    /// px.
    pub inlier_threshold_px: f64,
    /// A scene is kept only if every object has at least this many matches
    /// within the band of its F. Default 8 (HOPE-F: "more than 7").
    pub min_inliers_per_object: usize,
    /// Draws of a scene before giving up. Default 1000.
    pub max_attempts: u32,
}

impl Default for HopefParams {
    fn default() -> Self {
        Self {
            image_size: [1024, 1024],
            sensor_mm: 30.0,
            focal_mm: [24.0, 40.0],
            camera_distance: [3.0, 5.0],
            camera_tilt_deg: [25.0, 65.0],
            camera_azimuth_deg: [90.0, 270.0],
            base_offset: 0.5,
            position_jitter: 0.25,
            yaw_deg: 10.0,
            box_share: 0.5,
            box_long_side: [0.4, 1.4],
            box_middle_ratio: [0.35, 1.0],
            box_short_ratio: [0.2, 0.6],
            cylinder_diameter: [0.3, 0.7],
            cylinder_height: [0.25, 1.4],
            texture_density: [30.0, 1500.0],
            face_texture: [0.2, 1.0],
            repeatability: 0.8,
            grazing_cos: [0.1, 0.4],
            match_rate: 0.85,
            keypoint_scale_px: 0.8,
            octave_decay: 4.0,
            max_octaves: 5.0,
            localisation: 0.5,
            keypoint_offset_px: -0.5,
            mismatch_share: [0.2, 0.55],
            same_object_mismatch: 0.5,
            ratio_test: 0.9,
            ratio_beta_correct: [2.0, 3.0],
            ratio_beta_mismatch: [5.0, 1.5],
            inlier_threshold_px: 2.0,
            min_inliers_per_object: 8,
            max_attempts: 1000,
        }
    }
}

fn bad(field: &'static str, problem: String) -> Result<(), DatasetError> {
    Err(DatasetError::InvalidParams { field, problem })
}

/// `[lo, hi]` finite with `min <= lo <= hi <= max`.
fn range(field: &'static str, [lo, hi]: [f64; 2], min: f64, max: f64) -> Result<(), DatasetError> {
    if lo.is_finite() && hi.is_finite() && min <= lo && lo <= hi && hi <= max {
        Ok(())
    } else {
        bad(
            field,
            format!("[{lo}, {hi}] must be finite with {min} <= min <= max <= {max}"),
        )
    }
}

/// A single value `v` finite with `min <= v <= max`.
fn value(field: &'static str, v: f64, min: f64, max: f64) -> Result<(), DatasetError> {
    if v.is_finite() && min <= v && v <= max {
        Ok(())
    } else {
        bad(field, format!("{v} must be finite and in [{min}, {max}]"))
    }
}

impl HopefParams {
    /// Checks every field; [`DatasetError::InvalidParams`] names the first
    /// offending one.
    ///
    /// ```
    /// use datasets::hopef_synth::HopefParams;
    /// assert!(HopefParams::default().validate().is_ok());
    /// let bad = HopefParams { mismatch_share: [0.5, 0.2], ..HopefParams::default() };
    /// assert!(bad.validate().unwrap_err().to_string().contains("mismatch_share"));
    /// ```
    pub fn validate(&self) -> Result<(), DatasetError> {
        const POSITIVE: f64 = f64::MIN_POSITIVE;
        const BIG: f64 = f64::MAX;
        let [w, h] = self.image_size;
        if w < 16 || h < 16 {
            return bad(
                "image_size",
                format!("{w} x {h} is too small (16 x 16 at least)"),
            );
        }
        value("sensor_mm", self.sensor_mm, POSITIVE, BIG)?;
        range("focal_mm", self.focal_mm, POSITIVE, BIG)?;
        range("camera_distance", self.camera_distance, POSITIVE, BIG)?;
        range("camera_tilt_deg", self.camera_tilt_deg, 0.0, 89.0)?;
        range("camera_azimuth_deg", self.camera_azimuth_deg, -360.0, 720.0)?;
        value("base_offset", self.base_offset, 0.0, BIG)?;
        value("position_jitter", self.position_jitter, 0.0, BIG)?;
        value("yaw_deg", self.yaw_deg, 0.0, 180.0)?;
        value("box_share", self.box_share, 0.0, 1.0)?;
        range("box_long_side", self.box_long_side, POSITIVE, BIG)?;
        range("box_middle_ratio", self.box_middle_ratio, POSITIVE, 1.0)?;
        range("box_short_ratio", self.box_short_ratio, POSITIVE, 1.0)?;
        range("cylinder_diameter", self.cylinder_diameter, POSITIVE, BIG)?;
        range("cylinder_height", self.cylinder_height, POSITIVE, BIG)?;
        range("texture_density", self.texture_density, POSITIVE, 1e6)?;
        range("face_texture", self.face_texture, 0.0, 1.0)?;
        value("repeatability", self.repeatability, POSITIVE, 1.0)?;
        range("grazing_cos", self.grazing_cos, 0.0, 1.0)?;
        if self.grazing_cos[0] == self.grazing_cos[1] {
            return bad(
                "grazing_cos",
                format!("{:?} must have min < max", self.grazing_cos),
            );
        }
        value("match_rate", self.match_rate, POSITIVE, 1.0)?;
        value("keypoint_scale_px", self.keypoint_scale_px, 0.0, BIG)?;
        value("octave_decay", self.octave_decay, 1.0 + 1e-9, BIG)?;
        value("max_octaves", self.max_octaves, 0.0, 20.0)?;
        value("localisation", self.localisation, 0.0, BIG)?;
        value("keypoint_offset_px", self.keypoint_offset_px, -1.0, 1.0)?;
        range("mismatch_share", self.mismatch_share, 0.0, 0.9)?;
        value("same_object_mismatch", self.same_object_mismatch, 0.0, 1.0)?;
        value("ratio_test", self.ratio_test, POSITIVE, 1.0)?;
        for (field, [a, b]) in [
            ("ratio_beta_correct", self.ratio_beta_correct),
            ("ratio_beta_mismatch", self.ratio_beta_mismatch),
        ] {
            value(field, a, POSITIVE, 1e6)?;
            value(field, b, POSITIVE, 1e6)?;
        }
        value(
            "inlier_threshold_px",
            self.inlier_threshold_px,
            POSITIVE,
            BIG,
        )?;
        if self.min_inliers_per_object < 8 {
            return bad(
                "min_inliers_per_object",
                format!("{} must be at least 8", self.min_inliers_per_object),
            );
        }
        if self.max_attempts == 0 {
            return bad("max_attempts", "must be at least 1".into());
        }
        Ok(())
    }

    /// The focal length range in pixels, `focal_mm / sensor_mm × W`.
    ///
    /// ```
    /// let [lo, hi] = datasets::hopef_synth::HopefParams::default().focal_px();
    /// assert!((lo - 819.2).abs() < 1e-9 && (hi - 4096.0 / 3.0).abs() < 1e-9);
    /// ```
    pub fn focal_px(&self) -> [f64; 2] {
        let scale = f64::from(self.image_size[0]) / self.sensor_mm;
        [self.focal_mm[0] * scale, self.focal_mm[1] * scale]
    }
}
