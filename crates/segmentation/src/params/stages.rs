//! The parameters of each stage of Algorithm 1 (docs/method.md "Parameters"),
//! one struct per stage, as [`crate::Params`] nests them. Each default is
//! that of [`crate::Params::default`] (the `default` profile).

use super::Params;
pub use clustering::{Linkage, SizeRule};
pub use focal::OnFailure;
pub use geometry::IrlsFit;

pub use crate::variants::{
    EightPoint, FinalAssignment, FocalSolver, LocalTest, Method, MinimalSolutions, MinimalSolver,
    Sampling, SubsetExtension,
};
pub use crate::weight_sets::{WeightPreset, WeightSets};

/// Steps 1–2: which matches, how many samples, drawn how, fitted how.
#[derive(Debug, Clone, PartialEq)]
pub struct SamplingParams {
    /// M, the number of minimal sample sets drawn (step 1). Table 1: 3000.
    pub num_samples: usize,
    /// Correspondences per minimal sample set of the 8-point (step 1).
    /// Table 1: 8.
    pub mss_size: usize,
    /// Minimal solver of step 2: `eight-point` (the thesis) or `five-point`
    /// (essential matrices at the focal prior, samples of 5; `mss_size`
    /// applies to `eight-point`). The five-point's refinement (step 3)
    /// starts from the matches within `thr_px` of the chosen solution
    /// instead of the sample. Default `five-point` (the thesis:
    /// `eight-point`).
    pub minimal_solver: MinimalSolver,
    /// Which solution of a five-point sample becomes its hypothesis: `best`
    /// (most matches within `thr_px`) or `best-unpolished` (the same scored
    /// on the roots before their polish, the winner left unpolished, with
    /// the consensus set it was scored with). Ignored by `eight-point`,
    /// which has one. Default `best`.
    pub minimal_solutions: MinimalSolutions,
    /// How the matches of a minimal sample are drawn (step 1): `uniform`
    /// (the thesis), `localized` (the first uniformly, the others among
    /// its nearest matches in image 1: NAPSAC, Torr et al. 2002, as
    /// J-/T-Linkage (Toldo & Fusiello 2008) and Progressive-X sample;
    /// neighbourhood size [`crate::neighbourhood_size`]) or `guided`
    /// (uniform and localized in turn, the uniform turns guided by the
    /// hypotheses so far after the first batch, [`Sampling::Guided`]).
    /// Default `uniform`.
    pub sampling: Sampling,
    /// Samples per batch of `sampling = "guided"`: the first batch is
    /// drawn unguided, each later one guided by the co-inlier counts of
    /// every hypothesis before it ([`crate::CoInlierKernel`]). Smaller
    /// batches guide sooner and rebuild the counts more often (each
    /// rebuild costs N²/2 · M/64 word operations). Ignored by the other
    /// samplings. Default 100.
    pub guided_batch: usize,
    /// Steps 1–9 on at most this many matches, drawn at random per seed
    /// ([`crate::subset_indices`]); every other match then joins the
    /// cluster it is nearest to ([`SelectionParams::subset_extension`]).
    /// T-Linkage costs the square of the matches it clusters, so this
    /// bounds the time of large scenes. `0`: all matches (the thesis);
    /// otherwise at least `mss_size`. Default 0.
    pub cluster_subset: usize,
    /// Seed of the hypothesis sampling: hypothesis `j` draws from ChaCha8
    /// stream `j` under a key expanded from the seed
    /// ([`crate::hypothesis_rng`]), so the labels depend on the seed and
    /// the input only. Default 12345 (the reference code's).
    pub seed: u64,
}

/// Step 3: the IRLS-Tukey refinement (Eqs. 33–34) and the inlier scale.
#[derive(Debug, Clone, PartialEq)]
pub struct RefinementParams {
    /// Inlier threshold in pixels: IRLS inlier bound `thr_px²` (step 3e) and
    /// preference scale `tau = thr_px²` (Eq. 38). Table 1: 2.5.
    pub thr_px: f64,
    /// Outer IRLS-Tukey iterations (step 3, Eqs. 33–34). Table 1: 5.
    pub irls_iters: usize,
    /// Refine each minimal-sample F by IRLS-Tukey (step 3); `false` is the
    /// "raw MSS" ablation. Default `true`.
    pub refine: bool,
}

/// Steps 4–6: which hypotheses reach the clustering, and the focal
/// lengths and filter of `semical`.
#[derive(Debug, Clone, PartialEq)]
pub struct FocalParams {
    /// `semical` (focal filtering, steps 4–6) or `baseline` (every refined
    /// hypothesis kept). Default `baseline` (with the five-point
    /// hypotheses; the thesis: `semical`).
    pub method: Method,
    /// τ_diff, the largest relative focal difference `|f1 - f2| / f_avg` of
    /// the local test (Eq. 36). Table 1: 0.05.
    pub tau_diff: f64,
    /// τ_range, the half-width of the focal band around f_peak relative to
    /// f_peak (Eq. 37). Table 1: 0.20.
    pub tau_range: f64,
    /// Focal solver (step 4): `kocur`, `bougnoux` or `external`. Default
    /// `kocur`.
    pub focal_solver: FocalSolver,
    /// Multi-start weight sets of the robust solver: `adelaidermf` (4 sets),
    /// `hopef` (6 sets) or an explicit list. Default `adelaidermf`.
    pub weight_sets: WeightSets,
    /// Iteration cap of the robust solver (step 4). Default 100 (the
    /// reference's AdelaideRMF value; its HOPE-F value is 120).
    pub max_iters: usize,
}

/// Steps 8–9: the linkage and the clusters it keeps.
#[derive(Debug, Clone, PartialEq)]
pub struct ClusterParams {
    /// Clustering (step 8): `t-linkage` or `j-linkage`. Default `t-linkage`.
    pub linkage: Linkage,
    /// Clusters with fewer points become outliers (step 9). Default 8.
    pub min_cluster_size: usize,
    /// Which clusters step 9 keeps: `min-size` (`min_cluster_size` alone,
    /// the thesis) or `{ relative-min = f }` (at least ⌈f N⌉ points);
    /// `min_cluster_size` is a floor under each ([`clustering::SizeRule`]).
    /// Default `min-size`.
    pub size_rule: SizeRule,
}

/// After step 9: the final labels of the clustered matches and of those
/// left out of [`SamplingParams::cluster_subset`].
#[derive(Debug, Clone, PartialEq)]
pub struct SelectionParams {
    /// After the size filter: `none` (the clustering's labels, the thesis)
    /// or `merge` (a cluster joins a larger one whose best-supported
    /// hypothesis explains [`crate::MERGE_SHARE`] of its matches,
    /// [`crate::merge_explained`]). Default `merge` (the thesis: `none`).
    pub final_assignment: FinalAssignment,
    /// How the matches left out of `cluster_subset` join the clusters
    /// ([`SubsetExtension`]): `preference` (the nearest mean preference
    /// vector in Tanimoto distance, the subset's outliers a class of their
    /// own) or `preference-explained` (the same, then an outlier unless the
    /// cluster's best-supported hypothesis explains it within `thr_px`).
    /// Default `preference-explained` (results/README.md, "Real-sized
    /// scenes").
    pub subset_extension: SubsetExtension,
}

/// The switches between the thesis text (every default) and its reference
/// implementation, step by step (docs/method.md, "reference code").
#[derive(Debug, Clone, PartialEq)]
pub struct ReferenceCode {
    /// 8-point variant (step 2): `normalized` (text) or `plain` (reference
    /// code). Default `normalized`.
    pub eight_point: EightPoint,
    /// The weighted refit of each IRLS iteration (step 3d): `normalized`
    /// (Hartley-normalised weighted 8-point, the text) or `plain` (the
    /// weighted system in centred pixel coordinates, the reference code).
    /// Default `normalized`.
    pub irls_fit: IrlsFit,
    /// When fewer than 8 Tukey weights are positive (or the weighted system
    /// is rank-deficient), refit with unit weights (`true`, this project's
    /// rule for the case the text leaves open) or drop the hypothesis
    /// (`false`, the closest reproducible reading of the reference code).
    /// Default `true`.
    pub irls_unit_weight_fallback: bool,
    /// Added to the robust scale of IRLS (Eq. 34), px:
    /// `σ = 1.4826 · MAD + irls_sigma_offset_px`. Default 0 (the text); the
    /// reference code adds 1e-12.
    pub irls_sigma_offset_px: f64,
    /// Polish each minimal-sample F on its sample before IRLS by
    /// Levenberg–Marquardt on the Sampson error (PoseLib's
    /// `refine_fundamental`, as the reference code does). Default `false`.
    pub irls_polish: bool,
    /// What a failed focal solve yields (step 4): `report` (a failure) or
    /// `prior` (the priors, as the reference code). Default `report`.
    pub focal_failure: OnFailure,
    /// Truncate f1, f2 to integers after solving (step 4), as the
    /// reference code does. Default `false`.
    pub truncate_focals: bool,
    /// Local test variant (step 5): `algorithm1` or `reference-code`.
    /// Default `algorithm1`.
    pub local_test: LocalTest,
}

impl Default for SamplingParams {
    fn default() -> Self {
        Params::default().sampling
    }
}

impl Default for RefinementParams {
    fn default() -> Self {
        Params::default().refinement
    }
}

impl Default for FocalParams {
    fn default() -> Self {
        Params::default().focal
    }
}

impl Default for ClusterParams {
    fn default() -> Self {
        Params::default().clustering
    }
}

impl Default for SelectionParams {
    fn default() -> Self {
        Params::default().selection
    }
}

impl Default for ReferenceCode {
    fn default() -> Self {
        Params::default().reference_code
    }
}
