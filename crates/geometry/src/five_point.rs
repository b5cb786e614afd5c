//! The 5-point essential-matrix solver: Nistér 2004 ("An efficient solution
//! to the five-point relative pose problem", PAMI 26(6)) in the Gröbner-basis
//! form of Stewénius, Engels & Nistér 2006 ("Recent developments on direct
//! relative orientation", ISPRS J. 60, §3).
//!
//! Five matches of calibrated bearings `q1 ↔ q2` give five equations
//! `q2ᵀ E q1 = 0`; their null space is four-dimensional,
//! `E = x X + y Y + z Z + W`. The essential matrices are the real solutions
//! of the ten cubic equations
//!
//! ```text
//! det E = 0,                       2 E Eᵀ E − tr(E Eᵀ) E = 0
//! ```
//!
//! (Nistér Eqs. 4–5). Their coefficients form a 10 × 20 matrix over the
//! monomials `x³, x²y, x²z, xy², xyz, xz², y³, y²z, yz², z³ | x², xy, xz,
//! y², yz, z², x, y, z, 1`; Gauss–Jordan elimination of the first block
//! (`[I | B]`) expresses the six cubics divisible by `x` in the ten
//! monomials after the bar, which gives the 10 × 10 action matrix of
//! multiplication by `x` on the quotient ring (Stewénius et al. 2006, §3.3).
//! Its real eigenvalues are the `x` of the real solutions; its eigenvectors
//! are the monomial vectors, from which `y = v_y / v_1`, `z = v_z / v_1`.
//! Each root is then polished by Gauss–Newton steps on the ten equations.
//! Up to 10 solutions.

use crate::action::{null_vector, real_eigenvalues};
use crate::eight_point::finish;
use crate::minimal::{
    check_sample_size, epipolar_row, is_duplicate, matrix_from_row_major, null_basis,
};
use crate::poly::{det, mat_mul, polish_root, trace_constraint, transpose, Poly3, PolyMatrix};
use crate::GeometryError;
use nalgebra::{DMatrix, Matrix3, SMatrix, Vector3};

/// Number of matches of the 5-point solver.
pub const FIVE_POINT_SAMPLE: usize = 5;

/// Gauss–Newton steps on the ten constraints that polish each root read off
/// the action matrix (its eigenvalues of a non-normal matrix carry errors
/// up to ~1e-8; two steps bring them to rounding level).
const POLISH_STEPS: usize = 3;

/// Exponents `(x, y, z)` of the 20 monomials of degree ≤ 3, in the
/// elimination order of Stewénius et al. 2006 (the 10 cubics first).
const MONOMIALS: [(usize, usize, usize); 20] = [
    (3, 0, 0),
    (2, 1, 0),
    (2, 0, 1),
    (1, 2, 0),
    (1, 1, 1),
    (1, 0, 2),
    (0, 3, 0),
    (0, 2, 1),
    (0, 1, 2),
    (0, 0, 3),
    (2, 0, 0),
    (1, 1, 0),
    (1, 0, 1),
    (0, 2, 0),
    (0, 1, 1),
    (0, 0, 2),
    (1, 0, 0),
    (0, 1, 0),
    (0, 0, 1),
    (0, 0, 0),
];

/// All real essential matrices (up to 10) consistent with five matches of
/// calibrated bearings: `q2ᵀ E q1 = 0` for each match, `det E = 0` and
/// `2 E Eᵀ E − tr(E Eᵀ) E = 0` (Nistér 2004; Stewénius et al. 2006).
///
/// Input: bearings `q = K⁻¹ (u, v, 1)ᵀ` of image 1 and image 2, any
/// non-zero length (normalised internally); for normalised image points
/// `(x, y)` pass `(x, y, 1)`. Output: each `E` with unit Frobenius norm and
/// the sign that makes its entry of largest magnitude positive; possibly
/// empty when the system has no real solution (an honest answer for some
/// noisy samples, not an error).
///
/// Errors: [`GeometryError::LengthMismatch`], [`GeometryError::SampleSize`]
/// (exactly 5 needed), [`GeometryError::NonFinite`] (field `bearing1` or
/// `bearing2`), [`GeometryError::ZeroBearing`], and
/// [`GeometryError::Degenerate`] for a rank-deficient sample (repeated
/// matches, a null space of dimension > 4) or a singular elimination
/// template.
///
/// ```
/// use geometry::five_point;
/// use nalgebra::{Rotation3, Vector3};
/// let r = Rotation3::from_euler_angles(0.1, -0.2, 0.05);
/// let t = Vector3::new(1.0, 0.1, -0.2);
/// let world = [[0.1, 0.2, 4.0], [-1.0, 0.5, 5.0], [0.7, -0.8, 6.0], [-0.3, -0.4, 3.0], [1.2, 0.9, 7.0]];
/// let q1: Vec<Vector3<f64>> = world.iter().map(|p| Vector3::from(*p)).collect();
/// let q2: Vec<Vector3<f64>> = q1.iter().map(|p| r * p + t).collect();
/// let es = five_point(&q1, &q2).unwrap();
/// assert!(es.iter().all(|e| q1.iter().zip(&q2).all(|(a, b)| (b.transpose() * e * a)[0].abs() < 1e-9 * a.norm() * b.norm())));
/// ```
pub fn five_point(
    x1: &[Vector3<f64>],
    x2: &[Vector3<f64>],
) -> Result<Vec<Matrix3<f64>>, GeometryError> {
    if x1.len() != x2.len() {
        return Err(GeometryError::LengthMismatch {
            points1: x1.len(),
            points2: x2.len(),
        });
    }
    check_sample_size(x1.len(), FIVE_POINT_SAMPLE)?;
    let q1 = unit_bearings(x1, 1)?;
    let q2 = unit_bearings(x2, 2)?;
    let rows: Vec<[f64; 9]> = q1
        .iter()
        .zip(&q2)
        .map(|(a, b)| epipolar_row((*a).into(), (*b).into()))
        .collect();
    let basis = null_basis::<4>(&rows)?.map(|v| matrix_from_row_major(&v));
    let equations = constraints(&basis);
    let coefficients = constraint_matrix(&equations);
    let action = action_matrix(&coefficients)?;
    let values = real_eigenvalues(&action).ok_or(GeometryError::Degenerate(
        "5-point: eigenvalues of the action matrix did not converge",
    ))?;
    let [bx, by, bz, bw] = basis;
    let mut solutions = Vec::with_capacity(values.len());
    for x in values {
        let shifted = &action - DMatrix::identity(10, 10) * x;
        let Some(v) = null_vector(&shifted) else {
            continue;
        };
        // v = (x², xy, xz, y², yz, z², x, y, z, 1) up to scale.
        if v[9].abs() <= 1e-12 * v.norm() {
            continue;
        }
        let ([x, y, z], _) = polish_root(&equations, [x, v[7] / v[9], v[8] / v[9]], POLISH_STEPS);
        let e = finish(bx * x + by * y + bz * z + bw)?;
        if !is_duplicate(solutions.iter(), &e) {
            solutions.push(e);
        }
    }
    Ok(solutions)
}

/// The bearings scaled to unit length; errors name the image and index.
fn unit_bearings(x: &[Vector3<f64>], image: usize) -> Result<Vec<Vector3<f64>>, GeometryError> {
    let field = if image == 1 { "bearing1" } else { "bearing2" };
    x.iter()
        .enumerate()
        .map(|(index, q)| {
            if !q.iter().all(|v| v.is_finite()) {
                return Err(GeometryError::NonFinite { field, index });
            }
            let norm = q.norm();
            if norm == 0.0 {
                return Err(GeometryError::ZeroBearing { image, index });
            }
            if !norm.is_finite() {
                return Err(GeometryError::Overflow("bearing norm"));
            }
            Ok(q / norm)
        })
        .collect()
}

/// `det E` and the nine entries of `2 E Eᵀ E − tr(E Eᵀ) E` for
/// `E = x X + y Y + z Z + W` (Nistér 2004, Eqs. 4–5).
fn constraints(basis: &[Matrix3<f64>; 4]) -> [Poly3; 10] {
    let [bx, by, bz, bw] = basis;
    let e: PolyMatrix = std::array::from_fn(|r| {
        std::array::from_fn(|c| Poly3::linear(bx[(r, c)], by[(r, c)], bz[(r, c)], bw[(r, c)]))
    });
    let eet = mat_mul(&e, &transpose(&e));
    let trace = trace_constraint(&eet, &e);
    std::array::from_fn(|k| if k == 0 { det(&e) } else { trace[k - 1] })
}

/// The 10 × 20 coefficient matrix of the ten constraints, columns in
/// [`MONOMIALS`] order.
fn constraint_matrix(equations: &[Poly3; 10]) -> SMatrix<f64, 10, 20> {
    let mut m = SMatrix::<f64, 10, 20>::zeros();
    for (row, equation) in equations.iter().enumerate() {
        for (col, &(a, b, c)) in MONOMIALS.iter().enumerate() {
            m[(row, col)] = equation.coeff(a, b, c);
        }
    }
    m
}

/// The 10 × 10 action matrix of multiplication by `x` on the basis
/// `(x², xy, xz, y², yz, z², x, y, z, 1)`: `x · b = M b` at every solution.
/// Rows 0–5 come from the eliminated template `[I | B]` (`x·x² = x³ = −B₀ b`,
/// …, `x·z² = xz² = −B₅ b`), rows 6–9 are shifts (`x·x = x²`, `x·y = xy`,
/// `x·z = xz`, `x·1 = x`).
fn action_matrix(coefficients: &SMatrix<f64, 10, 20>) -> Result<DMatrix<f64>, GeometryError> {
    let left = coefficients.fixed_view::<10, 10>(0, 0).into_owned();
    let right = coefficients.fixed_view::<10, 10>(0, 10).into_owned();
    let b = left
        .lu()
        .solve(&right)
        .filter(|b| b.iter().all(|v| v.is_finite()))
        .ok_or(GeometryError::Degenerate(
            "5-point: singular elimination template",
        ))?;
    let mut m = DMatrix::zeros(10, 10);
    for r in 0..6 {
        for c in 0..10 {
            m[(r, c)] = -b[(r, c)];
        }
    }
    for (r, c) in [(6, 0), (7, 1), (8, 2), (9, 6)] {
        m[(r, c)] = 1.0;
    }
    Ok(m)
}
