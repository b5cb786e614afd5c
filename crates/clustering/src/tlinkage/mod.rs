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
mod tests {
    use super::*;
    use crate::reference;

    /// A small deterministic generator (xorshift) for the tests of this module.
    struct Xorshift(u64);

    impl Xorshift {
        fn next(&mut self) -> u64 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            self.0
        }
        fn uniform(&mut self) -> f64 {
            (self.next() >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// Values that stress the quantisation: 1, the Eq. 38 minimum, values on
    /// and next to the quantisation grid, tiny and subnormal values.
    fn awkward_value(rng: &mut Xorshift) -> f64 {
        let k = (rng.next() % (u64::from(Level::MAX) + 1)) as f64;
        match rng.next() % 8 {
            0 => 1.0,
            1 => (-5.0f64).exp(),
            2 => k / LEVELS,
            3 => (k / LEVELS) * (1.0 + f64::EPSILON),
            4 => (k / LEVELS) * (1.0 - f64::EPSILON),
            5 => 1e-300 * rng.uniform(),
            6 => f64::from_bits(1 + rng.next() % 1000),
            _ => rng.uniform(),
        }
    }

    fn random_matrix(rng: &mut Xorshift, n: usize, m: usize, density: f64) -> PreferenceMatrix {
        let rows: Vec<Vec<f64>> = (0..n)
            .map(|_| {
                (0..m)
                    .map(|_| {
                        if rng.uniform() < density {
                            awkward_value(rng)
                        } else {
                            0.0
                        }
                    })
                    .collect()
            })
            .collect();
        PreferenceMatrix::from_rows(&rows).unwrap()
    }

    /// Test case `case`: N in `n.0..n.0 + n.1`, M in `m.0..m.0 + m.1`, the
    /// density cycling through `densities`.
    fn random_case(
        rng: &mut Xorshift,
        case: usize,
        n: (usize, u64),
        m: (usize, u64),
        densities: [f64; 3],
    ) -> PreferenceMatrix {
        let n = n.0 + (rng.next() % n.1) as usize;
        let m = m.0 + (rng.next() % m.1) as usize;
        random_matrix(rng, n, m, densities[case % 3])
    }

    /// The states of `p` for the portable kernels and, where the CPU has
    /// them, the AVX2 ones.
    fn kernel_states(p: &PreferenceMatrix) -> Vec<ContinuousState<'_>> {
        [false, avx2_available()]
            .into_iter()
            .map(|avx2| ContinuousState {
                avx2,
                ..ContinuousState::new(p)
            })
            .collect()
    }

    /// Merges `removed` into `kept` as the agglomeration does (marked
    /// inactive first), leaving the merged cluster's candidates in `fresh`.
    fn absorb(
        state: &mut ContinuousState,
        (kept, removed): (usize, usize),
        active: &mut [bool],
        fresh: &mut Vec<(u32, Candidate)>,
    ) {
        active[removed] = false;
        fresh.clear();
        let merge = Merge {
            kept,
            removed,
            distance: 0.0,
        };
        state.merge(&merge, active, fresh);
    }

    #[test]
    fn quantisation_rounds_up_and_keeps_zero() {
        let mut rng = Xorshift(99);
        assert_eq!(quantise(0.0), 0);
        assert_eq!(quantise(1.0), Level::MAX);
        assert_eq!(quantise(f64::from_bits(1)), 1);
        for _ in 0..100_000 {
            let v = awkward_value(&mut rng);
            let q = quantise(v);
            assert!(f64::from(q) >= v * LEVELS, "q({v}) = {q}");
            assert!(
                f64::from(q) <= v * LEVELS * (1.0 + 1e-12) + 1.0,
                "q({v}) = {q} too large"
            );
        }
    }

    /// Every candidate the kernels produce, initial or after a merge, is at
    /// most the exact distance (a certified lower bound), for both kernel
    /// versions.
    #[test]
    fn bounds_never_exceed_distances() {
        let mut rng = Xorshift(12345);
        for case in 0..60 {
            let p = random_case(&mut rng, case, (2, 40), (1, 300), [0.05, 0.3, 1.0]);
            let n = p.n_points();
            for mut state in kernel_states(&p) {
                let mut pairs = Vec::new();
                state.initial_distances(0..n, &mut pairs);
                for &(i, k, c) in &pairs {
                    let d = state.exact_distance(i as usize, k as usize);
                    assert!(
                        !c.exact && c.d <= d,
                        "case {case}: ({i}, {k}) bound {} > {d}",
                        c.d
                    );
                }
                // Every pair with d < 1 has a candidate.
                let expected = (0..n)
                    .flat_map(|i| (i + 1..n).map(move |k| (i, k)))
                    .filter(|&(i, k)| state.exact_distance(i, k) < 1.0)
                    .count();
                assert!(pairs.len() >= expected);
                let (mut active, mut fresh) = (vec![true; n], Vec::new());
                for removed in (1..n).rev().step_by(3) {
                    let kept = (rng.next() as usize) % removed;
                    if !active[kept] || !active[removed] {
                        continue;
                    }
                    absorb(&mut state, (kept, removed), &mut active, &mut fresh);
                    for &(k, c) in &fresh {
                        let d = state.exact_distance(kept, k as usize);
                        assert!(
                            c.d <= d,
                            "case {case}: merged ({kept}, {k}) bound {} > {d}",
                            c.d
                        );
                    }
                }
            }
        }
    }

    /// The initial kernel (blocks of rows) and the sweep (one cluster) give
    /// a singleton pair the same bound, bit for bit: a refill recomputes
    /// dropped initial pairs with the sweep and compares them to the floor.
    #[test]
    fn initial_bounds_equal_the_sweeps_bit_for_bit() {
        let mut rng = Xorshift(31);
        for case in 0..12 {
            let p = random_case(&mut rng, case, (20, 60), (50, 400), [0.1, 0.5, 0.95]);
            let n = p.n_points();
            for mut state in kernel_states(&p) {
                let avx2 = state.avx2;
                let mut initial = Vec::new();
                state.initial_distances(0..n, &mut initial);
                let active = vec![true; n];
                for i in 0..n {
                    let mut swept = Vec::new();
                    state.candidates(i, &active, &mut swept);
                    let later: Vec<(u32, u64)> = swept
                        .iter()
                        .filter(|&&(k, _)| k as usize > i)
                        .map(|&(k, c)| (k, c.d.to_bits()))
                        .collect();
                    let rows: Vec<(u32, u64)> = initial
                        .iter()
                        .filter(|&&(r, _, _)| r as usize == i)
                        .map(|&(_, k, c)| (k, c.d.to_bits()))
                        .collect();
                    assert_eq!(rows, later, "case {case}, row {i}, avx2 {avx2}");
                }
            }
        }
    }

    #[test]
    fn portable_kernels_give_the_reference_result() {
        let mut rng = Xorshift(7);
        for case in 0..30 {
            let (n, m) = (
                2 + (rng.next() % 80) as usize,
                1 + (rng.next() % 200) as usize,
            );
            let p = random_matrix(&mut rng, n, m, [0.1, 0.4, 0.9][case % 3]);
            let mut state = ContinuousState::new(&p);
            state.avx2 = false;
            let merges = agglomerate(state, RUN_CAPACITY);
            assert_eq!(
                labels_from_merges(n, merges, SizeRule::MinSize, 0),
                reference::t_linkage(&p, 0),
                "case {case}"
            );
        }
    }

    /// Consuming the matrix (rows merged in place, absorbed rows freed)
    /// leaves every surviving row at exactly its length (its merges are
    /// checked in `bounded_runs_give_the_reference_result`).
    #[test]
    fn owned_rows_stay_at_their_length() {
        let mut rng = Xorshift(44);
        for case in 0..30 {
            let p = random_case(&mut rng, case, (2, 70), (1, 150), [0.05, 0.4, 0.9]);
            let n = p.n_points();
            let mut state = ContinuousState::owning(p);
            let mut active = vec![true; n];
            let mut fresh = Vec::new();
            for removed in (1..n).rev() {
                absorb(&mut state, (0, removed), &mut active, &mut fresh);
                assert_eq!(state.index[0].len(), state.value[0].len());
                assert!(matches!(state.index[0], Cow::Owned(ref v) if v.capacity() == v.len()));
                assert!(state.index[removed].is_empty());
            }
        }
    }

    /// After merges and in-place compactions (those the rule triggers, and
    /// one every 40 merges), the bound matrix holds exactly the quantised
    /// exact vector of every active cluster in its slot, and nothing in
    /// the other slots.
    #[test]
    fn compaction_keeps_every_live_column() {
        let mut rng = Xorshift(8);
        let (n, m) = (300, 120);
        let p = random_matrix(&mut rng, n, m, 0.5);
        let mut state = ContinuousState::owning(p);
        let mut active = vec![true; n];
        let mut fresh = Vec::new();
        let mut widths = vec![state.width];
        for removed in (1..n).rev().filter(|r| r % 5 != 0) {
            let kept = (rng.next() as usize) % removed;
            if !active[kept] {
                continue;
            }
            absorb(&mut state, (kept, removed), &mut active, &mut fresh);
            if widths.len() % 40 == 0 && state.width - state.live_slots >= LANES {
                state.compact();
            }
            widths.push(state.width);
        }
        assert!(
            widths.windows(2).filter(|w| w[1] < w[0]).count() >= 3,
            "{widths:?}"
        );
        assert_eq!(state.bounds.len(), m * state.width);
        for (slot, &c) in state.cluster_of_slot.iter().enumerate() {
            let mut expected = vec![0 as Level; m];
            if c != DEAD {
                let c = c as usize;
                assert!(active[c] && state.slot_of_cluster[c] as usize == slot);
                for (&j, &v) in state.index[c].iter().zip(state.value[c].iter()) {
                    expected[j as usize] = quantise(v);
                }
            }
            let column: Vec<Level> = (0..m)
                .map(|j| state.bounds[j * state.width + slot])
                .collect();
            assert_eq!(column, expected, "slot {slot}");
        }
    }

    /// Runs bounded to very few entries (refilled all the time) give the
    /// reference merges: the bound changes the memory, not the result.
    #[test]
    fn bounded_runs_give_the_reference_result() {
        let mut rng = Xorshift(21);
        for case in 0..40 {
            let p = random_case(&mut rng, case, (2, 70), (1, 150), [0.05, 0.3, 0.8]);
            let n = p.n_points();
            let expected = reference::t_linkage(&p, 0);
            for capacity in [1, 2, 3, 7, RUN_CAPACITY] {
                // Borrowing the matrix, and consuming it (rows merged in place).
                for state in [ContinuousState::new(&p), ContinuousState::owning(p.clone())] {
                    let merges = agglomerate(state, capacity);
                    assert_eq!(
                        labels_from_merges(n, merges, SizeRule::MinSize, 0),
                        expected,
                        "case {case}, capacity {capacity}"
                    );
                }
            }
        }
    }

    /// At a realistic size the bounded heap gives the merges of the
    /// unbounded one (every pair kept: the implementation before the bound).
    #[test]
    fn bounded_runs_equal_the_unbounded_heap_at_large_n() {
        let mut rng = Xorshift(5);
        let p = random_matrix(&mut rng, 900, 250, 0.2);
        let unbounded = agglomerate(ContinuousState::new(&p), usize::MAX);
        assert!(unbounded.len() > 800);
        for capacity in [RUN_CAPACITY, 4] {
            assert_eq!(
                agglomerate(ContinuousState::new(&p), capacity),
                unbounded,
                "capacity {capacity}"
            );
        }
    }

    #[test]
    fn exact_dot_is_the_ordered_sum() {
        let mut rng = Xorshift(3);
        let p = random_matrix(&mut rng, 2, 500, 0.5);
        let (pi, pv) = p.row_support(0);
        let (qi, qv) = p.row_support(1);
        assert_eq!(
            exact_dot(pi, pv, qi, qv).to_bits(),
            crate::ordered_dot(&p.row(0), &p.row(1)).to_bits()
        );
    }
}
