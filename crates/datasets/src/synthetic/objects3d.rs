//! The `objects-3d` family: 1–5 general 3-D objects (points on ellipsoids,
//! relief planes and boxes, [`super::surfaces`]) moving independently in
//! front of a camera that itself moves, with or without a static
//! background, at varied image sizes, focal lengths, object sizes and
//! counts; built apart from the other generators (no grid, no road, no
//! HOPE-F process).
//!
//! Draws, in this order, from the scene RNG seeded with
//! [`scene_seed`]`(seed, category, index)`: σ; the number of objects k;
//! whether there is a background (`background_probability`); the outlier
//! share o; N log-uniform in `size_range`, its lower end raised to
//! `min_points · motions / (1 − o)`; the counts (each object but the first
//! is small with `small_object_probability`, with a count in
//! `small_object_points`; the other motions get `min_points` plus a share of
//! the rest in proportion to log-uniform weights); W, H, the focal length
//! `focal_factor · max(W, H)` (principal point at the centre); the camera's
//! motion `X₂ = R_e X₁ + t_e` (rotation about a uniform axis, translation
//! in a uniform direction).
//!
//! Objects, one after the other: a surface and its orientation, a depth, an
//! extent (log-uniform), an image-1 position keeping its bounding sphere's
//! disc in the image; a rotation `R_j` about a uniform axis through its
//! centre `c` and a translation `t_j`; so `R = R_e R_j`,
//! `T = R_e (c − R_j c + t_j) + t_e` and `F = K⁻ᵀ [T]ₓ R K⁻¹`
//! (Hartley & Zisserman, Eq. 9.12). Surface points are drawn until the
//! object has its count in view in both images (a point outside either is
//! redrawn). The background is a plane (depth, tilt drawn) with a
//! sinusoidal relief, its points drawn outside the objects' image-1 boxes
//! (`R = R_e`, `T = t_e`).
//!
//! Distinct motions. For every ordered pair of motions (i, j), at most
//! `max_shared_share` of i's noise-free matches may lie within
//! `distinct_threshold_px` (Sampson distance) of j's true F, i.e. with the
//! defaults the median distance is at least the default pipeline's
//! threshold. An object failing this against an earlier object or the
//! background's F, or overlapping an earlier object's image-1 box, is
//! redrawn (up to [`OBJECT_ATTEMPTS`] times); a background failing it
//! against an object makes the whole layout redrawn (up to
//! [`SCENE_ATTEMPTS`] times, then a [`DatasetError::Generation`]).
//!
//! Labels: 0 outlier, then the background (if any), then the objects; the
//! drawn difficulty is the scene's [`SceneRecord`]; every scene is in
//! category folder 0.

use nalgebra::{Matrix3, Rotation3, Vector3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::driving::{boxes_meet, generation_error, Tracks};
use super::generate::{push_outliers, shuffled_scene, EgoMotion, Matches};
use super::objects3d_params::Objects3dParams;
use super::record::{separations, MotionKind, MotionRecord, SceneRecord};
use super::sampling::{
    fundamental, intrinsics, log_uniform, project, random_rotation, random_unit, truncated_noise,
    uniform, uniform_count, view2, Camera,
};
use super::surfaces::Surface;
use super::{scene_seed, SyntheticScene};
use crate::hopef::scene_name;
use crate::DatasetError;
use geometry::sampson_distance;

/// Attempts to place one object before the layout is redrawn.
pub const OBJECT_ATTEMPTS: usize = 200;

/// Attempts at a whole layout before giving up.
pub const SCENE_ATTEMPTS: usize = 50;

/// Surface or background points drawn per point kept, at most.
const DRAWS_PER_POINT: usize = 50;

/// The counts and noise drawn for a scene.
struct Draws {
    n: usize,
    sigma: f64,
    outliers: usize,
    /// The background's matches, when there is one.
    background: Option<usize>,
    objects: Vec<usize>,
}

/// The camera, its motion and the margin noise-free points keep.
struct View {
    cam: Camera,
    ego: EgoMotion,
    size: (u32, u32),
    margin: f64,
}

/// One motion's noise-free matches, true F, image-1 box and rotation.
struct Body {
    tracks: Tracks,
    f: Matrix3<f64>,
    bbox: [f64; 4],
    rotation_deg: f64,
}

/// Generates `objects-3d` scene `<category>/<index>` of a dataset made with
/// `seed`; the model is described in `synthetic/objects3d.rs`.
///
/// ```
/// use datasets::synthetic::{generate_objects3d_scene, Objects3dParams};
/// let s = generate_objects3d_scene(&Objects3dParams::default(), 1, 0, 800)?;
/// let record = s.record.as_ref().unwrap();
/// assert_eq!(s.scene.len(), record.n);
/// assert_eq!(s.scene.num_motions(), record.motions.len());
/// # Ok::<(), datasets::DatasetError>(())
/// ```
pub fn generate_objects3d_scene(
    params: &Objects3dParams,
    seed: u64,
    category: u32,
    index: u32,
) -> Result<SyntheticScene, DatasetError> {
    params.validate()?;
    let name = scene_name(category, index);
    let mut rng = ChaCha8Rng::seed_from_u64(scene_seed(seed, category, index));
    let draws = draw_difficulty(&mut rng, params);
    let view = draw_view(&mut rng, params, draws.sigma)
        .ok_or_else(|| generation_error(&name, "singular intrinsics".into()))?;
    let bodies = (0..SCENE_ATTEMPTS)
        .find_map(|_| layout(&mut rng, params, &view, &draws))
        .ok_or_else(|| {
            generation_error(
                &name,
                format!(
                    "no layout of {} objects in view, apart and distinct after {SCENE_ATTEMPTS} x {OBJECT_ATTEMPTS} attempts",
                    draws.objects.len()
                ),
            )
        })?;
    let mut matches = Matches::default();
    for (j, body) in bodies.iter().enumerate() {
        add_noisy(
            &mut rng,
            params,
            draws.sigma,
            &body.tracks,
            j as i32 + 1,
            &mut matches,
        );
    }
    push_outliers(&mut rng, draws.outliers, &view.cam, &mut matches);
    let fundamentals: Vec<Matrix3<f64>> = bodies.iter().map(|b| b.f).collect();
    let record = scene_record(&draws, &view, &bodies, &fundamentals);
    let scene = shuffled_scene(&mut rng, view.size, &view.cam, &name, matches, fundamentals);
    scene.validate()?;
    Ok(SyntheticScene {
        category,
        index,
        scene,
        intrinsics: view.cam.k,
        ego_rotation: view.ego.rotation,
        ego_translation: view.ego.translation,
        hopef: None,
        record: Some(record),
    })
}

/// σ, k, the background, N, the outliers and each motion's count (module
/// docs).
fn draw_difficulty(rng: &mut ChaCha8Rng, p: &Objects3dParams) -> Draws {
    let sigma = uniform(rng, p.noise_sigma);
    let num_objects = rng.gen_range(p.objects[0]..=p.objects[1]);
    let has_background = rng.gen_bool(p.background_probability);
    let motions = num_objects + usize::from(has_background);
    let o = uniform(rng, p.outlier_share);
    let least = p.min_points * motions;
    let n_min = (least as f64 / (1.0 - o)).ceil().max(p.size_range[0]);
    let n = (log_uniform(rng, [n_min, p.size_range[1].max(n_min)]).round() as usize).max(least);
    let outliers = ((o * n as f64).round() as usize).min(n - least);
    let mut counts = motion_counts(rng, p, n - outliers, motions, usize::from(has_background));
    let background = has_background.then(|| counts.remove(0));
    Draws {
        n,
        sigma,
        outliers,
        background,
        objects: counts,
    }
}

/// The counts of `motions` motions sharing `inliers` matches, the first
/// object at `first_object`: small objects (never the first) a count in
/// `small_object_points`, the others `min_points` plus a share of the rest
/// by weights `exp(u)`, u uniform in `[−spread, spread]`; when the small
/// ones leave the others too little, none is small.
fn motion_counts(
    rng: &mut ChaCha8Rng,
    p: &Objects3dParams,
    inliers: usize,
    motions: usize,
    first_object: usize,
) -> Vec<usize> {
    let mut small: Vec<Option<usize>> = (0..motions)
        .map(|i| {
            (i > first_object && rng.gen_bool(p.small_object_probability))
                .then(|| uniform_count(rng, p.small_object_points))
        })
        .collect();
    let free = |s: &[Option<usize>]| s.iter().filter(|c| c.is_none()).count();
    let fixed = |s: &[Option<usize>]| s.iter().flatten().sum::<usize>();
    if fixed(&small) + free(&small) * p.min_points > inliers {
        small = vec![None; motions];
    }
    let spare = inliers - fixed(&small) - free(&small) * p.min_points;
    let spread = [-p.weight_spread, p.weight_spread];
    let weights: Vec<f64> = small
        .iter()
        .map(|s| {
            if s.is_none() {
                uniform(rng, spread).exp()
            } else {
                0.0
            }
        })
        .collect();
    let total: f64 = weights.iter().sum();
    let mut counts: Vec<usize> = small
        .iter()
        .zip(&weights)
        .map(|(s, w)| s.unwrap_or(p.min_points + (spare as f64 * w / total).floor() as usize))
        .collect();
    let given: usize = counts.iter().sum();
    counts[first_object] += inliers - given;
    counts
}

/// The image size, the camera (principal point at the centre) and its
/// motion; `None` for a singular K.
fn draw_view(rng: &mut ChaCha8Rng, p: &Objects3dParams, sigma: f64) -> Option<View> {
    let w = rng.gen_range(p.image_width[0]..=p.image_width[1]);
    let h = rng.gen_range(p.image_height[0]..=p.image_height[1]);
    let (width, height) = (f64::from(w), f64::from(h));
    let focal = uniform(rng, p.focal_factor) * width.max(height);
    let principal_point = [(width - 1.0) / 2.0, (height - 1.0) / 2.0];
    let k = intrinsics(focal, principal_point);
    let k_inv = k.try_inverse()?;
    let rotation = *random_rotation(rng, p.ego_rotation_deg).matrix();
    let translation = random_unit(rng).into_inner() * uniform(rng, p.ego_translation);
    Some(View {
        cam: Camera {
            k,
            k_inv,
            focal,
            principal_point,
            width,
            height,
        },
        ego: EgoMotion {
            rotation,
            translation,
        },
        size: (w, h),
        margin: p.noise_truncation * sigma,
    })
}

/// Whether `q` is in the image at least the view's margin from its border.
fn inside(view: &View, q: [f64; 2]) -> bool {
    let (m, cam) = (view.margin, &view.cam);
    (m..=cam.width - 1.0 - m).contains(&q[0]) && (m..=cam.height - 1.0 - m).contains(&q[1])
}

/// The share of `tracks` within `distinct_threshold_px` of `f`.
fn shared_share(p: &Objects3dParams, f: &Matrix3<f64>, tracks: &Tracks) -> f64 {
    let close = tracks
        .iter()
        .filter(|&&(a, b)| sampson_distance(f, a, b) < p.distinct_threshold_px)
        .count();
    close as f64 / tracks.len() as f64
}

/// Whether neither body's matches agree with the other's F (module docs).
fn distinct(p: &Objects3dParams, a: &Body, b: &Body) -> bool {
    shared_share(p, &b.f, &a.tracks) <= p.max_shared_share
        && shared_share(p, &a.f, &b.tracks) <= p.max_shared_share
}

/// The objects placed one after the other, then the background; `None`
/// when an object finds no place or the background is not distinct.
fn layout(
    rng: &mut ChaCha8Rng,
    p: &Objects3dParams,
    view: &View,
    draws: &Draws,
) -> Option<Vec<Body>> {
    let f_background = fundamental(&view.cam.k_inv, &view.ego.rotation, &view.ego.translation);
    let f_bg = draws.background.map(|_| &f_background);
    let mut objects: Vec<Body> = Vec::with_capacity(draws.objects.len());
    for &count in &draws.objects {
        let body =
            (0..OBJECT_ATTEMPTS).find_map(|_| place_object(rng, p, view, count, &objects, f_bg))?;
        objects.push(body);
    }
    let mut bodies = Vec::with_capacity(objects.len() + 1);
    if let Some(count) = draws.background {
        let background = Body {
            tracks: background_tracks(rng, p, view, &objects, count)?,
            f: f_background,
            bbox: [0.0; 4],
            rotation_deg: 0.0,
        };
        if !objects.iter().all(|o| distinct(p, &background, o)) {
            return None;
        }
        bodies.push(background);
    }
    bodies.extend(objects);
    Some(bodies)
}

/// One object with `count` matches (module docs); `None` when it leaves
/// the images, meets a `placed` object's box or is not distinct from it or
/// from the background's F `f_bg`.
fn place_object(
    rng: &mut ChaCha8Rng,
    p: &Objects3dParams,
    view: &View,
    count: usize,
    placed: &[Body],
    f_bg: Option<&Matrix3<f64>>,
) -> Option<Body> {
    let cam = &view.cam;
    let surface = Surface::draw(rng, &p.surfaces);
    let orientation = *random_rotation(rng, [0.0, 180.0]).matrix();
    let depth = uniform(rng, p.object_depth);
    let radius_px = log_uniform(rng, p.object_extent) * cam.width.min(cam.height) / 2.0;
    let m = view.margin + radius_px;
    if 2.0 * m >= cam.width.min(cam.height) - 1.0 {
        return None;
    }
    let centre_px = [
        rng.gen_range(m..=cam.width - 1.0 - m),
        rng.gen_range(m..=cam.height - 1.0 - m),
    ];
    let centre = cam.back_project(centre_px, depth);
    let radius = radius_px * depth / cam.focal;
    let turn = random_rotation(rng, p.rotation_deg);
    let shift = random_unit(rng).into_inner() * uniform(rng, p.translation) * depth;
    let (r_e, t_e) = (&view.ego.rotation, &view.ego.translation);
    let r = r_e * turn.matrix();
    let t = r_e * (centre - turn * centre + shift) + t_e;
    if t.norm() < 1e-6 * depth {
        return None;
    }
    let point = |rng: &mut ChaCha8Rng| centre + orientation * surface.sample(rng) * radius;
    let tracks = tracks_in_view(rng, view, &r, &t, count, point)?;
    let body = Body {
        bbox: image1_box(&tracks),
        f: fundamental(&cam.k_inv, &r, &t),
        tracks,
        rotation_deg: turn.angle().to_degrees(),
    };
    let clear = !placed.iter().any(|o| boxes_meet(&o.bbox, &body.bbox, 2.0))
        && f_bg.map_or(true, |f| {
            shared_share(p, f, &body.tracks) <= p.max_shared_share
        })
        && placed.iter().all(|o| distinct(p, o, &body));
    clear.then_some(body)
}

/// `count` noise-free matches of points drawn by `point` and moving by
/// `(r, t)`, each in both images (a point outside either is redrawn, up to
/// [`DRAWS_PER_POINT`] draws per match).
fn tracks_in_view(
    rng: &mut ChaCha8Rng,
    view: &View,
    r: &Matrix3<f64>,
    t: &Vector3<f64>,
    count: usize,
    mut point: impl FnMut(&mut ChaCha8Rng) -> Vector3<f64>,
) -> Option<Tracks> {
    let mut tracks = Tracks::with_capacity(count);
    for _ in 0..count * DRAWS_PER_POINT {
        if tracks.len() == count {
            break;
        }
        let x = point(rng);
        let p1 = project(&view.cam.k, &x).filter(|&q| inside(view, q));
        let p2 = view2(&view.cam, r, t, &x).filter(|&q| inside(view, q));
        if let (Some(p1), Some(p2)) = (p1, p2) {
            tracks.push((p1, p2));
        }
    }
    (tracks.len() == count).then_some(tracks)
}

/// The image-1 bounding box `[x_lo, y_lo, x_hi, y_hi]` of `tracks`.
fn image1_box(tracks: &Tracks) -> [f64; 4] {
    tracks.iter().fold(
        [
            f64::INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NEG_INFINITY,
        ],
        |b, (q, _)| {
            [
                b[0].min(q[0]),
                b[1].min(q[1]),
                b[2].max(q[0]),
                b[3].max(q[1]),
            ]
        },
    )
}

/// `count` background matches: pixels of image 1 outside the objects'
/// boxes, on a plane at a drawn depth and tilt with a sinusoidal relief,
/// seen in image 2 under the camera's motion; `None` when too few stay in
/// view.
fn background_tracks(
    rng: &mut ChaCha8Rng,
    p: &Objects3dParams,
    view: &View,
    objects: &[Body],
    count: usize,
) -> Option<Tracks> {
    let cam = &view.cam;
    let depth = uniform(rng, p.background_depth);
    let azimuth = rng.gen_range(0.0..std::f64::consts::TAU);
    let tilt_axis = nalgebra::Unit::new_normalize(Vector3::new(azimuth.cos(), azimuth.sin(), 0.0));
    let tilt = uniform(rng, p.background_tilt_deg).to_radians();
    let normal = Rotation3::from_axis_angle(&tilt_axis, tilt) * Vector3::z();
    let relief = uniform(rng, p.background_relief);
    let cycles = [rng.gen_range(1.0..=4.0), rng.gen_range(1.0..=4.0)];
    let phase = [
        rng.gen_range(0.0..std::f64::consts::TAU),
        rng.gen_range(0.0..std::f64::consts::TAU),
    ];
    let tau = std::f64::consts::TAU;
    let point = |rng: &mut ChaCha8Rng| -> Option<Vector3<f64>> {
        let q = cam.random_pixel(rng);
        let here = [q[0], q[1], q[0], q[1]];
        if objects.iter().any(|o| boxes_meet(&o.bbox, &here, 2.0)) {
            return None;
        }
        let ray = cam.back_project(q, 1.0);
        let facing = normal.dot(&ray);
        if facing < 0.2 {
            return None;
        }
        let bump = (tau * cycles[0] * q[0] / cam.width + phase[0]).sin()
            * (tau * cycles[1] * q[1] / cam.height + phase[1]).sin();
        Some(ray * (depth / facing) * (1.0 + relief * bump))
    };
    // A rejected pixel becomes a point behind camera 1, which
    // `tracks_in_view` redraws like any point out of view.
    let behind = Vector3::new(0.0, 0.0, -1.0);
    tracks_in_view(
        rng,
        view,
        &view.ego.rotation,
        &view.ego.translation,
        count,
        |rng| point(rng).unwrap_or(behind),
    )
}

/// The `tracks` with truncated Gaussian noise of σ `sigma`, labelled
/// `label`; they stay in the images because noise-free points keep the
/// margin.
fn add_noisy(
    rng: &mut ChaCha8Rng,
    p: &Objects3dParams,
    sigma: f64,
    tracks: &Tracks,
    label: i32,
    m: &mut Matches,
) {
    for &(p1, p2) in tracks {
        let e = truncated_noise(rng, sigma, p.noise_truncation);
        m.points1.push([p1[0] + e[0], p1[1] + e[1]]);
        m.points2.push([p2[0] + e[2], p2[1] + e[3]]);
        m.labels.push(label);
    }
}

/// The scene's [`SceneRecord`]: the draws and, per motion in label order,
/// its count, share, separations and rotation.
fn scene_record(
    draws: &Draws,
    view: &View,
    bodies: &[Body],
    fundamentals: &[Matrix3<f64>],
) -> SceneRecord {
    let tracks: Vec<&Tracks> = bodies.iter().map(|b| &b.tracks).collect();
    let background = draws.background.map(|_| 0);
    let motions = bodies
        .iter()
        .enumerate()
        .map(|(i, b)| {
            let (to_background, nearest) = separations(i, &tracks, fundamentals, background);
            MotionRecord {
                label: i as i32 + 1,
                kind: if background == Some(i) {
                    MotionKind::Background
                } else {
                    MotionKind::Object
                },
                points: b.tracks.len(),
                share: b.tracks.len() as f64 / draws.n as f64,
                target_separation_px: None,
                background_separation_px: to_background,
                nearest_separation_px: nearest,
                rotation_deg: b.rotation_deg,
            }
        })
        .collect();
    SceneRecord {
        family: "objects-3d",
        n: draws.n,
        noise_sigma: draws.sigma,
        outlier_share: draws.outliers as f64 / draws.n as f64,
        focal: view.cam.focal,
        image_size: view.size,
        motions,
    }
}
