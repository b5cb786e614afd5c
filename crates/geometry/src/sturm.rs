//! Real roots of a univariate polynomial without an eigen-decomposition:
//! a Sturm sequence counts the distinct real roots in an interval (Sturm's
//! theorem, e.g. Basu, Pollack & Roy, "Algorithms in Real Algebraic
//! Geometry", Thm. 2.50), bisection isolates them inside Fujiwara's root
//! bound, and a bracketed Newton iteration (bisection as safeguard)
//! converges on each isolated root. Fixed-size arrays, no allocation.

use crate::simd::dispatch;

/// Largest degree handled (the 5-point solver's `det B(z)`); the
/// sequence and the roots live in arrays of this size.
pub(crate) const MAX_DEGREE: usize = 10;

/// Bisection depth at which a sub-interval that still holds several roots
/// (a cluster below `2⁻⁶⁴` of the root bound) gives up and reports its
/// midpoint once.
const MAX_DEPTH: usize = 64;

/// Iteration cap of the bracketed Newton solve of one isolated root.
const MAX_NEWTON: usize = 100;

/// Up to [`MAX_DEGREE`] real roots in ascending order.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Roots {
    values: [f64; MAX_DEGREE],
    len: usize,
}

impl Roots {
    /// The roots found, ascending.
    pub fn as_slice(&self) -> &[f64] {
        &self.values[..self.len]
    }

    fn push(&mut self, t: f64) {
        if self.len < MAX_DEGREE {
            self.values[self.len] = t;
            self.len += 1;
        }
    }
}

/// A polynomial `Σ c_k tᵏ` of degree `degree` (`c[degree] ≠ 0`, and
/// `c[k] = 0` above it).
#[derive(Debug, Clone, Copy)]
struct Poly {
    c: [f64; MAX_DEGREE + 1],
    degree: usize,
}

impl Poly {
    /// The value at `t` (Horner). The loop runs over all
    /// `MAX_DEGREE + 1` coefficients (a fixed count, unrolled): the zeros
    /// above the degree keep the value at (signed) zero, and
    /// `±0 · t + c = c` exactly, so the bits are those of Horner's rule
    /// from the leading coefficient.
    fn eval(&self, t: f64) -> f64 {
        self.c.iter().rev().fold(0.0, |acc, &c| acc * t + c)
    }

    /// The value and the derivative at `t` (Horner; all coefficients, as
    /// in [`Poly::eval`]).
    fn eval_with_derivative(&self, t: f64) -> (f64, f64) {
        self.c
            .iter()
            .rev()
            .fold((0.0, 0.0), |(p, dp), &c| (p * t + c, dp * t + p))
    }

    /// `self` divided by `|leading coefficient|` (signs kept).
    fn normalised(mut self) -> Self {
        let lead = self.c[self.degree].abs();
        self.c[..=self.degree].iter_mut().for_each(|c| *c /= lead);
        self
    }
}

/// Lanes of [`Sturm::table`]: the at most `MAX_DEGREE + 1` polynomials of
/// a sequence, padded to a multiple of four.
const LANES: usize = (MAX_DEGREE + 1).div_ceil(4) * 4;

/// The Sturm sequence `p₀ = p, p₁ = p', p_{k+1} = −rem(p_{k−1}, p_k)`, each
/// scaled to a leading coefficient of magnitude 1.
struct Sturm {
    /// Coefficient-major: `table[k][i]` is the coefficient of `tᵏ` in
    /// `p_i`, zero above its degree and in the lanes past `len`, so that
    /// one Horner loop evaluates the whole sequence lane by lane.
    table: [[f64; LANES]; MAX_DEGREE + 1],
    len: usize,
}

impl Sturm {
    fn new(p: Poly) -> Option<Self> {
        let mut seq = [p; MAX_DEGREE + 1];
        let mut derivative = Poly {
            c: [0.0; MAX_DEGREE + 1],
            degree: p.degree - 1,
        };
        for k in 1..=p.degree {
            derivative.c[k - 1] = k as f64 * p.c[k];
        }
        seq[0] = p.normalised();
        seq[1] = derivative.normalised();
        let mut len = 2;
        while seq[len - 1].degree > 0 {
            let Some(r) = remainder(&seq[len - 2], &seq[len - 1]) else {
                break;
            };
            let mut next = r.normalised();
            next.c[..=next.degree].iter_mut().for_each(|c| *c = -*c);
            if !next.c[..=next.degree].iter().all(|c| c.is_finite()) {
                return None;
            }
            seq[len] = next;
            len += 1;
        }
        let mut table = [[0.0; LANES]; MAX_DEGREE + 1];
        for (i, p) in seq[..len].iter().enumerate() {
            for (k, &c) in p.c[..=p.degree].iter().enumerate() {
                table[k][i] = c;
            }
        }
        Some(Self { table, len })
    }

    /// Sign changes of the sequence at `t` (zeros skipped).
    fn variations(&self, t: f64) -> usize {
        count_changes(self.values(t)[..self.len].iter().copied())
    }

    /// `p_i(t)` in lane `i`: Horner's rule in every lane from degree
    /// `MAX_DEGREE` down. The zero coefficients above a polynomial's degree
    /// leave its lane at (signed) zero until its leading coefficient, and
    /// `±0 · t + c = c` exactly, so each value has the bits of
    /// [`Poly::eval`].
    fn values(&self, t: f64) -> [f64; LANES] {
        sequence_values(&self.table, t)
    }
}

dispatch! {
    /// The body of [`Sturm::values`] (four lanes per instruction in the
    /// AVX2 build).
    fn sequence_values(table: &[[f64; LANES]; MAX_DEGREE + 1], t: f64) -> [f64; LANES]
        => sequence_values_kernel
}

#[inline(always)]
fn sequence_values_kernel(table: &[[f64; LANES]; MAX_DEGREE + 1], t: f64) -> [f64; LANES] {
    let mut values = [0.0; LANES];
    for row in table.iter().rev() {
        for (v, &c) in values.iter_mut().zip(row) {
            *v = *v * t + c;
        }
    }
    values
}

/// Sign changes along `values`, zeros skipped (without a branch: a zero
/// neither counts against the last non-zero value nor replaces it).
fn count_changes(values: impl Iterator<Item = f64>) -> usize {
    let mut last = 0.0;
    let mut changes = 0;
    for v in values {
        changes += usize::from(last * v < 0.0);
        last = if v != 0.0 { v } else { last };
    }
    changes
}

/// The remainder of `a / b` (`deg a ≥ deg b`), trimmed of exactly zero
/// leading coefficients; `None` when it is identically zero (`b` divides
/// `a`: the sequence ends with their gcd).
fn remainder(a: &Poly, b: &Poly) -> Option<Poly> {
    let mut r = *a;
    let lead = b.c[b.degree];
    for shift in (0..=a.degree - b.degree).rev() {
        let q = r.c[shift + b.degree] / lead;
        for k in 0..=b.degree {
            r.c[shift + k] -= q * b.c[k];
        }
        r.c[shift + b.degree] = 0.0;
    }
    let degree = (0..b.degree).rev().find(|&k| r.c[k] != 0.0)?;
    r.degree = degree;
    Some(r)
}

/// Fujiwara's bound `2 max_k |c_{n−k} / c_n|^{1/k}` on the magnitude of
/// every root.
fn root_bound(p: &Poly) -> f64 {
    let n = p.degree;
    let lead = p.c[n];
    (1..=n)
        .map(|k| {
            let c = (p.c[n - k] / lead).abs();
            let c = if k == n { c / 2.0 } else { c };
            c.powf(1.0 / k as f64)
        })
        .fold(0.0, f64::max)
        * 2.0
}

/// The distinct real roots of `Σ c_k tᵏ` (`coeffs[k] = c_k`, at most
/// [`MAX_DEGREE`] + 1 of them; trailing exact zeros are dropped), ascending.
/// A cluster of roots closer than `2⁻⁶⁴` times the root bound is reported
/// once. `None` when a coefficient is not finite, all are zero, or the
/// sequence overflows.
pub(crate) fn sturm_roots(coeffs: &[f64]) -> Option<Roots> {
    if coeffs.len() > MAX_DEGREE + 1 || !coeffs.iter().all(|c| c.is_finite()) {
        return None;
    }
    let degree = coeffs.iter().rposition(|&c| c != 0.0)?;
    let mut roots = Roots {
        values: [0.0; MAX_DEGREE],
        len: 0,
    };
    if degree == 0 {
        return Some(roots);
    }
    let mut p = Poly {
        c: [0.0; MAX_DEGREE + 1],
        degree,
    };
    p.c[..=degree].copy_from_slice(&coeffs[..=degree]);
    let p = p.normalised();
    let sturm = Sturm::new(p)?;
    let bound = root_bound(&p);
    if !bound.is_finite() {
        return None;
    }
    // Roots lie in (−bound, bound); the interval is widened slightly so
    // that none sits on an end point.
    let (lo, hi) = (-1.01 * bound - 1e-300, 1.01 * bound + 1e-300);
    let ends = (sturm.variations(lo), sturm.variations(hi));
    isolate(&p, &sturm, (lo, hi), ends, 0, &mut roots);
    Some(roots)
}

/// The distinct real roots of `p` in `(a, b)`, where its Sturm sequence
/// has `va` and `vb` sign changes, pushed onto `roots` in ascending order:
/// bracketed Newton on an interval with one root and a sign change,
/// bisection (left half first) otherwise, the midpoint once at
/// [`MAX_DEPTH`] or when the interval can no longer be halved.
fn isolate(
    p: &Poly,
    sturm: &Sturm,
    (a, b): (f64, f64),
    (va, vb): (usize, usize),
    depth: usize,
    roots: &mut Roots,
) {
    let count = va.saturating_sub(vb);
    if count == 0 {
        return;
    }
    if count == 1 {
        let (pa, pb) = (p.eval(a), p.eval(b));
        if pa * pb < 0.0 {
            roots.push(bracketed_newton(p, a, b, pa));
            return;
        }
    }
    let mid = 0.5 * (a + b);
    if depth >= MAX_DEPTH || mid <= a || mid >= b {
        roots.push(mid);
        return;
    }
    let vm = sturm.variations(mid);
    isolate(p, sturm, (a, mid), (va, vm), depth + 1, roots);
    isolate(p, sturm, (mid, b), (vm, vb), depth + 1, roots);
}

/// The root of `p` in `(a, b)` with `p(a) p(b) < 0` (`pa = p(a)`): Newton
/// steps that stay inside the shrinking bracket, bisection otherwise, until
/// the step or the bracket is at rounding level.
fn bracketed_newton(p: &Poly, mut a: f64, mut b: f64, pa: f64) -> f64 {
    let negative_at_a = pa < 0.0;
    let mut t = 0.5 * (a + b);
    for _ in 0..MAX_NEWTON {
        let (v, dv) = p.eval_with_derivative(t);
        if v == 0.0 {
            return t;
        }
        if (v < 0.0) == negative_at_a {
            a = t;
        } else {
            b = t;
        }
        let newton = t - v / dv;
        let next = if newton > a && newton < b && newton.is_finite() {
            newton
        } else {
            0.5 * (a + b)
        };
        let step = (next - t).abs();
        t = next;
        if step <= 2.0 * f64::EPSILON * t.abs() || b - a <= 2.0 * f64::EPSILON * t.abs() {
            break;
        }
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Ascending coefficients of `Π (t − r_i)`.
    fn from_roots(roots: &[f64]) -> Vec<f64> {
        let mut c = vec![1.0];
        for &r in roots {
            let mut next = vec![0.0; c.len() + 1];
            for (k, &v) in c.iter().enumerate() {
                next[k + 1] += v;
                next[k] -= r * v;
            }
            c = next;
        }
        c
    }

    #[test]
    fn recovers_ten_well_separated_roots() {
        let want = [-7.5, -3.0, -1.2, -0.4, 0.05, 0.3, 1.1, 2.5, 4.0, 9.0];
        let coeffs: Vec<f64> = from_roots(&want).iter().map(|c| c * 3.7).collect();
        let got = sturm_roots(&coeffs).unwrap();
        assert_eq!(got.as_slice().len(), want.len());
        for (g, w) in got.as_slice().iter().zip(want) {
            assert!((g - w).abs() < 1e-10 * (1.0 + w.abs()), "{g} vs {w}");
        }
    }

    #[test]
    fn complex_pairs_and_double_roots() {
        // (t² + 1)(t − 2): one real root.
        let got = sturm_roots(&[-2.0, 1.0, -2.0, 1.0]).unwrap();
        assert_eq!(got.as_slice().len(), 1);
        assert!((got.as_slice()[0] - 2.0).abs() < 1e-14);
        // (t − 1)² (t + 3): the simple root, and the double root (which
        // rounding may split into a close pair or hide) nowhere else.
        let got = sturm_roots(&from_roots(&[1.0, 1.0, -3.0])).unwrap();
        assert!((got.as_slice()[0] + 3.0).abs() < 1e-12);
        assert!(got.as_slice()[1..].iter().all(|t| (t - 1.0).abs() < 1e-6));
        // A trailing zero leading coefficient lowers the degree.
        let got = sturm_roots(&[-1.0, 1.0, 0.0]).unwrap();
        assert_eq!(got.as_slice(), &[1.0]);
    }

    /// The lane-wise evaluation of the whole sequence (both builds) and
    /// the fixed-length evaluation of one polynomial give Horner's rule
    /// from the leading coefficient bit for bit.
    #[test]
    fn table_evaluation_equals_horner_per_polynomial() {
        let coeffs: Vec<f64> = from_roots(&[-7.5, -3.0, -1.2, -0.4, 0.05, 0.3, 1.1, 2.5, 4.0, 9.0])
            .iter()
            .map(|c| c * 3.7)
            .collect();
        let mut p = Poly {
            c: [0.0; MAX_DEGREE + 1],
            degree: MAX_DEGREE,
        };
        p.c.copy_from_slice(&coeffs);
        let sturm = Sturm::new(p.normalised()).unwrap();
        let polys: Vec<Poly> = (0..sturm.len)
            .map(|i| {
                let degree = (0..=MAX_DEGREE)
                    .rev()
                    .find(|&k| sturm.table[k][i] != 0.0)
                    .unwrap();
                let mut q = Poly {
                    c: [0.0; MAX_DEGREE + 1],
                    degree,
                };
                (0..=degree).for_each(|k| q.c[k] = sturm.table[k][i]);
                q
            })
            .collect();
        assert_eq!(polys.len(), MAX_DEGREE + 1);
        for t in [-9.3, -7.5, -2.0, -0.4, -1e-3, 0.0, 0.3, 1.7, 4.0, 11.0] {
            // Horner's rule from the leading coefficient, value and derivative.
            let horner = |q: &Poly| {
                q.c[..=q.degree]
                    .iter()
                    .rev()
                    .fold((0.0, 0.0), |(v, dv): (f64, f64), &c| {
                        (v * t + c, dv * t + v)
                    })
            };
            let portable = crate::simd::with_portable(|| sturm.values(t));
            for values in [sturm.values(t), portable] {
                for (i, q) in polys.iter().enumerate() {
                    assert_eq!(values[i].to_bits(), horner(q).0.to_bits(), "p_{i}({t})");
                }
            }
            for q in &polys {
                let (v, dv) = q.eval_with_derivative(t);
                assert_eq!(
                    (v.to_bits(), dv.to_bits()),
                    (horner(q).0.to_bits(), horner(q).1.to_bits())
                );
                assert_eq!(q.eval(t).to_bits(), v.to_bits());
            }
            // Sign changes counted the plain way: zeros dropped first.
            let nonzero: Vec<f64> = polys
                .iter()
                .map(|q| q.eval(t))
                .filter(|v| *v != 0.0)
                .collect();
            let direct = nonzero.windows(2).filter(|w| w[0] * w[1] < 0.0).count();
            assert_eq!(sturm.variations(t), direct, "t = {t}");
        }
        assert_eq!(
            count_changes([0.0, 2.0, 0.0, -1.0, 0.0, -3.0, 4.0].into_iter()),
            2
        );
    }

    #[test]
    fn invalid_input_is_rejected() {
        assert!(sturm_roots(&[1.0, f64::NAN]).is_none());
        assert!(sturm_roots(&[0.0, 0.0]).is_none());
        assert!(sturm_roots(&[0.0; MAX_DEGREE + 2]).is_none());
        assert!(sturm_roots(&[2.0]).unwrap().as_slice().is_empty());
    }
}
