//! The paired Wilcoxon signed-rank test (docs/method.md, "Wilcoxon signed-rank
//! test"; thesis Section 7.4.2).
//!
//! Matches `scipy.stats.wilcoxon(x, y, alternative=..., zero_method='wilcox',
//! correction=False, method=...)`:
//! - differences `d = x − y`; zero differences are dropped, leaving `n`;
//! - `|d|` is ranked 1..n, tied values get the average of their ranks;
//! - the statistic `T+` is the sum of the ranks of the positive differences
//!   (for a two-sided test the reported statistic is `min(T+, T−)`);
//! - [`Mode::Auto`] picks, with `N` the number of pairs *before* dropping
//!   zeros: the exact null distribution when `N ≤ 50` and there are neither
//!   ties nor zeros; the exact permutation distribution over all `2^N` sign
//!   flips when there are ties or zeros and `N ≤ 13`; else the normal
//!   approximation with tie-corrected variance.
//!
//! The exact distribution is the dynamic-programming count of the subsets of
//! `{1..n}` by sum, in probabilities (each step halves), and its tails are
//! summed in the same order as numpy's pairwise summation so that the
//! p-values agree with scipy's bit for bit, rounding included.

use serde::{Deserialize, Serialize};
use statrs::distribution::{ContinuousCDF, Normal};
use thiserror::Error;

/// Largest `N` (pairs, zeros included) for which [`Mode::Auto`] uses the
/// exact null distribution when there are no ties or zeros.
pub const AUTO_EXACT_MAX_PAIRS: usize = 50;

/// Largest `N` (pairs, zeros included) for which [`Mode::Auto`] enumerates
/// the `2^N` sign flips when there are ties or zeros.
pub const AUTO_PERMUTATION_MAX_PAIRS: usize = 13;

/// Largest number of non-zero differences for which [`Mode::Exact`] builds
/// the exact null distribution (`n(n+1)/2 + 1` probabilities; beyond about
/// 1074 pairs the probabilities underflow anyway).
pub const EXACT_MAX_N: usize = 1000;

/// The alternative hypothesis about the differences `d = x − y`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Alternative {
    /// H1: `x` tends to be larger than `y` (the evaluation's "baseline >
    /// method"); p = P(T+ ≥ observed).
    Greater,
    /// H1: `x` tends to be smaller than `y`; p = P(T+ ≤ observed).
    Less,
    /// H1: the differences are not symmetric about 0; p = 2 min(P(T+ ≤ t),
    /// P(T+ ≥ t)), clipped to 1.
    TwoSided,
}

/// How the null distribution of the statistic is obtained.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Mode {
    /// scipy's `method='auto'` (see the module documentation).
    Auto,
    /// The exact null distribution of `T+` for `n` untied non-zero ranks
    /// (scipy's `method='exact'`). With ties the statistic is rounded down
    /// (`Greater`) or up (`Less`) first, which is conservative.
    Exact,
    /// The normal approximation with tie-corrected variance, no continuity
    /// correction (scipy's `method='approx'` / `'asymptotic'`).
    Approx,
}

/// The branch that produced the p-value.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ModeUsed {
    /// Exact null distribution of `T+` for `n` untied ranks.
    Exact,
    /// Exact permutation distribution over all sign flips of the observed
    /// (possibly tied) ranks.
    Permutation,
    /// Normal approximation.
    Approx,
}

impl std::fmt::Display for ModeUsed {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            ModeUsed::Exact => "exact",
            ModeUsed::Permutation => "permutation",
            ModeUsed::Approx => "approx",
        })
    }
}

/// Outcome of [`wilcoxon`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct WilcoxonResult {
    /// `T+`, the sum of the ranks of the positive differences, for
    /// `Greater` and `Less`; `min(T+, T−)` for `TwoSided` (scipy's
    /// convention).
    pub statistic: f64,
    /// The p-value under the chosen alternative.
    pub p_value: f64,
    /// The branch that computed the p-value.
    pub mode_used: ModeUsed,
    /// Number of non-zero differences (the pairs that are ranked).
    pub n: usize,
    /// Number of zero differences dropped.
    pub n_zero: usize,
}

/// Why the test cannot be computed.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum WilcoxonError {
    /// The samples are not paired one to one.
    #[error("paired samples differ in length: x has {x} values, y has {y}")]
    LengthMismatch {
        /// Length of `x`.
        x: usize,
        /// Length of `y`.
        y: usize,
    },
    /// A value is NaN or infinite.
    #[error("{sample}[{index}] is not a finite number")]
    NonFinite {
        /// `"x"` or `"y"`.
        sample: &'static str,
        /// Position of the value (0-based).
        index: usize,
    },
    /// No pairs at all.
    #[error("no paired values")]
    Empty,
    /// Every difference is zero: nothing to rank.
    #[error("all {pairs} differences are zero: the test is undefined")]
    AllZero {
        /// Number of pairs.
        pairs: usize,
    },
    /// [`Mode::Exact`] was asked for too many non-zero differences.
    #[error("exact null distribution requested for {n} non-zero differences; at most {max} are supported (use the approximation)")]
    ExactTooLarge {
        /// Number of non-zero differences.
        n: usize,
        /// [`EXACT_MAX_N`].
        max: usize,
    },
}

/// One-tailed (or two-sided) paired Wilcoxon signed-rank test of `x` against
/// `y` (docs/method.md "Wilcoxon signed-rank test"; thesis Section 7.4.2).
///
/// With `d = x − y`, zeros dropped and the `n` remaining `|d|` ranked with
/// ties averaged, `T+ = Σ_{d_i > 0} rank_i`, `E[T+] = n(n+1)/4` and
/// `Var[T+] = (n(n+1)(2n+1) − Σ_groups (t³ − t)/2) / 24`. The p-value comes
/// from the branch chosen by `mode` (see [`Mode`] and the module
/// documentation).
///
/// # Errors
/// [`WilcoxonError`] for samples of different length, a NaN or infinite
/// value, no pairs, no non-zero difference, or [`Mode::Exact`] with more
/// than [`EXACT_MAX_N`] non-zero differences.
pub fn wilcoxon(
    x: &[f64],
    y: &[f64],
    alternative: Alternative,
    mode: Mode,
) -> Result<WilcoxonResult, WilcoxonError> {
    if x.len() != y.len() {
        return Err(WilcoxonError::LengthMismatch {
            x: x.len(),
            y: y.len(),
        });
    }
    for (sample, values) in [("x", x), ("y", y)] {
        if let Some(index) = values.iter().position(|v| !v.is_finite()) {
            return Err(WilcoxonError::NonFinite { sample, index });
        }
    }
    if x.is_empty() {
        return Err(WilcoxonError::Empty);
    }
    let pairs = x.len();
    let differences: Vec<f64> = x
        .iter()
        .zip(y)
        .map(|(a, b)| a - b)
        .filter(|&d| d != 0.0)
        .collect();
    let n = differences.len();
    let n_zero = pairs - n;
    if n == 0 {
        return Err(WilcoxonError::AllZero { pairs });
    }
    let ranked = SignedRanks::new(&differences);
    let r_plus = ranked.rank_sum_positive();
    let r_minus = ranked.rank_sum_negative();

    let mode_used = match mode {
        Mode::Exact => ModeUsed::Exact,
        Mode::Approx => ModeUsed::Approx,
        Mode::Auto if pairs > AUTO_EXACT_MAX_PAIRS => ModeUsed::Approx,
        Mode::Auto if !ranked.has_ties() && n_zero == 0 => ModeUsed::Exact,
        Mode::Auto if pairs <= AUTO_PERMUTATION_MAX_PAIRS => ModeUsed::Permutation,
        Mode::Auto => ModeUsed::Approx,
    };
    let p_value = match mode_used {
        ModeUsed::Exact => {
            if n > EXACT_MAX_N {
                return Err(WilcoxonError::ExactTooLarge {
                    n,
                    max: EXACT_MAX_N,
                });
            }
            exact_p_value(n, r_plus, alternative)
        }
        ModeUsed::Permutation => permutation_p_value(&ranked, alternative),
        ModeUsed::Approx => approx_p_value(n, r_plus, ranked.tie_correction(), alternative),
    };
    let statistic = match alternative {
        Alternative::TwoSided => r_plus.min(r_minus),
        Alternative::Greater | Alternative::Less => r_plus,
    };
    Ok(WilcoxonResult {
        statistic,
        p_value,
        mode_used,
        n,
        n_zero,
    })
}

/// Ranks of `|d|` for non-zero differences, kept doubled so that averaged
/// ranks of ties stay integers (a tie group over sorted positions
/// `a..=b`, 1-based, has rank `(a + b) / 2`).
struct SignedRanks {
    /// `(2 · rank, d > 0)` per difference.
    doubled: Vec<(u64, bool)>,
    /// Sizes of the groups of tied `|d|`.
    tie_groups: Vec<u64>,
}

impl SignedRanks {
    fn new(differences: &[f64]) -> Self {
        let mut order: Vec<usize> = (0..differences.len()).collect();
        order.sort_by(|&a, &b| differences[a].abs().total_cmp(&differences[b].abs()));
        let mut doubled = vec![(0u64, false); differences.len()];
        let mut tie_groups = Vec::new();
        let mut start = 0;
        while start < order.len() {
            let magnitude = differences[order[start]].abs();
            let end = order[start..]
                .iter()
                .position(|&i| differences[i].abs() != magnitude)
                .map_or(order.len(), |offset| start + offset);
            // Positions start+1 ..= end (1-based) share rank (start + 1 + end) / 2.
            let twice_rank = (start + 1 + end) as u64;
            for &i in &order[start..end] {
                doubled[i] = (twice_rank, differences[i] > 0.0);
            }
            tie_groups.push((end - start) as u64);
            start = end;
        }
        Self {
            doubled,
            tie_groups,
        }
    }

    fn rank_sum_positive(&self) -> f64 {
        self.doubled
            .iter()
            .filter(|(_, pos)| *pos)
            .map(|(r, _)| *r)
            .sum::<u64>() as f64
            / 2.0
    }

    fn rank_sum_negative(&self) -> f64 {
        self.doubled
            .iter()
            .filter(|(_, pos)| !*pos)
            .map(|(r, _)| *r)
            .sum::<u64>() as f64
            / 2.0
    }

    fn has_ties(&self) -> bool {
        self.tie_groups.iter().any(|&t| t > 1)
    }

    /// `Σ_groups (t³ − t)`.
    fn tie_correction(&self) -> f64 {
        self.tie_groups
            .iter()
            .map(|&t| (t * t * t - t) as f64)
            .sum()
    }
}

/// Null distribution of `T+` for `n` untied ranks: `pmf[k] = P(T+ = k)`,
/// `k = 0..=n(n+1)/2`, i.e. (number of subsets of `{1..n}` summing to `k`)
/// / 2^n, built one rank at a time: `pmf_m[k] = (pmf_{m−1}[k] +
/// pmf_{m−1}[k − m]) / 2`.
pub fn signed_rank_null_pmf(n: usize) -> Vec<f64> {
    let mut pmf = vec![0.0; n * (n + 1) / 2 + 1];
    pmf[0] = 1.0;
    for m in 1..=n {
        let len = m * (m + 1) / 2 + 1;
        let prev_len = len - m;
        // Descending, so that pmf[k − m] still holds the previous step.
        for k in (0..len).rev() {
            let keep = if k < prev_len { pmf[k] * 0.5 } else { 0.0 };
            let add = if k >= m { pmf[k - m] * 0.5 } else { 0.0 };
            pmf[k] = keep + add;
        }
    }
    pmf
}

/// Sum in numpy's pairwise order (blocks of at most 128 summed with eight
/// accumulators, halves at multiples of 8), so that tail probabilities
/// round exactly as scipy's do.
fn pairwise_sum(values: &[f64]) -> f64 {
    const BLOCK: usize = 128;
    let n = values.len();
    if n < 8 {
        values.iter().fold(0.0, |acc, v| acc + v)
    } else if n <= BLOCK {
        let mut r = [0.0; 8];
        r.copy_from_slice(&values[..8]);
        let whole = n - n % 8;
        for chunk in values[8..whole].chunks_exact(8) {
            for (acc, v) in r.iter_mut().zip(chunk) {
                *acc += v;
            }
        }
        let mut res = ((r[0] + r[1]) + (r[2] + r[3])) + ((r[4] + r[5]) + (r[6] + r[7]));
        for v in &values[whole..] {
            res += v;
        }
        res
    } else {
        let mut half = n / 2;
        half -= half % 8;
        pairwise_sum(&values[..half]) + pairwise_sum(&values[half..])
    }
}

/// `P(T+ ≥ k)` as scipy computes it: the upper tail when `k ≤ E[T+]`, else
/// one minus the lower tail.
fn exact_sf(pmf: &[f64], k: usize, mean: f64) -> f64 {
    let k = k.min(pmf.len());
    if k as f64 <= mean {
        pairwise_sum(&pmf[k..])
    } else {
        1.0 - pairwise_sum(&pmf[..k])
    }
}

/// `P(T+ ≤ k)` as scipy computes it.
fn exact_cdf(pmf: &[f64], k: usize, mean: f64) -> f64 {
    if k as f64 <= mean {
        pairwise_sum(&pmf[..=k.min(pmf.len() - 1)])
    } else {
        1.0 - pairwise_sum(&pmf[(k + 1).min(pmf.len())..])
    }
}

fn exact_p_value(n: usize, r_plus: f64, alternative: Alternative) -> f64 {
    let pmf = signed_rank_null_pmf(n);
    let mean = (n * (n + 1)) as f64 / 4.0;
    // T+ is a multiple of 1/2; with ties it is rounded conservatively.
    let floor = r_plus.floor() as usize;
    let ceil = r_plus.ceil() as usize;
    match alternative {
        Alternative::Greater => exact_sf(&pmf, floor, mean),
        Alternative::Less => exact_cdf(&pmf, ceil, mean),
        Alternative::TwoSided => {
            (2.0 * exact_sf(&pmf, floor, mean).min(exact_cdf(&pmf, ceil, mean))).clamp(0.0, 1.0)
        }
    }
}

/// Exact permutation p-value: the observed `T+` against its value under
/// every one of the `2^n` sign patterns of the observed ranks (zeros, whose
/// sign flips change nothing, cancel out of the proportion).
fn permutation_p_value(ranked: &SignedRanks, alternative: Alternative) -> f64 {
    let observed: u64 = ranked
        .doubled
        .iter()
        .filter(|(_, pos)| *pos)
        .map(|(r, _)| *r)
        .sum();
    let total: u64 = ranked.doubled.iter().map(|(r, _)| *r).sum();
    // counts[s] = number of sign patterns whose doubled T+ equals s.
    let mut counts = vec![0.0f64; total as usize + 1];
    counts[0] = 1.0;
    let mut reach = 0usize;
    for &(r, _) in &ranked.doubled {
        let r = r as usize;
        for s in (0..=reach).rev() {
            let c = counts[s];
            counts[s + r] += c;
        }
        reach += r;
    }
    let patterns = 2f64.powi(ranked.doubled.len() as i32);
    let observed = observed as usize;
    let upper = counts[observed..].iter().sum::<f64>() / patterns;
    let lower = counts[..=observed].iter().sum::<f64>() / patterns;
    match alternative {
        Alternative::Greater => upper,
        Alternative::Less => lower,
        Alternative::TwoSided => (2.0 * upper.min(lower)).clamp(0.0, 1.0),
    }
}

fn approx_p_value(n: usize, r_plus: f64, tie_correction: f64, alternative: Alternative) -> f64 {
    let n = n as f64;
    let mean = n * (n + 1.0) * 0.25;
    let variance_24 = n * (n + 1.0) * (2.0 * n + 1.0) - tie_correction / 2.0;
    let se = (variance_24 / 24.0).sqrt();
    let z = (r_plus - mean) / se;
    let normal = Normal::standard();
    match alternative {
        Alternative::Greater => normal.sf(z),
        Alternative::Less => normal.cdf(z),
        Alternative::TwoSided => 2.0 * normal.sf(z.abs()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn null_pmf_counts_subsets_by_sum() {
        // Brute force over all subsets of {1..n}.
        for n in 0..=10usize {
            let pmf = signed_rank_null_pmf(n);
            let mut counts = vec![0u32; n * (n + 1) / 2 + 1];
            for mask in 0u32..(1 << n) {
                let s: usize = (0..n).filter(|i| mask >> i & 1 == 1).map(|i| i + 1).sum();
                counts[s] += 1;
            }
            let scale = 2f64.powi(n as i32);
            for (k, (&p, &c)) in pmf.iter().zip(&counts).enumerate() {
                assert_eq!(p * scale, c as f64, "n={n} k={k}");
            }
        }
    }

    #[test]
    fn pairwise_sum_is_the_plain_sum_on_integers() {
        for n in [0usize, 1, 7, 8, 9, 127, 128, 129, 1000, 4097] {
            let v: Vec<f64> = (0..n).map(|i| (i % 17) as f64).collect();
            let plain: f64 = v.iter().sum();
            assert_eq!(pairwise_sum(&v), plain, "n={n}");
        }
    }

    #[test]
    fn ranks_average_over_ties() {
        let r = SignedRanks::new(&[1.0, -2.0, 2.0, 3.0, -2.0]);
        // |d| sorted: 1 | 2 2 2 | 3 -> ranks 1, 3, 3, 3, 5.
        let ranks: Vec<u64> = r.doubled.iter().map(|(d, _)| *d).collect();
        assert_eq!(ranks, vec![2, 6, 6, 10, 6]);
        assert_eq!(r.rank_sum_positive(), 1.0 + 3.0 + 5.0);
        assert_eq!(r.rank_sum_negative(), 6.0);
        assert!(r.has_ties());
        assert_eq!(r.tie_correction(), 24.0);
    }

    #[test]
    fn permutation_equals_enumeration_of_sign_flips() {
        let d = [0.5, -0.5, 1.0, 2.0, -2.0, 2.0, 3.0];
        let ranked = SignedRanks::new(&d);
        let observed: u64 = ranked
            .doubled
            .iter()
            .filter(|(_, p)| *p)
            .map(|(r, _)| *r)
            .sum();
        let n = d.len();
        let (mut ge, mut le) = (0u32, 0u32);
        for mask in 0u32..(1 << n) {
            let t: u64 = (0..n)
                .filter(|i| mask >> i & 1 == 1)
                .map(|i| ranked.doubled[i].0)
                .sum();
            ge += (t >= observed) as u32;
            le += (t <= observed) as u32;
        }
        let total = (1u32 << n) as f64;
        assert_eq!(
            permutation_p_value(&ranked, Alternative::Greater),
            ge as f64 / total
        );
        assert_eq!(
            permutation_p_value(&ranked, Alternative::Less),
            le as f64 / total
        );
    }
}

#[cfg(test)]
mod scipy_fixtures;
#[cfg(test)]
#[path = "../../tests/support/fixtures.rs"]
mod test_fixtures;

/// The examples once in the documentation of this module's items.
#[cfg(test)]
mod examples {
    #[test]
    fn module_example() {
        use crate::wilcoxon::{wilcoxon, Alternative, Mode, ModeUsed};

        // Per-scene errors of a baseline and of a method (H1: baseline > method).
        let baseline = [0.30, 0.12, 0.25, 0.40, 0.18, 0.22, 0.35, 0.09];
        let method = [0.20, 0.10, 0.28, 0.15, 0.12, 0.21, 0.30, 0.02];
        let r = wilcoxon(&baseline, &method, Alternative::Greater, Mode::Auto).unwrap();
        assert_eq!(r.mode_used, ModeUsed::Exact);
        assert_eq!(r.n, 8);
        assert_eq!(r.statistic, 33.0); // every rank but that of -0.03 (rank 3)
        assert_eq!(r.p_value, 5.0 / 256.0); // T+ >= 33 in 5 of the 2^8 sign patterns
    }

    #[test]
    fn wilcoxon_example() {
        use crate::wilcoxon::{wilcoxon, Alternative, Mode, ModeUsed};

        let x = [1.0, 2.0, 3.0, 4.0, 5.0];
        let y = [0.0, 0.0, 0.0, 0.0, 0.0];
        let r = wilcoxon(&x, &y, Alternative::Greater, Mode::Exact).unwrap();
        assert_eq!((r.statistic, r.p_value), (15.0, 1.0 / 32.0));

        let approx = wilcoxon(&x, &y, Alternative::Greater, Mode::Approx).unwrap();
        assert_eq!(approx.mode_used, ModeUsed::Approx);
        assert!((approx.p_value - 0.021557223391537678).abs() < 1e-12);

        assert!(wilcoxon(&x, &y[..4], Alternative::Greater, Mode::Auto).is_err());
    }

    #[test]
    fn signed_rank_null_pmf_example() {
        use crate::wilcoxon::signed_rank_null_pmf;

        // Subsets of {1, 2, 3}: sums 0, 1, 2, 3, 3, 4, 5, 6.
        assert_eq!(
            signed_rank_null_pmf(3),
            [1.0, 1.0, 1.0, 2.0, 1.0, 1.0, 1.0]
                .iter()
                .map(|c| c / 8.0)
                .collect::<Vec<_>>()
        );
    }
}
