//! The min-heap of pair distances of the agglomeration (thesis Section 6.3)
//! with lazy deletion, kept as a two-level heap of bounded runs so that its
//! memory is O(N · capacity) instead of O(N²).

use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// Entries kept per run by default: the smallest ones; the others are
/// recomputed on demand (see [`PairHeap`]).
pub(crate) const RUN_CAPACITY: usize = 64;

/// An entry of the run of cluster `owner`: the pair `(owner, other)` at
/// distance (or lower bound) `d`, computed when `other` had version
/// `tag >> 2`; bit 0 of `tag` says whether `d` is exact, bit 1 whether it
/// is the exact distance of a popped lower bound (a *refined* entry: a
/// recomputation of the run would give its pair the lower bound again, so
/// it is never dropped, see [`PairHeap`]).
#[derive(Debug, Clone, Copy)]
pub(crate) struct RunEntry {
    pub(crate) d: f64,
    pub(crate) other: u32,
    tag: u32,
}

impl RunEntry {
    pub(crate) fn new(d: f64, other: u32, other_version: u32, exact: bool) -> Self {
        Self {
            d,
            other,
            tag: other_version << 2 | u32::from(exact),
        }
    }

    /// The exact distance `d` of a pair whose lower bound was popped.
    pub(crate) fn refined(d: f64, other: u32, other_version: u32) -> Self {
        Self {
            d,
            other,
            tag: other_version << 2 | 0b11,
        }
    }

    pub(crate) fn other_version(&self) -> u32 {
        self.tag >> 2
    }

    pub(crate) fn exact(&self) -> bool {
        self.tag & 1 == 1
    }

    fn is_refined(&self) -> bool {
        self.tag & 2 == 2
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
pub(crate) struct Head {
    d: f64,
    i: u32,
    j: u32,
    pub(crate) owner: u32,
    pub(crate) owner_version: u32,
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

impl RunEntry {
    /// The pair order within one owner's run, `(d, other)`, ignoring the
    /// version and exactness.
    fn pair_cmp(&self, other: &Self) -> Ordering {
        self.d
            .total_cmp(&other.d)
            .then(self.other.cmp(&other.other))
    }

    /// Whether the entry's pair key is at least that of `floor`.
    pub(crate) fn not_below(&self, floor: &Self) -> bool {
        self.pair_cmp(floor) != Ordering::Less
    }
}

/// What the top of one run holds: an entry, or its floor (the run must be
/// refilled with [`PairHeap::take_run`] before anything else of it is used).
pub(crate) enum RunTop {
    /// The smallest entry of the run, removed from it.
    Entry(RunEntry),
    /// The run's floor is below every entry it holds.
    Refill,
}

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
///
/// *Bounded runs.* A run keeps only its `capacity` smallest entries, besides
/// its refined ones; the smallest entry dropped is kept as the run's *floor*
/// and competes in the heap of heads like an entry. Every dropped pair has a
/// key `≥` the floor, so as long as the floor is not the smallest head, no
/// dropped pair can be the next merge. When it is, the owner's entries are
/// recomputed from its current vector and those `≥` the floor refill the run
/// (the pairs below the floor are still in the run, were merged, or changed
/// on the partner's side, whose own run then holds them). This needs every
/// dropped pair to come back with the key it was dropped with, and a
/// recomputation gives a pair its lower bound, bit for bit as before, not
/// the exact distance a refined entry holds (which can be above the floor
/// while its bound is below): refined entries are therefore never dropped.
/// There is at most one per lower bound popped from the run. The heap thus
/// holds `O(N · capacity)` entries instead of up to N²/2, and the merges are
/// unchanged.
pub(crate) struct PairHeap {
    runs: Vec<BinaryHeap<RunEntry>>,
    floors: Vec<Option<RunEntry>>,
    pub(crate) heads: BinaryHeap<Head>,
    capacity: usize,
    /// Scratch for [`PairHeap::replace_run`].
    scratch: Vec<RunEntry>,
}

impl PairHeap {
    /// An empty heap for `n` clusters whose runs keep at most `capacity`
    /// entries (at least 1).
    pub(crate) fn new(n: usize, capacity: usize) -> Self {
        Self {
            runs: vec![BinaryHeap::new(); n],
            floors: vec![None; n],
            heads: BinaryHeap::with_capacity(n),
            capacity: capacity.max(1),
            scratch: Vec::new(),
        }
    }

    /// The refined entries of `entries` and the `capacity` smallest of the
    /// others, in a vector of their exact size, and the smallest of the rest;
    /// `entries` is left empty (it is a scratch buffer: runs never keep a
    /// buffer grown to N entries, whose shrinking in place would fragment
    /// the allocator's memory).
    pub(crate) fn truncate(
        entries: &mut Vec<RunEntry>,
        capacity: usize,
    ) -> (Vec<RunEntry>, Option<RunEntry>) {
        // Refined entries first: they are kept whatever their key.
        let mut refined = 0;
        for k in 0..entries.len() {
            if entries[k].is_refined() {
                entries.swap(refined, k);
                refined += 1;
            }
        }
        let keep = refined + capacity;
        let floor = if entries.len() > keep {
            entries[refined..].select_nth_unstable_by(capacity, RunEntry::key_cmp);
            let floor = entries[keep];
            entries.truncate(keep);
            Some(floor)
        } else {
            None
        };
        let kept = entries.as_slice().to_vec();
        entries.clear();
        (kept, floor)
    }

    /// Pushes the head of `owner`'s run: its smallest entry or its floor.
    pub(crate) fn push_head(&mut self, owner: usize, owner_version: u32) {
        let top = match (self.runs[owner].peek(), &self.floors[owner]) {
            (Some(top), Some(floor)) => Some(if floor.key_cmp(top) == Ordering::Less {
                floor
            } else {
                top
            }),
            (top, floor) => top.or(floor.as_ref()),
        };
        if let Some(top) = top {
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

    /// Replaces `owner`'s run by `entries` (truncated to the capacity) and
    /// pushes its head.
    pub(crate) fn replace_run(
        &mut self,
        owner: usize,
        owner_version: u32,
        entries: impl IntoIterator<Item = RunEntry>,
    ) {
        self.scratch.extend(entries);
        let (run, floor) = Self::truncate(&mut self.scratch, self.capacity);
        self.floors[owner] = floor;
        self.runs[owner] = BinaryHeap::from(run);
        self.push_head(owner, owner_version);
    }

    /// Sets `owner`'s initial run (already truncated) and floor, and pushes
    /// its head.
    pub(crate) fn set_run(
        &mut self,
        owner: usize,
        entries: Vec<RunEntry>,
        floor: Option<RunEntry>,
    ) {
        self.floors[owner] = floor;
        self.runs[owner] = BinaryHeap::from(entries);
        self.push_head(owner, 0);
    }

    /// Pushes an entry onto `owner`'s run (its head is not pushed).
    pub(crate) fn push(&mut self, owner: usize, entry: RunEntry) {
        self.runs[owner].push(entry);
    }

    /// Drops `owner`'s run.
    pub(crate) fn clear(&mut self, owner: usize) {
        self.runs[owner] = BinaryHeap::new();
        self.floors[owner] = None;
    }

    /// Removes the smallest entry of `owner`'s run, unless its floor comes
    /// first. Call only for a run whose head was just popped.
    pub(crate) fn pop_run(&mut self, owner: usize) -> RunTop {
        let floor_first = match (self.runs[owner].peek(), &self.floors[owner]) {
            (Some(top), Some(floor)) => floor.key_cmp(top) == Ordering::Less,
            (None, floor) => floor.is_some(),
            (Some(_), None) => false,
        };
        if floor_first {
            return RunTop::Refill;
        }
        RunTop::Entry(
            self.runs[owner]
                .pop()
                .expect("a live head is its run's top or its floor"),
        )
    }

    /// Empties `owner`'s run for a refill: its remaining entries and its floor.
    pub(crate) fn take_run(&mut self, owner: usize) -> (Vec<RunEntry>, Option<RunEntry>) {
        let floor = self.floors[owner].take();
        (std::mem::take(&mut self.runs[owner]).into_vec(), floor)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Truncation keeps every refined entry, however large its key, and the
    /// `capacity` smallest of the others; the floor is the smallest other
    /// entry dropped.
    #[test]
    fn truncation_never_drops_refined_entries() {
        let mut entries = vec![
            RunEntry::refined(0.9, 1, 0),
            RunEntry::new(0.2, 2, 0, false),
            RunEntry::new(0.5, 3, 0, false),
            RunEntry::refined(0.8, 4, 0),
            RunEntry::new(0.4, 5, 0, false),
            RunEntry::new(0.3, 6, 0, false),
        ];
        let (kept, floor) = PairHeap::truncate(&mut entries, 2);
        let mut others: Vec<u32> = kept.iter().map(|e| e.other).collect();
        others.sort_unstable();
        assert_eq!(others, [1, 2, 4, 6]);
        assert_eq!(floor.map(|f| f.other), Some(5));
        assert!(entries.is_empty());
        // Nothing to drop: no floor.
        let mut few = vec![RunEntry::refined(0.9, 1, 0), RunEntry::new(0.2, 2, 0, true)];
        let (kept, floor) = PairHeap::truncate(&mut few, 1);
        assert_eq!((kept.len(), floor.is_none()), (2, true));
    }
}
