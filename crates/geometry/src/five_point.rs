//! The 5-point essential-matrix solver: Nistér 2004 ("An efficient solution
//! to the five-point relative pose problem", PAMI 26(6)), with the
//! elimination of Stewénius, Engels & Nistér 2006 ("Recent developments on
//! direct relative orientation", ISPRS J. 60, §3).
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
//! monomials `x³, y³, x²y, xy², x²z, x², y²z, y², xyz, xy | xz², xz, x,
//! yz², yz, y, z³, z², z, 1` (Nistér's Table 1); LU elimination of the
//! first block leaves rows `⟨x²z⟩, ⟨x²⟩, ⟨y²z⟩, ⟨y²⟩, ⟨xyz⟩, ⟨xy⟩` whose
//! remaining monomials are `[x, y, 1]` times powers of `z`. The three
//! differences `⟨x²z⟩ − z⟨x²⟩`, `⟨y²z⟩ − z⟨y²⟩`, `⟨xyz⟩ − z⟨xy⟩` form a
//! 3 × 3 matrix `B(z)` (cubic, cubic, quartic columns) with
//! `B(z) (x, y, 1)ᵀ = 0` (Nistér §3.2, Eqs. 11–14), so `z` is a real root
//! of the degree-10 polynomial `det B(z)`. Its real roots come from a Sturm
//! sequence and bracketed Newton steps (no eigen-decomposition); `(x, y, 1)`
//! is the cross product of two rows of `B(z)`. Each root is then polished
//! by Gauss–Newton steps on the ten equations. Up to 10 solutions.

use crate::eight_point::finish;
use crate::essential_system::{constraint_rows, ConstraintRows, EssentialSystem};
use crate::lu::lu_solve_template;
use crate::minimal::{
    check_sample_size, epipolar_row, is_duplicate, matrix_from_row_major, null_basis,
};
use crate::poly::polish_root;
use crate::sturm::sturm_roots;
use crate::GeometryError;
use nalgebra::{Matrix3, Vector3};
use std::sync::OnceLock;

/// Number of matches of the 5-point solver.
pub const FIVE_POINT_SAMPLE: usize = 5;

/// Gauss–Newton steps on the ten constraints that polish each root (a
/// step is kept only while it lowers the residual; from the Sturm roots
/// one step usually reaches rounding level).
const POLISH_STEPS: usize = 3;

/// A candidate whose `(x, y, 1)` has a last entry below this fraction of
/// its norm is a solution at infinity (`E` without a `W` component) and is
/// dropped.
const AT_INFINITY: f64 = 1e-12;

/// `B(z)`: three rows of `[x-coefficient, y-coefficient, 1-coefficient]`,
/// each a polynomial in `z` with ascending coefficients (degrees 3, 3, 4).
type HiddenMatrix = [[[f64; 5]; 3]; 3];

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
    let roots = FivePointRoots::new(x1, x2)?;
    let mut solutions = Vec::with_capacity(roots.len());
    for k in 0..roots.len() {
        let e = roots.polished(k)?;
        if !is_duplicate(solutions.iter(), &e) {
            solutions.push(e);
        }
    }
    Ok(solutions)
}

/// The real roots of the 5-point system before their Gauss–Newton polish:
/// each root's essential matrix to a few 1e-6 (relative), enough to score
/// it against pixel thresholds, and the polish of any one of them on
/// demand. [`five_point`] is every root polished, duplicates dropped; a
/// RANSAC-style caller that keeps only the best-scoring solution of a
/// sample polishes that one alone ([`FivePointRoots::polished`] of it
/// equals the matching entry of [`five_point`] bit for bit).
///
/// ```
/// use geometry::{five_point, FivePointRoots};
/// use nalgebra::{Rotation3, Vector3};
/// let r = Rotation3::from_euler_angles(0.1, -0.2, 0.05);
/// let t = Vector3::new(1.0, 0.1, -0.2);
/// let world = [[0.1, 0.2, 4.0], [-1.0, 0.5, 5.0], [0.7, -0.8, 6.0], [-0.3, -0.4, 3.0], [1.2, 0.9, 7.0]];
/// let q1: Vec<Vector3<f64>> = world.iter().map(|p| Vector3::from(*p)).collect();
/// let q2: Vec<Vector3<f64>> = q1.iter().map(|p| r * p + t).collect();
/// let roots = FivePointRoots::new(&q1, &q2).unwrap();
/// let polished = five_point(&q1, &q2).unwrap();
/// assert_eq!(roots.polished(0).unwrap(), polished[0]);
/// assert!((roots.unpolished(0).unwrap() - polished[0]).norm() < 1e-6);
/// ```
#[derive(Debug, Clone)]
pub struct FivePointRoots {
    /// The null-space basis `[X, Y, Z, W]` of the five epipolar equations.
    basis: [Matrix3<f64>; 4],
    /// The ten cubic constraints over that basis, row by row.
    constraints: ConstraintRows,
    /// The same constraints arranged for the polish, built at its first
    /// call (a caller that keeps roots unpolished never needs them; boxed,
    /// so that moving the roots does not copy its 3 KB).
    system: OnceLock<Box<EssentialSystem>>,
    /// `(x, y, z)` of each real root, as the Sturm sequence and the back
    /// substitution give it.
    roots: Vec<[f64; 3]>,
}

impl FivePointRoots {
    /// The roots of five matches of calibrated bearings; inputs and errors
    /// as [`five_point`].
    pub fn new(x1: &[Vector3<f64>], x2: &[Vector3<f64>]) -> Result<Self, GeometryError> {
        if x1.len() != x2.len() {
            return Err(GeometryError::LengthMismatch {
                points1: x1.len(),
                points2: x2.len(),
            });
        }
        check_sample_size(x1.len(), FIVE_POINT_SAMPLE)?;
        let q1 = unit_bearings(x1, 1)?;
        let q2 = unit_bearings(x2, 2)?;
        let rows: [[f64; 9]; FIVE_POINT_SAMPLE] =
            std::array::from_fn(|i| epipolar_row(q1[i].into(), q2[i].into()));
        let basis = null_basis::<4>(&rows)?.map(|v| matrix_from_row_major(&v));
        let constraints = constraint_rows(&basis);
        let hidden = hidden_variable_matrix(&constraints)?;
        let zs = sturm_roots(&determinant(&hidden)).ok_or(GeometryError::Degenerate(
            "5-point: the degree-10 polynomial is not finite or vanishes",
        ))?;
        let roots = zs
            .as_slice()
            .iter()
            .filter_map(|&z| back_substitute(&hidden, z).map(|(x, y)| [x, y, z]))
            .collect();
        Ok(Self {
            basis,
            constraints,
            system: OnceLock::new(),
            roots,
        })
    }

    /// Number of roots.
    pub fn len(&self) -> usize {
        self.roots.len()
    }

    /// Whether the system has no real root.
    pub fn is_empty(&self) -> bool {
        self.roots.is_empty()
    }

    /// Root `k`'s essential matrix as found, before the polish (unit norm,
    /// canonical sign). Panics if `k >= len()`.
    pub fn unpolished(&self, k: usize) -> Result<Matrix3<f64>, GeometryError> {
        self.essential(self.roots[k])
    }

    /// Root `k` after `POLISH_STEPS` Gauss–Newton steps on the ten
    /// constraints (a step kept only while it lowers their residual).
    /// Panics if `k >= len()`.
    pub fn polished(&self, k: usize) -> Result<Matrix3<f64>, GeometryError> {
        let system = self
            .system
            .get_or_init(|| Box::new(EssentialSystem::from_rows(&self.constraints)));
        let (root, _) = polish_root(&**system, self.roots[k], POLISH_STEPS);
        self.essential(root)
    }

    /// `x X + y Y + z Z + W`, unit norm and canonical sign.
    fn essential(&self, [x, y, z]: [f64; 3]) -> Result<Matrix3<f64>, GeometryError> {
        let [bx, by, bz, bw] = self.basis;
        finish(bx * x + by * y + bz * z + bw)
    }
}

/// The bearings scaled to unit length; errors name the image and index.
fn unit_bearings(
    x: &[Vector3<f64>],
    image: usize,
) -> Result<[Vector3<f64>; FIVE_POINT_SAMPLE], GeometryError> {
    let field = if image == 1 { "bearing1" } else { "bearing2" };
    let mut out = [Vector3::zeros(); FIVE_POINT_SAMPLE];
    for (index, (q, unit)) in x.iter().zip(out.iter_mut()).enumerate() {
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
        *unit = q / norm;
    }
    Ok(out)
}

/// `B(z)` from the 10 × 20 coefficient matrix: LU elimination of the first
/// ten columns ([`lu_solve_template`], the other ten in columns 10–19 of its
/// answer), then `⟨x²z⟩ − z⟨x²⟩`, `⟨y²z⟩ − z⟨y²⟩`, `⟨xyz⟩ − z⟨xy⟩`
/// (Nistér 2004, §3.2). Columns 10–19 are `xz², xz, x, yz², yz, y, z³, z²,
/// z, 1`.
fn hidden_variable_matrix(rows: &ConstraintRows) -> Result<HiddenMatrix, GeometryError> {
    let b = lu_solve_template(*rows)
        .filter(|b| b.iter().all(|row| row[10..].iter().all(|v| v.is_finite())))
        .ok_or(GeometryError::Degenerate(
            "5-point: singular elimination template",
        ))?;
    Ok([(4, 5), (6, 7), (8, 9)].map(|(with_z, without)| {
        // Row `with_z` minus z times row `without`, per block of columns.
        let shifted = |first: usize, len: usize| {
            let mut p = [0.0; 5];
            for k in 0..len {
                // Column first + k holds the power len − 1 − k of z.
                p[len - 1 - k] += b[with_z][10 + first + k];
                p[len - k] -= b[without][10 + first + k];
            }
            p
        };
        [shifted(0, 3), shifted(3, 3), shifted(6, 4)]
    }))
}

/// `Σ a_i tⁱ · Σ b_j tʲ` added into `out`.
fn add_product(a: &[f64], b: &[f64], out: &mut [f64]) {
    for (i, ai) in a.iter().enumerate() {
        for (j, bj) in b.iter().enumerate() {
            out[i + j] += ai * bj;
        }
    }
}

/// `det B(z)`, ascending coefficients of degree ≤ 10 (cofactor expansion
/// along the third column).
fn determinant(m: &HiddenMatrix) -> [f64; 11] {
    let mut out = [0.0; 11];
    for r in 0..3 {
        let (r1, r2) = ((r + 1) % 3, (r + 2) % 3);
        let mut minor = [0.0; 7];
        add_product(&m[r1][0][..4], &m[r2][1][..4], &mut minor);
        let negated = m[r2][0].map(|v| -v);
        add_product(&negated[..4], &m[r1][1][..4], &mut minor);
        add_product(&minor, &m[r][2], &mut out);
    }
    out
}

/// `(x, y)` at the root `z`: the null vector `(x, y, 1)` of `B(z)` as the
/// largest cross product of two of its rows; `None` at infinity.
fn back_substitute(m: &HiddenMatrix, z: f64) -> Option<(f64, f64)> {
    let eval = |p: &[f64; 5]| p.iter().rev().fold(0.0, |acc, c| acc * z + c);
    let rows = m.map(|row| Vector3::new(eval(&row[0]), eval(&row[1]), eval(&row[2])));
    let v = [
        rows[0].cross(&rows[1]),
        rows[0].cross(&rows[2]),
        rows[1].cross(&rows[2]),
    ]
    .into_iter()
    .max_by(|a, b| a.norm_squared().total_cmp(&b.norm_squared()))?;
    (v[2].abs() > AT_INFINITY * v.norm() && v.iter().all(|c| c.is_finite()))
        .then(|| (v[0] / v[2], v[1] / v[2]))
}
