#![warn(missing_docs)]
//! The clustering phase of Algorithm 1 (method.md steps 7–9; thesis Sections
//! 5.2.4 and 6.3): preference matrices and T-Linkage / J-Linkage.
//!
//! The crate knows nothing of geometry: its input is an N × M matrix of
//! residuals `r_ij` of point i to hypothesis j (squared Sampson distances in
//! the pipeline) with a threshold τ, or the preference matrix itself.
//!
//! * [`preference()`] / [`PreferenceMatrix`]: continuous preferences
//!   `φ_ij = exp(−r_ij / τ)` if `r_ij ≤ 5τ`, else 0 (Eq. 38).
//! * [`tanimoto_distance`]: Eq. 39; [`jaccard_distance`] for J-Linkage.
//! * [`t_linkage`]: agglomerative clustering, element-wise minimum merge
//!   (Eq. 40), lazy-deletion min-heap (Section 6.3), stop at `d ≥ 1`;
//!   clusters smaller than `min_cluster_size` become outliers (label −1).
//! * [`j_linkage`]: the same with binary preferences `r ≤ τ`, Jaccard
//!   distance and intersection merge.
//! * [`reference`](mod@reference): plain O(N³) versions of both, for tests and benchmarks.
//!
//! Results are deterministic and independent of the rayon thread count; the
//! labels are exactly those of the plain definition (see [`distance`] for
//! the arithmetic).
//!
//! ```
//! use clustering::{ClusteringParams, PreferenceBuilder};
//! let params = ClusteringParams { min_cluster_size: 2, ..Default::default() };
//! // 4 points, τ = 1; hypotheses 0 and 1 fit points {0, 1}, hypothesis 2 fits {2, 3}.
//! let mut builder = params.preference_builder(4, 1.0).unwrap();
//! builder.push_residuals(&[0.0, 0.1, 50.0, 60.0]).unwrap();
//! builder.push_residuals(&[0.2, 0.0, 40.0, 70.0]).unwrap();
//! builder.push_residuals(&[30.0, 20.0, 0.0, 0.3]).unwrap();
//! let clustering = params.cluster(&builder.finish());
//! assert_eq!(clustering.labels, vec![0, 0, 1, 1]);
//! ```

pub mod distance;
pub mod error;
mod jlinkage;
mod linkage;
pub mod preference;
pub mod reference;
mod tlinkage;

pub use distance::{
    jaccard_distance, ordered_dot, tanimoto_distance, tanimoto_distance_dense,
    TANIMOTO_MIN_DENOMINATOR,
};
pub use error::ClusteringError;
pub use jlinkage::j_linkage;
pub use linkage::{Clustering, Merge};
pub use preference::{
    binary_preference, preference, BinaryPreferenceMatrix, Linkage, PreferenceBuilder,
    PreferenceMatrix, Preferences, PREFERENCE_CUTOFF,
};
pub use tlinkage::t_linkage;

use serde::{Deserialize, Serialize};

/// Default of [`ClusteringParams::min_cluster_size`] (method.md step 9).
pub const DEFAULT_MIN_CLUSTER_SIZE: usize = 8;

/// Parameters of the clustering phase.
///
/// Serde defaults (a missing field takes its default):
/// * `linkage = "t-linkage"` — [`Linkage::TLinkage`] (Eq. 38–40); `"j-linkage"`
///   selects binary preferences and the Jaccard distance;
/// * `min_cluster_size = 8` — clusters with fewer points are outliers (step 9).
///
/// ```
/// use clustering::{ClusteringParams, Linkage};
/// let p: ClusteringParams = serde_json::from_str(r#"{"linkage": "j-linkage"}"#).unwrap();
/// assert_eq!(p.linkage, Linkage::JLinkage);
/// assert_eq!(p.min_cluster_size, 8);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ClusteringParams {
    /// Which agglomeration to run (default T-Linkage).
    pub linkage: Linkage,
    /// Clusters with fewer points than this get label −1 (default 8).
    pub min_cluster_size: usize,
}

impl Default for ClusteringParams {
    fn default() -> Self {
        Self {
            linkage: Linkage::TLinkage,
            min_cluster_size: DEFAULT_MIN_CLUSTER_SIZE,
        }
    }
}

impl ClusteringParams {
    /// A column-at-a-time builder of the preferences of `self.linkage` for
    /// `n_points` points and threshold τ (`thr_px²`).
    pub fn preference_builder(
        &self,
        n_points: usize,
        tau: f64,
    ) -> Result<PreferenceBuilder, ClusteringError> {
        PreferenceBuilder::new(self.linkage, n_points, tau)
    }

    /// Clusters `preferences` with the linkage they were built for and the
    /// size filter `self.min_cluster_size`.
    pub fn cluster(&self, preferences: &Preferences) -> Clustering {
        cluster(preferences, self.min_cluster_size)
    }
}

/// T-Linkage of continuous preferences, J-Linkage of binary ones, then the
/// size filter (method.md steps 8–9).
pub fn cluster(preferences: &Preferences, min_cluster_size: usize) -> Clustering {
    match preferences {
        Preferences::Continuous(p) => t_linkage(p, min_cluster_size),
        Preferences::Binary(b) => j_linkage(b, min_cluster_size),
    }
}
