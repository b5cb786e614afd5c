//! The memory the clustering phase needs, so that a problem too large for a
//! budget is refused at once ([`crate::ClusteringParams::check_memory`])
//! instead of failing after minutes of work.
//!
//! The model counts the largest structures at their sizes (bytes), for the
//! pipeline's path: preferences built one point at a time
//! ([`crate::Preferences::from_residual_rows`], rows at exactly their size)
//! and clustered by [`crate::ClusteringParams::try_cluster_owned`] (merged
//! vectors written over the rows):
//!
//! | structure | T-Linkage | J-Linkage |
//! |---|---|---|
//! | preferences | `12 · nnz` (u32 index + f64 value) | `N · ⌈M/64⌉ · 8`, ×2 (matrix, cluster copy) |
//! | bound matrix | `M · ⌈N⌉₁₆` (u8, hypothesis-major) | — |
//! | heap | `N · (RUN_CAPACITY + 1) · 16` | same |
//! | per-point scratch | `64 · N` | same |
//!
//! with `nnz = density · N · M` the non-zero preferences. The other paths
//! need more: the one-hypothesis-at-a-time [`crate::PreferenceBuilder`]'s
//! rows grow by doubling (up to `12 · nnz` more, and J-Linkage's builder
//! holds its columns too), and [`crate::ClusteringParams::try_cluster`],
//! which leaves the caller's matrix untouched, copies the merged vectors
//! (up to `12 · nnz` more). It is an estimate of the phase alone (not of
//! the caller's points and hypotheses): on the synthetic scenes of
//! `examples/peak_memory.rs` the whole process's peak resident memory is
//! 3–4 MB above it, the program and the scene's own data (see the crate
//! README).

use crate::heap::RUN_CAPACITY;
use crate::Linkage;

/// Bytes of one non-zero continuous preference: a u32 hypothesis index and
/// an f64 value.
const BYTES_PER_NONZERO: f64 = 12.0;

/// Estimated peak bytes of building the preferences and clustering them,
/// for N points, M hypotheses and a fraction `density ∈ [0, 1]` of non-zero
/// preferences (T-Linkage; J-Linkage ignores it). A density outside
/// `[0, 1]` (or NaN) is taken as 1, the worst case.
///
/// ```
/// use clustering::{required_memory, Linkage};
/// let small = required_memory(Linkage::TLinkage, 5000, 3000, 0.2);
/// let large = required_memory(Linkage::TLinkage, 20_000, 3000, 0.2);
/// assert!(small < 200_000_000 && large > 3 * small);
/// ```
pub fn required_memory(
    linkage: Linkage,
    n_points: usize,
    n_hypotheses: usize,
    density: f64,
) -> u64 {
    let (n, m) = (n_points as f64, n_hypotheses as f64);
    let density = if (0.0..=1.0).contains(&density) {
        density
    } else {
        1.0
    };
    let heap = n * (RUN_CAPACITY as f64 + 1.0) * 16.0;
    let scratch = 64.0 * n;
    let bytes = match linkage {
        Linkage::TLinkage => {
            let nonzeros = density * n * m;
            let preferences = BYTES_PER_NONZERO * nonzeros;
            let bounds = m * (n / 16.0).ceil() * 16.0;
            preferences + bounds + heap + scratch
        }
        Linkage::JLinkage => 2.0 * n * (m / 64.0).ceil() * 8.0 + heap + scratch,
    };
    bytes.ceil() as u64
}
