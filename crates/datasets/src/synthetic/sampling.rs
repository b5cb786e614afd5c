//! The random draws and the camera geometry of the synthetic generator:
//! uniform values and counts, random directions and rotations, the
//! fundamental matrix of a motion, projection, and the shapes' surface
//! points.

use nalgebra::{Matrix3, Rotation3, Unit, Vector3};
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};

use super::ShapeMix;

/// A uniform draw from `[lo, hi]` (`lo` when the range is empty).
pub(crate) fn uniform(rng: &mut ChaCha8Rng, [lo, hi]: [f64; 2]) -> f64 {
    if hi > lo {
        rng.gen_range(lo..=hi)
    } else {
        lo
    }
}

/// A log-uniform draw from `[lo, hi]`, `0 < lo` (`lo` when the range is
/// empty): `exp` of a uniform draw from `[ln lo, ln hi]`.
pub(super) fn log_uniform(rng: &mut ChaCha8Rng, [lo, hi]: [f64; 2]) -> f64 {
    uniform(rng, [lo.ln(), hi.ln()]).exp().clamp(lo, hi)
}

/// A uniform count from `[lo, hi]`.
pub(super) fn uniform_count(rng: &mut ChaCha8Rng, [lo, hi]: [usize; 2]) -> usize {
    rng.gen_range(lo..=hi)
}

/// A uniformly random unit vector (a normalised Gaussian 3-vector).
pub(super) fn random_unit(rng: &mut ChaCha8Rng) -> Unit<Vector3<f64>> {
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

/// A Gaussian 4-vector of standard deviation `sigma` per coordinate (the
/// noise of a match `(x1, y1, x2, y2)`), redrawn while its length exceeds
/// `truncation` σ (`truncation` 0: never redrawn).
pub(super) fn truncated_noise(rng: &mut ChaCha8Rng, sigma: f64, truncation: f64) -> [f64; 4] {
    let limit = truncation * sigma;
    loop {
        let v: [f64; 4] = std::array::from_fn(|_| {
            let z: f64 = StandardNormal.sample(rng);
            z * sigma
        });
        if limit == 0.0 || v.iter().map(|x| x * x).sum::<f64>() <= limit * limit {
            return v;
        }
    }
}

/// A rotation about a random axis by an angle uniform in `degrees`.
pub(super) fn random_rotation(rng: &mut ChaCha8Rng, degrees: [f64; 2]) -> Rotation3<f64> {
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

/// `K = [[f, 0, cx], [0, f, cy], [0, 0, 1]]` (square pixels, no skew).
pub(super) fn intrinsics(focal: f64, principal_point: [f64; 2]) -> Matrix3<f64> {
    let [cx, cy] = principal_point;
    Matrix3::new(focal, 0.0, cx, 0.0, focal, cy, 0.0, 0.0, 1.0)
}

/// The pixel of the camera-frame point `x` (`None` behind the camera).
pub(super) fn project(k: &Matrix3<f64>, x: &Vector3<f64>) -> Option<[f64; 2]> {
    if x.z <= 1e-9 {
        return None;
    }
    let p = k * x;
    Some([p.x / p.z, p.y / p.z])
}

/// Shape-local points (bounding sphere of diameter `size` about the origin).
pub(super) fn sample_shape(
    rng: &mut ChaCha8Rng,
    mix: &ShapeMix,
    n: usize,
    size: f64,
) -> Vec<Vector3<f64>> {
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

/// The pinhole camera of both views (`K`, its inverse, the image size).
pub(super) struct Camera {
    /// The intrinsics `K`.
    pub(super) k: Matrix3<f64>,
    /// `K⁻¹`.
    pub(super) k_inv: Matrix3<f64>,
    /// The focal length `f`, px.
    pub(super) focal: f64,
    /// The principal point `(cx, cy)`, px.
    pub(super) principal_point: [f64; 2],
    /// Image width W, px.
    pub(super) width: f64,
    /// Image height H, px.
    pub(super) height: f64,
}

impl Camera {
    /// Whether the pixel lies in the image (`0 ≤ x ≤ W−1`, `0 ≤ y ≤ H−1`).
    pub(super) fn inside(&self, p: [f64; 2]) -> bool {
        (0.0..=self.width - 1.0).contains(&p[0]) && (0.0..=self.height - 1.0).contains(&p[1])
    }

    /// A pixel uniform in the image (x first, then y).
    pub(super) fn random_pixel(&self, rng: &mut ChaCha8Rng) -> [f64; 2] {
        [
            rng.gen_range(0.0..=self.width - 1.0),
            rng.gen_range(0.0..=self.height - 1.0),
        ]
    }

    /// The camera-frame point of `pixel` at `depth`.
    pub(super) fn back_project(&self, pixel: [f64; 2], depth: f64) -> Vector3<f64> {
        self.k_inv * Vector3::new(pixel[0], pixel[1], 1.0) * depth
    }
}

/// The camera-2 image of a point `x` (camera-1 coordinates) that moves by
/// `(R, T)` in camera-2 coordinates.
pub(super) fn view2(
    cam: &Camera,
    r: &Matrix3<f64>,
    t: &Vector3<f64>,
    x: &Vector3<f64>,
) -> Option<[f64; 2]> {
    project(&cam.k, &(r * x + t))
}
