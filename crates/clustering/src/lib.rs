#![warn(missing_docs)]
//! The clustering phase of Algorithm 1 (docs/method.md steps 7–9; thesis Sections
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
//! * [`SizeRule`]: which clusters are kept (step 9) — `min_cluster_size`
//!   alone or a minimum relative to N; [`cluster_with_rule`], [`ClusteringParams::cluster`].
//! * [`required_memory`]: the memory estimate behind
//!   [`ClusteringParams::max_memory_bytes`] and [`ClusteringParams::check_memory`].
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

pub mod dendrogram;
pub mod distance;
pub mod error;
mod heap;
mod jlinkage;
mod linkage;
mod memory;
pub mod preference;
pub mod reference;
mod size_rule;
mod tlinkage;

pub use distance::{
    jaccard_distance, ordered_dot, tanimoto_distance, tanimoto_distance_dense,
    TANIMOTO_MIN_DENOMINATOR,
};
pub use error::ClusteringError;
pub use jlinkage::j_linkage;
pub use linkage::{Clustering, Merge};
pub use memory::required_memory;
pub use preference::{
    binary_preference, preference, BinaryPreferenceMatrix, Linkage, PreferenceBuilder,
    PreferenceMatrix, Preferences, PREFERENCE_CUTOFF,
};
pub use size_rule::SizeRule;
pub use tlinkage::t_linkage;

use serde::{Deserialize, Serialize};

/// Default of [`ClusteringParams::min_cluster_size`] (docs/method.md step 9).
pub const DEFAULT_MIN_CLUSTER_SIZE: usize = 8;

/// Parameters of the clustering phase.
///
/// Serde defaults (a missing field takes its default):
/// * `linkage = "t-linkage"` — [`Linkage::TLinkage`] (Eq. 38–40); `"j-linkage"`
///   selects binary preferences and the Jaccard distance;
/// * `min_cluster_size = 8` — clusters with fewer points are outliers (step 9);
///   a floor under every `size_rule`;
/// * `size_rule = "min-size"` — [`SizeRule::MinSize`], `min_cluster_size`
///   alone; `"largest-gap"` cuts the sorted cluster sizes at their largest
///   ratio (Magri & Fusiello 2014), `{"relative-min": f}` keeps clusters of
///   at least `⌈f · N⌉` points;
/// * `max_memory_bytes = null` — no bound; with a bound,
///   [`ClusteringParams::check_memory`] and [`ClusteringParams::try_cluster`]
///   refuse a problem whose [`required_memory`] exceeds it.
///
/// ```
/// use clustering::{ClusteringParams, Linkage, SizeRule};
/// let p: ClusteringParams = serde_json::from_str(r#"{"linkage": "j-linkage"}"#).unwrap();
/// assert_eq!(p.linkage, Linkage::JLinkage);
/// assert_eq!(p.min_cluster_size, 8);
/// assert_eq!(p.size_rule, SizeRule::MinSize);
/// let p: ClusteringParams = serde_json::from_str(r#"{"size_rule": {"relative-min": 0.01}}"#).unwrap();
/// assert_eq!(p.size_rule, SizeRule::RelativeMin(0.01));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ClusteringParams {
    /// Which agglomeration to run (default T-Linkage).
    pub linkage: Linkage,
    /// Clusters with fewer points than this get label −1 (default 8); the
    /// floor of every [`SizeRule`].
    pub min_cluster_size: usize,
    /// Which clusters are kept (docs/method.md step 9; default
    /// [`SizeRule::MinSize`], `min_cluster_size` alone).
    pub size_rule: SizeRule,
    /// The memory the phase may need, in bytes (default `None`: no bound);
    /// see [`required_memory`].
    pub max_memory_bytes: Option<u64>,
}

impl Default for ClusteringParams {
    fn default() -> Self {
        Self {
            linkage: Linkage::TLinkage,
            min_cluster_size: DEFAULT_MIN_CLUSTER_SIZE,
            size_rule: SizeRule::MinSize,
            max_memory_bytes: None,
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

    /// Clusters `preferences` with the linkage they were built for, then
    /// keeps the clusters of `self.size_rule` (at least
    /// `self.min_cluster_size` points). Neither validates the parameters nor
    /// checks the memory bound: see [`ClusteringParams::try_cluster`].
    pub fn cluster(&self, preferences: &Preferences) -> Clustering {
        cluster_with_rule(preferences, self.size_rule, self.min_cluster_size)
    }

    /// [`ClusteringParams::cluster`] after [`ClusteringParams::validate`] and
    /// [`ClusteringParams::check_memory`] at the matrix's own size and density.
    pub fn try_cluster(&self, preferences: &Preferences) -> Result<Clustering, ClusteringError> {
        self.check_problem(preferences)?;
        Ok(self.cluster(preferences))
    }

    /// [`ClusteringParams::try_cluster`] on preferences it consumes: the
    /// same clustering, but T-Linkage writes each merged vector over the
    /// surviving cluster's row and frees the absorbed one instead of
    /// copying rows, so the phase needs less memory.
    pub fn try_cluster_owned(
        &self,
        preferences: Preferences,
    ) -> Result<Clustering, ClusteringError> {
        let never = || false;
        let clustering = self.try_cluster_owned_until(preferences, &never)?;
        Ok(clustering.expect("a clustering never stopped ends"))
    }

    /// [`ClusteringParams::try_cluster_owned`], stopped by the caller:
    /// `stop` is called every few merges (a cheap check, such as a
    /// cancellation flag's) and once it returns true the clustering ends
    /// with `Ok(None)`.
    pub fn try_cluster_owned_until(
        &self,
        preferences: Preferences,
        stop: &dyn Fn() -> bool,
    ) -> Result<Option<Clustering>, ClusteringError> {
        self.check_problem(&preferences)?;
        let n = preferences.n_points();
        let merges = match preferences {
            Preferences::Continuous(p) => tlinkage::merge_sequence_owned(p, stop),
            Preferences::Binary(b) => jlinkage::merge_sequence_until(&b, stop),
        };
        if stop() {
            return Ok(None);
        }
        Ok(Some(linkage::labels_from_merges(
            n,
            merges,
            self.size_rule,
            self.min_cluster_size,
        )))
    }

    /// [`ClusteringParams::validate`], then
    /// [`ClusteringParams::check_memory`] at the matrix's own size and
    /// density.
    fn check_problem(&self, preferences: &Preferences) -> Result<(), ClusteringError> {
        self.validate()?;
        self.check_memory(
            preferences.n_points(),
            preferences.n_hypotheses(),
            preferences.density(),
        )?;
        Ok(())
    }

    /// Errors on a [`SizeRule::RelativeMin`] fraction outside `[0, 1]`.
    pub fn validate(&self) -> Result<(), ClusteringError> {
        match self.size_rule {
            SizeRule::RelativeMin(f) if !(0.0..=1.0).contains(&f) => {
                Err(ClusteringError::InvalidRelativeMin(f))
            }
            _ => Ok(()),
        }
    }

    /// The [`required_memory`] of N points, M hypotheses and a fraction
    /// `density` of non-zero preferences; errors with
    /// [`ClusteringError::MemoryBound`] when it exceeds
    /// `self.max_memory_bytes`. Call it before generating hypotheses to stop
    /// at once (with `density` an assumption, e.g. 0.2 for F-matrix
    /// preferences at `thr_px` 2–3, or 1 for the worst case).
    ///
    /// ```
    /// use clustering::{ClusteringError, ClusteringParams};
    /// let params = ClusteringParams { max_memory_bytes: Some(200_000_000), ..Default::default() };
    /// assert!(params.check_memory(5000, 3000, 0.2).is_ok());
    /// let Err(ClusteringError::MemoryBound { required, .. }) = params.check_memory(20_000, 3000, 0.2)
    /// else { panic!("N = 20 000 needs more than 200 MB") };
    /// assert!(required > 200_000_000);
    /// ```
    pub fn check_memory(
        &self,
        n_points: usize,
        n_hypotheses: usize,
        density: f64,
    ) -> Result<u64, ClusteringError> {
        let required = required_memory(self.linkage, n_points, n_hypotheses, density);
        match self.max_memory_bytes {
            Some(limit) if required > limit => Err(ClusteringError::MemoryBound {
                n_points,
                n_hypotheses,
                required,
                limit,
            }),
            _ => Ok(required),
        }
    }
}

/// T-Linkage of continuous preferences, J-Linkage of binary ones, then the
/// size filter (docs/method.md steps 8–9).
pub fn cluster(preferences: &Preferences, min_cluster_size: usize) -> Clustering {
    cluster_with_rule(preferences, SizeRule::MinSize, min_cluster_size)
}

/// T-Linkage of continuous preferences, J-Linkage of binary ones, then the
/// clusters of `rule` are kept (docs/method.md steps 8–9; `min_cluster_size` is
/// the rule's floor).
pub fn cluster_with_rule(
    preferences: &Preferences,
    rule: SizeRule,
    min_cluster_size: usize,
) -> Clustering {
    let (n, merges) = match preferences {
        Preferences::Continuous(p) => (p.n_points(), tlinkage::merge_sequence(p)),
        Preferences::Binary(b) => (b.n_points(), jlinkage::merge_sequence(b)),
    };
    linkage::labels_from_merges(n, merges, rule, min_cluster_size)
}
