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

use crate::hopef::{scene_name, CAMERA_FILE, FEATURES_FILE};
use crate::hopef_synth::{self, HopefParams, HopefTruth};
use crate::npz::{write_npz, NpyArray};
use crate::{DatasetError, Scene};
use nalgebra::{Matrix3, Rotation3, Unit, Vector3};
use rand::seq::SliceRandom;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};
use serde::{Deserialize, Serialize};
use std::path::Path;

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
        let bad = |field: &'static str, problem: String| {
            Err(DatasetError::InvalidParams { field, problem })
        };
        let range = |field: &'static str, [lo, hi]: [f64; 2], min: f64| {
            if lo.is_finite() && hi.is_finite() && lo >= min && lo <= hi {
                Ok(())
            } else {
                bad(
                    field,
                    format!("[{lo}, {hi}] must be finite with {min} <= min <= max"),
                )
            }
        };
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
        let mix = self.shape_mix;
        let weights = [mix.boxes, mix.cylinders, mix.clouds];
        if weights.iter().any(|w| !(w.is_finite() && *w >= 0.0))
            || weights.iter().sum::<f64>() <= 0.0
        {
            return bad(
                "shape_mix",
                format!("{weights:?} must be >= 0 with a positive sum"),
            );
        }
        let bg = &self.background;
        if bg.enabled {
            let [lo, hi] = bg.points;
            if lo < 8 || lo > hi {
                return bad(
                    "background.points",
                    format!("[{lo}, {hi}] needs 8 <= min <= max"),
                );
            }
            range("background.depth_range", bg.depth_range, f64::MIN_POSITIVE)?;
            range("background.ego_rotation_deg", bg.ego_rotation_deg, 0.0)?;
            range(
                "background.ego_translation",
                bg.ego_translation,
                f64::MIN_POSITIVE,
            )?;
        }
        Ok(())
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
        ego_rotation: generated.ego_rotation,
        ego_translation: generated.ego_translation,
        hopef: None,
    })
}

struct Generated {
    scene: Scene,
    intrinsics: Matrix3<f64>,
    ego_rotation: Matrix3<f64>,
    ego_translation: Vector3<f64>,
}

/// The most objects a scene may have.
pub const MAX_OBJECTS: usize = 16;

/// Attempts to place one object before giving up.
const PLACEMENT_ATTEMPTS: usize = 200;

/// A match before noise: 3-D point seen in both views, with its label.
struct Track {
    p1: [f64; 2],
    p2: [f64; 2],
    label: i32,
}

/// A uniform draw from `[lo, hi]` (`lo` when the range is empty).
pub(crate) fn uniform(rng: &mut ChaCha8Rng, [lo, hi]: [f64; 2]) -> f64 {
    if hi > lo {
        rng.gen_range(lo..=hi)
    } else {
        lo
    }
}

fn uniform_count(rng: &mut ChaCha8Rng, [lo, hi]: [usize; 2]) -> usize {
    rng.gen_range(lo..=hi)
}

fn random_unit(rng: &mut ChaCha8Rng) -> Unit<Vector3<f64>> {
    loop {
        let v = Vector3::new(
            StandardNormal.sample(rng),
            StandardNormal.sample(rng),
            StandardNormal.sample(rng),
        );
        if v.norm() > 1e-6 {
            return Unit::new_normalize(v);
        }
    }
}

fn random_rotation(rng: &mut ChaCha8Rng, degrees: [f64; 2]) -> Rotation3<f64> {
    let axis = random_unit(rng);
    Rotation3::from_axis_angle(&axis, uniform(rng, degrees).to_radians())
}

/// `[v]ₓ`, the cross-product matrix.
fn skew(v: &Vector3<f64>) -> Matrix3<f64> {
    Matrix3::new(0.0, -v.z, v.y, v.z, 0.0, -v.x, -v.y, v.x, 0.0)
}

/// `F = K⁻ᵀ [T]ₓ R K⁻¹` scaled to unit Frobenius norm (`x₂ᵀ F x₁ = 0` for
/// `X₂ = R X₁ + T`; Hartley & Zisserman Eq. 9.12).
pub(crate) fn fundamental(
    k_inv: &Matrix3<f64>,
    r: &Matrix3<f64>,
    t: &Vector3<f64>,
) -> Matrix3<f64> {
    let f = k_inv.transpose() * skew(t) * r * k_inv;
    f / f.norm()
}

fn project(k: &Matrix3<f64>, x: &Vector3<f64>) -> Option<[f64; 2]> {
    if x.z <= 1e-9 {
        return None;
    }
    let p = k * x;
    Some([p.x / p.z, p.y / p.z])
}

/// Shape-local points (bounding sphere of diameter `size` about the origin).
fn sample_shape(rng: &mut ChaCha8Rng, mix: &ShapeMix, n: usize, size: f64) -> Vec<Vector3<f64>> {
    let total = mix.boxes + mix.cylinders + mix.clouds;
    let pick = rng.gen_range(0.0..total);
    let radius = size / 2.0;
    if pick < mix.boxes {
        // Box with random proportions scaled so its half-diagonal is `radius`.
        let dims = Vector3::<f64>::new(
            rng.gen_range(0.5..1.0),
            rng.gen_range(0.5..1.0),
            rng.gen_range(0.5..1.0),
        );
        let dims = dims * (2.0 * radius / dims.norm());
        let areas = [dims.y * dims.z, dims.x * dims.z, dims.x * dims.y];
        let area_sum: f64 = areas.iter().sum();
        (0..n)
            .map(|_| {
                let a = rng.gen_range(0.0..area_sum);
                let axis = if a < areas[0] {
                    0
                } else if a < areas[0] + areas[1] {
                    1
                } else {
                    2
                };
                let mut p = Vector3::new(
                    rng.gen_range(-0.5..0.5) * dims.x,
                    rng.gen_range(-0.5..0.5) * dims.y,
                    rng.gen_range(-0.5..0.5) * dims.z,
                );
                p[axis] = if rng.gen_bool(0.5) { 0.5 } else { -0.5 } * dims[axis];
                p
            })
            .collect()
    } else if pick < mix.boxes + mix.cylinders {
        // Cylinder along z: radius r, height h, with r² + (h/2)² = radius².
        let aspect: f64 = rng.gen_range(0.6..1.6); // h / (2 r)
        let r = radius / (1.0 + aspect * aspect).sqrt();
        let h = 2.0 * r * aspect;
        let side = 2.0 * std::f64::consts::PI * r * h;
        let caps = 2.0 * std::f64::consts::PI * r * r;
        (0..n)
            .map(|_| {
                let theta = rng.gen_range(0.0..std::f64::consts::TAU);
                if rng.gen_range(0.0..side + caps) < side {
                    Vector3::new(
                        r * theta.cos(),
                        r * theta.sin(),
                        rng.gen_range(-0.5..0.5) * h,
                    )
                } else {
                    let rho = r * rng.gen::<f64>().sqrt();
                    let z = if rng.gen_bool(0.5) { 0.5 } else { -0.5 } * h;
                    Vector3::new(rho * theta.cos(), rho * theta.sin(), z)
                }
            })
            .collect()
    } else {
        // Ellipsoid filled uniformly; semi-axes at most `radius`.
        let axes = Vector3::new(
            rng.gen_range(0.6..1.0),
            rng.gen_range(0.6..1.0),
            rng.gen_range(0.6..1.0),
        ) * radius;
        (0..n)
            .map(|_| {
                let dir = random_unit(rng).into_inner();
                let rho = rng.gen::<f64>().cbrt();
                dir.component_mul(&axes) * rho
            })
            .collect()
    }
}

struct Camera {
    k: Matrix3<f64>,
    k_inv: Matrix3<f64>,
    focal: f64,
    width: f64,
    height: f64,
}

impl Camera {
    fn inside(&self, p: [f64; 2]) -> bool {
        (0.0..=self.width - 1.0).contains(&p[0]) && (0.0..=self.height - 1.0).contains(&p[1])
    }

    fn back_project(&self, pixel: [f64; 2], depth: f64) -> Vector3<f64> {
        self.k_inv * Vector3::new(pixel[0], pixel[1], 1.0) * depth
    }
}

/// The camera-2 image of a point `x` (camera-1 coordinates) that moves by
/// `(R, T)` in camera-2 coordinates.
fn view2(cam: &Camera, r: &Matrix3<f64>, t: &Vector3<f64>, x: &Vector3<f64>) -> Option<[f64; 2]> {
    project(&cam.k, &(r * x + t))
}

/// One object in its grid cell: its tracks, `(R, T)` and image-1 bounding box.
fn place_object(
    rng: &mut ChaCha8Rng,
    params: &SyntheticParams,
    cam: &Camera,
    cell: ([f64; 2], [f64; 2]),
    ego: (&Matrix3<f64>, &Vector3<f64>),
    label: i32,
) -> Option<(Vec<Track>, Matrix3<f64>, Vector3<f64>)> {
    let (cell_min, cell_max) = cell;
    let cell_w = cell_max[0] - cell_min[0];
    let cell_h = cell_max[1] - cell_min[1];
    let extent_px = uniform(rng, params.object_extent) * cell_w.min(cell_h);
    let margin_x = ((cell_w - extent_px) / 2.0).max(0.0) * 0.8;
    let margin_y = ((cell_h - extent_px) / 2.0).max(0.0) * 0.8;
    let centre_px = [
        (cell_min[0] + cell_max[0]) / 2.0 + rng.gen_range(-1.0..=1.0) * margin_x,
        (cell_min[1] + cell_max[1]) / 2.0 + rng.gen_range(-1.0..=1.0) * margin_y,
    ];
    let depth = uniform(rng, params.depth_range);
    let centre = cam.back_project(centre_px, depth);
    let size = extent_px * depth / cam.focal;
    let n = uniform_count(rng, params.points_per_object);
    let orientation = random_rotation(rng, [0.0, 180.0]);
    let local = sample_shape(rng, &params.shape_mix, n, size);
    let rotation = random_rotation(rng, params.rotation_deg);
    let translation = random_unit(rng).into_inner() * uniform(rng, params.translation) * depth;
    // X₂ = R_e (R_j (X − c) + c + t_j) + t_e = R X + T.
    let (r_e, t_e) = ego;
    let r = r_e * rotation.matrix();
    let t = r_e * (centre - rotation * centre + translation) + t_e;
    let mut tracks = Vec::with_capacity(n);
    for p in &local {
        let x = orientation * p + centre;
        if let (Some(p1), Some(p2)) = (project(&cam.k, &x), view2(cam, &r, &t, &x)) {
            if cam.inside(p1) && cam.inside(p2) {
                tracks.push(Track { p1, p2, label });
            }
        }
    }
    (tracks.len() >= params.min_points_per_object).then_some((tracks, r, t))
}

fn generate(
    params: &SyntheticParams,
    seed: u64,
    num_objects: usize,
    name: &str,
) -> Result<Generated, DatasetError> {
    params.validate()?;
    if !(1..=MAX_OBJECTS).contains(&num_objects) {
        return Err(DatasetError::InvalidParams {
            field: "num_objects",
            problem: format!("{num_objects} is not in 1..={MAX_OBJECTS}"),
        });
    }
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let width = f64::from(params.image_width);
    let height = f64::from(params.image_height);
    let focal = uniform(&mut rng, params.focal_range);
    let jitter = params.principal_point_jitter;
    let principal_point = [
        (width - 1.0) / 2.0 + rng.gen_range(-1.0..=1.0) * jitter,
        (height - 1.0) / 2.0 + rng.gen_range(-1.0..=1.0) * jitter,
    ];
    let k = Matrix3::new(
        focal,
        0.0,
        principal_point[0],
        0.0,
        focal,
        principal_point[1],
        0.0,
        0.0,
        1.0,
    );
    let k_inv = k.try_inverse().ok_or_else(|| DatasetError::Generation {
        scene: name.to_string(),
        problem: "singular intrinsics".into(),
    })?;
    let cam = Camera {
        k,
        k_inv,
        focal,
        width,
        height,
    };

    let background = params.background.enabled;
    let (ego_rotation, ego_translation) = if background {
        let r = random_rotation(&mut rng, params.background.ego_rotation_deg);
        // Mostly forward motion, as a driving camera.
        let mut dir = random_unit(&mut rng).into_inner();
        dir.z = dir.z.abs() + 1.0;
        let t = dir.normalize() * uniform(&mut rng, params.background.ego_translation);
        (*r.matrix(), t)
    } else {
        (Matrix3::identity(), Vector3::zeros())
    };

    // Grid cells, one per object, in random order.
    let cols = (num_objects as f64).sqrt().ceil() as usize;
    let rows = num_objects.div_ceil(cols);
    let mut cells: Vec<([f64; 2], [f64; 2])> = (0..rows * cols)
        .map(|c| {
            let (i, j) = (c % cols, c / cols);
            let (cw, ch) = (width / cols as f64, height / rows as f64);
            (
                [i as f64 * cw, j as f64 * ch],
                [(i + 1) as f64 * cw, (j + 1) as f64 * ch],
            )
        })
        .collect();
    cells.shuffle(&mut rng);

    let first_object_label = if background { 2 } else { 1 };
    let mut fundamentals = Vec::with_capacity(num_objects + usize::from(background));
    if background {
        fundamentals.push(fundamental(&k_inv, &ego_rotation, &ego_translation));
    }
    let mut tracks: Vec<Track> = Vec::new();
    let mut boxes: Vec<([f64; 2], [f64; 2])> = Vec::new();
    for (j, &cell) in cells.iter().take(num_objects).enumerate() {
        let label = first_object_label + j as i32;
        let placed = (0..PLACEMENT_ATTEMPTS).find_map(|_| {
            place_object(
                &mut rng,
                params,
                &cam,
                cell,
                (&ego_rotation, &ego_translation),
                label,
            )
        });
        let Some((object, r, t)) = placed else {
            return Err(DatasetError::Generation {
                scene: name.to_string(),
                problem: format!(
                    "object {} kept fewer than {} points in view after {PLACEMENT_ATTEMPTS} attempts",
                    j + 1,
                    params.min_points_per_object
                ),
            });
        };
        fundamentals.push(fundamental(&k_inv, &r, &t));
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for tr in &object {
            for a in 0..2 {
                lo[a] = lo[a].min(tr.p1[a]);
                hi[a] = hi[a].max(tr.p1[a]);
            }
        }
        boxes.push((lo, hi));
        tracks.extend(object);
    }

    if background {
        // Static points at background depths, hidden where an object covers them in image 1.
        let bg = &params.background;
        let n = uniform_count(&mut rng, bg.points);
        let pad = 10.0;
        for _ in 0..n {
            let pixel = [
                rng.gen_range(0.0..=width - 1.0),
                rng.gen_range(0.0..=height - 1.0),
            ];
            let occluded = boxes.iter().any(|(lo, hi)| {
                (lo[0] - pad..=hi[0] + pad).contains(&pixel[0])
                    && (lo[1] - pad..=hi[1] + pad).contains(&pixel[1])
            });
            if occluded {
                continue;
            }
            let x = cam.back_project(pixel, uniform(&mut rng, bg.depth_range));
            if let Some(p2) = view2(&cam, &ego_rotation, &ego_translation, &x) {
                if cam.inside(p2) {
                    tracks.push(Track {
                        p1: pixel,
                        p2,
                        label: 1,
                    });
                }
            }
        }
    }

    // Noise, then clipping to both images.
    let sigma = params.noise_sigma;
    let limit = params.noise_truncation * sigma;
    let mut points1 = Vec::with_capacity(tracks.len());
    let mut points2 = Vec::with_capacity(tracks.len());
    let mut labels = Vec::with_capacity(tracks.len());
    for tr in &tracks {
        let noise = loop {
            let v: [f64; 4] = std::array::from_fn(|_| {
                let z: f64 = StandardNormal.sample(&mut rng);
                z * sigma
            });
            if limit == 0.0 || v.iter().map(|x| x * x).sum::<f64>() <= limit * limit {
                break v;
            }
        };
        let p1 = [tr.p1[0] + noise[0], tr.p1[1] + noise[1]];
        let p2 = [tr.p2[0] + noise[2], tr.p2[1] + noise[3]];
        if cam.inside(p1) && cam.inside(p2) {
            points1.push(p1);
            points2.push(p2);
            labels.push(tr.label);
        }
    }

    // Gross outliers: a fraction `q` of the final total, so n_out = q n_in / (1 − q).
    let q = params.outlier_fraction;
    let n_out = (q * labels.len() as f64 / (1.0 - q)).round() as usize;
    for _ in 0..n_out {
        points1.push([
            rng.gen_range(0.0..=width - 1.0),
            rng.gen_range(0.0..=height - 1.0),
        ]);
        points2.push([
            rng.gen_range(0.0..=width - 1.0),
            rng.gen_range(0.0..=height - 1.0),
        ]);
        labels.push(0);
    }

    // Shuffle so that labels are not grouped.
    let mut order: Vec<usize> = (0..labels.len()).collect();
    order.shuffle(&mut rng);
    let scene = Scene {
        name: name.to_string(),
        points1: order.iter().map(|&i| points1[i]).collect(),
        points2: order.iter().map(|&i| points2[i]).collect(),
        labels: Some(order.iter().map(|&i| labels[i]).collect()),
        image_size: (params.image_width, params.image_height),
        principal_point,
        true_focal: Some(focal),
        gt_fundamentals: fundamentals,
        images: None,
    };
    scene.validate()?;
    Ok(Generated {
        scene,
        intrinsics: k,
        ego_rotation,
        ego_translation,
    })
}

/// Named generator configurations.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Preset {
    /// `hopef-like`: HOPE-F's structure, categories 1–4 objects × 100 test
    /// scenes (folders 0900–0999), default parameters: 400 scenes.
    HopefLike,
    /// `quick`: 4 small scenes (categories 1 and 2, folders 0900–0901, 30–50
    /// points per object), for tests and a first run in seconds.
    Quick,
    /// `kitti-like`: static background under ego-motion plus 1–2 movers
    /// (categories 1 and 2, folders 0900–0909): 20 scenes.
    KittiLike,
    /// `hopef`: HOPE-F's own process ([`crate::hopef_synth`]), categories
    /// 1–4 × folders 0000–0999 (train 0000–0799, validation 0800–0899, test
    /// 0900–0999): 4000 scenes.
    Hopef,
}

/// The parameters of a preset's generator.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(untagged)]
pub enum PresetParams {
    /// The generator of this module ([`generate_hopef_scene`]).
    Synthetic(SyntheticParams),
    /// The HOPE-F-faithful generator ([`hopef_synth::generate_scene`]).
    Hopef(HopefParams),
}

impl PresetParams {
    /// Checks the parameters (see [`SyntheticParams::validate`] and
    /// [`HopefParams::validate`]).
    pub fn validate(&self) -> Result<(), DatasetError> {
        match self {
            PresetParams::Synthetic(p) => p.validate(),
            PresetParams::Hopef(p) => p.validate(),
        }
    }

    /// Generates scene `<category>/<index>` of a dataset made with `seed`.
    pub fn generate_scene(
        &self,
        seed: u64,
        category: u32,
        index: u32,
    ) -> Result<SyntheticScene, DatasetError> {
        match self {
            PresetParams::Synthetic(p) => generate_hopef_scene(p, seed, category, index),
            PresetParams::Hopef(p) => hopef_synth::generate_scene(p, seed, category, index),
        }
    }

    /// The parameters of this module's generator, if they are those.
    pub fn as_synthetic(&self) -> Option<&SyntheticParams> {
        match self {
            PresetParams::Synthetic(p) => Some(p),
            PresetParams::Hopef(_) => None,
        }
    }
}

impl Preset {
    /// All presets.
    pub const ALL: [Preset; 4] = [
        Preset::HopefLike,
        Preset::Quick,
        Preset::KittiLike,
        Preset::Hopef,
    ];

    /// The preset's name (`hopef-like`, `quick`, `kitti-like`, `hopef`).
    pub fn name(self) -> &'static str {
        match self {
            Preset::HopefLike => "hopef-like",
            Preset::Quick => "quick",
            Preset::KittiLike => "kitti-like",
            Preset::Hopef => "hopef",
        }
    }

    /// The preset called `name`.
    ///
    /// ```
    /// use datasets::synthetic::Preset;
    /// assert_eq!(Preset::from_name("quick"), Some(Preset::Quick));
    /// assert_eq!(Preset::from_name("nope"), None);
    /// ```
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|p| p.name() == name)
    }

    /// The generator parameters.
    pub fn params(self) -> PresetParams {
        PresetParams::Synthetic(match self {
            Preset::HopefLike => SyntheticParams::default(),
            Preset::Quick => SyntheticParams {
                points_per_object: [30, 50],
                min_points_per_object: 20,
                ..SyntheticParams::default()
            },
            Preset::KittiLike => SyntheticParams {
                background: BackgroundParams {
                    enabled: true,
                    ..BackgroundParams::default()
                },
                ..SyntheticParams::default()
            },
            Preset::Hopef => return PresetParams::Hopef(HopefParams::default()),
        })
    }

    /// Reads a table of this preset's generator parameters (e.g. its own,
    /// serialised, with a user's overrides merged in).
    ///
    /// ```
    /// use datasets::synthetic::{Preset, PresetParams};
    /// let table: toml::Value = toml::from_str("mismatch_share = [0.2, 0.3]").unwrap();
    /// let PresetParams::Hopef(p) = Preset::Hopef.params_from_toml(table).unwrap() else {
    ///     panic!("hopef parameters expected");
    /// };
    /// assert_eq!(p.mismatch_share, [0.2, 0.3]);
    /// ```
    pub fn params_from_toml(self, table: toml::Value) -> Result<PresetParams, toml::de::Error> {
        match self.params() {
            PresetParams::Synthetic(_) => table.try_into().map(PresetParams::Synthetic),
            PresetParams::Hopef(_) => table.try_into().map(PresetParams::Hopef),
        }
    }

    /// The category folders (numbers of moving objects).
    pub fn categories(self) -> Vec<u32> {
        match self {
            Preset::HopefLike | Preset::Hopef => vec![1, 2, 3, 4],
            Preset::Quick | Preset::KittiLike => vec![1, 2],
        }
    }

    /// The scene folder indices of each category.
    pub fn indices(self) -> std::ops::RangeInclusive<u32> {
        match self {
            Preset::HopefLike => 900..=999,
            Preset::Quick => 900..=901,
            Preset::KittiLike => 900..=909,
            Preset::Hopef => 0..=999,
        }
    }

    /// Number of scenes the preset generates.
    pub fn len(self) -> usize {
        self.categories().len() * self.indices().count()
    }

    /// Always false: every preset has scenes.
    pub fn is_empty(self) -> bool {
        self.len() == 0
    }

    /// Generates all scenes of the preset from `seed` with `params`
    /// (normally [`Preset::params`]), calling `progress(done, total)` after
    /// each scene.
    pub fn generate_with(
        self,
        params: &PresetParams,
        seed: u64,
        mut progress: impl FnMut(usize, usize),
    ) -> Result<Vec<SyntheticScene>, DatasetError> {
        let total = self.len();
        let mut out = Vec::with_capacity(total);
        for category in self.categories() {
            for index in self.indices() {
                out.push(params.generate_scene(seed, category, index)?);
                progress(out.len(), total);
            }
        }
        Ok(out)
    }

    /// Generates all scenes of the preset from `seed` with its own parameters.
    ///
    /// ```
    /// use datasets::synthetic::Preset;
    /// let scenes = Preset::Quick.generate(7)?;
    /// let names: Vec<&str> = scenes.iter().map(|s| s.scene.name.as_str()).collect();
    /// assert_eq!(names, ["1/0900", "1/0901", "2/0900", "2/0901"]);
    /// # Ok::<(), datasets::DatasetError>(())
    /// ```
    pub fn generate(self, seed: u64) -> Result<Vec<SyntheticScene>, DatasetError> {
        self.generate_with(&self.params(), seed, |_, _| {})
    }
}

/// Writes scenes in the HOPE-F on-disk layout under `root`
/// (`<root>/<category>/<NNNN>/features_and_ground_truth.npz` and
/// `camera_parameters.npz`), readable by [`crate::hopef`] and by
/// `numpy.load`. Existing files of the same names are replaced.
///
/// Arrays: `points1`, `points2` (N × 3, third column 1), `labels` (N,
/// int64), `F` (motions × 3 × 3), `ratios` (N zeros: synthetic matches have
/// no descriptor ratio, and 0 passes any ratio test); `K`, `R` = `R_e`,
/// `t` = `t_e` and `image_size` = (W, H) (int64, an addition to HOPE-F's
/// arrays that makes the round trip lossless).
///
/// Scenes of the `hopef` preset are written as HOPE-F writes them: their
/// drawn `ratios`, the camera's `R` (Blender's camera-to-world rotation)
/// and `t` = (0, 0, −d), and one `object_<i>.npz` per object
/// ([`hopef_synth::layout`]).
pub fn write_hopef_layout(root: &Path, scenes: &[SyntheticScene]) -> Result<(), DatasetError> {
    write_hopef_layout_with(root, scenes, |_, _| {})
}

/// [`write_hopef_layout`], calling `progress(done, total)` after each scene.
pub fn write_hopef_layout_with(
    root: &Path,
    scenes: &[SyntheticScene],
    mut progress: impl FnMut(usize, usize),
) -> Result<(), DatasetError> {
    for (i, s) in scenes.iter().enumerate() {
        let dir = root
            .join(s.category.to_string())
            .join(format!("{:04}", s.index));
        write_hopef_scene(&dir, s)?;
        progress(i + 1, scenes.len());
    }
    Ok(())
}

/// The entries of a 3 × 3 matrix in row-major (NumPy C) order.
fn row_major(m: &Matrix3<f64>) -> Vec<f64> {
    m.transpose().as_slice().to_vec()
}

/// Writes one scene's two `.npz` files into `dir` (created if needed).
pub fn write_hopef_scene(dir: &Path, s: &SyntheticScene) -> Result<(), DatasetError> {
    std::fs::create_dir_all(dir).map_err(|e| DatasetError::io(dir, e))?;
    let scene = &s.scene;
    let n = scene.len();
    let homogeneous = |pts: &[[f64; 2]]| {
        NpyArray::from_f64(
            vec![pts.len(), 3],
            pts.iter().flat_map(|p| [p[0], p[1], 1.0]).collect(),
        )
    };
    let labels: Vec<i64> = scene
        .labels
        .as_ref()
        .map(|l| l.iter().map(|&x| i64::from(x)).collect())
        .unwrap_or_else(|| vec![0; n]);
    let shape_err = || DatasetError::Generation {
        scene: scene.name.clone(),
        problem: "inconsistent array lengths".into(),
    };
    let points1 = homogeneous(&scene.points1).ok_or_else(shape_err)?;
    let points2 = homogeneous(&scene.points2).ok_or_else(shape_err)?;
    let labels = NpyArray::from_i64(vec![labels.len()], labels).ok_or_else(shape_err)?;
    let f = NpyArray::from_f64(
        vec![scene.gt_fundamentals.len(), 3, 3],
        scene.gt_fundamentals.iter().flat_map(row_major).collect(),
    )
    .ok_or_else(shape_err)?;
    let (ratios, rotation, translation) = match &s.hopef {
        Some(truth) => (
            truth.ratios.clone(),
            truth.camera_rotation,
            Vector3::new(0.0, 0.0, -truth.camera_distance),
        ),
        None => (vec![0.0; n], s.ego_rotation, s.ego_translation),
    };
    let ratios = NpyArray::from_f64(vec![n], ratios).ok_or_else(shape_err)?;
    let k = NpyArray::from_f64(vec![3, 3], row_major(&s.intrinsics)).ok_or_else(shape_err)?;
    let r = NpyArray::from_f64(vec![3, 3], row_major(&rotation)).ok_or_else(shape_err)?;
    let t =
        NpyArray::from_f64(vec![3], translation.iter().copied().collect()).ok_or_else(shape_err)?;
    let size = NpyArray::from_i64(
        vec![2],
        vec![i64::from(scene.image_size.0), i64::from(scene.image_size.1)],
    )
    .ok_or_else(shape_err)?;

    let write = |name: &str, arrays: &[(&str, &NpyArray)]| write_npz_file(&dir.join(name), arrays);
    write(
        FEATURES_FILE,
        &[
            ("F", &f),
            ("labels", &labels),
            ("points1", &points1),
            ("points2", &points2),
            ("ratios", &ratios),
        ],
    )?;
    write(
        CAMERA_FILE,
        &[("K", &k), ("R", &r), ("t", &t), ("image_size", &size)],
    )?;
    match &s.hopef {
        Some(truth) => hopef_synth::layout::write_objects(dir, truth),
        None => Ok(()),
    }
}

/// Writes `arrays` as the `.npz` archive `path`.
pub(crate) fn write_npz_file(
    path: &Path,
    arrays: &[(&str, &NpyArray)],
) -> Result<(), DatasetError> {
    let file = std::fs::File::create(path).map_err(|e| DatasetError::io(path, e))?;
    write_npz(std::io::BufWriter::new(file), arrays).map_err(|source| DatasetError::Npz {
        path: path.to_path_buf(),
        array: None,
        source,
    })
}
