//! T-Linkage (docs/method.md step 8): Tanimoto distance (Eq. 39) between
//! continuous preference vectors, merged by element-wise minimum (Eq. 40).

mod kernels;

use crate::distance::{tanimoto_distance, tanimoto_lower_bound};
use crate::heap::RUN_CAPACITY;
use crate::linkage::{
    agglomerate, agglomerate_until, labels_from_merges, AgglomerationState, Candidate, Clustering,
};
use crate::{Merge, PreferenceMatrix, SizeRule};
use kernels::{avx2_available, bound_margin, quantise, Level, LANES, LEVELS};
use std::borrow::Cow;
use std::ops::Range;

/// T-Linkage clustering of a continuous preference matrix (docs/method.md steps
/// 8–9, Eq. 39–40), with the lazy-deletion min-heap of Section 6.3.
///
/// Pairs are merged closest first, ties broken by the smaller `(i, j)`; the
/// merged vector is the element-wise minimum of the two (Eq. 40) and keeps
/// the smaller id; the agglomeration stops when the closest pair has
/// Tanimoto distance `≥ 1` (no shared preference). Clusters with fewer than
/// `min_cluster_size` points are labelled −1 (step 9; 0 or 1 keeps all).
///
/// The labels and merges are exactly those of
/// [`crate::reference::t_linkage`], the plain O(N³) definition: every
/// distance that decides a merge is computed in f64 with the inner products
/// summed in hypothesis order (see [`crate::distance`]).
///
/// ```
/// use clustering::{t_linkage, PreferenceMatrix};
/// let p = PreferenceMatrix::from_rows(&[
///     vec![1.0, 0.9, 0.0, 0.0],
///     vec![0.0, 0.0, 1.0, 0.8],
///     vec![0.9, 1.0, 0.0, 0.0],
///     vec![0.0, 0.0, 0.7, 1.0],
///     vec![0.0, 0.0, 0.0, 0.0], // prefers nothing
/// ])
/// .unwrap();
/// let c = t_linkage(&p, 2);
/// assert_eq!(c.labels, vec![0, 1, 0, 1, -1]);
/// assert_eq!((c.clusters_before_filter, c.clusters_after_filter), (3, 2));
/// assert_eq!((c.merges[0].kept, c.merges[0].removed), (0, 2));
/// ```
pub fn t_linkage(preferences: &PreferenceMatrix, min_cluster_size: usize) -> Clustering {
    labels_from_merges(
        preferences.n_points(),
        merge_sequence(preferences),
        SizeRule::MinSize,
        min_cluster_size,
    )
}

/// The merges of T-Linkage (docs/method.md step 8), before any size filter.
pub(crate) fn merge_sequence(preferences: &PreferenceMatrix) -> Vec<Merge> {
    agglomerate(ContinuousState::new(preferences), RUN_CAPACITY)
}

/// [`merge_sequence`] on preferences it may consume: each merge writes the
/// merged vector over the surviving cluster's row and frees the absorbed
/// one, so the clustering copies no row. The merges are the same.
/// The merges stop early once `stop` returns true ([`agglomerate_until`]).
pub(crate) fn merge_sequence_owned(
    preferences: PreferenceMatrix,
    stop: &dyn Fn() -> bool,
) -> Vec<Merge> {
    agglomerate_until(ContinuousState::owning(preferences), RUN_CAPACITY, stop)
}

/// Marks a slot that holds no active cluster.
const DEAD: u32 = u32::MAX;
/// The bound matrix is compacted (its dead slots dropped) once the sweeps
/// since the last compaction have read at least this many times as many
/// dead slots as the matrix has entries (and it has more than
/// [`MIN_COMPACTION_WIDTH`] slots): a compaction moves every entry once,
/// and a dead slot costs every sweep that reads it. Rent-or-buy: the
/// reads wasted never exceed about this multiple of the compactions' cost.
/// How many rows a sweep reads depends on the clusters (few at N 200 with
/// M 600, many at N 3000 with M 3000), so a fixed share of dead slots
/// either compacts too often for the first or too rarely for the second.
const COMPACTION_PAYBACK: usize = 8;
/// See [`COMPACTION_PAYBACK`].
const MIN_COMPACTION_WIDTH: usize = 64;

/// Inner products of exact preference vectors, as sparse sorted lists:
/// `Σ_j p_j · q_j` over the common hypotheses in ascending order — the
/// ordered sum of [`crate::distance`] without its zero terms.
fn exact_dot(p_index: &[u32], p_value: &[f64], q_index: &[u32], q_value: &[f64]) -> f64 {
    let (mut x, mut y, mut sum) = (0, 0, 0.0);
    while x < p_index.len() && y < q_index.len() {
        match p_index[x].cmp(&q_index[y]) {
            std::cmp::Ordering::Less => x += 1,
            std::cmp::Ordering::Greater => y += 1,
            std::cmp::Ordering::Equal => {
                sum += p_value[x] * q_value[y];
                x += 1;
                y += 1;
            }
        }
    }
    sum
}

/// Cluster vectors of T-Linkage.
///
/// *Exact part.* Each cluster's preference vector as two sorted lists (the
/// hypotheses it prefers, `> 0`, and the f64 values), and its squared norm
/// summed in hypothesis order. Merges (Eq. 40) and every distance that can
/// decide a merge use only these, with the arithmetic of the reference.
///
/// *Bound part.* An N × M matrix of `u8` upper bounds `q_cj ≥ 255 φ_cj`,
/// hypothesis-major (row j holds every slot's `q` for hypothesis j; each
/// active cluster owns a slot, slots in ascending cluster order, compacted
/// when an eighth are dead). After a merge, one sweep over the rows of the merged
/// cluster's hypotheses gives, for every other cluster at once,
/// `S = Σ_j q_aj · q_kj ≥ 255² <p_a, p_k>`; the Tanimoto distance at
/// `dot_upper(S)` is a certified lower bound, pushed instead of the
/// distance. Exact distances are computed only for the bounds that reach
/// the top of the heap, typically about one per merge. The `u8` matrix is
/// an eighth of an f64 one, and the sweeps, which stream it from memory,
/// are bound by its size.
struct ContinuousState<'a> {
    n: usize,
    /// Borrowed from the matrix until the cluster first absorbs another
    /// (owned from the start by [`ContinuousState::owning`]).
    index: Vec<Cow<'a, [u32]>>,
    value: Vec<Cow<'a, [f64]>>,
    norms: Vec<f64>,
    /// Slots per row of `bounds`, a multiple of [`LANES`].
    width: usize,
    bounds: Vec<Level>,
    cluster_of_slot: Vec<u32>,
    slot_of_cluster: Vec<u32>,
    live_slots: usize,
    /// Dead slots read by the sweeps since the last compaction (one read
    /// per slot per swept row); see [`COMPACTION_PAYBACK`].
    dead_reads: usize,
    /// See [`bound_margin`].
    margin: f64,
    /// Scratch: bound sums of the merged cluster with every slot, and their
    /// f32 partial sums.
    acc: Vec<f64>,
    partial: Vec<f32>,
    /// Scratch: the merged cluster's quantised preferences.
    multipliers: Vec<(u32, f32)>,
    /// Whether to run the AVX2 versions of the bound kernels.
    avx2: bool,
}

impl<'a> ContinuousState<'a> {
    /// The singletons of `preferences`, borrowing its rows.
    fn new(preferences: &'a PreferenceMatrix) -> Self {
        let (index, value) = (0..preferences.n_points())
            .map(|i| {
                let (hypotheses, values) = preferences.row_support(i);
                (Cow::Borrowed(hypotheses), Cow::Borrowed(values))
            })
            .unzip();
        Self::from_rows(preferences.n_hypotheses(), index, value)
    }

    /// The singletons of `preferences`, taking its rows.
    fn owning(preferences: PreferenceMatrix) -> Self {
        let m = preferences.n_hypotheses();
        let (index, value) = preferences.into_rows();
        Self::from_rows(
            m,
            index.into_iter().map(Cow::Owned).collect(),
            value.into_iter().map(Cow::Owned).collect(),
        )
    }

    /// The singletons of the rows `index[i]`, `value[i]` (M hypotheses).
    fn from_rows(m: usize, index: Vec<Cow<'a, [u32]>>, value: Vec<Cow<'a, [f64]>>) -> Self {
        let n = index.len();
        let width = n.next_multiple_of(LANES);
        let mut bounds = vec![0 as Level; m * width];
        let mut norms = Vec::with_capacity(n);
        for (i, (hypotheses, values)) in index.iter().zip(&value).enumerate() {
            let mut norm = 0.0;
            for (&j, &v) in hypotheses.iter().zip(values.iter()) {
                bounds[j as usize * width + i] = quantise(v);
                norm += v * v;
            }
            norms.push(norm);
        }
        Self {
            n,
            index,
            value,
            norms,
            width,
            bounds,
            cluster_of_slot: (0..width)
                .map(|s| if s < n { s as u32 } else { DEAD })
                .collect(),
            slot_of_cluster: (0..n as u32).collect(),
            live_slots: n,
            dead_reads: 0,
            margin: bound_margin(m),
            acc: vec![0.0; width],
            partial: vec![0.0; width],
            multipliers: Vec::new(),
            avx2: avx2_available(),
        }
    }

    /// An upper bound of the computed inner product `<p, q>` from the bound
    /// sum `S` of the quantised vectors.
    ///
    /// In exact arithmetic `Σ_j q_pj q_qj / 255² ≥ <p, q>`, since every
    /// `q ≥ 255 φ`. The kernels form the products and partial sums of at
    /// most [`kernels::CHUNK`] terms in f32 (relative loss at most `γ³²_(C+1)`, all
    /// terms being non-negative integers-valued products, so no underflow;
    /// with one-byte levels they are even exact, every product and chunk
    /// sum being an integer below 2²⁴),
    /// then add the partial sums in f64 (loss at most `γ⁶⁴_M`); the ordered
    /// f64 sum of the exact inner product exceeds the real value by at most
    /// `1 + γ⁶⁴_(M+1)`. [`bound_margin`] covers all of these and the
    /// roundings of this function.
    #[inline]
    fn dot_upper(&self, sum: f64) -> f64 {
        sum * self.margin / (LEVELS * LEVELS)
    }

    fn lower_bound(&self, sum: f64, norm_p: f64, norm_q: f64) -> Candidate {
        Candidate {
            d: tanimoto_lower_bound(self.dot_upper(sum), norm_p, norm_q),
            exact: false,
        }
    }

    /// Drops the dead slots: moves the live slots of every row of the bound
    /// matrix to its front, in the same (ascending cluster) order, and
    /// gives the rest back.
    fn compact(&mut self) {
        let live: Vec<usize> = (0..self.width)
            .filter(|&s| self.cluster_of_slot[s] != DEAD)
            .collect();
        let (old_width, width) = (self.width, live.len().next_multiple_of(LANES));
        let m = self.bounds.len() / old_width;
        // In place, row by row: every entry moves to a position no later
        // than its own (rows shrink, live slots keep their order), so each
        // is read before anything is written over it.
        for j in 0..m {
            let (old_row, new_row) = (j * old_width, j * width);
            for (k, &s) in live.iter().enumerate() {
                self.bounds[new_row + k] = self.bounds[old_row + s];
            }
            self.bounds[new_row + live.len()..new_row + width].fill(0);
        }
        self.bounds.truncate(m * width);
        self.bounds.shrink_to_fit();
        let mut cluster_of_slot = vec![DEAD; width];
        for (new, &old) in live.iter().enumerate() {
            let c = self.cluster_of_slot[old];
            cluster_of_slot[new] = c;
            self.slot_of_cluster[c as usize] = new as u32;
        }
        self.width = width;
        self.cluster_of_slot = cluster_of_slot;
        self.acc = vec![0.0; width];
        self.partial = vec![0.0; width];
        self.dead_reads = 0;
    }

    /// Eq. 40 on the exact lists: `kept ← min(kept, removed)`, which is
    /// non-zero exactly on the common hypotheses; the bound column of `kept`
    /// is rewritten to match and the lists of `removed` are dropped. The
    /// merged lists overwrite `kept`'s (a borrowed row is copied first) and
    /// are shrunk to their length. Returns the new squared norm.
    fn merge_exact(&mut self, kept: usize, removed: usize) -> f64 {
        let (b_index, b_value) = (
            std::mem::take(&mut self.index[removed]),
            std::mem::take(&mut self.value[removed]),
        );
        let mut index = std::mem::take(&mut self.index[kept]).into_owned();
        let mut value = std::mem::take(&mut self.value[kept]).into_owned();
        let (slot, width) = (self.slot_of_cluster[kept] as usize, self.width);
        let bounds = &mut self.bounds;
        let norm = intersect_in_place(&mut index, &mut value, &b_index, &b_value, |j, merged| {
            bounds[j as usize * width + slot] = quantise(merged);
        });
        index.shrink_to_fit();
        value.shrink_to_fit();
        self.index[kept] = Cow::Owned(index);
        self.value[kept] = Cow::Owned(value);
        norm
    }
}

/// `a ← min(a, b)` (Eq. 40) on sorted sparse lists, in place: `a` keeps
/// its hypotheses that `b` has too, each with the smaller value. Calls
/// `visit(j, merged)` for every hypothesis j of the old `a` (`merged` 0 for
/// the dropped ones) and returns the squared norm of the new `a`, summed in
/// hypothesis order.
fn intersect_in_place(
    a_index: &mut Vec<u32>,
    a_value: &mut Vec<f64>,
    b_index: &[u32],
    b_value: &[f64],
    mut visit: impl FnMut(u32, f64),
) -> f64 {
    let (mut y, mut written, mut norm) = (0, 0, 0.0);
    for read in 0..a_index.len() {
        let (j, a) = (a_index[read], a_value[read]);
        while y < b_index.len() && b_index[y] < j {
            y += 1;
        }
        let merged = if y < b_index.len() && b_index[y] == j {
            let v = a.min(b_value[y]);
            a_index[written] = j;
            a_value[written] = v;
            written += 1;
            norm += v * v;
            v
        } else {
            0.0
        };
        visit(j, merged);
    }
    a_index.truncate(written);
    a_value.truncate(written);
    norm
}

impl AgglomerationState for ContinuousState<'_> {
    fn n_clusters(&self) -> usize {
        self.n
    }

    fn initial_distances(&self, rows: Range<usize>, out: &mut Vec<(u32, u32, Candidate)>) {
        kernels::initial_bounds(self, rows, out)
    }

    fn exact_distance(&mut self, i: usize, k: usize) -> f64 {
        let dot = exact_dot(
            &self.index[i],
            &self.value[i],
            &self.index[k],
            &self.value[k],
        );
        tanimoto_distance(dot, self.norms[i], self.norms[k])
    }

    fn merge(&mut self, merge: &Merge, active: &[bool], out: &mut Vec<(u32, Candidate)>) {
        let (kept, removed) = (merge.kept, merge.removed);
        self.norms[kept] = self.merge_exact(kept, removed);
        let removed_slot = self.slot_of_cluster[removed] as usize;
        self.cluster_of_slot[removed_slot] = DEAD;
        self.slot_of_cluster[removed] = DEAD;
        self.live_slots -= 1;
        let dead = self.width - self.live_slots;
        // The sweep below reads every slot of the merged cluster's rows,
        // and the candidate loop every slot once.
        self.dead_reads += dead * (self.index[kept].len() + 1);
        let rows = self.bounds.len() / self.width;
        // At least a lane of dead slots, so that the padding alone never
        // triggers a compaction.
        if self.width > MIN_COMPACTION_WIDTH
            && dead >= LANES
            && self.dead_reads >= COMPACTION_PAYBACK * rows * self.width
        {
            self.compact();
        }
        self.candidates(kept, active, out);
    }

    fn candidates(&mut self, cluster: usize, active: &[bool], out: &mut Vec<(u32, Candidate)>) {
        kernels::merged_bounds(self, cluster);
        let norm = self.norms[cluster];
        let own_slot = self.slot_of_cluster[cluster] as usize;
        for (s, &c) in self.cluster_of_slot.iter().enumerate() {
            if c == DEAD || s == own_slot || !active[c as usize] {
                continue;
            }
            let candidate = self.lower_bound(self.acc[s], norm, self.norms[c as usize]);
            if candidate.d < 1.0 {
                out.push((c, candidate));
            }
        }
    }
}

#[cfg(test)]
mod tests;
