//! The memory guard of `max_memory_mb = 0` (the default): before drawing a
//! sample, the need of the whole run (hypotheses, preferences, clustering:
//! docs/method.md steps 1–9) is estimated and compared with the memory the
//! machine has available, so that a problem too large is refused with its
//! figures instead of aborting the process when an allocation fails.
//!
//! The available memory is Linux's `MemAvailable` (`/proc/meminfo`, the
//! kernel's estimate of what can be allocated without swapping). Elsewhere,
//! or when the file cannot be read or parsed, there is no automatic bound
//! (the run proceeds as with no guard); an explicit `max_memory_mb` bounds
//! it on every system.

use crate::{MinimalSolver, Params, Sampling, SegmentationError};
use clustering::required_memory;

/// The share of non-zero preferences (and of matches in a minimal
/// solution's consensus set) assumed by the memory checks made before
/// sampling: F hypotheses at `thr_px` 2–3 px give 5–20 % on scenes of
/// several comparable motions. Scenes whose background holds most matches
/// give more (35–70 % on the kitti-real validation scenes); there the
/// check after step 7, at the matrix's own density, is the one that binds.
pub(crate) const ASSUMED_PREFERENCE_DENSITY: f64 = 0.2;

/// Estimated peak bytes of a segmentation, in two parts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MemoryNeed {
    /// Steps 1–3 and the matches: the centred points (all N, and the
    /// clustered subset), labels and residuals (48 bytes per match and per
    /// clustered match); per hypothesis its model, status and inlier set
    /// (`⌈n/64⌉` words of the `n` clustered matches), and, for the
    /// minimal solvers other than the 8-point, the consensus set of each
    /// solution while its batch is refined (20 % of the scored matches,
    /// 8 bytes each); guided sampling's co-inlier kernel (`n² · 8` bytes
    /// and `n · ⌈M/64⌉ · 8` of co-inlier bits).
    pub hypotheses: u64,
    /// Steps 7–8: [`clustering::required_memory`] for the clustered
    /// matches and M hypotheses at 20 % non-zero preferences.
    pub clustering: u64,
}

impl MemoryNeed {
    /// The whole estimate, bytes.
    pub fn total(&self) -> u64 {
        self.hypotheses.saturating_add(self.clustering)
    }
}

/// The estimated need of segmenting `n_matches` matches with `params`
/// ([`MemoryNeed`]); M is `num_samples` (the cap with adaptive sampling).
///
/// ```
/// use segmentation::{memory_need, Params};
/// // Every match clustered: the need grows as N².
/// let params = Params::default().with(|q| q.sampling.cluster_subset = 0);
/// let small = memory_need(1_000, &params).total();
/// let large = memory_need(100_000, &params).total();
/// assert!(small < 100_000_000 && large > 50 * small);
/// ```
pub fn memory_need(n_matches: usize, params: &Params) -> MemoryNeed {
    let (n, m) = (n_matches as f64, params.sampling.num_samples as f64);
    let clustered = params.clustered_matches(n_matches);
    let c = clustered as f64;
    let points = 48.0 * (n + c);
    let words = (c / 64.0).ceil() * 8.0;
    let per_hypothesis = 128.0 + words;
    let consensus = if params.sampling.minimal_solver == MinimalSolver::EightPoint {
        0.0
    } else {
        m * ASSUMED_PREFERENCE_DENSITY * c * 8.0
    };
    let guided = if params.sampling.sampling == Sampling::Guided {
        c * c * 8.0 + c * (m / 64.0).ceil() * 8.0
    } else {
        0.0
    };
    MemoryNeed {
        hypotheses: (points + m * per_hypothesis + consensus + guided).ceil() as u64,
        clustering: required_memory(
            params.clustering.linkage,
            clustered,
            params.sampling.num_samples,
            ASSUMED_PREFERENCE_DENSITY,
        ),
    }
}

/// Refuses, with the figures, a run whose [`memory_need`] exceeds
/// `available` bytes when `max_memory_mb = 0`. An explicit
/// `max_memory_mb` (checked by the clustering, see
/// [`crate::Params::max_memory_mb`]) or an unknown `available` (`None`)
/// passes. A pure function: [`crate::segment`] calls it with
/// [`available_memory`].
pub fn check_available_memory(
    n_matches: usize,
    params: &Params,
    available: Option<u64>,
) -> Result<(), SegmentationError> {
    let Some(available) = available.filter(|_| params.max_memory_mb == 0) else {
        return Ok(());
    };
    let need = memory_need(n_matches, params);
    if need.total() <= available {
        return Ok(());
    }
    let mb = |bytes: u64| bytes.div_ceil(1_000_000);
    Err(SegmentationError::MemoryAvailable {
        n_matches,
        n_clustered: params.clustered_matches(n_matches),
        n_hypotheses: params.sampling.num_samples,
        needed_mb: mb(need.total()),
        hypotheses_mb: mb(need.hypotheses),
        clustering_mb: mb(need.clustering),
        available_mb: available / 1_000_000,
    })
}

/// The memory the machine has available, bytes: `MemAvailable` of
/// `/proc/meminfo` on Linux; `None` elsewhere or when it cannot be read.
pub fn available_memory() -> Option<u64> {
    let meminfo = std::fs::read_to_string("/proc/meminfo").ok()?;
    mem_available(&meminfo)
}

/// The `MemAvailable:  <kB> kB` line of a `/proc/meminfo` text, in bytes.
///
/// ```
/// let text = "MemTotal:  16000000 kB\nMemAvailable:    2048 kB\n";
/// assert_eq!(segmentation::mem_available(text), Some(2_097_152));
/// assert_eq!(segmentation::mem_available("MemTotal: 1 kB\n"), None);
/// ```
pub fn mem_available(meminfo: &str) -> Option<u64> {
    let line = meminfo
        .lines()
        .find_map(|l| l.strip_prefix("MemAvailable:"))?;
    let mut fields = line.split_whitespace();
    let kb: u64 = fields.next()?.parse().ok()?;
    match fields.next() {
        Some("kB") | None => kb.checked_mul(1024),
        Some(_) => None,
    }
}

/// The bound, bytes, of the clustering's check at the preferences' real
/// density: the explicit `max_memory_mb`, else the available memory
/// (`None`: no bound).
pub(crate) fn memory_limit(params: &Params) -> Option<u64> {
    match params.max_memory_mb {
        0 => available_memory(),
        mb => Some(mb.saturating_mul(1_000_000)),
    }
}
