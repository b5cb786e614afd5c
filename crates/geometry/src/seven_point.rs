//! The 7-point fundamental-matrix solver (Hartley & Zisserman, *Multiple
//! View Geometry*, 2nd ed., §11.1.2).
//!
//! Seven matches give seven equations `x2ᵀ F x1 = 0`, linear in the nine
//! entries of `F`: their null space is two-dimensional, `F = a F1 + b F2`.
//! The rank constraint `det(a F1 + b F2) = 0` is a homogeneous cubic in
//! `(a, b)` (H&Z write it `det(αF1 + (1 − α)F2) = 0`), with one or three
//! real roots, each a fundamental matrix consistent with the seven matches.
//!
//! Numerics: Hartley normalisation of each image first (centroid to the
//! origin, mean distance `√2`), the null space by a column-pivoted Householder QR,
//! and the cubic solved in `t = b/a` or `s = a/b`, whichever has the larger
//! leading coefficient (so a root at `a = 0` or `b = 0` is never lost), by
//! the eigenvalues of its companion matrix and two Newton steps.

use crate::action::real_roots;
use crate::eight_point::finish;
use crate::minimal::{
    check_sample_size, epipolar_row, is_duplicate, matrix_from_row_major, null_basis,
};
use crate::poly::{det, Poly3};
use crate::{Correspondences, GeometryError};
use nalgebra::{Matrix3, Vector3};

/// Number of matches of the 7-point solver.
pub const SEVEN_POINT_SAMPLE: usize = 7;

/// All fundamental matrices (1 or 3; 2 when a double root is returned
/// once) through exactly seven matches in
/// pixel coordinates: `x2ᵀ F x1 = 0` for each match and `det F = 0`
/// (Hartley & Zisserman §11.1.2). Each `F` has unit Frobenius norm and the
/// sign that makes its entry of largest magnitude positive.
///
/// Errors: [`GeometryError::SampleSize`] unless there are exactly 7 matches;
/// [`GeometryError::Degenerate`] when the points of one image coincide or the
/// 7 × 9 system has a null space of dimension > 2 (e.g. duplicated matches,
/// collinear points), or the cubic vanishes identically.
///
/// ```
/// use geometry::{seven_point, Correspondences};
/// let p1 = [[0.0, 0.0], [100.0, 0.0], [0.0, 80.0], [60.0, 50.0], [-70.0, 20.0], [30.0, -90.0], [-40.0, -60.0]];
/// // Pure sideways translation with varying depth: F ∝ [e1]x.
/// let p2: Vec<[f64; 2]> = p1.iter().enumerate().map(|(i, p)| [p[0] + 50.0 / (1.0 + i as f64), p[1]]).collect();
/// let fs = seven_point(&Correspondences::new(&p1, &p2).unwrap()).unwrap();
/// assert!(fs.iter().any(|f| (f[(1, 2)].abs() - 0.5f64.sqrt()).abs() < 1e-9));
/// ```
pub fn seven_point(points: &Correspondences) -> Result<Vec<Matrix3<f64>>, GeometryError> {
    check_sample_size(points.len(), SEVEN_POINT_SAMPLE)?;
    let (x1, y1, x2, y2) = points.columns();
    let t1 = hartley_transform(x1, y1)?;
    let t2 = hartley_transform(x2, y2)?;
    let rows: Vec<[f64; 9]> = (0..SEVEN_POINT_SAMPLE)
        .map(|i| {
            let q1 = t1 * Vector3::new(x1[i], y1[i], 1.0);
            let q2 = t2 * Vector3::new(x2[i], y2[i], 1.0);
            epipolar_row(q1.into(), q2.into())
        })
        .collect();
    let [f1, f2] = null_basis::<2>(&rows)?;
    let (f1, f2) = (matrix_from_row_major(&f1), matrix_from_row_major(&f2));
    let mut solutions = Vec::with_capacity(3);
    for (a, b) in pencil_roots(&f1, &f2)? {
        let f = finish(t2.transpose() * (f1 * a + f2 * b) * t1)?;
        if !is_duplicate(solutions.iter(), &f) {
            solutions.push(f);
        }
    }
    Ok(solutions)
}

/// The real roots `(a, b)` of the homogeneous cubic `det(a F1 + b F2) = 0`,
/// scaled so that the larger of `|a|, |b|` is 1.
fn pencil_roots(f1: &Matrix3<f64>, f2: &Matrix3<f64>) -> Result<Vec<(f64, f64)>, GeometryError> {
    // det(F1 + t F2) = d0 + d1 t + d2 t² + d3 t³, i.e.
    // det(a F1 + b F2) = Σ d_k a^(3−k) b^k.
    let entries: [[Poly3; 3]; 3] = std::array::from_fn(|r| {
        std::array::from_fn(|c| Poly3::linear(f2[(r, c)], 0.0, 0.0, f1[(r, c)]))
    });
    let cubic = det(&entries);
    let d: [f64; 4] = std::array::from_fn(|k| cubic.coeff(k, 0, 0));
    let scale = d.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    if scale.partial_cmp(&f64::MIN_POSITIVE) != Some(std::cmp::Ordering::Greater) {
        return Err(GeometryError::Degenerate(
            "7-point: det(a F1 + b F2) vanishes identically",
        ));
    }
    if d[3].abs() >= d[0].abs() {
        let roots = real_roots(&d).ok_or(GeometryError::Degenerate("7-point cubic"))?;
        Ok(roots.into_iter().map(|t| unit_pair(1.0, t)).collect())
    } else {
        let reversed = [d[3], d[2], d[1], d[0]];
        let roots = real_roots(&reversed).ok_or(GeometryError::Degenerate("7-point cubic"))?;
        Ok(roots.into_iter().map(|s| unit_pair(s, 1.0)).collect())
    }
}

/// `(a, b) / max(|a|, |b|)`.
fn unit_pair(a: f64, b: f64) -> (f64, f64) {
    let m = a.abs().max(b.abs());
    (a / m, b / m)
}

/// Hartley's normalising transform of one image's points: centroid to the
/// origin, mean distance to it `√2`. [`GeometryError::Degenerate`] when all
/// points coincide.
pub(crate) fn hartley_transform(xs: &[f64], ys: &[f64]) -> Result<Matrix3<f64>, GeometryError> {
    let n = xs.len() as f64;
    let (cx, cy) = (xs.iter().sum::<f64>() / n, ys.iter().sum::<f64>() / n);
    let mean = xs
        .iter()
        .zip(ys)
        .map(|(x, y)| (x - cx).hypot(y - cy))
        .sum::<f64>()
        / n;
    let s = std::f64::consts::SQRT_2 / mean;
    if !(s.is_finite() && s > 0.0 && cx.is_finite() && cy.is_finite()) {
        return Err(GeometryError::Degenerate(
            "all points coincide in one image",
        ));
    }
    Ok(Matrix3::new(
        s,
        0.0,
        -s * cx,
        0.0,
        s,
        -s * cy,
        0.0,
        0.0,
        1.0,
    ))
}
