//! The `driving-random` family: the driving scenes of the `kitti-real`
//! preset ([`super::driving`]: camera, forward ego-motion, static
//! background, cars as boxes of points) with every difficulty drawn per
//! scene, separability included.
//!
//! Draws, in this order, from the scene RNG seeded with
//! [`scene_seed`]`(seed, category, index)`: N log-uniform in
//! `size_range`; σ uniform in `noise_sigma`; the outlier share uniform in
//! `outlier_share`; the number of movers m uniform in `movers` (0–3); each
//! mover's share uniform in `mover_share` (lower end raised to
//! `min_mover_points / N`), all m redrawn together while the background
//! would keep less than `min_background_share` of N; each mover's target
//! separation s* log-uniform in `separation_px`. Then the camera and its
//! ego-motion, as `kitti-real`'s.
//!
//! Separation by construction (draw the target, then the motion that
//! achieves it). A mover's pose (lateral position, depth, heading) and the
//! direction of its motion relative to the road (a turn by θ about the
//! vertical tilted by up to `car_axis_tilt_deg`, a shift `t₀` sideways and
//! forward, `kitti-real`'s ranges) are drawn, and its points on the faces
//! camera 1 sees. The motion is then scaled by λ ≥ 0: turn λθ, shift λt₀,
//! so that λ = 0 moves the car with the background (separation 0). With
//! `X₂ = R X₁ + T`, `R = R_e R_j(λ)`, `T = R_e (c − R_j(λ) c + λ t₀) + t_e`,
//! the median Sampson distance s(λ) of the car's noise-free matches to the
//! background's F (Hartley & Zisserman, Eq. 11.9) is continuous with
//! s(0) = 0: λ is doubled from 1 until s(λ) ≥ s* (up to [`MAX_SCALE`], the
//! turn at most [`MAX_TURN_DEG`]) and then bisected until
//! |s(λ) − s*| ≤ `separation_tolerance` · s*. The pose is redrawn (up to
//! [`super::CAR_ATTEMPTS`] times, then all movers, up to
//! [`super::LAYOUT_ATTEMPTS`] times) when no λ is found, a corner leaves
//! either image, its image-1 box meets another mover's, or two movers are
//! less distinct than either is from the background: the median Sampson
//! distance of each one's matches to the other's F must be at least the
//! smaller of their two separations.
//!
//! Labels: 0 outlier, 1 background, 2..m+1 movers; the scene's drawn
//! difficulty is its [`SceneRecord`]. Every scene is in category folder 0
//! (the number of motions is drawn, not a folder).

use nalgebra::{Matrix3, Rotation3, Unit, Vector3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::driving::{
    add_noisy, background_tracks, box_corners, boxes_meet, draw_rig, face_points, generation_error,
    inside, median_sampson, signed, yaw, Car, Rig, Tracks,
};
use super::driving_random_params::DrivingRandomParams;
use super::generate::{push_outliers, shuffled_scene, Matches};
use super::record::{separations, MotionKind, MotionRecord, SceneRecord};
use super::sampling::{fundamental, log_uniform, project, uniform, view2};
use super::{scene_seed, DrivingParams, SyntheticScene, CAR_ATTEMPTS, LAYOUT_ATTEMPTS};
use crate::hopef::scene_name;
use crate::DatasetError;

/// Largest scale λ of a mover's drawn motion direction.
pub const MAX_SCALE: f64 = 8.0;

/// Largest turn of a mover between the views, degrees.
pub const MAX_TURN_DEG: f64 = 60.0;

/// Bisection steps of λ before the pose is redrawn.
const BISECTIONS: usize = 60;

/// Draws of the movers' shares before giving up.
const SHARE_ATTEMPTS: usize = 10_000;

/// The difficulty drawn for a scene, before any geometry.
struct Draws {
    n: usize,
    sigma: f64,
    outliers: usize,
    background: usize,
    /// Per mover: its number of matches and target separation, px.
    movers: Vec<(usize, f64)>,
}

/// The direction of a mover's motion relative to the road: a turn `angle`
/// (radians, signed) about `axis` through its centre and a `shift`.
struct Direction {
    axis: Unit<Vector3<f64>>,
    angle: f64,
    shift: Vector3<f64>,
}

/// A placed mover.
struct Mover {
    car: Car,
    target: f64,
    separation: f64,
    turn_deg: f64,
}

/// Generates `driving-random` scene `<category>/<index>` of a dataset made
/// with `seed`; the model is described in `synthetic/driving_random.rs`.
///
/// ```
/// use datasets::synthetic::{generate_driving_random_scene, DrivingRandomParams};
/// let s = generate_driving_random_scene(&DrivingRandomParams::default(), 1, 0, 800)?;
/// let record = s.record.as_ref().unwrap();
/// assert_eq!(s.scene.len(), record.n);
/// assert_eq!(s.scene.num_motions(), record.motions.len());
/// # Ok::<(), datasets::DatasetError>(())
/// ```
pub fn generate_driving_random_scene(
    params: &DrivingRandomParams,
    seed: u64,
    category: u32,
    index: u32,
) -> Result<SyntheticScene, DatasetError> {
    params.validate()?;
    let name = scene_name(category, index);
    let mut rng = ChaCha8Rng::seed_from_u64(scene_seed(seed, category, index));
    let draws = draw_difficulty(&mut rng, params).ok_or_else(|| {
        generation_error(
            &name,
            "no mover shares leave the background its share".into(),
        )
    })?;
    let geometry = params.geometry_for(draws.sigma);
    let rig = draw_rig(&mut rng, &geometry)
        .ok_or_else(|| generation_error(&name, "singular intrinsics".into()))?;
    let movers = (0..LAYOUT_ATTEMPTS)
        .find_map(|_| place_movers(&mut rng, params, &geometry, &rig, &draws.movers))
        .ok_or_else(|| {
            generation_error(
                &name,
                format!(
                    "no {} movers in view, apart and at their drawn separations after {LAYOUT_ATTEMPTS} x {CAR_ATTEMPTS} attempts",
                    draws.movers.len()
                ),
            )
        })?;
    let (cars, mover_info): (Vec<Car>, Vec<(f64, f64)>) = movers
        .into_iter()
        .map(|m| (m.car, (m.target, m.turn_deg)))
        .unzip();
    let background = background_tracks(&mut rng, &geometry, &rig, &cars, draws.background)
        .ok_or_else(|| generation_error(&name, "too few background points stay in view".into()))?;
    let mut matches = Matches::default();
    add_noisy(&mut rng, &geometry, &background, 1, &mut matches);
    for (j, car) in cars.iter().enumerate() {
        add_noisy(&mut rng, &geometry, &car.tracks, j as i32 + 2, &mut matches);
    }
    push_outliers(&mut rng, draws.outliers, &rig.cam, &mut matches);
    let mut fundamentals = vec![rig.f_background];
    fundamentals.extend(cars.iter().map(|c| c.f));
    let record = scene_record(
        &draws,
        &rig,
        &geometry,
        &background,
        &cars,
        &mover_info,
        &fundamentals,
    );
    let size = (geometry.image_width, geometry.image_height);
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
        record: Some(record),
    })
}

/// N, σ, the outliers, the background's and each mover's matches and each
/// mover's target separation; `None` when no draw of the movers' shares
/// leaves the background its share.
fn draw_difficulty(rng: &mut ChaCha8Rng, p: &DrivingRandomParams) -> Option<Draws> {
    let n = log_uniform(rng, p.size_range).round() as usize;
    let sigma = uniform(rng, p.noise_sigma);
    let outliers = (uniform(rng, p.outlier_share) * n as f64).round() as usize;
    let num_movers = rng.gen_range(p.movers[0]..=p.movers[1]);
    let lo = p.mover_share[0].max(p.min_mover_points as f64 / n as f64);
    let shares = [lo, p.mover_share[1].max(lo)];
    let min_background = (p.min_background_share * n as f64).ceil() as usize;
    let (counts, background) = (0..SHARE_ATTEMPTS).find_map(|_| {
        let counts: Vec<usize> = (0..num_movers)
            .map(|_| {
                let c = (uniform(rng, shares) * n as f64).round() as usize;
                c.max(p.min_mover_points)
            })
            .collect();
        let background = n.checked_sub(outliers + counts.iter().sum::<usize>())?;
        (background >= min_background).then_some((counts, background))
    })?;
    let movers = counts
        .into_iter()
        .map(|c| (c, log_uniform(rng, p.separation_px)))
        .collect();
    Some(Draws {
        n,
        sigma,
        outliers,
        background,
        movers,
    })
}

/// The movers with the drawn `(count, target)` each, placed one after the
/// other ([`place_mover`], up to [`CAR_ATTEMPTS`] times each); `None` when
/// one of them finds no place.
fn place_movers(
    rng: &mut ChaCha8Rng,
    params: &DrivingRandomParams,
    geometry: &DrivingParams,
    rig: &Rig,
    drawn: &[(usize, f64)],
) -> Option<Vec<Mover>> {
    let mut placed: Vec<Mover> = Vec::with_capacity(drawn.len());
    for &(count, target) in drawn {
        let tolerance = params.separation_tolerance;
        let mover = (0..CAR_ATTEMPTS)
            .find_map(|_| place_mover(rng, geometry, rig, (count, target, tolerance), &placed))?;
        placed.push(mover);
    }
    Some(placed)
}

/// One mover with `count` points at separation `target` (± `tolerance`
/// relative): pose, motion direction and points drawn, the scale found
/// ([`solve_scale`]), kept when in view in both images, clear of the
/// `placed` movers' image-1 boxes and distinct from them.
fn place_mover(
    rng: &mut ChaCha8Rng,
    g: &DrivingParams,
    rig: &Rig,
    (count, target, tolerance): (usize, f64, f64),
    placed: &[Mover],
) -> Option<Mover> {
    let dims = Vector3::from(g.car_size);
    let centre = Vector3::new(
        uniform(rng, g.car_lateral),
        g.camera_height - dims.y / 2.0,
        uniform(rng, g.car_depth),
    );
    let heading = yaw(uniform(rng, g.car_heading_deg));
    let corners = box_corners(&centre, &heading, &dims);
    let bbox = image1_box(rig, &corners)?;
    if placed.iter().any(|m| boxes_meet(&m.car.bbox, &bbox, 5.0)) {
        return None;
    }
    let direction = draw_direction(rng, g, &heading);
    let points = face_points(rng, &centre, &heading, &dims, count);
    let lambda = solve_scale(rig, &direction, &centre, &points, target, tolerance)?;
    let (r, t) = direction.motion(lambda, &centre, rig);
    let in_view2 = |x: &Vector3<f64>| view2(&rig.cam, &r, &t, x).is_some_and(|q| inside(rig, q));
    if t.norm() < 1e-6 || !corners.iter().all(in_view2) {
        return None;
    }
    let tracks = tracks_of(rig, &r, &t, &points)?;
    let f = fundamental(&rig.cam.k_inv, &r, &t);
    let separation = median_sampson(&rig.f_background, &tracks);
    let distinct = placed.iter().all(|m| {
        let least = separation.min(m.separation);
        median_sampson(&m.car.f, &tracks) >= least && median_sampson(&f, &m.car.tracks) >= least
    });
    distinct.then(|| Mover {
        car: Car { tracks, f, bbox },
        target,
        separation,
        turn_deg: (lambda * direction.angle).to_degrees().abs(),
    })
}

/// The image-1 bounding box `[x_lo, y_lo, x_hi, y_hi]` of `corners`, `None`
/// unless every corner is in image 1 (with the rig's margin).
fn image1_box(rig: &Rig, corners: &[Vector3<f64>]) -> Option<[f64; 4]> {
    let mut bbox = [
        f64::INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NEG_INFINITY,
    ];
    for x in corners {
        let p = project(&rig.cam.k, x).filter(|&p| inside(rig, p))?;
        bbox = [
            bbox[0].min(p[0]),
            bbox[1].min(p[1]),
            bbox[2].max(p[0]),
            bbox[3].max(p[1]),
        ];
    }
    Some(bbox)
}

/// A motion direction with `kitti-real`'s ranges: a turn by an angle in
/// `car_yaw_deg` (either sign) about the vertical tilted by an angle in
/// `car_axis_tilt_deg`, a shift sideways (either sign) and forward in the
/// car's `heading` frame.
fn draw_direction(rng: &mut ChaCha8Rng, g: &DrivingParams, heading: &Matrix3<f64>) -> Direction {
    let tilt = uniform(rng, g.car_axis_tilt_deg).to_radians();
    let azimuth = rng.gen_range(0.0..std::f64::consts::TAU);
    let axis = Vector3::new(
        tilt.sin() * azimuth.cos(),
        tilt.cos(),
        tilt.sin() * azimuth.sin(),
    );
    let angle = signed(rng, g.car_yaw_deg).to_radians();
    let shift = heading
        * Vector3::new(
            signed(rng, g.car_sideways),
            0.0,
            uniform(rng, g.car_forward),
        );
    Direction {
        axis: Unit::new_normalize(axis),
        angle,
        shift,
    }
}

impl Direction {
    /// `(R, T)` of the camera-2 frame, `X₂ = R X₁ + T`, for the motion
    /// scaled by `lambda` of a car centred at `centre` (module docs).
    fn motion(
        &self,
        lambda: f64,
        centre: &Vector3<f64>,
        rig: &Rig,
    ) -> (Matrix3<f64>, Vector3<f64>) {
        let turn = *Rotation3::from_axis_angle(&self.axis, lambda * self.angle).matrix();
        let (r_e, t_e) = (&rig.ego.rotation, &rig.ego.translation);
        let r = r_e * turn;
        let t = r_e * (centre - turn * centre + self.shift * lambda) + t_e;
        (r, t)
    }
}

/// The noise-free matches of `points` moving by `(r, t)`; `None` when one
/// is behind either camera.
fn tracks_of(
    rig: &Rig,
    r: &Matrix3<f64>,
    t: &Vector3<f64>,
    points: &[Vector3<f64>],
) -> Option<Tracks> {
    points
        .iter()
        .map(|x| Some((project(&rig.cam.k, x)?, view2(&rig.cam, r, t, x)?)))
        .collect()
}

/// The scale λ of `direction` at which the median Sampson distance of the
/// car's noise-free matches to the background's F is `target` within
/// `tolerance` (relative): doubling from 1, then bisection (module docs);
/// `None` past [`MAX_SCALE`] or [`MAX_TURN_DEG`], or without convergence.
fn solve_scale(
    rig: &Rig,
    direction: &Direction,
    centre: &Vector3<f64>,
    points: &[Vector3<f64>],
    target: f64,
    tolerance: f64,
) -> Option<f64> {
    let separation = |lambda: f64| -> Option<f64> {
        if (lambda * direction.angle).to_degrees().abs() > MAX_TURN_DEG {
            return None;
        }
        let (r, t) = direction.motion(lambda, centre, rig);
        Some(median_sampson(
            &rig.f_background,
            &tracks_of(rig, &r, &t, points)?,
        ))
    };
    let mut hi = 1.0;
    while separation(hi)? < target {
        hi *= 2.0;
        if hi > MAX_SCALE {
            return None;
        }
    }
    let mut lo = 0.0;
    for _ in 0..BISECTIONS {
        let mid = 0.5 * (lo + hi);
        let s = separation(mid)?;
        if (s - target).abs() <= tolerance * target {
            return Some(mid);
        }
        if s < target {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    None
}

/// The scene's [`SceneRecord`]: the draws and, per motion (background
/// first), its count, share, target and measured separations.
fn scene_record(
    draws: &Draws,
    rig: &Rig,
    g: &DrivingParams,
    background: &Tracks,
    cars: &[Car],
    mover_info: &[(f64, f64)],
    fundamentals: &[Matrix3<f64>],
) -> SceneRecord {
    let mut tracks: Vec<&Tracks> = vec![background];
    tracks.extend(cars.iter().map(|c| &c.tracks));
    let motions = (0..tracks.len())
        .map(|i| {
            let (to_background, nearest) = separations(i, &tracks, fundamentals, Some(0));
            let (target, turn) = if i == 0 {
                (None, 0.0)
            } else {
                (Some(mover_info[i - 1].0), mover_info[i - 1].1)
            };
            MotionRecord {
                label: i as i32 + 1,
                kind: if i == 0 {
                    MotionKind::Background
                } else {
                    MotionKind::Object
                },
                points: tracks[i].len(),
                share: tracks[i].len() as f64 / draws.n as f64,
                target_separation_px: target,
                background_separation_px: to_background,
                nearest_separation_px: nearest,
                rotation_deg: turn,
            }
        })
        .collect();
    SceneRecord {
        family: "driving-random",
        n: draws.n,
        noise_sigma: draws.sigma,
        outlier_share: draws.outliers as f64 / draws.n as f64,
        focal: rig.cam.focal,
        image_size: (g.image_width, g.image_height),
        motions,
    }
}
