//! Synthetic two-view scenes with several rigidly moving objects, and
//! fundamental-matrix hypotheses drawn around their motions: realistic
//! preference matrices for the clustering benchmarks and tests.
//!
//! Camera: `K = diag(f, f, 1)` with the principal point at the origin, a
//! 640 × 480 image. Object m is a cloud of 3D points in front of the camera
//! that moves by a random rigid motion `(R_m, t_m)` between the two views, so
//! its matches obey `F_m = K⁻ᵀ [t_m]ₓ R_m K⁻¹` (Eq. 23's convention
//! `x2ᵀ F x1 = 0`). Gross outliers are random pixel pairs.

use geometry::Correspondences;
use nalgebra::{Matrix3, Rotation3, Unit, Vector3};
use rand::Rng;

/// Image half-width and half-height (640 × 480, centred coordinates).
pub const HALF_WIDTH: f64 = 320.0;
/// See [`HALF_WIDTH`].
pub const HALF_HEIGHT: f64 = 240.0;
/// Focal length of both views, px.
pub const FOCAL: f64 = 700.0;

/// A rigid motion of one object between the two views: `X2 = R X1 + t`.
#[derive(Debug, Clone, Copy)]
pub struct Motion {
    pub rotation: Rotation3<f64>,
    pub translation: Vector3<f64>,
}

impl Motion {
    /// A random motion: rotation of 2–12° about a random axis, translation of
    /// length 0.3–1 in a random direction.
    pub fn random(rng: &mut impl Rng) -> Self {
        let axis = Unit::new_normalize(random_direction(rng));
        let angle = rng.gen_range(2.0f64..12.0).to_radians();
        Self {
            rotation: Rotation3::from_axis_angle(&axis, angle),
            translation: random_direction(rng) * rng.gen_range(0.3..1.0),
        }
    }

    /// The motion composed with a small random perturbation: rotation by
    /// `angle_deg` about a random axis, translation moved by a random vector
    /// of length `shift` (a stand-in for an estimated, refined hypothesis).
    pub fn perturbed(&self, rng: &mut impl Rng, angle_deg: f64, shift: f64) -> Self {
        let axis = Unit::new_normalize(random_direction(rng));
        let delta = Rotation3::from_axis_angle(&axis, angle_deg.to_radians() * rng.gen::<f64>());
        Self {
            rotation: delta * self.rotation,
            translation: self.translation + random_direction(rng) * shift * rng.gen::<f64>(),
        }
    }

    /// `F = K⁻ᵀ [t]ₓ R K⁻¹` with `K = diag(f, f, 1)`.
    pub fn fundamental(&self) -> Matrix3<f64> {
        let t = self.translation;
        let tx = Matrix3::new(0.0, -t.z, t.y, t.z, 0.0, -t.x, -t.y, t.x, 0.0);
        let k_inv = Matrix3::new(1.0 / FOCAL, 0.0, 0.0, 0.0, 1.0 / FOCAL, 0.0, 0.0, 0.0, 1.0);
        let f = k_inv.transpose() * tx * self.rotation.matrix() * k_inv;
        f / f.norm()
    }
}

fn random_direction(rng: &mut impl Rng) -> Vector3<f64> {
    loop {
        let v = Vector3::new(
            rng.gen_range(-1.0..1.0),
            rng.gen_range(-1.0..1.0),
            rng.gen_range(-1.0..1.0),
        );
        let norm = v.norm();
        if norm > 1e-3 && norm <= 1.0 {
            return v / norm;
        }
    }
}

fn project(x: &Vector3<f64>) -> Option<[f64; 2]> {
    if x.z <= 0.1 {
        return None;
    }
    let p = [FOCAL * x.x / x.z, FOCAL * x.y / x.z];
    (p[0].abs() < HALF_WIDTH && p[1].abs() < HALF_HEIGHT).then_some(p)
}

fn gaussian(rng: &mut impl Rng) -> f64 {
    // Box–Muller.
    let u1: f64 = rng.gen_range(f64::EPSILON..1.0);
    let u2: f64 = rng.gen();
    (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
}

/// A scene: matches, ground-truth labels (0 = outlier, 1..=k = motion) and
/// the motions.
pub struct Scene {
    pub points: Correspondences,
    pub labels: Vec<usize>,
    pub motions: Vec<Motion>,
}

/// `n_points` matches: a fraction `outlier_ratio` of random pixel pairs, the
/// rest split evenly over `n_motions` moving objects, with Gaussian noise of
/// `noise_px` pixels on each coordinate.
pub fn synthetic_scene(
    rng: &mut impl Rng,
    n_points: usize,
    n_motions: usize,
    outlier_ratio: f64,
    noise_px: f64,
) -> Scene {
    let motions: Vec<Motion> = (0..n_motions).map(|_| Motion::random(rng)).collect();
    let n_outliers = (n_points as f64 * outlier_ratio).round() as usize;
    let n_inliers = n_points - n_outliers;
    let (mut p1, mut p2, mut labels) = (Vec::new(), Vec::new(), Vec::new());
    for (m, motion) in motions.iter().enumerate() {
        let count = n_inliers / n_motions + usize::from(m < n_inliers % n_motions);
        let centre = Vector3::new(
            rng.gen_range(-1.5..1.5),
            rng.gen_range(-1.0..1.0),
            rng.gen_range(5.0..8.0),
        );
        let mut made = 0;
        while made < count {
            let x1 = centre
                + Vector3::new(
                    rng.gen_range(-1.5..1.5),
                    rng.gen_range(-1.2..1.2),
                    rng.gen_range(-1.0..1.0),
                );
            let x2 = motion.rotation * x1 + motion.translation;
            if let (Some(a), Some(b)) = (project(&x1), project(&x2)) {
                p1.push([
                    a[0] + noise_px * gaussian(rng),
                    a[1] + noise_px * gaussian(rng),
                ]);
                p2.push([
                    b[0] + noise_px * gaussian(rng),
                    b[1] + noise_px * gaussian(rng),
                ]);
                labels.push(m + 1);
                made += 1;
            }
        }
    }
    for _ in 0..n_outliers {
        let mut pixel = || {
            [
                rng.gen_range(-HALF_WIDTH..HALF_WIDTH),
                rng.gen_range(-HALF_HEIGHT..HALF_HEIGHT),
            ]
        };
        p1.push(pixel());
        p2.push(pixel());
        labels.push(0);
    }
    Scene {
        points: Correspondences::new(&p1, &p2).expect("finite synthetic coordinates"),
        labels,
        motions,
    }
}

/// How far a hypothesis of a motion is from the true motion: a rotation of
/// up to `angle_deg` and a translation shift of up to `shift`.
#[derive(Debug, Clone, Copy)]
pub struct Perturbation {
    pub angle_deg: f64,
    pub shift: f64,
}

/// The perturbation of the benchmarks: refined hypotheses whose residuals on
/// their motion's inliers stay within a few pixels.
pub const REFINED: Perturbation = Perturbation {
    angle_deg: 0.15,
    shift: 0.01,
};

/// `m` hypotheses: with probability `good_fraction` a perturbed copy of one
/// of the scene's motions (chosen uniformly), otherwise a random motion.
pub fn hypotheses(
    rng: &mut impl Rng,
    scene: &Scene,
    m: usize,
    good_fraction: f64,
    perturbation: Perturbation,
) -> Vec<Matrix3<f64>> {
    (0..m)
        .map(|_| {
            if rng.gen_bool(good_fraction) {
                let motion = scene.motions[rng.gen_range(0..scene.motions.len())];
                motion
                    .perturbed(rng, perturbation.angle_deg, perturbation.shift)
                    .fundamental()
            } else {
                Motion::random(rng).fundamental()
            }
        })
        .collect()
}
