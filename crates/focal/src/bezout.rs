//! The real solutions of two bivariate quartics `P = Q = 0` from the roots
//! of their resultant, and the one a robust focal step takes (docs/method.md
//! step 4: the smallest `|l1| + |l2|`): the common root t1 from the null
//! vector of the Bezout matrix at each near-real root t2 (or the real roots
//! of the first quartic), Newton's polish on the 2x2 system, and the
//! selection with its early stop.

use nalgebra::Complex;

use crate::aberth::{aberth_roots, MAX_DEGREE};
use crate::bivariate::Quartic2;
use crate::resultant::resultant_in_t2;
use crate::simd::Simd;

type C64 = Complex<f64>;

/// Resultant roots closer than this (relative to `1 + |t2|`) count as a
/// cluster, whose common roots t1 [`min_l1_real_solution`] finds from the
/// real roots of the first quartic rather than from a null vector.
const ISOLATION: f64 = 1e-1;

/// The smallest diagonal cofactor, relative to the cube of the largest
/// Bezout matrix entry, at which [`bezout_null_t1`] trusts the null vector.
const NULL_VECTOR_TOLERANCE: f64 = 1e-6;

/// The common root t1 of `P(., t2)` and `Q(., t2)` from the null vector
/// `(1, t1, t1^2, t1^3)` of their real 4x4 Bezout matrix at `t2` (a column
/// of its adjugate, the one of the largest diagonal cofactor). `None` when
/// that cofactor is below [`NULL_VECTOR_TOLERANCE`] (no simple common root:
/// two common roots, or a near-double root of the resultant) or the ratio is
/// not finite.
// The symmetric matrix is filled by index pairs (i, j), j >= i.
#[allow(clippy::needless_range_loop)]
#[inline(always)]
fn bezout_null_t1(p: &Quartic2, q: &Quartic2, t2: f64) -> Option<f64> {
    let a = p.coefs_in_t1(t2);
    let b = q.coefs_in_t1(t2);
    let mut m = [[0.0; 4]; 4];
    for i in 0..4usize {
        for j in i..4usize {
            let lo = (i + j + 1).saturating_sub(4);
            let mut s = 0.0;
            for qq in lo..=i {
                let pp = i + j + 1 - qq;
                s += a[pp] * b[qq] - a[qq] * b[pp];
            }
            m[i][j] = s;
            m[j][i] = s;
        }
    }
    // Cofactor C_ik: signed determinant of m without row i and column k.
    let cofactor = |i: usize, k: usize| -> f64 {
        let mut r = [0usize; 3];
        let mut c = [0usize; 3];
        let (mut nr, mut nc) = (0, 0);
        for x in 0..4 {
            if x != i {
                r[nr] = x;
                nr += 1;
            }
            if x != k {
                c[nc] = x;
                nc += 1;
            }
        }
        let e = |u: usize, v: usize| m[r[u]][c[v]];
        let det = e(0, 0) * (e(1, 1) * e(2, 2) - e(1, 2) * e(2, 1))
            - e(0, 1) * (e(1, 0) * e(2, 2) - e(1, 2) * e(2, 0))
            + e(0, 2) * (e(1, 0) * e(2, 1) - e(1, 1) * e(2, 0));
        if (i + k) % 2 == 0 {
            det
        } else {
            -det
        }
    };
    let diagonal = [0, 1, 2, 3].map(|x| cofactor(x, x).abs());
    let k = (0..4)
        .max_by(|&x, &y| diagonal[x].total_cmp(&diagonal[y]))
        .unwrap_or(0);
    // A rank-deficient adjugate (two common roots, or a near-double root
    // of the resultant) does not determine t1.
    let size = m.iter().flatten().fold(0.0_f64, |acc, v| acc.max(v.abs()));
    if diagonal[k].is_nan() || diagonal[k] <= NULL_VECTOR_TOLERANCE * size * size * size {
        return None;
    }
    let v = [0, 1, 2, 3].map(|i| cofactor(i, k));
    let t1 = if v[0].abs() >= v[3].abs() {
        v[1] / v[0]
    } else {
        v[3] / v[2]
    };
    t1.is_finite().then_some(t1)
}

/// A real solution (t1, t2) of `P = Q = 0`.
pub(crate) type Solution = [f64; 2];

/// Newton's method on the 2x2 system `P = Q = 0` from `t`. Returns the
/// polished point when it converged to a real solution: both residuals below
/// `1e-10` times their magnitude bound `sum |c_ij| |t1|^i |t2|^j`.
#[inline(always)]
pub(crate) fn polish(p: &Quartic2, q: &Quartic2, mut t: [f64; 2]) -> Option<Solution> {
    for _ in 0..12 {
        let (pv, p1, p2, pm) = p.eval_with_grad(t[0], t[1]);
        let (qv, q1, q2, qm) = q.eval_with_grad(t[0], t[1]);
        if pv.abs() <= 1e-15 * pm && qv.abs() <= 1e-15 * qm {
            break;
        }
        let det = p1 * q2 - p2 * q1;
        if det == 0.0 || !det.is_finite() {
            break;
        }
        let d1 = (pv * q2 - p2 * qv) / det;
        let d2 = (p1 * qv - pv * q1) / det;
        t[0] -= d1;
        t[1] -= d2;
        if !(t[0].is_finite() && t[1].is_finite()) {
            return None;
        }
        let size = 1.0 + t[0].abs() + t[1].abs();
        if d1.abs() + d2.abs() <= 1e-14 * size {
            break;
        }
    }
    let (pv, _, _, pm) = p.eval_with_grad(t[0], t[1]);
    let (qv, _, _, qm) = q.eval_with_grad(t[0], t[1]);
    if pv.abs() <= 1e-10 * pm && qv.abs() <= 1e-10 * qm {
        Some(t)
    } else {
        None
    }
}

/// Roots of the previous resultant, reused as the starting point of the
/// next root-finding (see [`min_l1_real_solution`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct RootCache {
    roots: [C64; MAX_DEGREE],
    len: usize,
}

impl Default for RootCache {
    fn default() -> Self {
        Self {
            roots: [C64::new(0.0, 0.0); MAX_DEGREE],
            len: 0,
        }
    }
}

/// The real solution `t` of `P(t1, t2) = Q(t1, t2) = 0` minimising
/// `|(M t)_1| + |(M t)_2|` for the 2x2 matrix `m` (row-major), or `None`
/// when no real solution is found.
///
/// Method: hidden-variable elimination of t1 (the Bezout resultant, a
/// polynomial of degree <= 16 in t2), all its complex roots by
/// Aberth–Ehrlich (started from `cache`, the roots of the previous call,
/// when it has the right degree; the new roots are stored back), and for
/// every root close to the real axis the common root t1 of `P(., t2)` and
/// `Q(., t2)` from the null vector of their Bezout matrix
/// ([`bezout_null_t1`]), or when that does not polish to a solution, the
/// real roots t1 of `P(., t2)` at which `Q` nearly vanishes; each pair is
/// polished by Newton's method on the 2x2 system and kept only when it
/// solves both equations. Candidates are
/// visited in increasing `|t2|`; since `|Mt|_1 >= sigma_min(M) |t|_2 >=
/// sigma_min(M) |t2|`, the search stops once no remaining candidate can
/// improve on the best.
#[inline(always)]
pub(crate) fn min_l1_real_solution(
    p: &Quartic2,
    q: &Quartic2,
    m: [[f64; 2]; 2],
    cache: &mut RootCache,
    simd: Simd,
) -> Option<Solution> {
    let nr = resultant_roots(p, q, cache, simd)?;
    let (cand, nc) = real_root_candidates(&cache.roots[..nr]);
    let sigma_min = smallest_singular_value(m);
    let objective = |s: &Solution| {
        (m[0][0] * s[0] + m[0][1] * s[1]).abs() + (m[1][0] * s[0] + m[1][1] * s[1]).abs()
    };
    let mut best: Option<(f64, Solution)> = None;
    for &RootCandidate { t2, isolated } in &cand[..nc] {
        if let Some((b, _)) = best {
            if sigma_min * t2.abs() > 1.01 * b {
                break;
            }
        }
        // At an isolated root, the common root from the Bezout matrix's null
        // vector, when it polishes to a solution; else every real root of
        // P(., t2).
        if let Some(s) = isolated
            .then(|| bezout_null_t1(p, q, t2))
            .flatten()
            .and_then(|t1| polish(p, q, [t1, t2]))
        {
            keep_better(&mut best, objective(&s), s);
            continue;
        }
        let (picked, np) = real_t1_candidates(p, q, t2, simd);
        let min_rel = picked[..np].iter().fold(f64::INFINITY, |a, c| a.min(c.rel));
        for c in &picked[..np] {
            if c.rel > 1e-3 && c.rel > min_rel {
                continue;
            }
            if let Some(s) = polish(p, q, [c.t1, t2]) {
                keep_better(&mut best, objective(&s), s);
            }
        }
    }
    best.map(|(_, s)| s)
}

/// The roots of the resultant of P and Q in t2, by Aberth–Ehrlich warm-
/// started from `cache` and stored back into it; returns their number, or
/// `None` when the resultant vanishes or is not finite.
#[inline(always)]
fn resultant_roots(p: &Quartic2, q: &Quartic2, cache: &mut RootCache, simd: Simd) -> Option<usize> {
    let res = resultant_in_t2(simd, p, q);
    let scale = res.iter().fold(0.0_f64, |acc, c| acc.max(c.abs()));
    if !(scale.is_finite() && scale > 1e-300) {
        return None;
    }
    // Drop leading coefficients that are negligible: they only create roots
    // near infinity.
    let mut n = res.len();
    while n > 1 && res[n - 1].abs() <= 1e-14 * scale {
        n -= 1;
    }
    let mut roots = [C64::new(0.0, 0.0); MAX_DEGREE];
    let warm = (cache.len > 0).then(|| &cache.roots[..cache.len]);
    let nr = aberth_roots(&res[..n], &mut roots, warm, simd);
    cache.roots = roots;
    cache.len = nr;
    Some(nr)
}

/// A root t2 of the resultant near the real axis.
#[derive(Clone, Copy)]
struct RootCandidate {
    /// Its real part.
    t2: f64,
    /// No other root lies within [`ISOLATION`] of it, so that one common
    /// root t1 belongs to it.
    isolated: bool,
}

/// The roots near the real axis, by increasing `|t2|` (the first `n`
/// entries), and `n`.
#[inline(always)]
fn real_root_candidates(roots: &[C64]) -> ([RootCandidate; MAX_DEGREE], usize) {
    let none = RootCandidate {
        t2: 0.0,
        isolated: false,
    };
    let mut cand = [none; MAX_DEGREE];
    let mut nc = 0;
    for (i, z) in roots.iter().enumerate() {
        if z.im.abs() <= 1e-2 * (1.0 + z.re.abs()) {
            let reach = ISOLATION * (1.0 + z.norm_sqr().sqrt());
            let isolated = roots
                .iter()
                .enumerate()
                .all(|(j, w)| j == i || (z - w).norm_sqr() > reach * reach);
            cand[nc] = RootCandidate { t2: z.re, isolated };
            nc += 1;
        }
    }
    cand[..nc].sort_by(|a, b| a.t2.abs().total_cmp(&b.t2.abs()));
    (cand, nc)
}

/// A real root t1 of one quartic at t2, with the relative size of the
/// other quartic there (at a common root, at the level of the error of t2).
#[derive(Clone, Copy)]
struct T1Candidate {
    t1: f64,
    rel: f64,
}

/// Up to four real roots t1 of `P(., t2)` (of `Q(., t2)` when P vanishes
/// identically there), each with the other polynomial's relative size.
#[inline(always)]
fn real_t1_candidates(
    p: &Quartic2,
    q: &Quartic2,
    t2: f64,
    simd: Simd,
) -> ([T1Candidate; 4], usize) {
    let (first, other) = if p.coefs_in_t1(t2).iter().any(|&c| c != 0.0) {
        (p, q)
    } else {
        (q, p)
    };
    let mut t1_roots = [C64::new(0.0, 0.0); MAX_DEGREE];
    let k = aberth_roots(&first.coefs_in_t1(t2), &mut t1_roots, None, simd);
    let none = T1Candidate {
        t1: 0.0,
        rel: f64::INFINITY,
    };
    let mut picked = [none; 4];
    let mut np = 0;
    for z in t1_roots.iter().take(k) {
        if z.im.abs() > 1e-2 * (1.0 + z.re.abs()) || np == picked.len() {
            continue;
        }
        let (v, _, _, mag) = other.eval_with_grad(z.re, t2);
        let rel = if mag > 0.0 { v.abs() / mag } else { 0.0 };
        picked[np] = T1Candidate { t1: z.re, rel };
        np += 1;
    }
    (picked, np)
}

/// Replaces `best` by `(norm, s)` when there is none yet or `norm` is
/// strictly smaller (so the first of equal candidates stays).
fn keep_better(best: &mut Option<(f64, Solution)>, norm: f64, s: Solution) {
    if best.map_or(true, |(b, _)| norm < b) {
        *best = Some((norm, s));
    }
}

/// The smallest singular value of a 2x2 matrix.
fn smallest_singular_value(m: [[f64; 2]; 2]) -> f64 {
    let (a, b, c, d) = (m[0][0], m[0][1], m[1][0], m[1][1]);
    let s1 = (a + d).hypot(c - b);
    let s2 = (a - d).hypot(c + b);
    0.5 * (s1 - s2).abs()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bivariate::Quad2;
    use crate::test_support::{intersection, lin, product_of_lines, LINES_P, LINES_Q};

    #[test]
    fn finds_the_smallest_of_sixteen_real_solutions() {
        let (lp, lq) = (LINES_P, LINES_Q);
        let p = product_of_lines(&lp);
        let q = product_of_lines(&lq);
        let mut cache = RootCache::default();
        for m in [
            [[1.0, 0.0], [0.0, 1.0]],
            [[1.0, 0.0], [0.0, 10.0]],
            [[7.0, 0.0], [0.0, 0.5]],
            [[1.0, 0.7], [-0.2, 1.5]],
            [[0.3, -2.0], [1.0, 1.0]],
        ] {
            // Naive reference: all 16 intersections, minimum |M t|_1.
            let norm = |t: [f64; 2]| {
                (m[0][0] * t[0] + m[0][1] * t[1]).abs() + (m[1][0] * t[0] + m[1][1] * t[1]).abs()
            };
            let mut best = (f64::INFINITY, [0.0; 2]);
            for a in &lp {
                for b in &lq {
                    let [t1, t2] = intersection(a, b);
                    if norm([t1, t2]) < best.0 {
                        best = (norm([t1, t2]), [t1, t2]);
                    }
                }
            }
            // Cold start, and warm start from the previous call's roots.
            for cache in [&mut RootCache::default(), &mut cache] {
                let s = min_l1_real_solution(&p, &q, m, cache, Simd::detect()).expect("a solution");
                assert!(
                    (s[0] - best.1[0]).abs() < 1e-9 && (s[1] - best.1[1]).abs() < 1e-9,
                    "M = {m:?}: got {s:?}, want {:?}",
                    best.1
                );
            }
        }
    }

    /// At the t2 of each of the 16 intersections of two sets of four lines,
    /// the Bezout null vector gives the intersection's t1.
    #[test]
    fn bezout_null_vector_recovers_the_common_root() {
        let p = product_of_lines(&LINES_P);
        let q = product_of_lines(&LINES_Q);
        let mut recovered = 0;
        for a in &LINES_P {
            for b in &LINES_Q {
                let [t1, t2] = intersection(a, b);
                if let Some(got) = bezout_null_t1(&p, &q, t2) {
                    assert!((got - t1).abs() <= 1e-9 * (1.0 + t1.abs()), "{got} vs {t1}");
                    recovered += 1;
                }
            }
        }
        // All 16 have distinct t2, so each is a simple common root.
        assert_eq!(recovered, 16);
        // P = Q: every root is common, the adjugate vanishes.
        assert_eq!(bezout_null_t1(&p, &p, 0.3), None);
    }

    #[test]
    fn no_real_solution_is_reported_as_none() {
        // P = (t1^2 + t2^2 + 1)(t1^2 + 2 t2^2 + 0.5) > 0 everywhere.
        let c1 = Quad2([[1.0, 0.0, 1.0], [0.0, 0.0, 0.0], [1.0, 0.0, 0.0]]);
        let c2 = Quad2([[0.5, 0.0, 2.0], [0.0, 0.0, 0.0], [1.0, 0.0, 0.0]]);
        let p = c1.mul(&c2);
        let q = lin(0.2, 1.0, -1.0)
            .mul(&lin(1.0, 0.3, 0.1))
            .mul(&lin(-0.4, 0.2, 1.0).mul(&lin(0.3, -1.0, 0.5)));
        // The resultant is not identically zero: the system is generic.
        let res = resultant_in_t2(Simd::detect(), &p, &q);
        assert!(res.iter().any(|c| c.abs() > 1e-6));
        assert!(min_l1_real_solution(
            &p,
            &q,
            [[1.0, 0.0], [0.0, 1.0]],
            &mut RootCache::default(),
            Simd::detect()
        )
        .is_none());
    }
}
