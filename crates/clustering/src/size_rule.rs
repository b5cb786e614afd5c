//! Rejection of spurious clusters (docs/method.md step 9): which clusters of the
//! agglomeration are kept as motions, the others becoming outliers.

use serde::{Deserialize, Serialize};

/// The rule that decides which clusters are kept (docs/method.md step 9). Every
/// rule yields a minimum size `s_min`: clusters with at least `s_min` points
/// are kept, the others are labelled −1. `min_cluster_size` is a floor of
/// `s_min` under every rule.
///
/// Serialised in kebab-case: `"min-size"` (default) or
/// `{"relative-min": 0.01}`.
///
/// ```
/// use clustering::SizeRule;
/// // The current rule: the floor alone.
/// assert_eq!(SizeRule::MinSize.min_size(4096, 8), 8);
/// // 1 % of N = 4096 points, rounded up.
/// assert_eq!(SizeRule::RelativeMin(0.01).min_size(4096, 8), 41);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SizeRule {
    /// `s_min = min_cluster_size` (the rule of docs/method.md step 9; default).
    /// Serialised as `"min-size"`.
    #[default]
    MinSize,
    /// `s_min = max(min_cluster_size, ⌈f · N⌉)`: a minimum size that grows
    /// with the number of points N. `f` should lie in `[0, 1]`
    /// ([`crate::ClusteringParams::validate`]); a NaN or negative `f` acts
    /// as 0. Serialised as `{"relative-min": f}`.
    RelativeMin(f64),
}

impl SizeRule {
    /// The minimum size `s_min` of a kept cluster, given the number of
    /// points N and the floor `min_cluster_size`.
    pub fn min_size(&self, n_points: usize, min_cluster_size: usize) -> usize {
        let rule = match *self {
            SizeRule::MinSize => 0,
            // A NaN or negative product saturates to 0.
            SizeRule::RelativeMin(f) => (f * n_points as f64).ceil() as usize,
        };
        rule.max(min_cluster_size)
    }
}
