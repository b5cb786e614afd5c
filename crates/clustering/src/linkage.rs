//! The agglomeration shared by T-Linkage and J-Linkage (docs/method.md steps 8–9):
//! a min-heap of pair distances with lazy deletion, and the final labelling.

use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::ops::Range;

use crate::heap::{PairHeap, RunEntry, RunTop};
use crate::SizeRule;

/// One step of the agglomeration: cluster `removed` was merged into cluster
/// `kept` at distance `distance`.
///
/// A cluster's id is the smallest point index it contains (the merged
/// cluster keeps the smaller id), so `kept < removed`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Merge {
    /// Id of the surviving cluster (the smaller id of the pair).
    pub kept: usize,
    /// Id of the cluster merged into `kept`; it is inactive afterwards.
    pub removed: usize,
    /// Distance between the two clusters when they were merged (Eq. 39 for
    /// T-Linkage, Jaccard for J-Linkage), in `[0, 1)`.
    pub distance: f64,
}

/// Result of a clustering (docs/method.md steps 8–9).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Clustering {
    /// One label per point: `0..clusters_after_filter` for the clusters kept
    /// by the size rule (by default those with at least `min_cluster_size`
    /// points; see [`crate::SizeRule`]), numbered in ascending order of
    /// their cluster id (their smallest point index); −1 for the points of
    /// smaller clusters (outliers).
    pub labels: Vec<i32>,
    /// Number of clusters when the agglomeration stopped.
    pub clusters_before_filter: usize,
    /// Number of clusters kept by the size rule (by default those with at
    /// least `min_cluster_size` points).
    pub clusters_after_filter: usize,
    /// The merges in the order they were made.
    pub merges: Vec<Merge>,
}

/// A distance handed to the agglomeration: either exact, or a certified
/// lower bound of the exact distance (which is then computed only if the
/// bound reaches the top of the heap).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Candidate {
    pub d: f64,
    pub exact: bool,
}

/// Per-linkage cluster representation driven by [`agglomerate`].
///
/// Cluster ids are point indices `0..n`; a merged cluster keeps the smaller id.
pub(crate) trait AgglomerationState: Sync {
    /// Number of points N (initial singleton clusters).
    fn n_clusters(&self) -> usize;
    /// Distances (or lower bounds) between the initial clusters `i` and `k`
    /// for every `i` in `rows` and every `k` in `i + 1..n`; appends
    /// `(i, k, candidate)` for the pairs with candidate `d < 1` only, in
    /// ascending order of `i`.
    fn initial_distances(&self, rows: Range<usize>, out: &mut Vec<(u32, u32, Candidate)>);
    /// The exact distance between the active clusters `i` and `k`.
    fn exact_distance(&mut self, i: usize, k: usize) -> f64;
    /// Merges cluster `merge.removed` into `merge.kept` (`kept < removed`;
    /// `active` already marks `removed` inactive), then appends the
    /// distances (or lower bounds) from the merged cluster to every other
    /// active cluster `k` as `(k, candidate)`, for the candidates with
    /// `d < 1` only (the same as [`AgglomerationState::candidates`] of
    /// `kept` after the merge).
    fn merge(&mut self, merge: &Merge, active: &[bool], out: &mut Vec<(u32, Candidate)>);
    /// Appends the distances (or lower bounds) from the active cluster
    /// `cluster` to every other active cluster `k` as `(k, candidate)`, for
    /// the candidates with `d < 1` only.
    fn candidates(&mut self, cluster: usize, active: &[bool], out: &mut Vec<(u32, Candidate)>);
}

/// Rows of the initial pair distances handled by one parallel task.
pub(crate) const ROWS_PER_TASK: usize = 8;

/// Agglomerative clustering with a lazy-deletion min-heap (docs/method.md step 8,
/// thesis Section 6.3); returns the merges (step 9 is [`labels_from_merges`]).
///
/// 1. Every pair `i < j` of points with `d < 1` enters the heap; entries are
///    ordered by `d`, then `i`, then `j`.
/// 2. Pop the smallest entry. Skip it if cluster `i` or `j` is inactive, or
///    if either has been merged since the entry was pushed (each cluster
///    carries a version counter, incremented when it absorbs another; the
///    entry records the versions it was computed at).
/// 3. Merge `j` into `i` (the smaller id survives), mark `j` inactive,
///    recompute the distances from `i` to all active clusters and push those
///    `< 1`.
/// 4. Stop when the heap is empty. Entries with `d ≥ 1` are never pushed:
///    popping a valid one would end the loop anyway, since every remaining
///    valid entry would be `≥ 1` too.
///
/// A state may push a certified lower bound instead of a distance (with the
/// same pair key). When a valid bound is popped, the exact distance is
/// computed and pushed back (if `< 1`); since it is `≥` the bound, every
/// entry popped as the smallest *exact* valid entry is the one the plain
/// algorithm would pop, and the merges are identical. The heap keeps at
/// most `run_capacity` entries per cluster and recomputes the others when
/// they could be next ([`PairHeap`]), which changes the memory, not the
/// merges.
///
/// The initial distances are computed in parallel, one task per block of
/// rows, and collected in row order, so the result does not depend on the
/// number of threads.
pub(crate) fn agglomerate<S: AgglomerationState>(state: S, run_capacity: usize) -> Vec<Merge> {
    agglomerate_until(state, run_capacity, &|| false)
}

/// How many heap pops pass between two calls of [`agglomerate_until`]'s
/// `stop`.
const STOP_CADENCE: usize = 64;

/// [`agglomerate`], ending early (with the merges so far) once `stop`,
/// called every [`STOP_CADENCE`] heap pops, returns true.
pub(crate) fn agglomerate_until<S: AgglomerationState>(
    mut state: S,
    run_capacity: usize,
    stop: &dyn Fn() -> bool,
) -> Vec<Merge> {
    let n = state.n_clusters();
    let mut heap = initial_heap(&state, run_capacity.max(1));
    let mut active = vec![true; n];
    let mut version = vec![0u32; n];
    let mut merges = Vec::new();
    let mut fresh = Vec::new();
    let mut pops = 0usize;
    while let Some(head) = heap.heads.pop() {
        pops += 1;
        if pops % STOP_CADENCE == 0 && stop() {
            break;
        }
        let owner = head.owner as usize;
        if !active[owner] || version[owner] != head.owner_version {
            continue; // the whole run is stale
        }
        let entry = match heap.pop_run(owner) {
            RunTop::Entry(entry) => entry,
            RunTop::Refill => {
                refill(&mut state, &mut heap, owner, &active, &version, &mut fresh);
                continue;
            }
        };
        let other = entry.other as usize;
        let valid = active[other] && version[other] == entry.other_version();
        if !(valid && entry.exact()) {
            if valid {
                let d = state.exact_distance(owner, other);
                debug_assert!(d >= entry.d, "lower bound {} above distance {d}", entry.d);
                if d < 1.0 {
                    heap.push(owner, RunEntry::refined(d, entry.other, version[other]));
                }
            }
            heap.push_head(owner, version[owner]);
            continue;
        }
        if entry.d >= 1.0 {
            break;
        }
        let (i, j) = if owner < other {
            (owner, other)
        } else {
            (other, owner)
        };
        active[j] = false;
        version[i] += 1;
        let merge = Merge {
            kept: i,
            removed: j,
            distance: entry.d,
        };
        fresh.clear();
        state.merge(&merge, &active, &mut fresh);
        merges.push(merge);
        heap.clear(j);
        let run = fresh
            .iter()
            .map(|&(k, c)| RunEntry::new(c.d, k, version[k as usize], c.exact));
        heap.replace_run(i, version[i], run);
    }
    merges
}

/// The heap before the first merge: each point's candidate pairs to the
/// later points (their initial distances, computed in parallel blocks of
/// rows), truncated to `capacity` entries per run.
fn initial_heap<S: AgglomerationState>(state: &S, capacity: usize) -> PairHeap {
    let n = state.n_clusters();
    let blocks: Vec<Vec<(Vec<RunEntry>, Option<RunEntry>)>> = (0..n.div_ceil(ROWS_PER_TASK))
        .into_par_iter()
        .map_init(
            || (Vec::new(), Vec::new()),
            |(pairs, scratch), block| {
                let rows = block * ROWS_PER_TASK..((block + 1) * ROWS_PER_TASK).min(n);
                pairs.clear();
                state.initial_distances(rows.clone(), pairs);
                // The pairs come in row order: each row's are a contiguous run.
                let mut rest = pairs.as_slice();
                rows.map(|i| {
                    let count = rest.iter().take_while(|p| p.0 as usize == i).count();
                    let (row, tail) = rest.split_at(count);
                    rest = tail;
                    scratch.extend(
                        row.iter()
                            .map(|&(_, k, c)| RunEntry::new(c.d, k, 0, c.exact)),
                    );
                    PairHeap::truncate(scratch, capacity)
                })
                .collect()
            },
        )
        .collect();
    let mut heap = PairHeap::new(n, capacity);
    for (i, (run, floor)) in blocks.into_iter().flatten().enumerate() {
        heap.set_run(i, run, floor);
    }
    heap
}

/// Refills the run of `owner` whose floor reached the top of the heap: its
/// candidates to the active clusters it was paired with (every later point
/// for an initial row, every other cluster after a merge) whose pair key is
/// not below the floor, with the entries the run still holds.
fn refill<S: AgglomerationState>(
    state: &mut S,
    heap: &mut PairHeap,
    owner: usize,
    active: &[bool],
    version: &[u32],
    fresh: &mut Vec<(u32, Candidate)>,
) {
    let (entries, floor) = heap.take_run(owner);
    let floor = floor.expect("a run is refilled only when it has a floor");
    fresh.clear();
    state.candidates(owner, active, fresh);
    let initial_row = version[owner] == 0;
    let recomputed = fresh
        .iter()
        .filter(|&&(k, _)| !initial_row || k as usize > owner)
        .map(|&(k, c)| RunEntry::new(c.d, k, version[k as usize], c.exact))
        .filter(|e| e.not_below(&floor));
    heap.replace_run(owner, version[owner], entries.into_iter().chain(recomputed));
}

/// Labels from the merge sequence (docs/method.md step 9): each point belongs to
/// the surviving cluster its merges lead to; clusters are numbered in
/// ascending order of surviving id; clusters smaller than the minimum size
/// of `rule` ([`SizeRule::min_size`], at least `min_cluster_size`) get −1.
pub(crate) fn labels_from_merges(
    n: usize,
    merges: Vec<Merge>,
    rule: SizeRule,
    min_cluster_size: usize,
) -> Clustering {
    let mut parent: Vec<usize> = (0..n).collect();
    for merge in &merges {
        parent[merge.removed] = merge.kept;
    }
    // `kept < removed`, so every parent precedes its child: one forward pass
    // resolves every point to its surviving cluster.
    let mut root = vec![0usize; n];
    for p in 0..n {
        root[p] = if parent[p] == p { p } else { root[parent[p]] };
    }
    let mut size = vec![0usize; n];
    for &r in &root {
        size[r] += 1;
    }
    let min_size = rule.min_size(n, min_cluster_size);
    let mut new_id = vec![-1i32; n];
    let mut clusters_before_filter = 0;
    let mut clusters_after_filter = 0;
    for c in 0..n {
        if size[c] == 0 {
            continue;
        }
        clusters_before_filter += 1;
        if size[c] >= min_size {
            new_id[c] = clusters_after_filter as i32;
            clusters_after_filter += 1;
        }
    }
    Clustering {
        labels: root.iter().map(|&r| new_id[r]).collect(),
        clusters_before_filter,
        clusters_after_filter,
        merges,
    }
}
