//! The agglomeration shared by T-Linkage and J-Linkage (method.md steps 8–9):
//! a min-heap of pair distances with lazy deletion, and the final labelling.

use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::cmp::Ordering;
use std::collections::BinaryHeap;
use std::ops::Range;

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

/// Result of a clustering (method.md steps 8–9).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Clustering {
    /// One label per point: `0..clusters_after_filter` for the clusters with
    /// at least `min_cluster_size` points, numbered in ascending order of
    /// their cluster id (their smallest point index); −1 for the points of
    /// smaller clusters (outliers).
    pub labels: Vec<i32>,
    /// Number of clusters when the agglomeration stopped.
    pub clusters_before_filter: usize,
    /// Number of clusters with at least `min_cluster_size` points.
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
    /// `(i, k, candidate)` for the pairs with candidate `d < 1` only.
    fn initial_distances(&self, rows: Range<usize>, out: &mut Vec<(u32, u32, Candidate)>);
    /// The exact distance between the active clusters `i` and `k`.
    fn exact_distance(&mut self, i: usize, k: usize) -> f64;
    /// Merges cluster `removed` into `kept` (`kept < removed`; `active`
    /// already marks `removed` inactive), then appends the distances (or
    /// lower bounds) from the merged cluster to every other active cluster
    /// `k` as `(k, candidate)`, for the candidates with `d < 1` only.
    fn merge(
        &mut self,
        kept: usize,
        removed: usize,
        active: &[bool],
        out: &mut Vec<(u32, Candidate)>,
    );
}

/// An entry of the run of cluster `owner`: the pair `(owner, other)` at
/// distance (or lower bound) `d`, computed when `other` had version
/// `tag >> 1`; bit 0 of `tag` says whether `d` is exact.
#[derive(Debug, Clone, Copy)]
struct RunEntry {
    d: f64,
    other: u32,
    tag: u32,
}

impl RunEntry {
    fn new(d: f64, other: u32, other_version: u32, exact: bool) -> Self {
        Self {
            d,
            other,
            tag: other_version << 1 | u32::from(exact),
        }
    }

    fn other_version(&self) -> u32 {
        self.tag >> 1
    }

    fn exact(&self) -> bool {
        self.tag & 1 == 1
    }

    /// Within one owner's run the pair key `(d, min(owner, other),
    /// max(owner, other))` orders like `(d, other)`.
    fn key_cmp(&self, other: &Self) -> Ordering {
        self.d
            .total_cmp(&other.d)
            .then(self.other.cmp(&other.other))
            .then(self.tag.cmp(&other.tag))
    }
}

impl PartialEq for RunEntry {
    fn eq(&self, other: &Self) -> bool {
        self.key_cmp(other) == Ordering::Equal
    }
}

impl Eq for RunEntry {}

impl PartialOrd for RunEntry {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for RunEntry {
    /// Reversed: `BinaryHeap` is a max-heap and we pop the smallest.
    fn cmp(&self, other: &Self) -> Ordering {
        other.key_cmp(self)
    }
}

/// The smallest entry of the run of `owner` (at version `owner_version`),
/// keyed by the pair `(d, i, j)`, `i < j`.
#[derive(Debug, Clone, Copy)]
struct Head {
    d: f64,
    i: u32,
    j: u32,
    owner: u32,
    owner_version: u32,
}

impl Head {
    fn key_cmp(&self, other: &Self) -> Ordering {
        self.d
            .total_cmp(&other.d)
            .then(self.i.cmp(&other.i))
            .then(self.j.cmp(&other.j))
            .then(self.owner.cmp(&other.owner))
            .then(self.owner_version.cmp(&other.owner_version))
    }
}

impl PartialEq for Head {
    fn eq(&self, other: &Self) -> bool {
        self.key_cmp(other) == Ordering::Equal
    }
}

impl Eq for Head {}

impl PartialOrd for Head {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Head {
    fn cmp(&self, other: &Self) -> Ordering {
        other.key_cmp(self)
    }
}

/// Rows of the initial pair distances handled by one parallel task.
pub(crate) const ROWS_PER_TASK: usize = 8;

/// The min-heap of pair entries with lazy deletion.
///
/// It is kept as a two-level heap: every entry belongs to the *run* of the
/// cluster whose merge (or initial row) produced it — a small min-heap of
/// the entries `(owner, other)` — and a heap of *heads* holds the smallest
/// entry of every run. Popping the smallest head pops the smallest entry of
/// all, ordered by `(d, i, j)` exactly as one flat heap would. When a
/// cluster changes, every entry of its run is stale at once, so its run is
/// discarded whole instead of entry by entry; this only changes how fast
/// stale entries are discarded, not which entry is the smallest valid one.
struct PairHeap {
    runs: Vec<BinaryHeap<RunEntry>>,
    heads: BinaryHeap<Head>,
}

impl PairHeap {
    fn push_head(&mut self, owner: usize, owner_version: u32) {
        if let Some(top) = self.runs[owner].peek() {
            let (i, j) = if (top.other as usize) < owner {
                (top.other, owner as u32)
            } else {
                (owner as u32, top.other)
            };
            self.heads.push(Head {
                d: top.d,
                i,
                j,
                owner: owner as u32,
                owner_version,
            });
        }
    }

    fn replace_run(&mut self, owner: usize, owner_version: u32, entries: Vec<RunEntry>) {
        self.runs[owner] = BinaryHeap::from(entries);
        self.push_head(owner, owner_version);
    }
}

/// Agglomerative clustering with a lazy-deletion min-heap (method.md step 8,
/// thesis Section 6.3), then the size filter (step 9).
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
/// algorithm would pop, and the merges are identical.
///
/// The initial distances are computed in parallel, one task per block of
/// rows, and collected in row order, so the result does not depend on the
/// number of threads.
pub(crate) fn agglomerate<S: AgglomerationState>(
    mut state: S,
    min_cluster_size: usize,
) -> Clustering {
    let n = state.n_clusters();
    let rows: Vec<Vec<RunEntry>> = (0..n.div_ceil(ROWS_PER_TASK))
        .into_par_iter()
        .flat_map_iter(|block| {
            let rows = block * ROWS_PER_TASK..((block + 1) * ROWS_PER_TASK).min(n);
            let mut pairs = Vec::new();
            state.initial_distances(rows.clone(), &mut pairs);
            let mut runs = vec![Vec::new(); rows.len()];
            for (i, k, c) in pairs {
                runs[i as usize - rows.start].push(RunEntry::new(c.d, k, 0, c.exact));
            }
            runs
        })
        .collect();
    let mut heap = PairHeap {
        runs: vec![BinaryHeap::new(); n],
        heads: BinaryHeap::with_capacity(n),
    };
    for (i, run) in rows.into_iter().enumerate() {
        heap.replace_run(i, 0, run);
    }

    let mut active = vec![true; n];
    let mut version = vec![0u32; n];
    let mut merges = Vec::new();
    let mut fresh = Vec::new();
    while let Some(head) = heap.heads.pop() {
        let owner = head.owner as usize;
        if !active[owner] || version[owner] != head.owner_version {
            continue; // the whole run is stale
        }
        let entry = heap.runs[owner]
            .pop()
            .expect("a live head is its run's top");
        let other = entry.other as usize;
        let valid = active[other] && version[other] == entry.other_version();
        if !(valid && entry.exact()) {
            if valid {
                let d = state.exact_distance(owner, other);
                debug_assert!(d >= entry.d, "lower bound {} above distance {d}", entry.d);
                if d < 1.0 {
                    heap.runs[owner].push(RunEntry::new(d, entry.other, version[other], true));
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
        merges.push(Merge {
            kept: i,
            removed: j,
            distance: entry.d,
        });
        fresh.clear();
        state.merge(i, j, &active, &mut fresh);
        heap.runs[j] = BinaryHeap::new();
        let run = fresh
            .iter()
            .map(|&(k, c)| RunEntry::new(c.d, k, version[k as usize], c.exact))
            .collect();
        heap.replace_run(i, version[i], run);
    }
    labels_from_merges(n, merges, min_cluster_size)
}

/// Labels from the merge sequence (method.md step 9): each point belongs to
/// the surviving cluster its merges lead to; clusters are numbered in
/// ascending order of surviving id; clusters smaller than
/// `min_cluster_size` get −1.
pub(crate) fn labels_from_merges(
    n: usize,
    merges: Vec<Merge>,
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
    let mut new_id = vec![-1i32; n];
    let mut clusters_before_filter = 0;
    let mut clusters_after_filter = 0;
    for c in 0..n {
        if size[c] == 0 {
            continue;
        }
        clusters_before_filter += 1;
        if size[c] >= min_cluster_size {
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
