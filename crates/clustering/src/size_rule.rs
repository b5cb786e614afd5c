//! Rejection of spurious clusters (docs/method.md step 9): which clusters of the
//! agglomeration are kept as motions, the others becoming outliers.

use serde::{Deserialize, Serialize};

/// The rule that decides which clusters are kept (docs/method.md step 9). Every
/// rule yields a minimum size `s_min`: clusters with at least `s_min` points
/// are kept, the others are labelled −1. `min_cluster_size` is a floor of
/// `s_min` under every rule.
///
/// Serialised in kebab-case: `"min-size"` (default), `"largest-gap"`,
/// `{"relative-min": 0.01}`.
///
/// ```
/// use clustering::SizeRule;
/// let sizes = [3000, 600, 450, 20, 12, 9, 2, 1, 1];
/// // The current rule: the floor alone.
/// assert_eq!(SizeRule::MinSize.min_size(&sizes, 4096, 8), 8);
/// // The largest ratio of consecutive sizes is 450 / 20: three clusters kept.
/// assert_eq!(SizeRule::LargestGap.min_size(&sizes, 4096, 8), 450);
/// // 1 % of N = 4096 points, rounded up.
/// assert_eq!(SizeRule::RelativeMin(0.01).min_size(&sizes, 4096, 8), 41);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SizeRule {
    /// `s_min = min_cluster_size` (the rule of docs/method.md step 9; default).
    /// Serialised as `"min-size"`.
    #[default]
    MinSize,
    /// T-Linkage's own rule (Magri & Fusiello, CVPR 2014, Section 3): sort
    /// the cluster sizes in decreasing order and cut at the largest gap. See
    /// [`largest_gap_cut`] for the exact definition (the gap is a *ratio*
    /// of consecutive sizes). Serialised as `"largest-gap"`.
    LargestGap,
    /// `s_min = max(min_cluster_size, ⌈f · N⌉)`: a minimum size that grows
    /// with the number of points N. `f` should lie in `[0, 1]`
    /// ([`crate::ClusteringParams::validate`]); a NaN or negative `f` acts
    /// as 0. Serialised as `{"relative-min": f}`.
    RelativeMin(f64),
}

impl SizeRule {
    /// The minimum size `s_min` of a kept cluster, given the sizes of all
    /// clusters of the agglomeration (any order, singletons included), the
    /// number of points N and the floor `min_cluster_size`.
    pub fn min_size(&self, sizes: &[usize], n_points: usize, min_cluster_size: usize) -> usize {
        let rule = match *self {
            SizeRule::MinSize => 0,
            SizeRule::LargestGap => largest_gap_cut(sizes),
            // A NaN or negative product saturates to 0.
            SizeRule::RelativeMin(f) => (f * n_points as f64).ceil() as usize,
        };
        rule.max(min_cluster_size)
    }
}

/// The size-gap cut of T-Linkage (Magri & Fusiello 2014): the size of the
/// smallest cluster kept, 0 for no clusters.
///
/// Definition. Let `s_1 ≥ s_2 ≥ … ≥ s_K` be the cluster sizes in decreasing
/// order, closed by a virtual `s_(K+1) = 1` (a lone outlier, so that a
/// clustering made only of large clusters keeps them all). The cut is after
/// `k* = argmax_k s_k / s_(k+1)` over `k = 1..K`, the largest `k` on a tie
/// (keep more rather than fewer; the floor `min_cluster_size` then applies),
/// and the result is `s_(k*)`: the clusters with at least `s_(k*)` points
/// are exactly the first `k*`.
///
/// Why a ratio and not a difference: at large N the background holds most
/// points, so the largest *difference* is usually the one between the
/// background and the next motion, and a difference cut would discard every
/// moving object. A ratio is scale-free: a fragment of 20 points after an
/// object of 450 is a gap of 22×, whatever N is.
///
/// ```
/// use clustering::largest_gap_cut;
/// assert_eq!(largest_gap_cut(&[100, 90, 80]), 80); // ratios 1.1, 1.1, 80 (virtual 1)
/// assert_eq!(largest_gap_cut(&[1, 3000, 2, 800]), 800);
/// assert_eq!(largest_gap_cut(&[]), 0);
/// ```
pub fn largest_gap_cut(sizes: &[usize]) -> usize {
    let mut sorted: Vec<usize> = sizes.iter().copied().filter(|&s| s > 0).collect();
    sorted.sort_unstable_by(|a, b| b.cmp(a));
    sorted.push(1);
    let mut best: Option<(usize, usize)> = None; // (s_k, s_(k+1)) of the best cut
    for pair in sorted.windows(2) {
        let (big, small) = (pair[0], pair[1]);
        // big / small ≥ best_big / best_small, compared exactly in integers.
        let better = best.map_or(true, |(bb, bs)| {
            big as u128 * bs as u128 >= bb as u128 * small as u128
        });
        if better {
            best = Some((big, small));
        }
    }
    best.map_or(0, |(big, _)| big)
}
