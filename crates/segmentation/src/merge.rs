//! Merging clusters that one model explains (`final_assignment = "merge"`):
//! T-Linkage splits a large motion into fragments when N is large, and each
//! fragment's best hypothesis then explains the others' matches. The
//! merge step of multi-model fitting (Progressive-X, Barath & Matas, ICCV
//! 2019; consensus-space clustering, Barath et al., CVPR 2023) joins them.

use nalgebra::Matrix3;

/// The share of a cluster's matches that a larger cluster's model must
/// explain (squared Sampson distance `≤ thr_px²`) for the two to merge.
pub const MERGE_SHARE: f64 = 0.8;

/// The inlier sets (`r ≤ τ`) of the hypotheses that entered the
/// preferences, one bit per match.
#[derive(Debug, Clone, Default)]
pub struct InlierBits {
    words: usize,
    bits: Vec<u64>,
}

impl InlierBits {
    /// An empty set of hypotheses over `n` matches.
    pub fn new(n: usize) -> Self {
        Self {
            words: n.div_ceil(64),
            bits: Vec::new(),
        }
    }

    /// Adds a hypothesis: the matches whose residual is `≤ tau`.
    pub fn push(&mut self, residuals: &[f64], tau: f64) {
        self.push_words(inlier_words(residuals, tau));
    }

    /// Adds a hypothesis given as [`inlier_words`].
    pub(crate) fn push_words(&mut self, words: Vec<u64>) {
        debug_assert_eq!(words.len(), self.words);
        self.bits.extend(words);
    }

    fn len(&self) -> usize {
        self.bits.len().checked_div(self.words).unwrap_or(0)
    }

    fn hypothesis(&self, h: usize) -> &[u64] {
        &self.bits[h * self.words..(h + 1) * self.words]
    }
}

/// The inlier set `r ≤ tau` of `residuals` as bits, 64 matches a word.
pub(crate) fn inlier_words(residuals: &[f64], tau: f64) -> Vec<u64> {
    let mut words = vec![0u64; residuals.len().div_ceil(64)];
    for (i, &r) in residuals.iter().enumerate() {
        if r <= tau {
            words[i / 64] |= 1 << (i % 64);
        }
    }
    words
}

fn contains(words: &[u64], i: usize) -> bool {
    words[i / 64] >> (i % 64) & 1 == 1
}

/// New labels for `labels` (clusters `0..clusters`, −1 outliers) after
/// merging:
///
/// 1. each cluster's model is the hypothesis of `inliers` with the most
///    inliers among its matches (the lower index on ties);
/// 2. clusters are visited from the largest (the lower label on ties); a
///    cluster joins the earlier kept cluster whose model explains the
///    largest share of its matches when that share is `≥ MERGE_SHARE`,
///    else it is kept;
/// 3. labels are renumbered 0, 1, … by first appearance; outliers stay −1.
///
/// ```
/// use segmentation::{merge_explained, InlierBits};
/// // Two fragments of one motion (labels 0 and 1) and another motion (2):
/// // hypothesis 0 explains matches 0–5, hypothesis 1 matches 6–8.
/// let labels = [0, 0, 0, 1, 1, -1, 2, 2, 2];
/// let mut inliers = InlierBits::new(9);
/// inliers.push(&[0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 9.0, 9.0, 9.0], 1.0);
/// inliers.push(&[9.0, 9.0, 9.0, 9.0, 9.0, 9.0, 0.0, 0.0, 0.0], 1.0);
/// assert_eq!(merge_explained(&labels, 3, &inliers), [0, 0, 0, 0, 0, -1, 1, 1, 1]);
/// ```
pub fn merge_explained(labels: &[i32], clusters: usize, inliers: &InlierBits) -> Vec<i32> {
    let members = crate::assignment::members(labels, clusters);
    let models = best_hypotheses(labels, clusters, inliers);
    let order = largest_first(&members);

    let mut target: Vec<usize> = (0..clusters).collect();
    let mut kept: Vec<usize> = Vec::new();
    for &b in &order {
        let share = |a: usize| -> f64 {
            let Some(h) = models[a] else { return 0.0 };
            let words = inliers.hypothesis(h);
            let explained = members[b].iter().filter(|&&i| contains(words, i)).count();
            explained as f64 / members[b].len().max(1) as f64
        };
        let best =
            kept.iter()
                .map(|&a| (a, share(a)))
                .fold(None, |best: Option<(usize, f64)>, (a, s)| match best {
                    Some((_, bs)) if bs >= s => best,
                    _ => Some((a, s)),
                });
        match best {
            Some((a, s)) if s >= MERGE_SHARE => target[b] = a,
            _ => kept.push(b),
        }
    }
    apply_merges(labels, &target)
}

/// The clusters (indices of `members`) from the largest down, the lower
/// index on ties: the order in which the merges visit them.
fn largest_first(members: &[Vec<usize>]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..members.len()).collect();
    order.sort_by_key(|&c| (std::cmp::Reverse(members[c].len()), c));
    order
}

/// `labels` with each cluster `l` replaced by `target[l]` (every target
/// `< target.len()`), then renumbered 0, 1, … by first appearance;
/// outliers and labels out of range stay −1.
fn apply_merges(labels: &[i32], target: &[usize]) -> Vec<i32> {
    let merged: Vec<i32> = labels
        .iter()
        .map(|&l| match usize::try_from(l) {
            Ok(l) if l < target.len() => target[l] as i32,
            _ => -1,
        })
        .collect();
    crate::assignment::drop_small_and_renumber(&merged, target.len(), 0)
}

/// For each cluster, the hypothesis with the most inliers among its
/// matches (None when no hypothesis has one).
pub(crate) fn best_hypotheses(
    labels: &[i32],
    clusters: usize,
    inliers: &InlierBits,
) -> Vec<Option<usize>> {
    let mut best: Vec<(usize, Option<usize>)> = vec![(0, None); clusters];
    let mut counts = vec![0usize; clusters];
    for h in 0..inliers.len() {
        counts.fill(0);
        for (w, &word) in inliers.hypothesis(h).iter().enumerate() {
            let mut bits = word;
            while bits != 0 {
                let i = w * 64 + bits.trailing_zeros() as usize;
                bits &= bits - 1;
                if let Some(&l) = labels.get(i) {
                    if let Some(c) = usize::try_from(l).ok().filter(|&c| c < clusters) {
                        counts[c] += 1;
                    }
                }
            }
        }
        for (b, &count) in best.iter_mut().zip(&counts) {
            if count > b.0 {
                *b = (count, Some(h));
            }
        }
    }
    best.into_iter().map(|(_, h)| h).collect()
}

/// For each cluster, the model of its best-supported hypothesis
/// ([`best_hypotheses`]) among `models`, the entering hypotheses in order.
pub(crate) fn cluster_hypotheses(
    labels: &[i32],
    clusters: usize,
    inliers: &InlierBits,
    models: &[Matrix3<f64>],
) -> Vec<Option<Matrix3<f64>>> {
    best_hypotheses(labels, clusters, inliers)
        .into_iter()
        .map(|h| h.and_then(|h| models.get(h).copied()))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Hypotheses with the given inlier matches, over `n` matches.
    fn hypotheses(n: usize, sets: &[&[usize]]) -> InlierBits {
        let mut bits = InlierBits::new(n);
        for set in sets {
            let residuals: Vec<f64> = (0..n)
                .map(|i| if set.contains(&i) { 0.0 } else { 1.0 })
                .collect();
            bits.push(&residuals, 0.5);
        }
        bits
    }

    #[test]
    fn a_cluster_merges_at_the_share_and_not_below() {
        // Cluster 0: matches 0-5; cluster 1: matches 6-10 (5 matches).
        let labels = [0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 1];
        // Cluster 0's best hypothesis explains 4 of cluster 1's 5 (0.8).
        let at = hypotheses(11, &[&[0, 1, 2, 3, 4, 5, 6, 7, 8, 9]]);
        assert_eq!(merge_explained(&labels, 2, &at), [0; 11]);
        // 3 of 5 (0.6): both stay.
        let below = hypotheses(11, &[&[0, 1, 2, 3, 4, 5, 6, 7, 8]]);
        assert_eq!(merge_explained(&labels, 2, &below), labels);
    }

    #[test]
    fn the_larger_cluster_absorbs_and_labels_follow_first_appearance() {
        // Cluster 1 (matches 3-8) is larger than cluster 0 (matches 0-2),
        // so it is kept first and absorbs cluster 0.
        let labels = [0, 0, 0, 1, 1, 1, 1, 1, 1, -1];
        let bits = hypotheses(10, &[&[0, 1, 2, 3, 4, 5, 6, 7, 8], &[0, 1, 2]]);
        assert_eq!(
            merge_explained(&labels, 2, &bits),
            [0, 0, 0, 0, 0, 0, 0, 0, 0, -1]
        );
        // Without hypotheses nothing merges.
        assert_eq!(merge_explained(&labels, 2, &InlierBits::new(10)), labels);
    }
}
