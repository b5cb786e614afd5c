//! Bougnoux's closed-form focal lengths (docs/method.md step 4).

use nalgebra::{Matrix3, Vector3};

use crate::error::FocalFailure;
use crate::kruppa::sorted_svd;

/// Focal lengths `(f1, f2)` of image 1 and image 2 from a fundamental matrix
/// by Bougnoux's closed form (Bougnoux 1998; Hartley & Zisserman), for the
/// principal points `pp1` (image 1) and `pp2` (image 2), in the pixel frame
/// in which `x2^T F x1 = 0`.
///
/// With `p = (pp1, 1)`, `p' = (pp2, 1)`, the epipoles `e` (`F e = 0`) and
/// `e'` (`F^T e' = 0`) and `I~ = diag(1, 1, 0)`:
///
/// ```text
/// f1^2 = - (p'^T [e']x I~ F p) (p^T F^T p') / (p'^T [e']x I~ F I~ F^T p')
/// f2^2 = - (p^T [e]x I~ F^T p') (p'^T F p) / (p^T [e]x I~ F^T I~ F p)
/// ```
///
/// The formula is invariant to the scale and sign of F and of the epipoles.
/// Fails with [`FocalFailure::NoRealFocal`] when `f^2 <= 0`,
/// [`FocalFailure::Singular`] when a denominator `a . b` is below
/// `1e-12 |a| |b|` (twelve digits of cancellation) or the result is not
/// finite, and
/// [`FocalFailure::InvalidMatrix`] / [`FocalFailure::InvalidParameter`] on
/// non-finite input. The first failing image decides the error; use
/// [`bougnoux_per_image`] to get each image's answer separately.
///
/// ```
/// use nalgebra::{Matrix3, Rotation3, Vector3};
/// // F = K2^-T [t]x R K1^-1 for focal lengths 700 and 1300.
/// let r = Rotation3::from_euler_angles(0.1, -0.2, 0.05).into_inner();
/// let t = Vector3::new(0.3, -0.1, 1.0);
/// let k1_inv = Matrix3::from_diagonal(&Vector3::new(1.0 / 700.0, 1.0 / 700.0, 1.0));
/// let k2_inv = Matrix3::from_diagonal(&Vector3::new(1.0 / 1300.0, 1.0 / 1300.0, 1.0));
/// let f = k2_inv.transpose() * t.cross_matrix() * r * k1_inv;
/// let (f1, f2) = focal::bougnoux(&f, [0.0, 0.0], [0.0, 0.0]).unwrap();
/// assert!((f1 - 700.0).abs() < 1e-6 && (f2 - 1300.0).abs() < 1e-6);
/// ```
pub fn bougnoux(
    f: &Matrix3<f64>,
    pp1: [f64; 2],
    pp2: [f64; 2],
) -> Result<(f64, f64), FocalFailure> {
    let [a, b] = bougnoux_per_image(f, pp1, pp2);
    Ok((a?, b?))
}

/// Bougnoux's focal length of each image separately (see [`bougnoux`] for
/// the formula): `[f1, f2]`, each a value or the reason it has none.
pub fn bougnoux_per_image(
    f: &Matrix3<f64>,
    pp1: [f64; 2],
    pp2: [f64; 2],
) -> [Result<f64, FocalFailure>; 2] {
    match prepare(f, pp1, pp2) {
        Err(e) => [Err(e), Err(e)],
        Ok((fnorm, e1, e2, p1, p2)) => [
            // Image 1: epipole of image 2.
            focal_from(&fnorm, &e2, &p2, &p1),
            // Image 2: the same formula on F^T with the roles swapped.
            focal_from(&fnorm.transpose(), &e1, &p1, &p2),
        ],
    }
}

type Prepared = (
    Matrix3<f64>,
    Vector3<f64>,
    Vector3<f64>,
    Vector3<f64>,
    Vector3<f64>,
);

fn prepare(f: &Matrix3<f64>, pp1: [f64; 2], pp2: [f64; 2]) -> Result<Prepared, FocalFailure> {
    if !f.iter().all(|v| v.is_finite()) {
        return Err(FocalFailure::InvalidMatrix);
    }
    for (name, pp) in [("pp1", pp1), ("pp2", pp2)] {
        for v in pp {
            if !v.is_finite() {
                return Err(FocalFailure::InvalidParameter {
                    name,
                    value: v,
                    requirement: "must be finite",
                });
            }
        }
    }
    let norm = f.norm();
    if !(norm.is_finite() && norm > 0.0) {
        return Err(FocalFailure::InvalidMatrix);
    }
    let fnorm = f / norm;
    let (u, _, v) = sorted_svd(&fnorm).ok_or(FocalFailure::InvalidMatrix)?;
    let e1 = v.column(2).into_owned();
    let e2 = u.column(2).into_owned();
    let p1 = Vector3::new(pp1[0], pp1[1], 1.0);
    let p2 = Vector3::new(pp2[0], pp2[1], 1.0);
    Ok((fnorm, e1, e2, p1, p2))
}

/// The denominator of [`focal_from`] counts as zero when it is below this
/// fraction of the product of its two factors' norms (its Cauchy–Schwarz
/// bound): beyond about twelve digits of cancellation it is rounding noise.
/// Relative, so that the test does not depend on the focal length or the
/// principal point, which set the denominator's magnitude.
const SINGULAR_CANCELLATION: f64 = 1e-12;

/// `f^2 = - (q^T [e]x I~ F p)(q^T F p) / (q^T [e]x I~ F I~ F^T q)`, the
/// focal of the image whose principal point is `p` (F maps its points to
/// lines in the other image, whose epipole is `e` and principal point `q`).
fn focal_from(
    f: &Matrix3<f64>,
    e: &Vector3<f64>,
    q: &Vector3<f64>,
    p: &Vector3<f64>,
) -> Result<f64, FocalFailure> {
    let itilde = Matrix3::from_diagonal(&Vector3::new(1.0, 1.0, 0.0));
    let row = q.transpose() * e.cross_matrix() * itilde * f; // q^T [e]x I~ F
    let col = itilde * f.transpose() * q; // I~ F^T q
    let num = -(row * p)[0] * (q.transpose() * f * p)[0];
    let den = (row * col)[0];
    if den.is_nan() || den.abs() <= SINGULAR_CANCELLATION * row.norm() * col.norm() {
        return Err(FocalFailure::Singular);
    }
    let f_sq = num / den;
    if !f_sq.is_finite() {
        return Err(FocalFailure::Singular);
    }
    if f_sq <= 0.0 {
        return Err(FocalFailure::NoRealFocal);
    }
    Ok(f_sq.sqrt())
}
