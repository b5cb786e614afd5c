//! J-Linkage: binary preference sets, Jaccard distance, merged by
//! intersection — the ancestor of T-Linkage, on the same heap machinery.

use crate::distance::jaccard_distance;
use crate::heap::RUN_CAPACITY;
use crate::linkage::{
    agglomerate_until, labels_from_merges, AgglomerationState, Candidate, Clustering,
};
use crate::{BinaryPreferenceMatrix, Merge, SizeRule};
use std::ops::Range;

/// J-Linkage clustering of a binary preference matrix: agglomerate the
/// closest pair by Jaccard distance `1 − |A ∩ B| / |A ∪ B|` (ties broken by
/// the smaller `(i, j)`), the merged set being the intersection `A ∩ B` and
/// keeping the smaller id, until the closest pair has distance `≥ 1`;
/// clusters with fewer than `min_cluster_size` points are labelled −1.
///
/// Same lazy-deletion min-heap as [`crate::t_linkage`]; the labels and merges
/// are exactly those of [`crate::reference::j_linkage`].
///
/// ```
/// use clustering::{j_linkage, BinaryPreferenceMatrix};
/// let b = BinaryPreferenceMatrix::from_rows(&[
///     vec![true, true, false],
///     vec![false, false, true],
///     vec![true, true, false],
/// ])
/// .unwrap();
/// let c = j_linkage(&b, 0);
/// assert_eq!(c.labels, vec![0, 1, 0]);
/// assert_eq!(c.merges[0].distance, 0.0);
/// ```
pub fn j_linkage(preferences: &BinaryPreferenceMatrix, min_cluster_size: usize) -> Clustering {
    labels_from_merges(
        preferences.n_points(),
        merge_sequence(preferences),
        SizeRule::MinSize,
        min_cluster_size,
    )
}

/// The merges of J-Linkage, before any size filter.
pub(crate) fn merge_sequence(preferences: &BinaryPreferenceMatrix) -> Vec<Merge> {
    merge_sequence_until(preferences, &|| false)
}

/// [`merge_sequence`], stopping early once `stop` returns true
/// ([`agglomerate_until`]).
pub(crate) fn merge_sequence_until(
    preferences: &BinaryPreferenceMatrix,
    stop: &dyn Fn() -> bool,
) -> Vec<Merge> {
    agglomerate_until(BinaryState::new(preferences), RUN_CAPACITY, stop)
}

/// Bit sets of the clusters (point-major, `words` words each) and their sizes.
struct BinaryState {
    n: usize,
    words: usize,
    bits: Vec<u64>,
    counts: Vec<u64>,
}

impl BinaryState {
    fn new(preferences: &BinaryPreferenceMatrix) -> Self {
        let n = preferences.n_points();
        let words = preferences.words_per_row();
        let bits: Vec<u64> = (0..n)
            .flat_map(|i| preferences.row_bits(i).iter().copied())
            .collect();
        let counts = (0..n)
            .map(|i| popcount(&bits[i * words..(i + 1) * words]))
            .collect();
        Self {
            n,
            words,
            bits,
            counts,
        }
    }

    fn row(&self, i: usize) -> &[u64] {
        &self.bits[i * self.words..(i + 1) * self.words]
    }

    fn distance(&self, i: usize, k: usize) -> f64 {
        let intersection: u64 = self
            .row(i)
            .iter()
            .zip(self.row(k))
            .map(|(a, b)| u64::from((a & b).count_ones()))
            .sum();
        jaccard_distance(intersection, self.counts[i] + self.counts[k] - intersection)
    }
}

fn popcount(words: &[u64]) -> u64 {
    words.iter().map(|w| u64::from(w.count_ones())).sum()
}

impl AgglomerationState for BinaryState {
    fn n_clusters(&self) -> usize {
        self.n
    }

    fn initial_distances(&self, rows: Range<usize>, out: &mut Vec<(u32, u32, Candidate)>) {
        for i in rows {
            if self.counts[i] == 0 {
                continue;
            }
            for k in i + 1..self.n {
                let d = self.distance(i, k);
                if d < 1.0 {
                    out.push((i as u32, k as u32, Candidate { d, exact: true }));
                }
            }
        }
    }

    fn exact_distance(&mut self, i: usize, k: usize) -> f64 {
        self.distance(i, k)
    }

    fn merge(&mut self, merge: &Merge, active: &[bool], out: &mut Vec<(u32, Candidate)>) {
        let (kept, removed, w) = (merge.kept, merge.removed, self.words);
        let (head, tail) = self.bits.split_at_mut(removed * w);
        for (a, b) in head[kept * w..(kept + 1) * w].iter_mut().zip(&tail[..w]) {
            *a &= b;
        }
        self.counts[kept] = popcount(self.row(kept));
        self.counts[removed] = 0;
        self.candidates(kept, active, out);
    }

    fn candidates(&mut self, cluster: usize, active: &[bool], out: &mut Vec<(u32, Candidate)>) {
        if self.counts[cluster] == 0 {
            return;
        }
        for k in (0..self.n).filter(|&k| k != cluster && active[k]) {
            let d = self.distance(cluster, k);
            if d < 1.0 {
                out.push((k as u32, Candidate { d, exact: true }));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::linkage::agglomerate;
    use crate::reference;

    /// Runs bounded to very few entries give the reference merges.
    #[test]
    fn bounded_runs_give_the_reference_result() {
        let mut seed = 17u64;
        let mut next = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        };
        for case in 0..30 {
            let (n, m) = (2 + (next() % 60) as usize, 1 + (next() % 100) as usize);
            let rows: Vec<Vec<bool>> = (0..n)
                .map(|_| (0..m).map(|_| next() % 4 == 0).collect())
                .collect();
            let b = BinaryPreferenceMatrix::from_rows(&rows).unwrap();
            let expected = reference::j_linkage(&b, 0);
            for capacity in [1, 2, 5] {
                let merges = agglomerate(BinaryState::new(&b), capacity);
                assert_eq!(
                    labels_from_merges(n, merges, SizeRule::MinSize, 0),
                    expected,
                    "case {case}, capacity {capacity}"
                );
            }
        }
    }
}
