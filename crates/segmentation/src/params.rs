//! The parameters of Algorithm 1 ([`Params`]) and the switches between the
//! thesis text and its reference implementation.
//!
//! Every parameter of docs/method.md's "Parameters" table is a field of
//! [`Params`]; its default is the thesis's Table 1 value (or the text's
//! choice where Table 1 has none). With the `serde` feature the struct reads
//! from and writes to TOML/JSON under the same names, unknown keys refused.

pub use clustering::{Linkage, SizeRule};
pub use focal::OnFailure;
pub use geometry::IrlsFit;
use geometry::IrlsParams;
use thiserror::Error;

pub use crate::variants::{
    DuplicateFilter, EightPoint, FinalAssignment, FocalSolver, ImplausibleFocal, LocalTest, Method,
    MinimalSolutions, MinimalSolver, RecoverOutliers, Sampling, SubsetExtension,
};
pub use crate::weight_sets::{WeightPreset, WeightSets};

/// Every parameter of Algorithm 1 (docs/method.md "Parameters" and the switches
/// between the thesis text and the reference code).
///
/// The defaults are the best configuration measured (results/README.md,
/// "Minimal solvers" and "Real-sized scenes"): hypotheses from five-point
/// samples as essential matrices at the focal prior (the one camera enters
/// the hypotheses), no focal filter, clusters that one model explains
/// merged, and the thesis's Table 1 values for everything else.
/// [`Params::thesis`] gives the thesis text's semi-calibrated method; the
/// reference implementation's AdelaideRMF parameters are
/// `num_samples = 5000, thr_px = 4.5, tau_diff = 0.15, tau_range = 0.25`
/// with its variants (`eight_point = "plain"`, `irls_fit = "plain"`,
/// `focal_failure = "prior"`, `truncate_focals = true`,
/// `local_test = "reference-code"`, …).
///
/// ```
/// use segmentation::{Method, MinimalSolver, Params};
/// let p = Params { num_samples: 500, ..Default::default() };
/// assert_eq!(p.thr_px, 2.5); // Table 1
/// assert_eq!((p.method, p.minimal_solver), (Method::Baseline, MinimalSolver::FivePoint));
/// assert!(p.validate().is_ok());
/// let thesis = Params::thesis();
/// assert_eq!((thesis.method, thesis.minimal_solver), (Method::Semical, MinimalSolver::EightPoint));
/// ```
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(deny_unknown_fields, default)
)]
pub struct Params {
    /// `semical` (focal filtering, steps 4–6) or `baseline` (every refined
    /// hypothesis kept). Default `baseline` (with the five-point
    /// hypotheses; the thesis: `semical`).
    pub method: Method,
    /// M, the number of minimal sample sets drawn (step 1). Table 1: 3000.
    pub num_samples: usize,
    /// Adaptive M (step 1): `0` draws all `num_samples` samples; `B > 0`
    /// draws them in batches of B and stops after the first batch, from the
    /// second on, in which fewer than `adaptive_tolerance · N` points gained
    /// a better-supported hypothesis ([`crate::SupportTracker`]); at most
    /// `num_samples` in all. The hypotheses drawn are the first ones of the
    /// fixed-M run. Default 0 (fixed M, the thesis).
    pub adaptive_batch: usize,
    /// The adaptive stop rule's tolerance, a fraction of the points in
    /// `[0, 1]`. Default 0.01.
    pub adaptive_tolerance: f64,
    /// Correspondences per minimal sample set (step 1). Table 1: 8.
    pub mss_size: usize,
    /// Inlier threshold in pixels: IRLS inlier bound `thr_px²` (step 3e) and
    /// preference scale `tau = thr_px²` (Eq. 38). Table 1: 2.5.
    pub thr_px: f64,
    /// τ_diff, the largest relative focal difference `|f1 - f2| / f_avg` of
    /// the local test (Eq. 36). Table 1: 0.05.
    pub tau_diff: f64,
    /// τ_range, the half-width of the focal band around f_peak relative to
    /// f_peak (Eq. 37). Table 1: 0.20.
    pub tau_range: f64,
    /// Outer IRLS-Tukey iterations (step 3, Eqs. 33–34). Table 1: 5.
    pub irls_iters: usize,
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
    /// Refine each minimal-sample F by IRLS-Tukey (step 3); `false` is the
    /// "raw MSS" ablation. Default `true`.
    pub refine: bool,
    /// 8-point variant (step 2): `normalized` (text) or `plain` (reference
    /// code). Default `normalized`.
    pub eight_point: EightPoint,
    /// Minimal solver of step 2: `eight-point` (the thesis), `seven-point`,
    /// `five-point` (essential matrices at the focal prior) or
    /// `six-point-focal` (shared unknown focal). The last three draw their
    /// own sample size; `mss_size` applies to `eight-point`. Refinement
    /// (step 3) starts from the matches within `thr_px` of the chosen
    /// solution instead of the sample. Default `five-point` (the thesis:
    /// `eight-point`).
    pub minimal_solver: MinimalSolver,
    /// Which solutions of a minimal sample become hypotheses: `best` (most
    /// matches within `thr_px`), `all`, `best-then-polish` (`best`
    /// scored on the five-point roots before their polish, the winner
    /// alone polished) or `best-unpolished` (the winner left unpolished,
    /// with the consensus set it was scored with). Ignored by
    /// `eight-point`, which has one. Default `best`.
    pub minimal_solutions: MinimalSolutions,
    /// A minimal solution with fewer matches within `thr_px` than this is
    /// dropped before its refinement (step 3) and gives no hypothesis: the
    /// hypotheses of samples that mix motions or hold outliers rarely
    /// explain many matches, and each one dropped saves its refinement,
    /// its preference column and its share of the clustering. Ignored by
    /// `eight-point`, whose refinement starts from its sample. A solution
    /// with fewer than 8 such matches is never refined (the weighted
    /// 8-point needs 8), so values up to 8 change nothing. Default 0.
    pub min_consensus: usize,
    /// Which of a sample's solutions compete for `best`,
    /// `best-then-polish` and `best-unpolished`: with a value K below the
    /// number of matches the samples are drawn from (all, or
    /// `cluster_subset` of them), every solution is first scored on K matches drawn
    /// at random per seed, and only those with the most of them within
    /// `thr_px` are scored on all matches (preemptive scoring: Nistér,
    /// ICCV 2003; Matas & Chum's T(d,d) test, BMVC 2002). A five-point
    /// sample has four roots on average and one survives, so the losers
    /// cost K matches each instead of up to N. `0`: every solution scored
    /// on all matches. Default 0.
    pub preselect_matches: usize,
    /// How the matches of a minimal sample are drawn (step 1): `uniform`
    /// (the thesis) or `localized` (the first uniformly, the others among
    /// its nearest matches in image 1: NAPSAC, Torr et al. 2002, as
    /// J-/T-Linkage (Toldo & Fusiello 2008) and Progressive-X sample;
    /// neighbourhood size [`crate::neighbourhood_size`]). Default
    /// `uniform`.
    pub sampling: Sampling,
    /// Samples per batch of `sampling = "guided"`: the first batch is
    /// drawn as `mixed`, each later one guided by the co-inlier counts of
    /// every hypothesis before it ([`crate::CoInlierKernel`]). Smaller
    /// batches guide sooner and rebuild the counts more often (each
    /// rebuild costs N²/2 · M/64 word operations). Ignored by the other
    /// samplings. Default 100.
    pub guided_batch: usize,
    /// Focal solver (step 4): `kocur`, `bougnoux` or `external`. Default
    /// `kocur`.
    pub focal_solver: FocalSolver,
    /// Multi-start weight sets of the robust solver: `adelaidermf` (4 sets),
    /// `hopef` (6 sets) or an explicit list. Default `adelaidermf`.
    pub weight_sets: WeightSets,
    /// Iteration cap of the robust solver (step 4). Default 100 (the
    /// reference's AdelaideRMF value; its HOPE-F value is 120).
    pub max_iters: usize,
    /// What a failed focal solve yields: `report` (a failure) or `prior`
    /// (the priors, as the reference code). Default `report`.
    pub focal_failure: OnFailure,
    /// Truncate f1, f2 to integers after solving, as the reference code
    /// does. Default `false`.
    pub truncate_focals: bool,
    /// Local test variant (step 5): `algorithm1` or `reference-code`.
    /// Default `algorithm1`.
    pub local_test: LocalTest,
    /// When f_peak lies outside [`crate::PLAUSIBLE_FOCAL_RANGE`] times the
    /// focal prior: `filter` all the same (the thesis) or `abstain` (keep
    /// every refined hypothesis: the baseline's labels). Default `filter`.
    pub implausible_focal: ImplausibleFocal,
    /// Clustering (step 8): `t-linkage` or `j-linkage`. Default `t-linkage`.
    pub linkage: Linkage,
    /// Clusters with fewer points become outliers (step 9). Default 8.
    pub min_cluster_size: usize,
    /// Which clusters step 9 keeps: `min-size` (`min_cluster_size` alone,
    /// the thesis), `largest-gap` (T-Linkage's rule, Magri & Fusiello
    /// 2014: sizes sorted, cut at the largest ratio of consecutive sizes) or
    /// `{ relative-min = f }` (at least ⌈f N⌉ points); `min_cluster_size` is
    /// a floor under each ([`clustering::SizeRule`]). Default `min-size`.
    pub size_rule: SizeRule,
    /// After the size filter: `none` (the clustering's labels, the thesis)
    /// or `refit` (each cluster's F refitted by IRLS-Tukey on its points,
    /// then every match to the cluster of smallest Sampson distance within
    /// `thr_px`, else outlier; clusters left below `min_cluster_size`
    /// become outliers; labels numbered by first appearance), as
    /// Progressive-X (Barath & Matas, ICCV 2019) and consensus-space
    /// clustering (Barath et al., CVPR 2023) end ([`crate::reassign`]);
    /// or `merge` (a cluster joins a larger one whose best-supported
    /// hypothesis explains [`crate::MERGE_SHARE`] of its matches,
    /// [`crate::merge_explained`]) or `merge-refit` (`merge`, then a
    /// cluster joins a larger one when the F refitted on the two explains
    /// `MERGE_SHARE` of each, [`crate::merge_refitted`]) or
    /// `merge-anchored` (the same, the refit started from the larger
    /// cluster's model, [`crate::merge_anchored`]). Default `merge`
    /// (the thesis: `none`).
    pub final_assignment: FinalAssignment,
    /// Which kept hypotheses enter the preferences (step 7): `none` (all,
    /// the thesis) or `same-inliers` (one per distinct inlier set,
    /// [`DuplicateFilter`]). Default `none`.
    pub duplicate_filter: DuplicateFilter,
    /// Steps 1–9 on at most this many matches, drawn at random per seed
    /// ([`crate::subset_indices`]); every other match then joins the
    /// cluster it is nearest to ([`Params::subset_extension`]). T-Linkage
    /// costs the square of the matches it clusters, so this bounds the
    /// time of large scenes. `0`: all matches (the thesis); otherwise at
    /// least `mss_size`. Default 0.
    pub cluster_subset: usize,
    /// How the matches left out of `cluster_subset` join the clusters
    /// ([`SubsetExtension`]): `preference` (the nearest mean preference
    /// vector in Tanimoto distance, the subset's outliers a class of their
    /// own), `preference-explained` (the same, then an outlier unless the
    /// cluster's best-supported hypothesis explains it within `thr_px`) or
    /// `model` (the nearest best-supported hypothesis within `thr_px`);
    /// `preference-refit` and `model-refit` are the last two with each
    /// cluster's model refitted by IRLS-Tukey on its clustered matches
    /// ([`crate::refitted_cluster_models`]); `neighbours` (the label most
    /// of its [`crate::EXTENSION_NEIGHBOURS`] nearest clustered matches in
    /// (x₁, y₁, x₂, y₂) have, then an outlier unless that cluster's
    /// best-supported hypothesis explains it within `thr_px`). Default
    /// `preference-explained` (results/README.md, "Real-sized scenes").
    pub subset_extension: SubsetExtension,
    /// After the final assignment and the subset's extension: `none` (the
    /// outliers stay, the thesis) or `refit` (each cluster's F refitted by
    /// IRLS-Tukey, [`crate::CLUSTER_REFIT_ITERS`] iterations; an outlier
    /// joins the cluster whose refitted F explains it best within
    /// `thr_px`, [`crate::recover_outliers`]). Default `none`.
    pub recover_outliers: RecoverOutliers,
    /// Memory bound of the preferences and the clustering (steps 7–8), MB
    /// (10⁶ bytes; [`clustering::required_memory`]). With a bound the
    /// segmentation stops before drawing a sample when N points and
    /// `num_samples` hypotheses would need more at 20 % non-zero
    /// preferences, and before clustering when the preferences' real
    /// density does. `0` (default): the bound is the memory the machine
    /// has available (Linux `MemAvailable`, [`crate::available_memory`]):
    /// the whole run's need ([`crate::memory_need`]: hypotheses,
    /// preferences, clustering) is checked against it before sampling
    /// ([`crate::check_available_memory`]) and the clustering against it
    /// at the real density; where that figure is unknown (not Linux, or
    /// `/proc/meminfo` unreadable) there is no bound. Default 0.
    pub max_memory_mb: u64,
    /// Seed of the hypothesis sampling: hypothesis `j` draws from ChaCha8
    /// stream `j` under a key expanded from the seed ([`crate::hypothesis_rng`]),
    /// so the labels depend on the seed and the input only. Default 12345
    /// (the reference code's).
    pub seed: u64,
}

impl Default for Params {
    fn default() -> Self {
        Self {
            minimal_solver: MinimalSolver::FivePoint,
            method: Method::Baseline,
            final_assignment: FinalAssignment::Merge,
            ..Self::thesis()
        }
    }
}

impl Params {
    /// The thesis text's semi-calibrated T-Linkage: Algorithm 1 with the
    /// Table 1 parameters, the normalised 8-point, the robust focal solver
    /// and the focal filter (`method = "semical"`,
    /// `minimal_solver = "eight-point"`).
    pub fn thesis() -> Self {
        Self {
            method: Method::Semical,
            num_samples: 3000,
            adaptive_batch: 0,
            adaptive_tolerance: 0.01,
            mss_size: 8,
            thr_px: 2.5,
            tau_diff: 0.05,
            tau_range: 0.20,
            irls_iters: 5,
            irls_fit: IrlsFit::Normalized,
            irls_unit_weight_fallback: true,
            irls_sigma_offset_px: 0.0,
            irls_polish: false,
            refine: true,
            eight_point: EightPoint::Normalized,
            minimal_solver: MinimalSolver::EightPoint,
            minimal_solutions: MinimalSolutions::Best,
            min_consensus: 0,
            preselect_matches: 0,
            sampling: Sampling::Uniform,
            guided_batch: 100,
            focal_solver: FocalSolver::Kocur,
            weight_sets: WeightSets::Preset(WeightPreset::Adelaidermf),
            max_iters: 100,
            focal_failure: OnFailure::Report,
            truncate_focals: false,
            local_test: LocalTest::Algorithm1,
            implausible_focal: ImplausibleFocal::Filter,
            linkage: Linkage::TLinkage,
            min_cluster_size: 8,
            size_rule: SizeRule::MinSize,
            final_assignment: FinalAssignment::None,
            duplicate_filter: DuplicateFilter::None,
            cluster_subset: 0,
            subset_extension: SubsetExtension::PreferenceExplained,
            recover_outliers: RecoverOutliers::None,
            max_memory_mb: 0,
            seed: 12345,
        }
    }
}

/// The keys of [`Params`] in declaration order.
pub const PARAM_KEYS: [&str; 38] = [
    "method",
    "num_samples",
    "adaptive_batch",
    "adaptive_tolerance",
    "mss_size",
    "thr_px",
    "tau_diff",
    "tau_range",
    "irls_iters",
    "irls_fit",
    "irls_unit_weight_fallback",
    "irls_sigma_offset_px",
    "irls_polish",
    "refine",
    "eight_point",
    "minimal_solver",
    "minimal_solutions",
    "min_consensus",
    "preselect_matches",
    "sampling",
    "guided_batch",
    "focal_solver",
    "weight_sets",
    "max_iters",
    "focal_failure",
    "truncate_focals",
    "local_test",
    "implausible_focal",
    "linkage",
    "min_cluster_size",
    "size_rule",
    "final_assignment",
    "duplicate_filter",
    "cluster_subset",
    "subset_extension",
    "recover_outliers",
    "max_memory_mb",
    "seed",
];

/// A parameter out of its range: the [`Params`] key and why.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
#[error("invalid parameter `{key}`: {message}")]
pub struct ParamError {
    /// The [`Params`] field.
    pub key: &'static str,
    /// What is wrong.
    pub message: String,
}

impl ParamError {
    fn new(key: &'static str, message: impl Into<String>) -> Self {
        Self {
            key,
            message: message.into(),
        }
    }
}

impl Params {
    /// Checks the ranges the types cannot: the first offending key and why.
    pub fn validate(&self) -> Result<(), ParamError> {
        fn positive(key: &'static str, v: f64) -> Result<(), ParamError> {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err(ParamError::new(
                    key,
                    format!("must be a finite number > 0, got {v}"),
                ))
            }
        }
        if self.num_samples == 0 {
            return Err(ParamError::new("num_samples", "must be at least 1"));
        }
        if self.sampling == Sampling::Guided && self.guided_batch == 0 {
            return Err(ParamError::new("guided_batch", "must be at least 1"));
        }
        if !(0.0..=1.0).contains(&self.adaptive_tolerance) {
            return Err(ParamError::new(
                "adaptive_tolerance",
                format!(
                    "must be a fraction in [0, 1], got {}",
                    self.adaptive_tolerance
                ),
            ));
        }
        if self.mss_size < 8 {
            return Err(ParamError::new(
                "mss_size",
                format!(
                    "must be at least 8 (the 8-point algorithm; the other minimal solvers \
                     draw their own sample size and still refine on 8 or more), got {}",
                    self.mss_size
                ),
            ));
        }
        if self.cluster_subset != 0 && self.cluster_subset < self.mss_size {
            return Err(ParamError::new(
                "cluster_subset",
                format!(
                    "must be 0 (all matches) or at least mss_size = {}, got {}",
                    self.mss_size, self.cluster_subset
                ),
            ));
        }
        positive("thr_px", self.thr_px)?;
        positive("tau_diff", self.tau_diff)?;
        positive("tau_range", self.tau_range)?;
        if (self.refine || self.final_assignment == FinalAssignment::Refit) && self.irls_iters == 0
        {
            return Err(ParamError::new(
                "irls_iters",
                "must be at least 1 when refine = true or final_assignment = \"refit\"",
            ));
        }
        if !(self.irls_sigma_offset_px.is_finite() && self.irls_sigma_offset_px >= 0.0) {
            return Err(ParamError::new(
                "irls_sigma_offset_px",
                format!(
                    "must be a finite number >= 0, got {}",
                    self.irls_sigma_offset_px
                ),
            ));
        }
        if self.max_iters == 0 {
            return Err(ParamError::new("max_iters", "must be at least 1"));
        }
        if let SizeRule::RelativeMin(f) = self.size_rule {
            if !(0.0..=1.0).contains(&f) {
                return Err(ParamError::new(
                    "size_rule",
                    format!("relative-min must be a fraction in [0, 1], got {f}"),
                ));
            }
        }
        self.validate_weight_sets()
    }

    fn validate_weight_sets(&self) -> Result<(), ParamError> {
        let sets = self.weight_sets.sets();
        if sets.is_empty() {
            return Err(ParamError::new(
                "weight_sets",
                "must hold at least one weight set",
            ));
        }
        for (i, set) in sets.iter().enumerate() {
            let w = [set.f1, set.pp1, set.f2, set.pp2];
            if w.iter().any(|w| !(w.is_finite() && *w > 0.0)) {
                return Err(ParamError::new(
                    "weight_sets",
                    format!("set {i} {w:?}: every weight must be a finite number > 0"),
                ));
            }
        }
        Ok(())
    }

    /// What steps 1–3 depend on ([`crate::generate_hypotheses`]): two
    /// parameter sets with equal keys give the same hypotheses on an input.
    pub fn hypothesis_key(&self) -> HypothesisKey {
        HypothesisKey {
            seed: self.seed,
            num_samples: self.num_samples,
            cluster_subset: self.cluster_subset,
            adaptive_batch: self.adaptive_batch,
            adaptive_tolerance_bits: self.adaptive_tolerance.to_bits(),
            mss_size: self.mss_size,
            eight_point: self.eight_point,
            minimal_solver: self.minimal_solver,
            minimal_solutions: self.minimal_solutions,
            min_consensus: self.min_consensus,
            preselect_matches: self.preselect_matches,
            sampling: self.sampling,
            guided_batch: match self.sampling {
                Sampling::Guided => self.guided_batch,
                _ => 0,
            },
            refine: self.refine,
            thr_px_bits: self.thr_px.to_bits(),
            irls_iters: self.irls_iters,
            irls_fit: self.irls_fit,
            irls_unit_weight_fallback: self.irls_unit_weight_fallback,
            irls_sigma_offset_bits: self.irls_sigma_offset_px.to_bits(),
            irls_polish: self.irls_polish,
        }
    }

    /// How many of `n` matches steps 1–9 run on: `n`, or
    /// [`Params::cluster_subset`] when that is smaller and not 0.
    pub fn clustered_matches(&self, n: usize) -> usize {
        match self.cluster_subset {
            0 => n,
            size => size.min(n),
        }
    }

    /// The matches drawn per minimal sample (step 1): `mss_size` for the
    /// 8-point, the solver's minimal size otherwise.
    pub fn sample_size(&self) -> usize {
        self.minimal_solver.sample_size(self.mss_size)
    }

    /// The IRLS-Tukey parameters of step 3.
    pub fn irls(&self) -> IrlsParams {
        IrlsParams {
            thr_px: self.thr_px,
            max_iters: self.irls_iters,
            fit: self.irls_fit,
            unit_weight_fallback: self.irls_unit_weight_fallback,
            sigma_offset_px: self.irls_sigma_offset_px,
            polish: self.irls_polish,
            ..IrlsParams::default()
        }
    }

    /// What step 4 depends on besides the hypotheses and the focal prior
    /// ([`crate::estimate_hypothesis_focals`]).
    pub fn focal_key(&self) -> FocalKey {
        FocalKey {
            solver: self.focal_solver,
            weight_sets: self.weight_sets.key(),
            max_iters: self.max_iters,
            failure: self.focal_failure,
            truncate: self.truncate_focals,
        }
    }
}

/// The parameters of steps 1–3 ([`Params::hypothesis_key`]).
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct HypothesisKey {
    seed: u64,
    num_samples: usize,
    cluster_subset: usize,
    adaptive_batch: usize,
    adaptive_tolerance_bits: u64,
    mss_size: usize,
    eight_point: EightPoint,
    minimal_solver: MinimalSolver,
    minimal_solutions: MinimalSolutions,
    min_consensus: usize,
    preselect_matches: usize,
    sampling: Sampling,
    guided_batch: usize,
    refine: bool,
    thr_px_bits: u64,
    irls_iters: usize,
    irls_fit: IrlsFit,
    irls_unit_weight_fallback: bool,
    irls_sigma_offset_bits: u64,
    irls_polish: bool,
}

/// The parameters of step 4 ([`Params::focal_key`]).
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct FocalKey {
    solver: FocalSolver,
    weight_sets: Vec<[u64; 4]>,
    max_iters: usize,
    failure: OnFailure,
    truncate: bool,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_range_check_names_its_key() {
        let cases: [(&str, Params); 8] = [
            (
                "num_samples",
                Params {
                    num_samples: 0,
                    ..Default::default()
                },
            ),
            (
                "mss_size",
                Params {
                    mss_size: 7,
                    ..Default::default()
                },
            ),
            (
                "cluster_subset",
                Params {
                    cluster_subset: 5,
                    ..Default::default()
                },
            ),
            (
                "thr_px",
                Params {
                    thr_px: f64::NAN,
                    ..Default::default()
                },
            ),
            (
                "tau_diff",
                Params {
                    tau_diff: 0.0,
                    ..Default::default()
                },
            ),
            (
                "tau_range",
                Params {
                    tau_range: -0.1,
                    ..Default::default()
                },
            ),
            (
                "irls_iters",
                Params {
                    irls_iters: 0,
                    ..Default::default()
                },
            ),
            (
                "weight_sets",
                Params {
                    weight_sets: WeightSets::Explicit(vec![[1.0, 0.0, 1.0, 1.0]]),
                    ..Default::default()
                },
            ),
        ];
        for (key, params) in cases {
            assert_eq!(params.validate().unwrap_err().key, key);
        }
        assert!(Params::default().validate().is_ok());
        let no_refine = Params {
            refine: false,
            irls_iters: 0,
            ..Default::default()
        };
        assert!(no_refine.validate().is_ok());
        let refit_without_iterations = Params {
            final_assignment: FinalAssignment::Refit,
            ..no_refine
        };
        assert_eq!(
            refit_without_iterations.validate().unwrap_err().key,
            "irls_iters"
        );
    }

    #[test]
    fn keys_separate_what_changes_the_stage() {
        let a = Params::default();
        let b = Params {
            method: Method::Baseline,
            tau_range: 0.3,
            ..a.clone()
        };
        assert_eq!(a.hypothesis_key(), b.hypothesis_key());
        assert_eq!(a.focal_key(), b.focal_key());
        let c = Params {
            thr_px: 3.0,
            ..a.clone()
        };
        assert_ne!(a.hypothesis_key(), c.hypothesis_key());
        let localized = Params {
            sampling: Sampling::Localized,
            ..a.clone()
        };
        assert_ne!(a.hypothesis_key(), localized.hypothesis_key());
        let subset = Params {
            cluster_subset: 1000,
            ..a.clone()
        };
        assert_ne!(a.hypothesis_key(), subset.hypothesis_key());
        let preselect = Params {
            preselect_matches: 32,
            ..a.clone()
        };
        assert_ne!(a.hypothesis_key(), preselect.hypothesis_key());
        let batch = Params {
            guided_batch: 50,
            ..a.clone()
        };
        assert_eq!(a.hypothesis_key(), batch.hypothesis_key());
        let guided = Params {
            sampling: Sampling::Guided,
            ..a.clone()
        };
        assert_ne!(a.hypothesis_key(), guided.hypothesis_key());
        let guided_batch = Params {
            guided_batch: 50,
            ..guided.clone()
        };
        assert_ne!(guided.hypothesis_key(), guided_batch.hypothesis_key());
        let refit = Params {
            final_assignment: FinalAssignment::Refit,
            ..a.clone()
        };
        assert_eq!(a.hypothesis_key(), refit.hypothesis_key());
        let d = Params {
            weight_sets: WeightSets::Preset(WeightPreset::Hopef),
            ..a.clone()
        };
        assert_ne!(a.focal_key(), d.focal_key());
    }
}
