//! The natural logarithm of the binomial upper tail, `ln P(X ≥ k)` for
//! `X ~ Binomial(n, p)`, accurate far below `f64`'s smallest positive value
//! (the a-contrario tests of [`super::nfa`] need tails like 10⁻⁵⁰⁰⁰).
//!
//! `P(X ≥ k) = I_p(k, n − k + 1)`, the regularised incomplete beta function
//! (Abramowitz & Stegun 26.5.24), evaluated in logarithms by its continued
//! fraction (A&S 26.5.8, modified Lentz's method) where it converges fast,
//! `x < (a + 1) / (a + b + 2)`, and through `I_x(a, b) = 1 − I_{1−x}(b, a)`
//! elsewhere.

use statrs::function::gamma::ln_gamma;

/// Continued-fraction iterations before giving up (the fraction converges
/// in O(√max(a, b)) steps in its region).
const MAX_ITERS: usize = 10_000;
/// Relative convergence tolerance of the continued fraction.
const EPS: f64 = 1e-15;
/// Lentz's guard against a zero denominator.
const TINY: f64 = 1e-300;

/// `ln P(X ≥ k)` for `X ~ Binomial(n, p)`: 0 when `k = 0`, −∞ when `k > n`
/// or `p ≤ 0` (and `k > 0`), 0 when `p ≥ 1`.
pub fn ln_binomial_tail(n: u64, k: u64, p: f64) -> f64 {
    if k == 0 || p >= 1.0 {
        return 0.0;
    }
    if k > n || p <= 0.0 || p.is_nan() {
        return f64::NEG_INFINITY;
    }
    ln_beta_regularized(k as f64, (n - k + 1) as f64, p)
}

/// `ln I_x(a, b)` for `a, b > 0` and `0 < x < 1`.
fn ln_beta_regularized(a: f64, b: f64, x: f64) -> f64 {
    if x < (a + 1.0) / (a + b + 2.0) {
        ln_front(a, b, x) + continued_fraction(a, b, x).ln() - a.ln()
    } else {
        let complement =
            (ln_front(b, a, 1.0 - x) + continued_fraction(b, a, 1.0 - x).ln() - b.ln()).exp();
        (-complement).ln_1p()
    }
}

/// `ln(x^a (1 − x)^b / B(a, b))`.
fn ln_front(a: f64, b: f64, x: f64) -> f64 {
    a * x.ln() + b * (-x).ln_1p() + ln_gamma(a + b) - ln_gamma(a) - ln_gamma(b)
}

/// The continued fraction of `I_x(a, b)` (A&S 26.5.8) by the modified
/// Lentz method, as Numerical Recipes' `betacf`.
fn continued_fraction(a: f64, b: f64, x: f64) -> f64 {
    let guard = |v: f64| if v.abs() < TINY { TINY } else { v };
    let (qab, qap, qam) = (a + b, a + 1.0, a - 1.0);
    let mut c = 1.0;
    let mut d = 1.0 / guard(1.0 - qab * x / qap);
    let mut h = d;
    for m in 1..=MAX_ITERS {
        let m = m as f64;
        let m2 = 2.0 * m;
        let even = m * (b - m) * x / ((qam + m2) * (a + m2));
        d = 1.0 / guard(1.0 + even * d);
        c = guard(1.0 + even / c);
        h *= d * c;
        let odd = -(a + m) * (qab + m) * x / ((a + m2) * (qap + m2));
        d = 1.0 / guard(1.0 + odd * d);
        c = guard(1.0 + odd / c);
        let step = d * c;
        h *= step;
        if (step - 1.0).abs() < EPS {
            break;
        }
    }
    h
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `ln P(X ≥ k)` by summing the probability mass function term by term
    /// in logarithms: the naive reference.
    fn naive(n: u64, k: u64, p: f64) -> f64 {
        let ln_choose = |n: u64, i: u64| {
            ln_gamma(n as f64 + 1.0) - ln_gamma(i as f64 + 1.0) - ln_gamma((n - i) as f64 + 1.0)
        };
        let terms: Vec<f64> = (k..=n)
            .map(|i| ln_choose(n, i) + i as f64 * p.ln() + (n - i) as f64 * (-p).ln_1p())
            .collect();
        let max = terms.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
        max + terms.iter().map(|t| (t - max).exp()).sum::<f64>().ln()
    }

    #[test]
    fn agrees_with_the_summed_mass_function() {
        for &(n, p) in &[(20u64, 0.3), (500, 0.007), (2000, 0.02), (60, 0.9)] {
            for k in [1, 2, 5, 10, 15, 20, n / 2, n - 1, n] {
                let (got, want) = (ln_binomial_tail(n, k, p), naive(n, k, p));
                assert!(
                    (got - want).abs() <= 1e-9 * want.abs().max(1.0),
                    "n {n} k {k} p {p}: {got} vs {want}"
                );
            }
        }
    }

    #[test]
    fn reaches_far_below_the_smallest_double() {
        // P(X = 5000) = p^5000 for n = k = 5000: ln = 5000 ln 0.01.
        let got = ln_binomial_tail(5000, 5000, 0.01);
        assert!((got - 5000.0 * 0.01f64.ln()).abs() < 1e-6 * got.abs());
    }

    #[test]
    fn edge_cases() {
        assert_eq!(ln_binomial_tail(10, 0, 0.5), 0.0);
        assert_eq!(ln_binomial_tail(10, 11, 0.5), f64::NEG_INFINITY);
        assert_eq!(ln_binomial_tail(10, 3, 0.0), f64::NEG_INFINITY);
        assert_eq!(ln_binomial_tail(10, 3, 1.0), 0.0);
    }
}
