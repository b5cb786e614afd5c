//! Fixtures shared by the unit tests of the polynomial solver's modules
//! (bivariate products, resultant, Aberth, Bezout, SIMD builds, the
//! robust solve).

use nalgebra::{Matrix3, Rotation3, Vector3};

use crate::bivariate::{Lin2, Quartic2};

/// The line `c0 + c1 t1 + c2 t2`.
pub(crate) fn lin(c0: f64, c1: f64, c2: f64) -> Lin2 {
    Lin2([c0, c1, c2])
}

/// Product of four lines `a_k + b_k t1 + c_k t2`.
pub(crate) fn product_of_lines(lines: &[[f64; 3]; 4]) -> Quartic2 {
    let line = |l: &[f64; 3]| lin(l[0], l[1], l[2]);
    let q1 = line(&lines[0]).mul(&line(&lines[1]));
    let q2 = line(&lines[2]).mul(&line(&lines[3]));
    q1.mul(&q2)
}

/// Two sets of four lines `a0 + a1 t1 + a2 t2 = 0` whose products are
/// P and Q: their 16 intersections are the real solutions.
pub(crate) const LINES_P: [[f64; 3]; 4] = [
    [0.3, 1.0, 0.2],
    [-0.5, 1.0, -0.4],
    [0.1, 0.8, 1.0],
    [-0.9, -0.3, 1.0],
];
/// See [`LINES_P`].
pub(crate) const LINES_Q: [[f64; 3]; 4] = [
    [0.2, 1.0, 0.9],
    [0.7, -1.0, 0.35],
    [-0.4, 0.15, 1.0],
    [0.6, 0.5, -1.0],
];

/// The intersection `(t1, t2)` of the lines `a` and `b`.
pub(crate) fn intersection(a: &[f64; 3], b: &[f64; 3]) -> [f64; 2] {
    let det = a[1] * b[2] - a[2] * b[1];
    let t1 = (-a[0] * b[2] + a[2] * b[0]) / det;
    let t2 = (a[1] * (-b[0]) + a[0] * b[1]) / det;
    [t1, t2]
}

/// Ascending coefficients of `prod (z - r)` over real roots and
/// conjugate pairs `a ± bi`.
pub(crate) fn poly_from_roots(real: &[f64], pairs: &[(f64, f64)]) -> Vec<f64> {
    let mut poly = vec![1.0];
    let mut mul = |r: &[f64]| {
        let mut out = vec![0.0; poly.len() + r.len() - 1];
        for (i, a) in poly.iter().enumerate() {
            for (j, b) in r.iter().enumerate() {
                out[i + j] += a * b;
            }
        }
        poly = out;
    };
    for &r in real {
        mul(&[-r, 1.0]);
    }
    for &(a, b) in pairs {
        mul(&[a * a + b * b, -2.0 * a, 1.0]);
    }
    poly
}

/// `K2^-T [t]x R K1^-1` scaled to unit norm, plus a deterministic
/// perturbation of size `noise`.
pub(crate) fn sample_f(
    angles: [f64; 3],
    t: [f64; 3],
    f1: f64,
    f2: f64,
    noise: f64,
) -> Matrix3<f64> {
    let r = Rotation3::from_euler_angles(angles[0], angles[1], angles[2]).into_inner();
    let k1 = Matrix3::from_diagonal(&Vector3::new(1.0 / f1, 1.0 / f1, 1.0));
    let k2 = Matrix3::from_diagonal(&Vector3::new(1.0 / f2, 1.0 / f2, 1.0));
    let f = k2.transpose() * Vector3::from(t).cross_matrix() * r * k1;
    f / f.norm() + Matrix3::from_fn(|i, j| noise * ((3 * i + j) as f64 * 1.7).sin())
}
