//! Distances between preference vectors: Tanimoto (Eq. 39) and Jaccard.
//!
//! # Arithmetic
//! Every implementation in this crate (the min-heap clustering and the plain
//! reference) computes the inner products and squared norms of Eq. 39 in f64,
//! as `s = 0; for j in 0..M { s = s + p_j · q_j }` — products rounded, then
//! added in hypothesis order, no fused multiply-add. Skipping a term whose
//! product is exactly zero does not change `s` (all terms are `≥ +0`), so
//! the sparse sums over common hypotheses of [`crate::t_linkage`] give
//! bit-identical distances; its faster approximate arithmetic only produces
//! certified lower bounds, which decide which exact distances to compute,
//! never their values. This is what makes the labels of the fast
//! implementation exactly those of the specified algorithm.

/// Below this denominator `|p|² + |q|² − <p, q>` the Tanimoto distance is 1.
///
/// Since `|p|² + |q|² − <p, q> ≥ (|p|² + |q|²) / 2`, the denominator is this
/// small only when both vectors are (almost) zero: a point with no preference
/// shares nothing with anything. With Eq. 38 every non-zero preference is
/// `≥ exp(−5)`, so a non-zero vector has `|p|² ≥ exp(−10) ≈ 4.5e-5`, far above.
pub const TANIMOTO_MIN_DENOMINATOR: f64 = 1e-15;

/// Tanimoto distance (Eq. 39) from the inner product `dot = <p, q>` and the
/// squared norms `norm_p = |p|²`, `norm_q = |q|²`:
/// `d = 1 − <p, q> / (|p|² + |q|² − <p, q>)`, and `d = 1` when the
/// denominator is `≤` [`TANIMOTO_MIN_DENOMINATOR`]. Clamped below at 0 (for
/// non-negative vectors `d ∈ [0, 1]`; rounding could otherwise give `−ε`).
///
/// ```
/// use clustering::tanimoto_distance;
/// assert_eq!(tanimoto_distance(1.0, 1.0, 1.0), 0.0); // identical
/// assert_eq!(tanimoto_distance(0.0, 1.0, 2.0), 1.0); // disjoint supports
/// assert_eq!(tanimoto_distance(0.0, 0.0, 0.0), 1.0); // two zero vectors
/// assert_eq!(tanimoto_distance(0.5, 1.0, 0.5), 0.5);
/// ```
#[inline]
pub fn tanimoto_distance(dot: f64, norm_p: f64, norm_q: f64) -> f64 {
    let denominator = norm_p + norm_q - dot;
    if denominator <= TANIMOTO_MIN_DENOMINATOR {
        return 1.0;
    }
    let d = 1.0 - dot / denominator;
    if d < 0.0 {
        0.0
    } else {
        d
    }
}

/// A lower bound of [`tanimoto_distance`]`(dot, norm_p, norm_q)` from an
/// upper bound `dot_upper ≥ dot` of the inner product computed by the same
/// ordered f64 sum, with the same norms.
///
/// Every floating-point step of Eq. 39 is monotone in `dot` (the
/// denominator `(|p|² + |q|²) − dot` falls, the ratio rises, `1 − ratio`
/// falls), so evaluating it at the larger `dot_upper` cannot give more. When
/// the denominator at `dot_upper` is at or below the cut-off the bound is 0
/// (the exact value may use either branch).
pub(crate) fn tanimoto_lower_bound(dot_upper: f64, norm_p: f64, norm_q: f64) -> f64 {
    if norm_p + norm_q - dot_upper <= TANIMOTO_MIN_DENOMINATOR {
        0.0
    } else {
        tanimoto_distance(dot_upper, norm_p, norm_q)
    }
}

/// `Σ_j p_j · q_j` summed in hypothesis order (see the module docs).
///
/// ```
/// assert_eq!(clustering::ordered_dot(&[1.0, 2.0], &[3.0, 0.5]), 4.0);
/// ```
pub fn ordered_dot(p: &[f64], q: &[f64]) -> f64 {
    let mut sum = 0.0;
    for (a, b) in p.iter().zip(q) {
        sum += a * b;
    }
    sum
}

/// Tanimoto distance (Eq. 39) between two dense preference vectors, every
/// sum in hypothesis order: the plain definition the fast kernels reproduce.
///
/// ```
/// use clustering::tanimoto_distance_dense;
/// let p = [1.0, 0.5, 0.0];
/// assert_eq!(tanimoto_distance_dense(&p, &p), 0.0);
/// assert_eq!(tanimoto_distance_dense(&p, &[0.0, 0.0, 1.0]), 1.0);
/// ```
pub fn tanimoto_distance_dense(p: &[f64], q: &[f64]) -> f64 {
    tanimoto_distance(ordered_dot(p, q), ordered_dot(p, p), ordered_dot(q, q))
}

/// Jaccard distance of J-Linkage from the set sizes:
/// `d = 1 − |A ∩ B| / |A ∪ B|`, and `d = 1` when the union is empty.
///
/// ```
/// use clustering::jaccard_distance;
/// assert_eq!(jaccard_distance(2, 4), 0.5);
/// assert_eq!(jaccard_distance(0, 0), 1.0);
/// ```
#[inline]
pub fn jaccard_distance(intersection: u64, union: u64) -> f64 {
    if union == 0 {
        1.0
    } else {
        1.0 - intersection as f64 / union as f64
    }
}
