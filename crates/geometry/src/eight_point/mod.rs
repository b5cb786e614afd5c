//! The 8-point algorithm (step 2 of Algorithm 1, and step 3d's weighted fit).
//!
//! Every match `x1 ↔ x2` gives one linear equation `x2ᵀ F x1 = 0` in the nine
//! entries of `F` (row-major, `f = (F00, F01, …, F22)`), the design row
//!
//! ```text
//! X_i = [x2·x1, x2·y1, x2, y2·x1, y2·y1, y2, x1, y1, 1],   X_i f = x2ᵀ F x1.
//! ```
//!
//! With N ≥ 8 matches the estimate minimises the algebraic error
//! `fᵀ Xᵀ W X f` subject to `‖f‖ = 1` (`W = diag(w_i)`, `W = I` when
//! unweighted): `f` is the eigenvector of the smallest eigenvalue of the 9 × 9
//! normal matrix `Xᵀ W X`, equivalently the right singular vector of the
//! smallest singular value of `W^½ X`. The result is then made rank 2 by
//! zeroing the smallest singular value of `F`, the constraint `det F = 0`
//! that every fundamental matrix satisfies.
//!
//! Four variants, two coordinate frames × unweighted/weighted:
//! * [`eight_point_plain`]: the system in the given (principal-point-centred)
//!   pixel coordinates, as the reference implementation solves it. Its
//!   columns differ in scale by ~`10⁵`, so it is solved by an incremental
//!   Givens QR of `X` and a one-sided Jacobi SVD of the 9 × 9 triangular
//!   factor, never by the normal matrix (whose condition number would be the
//!   square). With exactly 8 matches the solution is the null vector of `X`,
//!   which the normalised system gives more accurately.
//! * [`eight_point_weighted_plain`]: the same with weights, minimising
//!   `fᵀ Xᵀ W X f` in pixel coordinates (the reference code's IRLS refit):
//!   the rows enter the QR scaled by `√w_i`.
//! * [`eight_point_normalized`]: Hartley normalisation first (per image,
//!   centroid to the origin, mean distance to it `√2`: `x̂ = T x`), solve for
//!   `F̂`, enforce rank 2, denormalise `F = T2ᵀ F̂ T1`. The normalised system is
//!   well conditioned, so the normal matrix and a symmetric eigensolver are
//!   accurate; the normal matrix is accumulated as 36 moment sums per match
//!   (`XᵀWX = Σ w (x2 x2ᵀ) ⊗ (x1 x1ᵀ)`) with no allocation.
//! * [`eight_point_weighted`]: the same with weights, minimising
//!   `fᵀ Xᵀ W X f` (the IRLS step, Section 5.2.1); the normalisation uses
//!   weighted centroids and mean distances, so unit weights reproduce
//!   [`eight_point_normalized`] and zero weights remove points entirely.
//!
//! The two frames minimise different algebraic errors (the normalised one
//! weighs the nine monomials of a match comparably; in pixels the quadratic
//! ones dominate by ~`10⁵`), so on noisy data they give different `F`.
//!
//! All four return `F` with unit Frobenius norm and the sign that makes its
//! entry of largest magnitude positive. A system whose null space has more
//! than one dimension (duplicate points, all points of one image collinear,
//! fewer than 8 distinct matches) is [`GeometryError::Degenerate`]: the
//! second-smallest singular value of the column-balanced system is below
//! [`RANK_TOLERANCE`] times the largest.

// Dense kernels on fixed-size arrays read most clearly with explicit indices.
#![allow(clippy::needless_range_loop)]

use crate::linalg::{jacobi_svd, smallest_eigenpair, symmetric_eigenvalues, GivensQr9};
use crate::simd::dispatch;
use crate::{Correspondences, GeometryError};
use nalgebra::{Matrix3, SVector};
use std::cmp::Ordering;

/// Number of matches the 8-point algorithm needs.
pub const MIN_POINTS: usize = 8;

/// Relative threshold on singular values: the system is rank-deficient (null
/// space of dimension > 1) when its second-smallest singular value is below
/// `RANK_TOLERANCE · σ_max` after the columns are balanced (Hartley
/// normalisation, or unit column norms for the plain variant). For the
/// normal matrix this reads `λ_2nd < RANK_TOLERANCE² · λ_max`.
pub const RANK_TOLERANCE: f64 = 1e-6;

type Vector9 = SVector<f64, 9>;

/// The design row `X_i` of one match, so that `X_i · vec_row(F) = x2ᵀ F x1`.
#[inline(always)]
fn design_row(x1: f64, y1: f64, x2: f64, y2: f64) -> [f64; 9] {
    [x2 * x1, x2 * y1, x2, y2 * x1, y2 * y1, y2, x1, y1, 1.0]
}

/// Reshapes the row-major vector `f` into `F`.
#[inline]
fn matrix_from_row_major(f: &Vector9) -> Matrix3<f64> {
    Matrix3::new(f[0], f[1], f[2], f[3], f[4], f[5], f[6], f[7], f[8])
}

/// Rank-2 enforcement: `F = U diag(s1, s2, s3) Vᵀ ↦ U diag(s1, s2, 0) Vᵀ`, the
/// closest rank-2 matrix in Frobenius norm (Eckart–Young). A matrix that is
/// not finite, or whose SVD does not converge, is returned unchanged.
///
/// ```
/// use geometry::enforce_rank2;
/// use nalgebra::Matrix3;
/// let f = Matrix3::new(1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 10.0);
/// let g = enforce_rank2(f);
/// assert!(g.determinant().abs() < 1e-12 * g.norm().powi(3));
/// assert!((g - f).norm() < 0.2);
/// ```
pub fn enforce_rank2(f: Matrix3<f64>) -> Matrix3<f64> {
    // One-sided Jacobi rather than nalgebra's SVD: its 3 × 3 path goes
    // through the eigenvectors of FᵀF (half the digits of the smallest
    // triplet lost) and its general path can stop early on matrices with a
    // tiny singular value (absolute convergence threshold).
    let columns = [0, 1, 2].map(|c| [f[(0, c)], f[(1, c)], f[(2, c)]]);
    let Some(svd) = jacobi_svd(columns) else {
        return f;
    };
    let (smallest, _, _) = svd.extremes();
    // F = Σ_j (A V)_j v_jᵀ; drop the term of the smallest singular value.
    let mut g = Matrix3::zeros();
    for j in (0..3).filter(|&j| j != smallest) {
        for r in 0..3 {
            for c in 0..3 {
                g[(r, c)] += svd.av[j][r] * svd.v[j][c];
            }
        }
    }
    g
}

/// `F / ‖F‖_Frobenius`, with the sign that makes the entry of largest
/// magnitude (first one on ties, row-major) positive.
fn canonical_scale(f: Matrix3<f64>) -> Matrix3<f64> {
    let f = f / f.norm();
    let mut largest = 0.0_f64;
    for r in 0..3 {
        for c in 0..3 {
            if f[(r, c)].abs() > largest.abs() {
                largest = f[(r, c)];
            }
        }
    }
    if largest < 0.0 {
        -f
    } else {
        f
    }
}

/// Final checks and canonical form shared by the estimators.
pub(crate) fn finish(f: Matrix3<f64>) -> Result<Matrix3<f64>, GeometryError> {
    let norm = f.norm();
    if !norm.is_finite() {
        return Err(GeometryError::Overflow("fundamental matrix"));
    }
    if norm == 0.0 {
        return Err(GeometryError::Degenerate("estimated matrix is zero"));
    }
    Ok(canonical_scale(f))
}

/// Plain 8-point (step 2 as the reference code runs it): minimises `‖X f‖`
/// subject to `‖f‖ = 1` in the given pixel coordinates, which should already
/// have the principal point at the origin; then rank 2 (see
/// [`enforce_rank2`]) and unit Frobenius norm.
///
/// Numerics: with exactly 8 matches the minimiser is the null vector of `X`,
/// computed from the Hartley-normalised system (same null space, better
/// conditioned). Otherwise the rows are folded one by one into the 9 × 9 triangular factor
/// `R` of a Givens QR of `X` (`XᵀX = RᵀR`, no allocation proportional to N)
/// and `f` is the right singular vector of `R` for its smallest singular
/// value, from a one-sided Jacobi SVD (accurate for badly scaled columns).
/// Rank deficiency is tested on `R D⁻¹`, `D` the column norms, through the
/// eigenvalues of its Gram matrix.
///
/// Errors: [`GeometryError::TooFewPoints`] for N < 8,
/// [`GeometryError::Degenerate`] for a null space of dimension > 1,
/// [`GeometryError::Overflow`] when coordinates are too large for `f64`.
///
/// ```
/// use geometry::{eight_point_plain, Correspondences};
/// // Sideways translation: x2 = x1 + f·tx / Z, y2 = y1, depths Z varying.
/// let p1: Vec<[f64; 2]> = (0..8).map(|i| [(i * 37 % 11) as f64 * 20.0 - 100.0, (i * i % 7) as f64 * 15.0 - 50.0]).collect();
/// let p2: Vec<[f64; 2]> = p1.iter().enumerate().map(|(i, p)| [p[0] + 4000.0 / (4.0 + i as f64), p[1]]).collect();
/// let c = Correspondences::new(&p1, &p2).unwrap();
/// let f = eight_point_plain(&c).unwrap();
/// // F ∝ [t]x with t = (1, 0, 0): only F12 = -F21 are non-zero.
/// let s = std::f64::consts::FRAC_1_SQRT_2;
/// assert!((f[(1, 2)].abs() - s).abs() < 1e-9 && (f[(1, 2)] + f[(2, 1)]).abs() < 1e-9);
/// ```
pub fn eight_point_plain(points: &Correspondences) -> Result<Matrix3<f64>, GeometryError> {
    let n = points.len();
    if n < MIN_POINTS {
        return Err(GeometryError::TooFewPoints {
            got: n,
            needed: MIN_POINTS,
        });
    }
    fit_plain(points, (0..n).map(|i| (i, 1.0)))
}

/// Weighted plain 8-point (step 3d as the reference code runs it):
/// minimises `fᵀ Xᵀ W X f = ‖W^½ X f‖²` subject to `‖f‖ = 1`,
/// `W = diag(weights)`, in the given (principal-point-centred) pixel
/// coordinates, without Hartley normalisation; then rank 2 and unit
/// Frobenius norm. Unit weights give [`eight_point_plain`]; a zero weight
/// removes a match; multiplying all weights by a constant does not change
/// the minimiser.
///
/// Numerics as [`eight_point_plain`], with the rows scaled by `√w_i` (the
/// reference code takes the SVD of the normal matrix `XᵀWX` itself, which
/// squares the condition number; the minimiser is the same). With exactly 8
/// positive weights it is the null vector of those 8 rows, whatever the
/// weights.
///
/// Errors: as [`eight_point_weighted`] (weight count, invalid weight,
/// [`GeometryError::TooFewWeightedPoints`]), then as [`eight_point_plain`].
///
/// ```
/// use geometry::{eight_point_plain, eight_point_weighted_plain, frob_distance, Correspondences};
/// // Sideways translation with varying depth, plus one gross outlier.
/// let p1: Vec<[f64; 2]> = (0..10).map(|i| [(i * 37 % 11) as f64 * 20.0 - 100.0, (i * i % 7) as f64 * 15.0 - 50.0]).collect();
/// let mut p2: Vec<[f64; 2]> = p1.iter().enumerate().map(|(i, p)| [p[0] + 4000.0 / (4.0 + i as f64), p[1]]).collect();
/// p2[9] = [300.0, -200.0];
/// let all = Correspondences::new(&p1, &p2).unwrap();
/// let clean = Correspondences::new(&p1[..9], &p2[..9]).unwrap();
/// let mut w = vec![2.0; 10];
/// w[9] = 0.0;
/// let fw = eight_point_weighted_plain(&all, &w).unwrap();
/// assert!(frob_distance(&fw, &eight_point_plain(&clean).unwrap()) < 1e-12);
/// ```
pub fn eight_point_weighted_plain(
    points: &Correspondences,
    weights: &[f64],
) -> Result<Matrix3<f64>, GeometryError> {
    check_weights(points, weights)?;
    fit_plain(points, weights.iter().copied().enumerate())
}

/// The weighted plain solve behind [`eight_point_plain`],
/// [`eight_point_weighted_plain`] and the IRLS step's plain refit: `items`
/// yields `(index, weight)` pairs with valid indices and finite weights
/// `>= 0`; it is iterated twice.
pub(crate) fn fit_plain<I>(
    points: &Correspondences,
    items: I,
) -> Result<Matrix3<f64>, GeometryError>
where
    I: Iterator<Item = (usize, f64)> + Clone,
{
    let positive = items.clone().filter(|&(_, w)| w > 0.0).count();
    if positive < MIN_POINTS {
        return Err(GeometryError::TooFewWeightedPoints {
            got: positive,
            needed: MIN_POINTS,
        });
    }
    if positive == MIN_POINTS {
        // Eight matches in general position leave a one-dimensional null
        // space: the minimiser is that null vector in any coordinates and for
        // any positive weights, so it is computed from the well-conditioned
        // normalised system; rank 2 is then enforced in the given
        // coordinates, as the plain variant does.
        let solution = solve_normalized(points, items)?;
        let f = solution.t2.transpose() * solution.f_hat * solution.t1;
        return finish(enforce_rank2(f / f.norm()));
    }
    let (x1, y1, x2, y2) = points.columns();
    let mut qr = GivensQr9::default();
    for (i, w) in items.filter(|&(_, w)| w > 0.0) {
        // √1 = 1 exactly: unit weights fold the rows unchanged.
        let scale = w.sqrt();
        qr.push(design_row(x1[i], y1[i], x2[i], y2[i]).map(|v| v * scale));
    }
    let r = qr.r;
    if !r.iter().flatten().all(|v| v.is_finite()) {
        return Err(GeometryError::Overflow("design matrix"));
    }

    // Rank test on the column-balanced factor R D⁻¹ (same rank as X), by the
    // eigenvalues of its Gram matrix: σ_i² to O(ε) of the largest.
    let mut balanced = columns_of(&r);
    for column in balanced.iter_mut() {
        let norm = column.iter().map(|v| v * v).sum::<f64>().sqrt();
        if norm > 0.0 {
            column.iter_mut().for_each(|v| *v /= norm);
        }
    }
    let mut gram = [[0.0; 9]; 9];
    for i in 0..9 {
        for j in i..9 {
            let dot: f64 = (0..9).map(|k| balanced[i][k] * balanced[j][k]).sum();
            gram[i][j] = dot;
            gram[j][i] = dot;
        }
    }
    let mut eigenvalues = symmetric_eigenvalues(&gram)
        .ok_or(GeometryError::Degenerate("eigen solver did not converge"))?;
    eigenvalues.sort_by(f64::total_cmp);
    if eigenvalues[1].partial_cmp(&(RANK_TOLERANCE * RANK_TOLERANCE * eigenvalues[8]))
        != Some(Ordering::Greater)
    {
        return Err(GeometryError::Degenerate(
            "rank-deficient 8-point system (null space of dimension > 1)",
        ));
    }

    let svd = jacobi_svd(columns_of(&r)).ok_or(GeometryError::Degenerate(
        "singular value solver did not converge",
    ))?;
    let (smallest, _, _) = svd.extremes();
    let f = Vector9::from(svd.v[smallest]);
    finish(enforce_rank2(matrix_from_row_major(&f)))
}

/// The columns of the triangular factor rows `r`.
fn columns_of(r: &[[f64; 9]; 9]) -> [[f64; 9]; 9] {
    let mut columns = [[0.0; 9]; 9];
    for (i, row) in r.iter().enumerate() {
        for (j, &v) in row.iter().enumerate() {
            columns[j][i] = v;
        }
    }
    columns
}

/// Hartley-normalised 8-point (step 2 of Algorithm 1): with
/// `T = [[s, 0, −s·cx], [0, s, −s·cy], [0, 0, 1]]` per image (`c` the
/// centroid, `s = √2 / mean ‖x − c‖`), solves the 8-point system on
/// `x̂ = T x`, enforces rank 2 on `F̂` and returns `F = T2ᵀ F̂ T1` with unit
/// Frobenius norm. The result depends only on the matches, not on the
/// image coordinate frame.
///
/// Errors: [`GeometryError::TooFewPoints`] for N < 8,
/// [`GeometryError::Degenerate`] for coincident points or a null space of
/// dimension > 1, [`GeometryError::Overflow`] for coordinates too large.
///
/// ```
/// use geometry::{eight_point_normalized, sampson_distance, Correspondences};
/// use nalgebra::{Matrix3, Vector3};
/// // Synthetic scene: camera 2 = camera 1 rotated 0.1 rad about y, moved along x.
/// let (c, s) = (0.1f64.cos(), 0.1f64.sin());
/// let r = Matrix3::new(c, 0.0, s, 0.0, 1.0, 0.0, -s, 0.0, c);
/// let t = Vector3::new(1.0, 0.2, 0.1);
/// let k = Matrix3::new(800.0, 0.0, 0.0, 0.0, 800.0, 0.0, 0.0, 0.0, 1.0);
/// let (mut p1, mut p2) = (vec![], vec![]);
/// for i in 0..12 {
///     let x = Vector3::new((i % 4) as f64 - 1.5, (i / 4) as f64 - 1.0, 5.0 + (i * 7 % 5) as f64);
///     let (a, b) = (k * x, k * (r * x + t));
///     p1.push([a.x / a.z, a.y / a.z]);
///     p2.push([b.x / b.z, b.y / b.z]);
/// }
/// let points = Correspondences::new(&p1, &p2).unwrap();
/// let f = eight_point_normalized(&points).unwrap();
/// for i in 0..12 {
///     assert!(sampson_distance(&f, p1[i], p2[i]) < 1e-9);
/// }
/// ```
pub fn eight_point_normalized(points: &Correspondences) -> Result<Matrix3<f64>, GeometryError> {
    let n = points.len();
    if n < MIN_POINTS {
        return Err(GeometryError::TooFewPoints {
            got: n,
            needed: MIN_POINTS,
        });
    }
    fit_normalized(points, (0..n).map(|i| (i, 1.0)))
}

/// Weighted, Hartley-normalised 8-point (step 3d of Algorithm 1): minimises
/// `f̂ᵀ X̂ᵀ W X̂ f̂` subject to `‖f̂‖ = 1`, `W = diag(weights)`, on coordinates
/// normalised with the weighted centroid and weighted mean distance; then
/// rank 2 and `F = T2ᵀ F̂ T1` with unit Frobenius norm. Multiplying all
/// weights by a positive constant does not change the result; unit weights
/// give [`eight_point_normalized`]; a zero weight removes a match.
///
/// Errors: [`GeometryError::WeightCountMismatch`] unless
/// `weights.len() == points.len()`, [`GeometryError::InvalidWeight`] for a
/// negative or non-finite weight, [`GeometryError::TooFewWeightedPoints`]
/// when fewer than 8 weights are positive, otherwise as
/// [`eight_point_normalized`].
///
/// ```
/// use geometry::{eight_point_normalized, eight_point_weighted, frob_distance, Correspondences};
/// // Sideways translation with varying depth, plus one gross outlier.
/// let p1: Vec<[f64; 2]> = (0..10).map(|i| [(i * 37 % 11) as f64 * 20.0 - 100.0, (i * i % 7) as f64 * 15.0 - 50.0]).collect();
/// let mut p2: Vec<[f64; 2]> = p1.iter().enumerate().map(|(i, p)| [p[0] + 4000.0 / (4.0 + i as f64), p[1]]).collect();
/// p2[9] = [300.0, -200.0];
/// let all = Correspondences::new(&p1, &p2).unwrap();
/// let clean = Correspondences::new(&p1[..9], &p2[..9]).unwrap();
/// let mut w = vec![1.0; 10];
/// w[9] = 0.0;
/// let fw = eight_point_weighted(&all, &w).unwrap();
/// assert!(frob_distance(&fw, &eight_point_normalized(&clean).unwrap()) < 1e-12);
/// assert!(eight_point_weighted(&all, &[1.0; 3]).is_err());
/// ```
pub fn eight_point_weighted(
    points: &Correspondences,
    weights: &[f64],
) -> Result<Matrix3<f64>, GeometryError> {
    check_weights(points, weights)?;
    fit_normalized(points, weights.iter().copied().enumerate())
}

/// The checks of the weighted estimators: one weight per match, every
/// weight finite and `>= 0`, at least 8 matches.
fn check_weights(points: &Correspondences, weights: &[f64]) -> Result<(), GeometryError> {
    let n = points.len();
    if weights.len() != n {
        return Err(GeometryError::WeightCountMismatch {
            weights: weights.len(),
            points: n,
        });
    }
    if let Some((index, &value)) = weights
        .iter()
        .enumerate()
        .find(|(_, w)| !(w.is_finite() && **w >= 0.0))
    {
        return Err(GeometryError::InvalidWeight { index, value });
    }
    if n < MIN_POINTS {
        return Err(GeometryError::TooFewPoints {
            got: n,
            needed: MIN_POINTS,
        });
    }
    Ok(())
}

/// The weighted, normalised solve behind [`eight_point_normalized`],
/// [`eight_point_weighted`] and the IRLS step: `items` yields
/// `(index, weight)` pairs with valid indices and finite weights `>= 0`.
/// It is iterated twice (centroids, then distances and the normal matrix).
pub(crate) fn fit_normalized<I>(
    points: &Correspondences,
    items: I,
) -> Result<Matrix3<f64>, GeometryError>
where
    I: Iterator<Item = (usize, f64)> + Clone,
{
    let solution = solve_normalized(points, items)?;
    let f_hat = enforce_rank2(solution.f_hat);
    finish(solution.t2.transpose() * f_hat * solution.t1)
}

/// The minimiser `F̂` of the normalised weighted system (before rank 2) and
/// the two normalising transforms `T1`, `T2`.
struct NormalizedSolution {
    f_hat: Matrix3<f64>,
    t1: Matrix3<f64>,
    t2: Matrix3<f64>,
}

dispatch! {
    /// Hartley normalisation, normal matrix and smallest eigenvector: the part
    /// of [`fit_normalized`] before rank 2 and denormalisation.
    fn solve_normalized<I>(points: &Correspondences, items: I)
        -> Result<NormalizedSolution, GeometryError>
        where [I: Iterator<Item = (usize, f64)> + Clone]
        => solve_normalized_kernel
}

/// The body of [`solve_normalized`], in the build [`crate::simd::avx2`]
/// chooses.
#[inline(always)]
fn solve_normalized_kernel<I>(
    points: &Correspondences,
    items: I,
) -> Result<NormalizedSolution, GeometryError>
where
    I: Iterator<Item = (usize, f64)> + Clone,
{
    let (x1, y1, x2, y2) = points.columns();

    // Pass 1: weighted centroids.
    let (mut sw, mut sx1, mut sy1, mut sx2, mut sy2) = (0.0, 0.0, 0.0, 0.0, 0.0);
    let mut positive = 0usize;
    for (i, w) in items.clone() {
        if w > 0.0 {
            positive += 1;
            sw += w;
            sx1 += w * x1[i];
            sy1 += w * y1[i];
            sx2 += w * x2[i];
            sy2 += w * y2[i];
        }
    }
    if positive < MIN_POINTS {
        return Err(GeometryError::TooFewWeightedPoints {
            got: positive,
            needed: MIN_POINTS,
        });
    }
    let (cx1, cy1, cx2, cy2) = (sx1 / sw, sy1 / sw, sx2 / sw, sy2 / sw);

    // Pass 2: weighted mean distances to the centroids, and the normal matrix
    // of the centred (not yet scaled) rows. A row is the Kronecker product
    // x2 ⊗ x1 (x = (u, v, 1)), so XᵀWX = Σ w (x2 x2ᵀ) ⊗ (x1 x1ᵀ): its 45
    // distinct entries are the 36 sums S[p][q] = Σ w m2_p m1_q of products
    // of the monomials m = (u², uv, u, v², v, 1).
    let mut moments = [[0.0_f64; 6]; 6];
    let (mut d1, mut d2) = (0.0, 0.0);
    for (i, w) in items {
        if w > 0.0 {
            let (u1, v1, u2, v2) = (x1[i] - cx1, y1[i] - cy1, x2[i] - cx2, y2[i] - cy2);
            d1 += w * (u1 * u1 + v1 * v1).sqrt();
            d2 += w * (u2 * u2 + v2 * v2).sqrt();
            let m1 = [w * u1 * u1, w * u1 * v1, w * u1, w * v1 * v1, w * v1, w];
            let m2 = [u2 * u2, u2 * v2, u2, v2 * v2, v2, 1.0];
            for (row, &a) in moments.iter_mut().zip(&m2) {
                for (entry, &b) in row.iter_mut().zip(&m1) {
                    *entry += a * b;
                }
            }
        }
    }
    let (d1, d2) = (d1 / sw, d2 / sw);
    if d1.partial_cmp(&0.0) != Some(Ordering::Greater)
        || d2.partial_cmp(&0.0) != Some(Ordering::Greater)
    {
        return Err(GeometryError::Degenerate(
            "all points coincide in one image",
        ));
    }
    let (s1, s2) = (std::f64::consts::SQRT_2 / d1, std::f64::consts::SQRT_2 / d2);
    if !(s1.is_finite() && s2.is_finite()) {
        return Err(GeometryError::Degenerate(
            "all points coincide in one image",
        ));
    }

    let a = scaled_normal_matrix(&moments, s1, s2)?;

    let f_hat = matrix_from_row_major(&smallest_eigenvector(&a)?);
    // x̂ = T x; the denormalised matrix is F = T2ᵀ F̂ T1.
    let t1 = Matrix3::new(s1, 0.0, -s1 * cx1, 0.0, s1, -s1 * cy1, 0.0, 0.0, 1.0);
    let t2 = Matrix3::new(s2, 0.0, -s2 * cx2, 0.0, s2, -s2 * cy2, 0.0, 0.0, 1.0);
    Ok(NormalizedSolution { f_hat, t1, t2 })
}

/// The normal matrix `XᵀWX` of the Hartley-scaled rows from the moments of
/// the centred ones (see [`solve_normalized`]): scaled rows are
/// `D · (centred rows)`, `D = diag(s1s2, s1s2, s2, s1s2, s1s2, s2, s1, s1, 1)`.
fn scaled_normal_matrix(
    moments: &[[f64; 6]; 6],
    s1: f64,
    s2: f64,
) -> Result<[[f64; 9]; 9], GeometryError> {
    let s12 = s1 * s2;
    let scale = [s12, s12, s2, s12, s12, s2, s1, s1, 1.0];
    let mut a = [[0.0; 9]; 9];
    for r in 0..9 {
        for c in r..9 {
            // Row r = 3i + j pairs x2_i with x1_j.
            let (i, j, k, l) = (r / 3, r % 3, c / 3, c % 3);
            let v = moments[MONOMIAL[i][k]][MONOMIAL[j][l]] * scale[r] * scale[c];
            a[r][c] = v;
            a[c][r] = v;
        }
    }
    if !a.iter().flatten().all(|v| v.is_finite()) {
        return Err(GeometryError::Overflow("normal matrix"));
    }
    Ok(a)
}

/// Index of the monomial `x_i x_k` of `x = (u, v, 1)` in
/// `(u², uv, u, v², v, 1)`.
const MONOMIAL: [[usize; 3]; 3] = [[0, 1, 2], [1, 3, 4], [2, 4, 5]];

/// Unit eigenvector of the smallest eigenvalue of the symmetric positive
/// semi-definite 9 × 9 matrix `a`; [`GeometryError::Degenerate`] when the
/// second-smallest eigenvalue is below `RANK_TOLERANCE² · λ_max`.
fn smallest_eigenvector(a: &[[f64; 9]; 9]) -> Result<Vector9, GeometryError> {
    let pair =
        smallest_eigenpair(a).ok_or(GeometryError::Degenerate("eigen solver did not converge"))?;
    if pair
        .second
        .partial_cmp(&(RANK_TOLERANCE * RANK_TOLERANCE * pair.largest))
        != Some(Ordering::Greater)
    {
        return Err(GeometryError::Degenerate(
            "rank-deficient 8-point system (null space of dimension > 1)",
        ));
    }
    Ok(Vector9::from(pair.vector))
}

#[cfg(test)]
mod tests;
