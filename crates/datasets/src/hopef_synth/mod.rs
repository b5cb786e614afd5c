//! A HOPE-F-faithful generator (the `hopef` preset): scenes made the way
//! HOPE-F's scripts make them (Kluger & Rosenhahn, AAAI 2024;
//! fkluger/hope-f `blender_render.py` and `prepare_features_and_gt.py`),
//! with SIFT's feature process replaced by a documented model.
//!
//! Per scene (`k` = 1..4 objects):
//! 1. One static camera for both images (Blender convention, see
//!    [`world`]): focal uniform in 24–40 mm on a 30 mm sensor
//!    (819.2–1365.3 px at 1024 px), principal point (512, 512), distance
//!    3–5 from the origin, tilt 25–65°, azimuth 90–270°, looking at the
//!    origin.
//! 2. `k` objects, boxes or vertical cylinders of 0.3–1.4 units, standing on
//!    an untextured ground plane (no features on it). In each view
//!    independently: the base positions `(±0.5, ±0.5)` shuffled, object `i`
//!    at base `i` plus a uniform offset in `[−0.25, 0.25]²`, yaw uniform in
//!    `[−10°, 10°]`. Every motion is planar; objects may change quadrant.
//! 3. Texture features fixed on the objects' surfaces (log-uniform density
//!    per object, uniform factor per face), detected in a view when they
//!    face the camera, lie in the image and no other object hides them (a
//!    ray test against the other solids), with a grazing-angle fall-off;
//!    localisation noise Gaussian with σ proportional to a heavy-tailed
//!    keypoint scale (a scale mixture: mostly sub-pixel, some pixels).
//! 4. Correct matches between detections of the same feature; mismatches
//!    pair unmatched image-1 keypoints with image-2 keypoints (they lie on
//!    objects), a share uniform in 20–55 % per scene; `ratios` drawn from
//!    Beta laws below the 0.9 ratio test.
//! 5. HOPE-F's labels and acceptance rule ([`truth::hopef_label`],
//!    [`truth::hopef_accepts`]); a rejected draw is redrawn from the same
//!    random stream, so a scene depends only on (seed, category, index).
//!
//! Every value the scripts do not fix is a field of [`HopefParams`].

mod features;
pub mod layout;
pub mod params;
pub mod stats;
pub mod truth;
pub mod world;

pub use params::HopefParams;
pub use truth::{HopefTruth, MatchSource, ObjectTruth};
pub use world::{Pose, Shape};

use crate::hopef::scene_name;
use crate::synthetic::{scene_seed, uniform, SyntheticScene};
use crate::{DatasetError, Scene};
use features::{draw_matches, draw_sites, Object};
use rand::seq::SliceRandom;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use world::{draw_poses, Camera};

/// Most objects a scene may have: one per base position.
pub const MAX_OBJECTS: u32 = 4;

/// Generates scene `<category>/<index>` (`category` objects) of a dataset
/// made with `seed`, from the random stream [`scene_seed`]`(seed, category,
/// index)`: the same arguments always give the same scene.
///
/// ```
/// use datasets::hopef_synth::{generate_scene, HopefParams};
/// let params = HopefParams::default();
/// let s = generate_scene(&params, 1, 3, 950)?;
/// assert_eq!(s.scene.name, "3/0950");
/// assert_eq!(s.scene.gt_fundamentals.len(), 3);
/// assert_eq!(s.scene.principal_point, [512.0, 512.0]);
/// assert_eq!(s, generate_scene(&params, 1, 3, 950)?);
/// # Ok::<(), datasets::DatasetError>(())
/// ```
pub fn generate_scene(
    params: &HopefParams,
    seed: u64,
    category: u32,
    index: u32,
) -> Result<SyntheticScene, DatasetError> {
    params.validate()?;
    if !(1..=MAX_OBJECTS).contains(&category) {
        return Err(DatasetError::InvalidParams {
            field: "category",
            problem: format!("{category} objects; HOPE-F scenes have 1..={MAX_OBJECTS}"),
        });
    }
    let name = scene_name(category, index);
    let mut rng = ChaCha8Rng::seed_from_u64(scene_seed(seed, category, index));
    for attempt in 1..=params.max_attempts {
        if let Some(scene) = draw(&mut rng, params, category, index, attempt)? {
            return Ok(scene);
        }
    }
    Err(DatasetError::Generation {
        scene: name,
        problem: format!(
            "no draw in {} met the acceptance rule (every object with at least {} matches within {} px of its F)",
            params.max_attempts, params.min_inliers_per_object, params.inlier_threshold_px
        ),
    })
}

/// `k` objects: shapes and texture densities, the poses of view 1, those
/// of view 2, then each object's features.
fn draw_objects(rng: &mut ChaCha8Rng, params: &HopefParams, k: usize) -> Vec<Object> {
    let shapes: Vec<(Shape, f64)> = (0..k)
        .map(|_| {
            let shape = Shape::draw(rng, params);
            let [lo, hi] = params.texture_density.map(f64::ln);
            (shape, uniform(rng, [lo, hi]).exp())
        })
        .collect();
    let poses1 = draw_poses(rng, params, k);
    let poses2 = draw_poses(rng, params, k);
    shapes
        .into_iter()
        .zip(poses1.into_iter().zip(poses2))
        .map(|((shape, density), (a, b))| Object {
            sites: draw_sites(rng, params, &shape, density),
            truth: ObjectTruth {
                shape,
                poses: [a, b],
                texture_density: density,
            },
        })
        .collect()
}

/// One draw of a scene; `None` when it fails the acceptance rule (or an
/// object does not move at all).
fn draw(
    rng: &mut ChaCha8Rng,
    params: &HopefParams,
    category: u32,
    index: u32,
    attempt: u32,
) -> Result<Option<SyntheticScene>, DatasetError> {
    let k = category as usize;
    let camera = Camera::draw(rng, params);
    let objects = draw_objects(rng, params, k);
    let truth: Vec<ObjectTruth> = objects.iter().map(|o| o.truth.clone()).collect();
    let Some(fundamentals) = truth
        .iter()
        .map(|o| {
            let (r, t) = o.motion();
            truth::object_fundamental(&camera, &r, &t)
        })
        .collect::<Option<Vec<_>>>()
    else {
        return Ok(None);
    };

    let mut matches = draw_matches(rng, params, &camera, &objects)?;
    matches.shuffle(rng);
    let points1: Vec<[f64; 2]> = matches.iter().map(|m| m.p1).collect();
    let points2: Vec<[f64; 2]> = matches.iter().map(|m| m.p2).collect();
    let threshold = params.inlier_threshold_px;
    if !truth::hopef_accepts(
        &fundamentals,
        &points1,
        &points2,
        threshold,
        params.min_inliers_per_object,
    ) {
        return Ok(None);
    }
    let labels = points1
        .iter()
        .zip(&points2)
        .map(|(a, b)| truth::hopef_label(&fundamentals, *a, *b, threshold))
        .collect();
    let [w, h] = params.image_size;
    let scene = Scene {
        name: scene_name(category, index),
        points1,
        points2,
        labels: Some(labels),
        image_size: (w, h),
        principal_point: [camera.k[(0, 2)], camera.k[(1, 2)]],
        true_focal: Some(camera.focal()),
        gt_fundamentals: fundamentals,
        images: None,
    };
    scene.validate()?;
    Ok(Some(SyntheticScene {
        category,
        index,
        scene,
        intrinsics: camera.k,
        ego_rotation: nalgebra::Matrix3::identity(),
        ego_translation: nalgebra::Vector3::zeros(),
        hopef: Some(HopefTruth {
            camera_rotation: camera.blender_rotation,
            camera_distance: camera.distance,
            objects: truth,
            sources: matches.iter().map(|m| m.source).collect(),
            ratios: matches.iter().map(|m| m.ratio).collect(),
            attempts: attempt,
        }),
        record: None,
    }))
}
