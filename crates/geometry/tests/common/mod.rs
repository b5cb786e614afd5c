//! Seeded synthetic two-view scenes and naive reference estimators shared by
//! the integration tests and the benchmarks.
#![allow(dead_code)]

use geometry::Correspondences;
use nalgebra::{DMatrix, Matrix3, Rotation3, Unit, Vector3};
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal, UnitSphere};

/// Image size used for the synthetic views (principal point at the origin).
pub const WIDTH: f64 = 640.0;
pub const HEIGHT: f64 = 480.0;

/// A synthetic two-view scene: `inliers` matches of one rigid motion followed
/// by `outliers` gross outliers (uniform in both images).
pub struct Scene {
    pub points: Correspondences,
    /// The same matches before the noise was added (outliers unchanged).
    pub exact: Correspondences,
    /// `K2⁻ᵀ [t]x R K1⁻¹`.
    pub f_true: Matrix3<f64>,
    pub focal1: f64,
    pub focal2: f64,
    /// `is_inlier[i]`: match `i` follows the motion.
    pub is_inlier: Vec<bool>,
}

pub fn skew(t: &Vector3<f64>) -> Matrix3<f64> {
    Matrix3::new(0.0, -t.z, t.y, t.z, 0.0, -t.x, -t.y, t.x, 0.0)
}

pub fn intrinsics(focal: f64) -> Matrix3<f64> {
    Matrix3::new(focal, 0.0, 0.0, 0.0, focal, 0.0, 0.0, 0.0, 1.0)
}

/// Random rigid scene seen by two cameras with focal lengths in
/// [500, 1500] px: camera 1 at the origin, camera 2 = (R, t) with a random
/// rotation of 0.05–0.4 rad and a baseline of 0.5–1.5; 3-D points at depth
/// 4–12 that project inside the first image and in front of both cameras.
/// Gaussian noise of `noise_px` is added to every inlier coordinate.
pub fn random_scene(rng: &mut ChaCha8Rng, inliers: usize, outliers: usize, noise_px: f64) -> Scene {
    let focal1 = rng.gen_range(500.0..1500.0);
    let focal2 = rng.gen_range(500.0..1500.0);
    let axis: [f64; 3] = UnitSphere.sample(rng);
    let angle = rng.gen_range(0.05..0.4);
    let r = Rotation3::from_axis_angle(&Unit::new_normalize(Vector3::from(axis)), angle);
    let dir: [f64; 3] = UnitSphere.sample(rng);
    let t = Vector3::from(dir) * rng.gen_range(0.5..1.5);
    let (k1, k2) = (intrinsics(focal1), intrinsics(focal2));
    let f_true =
        k2.try_inverse().unwrap().transpose() * skew(&t) * r.matrix() * k1.try_inverse().unwrap();

    let noise = Normal::new(0.0, noise_px.max(f64::MIN_POSITIVE)).unwrap();
    let draw_noise = |rng: &mut ChaCha8Rng| {
        if noise_px > 0.0 {
            noise.sample(rng)
        } else {
            0.0
        }
    };
    let (mut p1, mut p2) = (Vec::new(), Vec::new());
    let (mut e1, mut e2) = (Vec::new(), Vec::new());
    while p1.len() < inliers {
        let u = rng.gen_range(-WIDTH / 2.0..WIDTH / 2.0);
        let v = rng.gen_range(-HEIGHT / 2.0..HEIGHT / 2.0);
        let depth = rng.gen_range(4.0..12.0);
        let x = Vector3::new(u / focal1, v / focal1, 1.0) * depth;
        let y = r * x + t;
        if y.z < 1.0 {
            continue;
        }
        let (u2, v2) = (focal2 * y.x / y.z, focal2 * y.y / y.z);
        if u2.abs() > WIDTH || v2.abs() > HEIGHT {
            continue;
        }
        p1.push([u + draw_noise(rng), v + draw_noise(rng)]);
        p2.push([u2 + draw_noise(rng), v2 + draw_noise(rng)]);
        e1.push([u, v]);
        e2.push([u2, v2]);
    }
    for _ in 0..outliers {
        p1.push(random_pixel(rng));
        p2.push(random_pixel(rng));
    }
    e1.extend_from_slice(&p1[inliers..]);
    e2.extend_from_slice(&p2[inliers..]);
    let mut is_inlier = vec![true; inliers];
    is_inlier.resize(inliers + outliers, false);
    Scene {
        points: Correspondences::new(&p1, &p2).unwrap(),
        exact: Correspondences::new(&e1, &e2).unwrap(),
        f_true,
        focal1,
        focal2,
        is_inlier,
    }
}

pub fn random_pixel(rng: &mut ChaCha8Rng) -> [f64; 2] {
    [
        rng.gen_range(-WIDTH / 2.0..WIDTH / 2.0),
        rng.gen_range(-HEIGHT / 2.0..HEIGHT / 2.0),
    ]
}

/// `k` distinct indices out of `0..n`, uniformly.
pub fn sample_indices(rng: &mut ChaCha8Rng, n: usize, k: usize) -> Vec<usize> {
    rand::seq::index::sample(rng, n, k).into_vec()
}

/// Textbook one-sided Jacobi SVD of a dynamic matrix (Demmel & Veselić):
/// returns `(singular values, V, A V)`, unsorted. Written independently of
/// the crate's fixed-size kernel, allocating freely; an oracle for tests.
pub fn naive_jacobi_svd(a: &DMatrix<f64>) -> (Vec<f64>, DMatrix<f64>, DMatrix<f64>) {
    let n = a.ncols();
    let mut u = a.clone();
    let mut v = DMatrix::<f64>::identity(n, n);
    for _ in 0..100 {
        let mut off = 0.0_f64;
        for p in 0..n {
            for q in p + 1..n {
                let alpha = u.column(p).norm_squared();
                let beta = u.column(q).norm_squared();
                let gamma = u.column(p).dot(&u.column(q));
                if gamma == 0.0 {
                    continue;
                }
                off = off.max(gamma.abs() / (alpha * beta).sqrt());
                let zeta = (beta - alpha) / (2.0 * gamma);
                let t = zeta.signum() / (zeta.abs() + (1.0 + zeta * zeta).sqrt());
                let c = 1.0 / (1.0 + t * t).sqrt();
                let s = c * t;
                for m in [&mut u, &mut v] {
                    let cp = m.column(p).clone_owned();
                    let cq = m.column(q).clone_owned();
                    m.set_column(p, &(&cp * c - &cq * s));
                    m.set_column(q, &(&cp * s + &cq * c));
                }
            }
        }
        if off < 1e-15 {
            break;
        }
    }
    let sv = (0..n).map(|j| u.column(j).norm()).collect();
    (sv, v, u)
}

/// Naive reference: the unit vector minimising `‖diag(√w) X f‖`, from the
/// Jacobi SVD of the full N × 9 design matrix (no QR, no normal matrix),
/// reshaped row-major; no normalisation, no rank 2.
pub fn naive_least_squares(p1: &[[f64; 2]], p2: &[[f64; 2]], weights: &[f64]) -> Matrix3<f64> {
    let mut x = DMatrix::<f64>::zeros(p1.len(), 9);
    for i in 0..p1.len() {
        let ([x1, y1], [x2, y2]) = (p1[i], p2[i]);
        let s = weights[i].sqrt();
        let row = [x2 * x1, x2 * y1, x2, y2 * x1, y2 * y1, y2, x1, y1, 1.0];
        for (j, v) in row.iter().enumerate() {
            x[(i, j)] = s * v;
        }
    }
    let (sv, v, _) = naive_jacobi_svd(&x);
    let k = (0..9).min_by(|&a, &b| sv[a].total_cmp(&sv[b])).unwrap();
    let f = v.column(k);
    Matrix3::new(f[0], f[1], f[2], f[3], f[4], f[5], f[6], f[7], f[8])
}

/// Naive rank-2 projection: `F = Σ_j (A V)_j v_jᵀ` without the smallest term.
pub fn naive_rank2(f: &Matrix3<f64>) -> Matrix3<f64> {
    let (sv, v, av) = naive_jacobi_svd(&DMatrix::from_fn(3, 3, |r, c| f[(r, c)]));
    let k = (0..3).min_by(|&a, &b| sv[a].total_cmp(&sv[b])).unwrap();
    let mut g = Matrix3::zeros();
    for j in (0..3).filter(|&j| j != k) {
        g += Matrix3::from_fn(|r, c| av[(r, j)] * v[(c, j)]);
    }
    g
}

/// Naive weighted Hartley-normalised 8-point written directly from the
/// textbook recipe: weighted centroid and mean distance, explicit
/// normalised coordinates, dynamic SVD, rank 2, `T2ᵀ F̂ T1`.
pub fn naive_normalized(p1: &[[f64; 2]], p2: &[[f64; 2]], weights: &[f64]) -> Matrix3<f64> {
    let transform = |pts: &[[f64; 2]]| {
        let sw: f64 = weights.iter().sum();
        let cx = pts.iter().zip(weights).map(|(p, w)| w * p[0]).sum::<f64>() / sw;
        let cy = pts.iter().zip(weights).map(|(p, w)| w * p[1]).sum::<f64>() / sw;
        let d = pts
            .iter()
            .zip(weights)
            .map(|(p, w)| w * ((p[0] - cx).powi(2) + (p[1] - cy).powi(2)).sqrt())
            .sum::<f64>()
            / sw;
        let s = 2f64.sqrt() / d;
        Matrix3::new(s, 0.0, -s * cx, 0.0, s, -s * cy, 0.0, 0.0, 1.0)
    };
    let (t1, t2) = (transform(p1), transform(p2));
    let apply = |t: &Matrix3<f64>, pts: &[[f64; 2]]| {
        pts.iter()
            .map(|p| {
                let q = t * Vector3::new(p[0], p[1], 1.0);
                [q.x, q.y]
            })
            .collect::<Vec<_>>()
    };
    let f_hat = naive_rank2(&naive_least_squares(
        &apply(&t1, p1),
        &apply(&t2, p2),
        weights,
    ));
    let f = t2.transpose() * f_hat * t1;
    f / f.norm()
}

/// `points` with the matches at `indices` replaced by their noise-free
/// positions from `scene.exact`.
pub fn with_exact(scene: &Scene, indices: &[usize]) -> Correspondences {
    let (mut p1, mut p2) = point_lists(&scene.points);
    for &i in indices {
        p1[i] = scene.exact.point1(i);
        p2[i] = scene.exact.point2(i);
    }
    Correspondences::new(&p1, &p2).unwrap()
}

/// The two point lists of a correspondence set.
pub fn point_lists(points: &Correspondences) -> (Vec<[f64; 2]>, Vec<[f64; 2]>) {
    (0..points.len())
        .map(|i| (points.point1(i), points.point2(i)))
        .unzip()
}

/// A fixture's JSON array of nine numbers as the row-major matrix.
pub fn json_matrix(v: &serde_json::Value) -> Matrix3<f64> {
    let e: Vec<f64> = v
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    Matrix3::from_row_slice(&e)
}

/// A fixture's JSON array of `N`-number arrays (points, bearings).
pub fn json_rows<const N: usize>(v: &serde_json::Value) -> Vec<[f64; N]> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|p| std::array::from_fn(|k| p[k].as_f64().unwrap()))
        .collect()
}
