//! Point-to-model distances for a fundamental matrix, and the FROB distance
//! between two fundamental matrices.
//!
//! For a match `x1 ↔ x2` (homogeneous, `x = (x, y, 1)`) let
//! `e = x2ᵀ F x1`, `F x1 = (a, b, ·)` and `Fᵀ x2 = (c, d, ·)`.

use crate::Correspondences;
use nalgebra::Matrix3;

/// Smallest denominator used by the distances: a point exactly at an epipole
/// has a zero gradient; it then gets distance 0 when it satisfies the
/// constraint and a huge distance otherwise, never NaN.
const MIN_DENOMINATOR: f64 = f64::MIN_POSITIVE;

#[inline(always)]
fn epipolar_terms(f: &Matrix3<f64>, p1: [f64; 2], p2: [f64; 2]) -> (f64, f64, f64) {
    let [x1, y1] = p1;
    let [x2, y2] = p2;
    // F x1
    let a = f[(0, 0)] * x1 + f[(0, 1)] * y1 + f[(0, 2)];
    let b = f[(1, 0)] * x1 + f[(1, 1)] * y1 + f[(1, 2)];
    let c3 = f[(2, 0)] * x1 + f[(2, 1)] * y1 + f[(2, 2)];
    // Fᵀ x2
    let c = f[(0, 0)] * x2 + f[(1, 0)] * y2 + f[(2, 0)];
    let d = f[(0, 1)] * x2 + f[(1, 1)] * y2 + f[(2, 1)];
    let e = x2 * a + y2 * b + c3;
    (e, a * a + b * b, c * c + d * d)
}

/// Squared Sampson distance (thesis Eq. 23), in px²:
/// `e² / (a² + b² + c² + d²)`.
///
/// Invariant to scaling and negating `F`.
///
/// ```
/// use geometry::sampson_distance_squared;
/// use nalgebra::Matrix3;
/// // Pure horizontal translation: F = [t]x with t = (1, 0, 0); epipolar lines are rows.
/// let f = Matrix3::new(0.0, 0.0, 0.0, 0.0, 0.0, -1.0, 0.0, 1.0, 0.0);
/// // The match is off by 2 px vertically: Sampson distance = 2² / 2.
/// let d2 = sampson_distance_squared(&f, [10.0, 5.0], [30.0, 7.0]);
/// assert!((d2 - 2.0).abs() < 1e-12);
/// ```
#[inline]
pub fn sampson_distance_squared(f: &Matrix3<f64>, p1: [f64; 2], p2: [f64; 2]) -> f64 {
    let (e, g1, g2) = epipolar_terms(f, p1, p2);
    e * e / (g1 + g2).max(MIN_DENOMINATOR)
}

/// Sampson distance (square root of Eq. 23), in px.
#[inline]
pub fn sampson_distance(f: &Matrix3<f64>, p1: [f64; 2], p2: [f64; 2]) -> f64 {
    sampson_distance_squared(f, p1, p2).sqrt()
}

/// Signed Sampson residual `e / sqrt(a² + b² + c² + d²)`, in px: the residual
/// whose median and MAD drive the IRLS scale (Eq. 34). Its sign flips with
/// the sign of `F`; its absolute value does not.
#[inline]
pub fn sampson_distance_signed(f: &Matrix3<f64>, p1: [f64; 2], p2: [f64; 2]) -> f64 {
    let (e, g1, g2) = epipolar_terms(f, p1, p2);
    e / (g1 + g2).max(MIN_DENOMINATOR).sqrt()
}

/// Symmetric epipolar distance (thesis Eq. 24), in px²: the sum of the squared
/// distances of each point to the epipolar line of the other,
/// `e² (1 / (a² + b²) + 1 / (c² + d²))`.
#[inline]
pub fn symmetric_epipolar_distance(f: &Matrix3<f64>, p1: [f64; 2], p2: [f64; 2]) -> f64 {
    let (e, g1, g2) = epipolar_terms(f, p1, p2);
    e * e * (1.0 / g1.max(MIN_DENOMINATOR) + 1.0 / g2.max(MIN_DENOMINATOR))
}

/// Squared Sampson distances (Eq. 23) of every correspondence to one `F`,
/// written into `out` (`out.len()` must equal `points.len()`; extra slots are
/// left untouched, missing ones are not written).
///
/// This is the hot loop of the preference matrix: it allocates nothing and
/// reads the four coordinate columns linearly.
///
/// ```
/// use geometry::{sampson_distances_squared, Correspondences};
/// use nalgebra::Matrix3;
/// let f = Matrix3::new(0.0, 0.0, 0.0, 0.0, 0.0, -1.0, 0.0, 1.0, 0.0);
/// let c = Correspondences::new(&[[0.0, 0.0], [5.0, 1.0]], &[[3.0, 0.0], [9.0, 3.0]]).unwrap();
/// let mut out = vec![0.0; 2];
/// sampson_distances_squared(&f, &c, &mut out);
/// assert_eq!(out[0], 0.0);
/// assert!((out[1] - 2.0).abs() < 1e-12);
/// ```
pub fn sampson_distances_squared(f: &Matrix3<f64>, points: &Correspondences, out: &mut [f64]) {
    let (x1, y1, x2, y2) = points.columns();
    let n = out.len().min(x1.len());
    let (f00, f01, f02) = (f[(0, 0)], f[(0, 1)], f[(0, 2)]);
    let (f10, f11, f12) = (f[(1, 0)], f[(1, 1)], f[(1, 2)]);
    let (f20, f21, f22) = (f[(2, 0)], f[(2, 1)], f[(2, 2)]);
    let (x1, y1, x2, y2) = (&x1[..n], &y1[..n], &x2[..n], &y2[..n]);
    for i in 0..n {
        let a = f00 * x1[i] + f01 * y1[i] + f02;
        let b = f10 * x1[i] + f11 * y1[i] + f12;
        let c3 = f20 * x1[i] + f21 * y1[i] + f22;
        let c = f00 * x2[i] + f10 * y2[i] + f20;
        let d = f01 * x2[i] + f11 * y2[i] + f21;
        let e = x2[i] * a + y2[i] * b + c3;
        out[i] = e * e / (a * a + b * b + c * c + d * d).max(MIN_DENOMINATOR);
    }
}

/// FROB distance between two fundamental matrices (thesis Eq. 45):
/// `min(‖Fa/‖Fa‖ − Fb/‖Fb‖‖, ‖Fa/‖Fa‖ + Fb/‖Fb‖‖)` with Frobenius norms, so
/// that the scale and sign ambiguity of `F` does not count. In `[0, √2]`.
///
/// ```
/// use geometry::frob_distance;
/// use nalgebra::Matrix3;
/// let f = Matrix3::new(1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 0.0);
/// assert!(frob_distance(&f, &(-3.0 * f)) < 1e-15);
/// ```
pub fn frob_distance(fa: &Matrix3<f64>, fb: &Matrix3<f64>) -> f64 {
    let a = fa / fa.norm();
    let b = fb / fb.norm();
    (a - b).norm().min((a + b).norm())
}
