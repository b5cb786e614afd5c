//! Point-to-model distances for a fundamental matrix, and the FROB distance
//! between two fundamental matrices.
//!
//! For a match `x1 ↔ x2` (homogeneous, `x = (x, y, 1)`) let
//! `e = x2ᵀ F x1`, `F x1 = (a, b, ·)` and `Fᵀ x2 = (c, d, ·)`.
//!
//! Every distance is invariant to multiplying `F` by any non-zero factor: `F`
//! is first rescaled by an exact power of two so that its largest entry lies
//! in `[1, 2)`, which also keeps the products clear of overflow and underflow.

use crate::simd::dispatch;
use crate::Correspondences;
use nalgebra::Matrix3;

/// `num / den` for the distances, with the limits of a zero gradient: a match
/// whose epipolar gradient vanishes (both points at the epipoles of a
/// degenerate `F`) is at distance 0 when it satisfies `x2ᵀ F x1 = 0`
/// (`e = 0`) and at distance `+∞` (signed: `±∞`) otherwise; never NaN.
#[inline(always)]
fn ratio(e: f64, num: f64, den: f64) -> f64 {
    let q = num / den;
    if e == 0.0 {
        0.0
    } else {
        q
    }
}

/// `2^k` for `k` in the normal exponent range `[-1022, 1023]`, built exactly.
#[inline(always)]
fn exp2i(k: i64) -> f64 {
    f64::from_bits(((k + 1023) as u64) << 52)
}

/// `f · 2^k` with `k` chosen so that `max |f_ij|` lies in `[1, 2)`: an exact
/// rescaling (no rounding, except for entries that fall below the normal
/// range), so the distances below do not depend on the scale of `F`.
/// A zero or non-finite matrix is returned unchanged.
#[inline]
pub(crate) fn rescale_power_of_two(f: &Matrix3<f64>) -> Matrix3<f64> {
    let max = f.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    if max == 0.0 || !max.is_finite() {
        return *f;
    }
    let mut g = *f;
    let mut max = max;
    if max < f64::MIN_POSITIVE {
        // Subnormal: lift into the normal range first.
        g *= exp2i(600);
        max *= exp2i(600);
    }
    let exponent = ((max.to_bits() >> 52) & 0x7ff) as i64 - 1023;
    // Two exact factors, each within the normal range, multiply to 2^-exponent.
    let k1 = -exponent / 2;
    g * exp2i(k1) * exp2i(-exponent - k1)
}

/// `(e, a, b, c, d)` for one match: the residual `e = x2ᵀ F x1` and the
/// epipolar lines `F x1 = (a, b, ·)`, `Fᵀ x2 = (c, d, ·)`.
#[inline(always)]
fn epipolar_lines(f: &Matrix3<f64>, x1: f64, y1: f64, x2: f64, y2: f64) -> [f64; 5] {
    lines_of_entries(&row_major(f), x1, y1, x2, y2)
}

/// The entries of `f` row by row, `[f00, f01, f02, f10, …, f22]`.
#[inline(always)]
fn row_major(f: &Matrix3<f64>) -> [f64; 9] {
    std::array::from_fn(|k| f[(k / 3, k % 3)])
}

/// [`epipolar_lines`] of the matrix with row-major entries `f`.
#[inline(always)]
fn lines_of_entries(f: &[f64; 9], x1: f64, y1: f64, x2: f64, y2: f64) -> [f64; 5] {
    // F x1
    let a = f[0] * x1 + f[1] * y1 + f[2];
    let b = f[3] * x1 + f[4] * y1 + f[5];
    let c3 = f[6] * x1 + f[7] * y1 + f[8];
    // Fᵀ x2
    let c = f[0] * x2 + f[3] * y2 + f[6];
    let d = f[1] * x2 + f[4] * y2 + f[7];
    [x2 * a + y2 * b + c3, a, b, c, d]
}

/// `(e, a² + b², c² + d²)` for one match (see [`epipolar_lines`]).
#[inline(always)]
fn epipolar_terms(f: &Matrix3<f64>, p1: [f64; 2], p2: [f64; 2]) -> (f64, f64, f64) {
    let [e, a, b, c, d] = epipolar_lines(f, p1[0], p1[1], p2[0], p2[1]);
    (e, a * a + b * b, c * c + d * d)
}

/// `(e, a² + b² + c² + d²)` for one match, the terms of the batch loops
/// (the gradient summed in that order, as both batch forms need it).
#[inline(always)]
fn batch_terms(f: &Matrix3<f64>, x1: f64, y1: f64, x2: f64, y2: f64) -> (f64, f64) {
    gradient_terms(epipolar_lines(f, x1, y1, x2, y2))
}

/// `(e, a² + b² + c² + d²)` from `[e, a, b, c, d]`, summed in that order.
#[inline(always)]
fn gradient_terms([e, a, b, c, d]: [f64; 5]) -> (f64, f64) {
    (e, a * a + b * b + c * c + d * d)
}

/// Squared Sampson distance (thesis Eq. 23), in px²:
/// `e² / (a² + b² + c² + d²)`.
///
/// Invariant to scaling and negating `F`. A match with a zero gradient
/// (`a = b = c = d = 0`, possible only for a degenerate `F`) is at distance 0
/// if `e = 0` and `+∞` otherwise.
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
    let (e, g1, g2) = epipolar_terms(&rescale_power_of_two(f), p1, p2);
    ratio(e, e * e, g1 + g2)
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
    let (e, g1, g2) = epipolar_terms(&rescale_power_of_two(f), p1, p2);
    ratio(e, e, (g1 + g2).sqrt())
}

/// Symmetric epipolar distance (thesis Eq. 24), in px²: the sum of the squared
/// distances of each point to the epipolar line of the other,
/// `e² (1 / (a² + b²) + 1 / (c² + d²))`.
#[inline]
pub fn symmetric_epipolar_distance(f: &Matrix3<f64>, p1: [f64; 2], p2: [f64; 2]) -> f64 {
    let (e, g1, g2) = epipolar_terms(&rescale_power_of_two(f), p1, p2);
    ratio(e, e * e * (1.0 / g1 + 1.0 / g2), 1.0)
}

dispatch! {
    /// Squared Sampson distances (Eq. 23) of every correspondence to one `F`,
    /// written into `out`: `out[i] = e_i² / (a_i² + b_i² + c_i² + d_i²)` in px².
    /// Only the first `min(out.len(), points.len())` slots are written.
    ///
    /// This is the hot loop of the preference matrix (Eq. 38): it allocates
    /// nothing, reads the four coordinate columns linearly and compiles to a
    /// branch-free, vectorised loop.
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
    pub fn sampson_distances_squared(f: &Matrix3<f64>, points: &Correspondences, out: &mut [f64])
        => distances_squared_kernel
}

/// The body of [`sampson_distances_squared`]: a compare-and-blend that
/// vectorises.
#[inline(always)]
fn distances_squared_kernel(f: &Matrix3<f64>, points: &Correspondences, out: &mut [f64]) {
    batch_map(f, points, out, |e, g| ratio(e, e * e, g));
}

/// `out[i] = value(e_i, a_i² + b_i² + c_i² + d_i²)` for the first
/// `min(out.len(), points.len())` correspondences, `F` rescaled first: the
/// loop of the batch forms, branch-free when `value` is.
#[inline(always)]
fn batch_map(
    f: &Matrix3<f64>,
    points: &Correspondences,
    out: &mut [f64],
    value: impl Fn(f64, f64) -> f64,
) {
    let f = rescale_power_of_two(f);
    let (x1, y1, x2, y2) = points.columns();
    let n = out.len().min(x1.len());
    let (x1, y1, x2, y2, out) = (&x1[..n], &y1[..n], &x2[..n], &y2[..n], &mut out[..n]);
    for i in 0..n {
        let (e, g) = batch_terms(&f, x1[i], y1[i], x2[i], y2[i]);
        out[i] = value(e, g);
    }
}

/// Many fundamental matrices, each rescaled once (by a power of two, as
/// for every distance here) and stored entry by entry, for the squared
/// Sampson distances of one match to all of them: the point-major form of
/// [`sampson_distances_squared`], equal to it bit for bit (the same
/// operations in the same order).
///
/// ```
/// use geometry::{sampson_distances_squared, Correspondences, SampsonModels};
/// use nalgebra::Matrix3;
/// let fs = [
///     Matrix3::new(0.0, 0.0, 0.0, 0.0, 0.0, -1.0, 0.0, 1.0, 0.0),
///     Matrix3::new(0.0, 0.0, 1.0, 0.0, 0.0, 0.0, -1.0, 0.0, 0.0),
/// ];
/// let c = Correspondences::new(&[[5.0, 1.0]], &[[9.0, 3.0]]).unwrap();
/// let mut row = [0.0; 2];
/// SampsonModels::new(&fs).distances_squared(c.point1(0), c.point2(0), &mut row);
/// let mut column = [0.0; 1];
/// sampson_distances_squared(&fs[1], &c, &mut column);
/// assert_eq!(row[1].to_bits(), column[0].to_bits());
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct SampsonModels {
    /// `entries[k][j]`: row-major entry k of model j, rescaled (one column
    /// per entry, so that a loop over the models reads each linearly).
    entries: [Vec<f64>; 9],
}

impl SampsonModels {
    /// The models `fs`, in that order.
    pub fn new(fs: &[Matrix3<f64>]) -> Self {
        let rows: Vec<[f64; 9]> = fs
            .iter()
            .map(|f| row_major(&rescale_power_of_two(f)))
            .collect();
        Self {
            entries: std::array::from_fn(|k| rows.iter().map(|row| row[k]).collect()),
        }
    }

    /// Number of models.
    pub fn len(&self) -> usize {
        self.entries[0].len()
    }

    /// Whether there are no models.
    pub fn is_empty(&self) -> bool {
        self.entries[0].is_empty()
    }

    /// `out[j]`: the squared Sampson distance (Eq. 23, px²) of the match
    /// `p1 ↔ p2` to model j, for the first `min(out.len(), len())` models.
    pub fn distances_squared(&self, p1: [f64; 2], p2: [f64; 2], out: &mut [f64]) {
        models_distances_squared(self, p1, p2, out);
    }
}

dispatch! {
    /// [`models_kernel`] in the build [`crate::simd::avx2`] chooses.
    fn models_distances_squared(models: &SampsonModels, p1: [f64; 2], p2: [f64; 2], out: &mut [f64])
        => models_kernel
}

/// The body of [`SampsonModels::distances_squared`].
#[inline(always)]
fn models_kernel(models: &SampsonModels, p1: [f64; 2], p2: [f64; 2], out: &mut [f64]) {
    let m = out.len().min(models.len());
    let e = models.entries.each_ref().map(|column| &column[..m]);
    for (j, r) in out[..m].iter_mut().enumerate() {
        let f = e.map(|column| column[j]);
        let (e, g) = gradient_terms(lines_of_entries(&f, p1[0], p1[1], p2[0], p2[1]));
        *r = ratio(e, e * e, g);
    }
}

dispatch! {
    /// The correspondences within `thr2` px² of `F` (squared Sampson distance,
    /// Eq. 23, computed exactly as [`sampson_distance_squared`]): their indices,
    /// increasing, written into `out` (cleared first). The consensus set of
    /// RANSAC-style hypothesis scoring.
    ///
    /// Gives up, returning `false`, once fewer than `at_least` correspondences
    /// can still be within the bound (tested every `CONSENSUS_BLOCK` matches;
    /// `out` then holds a partial set); `at_least = 0` never gives up. The
    /// answer and, when it is `true`, `out` do not depend on where it gave up.
    ///
    /// ```
    /// use geometry::{sampson_consensus, Correspondences};
    /// use nalgebra::Matrix3;
    /// let f = Matrix3::new(0.0, 0.0, 0.0, 0.0, 0.0, -1.0, 0.0, 1.0, 0.0);
    /// let c = Correspondences::new(&[[0.0, 0.0], [5.0, 1.0]], &[[3.0, 0.0], [9.0, 3.0]]).unwrap();
    /// let mut inliers = Vec::new();
    /// assert!(sampson_consensus(&f, &c, 1.0, 0, &mut inliers));
    /// assert_eq!(inliers, [0]);
    /// assert!(!sampson_consensus(&f, &c, 1.0, 2, &mut inliers));
    /// ```
    pub fn sampson_consensus(
        f: &Matrix3<f64>,
        points: &Correspondences,
        thr2: f64,
        at_least: usize,
        out: &mut Vec<usize>,
    ) -> bool => consensus_kernel
}

/// The body of [`sampson_consensus`].
#[inline(always)]
fn consensus_kernel(
    f: &Matrix3<f64>,
    points: &Correspondences,
    thr2: f64,
    at_least: usize,
    out: &mut Vec<usize>,
) -> bool {
    const B: usize = CONSENSUS_BLOCK;
    out.clear();
    let f = rescale_power_of_two(f);
    let (x1, y1, x2, y2) = points.columns();
    let n = points.len();
    // One allocation at most, instead of growing block by block.
    out.reserve(n);
    let blocks = x1[..n]
        .chunks(B)
        .zip(y1[..n].chunks(B))
        .zip(x2[..n].chunks(B).zip(y2[..n].chunks(B)));
    let mut d2 = [0.0; B];
    for (start, ((bx1, by1), (bx2, by2))) in (0..n).step_by(B).zip(blocks) {
        if out.len() + (n - start) < at_least {
            return false;
        }
        // Distances of the block (a branch-free loop that vectorises).
        let points = bx1.iter().zip(by1).zip(bx2.iter().zip(by2));
        for (d, ((&u1, &v1), (&u2, &v2))) in d2.iter_mut().zip(points) {
            let (e, g1, g2) = epipolar_terms(&f, [u1, v1], [u2, v2]);
            *d = ratio(e, e * e, g1 + g2);
        }
        // The block's matches within the bound as a bit mask, then their
        // indices from its set bits (a losing candidate has few).
        let mut mask = 0u64;
        for (k, d) in d2[..bx1.len()].iter().enumerate() {
            mask |= u64::from(*d <= thr2) << k;
        }
        while mask != 0 {
            out.push(start + mask.trailing_zeros() as usize);
            mask &= mask - 1;
        }
    }
    out.len() >= at_least
}

/// Matches per block of [`sampson_consensus`]: distances are computed a
/// block at a time, and the give-up test runs between blocks. At most 64
/// (the kernel marks a block's matches within the bound in a `u64`).
const CONSENSUS_BLOCK: usize = 32;
const _: () = assert!(CONSENSUS_BLOCK <= 64);

dispatch! {
    /// Signed Sampson residuals `r_i = e_i / sqrt(a_i² + b_i² + c_i² + d_i²)`
    /// (square root of Eq. 23, with the sign of `e_i`) of every correspondence to
    /// one `F`, written into `out`; `r_i²` is the squared Sampson distance.
    /// These are the residuals whose median and MAD give the IRLS scale (Eq. 34).
    /// Only the first `min(out.len(), points.len())` slots are written.
    ///
    /// ```
    /// use geometry::{sampson_residuals_signed, Correspondences};
    /// use nalgebra::Matrix3;
    /// let f = Matrix3::new(0.0, 0.0, 0.0, 0.0, 0.0, -1.0, 0.0, 1.0, 0.0);
    /// let c = Correspondences::new(&[[5.0, 1.0], [5.0, 1.0]], &[[9.0, 3.0], [9.0, -1.0]]).unwrap();
    /// let mut r = vec![0.0; 2];
    /// sampson_residuals_signed(&f, &c, &mut r);
    /// assert!((r[0] + r[1]).abs() < 1e-12 && (r[0].abs() - 2f64.sqrt()).abs() < 1e-12);
    /// ```
    pub fn sampson_residuals_signed(f: &Matrix3<f64>, points: &Correspondences, out: &mut [f64])
        => residuals_signed_kernel
}

/// The body of [`sampson_residuals_signed`].
#[inline(always)]
fn residuals_signed_kernel(f: &Matrix3<f64>, points: &Correspondences, out: &mut [f64]) {
    batch_map(f, points, out, |e, g| ratio(e, e, g.sqrt()));
}

/// Signed Sampson residuals of the correspondences listed in `indices`
/// (all in range), `out[k] = r_{indices[k]}`; `out.len() == indices.len()`.
pub(crate) fn sampson_residuals_signed_at(
    f: &Matrix3<f64>,
    points: &Correspondences,
    indices: &[usize],
    out: &mut [f64],
) {
    let f = rescale_power_of_two(f);
    for (r, &i) in out.iter_mut().zip(indices) {
        let (e, g1, g2) = epipolar_terms(&f, points.point1(i), points.point2(i));
        *r = ratio(e, e, (g1 + g2).sqrt());
    }
}

/// FROB distance between two fundamental matrices (thesis Eq. 45):
/// `min(‖Fa/‖Fa‖ − Fb/‖Fb‖‖, ‖Fa/‖Fa‖ + Fb/‖Fb‖‖)` with Frobenius norms, so
/// that the scale and sign ambiguity of `F` does not count. In `[0, √2]`;
/// NaN when either matrix is zero or not finite.
///
/// ```
/// use geometry::frob_distance;
/// use nalgebra::Matrix3;
/// let f = Matrix3::new(1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 0.0);
/// assert!(frob_distance(&f, &(-3.0 * f)) < 1e-15);
/// ```
pub fn frob_distance(fa: &Matrix3<f64>, fb: &Matrix3<f64>) -> f64 {
    // Exact rescaling first, so that ‖F‖ neither overflows nor underflows.
    let (fa, fb) = (rescale_power_of_two(fa), rescale_power_of_two(fb));
    let a = fa / fa.norm();
    let b = fb / fb.norm();
    (a - b).norm().min((a + b).norm())
}
