//! What a segmentation returns: labels, clusters, hypothesis fates, the
//! focal consensus, counts and stage timings.

use focal::FocalConsensus;
use nalgebra::Matrix3;

/// What happened to one hypothesis (Algorithm 1 steps 2–6).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum HypothesisStatus {
    /// The 8-point fit of the minimal sample failed (degenerate sample).
    Degenerate,
    /// IRLS-Tukey dropped it: fewer than 8 inliers or a non-finite F (step 3).
    RefineFailed,
    /// The focal solver gave no answer (step 4).
    FocalFailed,
    /// It failed the local test (Eq. 36, or `f_avg <= 0` for the
    /// reference-code variant).
    LocalTestFailed,
    /// Its `f_avg` lies outside the band around f_peak (Eq. 37).
    OutsideBand,
    /// It reached the clustering.
    Kept,
}

impl HypothesisStatus {
    /// A short lowercase name.
    pub fn name(self) -> &'static str {
        match self {
            Self::Degenerate => "degenerate",
            Self::RefineFailed => "refine-failed",
            Self::FocalFailed => "focal-failed",
            Self::LocalTestFailed => "local-test-failed",
            Self::OutsideBand => "outside-band",
            Self::Kept => "kept",
        }
    }
}

/// Whether the focal consensus of a segmentation is plausible
/// ([`crate::focal_verdict`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum FocalVerdict {
    /// No focal was estimated (`method = "baseline"`).
    #[default]
    NotEstimated,
    /// Focals were estimated but none passed the local test: no consensus.
    NoConsensus,
    /// f_peak lies within [`crate::PLAUSIBLE_FOCAL_RANGE`] times the prior.
    Plausible,
    /// f_peak lies outside [`crate::PLAUSIBLE_FOCAL_RANGE`] times the prior.
    Implausible,
}

impl FocalVerdict {
    /// A short lowercase name: `""` (not estimated), `none`, `plausible`,
    /// `implausible`.
    pub fn name(self) -> &'static str {
        match self {
            Self::NotEstimated => "",
            Self::NoConsensus => "none",
            Self::Plausible => "plausible",
            Self::Implausible => "implausible",
        }
    }
}

/// One hypothesis of a segmentation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hypothesis {
    /// Its fate.
    pub status: HypothesisStatus,
    /// Focal lengths of image 1 and image 2 (px) when estimated (step 4).
    pub focals: Option<(f64, f64)>,
}

/// A final cluster: its label, its size and the 8-point F of its points
/// (after the final assignment, when there is one).
#[derive(Debug, Clone, PartialEq)]
pub struct ClusterModel {
    /// The label (0, 1, …) in [`Segmentation::labels`].
    pub label: i32,
    /// Number of points.
    pub size: usize,
    /// Hartley-normalised 8-point F of its points (principal-point-centred
    /// coordinates); None when the fit is degenerate.
    pub f: Option<Matrix3<f64>>,
}

/// Hypothesis counts of one segmentation (Algorithm 1 steps 1–6).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct HypothesisCounts {
    /// Minimal sample sets drawn (M).
    pub generated: usize,
    /// Hypotheses that survived the 8-point fit and the refinement (step 3).
    pub refined: usize,
    /// Hypotheses that passed the local test (Eq. 36); equals `refined` for
    /// the baseline.
    pub local_ok: usize,
    /// Hypotheses that reached the clustering.
    pub kept: usize,
    /// Failed focal solves that left a hypothesis without focals (step 4).
    pub focal_failures: usize,
    /// Hypotheses whose focals are the prior standing in for a failed solve
    /// (step 4 with `focal_failure = "prior"`).
    pub focal_priors: usize,
}

/// Wall time of each stage of Algorithm 1, in seconds.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct StageTimings {
    /// Steps 1–2: sampling and the 8-point fits.
    pub sampling: f64,
    /// Step 3: IRLS-Tukey refinement.
    pub refine: f64,
    /// Step 4: focal estimation.
    pub focal: f64,
    /// Steps 5–6: local test, KDE consensus and band.
    pub consensus: f64,
    /// Step 7: preference matrix.
    pub preferences: f64,
    /// Steps 8–9: T-Linkage / J-Linkage and the size filter.
    pub clustering: f64,
    /// The 8-point fit of each final cluster, after the final assignment
    /// when there is one (`final_assignment = "refit"`, counted here).
    pub cluster_fit: f64,
    /// Whole segmentation.
    pub total: f64,
}

impl StageTimings {
    /// The stage names, in [`StageTimings::values`] order.
    pub const NAMES: [&'static str; 8] = [
        "sampling",
        "refine",
        "focal",
        "consensus",
        "preferences",
        "clustering",
        "cluster_fit",
        "total",
    ];

    /// The stages in [`StageTimings::NAMES`] order.
    pub fn values(&self) -> [f64; 8] {
        [
            self.sampling,
            self.refine,
            self.focal,
            self.consensus,
            self.preferences,
            self.clustering,
            self.cluster_fit,
            self.total,
        ]
    }
}

/// The output of [`crate::segment`]: labels and what a user needs to trust
/// them.
#[derive(Debug, Clone, PartialEq)]
pub struct Segmentation {
    /// One label per correspondence: 0, 1, … for the clusters, −1 for outliers.
    pub labels: Vec<i32>,
    /// Hypotheses generated / refined / passing the local test / kept.
    pub counts: HypothesisCounts,
    /// Every generated hypothesis in index order.
    pub hypotheses: Vec<Hypothesis>,
    /// The KDE focal consensus (Eq. 37) when it was computed.
    pub consensus: Option<FocalConsensus>,
    /// True when the focal filter kept every refined hypothesis because
    /// nothing passed the local test or nothing fell in the band (step 6).
    pub consensus_fallback: bool,
    /// Whether the focal consensus is plausible for the focal prior.
    pub focal_verdict: FocalVerdict,
    /// The clusters kept after the size filter, by label.
    pub clusters: Vec<ClusterModel>,
    /// Clusters before the size filter (step 9).
    pub clusters_before_filter: usize,
    /// Wall time of each stage.
    pub timings: StageTimings,
    /// `None`, or why every point is an outlier.
    pub degenerate: Option<String>,
    /// What looked wrong in the input that was still segmented
    /// ([`crate::check_matches`]): points far outside the image, an image
    /// size given as (height, width).
    pub warnings: Vec<crate::InputWarning>,
}

impl Segmentation {
    /// f_peak of the focal consensus, when computed.
    pub fn f_peak(&self) -> Option<f64> {
        self.consensus.as_ref().map(|c| c.f_peak)
    }

    /// Number of points labelled outlier (−1).
    pub fn outliers(&self) -> usize {
        self.labels.iter().filter(|&&l| l < 0).count()
    }

    /// The 8-point F of each final cluster that has one (centred coordinates).
    pub fn cluster_fundamentals(&self) -> Vec<Matrix3<f64>> {
        self.clusters.iter().filter_map(|c| c.f).collect()
    }

    /// The `f_avg = (f1 + f2)/2` values the focal consensus (step 6) was
    /// computed on: every hypothesis with focals passing the local test
    /// `|f1 − f2| / f_avg < τ_diff` (Eq. 36), in hypothesis order. Empty for
    /// the baseline (no focals are estimated).
    pub fn kde_values(&self, tau_diff: f64) -> Vec<f64> {
        self.hypotheses
            .iter()
            .filter_map(|h| h.focals)
            .filter(|&(f1, f2)| focal::passes_local_test(f1, f2, tau_diff))
            .map(|(f1, f2)| 0.5 * (f1 + f2))
            .collect()
    }
}
