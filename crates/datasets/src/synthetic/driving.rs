//! The driving-scene generator of the `kitti-real` preset: a camera driving
//! forward past a static background, with 1–[`MAX_CARS`] cars that turn and
//! move sideways, at the size of real image pairs (N 1 000–5 000 matches).
//!
//! Model. Camera 1 is `K [I | 0]`, `K = [[f, 0, cx], [0, f, cy], [0, 0, 1]]`
//! with the principal point at the image centre; x right, y down, z forward,
//! the road the plane `y = h` (the camera height). The camera drives a
//! distance d along the chord of an arc turning by ψ, so its centre moves to
//! `c = d (sin ψ/2, 0, cos ψ/2)` and static points satisfy
//! `X₂ = R_e X₁ + t_e`, `R_e = R_y(ψ)ᵀ`, `t_e = −R_e c`. A car is a box
//! standing on the road at heading α; between the views it turns by θ
//! (rotation `R_j`) about an axis through its centre `c_j`, the vertical
//! tilted by up to `car_axis_tilt_deg`, and moves by `t_j` (sideways and
//! forward in its own frame), so `X₂ = R X₁ + T` with `R = R_e R_j`,
//! `T = R_e (c_j − R_j c_j + t_j) + t_e`. Each motion's F is
//! `K⁻ᵀ [T]ₓ R K⁻¹` (Hartley & Zisserman, Eq. 9.12), unit Frobenius norm;
//! labels are 0 outlier, 1 background, 2.. cars.
//!
//! Counts. N is `sizes[index % len]`; the outlier and background shares are
//! drawn from their ranges, each car gets at least `min_car_share` N and the
//! cars split the rest by random weights. Every count is met exactly: a
//! point that would leave either image is redrawn, not dropped.
//!
//! Separability. A car's points lie on its faces visible from camera 1, all
//! 8 corners in both images and its image-1 box clear of the other cars'.
//! A placed car is kept only if the median Sampson distance of its
//! noise-free points to the background's true F is at least
//! `min_separation_px`, and likewise of its points to every earlier car's F
//! and of that car's points to its F; otherwise its pose and motion are
//! redrawn (up to [`CAR_ATTEMPTS`] times, then all cars are redrawn, up to
//! [`LAYOUT_ATTEMPTS`] times, then a [`DatasetError::Generation`]). Background points are not drawn inside a
//! car's image-1 box.

use nalgebra::{Matrix3, Rotation3, Vector3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::driving_params::{DrivingParams, MAX_CARS};
use super::generate::{push_outliers, shuffled_scene, EgoMotion, Matches};
use super::sampling::{fundamental, intrinsics, project, truncated_noise, uniform, view2, Camera};
use super::{scene_seed, SyntheticScene};
use crate::hopef::scene_name;
use crate::DatasetError;
use geometry::sampson_distance;

/// Attempts to place one car before the cars placed so far are redrawn.
pub const CAR_ATTEMPTS: usize = 200;

/// Attempts to place all cars of a scene before giving up.
pub const LAYOUT_ATTEMPTS: usize = 50;

/// Points of a car first checked for separability (a cheap rejection of
/// most poses before all its points are drawn).
const PILOT_POINTS: usize = 64;

/// Draws allowed per background point before giving up.
const BACKGROUND_ATTEMPTS_PER_POINT: usize = 200;

/// Noise-free matches `(x₁, x₂)` of one motion.
pub(super) type Tracks = Vec<([f64; 2], [f64; 2])>;

/// How many matches each part of the scene gets.
struct Counts {
    outliers: usize,
    background: usize,
    cars: Vec<usize>,
}

/// One placed car: its tracks, true F and image-1 bounding box.
pub(super) struct Car {
    pub(super) tracks: Tracks,
    pub(super) f: Matrix3<f64>,
    pub(super) bbox: [f64; 4],
}

/// The camera, its motion and the background's F, shared by every phase.
pub(super) struct Rig {
    pub(super) cam: Camera,
    pub(super) ego: EgoMotion,
    pub(super) f_background: Matrix3<f64>,
    /// Distance noise-free points keep from the image border, px.
    pub(super) margin: f64,
}

/// Generates driving scene `<category>/<index>` (`category` moving cars) of
/// a dataset made with `seed`, from the scene RNG seeded with
/// [`scene_seed`]`(seed, category, index)`; the model is described in `synthetic/driving.rs`.
///
/// ```
/// use datasets::synthetic::{generate_driving_scene, DrivingParams};
/// let s = generate_driving_scene(&DrivingParams::default(), 1, 2, 800)?;
/// assert_eq!(s.scene.len(), 1000);
/// assert_eq!(s.scene.num_motions(), 3);
/// # Ok::<(), datasets::DatasetError>(())
/// ```
pub fn generate_driving_scene(
    params: &DrivingParams,
    seed: u64,
    category: u32,
    index: u32,
) -> Result<SyntheticScene, DatasetError> {
    params.validate()?;
    let name = scene_name(category, index);
    let num_cars = category as usize;
    if !(1..=MAX_CARS).contains(&num_cars) {
        return Err(DatasetError::InvalidParams {
            field: "category",
            problem: format!("{category} cars is not in 1..={MAX_CARS}"),
        });
    }
    let n = params.sizes[index as usize % params.sizes.len()];
    let mut rng = ChaCha8Rng::seed_from_u64(scene_seed(seed, category, index));
    let rig = draw_rig(&mut rng, params)
        .ok_or_else(|| generation_error(&name, "singular intrinsics".into()))?;
    let counts = draw_counts(&mut rng, params, n, num_cars)?;
    let cars = (0..LAYOUT_ATTEMPTS)
        .find_map(|_| place_cars(&mut rng, params, &rig, &counts.cars))
        .ok_or_else(|| {
            generation_error(
                &name,
                format!(
                    "no {num_cars} cars in view, apart and separable by {} px after {LAYOUT_ATTEMPTS} x {CAR_ATTEMPTS} attempts",
                    params.min_separation_px
                ),
            )
        })?;
    let background = background_tracks(&mut rng, params, &rig, &cars, counts.background)
        .ok_or_else(|| generation_error(&name, "too few background points stay in view".into()))?;
    let mut matches = Matches::default();
    add_noisy(&mut rng, params, &background, 1, &mut matches);
    for (j, car) in cars.iter().enumerate() {
        add_noisy(&mut rng, params, &car.tracks, j as i32 + 2, &mut matches);
    }
    push_outliers(&mut rng, counts.outliers, &rig.cam, &mut matches);
    let mut fundamentals = vec![rig.f_background];
    fundamentals.extend(cars.iter().map(|c| c.f));
    let size = (params.image_width, params.image_height);
    let scene = shuffled_scene(&mut rng, size, &rig.cam, &name, matches, fundamentals);
    scene.validate()?;
    Ok(SyntheticScene {
        category,
        index,
        scene,
        intrinsics: rig.cam.k,
        ego_rotation: rig.ego.rotation,
        ego_translation: rig.ego.translation,
        hopef: None,
        record: None,
    })
}

/// [`DatasetError::Generation`] for scene `name`.
pub(super) fn generation_error(name: &str, problem: String) -> DatasetError {
    DatasetError::Generation {
        scene: name.to_string(),
        problem,
    }
}

/// A uniform draw from `range` with a random sign.
pub(super) fn signed(rng: &mut ChaCha8Rng, range: [f64; 2]) -> f64 {
    let v = uniform(rng, range);
    if rng.gen_bool(0.5) {
        v
    } else {
        -v
    }
}

/// The rotation by `degrees` about the camera's y axis (the vertical).
pub(super) fn yaw(degrees: f64) -> Matrix3<f64> {
    *Rotation3::from_axis_angle(&Vector3::y_axis(), degrees.to_radians()).matrix()
}

/// A car's turn between the views: by an angle in `car_yaw_deg`, either
/// sign, about the vertical tilted by an angle in `car_axis_tilt_deg`
/// towards a uniform direction.
fn turn(rng: &mut ChaCha8Rng, params: &DrivingParams) -> Matrix3<f64> {
    let tilt = uniform(rng, params.car_axis_tilt_deg).to_radians();
    let azimuth = rng.gen_range(0.0..std::f64::consts::TAU);
    let axis = Vector3::new(
        tilt.sin() * azimuth.cos(),
        tilt.cos(),
        tilt.sin() * azimuth.sin(),
    );
    let angle = signed(rng, params.car_yaw_deg).to_radians();
    *Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(axis), angle).matrix()
}

/// The camera (principal point at the centre), its ego-motion along the
/// chord of its arc, and the background's F (`None` for a singular K).
pub(super) fn draw_rig(rng: &mut ChaCha8Rng, params: &DrivingParams) -> Option<Rig> {
    let (width, height) = (
        f64::from(params.image_width),
        f64::from(params.image_height),
    );
    let focal = uniform(rng, params.focal_range);
    let principal_point = [(width - 1.0) / 2.0, (height - 1.0) / 2.0];
    let k = intrinsics(focal, principal_point);
    let k_inv = k.try_inverse()?;
    let psi = signed(rng, params.ego_yaw_deg);
    let d = uniform(rng, params.ego_forward);
    let half = (psi / 2.0).to_radians();
    let centre = Vector3::new(half.sin(), 0.0, half.cos()) * d;
    let rotation = yaw(psi).transpose();
    let translation = -(rotation * centre);
    let cam = Camera {
        k,
        k_inv,
        focal,
        principal_point,
        width,
        height,
    };
    Some(Rig {
        f_background: fundamental(&cam.k_inv, &rotation, &translation),
        margin: params.noise_truncation * params.noise_sigma,
        cam,
        ego: EgoMotion {
            rotation,
            translation,
        },
    })
}

/// The number of outliers, background points and points per car for N = `n`
/// (the background gives way, by rounding only, to the cars' minimum).
fn draw_counts(
    rng: &mut ChaCha8Rng,
    params: &DrivingParams,
    n: usize,
    num_cars: usize,
) -> Result<Counts, DatasetError> {
    let fixed = params.background_share[1] + params.outlier_share[1];
    let min_car = (params.min_car_share * n as f64).ceil() as usize;
    let for_cars = n.checked_sub(num_cars * min_car);
    let Some(for_cars) = for_cars.filter(|_| fixed + num_cars as f64 * params.min_car_share <= 1.0)
    else {
        return Err(DatasetError::InvalidParams {
            field: "min_car_share",
            problem: format!(
                "{num_cars} cars of {} with background and outlier shares up to {fixed} exceed N",
                params.min_car_share
            ),
        });
    };
    let share = |s: f64| (s * n as f64).round() as usize;
    let outliers = share(uniform(rng, params.outlier_share)).min(for_cars);
    let for_cars = for_cars - outliers;
    let background = share(uniform(rng, params.background_share)).min(for_cars);
    let spare = for_cars - background;
    let weights: Vec<f64> = (0..num_cars).map(|_| rng.gen_range(1.0..2.0)).collect();
    let total: f64 = weights.iter().sum();
    let mut cars: Vec<usize> = weights
        .iter()
        .map(|w| min_car + (spare as f64 * w / total).floor() as usize)
        .collect();
    let given: usize = cars.iter().sum();
    cars[0] += num_cars * min_car + spare - given;
    Ok(Counts {
        outliers,
        background,
        cars,
    })
}

/// Whether `p` is in the image at least `margin` px from its border.
pub(super) fn inside(rig: &Rig, p: [f64; 2]) -> bool {
    let m = rig.margin;
    (m..=rig.cam.width - 1.0 - m).contains(&p[0]) && (m..=rig.cam.height - 1.0 - m).contains(&p[1])
}

/// Whether two image boxes `[x_lo, y_lo, x_hi, y_hi]`, grown by `pad`, meet.
pub(super) fn boxes_meet(a: &[f64; 4], b: &[f64; 4], pad: f64) -> bool {
    a[0] - pad <= b[2] && b[0] - pad <= a[2] && a[1] - pad <= b[3] && b[1] - pad <= a[3]
}

/// The cars with `counts` points each, placed one after the other
/// ([`place_car`], up to [`CAR_ATTEMPTS`] times each); `None` when one of
/// them finds no place.
fn place_cars(
    rng: &mut ChaCha8Rng,
    params: &DrivingParams,
    rig: &Rig,
    counts: &[usize],
) -> Option<Vec<Car>> {
    let mut cars: Vec<Car> = Vec::with_capacity(counts.len());
    for &count in counts {
        let car = (0..CAR_ATTEMPTS).find_map(|_| place_car(rng, params, rig, count, &cars))?;
        cars.push(car);
    }
    Some(cars)
}

/// One car with `count` points: its pose and motion drawn, kept when all
/// its corners are in both images, its image-1 box clears the `placed`
/// cars' and it is separable from the background and from them.
fn place_car(
    rng: &mut ChaCha8Rng,
    params: &DrivingParams,
    rig: &Rig,
    count: usize,
    placed: &[Car],
) -> Option<Car> {
    let [w, h, l] = params.car_size;
    let dims = Vector3::new(w, h, l);
    let centre = Vector3::new(
        uniform(rng, params.car_lateral),
        params.camera_height - h / 2.0,
        uniform(rng, params.car_depth),
    );
    let heading = yaw(uniform(rng, params.car_heading_deg));
    let turn = turn(rng, params);
    let shift = heading
        * Vector3::new(
            signed(rng, params.car_sideways),
            0.0,
            uniform(rng, params.car_forward),
        );
    let (r_e, t_e) = (&rig.ego.rotation, &rig.ego.translation);
    let r = r_e * turn;
    let t = r_e * (centre - turn * centre + shift) + t_e;
    let corners = box_corners(&centre, &heading, &dims);
    let mut bbox = [
        f64::INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NEG_INFINITY,
    ];
    for x in &corners {
        let p1 = project(&rig.cam.k, x).filter(|&p| inside(rig, p))?;
        view2(&rig.cam, &r, &t, x).filter(|&p| inside(rig, p))?;
        bbox = [
            bbox[0].min(p1[0]),
            bbox[1].min(p1[1]),
            bbox[2].max(p1[0]),
            bbox[3].max(p1[1]),
        ];
    }
    if t.norm() < 1e-3 || placed.iter().any(|c| boxes_meet(&c.bbox, &bbox, 5.0)) {
        return None;
    }
    let f = fundamental(&rig.cam.k_inv, &r, &t);
    let tracks_of = |rng: &mut ChaCha8Rng, n: usize| -> Option<Tracks> {
        face_points(rng, &centre, &heading, &dims, n)
            .iter()
            .map(|x| Some((project(&rig.cam.k, x)?, view2(&rig.cam, &r, &t, x)?)))
            .collect()
    };
    let pilot = tracks_of(rng, PILOT_POINTS.min(count))?;
    if !separable(params, rig, &f, &pilot, placed) {
        return None;
    }
    let tracks = tracks_of(rng, count)?;
    separable(params, rig, &f, &tracks, placed).then_some(Car { tracks, f, bbox })
}

/// Whether a car's `tracks` have a median Sampson distance of at least
/// `min_separation_px` to the background's F and to each `placed` car's F,
/// and each placed car's tracks to the car's `f`.
fn separable(
    params: &DrivingParams,
    rig: &Rig,
    f: &Matrix3<f64>,
    tracks: &Tracks,
    placed: &[Car],
) -> bool {
    let min = params.min_separation_px;
    median_sampson(&rig.f_background, tracks) >= min
        && placed
            .iter()
            .all(|c| median_sampson(&c.f, tracks) >= min && median_sampson(f, &c.tracks) >= min)
}

/// The median Sampson distance (px) of `tracks` to `f`.
pub(super) fn median_sampson(f: &Matrix3<f64>, tracks: &Tracks) -> f64 {
    let mut d: Vec<f64> = tracks
        .iter()
        .map(|&(p1, p2)| sampson_distance(f, p1, p2))
        .collect();
    let mid = d.len() / 2;
    *d.select_nth_unstable_by(mid, f64::total_cmp).1
}

/// The 8 corners of the box of size `dims` centred at `centre`, rotated by
/// `heading`.
pub(super) fn box_corners(
    centre: &Vector3<f64>,
    heading: &Matrix3<f64>,
    dims: &Vector3<f64>,
) -> Vec<Vector3<f64>> {
    (0..8)
        .map(|i| {
            let s = Vector3::new(
                if i & 1 == 0 { -0.5 } else { 0.5 },
                if i & 2 == 0 { -0.5 } else { 0.5 },
                if i & 4 == 0 { -0.5 } else { 0.5 },
            );
            centre + heading * s.component_mul(dims)
        })
        .collect()
}

/// `n` points uniform on the faces of the box that face camera 1 (outward
/// normal pointing towards the camera centre), by area.
pub(super) fn face_points(
    rng: &mut ChaCha8Rng,
    centre: &Vector3<f64>,
    heading: &Matrix3<f64>,
    dims: &Vector3<f64>,
    n: usize,
) -> Vec<Vector3<f64>> {
    // Visible faces as (axis, side ±1, area).
    let faces: Vec<(usize, f64, f64)> = (0..3)
        .flat_map(|axis| [(axis, -1.0), (axis, 1.0)])
        .filter(|&(axis, side)| {
            let normal = heading.column(axis) * side;
            normal.dot(&(centre + normal * dims[axis] / 2.0)) < 0.0
        })
        .map(|(axis, side)| (axis, side, dims.product() / dims[axis]))
        .collect();
    let total: f64 = faces.iter().map(|f| f.2).sum();
    (0..n)
        .map(|_| {
            let mut pick = rng.gen_range(0.0..total);
            let &(axis, side, _) = faces
                .iter()
                .find(|f| {
                    pick -= f.2;
                    pick < 0.0
                })
                .unwrap_or(&faces[faces.len() - 1]);
            let mut s: Vector3<f64> = Vector3::from_fn(|_, _| rng.gen_range(-0.5..0.5));
            s[axis] = side * 0.5;
            centre + heading * s.component_mul(dims)
        })
        .collect()
}

/// `n` static points in view in both images and outside the cars'
/// image-1 boxes: a pixel of image 1 at a background depth, or on the road
/// below the horizon where that is nearer; `None` when too many draws fail.
pub(super) fn background_tracks(
    rng: &mut ChaCha8Rng,
    params: &DrivingParams,
    rig: &Rig,
    cars: &[Car],
    n: usize,
) -> Option<Tracks> {
    let cam = &rig.cam;
    let mut tracks = Tracks::with_capacity(n);
    for _ in 0..n * BACKGROUND_ATTEMPTS_PER_POINT {
        if tracks.len() == n {
            break;
        }
        let p1 = cam.random_pixel(rng);
        let mut depth = uniform(rng, params.background_depth);
        let below = p1[1] - cam.principal_point[1];
        if below > 0.0 {
            depth = depth.min(cam.focal * params.camera_height / below);
        }
        let point = [p1[0], p1[1], p1[0], p1[1]];
        if !inside(rig, p1) || cars.iter().any(|c| boxes_meet(&c.bbox, &point, 2.0)) {
            continue;
        }
        let x = cam.back_project(p1, depth);
        if let Some(p2) = view2(cam, &rig.ego.rotation, &rig.ego.translation, &x) {
            if inside(rig, p2) {
                tracks.push((p1, p2));
            }
        }
    }
    (tracks.len() == n).then_some(tracks)
}

/// The `tracks` with truncated Gaussian noise, labelled `label`; they stay
/// in the images because every noise-free point keeps the margin.
pub(super) fn add_noisy(
    rng: &mut ChaCha8Rng,
    params: &DrivingParams,
    tracks: &Tracks,
    label: i32,
    m: &mut Matches,
) {
    for &(p1, p2) in tracks {
        let e = truncated_noise(rng, params.noise_sigma, params.noise_truncation);
        m.points1.push([p1[0] + e[0], p1[1] + e[1]]);
        m.points2.push([p2[0] + e[2], p2[1] + e[3]]);
        m.labels.push(label);
    }
}
