//! The ten cubic constraints of the 5-point problem as a 10 × 20
//! coefficient matrix, expanded with fixed-size products of linear and
//! quadratic polynomials (no allocation), and their evaluation with the
//! Jacobian for the root polish.
//!
//! With `E = x X + y Y + z Z + W` (the null space of the five epipolar
//! equations), the constraints are `det E = 0` and the nine entries of
//! `2 E Eᵀ E − tr(E Eᵀ) E = 0` (Nistér 2004, Eqs. 4–5).

use crate::poly::Equations;
use crate::simd::dispatch;
use nalgebra::{Matrix3, SMatrix};

/// Exponents `(x, y, z)` of the 20 monomials of degree ≤ 3 in Nistér's
/// order (Nistér 2004, Table 1): the ten eliminated first, then
/// `[x, y, 1]` times the powers of the hidden variable `z`.
pub(crate) const MONOMIALS: [(usize, usize, usize); 20] = [
    (3, 0, 0),
    (0, 3, 0),
    (2, 1, 0),
    (1, 2, 0),
    (2, 0, 1),
    (2, 0, 0),
    (0, 2, 1),
    (0, 2, 0),
    (1, 1, 1),
    (1, 1, 0),
    (1, 0, 2),
    (1, 0, 1),
    (1, 0, 0),
    (0, 1, 2),
    (0, 1, 1),
    (0, 1, 0),
    (0, 0, 3),
    (0, 0, 2),
    (0, 0, 1),
    (0, 0, 0),
];

/// Monomials of a linear polynomial: `x, y, z, 1`.
const LINEAR: [(usize, usize, usize); 4] = [(1, 0, 0), (0, 1, 0), (0, 0, 1), (0, 0, 0)];

/// Monomials of a quadratic: `x², xy, xz, y², yz, z², x, y, z, 1`.
const QUADRATIC: [(usize, usize, usize); 10] = [
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

/// Position of the exponent triple `e` in `table` (evaluated at compile
/// time; a missing monomial fails the build).
const fn position(table: &[(usize, usize, usize)], e: (usize, usize, usize)) -> usize {
    let mut i = 0;
    while i < table.len() {
        if table[i].0 == e.0 && table[i].1 == e.1 && table[i].2 == e.2 {
            return i;
        }
        i += 1;
    }
    panic!("monomial missing from its table")
}

/// `PRODUCT[i][j]`: position in `to` of `from[i] · LINEAR[j]`.
const fn product_table<const N: usize>(
    from: &[(usize, usize, usize); N],
    to: &[(usize, usize, usize)],
) -> [[usize; 4]; N] {
    let mut out = [[0; 4]; N];
    let mut i = 0;
    while i < N {
        let mut j = 0;
        while j < 4 {
            let (a, b) = (from[i], LINEAR[j]);
            out[i][j] = position(to, (a.0 + b.0, a.1 + b.1, a.2 + b.2));
            j += 1;
        }
        i += 1;
    }
    out
}

const LINEAR_BY_LINEAR: [[usize; 4]; 4] = product_table(&LINEAR, &QUADRATIC);
const QUADRATIC_BY_LINEAR: [[usize; 4]; 10] = product_table(&QUADRATIC, &MONOMIALS);

type Linear = [f64; 4];
type Quadratic = [f64; 10];
type Cubic = [f64; 20];

/// `acc += a · b` for linear `a`, `b`.
fn add_linear_product(acc: &mut Quadratic, a: &Linear, b: &Linear) {
    for (i, row) in LINEAR_BY_LINEAR.iter().enumerate() {
        for (j, &k) in row.iter().enumerate() {
            acc[k] += a[i] * b[j];
        }
    }
}

/// `acc += a · b` for quadratic `a`, linear `b`.
fn add_quadratic_product(acc: &mut Cubic, a: &Quadratic, b: &Linear) {
    for (i, row) in QUADRATIC_BY_LINEAR.iter().enumerate() {
        for (j, &k) in row.iter().enumerate() {
            acc[k] += a[i] * b[j];
        }
    }
}

/// The ten constraints `det E` and `2 E Eᵀ E − tr(E Eᵀ) E` (row-major) for
/// `E = x X + y Y + z Z + W`, as rows of coefficients over [`MONOMIALS`],
/// stored column-major for the evaluation of the polish.
#[derive(Debug, Clone, Copy)]
pub(crate) struct EssentialSystem {
    /// Row `k`: the coefficients of equation `k` (0: `det E`, then the
    /// trace constraint row-major) over [`MONOMIALS`].
    pub coefficients: SMatrix<f64, 10, 20>,
    /// Their magnitudes (for the terms' scale `Σ |term|`).
    magnitudes: SMatrix<f64, 10, 20>,
}

/// The coefficient rows of [`EssentialSystem`], row `k` over
/// [`MONOMIALS`] (what the elimination of the 5-point solver reads).
pub(crate) type ConstraintRows = [[f64; 20]; 10];

impl EssentialSystem {
    /// Expands the constraints of the basis `[X, Y, Z, W]`.
    #[cfg(test)]
    pub fn new(basis: &[Matrix3<f64>; 4]) -> Self {
        Self::from_rows(&constraint_rows(basis))
    }

    /// The system of the rows [`constraint_rows`] expanded.
    pub fn from_rows(rows: &ConstraintRows) -> Self {
        let coefficients = SMatrix::from_fn(|r, c| rows[r][c]);
        Self {
            coefficients,
            magnitudes: coefficients.abs(),
        }
    }
}

/// Expands the ten constraints of the basis `[X, Y, Z, W]` into rows of
/// coefficients over [`MONOMIALS`].
pub(crate) fn constraint_rows(basis: &[Matrix3<f64>; 4]) -> ConstraintRows {
    let [bx, by, bz, bw] = basis;
    let e: [[Linear; 3]; 3] = std::array::from_fn(|r| {
        std::array::from_fn(|c| [bx[(r, c)], by[(r, c)], bz[(r, c)], bw[(r, c)]])
    });
    let mut rows = [[0.0; 20]; 10];
    // det E by the cofactors of the first row.
    for c in 0..3 {
        let (c1, c2) = ((c + 1) % 3, (c + 2) % 3);
        let mut cofactor = [0.0; 10];
        add_linear_product(&mut cofactor, &e[1][c1], &e[2][c2]);
        let neg: Linear = e[1][c2].map(|v| -v);
        add_linear_product(&mut cofactor, &neg, &e[2][c1]);
        add_quadratic_product(&mut rows[0], &cofactor, &e[0][c]);
    }
    // P = E Eᵀ, then 2 P − tr(P) I.
    let mut p = [[[0.0; 10]; 3]; 3];
    for (i, p_row) in p.iter_mut().enumerate() {
        for (j, entry) in p_row.iter_mut().enumerate() {
            for (a, b) in e[i].iter().zip(&e[j]) {
                add_linear_product(entry, a, b);
            }
        }
    }
    let trace: Quadratic = std::array::from_fn(|k| p[0][0][k] + p[1][1][k] + p[2][2][k]);
    for (i, row) in p.iter_mut().enumerate() {
        row[i]
            .iter_mut()
            .zip(&trace)
            .for_each(|(v, t)| *v -= 0.5 * t);
        row.iter_mut().flatten().for_each(|v| *v *= 2.0);
    }
    for r in 0..3 {
        for c in 0..3 {
            for k in 0..3 {
                add_quadratic_product(&mut rows[1 + 3 * r + c], &p[r][k], &e[k][c]);
            }
        }
    }
    rows
}

impl Equations for EssentialSystem {
    /// Values and gradients as one product `C [m ∂ₓm ∂ᵧm ∂_z m]` of the
    /// coefficients with the monomial vector and its partial derivatives;
    /// `Σ |term| = |C| |m|`.
    fn evaluate(&self, p: [f64; 3]) -> [(f64, [f64; 3], f64); 10] {
        evaluate(self, p)
    }
}

dispatch! {
    /// [`evaluate_kernel`] in the build [`crate::simd::avx2`] chooses.
    fn evaluate(system: &EssentialSystem, p: [f64; 3]) -> [(f64, [f64; 3], f64); 10]
        => evaluate_kernel
}

/// The body of [`EssentialSystem`]'s [`Equations::evaluate`]: the
/// products `C [m ∂ₓm ∂ᵧm ∂_z m]` and `|C| |m|` as nalgebra forms them
/// (each entry `C_k0 m_0 + C_k1 m_1 + …` summed in column order, so the
/// same bits), written out so that they compile into the chosen build.
#[inline(always)]
fn evaluate_kernel(system: &EssentialSystem, p: [f64; 3]) -> [(f64, [f64; 3], f64); 10] {
    let powers = |t: f64| [1.0, t, t * t, t * t * t];
    let (px, py, pz) = (powers(p[0]), powers(p[1]), powers(p[2]));
    let lower = |pw: &[f64; 4], a: usize| if a == 0 { 0.0 } else { a as f64 * pw[a - 1] };
    // Columns: the monomials, their x, y and z derivatives, |monomials|.
    let mut monomials = [[0.0; 20]; 5];
    for (j, &(a, b, c)) in MONOMIALS.iter().enumerate() {
        monomials[0][j] = px[a] * py[b] * pz[c];
        monomials[1][j] = lower(&px, a) * py[b] * pz[c];
        monomials[2][j] = px[a] * lower(&py, b) * pz[c];
        monomials[3][j] = px[a] * py[b] * lower(&pz, c);
        monomials[4][j] = monomials[0][j].abs();
    }
    // Column-major storage: entry (k, j) at 10 j + k.
    let (c, m) = (system.coefficients.as_slice(), system.magnitudes.as_slice());
    let mut sums = [[0.0; 10]; 5];
    for (column, (sum, x)) in sums.iter_mut().zip(&monomials).enumerate() {
        let matrix = if column == 4 { m } else { c };
        for k in 0..10 {
            sum[k] = matrix[k] * x[0];
        }
        for j in 1..20 {
            for k in 0..10 {
                sum[k] += matrix[10 * j + k] * x[j];
            }
        }
    }
    std::array::from_fn(|k| (sums[0][k], [sums[1][k], sums[2][k], sums[3][k]], sums[4][k]))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dense_poly::{det, mat_mul, trace_constraint, transpose, Poly3, PolyMatrix};
    use crate::poly::Equations;

    /// [`evaluate_kernel`]'s products formed by nalgebra instead, as the
    /// kernel's comment describes them.
    fn nalgebra_products(system: &EssentialSystem, p: [f64; 3]) -> [(f64, [f64; 3], f64); 10] {
        let powers = |t: f64| [1.0, t, t * t, t * t * t];
        let (px, py, pz) = (powers(p[0]), powers(p[1]), powers(p[2]));
        let lower = |pw: &[f64; 4], a: usize| if a == 0 { 0.0 } else { a as f64 * pw[a - 1] };
        let mut monomials = SMatrix::<f64, 20, 4>::zeros();
        for (j, &(a, b, c)) in MONOMIALS.iter().enumerate() {
            monomials[(j, 0)] = px[a] * py[b] * pz[c];
            monomials[(j, 1)] = lower(&px, a) * py[b] * pz[c];
            monomials[(j, 2)] = px[a] * lower(&py, b) * pz[c];
            monomials[(j, 3)] = px[a] * py[b] * lower(&pz, c);
        }
        let evaluated = system.coefficients * monomials;
        let magnitude = system.magnitudes * monomials.column(0).abs();
        std::array::from_fn(|k| {
            let row = evaluated.row(k);
            (row[0], [row[1], row[2], row[3]], magnitude[k])
        })
    }

    /// The fixed-size expansion equals the dense `Poly3` one.
    #[test]
    fn matches_the_dense_polynomial_expansion() {
        let basis: [Matrix3<f64>; 4] = std::array::from_fn(|b| {
            Matrix3::from_fn(|r, c| ((7 * b + 3 * r + c) as f64 * 0.77).sin())
        });
        let system = EssentialSystem::new(&basis);
        let e: PolyMatrix = std::array::from_fn(|r| {
            std::array::from_fn(|c| {
                Poly3::linear(
                    basis[0][(r, c)],
                    basis[1][(r, c)],
                    basis[2][(r, c)],
                    basis[3][(r, c)],
                )
            })
        });
        let eet = mat_mul(&e, &transpose(&e));
        let trace = trace_constraint(&eet, &e);
        let dense: [Poly3; 10] =
            std::array::from_fn(|k| if k == 0 { det(&e) } else { trace[k - 1] });
        for (k, equation) in dense.iter().enumerate() {
            for (j, &(a, b, c)) in MONOMIALS.iter().enumerate() {
                let d = (system.coefficients[(k, j)] - equation.coeff(a, b, c)).abs();
                assert!(d < 1e-14, "equation {k}, monomial {j}: {d:e}");
            }
        }
        let p = [0.3, -1.2, 0.7];
        let (ours, theirs) = (system.evaluate(p), dense.evaluate(p));
        assert_eq!(
            ours,
            nalgebra_products(&system, p),
            "the same bits as nalgebra's"
        );
        for (a, b) in ours.iter().zip(&theirs) {
            assert!((a.0 - b.0).abs() < 1e-13 && (a.2 - b.2).abs() < 1e-13);
            for j in 0..3 {
                assert!((a.1[j] - b.1[j]).abs() < 1e-13);
            }
        }
    }
}
