//! A seeded generator of HOPE-F-like two-view scenes: one pinhole camera,
//! k independently moving rigid objects, optional static background under
//! camera ego-motion, pixel noise and gross outliers, with full ground truth
//! (labels, F per motion, K).
//!
//! Model. Camera 1 is `P1 = K [I | 0]` with `K = [[f, 0, cx], [0, f, cy],
//! [0, 0, 1]]`. Camera 2 is `P2 = K [R_e | t_e]` (the ego-motion; identity
//! and zero unless a background is generated). Object j, with centre `c_j`,
//! moves rigidly between the views, `X' = R_j (X − c_j) + c_j + t_j`, so in
//! camera-2 coordinates `X₂ = R X + T` with `R = R_e R_j` and
//! `T = R_e (c_j − R_j c_j + t_j) + t_e`, and its fundamental matrix is
//! `F = K⁻ᵀ [T]ₓ R K⁻¹` (Hartley & Zisserman, Eq. 9.12), scaled to unit
//! Frobenius norm, with `x₂ᵀ F x₁ = 0`. The background has `R = R_e`,
//! `T = t_e`.
//!
//! Placement. The image is divided into a grid of `ceil(√k)` columns and
//! `ceil(k / columns)` rows; each object gets its own cell, a depth, and a
//! size such that its bounding sphere projects to a fraction
//! [`SyntheticParams::object_extent`] of the cell, which keeps objects
//! apart in image 1 and makes each large enough to segment.
//!
//! Noise. Each inlier match `(x1, y1, x2, y2)` gets a Gaussian 4-vector of
//! standard deviation σ per coordinate, redrawn while its length exceeds
//! [`SyntheticParams::noise_truncation`] σ (default 3): the Sampson distance
//! of a match to its true F is, to first order, the projection of that
//! vector on the unit gradient of `x₂ᵀ F x₁`, so it stays below 3σ. Matches
//! outside either image (`0 ≤ x ≤ W−1`, `0 ≤ y ≤ H−1`) are dropped. Gross
//! outliers are independent uniform points in the two images, labelled 0.
//!
//! Files: the parameters, scenes and entry points here; the random draws
//! and the camera in [`sampling`](self) (`sampling.rs`), the generation
//! phases in `generate.rs`, the named presets in `presets.rs` and the
//! HOPE-F layout writer in `write.rs`. The driving scenes of the
//! `kitti-real` preset (real image size, N 1 000–5 000, separable cars) have
//! their own generator ([`generate_driving_scene`], `driving.rs`) and
//! parameters ([`DrivingParams`], `driving_params.rs`). The randomised
//! families, whose every difficulty is drawn per scene and recorded
//! ([`SceneRecord`], `record.rs`): `driving-random`
//! ([`generate_driving_random_scene`], `driving_random.rs`,
//! `driving_random_params.rs`) and `objects-3d`
//! ([`generate_objects3d_scene`], `objects3d.rs`, `objects3d_params.rs`,
//! `surfaces.rs`).

mod driving;
mod driving_params;
mod driving_random;
mod driving_random_params;
mod generate;
mod objects3d;
mod objects3d_params;
mod presets;
mod record;
mod sampling;
mod surfaces;
mod write;

pub use driving::{generate_driving_scene, CAR_ATTEMPTS, LAYOUT_ATTEMPTS};
pub use driving_params::{DrivingParams, MAX_CARS};
pub use driving_random::{generate_driving_random_scene, MAX_SCALE, MAX_TURN_DEG};
pub use driving_random_params::{DrivingRandomParams, MAX_MOVERS};
pub use generate::MAX_OBJECTS;
pub use objects3d::{generate_objects3d_scene, OBJECT_ATTEMPTS, SCENE_ATTEMPTS};
pub use objects3d_params::{Objects3dParams, SurfaceMix, MAX_OBJECTS_3D};
pub use presets::{Preset, PresetParams};
pub use record::{write_records_csv, MotionKind, MotionRecord, SceneRecord, RECORDS_FILE};
pub(crate) use sampling::{fundamental, uniform};
pub(crate) use write::write_npz_file;
pub use write::{write_hopef_layout, write_hopef_layout_with, write_hopef_scene};

use crate::hopef::scene_name;
use crate::hopef_synth::HopefTruth;
use crate::{DatasetError, Scene};
use generate::generate;
use nalgebra::{Matrix3, Vector3};
use serde::{Deserialize, Serialize};

/// Relative frequencies of the object shapes (need not sum to 1).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ShapeMix {
    /// Points on the six faces of a box (planar patches, like man-made
    /// objects). Default 0.5.
    pub boxes: f64,
    /// Points on the side and caps of a cylinder. Default 0.3.
    pub cylinders: f64,
    /// Points filling an ellipsoid (a general 3-D cloud). Default 0.2.
    pub clouds: f64,
}

impl Default for ShapeMix {
    fn default() -> Self {
        Self {
            boxes: 0.5,
            cylinders: 0.3,
            clouds: 0.2,
        }
    }
}

/// The static background of the KITTI-like mode, seen under camera
/// ego-motion; it is motion label 1 and the objects are 2..k+1.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct BackgroundParams {
    /// Generate a background. Default false.
    pub enabled: bool,
    /// Number of background points before occlusion and clipping,
    /// `[min, max]`. Default `[150, 250]`.
    pub points: [usize; 2],
    /// Depth range of background points (scene units; objects are at
    /// [`SyntheticParams::depth_range`]). Default `[20, 40]`.
    pub depth_range: [f64; 2],
    /// Ego-rotation angle range in degrees (random axis). Default `[0, 3]`.
    pub ego_rotation_deg: [f64; 2],
    /// Ego-translation length range (scene units, random direction biased
    /// forward). Default `[0.4, 1.0]`.
    pub ego_translation: [f64; 2],
}

impl Default for BackgroundParams {
    fn default() -> Self {
        Self {
            enabled: false,
            points: [150, 250],
            depth_range: [20.0, 40.0],
            ego_rotation_deg: [0.0, 3.0],
            ego_translation: [0.4, 1.0],
        }
    }
}

/// Parameters of the generator. Ranges `[min, max]` are sampled uniformly.
/// Every field has a serde default, so a TOML file needs only the fields it
/// changes.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SyntheticParams {
    /// Image width W in pixels. Default 1024.
    pub image_width: u32,
    /// Image height H in pixels. Default 768.
    pub image_height: u32,
    /// Focal length range in pixels. Default `[500, 1500]`.
    pub focal_range: [f64; 2],
    /// Largest offset of the principal point from the image centre
    /// ((W−1)/2, (H−1)/2), per axis, in pixels. Default 10.
    pub principal_point_jitter: f64,
    /// Mix of object shapes. Default boxes 0.5, cylinders 0.3, clouds 0.2.
    pub shape_mix: ShapeMix,
    /// Points sampled per object before clipping. Default `[50, 150]`.
    pub points_per_object: [usize; 2],
    /// Fewest points an object may keep after clipping; the object is
    /// redrawn otherwise. Default 30.
    pub min_points_per_object: usize,
    /// Depth of object centres in camera 1 (scene units). Default `[6, 10]`.
    pub depth_range: [f64; 2],
    /// Projected diameter of an object's bounding sphere as a fraction of
    /// the smaller side of its grid cell. Default `[0.45, 0.7]`.
    pub object_extent: [f64; 2],
    /// Object rotation angle between the views, degrees (random axis
    /// through the object centre). Default `[3, 20]`.
    pub rotation_deg: [f64; 2],
    /// Object translation between the views as a fraction of its depth
    /// (random direction). Default `[0.03, 0.1]`.
    pub translation: [f64; 2],
    /// Pixel noise σ per coordinate. Default 0.5.
    pub noise_sigma: f64,
    /// Noise vectors longer than this many σ are redrawn (0 = no
    /// truncation). Default 3.
    pub noise_truncation: f64,
    /// Fraction of the final matches that are gross outliers. Default 0.2.
    pub outlier_fraction: f64,
    /// Static background under ego-motion. Default off.
    pub background: BackgroundParams,
}

impl Default for SyntheticParams {
    fn default() -> Self {
        Self {
            image_width: 1024,
            image_height: 768,
            focal_range: [500.0, 1500.0],
            principal_point_jitter: 10.0,
            shape_mix: ShapeMix::default(),
            points_per_object: [50, 150],
            min_points_per_object: 30,
            depth_range: [6.0, 10.0],
            object_extent: [0.45, 0.7],
            rotation_deg: [3.0, 20.0],
            translation: [0.03, 0.1],
            noise_sigma: 0.5,
            noise_truncation: 3.0,
            outlier_fraction: 0.2,
            background: BackgroundParams::default(),
        }
    }
}

impl SyntheticParams {
    /// Checks every range and value; [`DatasetError::InvalidParams`] names
    /// the first offending field.
    pub fn validate(&self) -> Result<(), DatasetError> {
        self.validate_geometry()?;
        self.validate_counts()?;
        self.validate_noise()?;
        self.shape_mix.validate()?;
        if self.background.enabled {
            self.background.validate()?;
        }
        Ok(())
    }

    /// The image, the camera, the objects' sizes and motions.
    fn validate_geometry(&self) -> Result<(), DatasetError> {
        if self.image_width < 16 || self.image_height < 16 {
            return bad(
                "image_width",
                format!(
                    "{} x {} is too small (16 x 16 at least)",
                    self.image_width, self.image_height
                ),
            );
        }
        range("focal_range", self.focal_range, f64::MIN_POSITIVE)?;
        range("depth_range", self.depth_range, f64::MIN_POSITIVE)?;
        range("object_extent", self.object_extent, f64::MIN_POSITIVE)?;
        if self.object_extent[1] > 1.0 {
            return bad(
                "object_extent",
                format!(
                    "{} exceeds 1 (objects would overlap)",
                    self.object_extent[1]
                ),
            );
        }
        range("rotation_deg", self.rotation_deg, 0.0)?;
        range("translation", self.translation, 0.0)?;
        if self.rotation_deg[0] == 0.0 && self.translation[0] == 0.0 {
            return bad(
                "translation",
                "with a zero minimum rotation the minimum translation must be positive (F needs a translation)".into(),
            );
        }
        Ok(())
    }

    /// Points per object and the minimum kept in view.
    fn validate_counts(&self) -> Result<(), DatasetError> {
        let [lo, hi] = self.points_per_object;
        if lo < 8 || lo > hi {
            return bad(
                "points_per_object",
                format!("[{lo}, {hi}] needs 8 <= min <= max"),
            );
        }
        if self.min_points_per_object < 8 || self.min_points_per_object > hi {
            return bad(
                "min_points_per_object",
                format!(
                    "{} must be in [8, points_per_object max = {hi}]",
                    self.min_points_per_object
                ),
            );
        }
        Ok(())
    }

    /// Principal-point jitter, pixel noise and the outlier fraction.
    fn validate_noise(&self) -> Result<(), DatasetError> {
        for (field, v) in [
            ("principal_point_jitter", self.principal_point_jitter),
            ("noise_sigma", self.noise_sigma),
            ("noise_truncation", self.noise_truncation),
        ] {
            if !(v.is_finite() && v >= 0.0) {
                return bad(field, format!("{v} must be finite and >= 0"));
            }
        }
        if self.noise_truncation > 0.0 && self.noise_truncation < 1.0 {
            return bad(
                "noise_truncation",
                format!("{} must be 0 (off) or >= 1", self.noise_truncation),
            );
        }
        if !(0.0..0.9).contains(&self.outlier_fraction) {
            return bad(
                "outlier_fraction",
                format!("{} must be in [0, 0.9)", self.outlier_fraction),
            );
        }
        Ok(())
    }
}

impl ShapeMix {
    /// Weights ≥ 0 with a positive sum.
    fn validate(&self) -> Result<(), DatasetError> {
        let weights = [self.boxes, self.cylinders, self.clouds];
        if weights.iter().any(|w| !(w.is_finite() && *w >= 0.0))
            || weights.iter().sum::<f64>() <= 0.0
        {
            return bad(
                "shape_mix",
                format!("{weights:?} must be >= 0 with a positive sum"),
            );
        }
        Ok(())
    }
}

impl BackgroundParams {
    /// The point count and the depth and ego-motion ranges.
    fn validate(&self) -> Result<(), DatasetError> {
        let [lo, hi] = self.points;
        if lo < 8 || lo > hi {
            return bad(
                "background.points",
                format!("[{lo}, {hi}] needs 8 <= min <= max"),
            );
        }
        range(
            "background.depth_range",
            self.depth_range,
            f64::MIN_POSITIVE,
        )?;
        range("background.ego_rotation_deg", self.ego_rotation_deg, 0.0)?;
        range(
            "background.ego_translation",
            self.ego_translation,
            f64::MIN_POSITIVE,
        )
    }
}

/// [`DatasetError::InvalidParams`] for `field`.
fn bad(field: &'static str, problem: String) -> Result<(), DatasetError> {
    Err(DatasetError::InvalidParams { field, problem })
}

/// A finite range `[lo, hi]` with `min <= lo <= hi`.
fn range(field: &'static str, [lo, hi]: [f64; 2], min: f64) -> Result<(), DatasetError> {
    if lo.is_finite() && hi.is_finite() && lo >= min && lo <= hi {
        Ok(())
    } else {
        bad(
            field,
            format!("[{lo}, {hi}] must be finite with {min} <= min <= max"),
        )
    }
}

/// A generated scene with the camera data that the HOPE-F layout stores.
#[derive(Debug, Clone, PartialEq)]
pub struct SyntheticScene {
    /// HOPE-F category folder (the number of objects).
    pub category: u32,
    /// HOPE-F scene folder index.
    pub index: u32,
    /// The scene (named `<category>/<NNNN>`).
    pub scene: Scene,
    /// Intrinsics K of both views.
    pub intrinsics: Matrix3<f64>,
    /// Camera ego-rotation `R_e` (identity without background).
    pub ego_rotation: Matrix3<f64>,
    /// Camera ego-translation `t_e` (zero without background).
    pub ego_translation: Vector3<f64>,
    /// The HOPE-F-faithful generator's record (`hopef` preset); `None` for
    /// the scenes of [`generate_hopef_scene`].
    pub hopef: Option<HopefTruth>,
    /// The drawn difficulty of a scene of the randomised families
    /// (`driving-random`, `objects-3d`); `None` for the other presets.
    pub record: Option<SceneRecord>,
}

/// The seed of scene `(category, index)` of a dataset generated with
/// `seed`: a SplitMix64 mix, so each scene is reproducible on its own,
/// independent of generation order.
///
/// ```
/// use datasets::synthetic::scene_seed;
/// assert_eq!(scene_seed(1, 2, 900), scene_seed(1, 2, 900));
/// assert_ne!(scene_seed(1, 2, 900), scene_seed(1, 2, 901));
/// assert_ne!(scene_seed(1, 2, 900), scene_seed(2, 2, 900));
/// ```
pub fn scene_seed(seed: u64, category: u32, index: u32) -> u64 {
    fn splitmix64(mut z: u64) -> u64 {
        z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    splitmix64(seed ^ splitmix64((u64::from(category) << 32) | u64::from(index)))
}

/// Generates one scene with `num_objects` moving objects (1 ≤ k ≤ 16) from
/// `seed`; the same arguments always give the same scene.
///
/// ```
/// use datasets::synthetic::{generate_scene, SyntheticParams};
/// let params = SyntheticParams::default();
/// let scene = generate_scene(&params, 42, 3, "demo")?;
/// assert_eq!(scene.num_motions(), 3);
/// assert_eq!(scene.gt_fundamentals.len(), 3);
/// assert_eq!(scene, generate_scene(&params, 42, 3, "demo")?);
/// // 20 % of the matches are outliers (rounded).
/// let outliers = scene.num_outliers() as f64 / scene.len() as f64;
/// assert!((outliers - 0.2).abs() < 0.01);
/// # Ok::<(), datasets::DatasetError>(())
/// ```
pub fn generate_scene(
    params: &SyntheticParams,
    seed: u64,
    num_objects: usize,
    name: &str,
) -> Result<Scene, DatasetError> {
    generate(params, seed, num_objects, name).map(|g| g.scene)
}

/// Generates scene `<category>/<index>` of a HOPE-F-layout dataset: `category`
/// objects, seeded with [`scene_seed`]`(seed, category, index)`.
pub fn generate_hopef_scene(
    params: &SyntheticParams,
    seed: u64,
    category: u32,
    index: u32,
) -> Result<SyntheticScene, DatasetError> {
    let generated = generate(
        params,
        scene_seed(seed, category, index),
        category as usize,
        &scene_name(category, index),
    )?;
    Ok(SyntheticScene {
        category,
        index,
        scene: generated.scene,
        intrinsics: generated.intrinsics,
        ego_rotation: generated.ego.rotation,
        ego_translation: generated.ego.translation,
        hopef: None,
        record: None,
    })
}
