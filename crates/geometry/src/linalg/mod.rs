//! Small dense kernels on the stack.
//!
//! * [`jacobi_svd`]: one-sided (Hestenes) Jacobi SVD for the 3 × 3 rank-2
//!   projection and the 9 × 9 plain 8-point system. It orthogonalises the
//!   columns of `A` by plane rotations, `A V = U Σ`: the singular values are
//!   the final column norms and `V` accumulates the rotations. Small singular
//!   values come out with high relative accuracy, independent of column
//!   scaling, which is what the null vectors of the 8-point systems need.
//! * [`smallest_eigenpair`]: the smallest eigenpair of the 9 × 9 normal
//!   matrix `XᵀWX` of the normalised 8-point: all eigenvalues by Householder
//!   tridiagonalisation and implicit QL (no eigenvectors), then the one
//!   eigenvector needed by inverse iteration with a Cholesky factor.
//! * [`GivensQr9`]: incremental Givens QR of a tall matrix with 9 columns
//!   (the plain 8-point's rows), `RᵀR = XᵀX` without forming `XᵀX`.

// Dense kernels on fixed-size arrays read most clearly with explicit indices.
#![allow(clippy::needless_range_loop)]

use std::cmp::Ordering;

/// Result of [`jacobi_svd`] for an `N × N` matrix.
#[derive(Debug, Clone, Copy)]
pub(crate) struct JacobiSvd<const N: usize> {
    /// Singular values, unsorted (`singular_values[j] = ‖(A V)_j‖`).
    pub singular_values: [f64; N],
    /// Columns of `V` (right singular vectors), `v[j]` for `singular_values[j]`.
    pub v: [[f64; N]; N],
    /// Columns of `A V = U Σ`.
    pub av: [[f64; N]; N],
}

impl<const N: usize> JacobiSvd<N> {
    /// Indices of the smallest and second-smallest singular values and the
    /// largest singular value.
    pub fn extremes(&self) -> (usize, f64, f64) {
        let s = &self.singular_values;
        let mut min = 0;
        let mut max = f64::NEG_INFINITY;
        for (j, &v) in s.iter().enumerate() {
            max = max.max(v);
            if v < s[min] {
                min = j;
            }
        }
        let second = (0..N)
            .filter(|&j| j != min)
            .map(|j| s[j])
            .fold(f64::INFINITY, f64::min);
        (min, second, max)
    }
}

/// Maximum number of sweeps; quadratic convergence makes 6–10 typical.
const MAX_SWEEPS: usize = 60;

/// One-sided Jacobi SVD of the `N × N` matrix given by its columns.
/// Returns `None` when an entry is not finite, the matrix is zero, or the
/// sweeps do not converge.
pub(crate) fn jacobi_svd<const N: usize>(columns: [[f64; N]; N]) -> Option<JacobiSvd<N>> {
    if !columns.iter().flatten().all(|v| v.is_finite()) {
        return None;
    }
    // Exact power-of-two scaling so that the largest entry is in [1, 2).
    let largest = columns
        .iter()
        .flatten()
        .fold(0.0_f64, |m, v| m.max(v.abs()));
    if largest == 0.0 {
        return None;
    }
    let exponent = largest.log2().floor() as i32;
    // Two factors each, so that no factor leaves the normal range.
    let half = exponent / 2;
    let (down1, down2) = (2f64.powi(-half), 2f64.powi(half - exponent));
    let (up1, up2) = (2f64.powi(half), 2f64.powi(exponent - half));
    let mut av = columns.map(|col| col.map(|x| x * down1 * down2));
    let mut v = [[0.0; N]; N];
    for (j, col) in v.iter_mut().enumerate() {
        col[j] = 1.0;
    }
    // Columns count as orthogonal when |cos| <= N·ε: the rounding error of a
    // length-N dot product, so that no sweep chases rounding noise.
    let tolerance = N as f64 * f64::EPSILON;
    let mut converged = false;
    for _ in 0..MAX_SWEEPS {
        let mut rotated = false;
        for p in 0..N {
            for q in p + 1..N {
                let (alpha, beta, gamma) = dots(&av[p], &av[q]);
                // A column whose squared norm underflows is zero to working
                // precision (entries are scaled to at most 2 below).
                if alpha < f64::MIN_POSITIVE
                    || beta < f64::MIN_POSITIVE
                    || gamma.abs() <= tolerance * alpha.sqrt() * beta.sqrt()
                {
                    continue;
                }
                rotated = true;
                // tan θ of the rotation that zeroes the dot product (the
                // smaller root, |t| <= 1); for huge ζ, t = 1 / (2ζ).
                let zeta = (beta - alpha) / (2.0 * gamma);
                let t = if zeta.abs() < 1e150 {
                    zeta.signum() / (zeta.abs() + (1.0 + zeta * zeta).sqrt())
                } else {
                    0.5 / zeta
                };
                let c = 1.0 / (1.0 + t * t).sqrt();
                let s = c * t;
                rotate(&mut av, p, q, c, s);
                rotate(&mut v, p, q, c, s);
            }
        }
        if !rotated {
            converged = true;
            break;
        }
    }
    if !converged {
        return None;
    }

    let av = av.map(|col| col.map(|x| x * up1 * up2));
    let mut singular_values = [0.0; N];
    for (s, col) in singular_values.iter_mut().zip(&av) {
        *s = col.iter().map(|x| x * x).sum::<f64>().sqrt();
    }
    Some(JacobiSvd {
        singular_values,
        v,
        av,
    })
}

#[inline(always)]
fn dots<const N: usize>(a: &[f64; N], b: &[f64; N]) -> (f64, f64, f64) {
    let (mut aa, mut bb, mut ab) = (0.0, 0.0, 0.0);
    for k in 0..N {
        aa += a[k] * a[k];
        bb += b[k] * b[k];
        ab += a[k] * b[k];
    }
    (aa, bb, ab)
}

/// Columns `p, q ← (c·p − s·q, s·p + c·q)`.
#[inline(always)]
fn rotate<const N: usize>(m: &mut [[f64; N]; N], p: usize, q: usize, c: f64, s: f64) {
    for k in 0..N {
        let (x, y) = (m[p][k], m[q][k]);
        m[p][k] = c * x - s * y;
        m[q][k] = s * x + c * y;
    }
}

/// The smallest eigenpair of a symmetric positive semi-definite 9 × 9
/// matrix, with the second-smallest and largest eigenvalues for the rank test.
#[derive(Debug, Clone, Copy)]
pub(crate) struct SmallestEigenpair {
    /// Unit eigenvector of the smallest eigenvalue.
    pub vector: [f64; 9],
    /// Second-smallest eigenvalue.
    pub second: f64,
    /// Largest eigenvalue.
    pub largest: f64,
}

/// Smallest eigenpair of the symmetric positive semi-definite matrix `a`
/// (rows; only symmetric input is meaningful). `None` when an entry is not
/// finite, the matrix is zero, or an iteration fails to converge.
///
/// Eigenvalues are accurate to `O(ε‖A‖)` absolutely. The eigenvector comes
/// from inverse iteration on `A − σI`, `σ = λ_min − δ`, `δ = 10⁻¹³ λ_max`
/// (so that the shifted matrix is positive definite whatever the rounding
/// in `λ_min`): each step shrinks the other components by
/// `δ / (λ_2 − λ_min + δ)`, and three steps are made.
pub(crate) fn smallest_eigenpair(a: &[[f64; 9]; 9]) -> Option<SmallestEigenpair> {
    if !a.iter().flatten().all(|v| v.is_finite()) {
        return None;
    }
    let mut values = symmetric_eigenvalues(a)?;
    values.sort_by(f64::total_cmp);
    let (smallest, second, largest) = (values[0], values[1], values[8]);
    if largest.partial_cmp(&0.0) != Some(Ordering::Greater) {
        return None;
    }

    // Inverse iteration with a Cholesky factor of A − σI; the shift is
    // widened if rounding leaves a non-positive pivot.
    let mut delta = 1e-13 * largest;
    for _ in 0..8 {
        let sigma = smallest - delta;
        if let Some(l) = cholesky(a, sigma) {
            // An irregular start vector: no structured eigenvector is
            // orthogonal to it.
            let mut x = [
                0.5377, 1.8339, -2.2588, 0.8622, 0.3188, -1.3077, -0.4336, 0.3426, 3.5784,
            ];
            for _ in 0..3 {
                cholesky_solve(&l, &mut x);
                let norm = x.iter().map(|v| v * v).sum::<f64>().sqrt();
                if !(norm.is_finite() && norm > 0.0) {
                    return None;
                }
                x.iter_mut().for_each(|v| *v /= norm);
            }
            return Some(SmallestEigenpair {
                vector: x,
                second,
                largest,
            });
        }
        delta *= 16.0;
    }
    None
}

/// All eigenvalues (unsorted) of the symmetric matrix `a`: Householder
/// reduction to tridiagonal form, then the implicit QL iteration with
/// Wilkinson-type shifts on the diagonal `d` and sub-diagonal `e`.
pub(crate) fn symmetric_eigenvalues(a: &[[f64; 9]; 9]) -> Option<[f64; 9]> {
    const N: usize = 9;
    // Exact power-of-two scaling to a largest entry in [1, 2): the plane
    // rotations below can then use sqrt(f² + g²) without overflow.
    let largest = a.iter().flatten().fold(0.0_f64, |m, v| m.max(v.abs()));
    if largest == 0.0 {
        return Some([0.0; N]);
    }
    let exponent = largest.log2().floor() as i32;
    let half = exponent / 2;
    let (down1, down2) = (2f64.powi(-half), 2f64.powi(half - exponent));
    let (up1, up2) = (2f64.powi(half), 2f64.powi(exponent - half));
    let scaled = a.map(|row| row.map(|v| v * down1 * down2));
    let (mut d, mut e) = tridiagonalize(scaled);
    implicit_ql(&mut d, &mut e)?;
    if d.iter().all(|v| v.is_finite()) {
        Some(d.map(|v| v * up1 * up2))
    } else {
        None
    }
}

/// Householder reduction of the exactly symmetric `m` (what the callers
/// build, entry `(c, r)` copied from `(r, c)`) to tridiagonal form: the
/// diagonal `d` and the sub-diagonal `e` (`e[i]` couples `d[i]` and
/// `d[i + 1]`, `e[8] = 0`). For column k, m[k+1.., k] is reflected onto a
/// multiple of e1.
fn tridiagonalize(mut m: [[f64; 9]; 9]) -> ([f64; 9], [f64; 9]) {
    const N: usize = 9;
    let mut d = [0.0; N];
    let mut e = [0.0; N];
    for k in 0..N - 2 {
        let mut v = [0.0; N];
        let mut norm2 = 0.0;
        for i in k + 1..N {
            v[i] = m[i][k];
            norm2 += v[i] * v[i];
        }
        let norm = norm2.sqrt();
        d[k] = m[k][k];
        if norm == 0.0 {
            e[k] = 0.0;
            continue;
        }
        let alpha = if v[k + 1] > 0.0 { -norm } else { norm };
        e[k] = alpha;
        v[k + 1] -= alpha;
        let vtv = norm2 - 2.0 * alpha * m[k + 1][k] + alpha * alpha;
        if vtv == 0.0 {
            continue;
        }
        let beta = 2.0 / vtv;
        // p = β M v, w = p − (β pᵀv / 2) v, M ← M − v wᵀ − w vᵀ. M stays
        // exactly symmetric (both products of an entry are added in either
        // order, and a + b = b + a), so row j serves as column j: each
        // p_i sums m_ij v_j over j = k+1, k+2, … in that order, as a row
        // by row loop would, while the loops over i run the full width.
        let mut sums = [0.0; N];
        for j in k + 1..N {
            for (sum, &m_ji) in sums.iter_mut().zip(&m[j]) {
                *sum += m_ji * v[j];
            }
        }
        let mut p = [0.0; N];
        for i in k + 1..N {
            p[i] = beta * sums[i];
        }
        let ptv: f64 = (k + 1..N).map(|i| p[i] * v[i]).sum();
        let kappa = 0.5 * beta * ptv;
        for i in k + 1..N {
            p[i] -= kappa * v[i];
        }
        // Entries of the finished columns (j ≤ k) see v_j = p_j = 0 and
        // are left as they are (x − 0 = x); they are not read again.
        for i in k + 1..N {
            let (vi, pi) = (v[i], p[i]);
            for ((m_ij, &pj), &vj) in m[i].iter_mut().zip(&p).zip(&v) {
                *m_ij -= vi * pj + pi * vj;
            }
        }
    }
    d[N - 2] = m[N - 2][N - 2];
    d[N - 1] = m[N - 1][N - 1];
    e[N - 2] = m[N - 1][N - 2];
    e[N - 1] = 0.0;

    (d, e)
}

/// The implicit QL iteration with Wilkinson-type shifts on a tridiagonal
/// matrix (diagonal `d`, sub-diagonal `e`), leaving the eigenvalues in
/// `d`; `None` when an eigenvalue needs more than 60 iterations.
fn implicit_ql(d: &mut [f64; 9], e: &mut [f64; 9]) -> Option<()> {
    const N: usize = 9;
    // Implicit QL: e[i] couples d[i] and d[i + 1]. An off-diagonal entry is
    // negligible relative to its neighbours or to the whole matrix (the
    // Householder step already limits the accuracy to ε‖A‖, and chasing a
    // relative ε next to eigenvalues of size ε‖A‖ would only spin).
    let norm = (0..N)
        .map(|i| d[i].abs() + e[i].abs() + if i > 0 { e[i - 1].abs() } else { 0.0 })
        .fold(0.0, f64::max);
    let negligible = f64::EPSILON * norm;
    for l in 0..N {
        let mut iterations = 0;
        loop {
            let mut m_end = l;
            while m_end < N - 1 {
                let dd = d[m_end].abs() + d[m_end + 1].abs();
                if e[m_end].abs() <= f64::EPSILON * dd || e[m_end].abs() <= negligible {
                    break;
                }
                m_end += 1;
            }
            if m_end == l {
                break;
            }
            iterations += 1;
            if iterations > 60 {
                return None;
            }
            let mut g = (d[l + 1] - d[l]) / (2.0 * e[l]);
            let mut r = (g * g + 1.0).sqrt();
            g = d[m_end] - d[l] + e[l] / (g + if g >= 0.0 { r } else { -r });
            let (mut s, mut c, mut p) = (1.0, 1.0, 0.0);
            let mut underflow = false;
            let mut i = m_end;
            while i > l {
                i -= 1;
                let f = s * e[i];
                let b = c * e[i];
                r = (f * f + g * g).sqrt();
                e[i + 1] = r;
                if r == 0.0 {
                    d[i + 1] -= p;
                    e[m_end] = 0.0;
                    underflow = true;
                    break;
                }
                s = f / r;
                c = g / r;
                g = d[i + 1] - p;
                r = (d[i] - g) * s + 2.0 * c * b;
                p = s * r;
                d[i + 1] = g + p;
                g = c * r - b;
            }
            if underflow {
                continue;
            }
            d[l] -= p;
            e[l] = g;
            e[m_end] = 0.0;
        }
    }
    Some(())
}

/// Lower Cholesky factor of `a − σI`, or `None` when a pivot is not positive.
fn cholesky(a: &[[f64; 9]; 9], sigma: f64) -> Option<[[f64; 9]; 9]> {
    let mut l = [[0.0; 9]; 9];
    for j in 0..9 {
        let mut diag = a[j][j] - sigma;
        for k in 0..j {
            diag -= l[j][k] * l[j][k];
        }
        if diag.partial_cmp(&0.0) != Some(Ordering::Greater) {
            return None;
        }
        let ljj = diag.sqrt();
        l[j][j] = ljj;
        for i in j + 1..9 {
            let mut sum = a[i][j];
            for k in 0..j {
                sum -= l[i][k] * l[j][k];
            }
            l[i][j] = sum / ljj;
        }
    }
    Some(l)
}

/// Solves `L Lᵀ x = b` in place.
fn cholesky_solve(l: &[[f64; 9]; 9], x: &mut [f64; 9]) {
    for i in 0..9 {
        let mut sum = x[i];
        for k in 0..i {
            sum -= l[i][k] * x[k];
        }
        x[i] = sum / l[i][i];
    }
    for i in (0..9).rev() {
        let mut sum = x[i];
        for k in i + 1..9 {
            sum -= l[k][i] * x[k];
        }
        x[i] = sum / l[i][i];
    }
}

/// Incremental QR factorisation of a tall matrix with 9 columns by Givens
/// rotations: after pushing the rows of `X`, `factor()` is an upper
/// triangular `R` with `RᵀR = XᵀX` (so the same singular values and right
/// singular vectors as `X`), computed without forming `XᵀX`.
#[derive(Debug, Clone, Default)]
pub(crate) struct GivensQr9 {
    /// The rows of the upper triangular factor `R`.
    pub r: [[f64; 9]; 9],
}

impl GivensQr9 {
    /// Folds one row into `R`, zeroing it against the diagonal.
    pub fn push(&mut self, mut row: [f64; 9]) {
        for k in 0..9 {
            let b = row[k];
            if b == 0.0 {
                continue;
            }
            let a = self.r[k][k];
            let h = a.hypot(b);
            let (c, s) = (a / h, b / h);
            self.r[k][k] = h;
            for j in k + 1..9 {
                let (rj, xj) = (self.r[k][j], row[j]);
                self.r[k][j] = c * rj + s * xj;
                row[j] = c * xj - s * rj;
            }
        }
    }
}

#[cfg(test)]
mod tests;
