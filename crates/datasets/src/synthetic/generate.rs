//! The generation of one synthetic scene, phase by phase (the model is in
//! the [module docs](super)): the camera, the ego-motion, the grid cells,
//! the objects, the background, the noise, the gross outliers and the final
//! shuffle. Every phase draws from the one scene RNG in this order, so a
//! seed gives the same scene.

use nalgebra::{Matrix3, Vector3};
use rand::seq::SliceRandom;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::sampling::{
    fundamental, intrinsics, project, random_rotation, random_unit, sample_shape, truncated_noise,
    uniform, uniform_count, view2, Camera,
};
use super::SyntheticParams;
use crate::{DatasetError, Scene};

/// A generated scene with the camera data the HOPE-F layout stores.
pub(super) struct Generated {
    /// The scene.
    pub(super) scene: Scene,
    /// Intrinsics K of both views.
    pub(super) intrinsics: Matrix3<f64>,
    /// The camera's ego-motion.
    pub(super) ego: EgoMotion,
}

/// The camera's motion between the views, `X₂ = R_e X₁ + t_e` for static
/// points (identity and zero without background).
pub(super) struct EgoMotion {
    /// `R_e`.
    pub(super) rotation: Matrix3<f64>,
    /// `t_e`.
    pub(super) translation: Vector3<f64>,
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

/// An axis-aligned image rectangle: a grid cell or an object's image-1
/// bounding box.
#[derive(Clone, Copy)]
struct Rect {
    lo: [f64; 2],
    hi: [f64; 2],
}

/// One placed object: its tracks and its motion `X₂ = R X + T`.
struct PlacedObject {
    tracks: Vec<Track>,
    rotation: Matrix3<f64>,
    translation: Vector3<f64>,
}

/// The objects of a scene: their tracks, the ground-truth F of every
/// motion (the background's first) and their image-1 bounding boxes.
struct Objects {
    tracks: Vec<Track>,
    fundamentals: Vec<Matrix3<f64>>,
    boxes: Vec<Rect>,
}

/// The matches of a scene, in generation order.
#[derive(Default)]
pub(super) struct Matches {
    /// Image-1 points.
    pub(super) points1: Vec<[f64; 2]>,
    /// Image-2 points.
    pub(super) points2: Vec<[f64; 2]>,
    /// Labels (0 outlier, 1.. motions).
    pub(super) labels: Vec<i32>,
}

/// Generates the scene `name` with `num_objects` moving objects from `seed`.
pub(super) fn generate(
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
    let cam = draw_camera(&mut rng, params, name)?;
    let ego = draw_ego_motion(&mut rng, params);
    let cells = grid_cells(&mut rng, num_objects, cam.width, cam.height);
    let mut objects = place_objects(&mut rng, params, &cam, &cells, num_objects, &ego, name)?;
    if params.background.enabled {
        add_background(&mut rng, params, &cam, &ego, &mut objects);
    }
    let mut matches = noisy_matches(&mut rng, params, &cam, &objects.tracks);
    add_outliers(&mut rng, params.outlier_fraction, &cam, &mut matches);
    let size = (params.image_width, params.image_height);
    let scene = shuffled_scene(&mut rng, size, &cam, name, matches, objects.fundamentals);
    scene.validate()?;
    Ok(Generated {
        scene,
        intrinsics: cam.k,
        ego,
    })
}

/// The camera: a focal length uniform in `focal_range` and a principal
/// point jittered about the image centre.
fn draw_camera(
    rng: &mut ChaCha8Rng,
    params: &SyntheticParams,
    name: &str,
) -> Result<Camera, DatasetError> {
    let width = f64::from(params.image_width);
    let height = f64::from(params.image_height);
    let focal = uniform(rng, params.focal_range);
    let jitter = params.principal_point_jitter;
    let principal_point = [
        (width - 1.0) / 2.0 + rng.gen_range(-1.0..=1.0) * jitter,
        (height - 1.0) / 2.0 + rng.gen_range(-1.0..=1.0) * jitter,
    ];
    let k = intrinsics(focal, principal_point);
    let k_inv = k.try_inverse().ok_or_else(|| DatasetError::Generation {
        scene: name.to_string(),
        problem: "singular intrinsics".into(),
    })?;
    Ok(Camera {
        k,
        k_inv,
        focal,
        principal_point,
        width,
        height,
    })
}

/// The ego-motion: a random rotation and a mostly forward translation, as
/// a driving camera (identity and zero without background; no draw then).
fn draw_ego_motion(rng: &mut ChaCha8Rng, params: &SyntheticParams) -> EgoMotion {
    if !params.background.enabled {
        return EgoMotion {
            rotation: Matrix3::identity(),
            translation: Vector3::zeros(),
        };
    }
    let r = random_rotation(rng, params.background.ego_rotation_deg);
    let mut dir = random_unit(rng).into_inner();
    dir.z = dir.z.abs() + 1.0;
    let t = dir.normalize() * uniform(rng, params.background.ego_translation);
    EgoMotion {
        rotation: *r.matrix(),
        translation: t,
    }
}

/// The grid of `ceil(√k)` columns and `ceil(k / columns)` rows, its cells
/// in random order.
fn grid_cells(rng: &mut ChaCha8Rng, num_objects: usize, width: f64, height: f64) -> Vec<Rect> {
    let cols = (num_objects as f64).sqrt().ceil() as usize;
    let rows = num_objects.div_ceil(cols);
    let mut cells: Vec<Rect> = (0..rows * cols)
        .map(|c| {
            let (i, j) = (c % cols, c / cols);
            let (cw, ch) = (width / cols as f64, height / rows as f64);
            Rect {
                lo: [i as f64 * cw, j as f64 * ch],
                hi: [(i + 1) as f64 * cw, (j + 1) as f64 * ch],
            }
        })
        .collect();
    cells.shuffle(rng);
    cells
}

/// One object per cell (the first `num_objects` cells), each retried up to
/// [`PLACEMENT_ATTEMPTS`] times until enough of its points are in view.
fn place_objects(
    rng: &mut ChaCha8Rng,
    params: &SyntheticParams,
    cam: &Camera,
    cells: &[Rect],
    num_objects: usize,
    ego: &EgoMotion,
    name: &str,
) -> Result<Objects, DatasetError> {
    let background = params.background.enabled;
    let first_object_label = if background { 2 } else { 1 };
    let mut objects = Objects {
        tracks: Vec::new(),
        fundamentals: Vec::with_capacity(num_objects + usize::from(background)),
        boxes: Vec::new(),
    };
    if background {
        let f = fundamental(&cam.k_inv, &ego.rotation, &ego.translation);
        objects.fundamentals.push(f);
    }
    for (j, &cell) in cells.iter().take(num_objects).enumerate() {
        let label = first_object_label + j as i32;
        let placed =
            (0..PLACEMENT_ATTEMPTS).find_map(|_| place_object(rng, params, cam, cell, ego, label));
        let Some(object) = placed else {
            return Err(DatasetError::Generation {
                scene: name.to_string(),
                problem: format!(
                    "object {} kept fewer than {} points in view after {PLACEMENT_ATTEMPTS} attempts",
                    j + 1,
                    params.min_points_per_object
                ),
            });
        };
        let f = fundamental(&cam.k_inv, &object.rotation, &object.translation);
        objects.fundamentals.push(f);
        objects.boxes.push(image1_box(&object.tracks));
        objects.tracks.extend(object.tracks);
    }
    Ok(objects)
}

/// The image-1 bounding box of the tracks.
fn image1_box(tracks: &[Track]) -> Rect {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for tr in tracks {
        for a in 0..2 {
            lo[a] = lo[a].min(tr.p1[a]);
            hi[a] = hi[a].max(tr.p1[a]);
        }
    }
    Rect { lo, hi }
}

/// One object in its grid cell: its tracks and `(R, T)`, or `None` when
/// fewer than `min_points_per_object` of its points are in both views.
fn place_object(
    rng: &mut ChaCha8Rng,
    params: &SyntheticParams,
    cam: &Camera,
    cell: Rect,
    ego: &EgoMotion,
    label: i32,
) -> Option<PlacedObject> {
    let (cell_min, cell_max) = (cell.lo, cell.hi);
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
    let (r_e, t_e) = (&ego.rotation, &ego.translation);
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
    (tracks.len() >= params.min_points_per_object).then_some(PlacedObject {
        tracks,
        rotation: r,
        translation: t,
    })
}

/// Static points at background depths (label 1), hidden where an object
/// covers them in image 1.
fn add_background(
    rng: &mut ChaCha8Rng,
    params: &SyntheticParams,
    cam: &Camera,
    ego: &EgoMotion,
    objects: &mut Objects,
) {
    let bg = &params.background;
    let n = uniform_count(rng, bg.points);
    let pad = 10.0;
    for _ in 0..n {
        let pixel = cam.random_pixel(rng);
        let occluded = objects.boxes.iter().any(|b| {
            (b.lo[0] - pad..=b.hi[0] + pad).contains(&pixel[0])
                && (b.lo[1] - pad..=b.hi[1] + pad).contains(&pixel[1])
        });
        if occluded {
            continue;
        }
        let x = cam.back_project(pixel, uniform(rng, bg.depth_range));
        if let Some(p2) = view2(cam, &ego.rotation, &ego.translation, &x) {
            if cam.inside(p2) {
                objects.tracks.push(Track {
                    p1: pixel,
                    p2,
                    label: 1,
                });
            }
        }
    }
}

/// The tracks with truncated Gaussian noise, clipped to both images.
fn noisy_matches(
    rng: &mut ChaCha8Rng,
    params: &SyntheticParams,
    cam: &Camera,
    tracks: &[Track],
) -> Matches {
    let mut m = Matches {
        points1: Vec::with_capacity(tracks.len()),
        points2: Vec::with_capacity(tracks.len()),
        labels: Vec::with_capacity(tracks.len()),
    };
    for tr in tracks {
        let noise = truncated_noise(rng, params.noise_sigma, params.noise_truncation);
        let p1 = [tr.p1[0] + noise[0], tr.p1[1] + noise[1]];
        let p2 = [tr.p2[0] + noise[2], tr.p2[1] + noise[3]];
        if cam.inside(p1) && cam.inside(p2) {
            m.points1.push(p1);
            m.points2.push(p2);
            m.labels.push(tr.label);
        }
    }
    m
}

/// Gross outliers (label 0), uniform in both images: a fraction `q` of the
/// final total, so `n_out = q n_in / (1 − q)`.
fn add_outliers(rng: &mut ChaCha8Rng, q: f64, cam: &Camera, m: &mut Matches) {
    let n_out = (q * m.labels.len() as f64 / (1.0 - q)).round() as usize;
    push_outliers(rng, n_out, cam, m);
}

/// `n` gross outliers (label 0): a pixel uniform in each image.
pub(super) fn push_outliers(rng: &mut ChaCha8Rng, n: usize, cam: &Camera, m: &mut Matches) {
    for _ in 0..n {
        m.points1.push(cam.random_pixel(rng));
        m.points2.push(cam.random_pixel(rng));
        m.labels.push(0);
    }
}

/// The scene with its matches shuffled, so that labels are not grouped.
pub(super) fn shuffled_scene(
    rng: &mut ChaCha8Rng,
    image_size: (u32, u32),
    cam: &Camera,
    name: &str,
    m: Matches,
    fundamentals: Vec<Matrix3<f64>>,
) -> Scene {
    let mut order: Vec<usize> = (0..m.labels.len()).collect();
    order.shuffle(rng);
    Scene {
        name: name.to_string(),
        points1: order.iter().map(|&i| m.points1[i]).collect(),
        points2: order.iter().map(|&i| m.points2[i]).collect(),
        labels: Some(order.iter().map(|&i| m.labels[i]).collect()),
        image_size,
        principal_point: cam.principal_point,
        true_focal: Some(cam.focal),
        gt_fundamentals: fundamentals,
        images: None,
    }
}
