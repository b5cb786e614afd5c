//! Relative pose with one unknown focal length shared by both views, from
//! six matches (Stewénius, Nistér, Kahl & Schaffalitzky 2008, "A minimal
//! solution for relative pose with unknown focal length", Image and Vision
//! Computing 26(7)).
//!
//! With the principal point at the origin, `K = diag(f, f, 1)` and
//! `E = K F K ∝ K' F K'`, `K' = diag(1, 1, 1/f)`. Six matches give six
//! equations `x2ᵀ F x1 = 0`; their null space is three-dimensional,
//! `F = x F1 + y F2 + F3`. With `w = 1/f²` and `Q = K'² = diag(1, 1, w)`
//! the essential-matrix trace constraint becomes (Stewénius et al. 2008,
//! Eqs. 3–4)
//!
//! ```text
//! det F = 0,               2 F Q Fᵀ Q F − tr(F Q Fᵀ Q) F = 0,
//! ```
//!
//! ten equations, cubic in `(x, y)` and (the nine trace equations)
//! quadratic in `w`; the system has 15 solutions in general.
//!
//! Solution method: the hidden-variable resultant of Li 2006 ("A simple
//! solution to the six-point two-view focal-length problem", ECCV) on the
//! same equations, rather than the 2008 paper's Gröbner-basis template —
//! the two give the same solution set. Written over the ten monomials
//! `m = (x³, x²y, xy², y³, x², xy, y², x, y, 1)` the equations read
//! `(C0 + w C1 + w² C2) m = 0` with 10 × 10 coefficient matrices. In
//! `μ = 1/w = f²` this is the quadratic eigenvalue problem
//! `(μ² C0 + μ C1 + C2) m = 0`, linearised as the 20 × 20 standard
//! eigenproblem `[0 I; −C0⁻¹C2 −C0⁻¹C1]`. Its real eigenvalues `μ > 0` are
//! the candidate `f²` (the problem's 15 roots, plus roots at `μ = 0` since
//! `C2` is singular — the row of `det F` has no `w`); the monomial vector
//! `m` is the null vector of `μ² C0 + μ C1 + C2`, giving
//! `x = m_x / m_1`, `y = m_y / m_1`.
//!
//! Conditioning: the pixels are divided by `s`, the mean distance of the
//! twelve points from the principal point, before the solve (so `f/s` is
//! of order 1); the returned `f` and `F` are in pixels again.

use crate::action::{null_vector, real_eigenvalues};
use crate::eight_point::finish;
use crate::minimal::{
    check_sample_size, epipolar_row, is_duplicate, matrix_from_row_major, null_basis,
};
use crate::poly::{det, mat_mul, polish_root, trace_constraint, transpose, Poly3, PolyMatrix};
use crate::{Correspondences, GeometryError};
use nalgebra::{DMatrix, DVector, Matrix3, SMatrix};

/// Number of matches of the 6-point shared-focal solver.
pub const SIX_POINT_SAMPLE: usize = 6;

/// Gauss–Newton steps on the ten equations in `(x, y, w)` that polish each
/// candidate read off the eigenproblem.
const POLISH_STEPS: usize = 6;

/// A candidate is a solution when, after polishing, the ten equations
/// vanish to this fraction of the magnitude of their terms (see
/// `relative_residual`): true roots reach rounding level (~1e-16), the
/// extraneous eigenvalues of the resultant stay far above.
pub const MAX_RESIDUAL: f64 = 1e-9;

/// Candidates with `f < MIN_FOCAL_RATIO · s` (`s` the mean distance of the
/// points from the principal point: a focal of a fraction of a pixel) are
/// the roots at `f² = 0` that `C2`'s rank deficiency creates, perturbed by
/// rounding; they are discarded with the non-positive ones.
pub const MIN_FOCAL_RATIO: f64 = 1e-3;

/// Exponents `(x, y)` of the ten monomials of degree ≤ 3 in `x, y`.
const MONOMIALS: [(usize, usize); 10] = [
    (3, 0),
    (2, 1),
    (1, 2),
    (0, 3),
    (2, 0),
    (1, 1),
    (0, 2),
    (1, 0),
    (0, 1),
    (0, 0),
];

/// One solution of the shared-focal problem.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FocalSolution {
    /// The focal length in pixels (`> 0`).
    pub focal: f64,
    /// `F` in the given (centred) pixel coordinates, `x2ᵀ F x1 = 0`, unit
    /// Frobenius norm, entry of largest magnitude positive.
    pub fundamental: Matrix3<f64>,
    /// `E = K F K`, `K = diag(f, f, 1)`, in the same canonical scale.
    pub essential: Matrix3<f64>,
}

/// All real solutions `(f, F)` with `f² > 0` of the six-point relative pose
/// problem with one unknown focal length shared by both views
/// (Stewénius et al. 2008; solved by Li 2006's hidden-variable resultant):
/// `x2ᵀ F x1 = 0` for each match, `det F = 0`, and `E = K F K` essential.
///
/// Input: six matches in pixels with the principal point at the origin
/// (e.g. [`Correspondences::shifted`]); no focal prior is needed (the
/// coordinates are scaled internally by their mean distance from the
/// origin). Output: up to 15 solutions, possibly none. Eigenvalues that are
/// complex (imaginary part above `1e-9 · (1 + |μ|)`), `f² ≤ 0` or
/// `f < MIN_FOCAL_RATIO · s` are discarded, as are candidates whose
/// monomial vector has a vanishing constant entry (solutions at infinity)
/// and extraneous roots of the resultant (the ten equations not satisfied
/// to [`MAX_RESIDUAL`] after polishing).
///
/// Errors: [`GeometryError::SampleSize`] (exactly 6 needed),
/// [`GeometryError::Degenerate`] for points all at the origin, a
/// rank-deficient sample (null space of dimension > 3), or a singular
/// `C0` (no finite-focal linearisation), [`GeometryError::Overflow`].
///
/// ```
/// use geometry::{six_point_focal, Correspondences};
/// use nalgebra::{Rotation3, Vector3};
/// let (f, r, t) = (900.0, Rotation3::from_euler_angles(0.2, -0.3, 0.1), Vector3::new(1.0, 0.2, 0.1));
/// let world = [[0.1, 0.2, 4.0], [-1.0, 0.5, 5.0], [0.7, -0.8, 6.0], [-0.3, -0.4, 3.0], [1.2, 0.9, 7.0], [-0.6, 1.1, 5.5]];
/// let project = |p: Vector3<f64>| [f * p.x / p.z, f * p.y / p.z];
/// let p1: Vec<[f64; 2]> = world.iter().map(|p| project(Vector3::from(*p))).collect();
/// let p2: Vec<[f64; 2]> = world.iter().map(|p| project(r * Vector3::from(*p) + t)).collect();
/// let sols = six_point_focal(&Correspondences::new(&p1, &p2).unwrap()).unwrap();
/// assert!(sols.iter().any(|s| (s.focal - f).abs() < 1e-6 * f));
/// ```
pub fn six_point_focal(points: &Correspondences) -> Result<Vec<FocalSolution>, GeometryError> {
    check_sample_size(points.len(), SIX_POINT_SAMPLE)?;
    let (x1, y1, x2, y2) = points.columns();
    let s = (0..SIX_POINT_SAMPLE)
        .map(|i| x1[i].hypot(y1[i]) + x2[i].hypot(y2[i]))
        .sum::<f64>()
        / (2 * SIX_POINT_SAMPLE) as f64;
    if !s.is_finite() {
        return Err(GeometryError::Overflow("six-point coordinate scale"));
    }
    if s <= 0.0 {
        return Err(GeometryError::Degenerate(
            "all points at the principal point",
        ));
    }
    let rows: Vec<[f64; 9]> = (0..SIX_POINT_SAMPLE)
        .map(|i| epipolar_row([x1[i] / s, y1[i] / s, 1.0], [x2[i] / s, y2[i] / s, 1.0]))
        .collect();
    let basis = null_basis::<3>(&rows)?.map(|v| matrix_from_row_major(&v));
    let equations = constraints(&basis);
    let [c0, c1, c2] = coefficient_matrices(&equations);
    let companion = linearisation(&c0, &c1, &c2)?;
    let values = real_eigenvalues(&companion).ok_or(GeometryError::Degenerate(
        "6-point: eigenvalues of the companion matrix did not converge",
    ))?;
    let unscale = Matrix3::new(1.0 / s, 0.0, 0.0, 0.0, 1.0 / s, 0.0, 0.0, 0.0, 1.0);
    let mut solutions = Vec::new();
    for mu in values
        .into_iter()
        .filter(|&mu| mu > MIN_FOCAL_RATIO * MIN_FOCAL_RATIO)
    {
        let Some(m) = monomial_vector(&c0, &c1, &c2, mu) else {
            continue;
        };
        let start = [m[7] / m[9], m[8] / m[9], 1.0 / mu];
        let ([x, y, w], residual) = polish_root(&equations, start, POLISH_STEPS);
        if !(residual <= MAX_RESIDUAL && w > 0.0 && w.sqrt() * MIN_FOCAL_RATIO < 1.0) {
            continue;
        }
        let f_scaled = basis[0] * x + basis[1] * y + basis[2];
        let focal = s / w.sqrt();
        let fundamental = finish(unscale * f_scaled * unscale)?;
        if is_duplicate(
            solutions.iter().map(|s: &FocalSolution| &s.fundamental),
            &fundamental,
        ) {
            continue;
        }
        let k = Matrix3::new(focal, 0.0, 0.0, 0.0, focal, 0.0, 0.0, 0.0, 1.0);
        let essential = finish(k * fundamental * k)?;
        solutions.push(FocalSolution {
            focal,
            fundamental,
            essential,
        });
    }
    Ok(solutions)
}

/// `det F` and the nine entries of `2 F Q Fᵀ Q F − tr(F Q Fᵀ Q) F` for
/// `F = x F1 + y F2 + F3`, `Q = diag(1, 1, w)`, as polynomials in
/// `(x, y, w)` (Stewénius et al. 2008, Eqs. 3–4).
fn constraints(basis: &[Matrix3<f64>; 3]) -> [Poly3; 10] {
    let [b1, b2, b3] = basis;
    // Variables (x, y, z = w) of Poly3.
    let f: PolyMatrix = std::array::from_fn(|r| {
        std::array::from_fn(|c| Poly3::linear(b1[(r, c)], b2[(r, c)], 0.0, b3[(r, c)]))
    });
    // F Q: the third column times w.
    let mut fq = f;
    for row in fq.iter_mut() {
        row[2] = row[2].times_z();
    }
    // F Q Fᵀ Q = (F Q) · (Fᵀ Q).
    let mut ftq = transpose(&f);
    for row in ftq.iter_mut() {
        row[2] = row[2].times_z();
    }
    let p = mat_mul(&fq, &ftq);
    let trace = trace_constraint(&p, &f);
    std::array::from_fn(|k| if k == 0 { det(&f) } else { trace[k - 1] })
}

/// `C0, C1, C2`: the coefficients of `w⁰, w¹, w²` of the ten equations over
/// [`MONOMIALS`].
fn coefficient_matrices(equations: &[Poly3; 10]) -> [SMatrix<f64, 10, 10>; 3] {
    let mut out = [SMatrix::<f64, 10, 10>::zeros(); 3];
    for (row, equation) in equations.iter().enumerate() {
        for (col, &(a, b)) in MONOMIALS.iter().enumerate() {
            for (k, c) in out.iter_mut().enumerate() {
                c[(row, col)] = equation.coeff(a, b, k);
            }
        }
    }
    out
}

/// The 20 × 20 matrix `[0 I; −C0⁻¹C2 −C0⁻¹C1]` whose eigenvalues are the
/// `μ` of `(μ² C0 + μ C1 + C2) m = 0`.
fn linearisation(
    c0: &SMatrix<f64, 10, 10>,
    c1: &SMatrix<f64, 10, 10>,
    c2: &SMatrix<f64, 10, 10>,
) -> Result<DMatrix<f64>, GeometryError> {
    let lu = c0.lu();
    let singular = GeometryError::Degenerate("6-point: singular leading coefficient matrix");
    let a2 = lu.solve(c2).ok_or(singular.clone())?;
    let a1 = lu.solve(c1).ok_or(singular.clone())?;
    if !(a1.iter().chain(a2.iter()).all(|v| v.is_finite())) {
        return Err(singular);
    }
    let mut m = DMatrix::zeros(20, 20);
    for i in 0..10 {
        m[(i, 10 + i)] = 1.0;
        for j in 0..10 {
            m[(10 + i, j)] = -a2[(i, j)];
            m[(10 + i, 10 + j)] = -a1[(i, j)];
        }
    }
    Ok(m)
}

/// The null vector of `μ² C0 + μ C1 + C2` (the monomial vector up to scale),
/// or `None` when its constant entry vanishes (a solution at infinity).
fn monomial_vector(
    c0: &SMatrix<f64, 10, 10>,
    c1: &SMatrix<f64, 10, 10>,
    c2: &SMatrix<f64, 10, 10>,
    mu: f64,
) -> Option<DVector<f64>> {
    let d = c0 * (mu * mu) + c1 * mu + c2;
    let m = null_vector(&DMatrix::from_iterator(10, 10, d.iter().copied()))?;
    (m[9].abs() > 1e-12 * m.norm()).then_some(m)
}
