//! The named switches of [`crate::Params`]: which method, which 8-point,
//! which minimal solver and which of its solutions, which focal solver,
//! which local test, what an implausible focal consensus does.

/// Declares one switch: a fieldless enum deriving `Debug, Clone, Copy,
/// PartialEq, Eq, Hash`, read and written in kebab-case with the `serde`
/// feature (`Method::Semical` is `"semical"`, `LocalTest::ReferenceCode`
/// `"reference-code"`).
macro_rules! param_enum {
    ($(#[$meta:meta])* pub enum $name:ident { $($body:tt)* }) => {
        $(#[$meta])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        #[cfg_attr(
            feature = "serde",
            derive(serde::Serialize, serde::Deserialize),
            serde(rename_all = "kebab-case")
        )]
        pub enum $name { $($body)* }
    };
}

param_enum! {
    /// Which hypotheses reach the clustering (Algorithm 1 steps 4–6).
    pub enum Method {
        /// Semi-calibrated T-Linkage: focal estimation, local test (Eq. 36) and
        /// scene-level focal consensus (Eq. 37) filter the hypotheses.
        Semical,
        /// The uncalibrated baseline: every refined hypothesis is kept.
        Baseline,
    }
}

param_enum! {
    /// The 8-point variant of Algorithm 1 step 2.
    pub enum EightPoint {
        /// Hartley-normalised 8-point (the text).
        Normalized,
        /// Un-normalised system on centred pixel coordinates (the reference code).
        Plain,
    }
}

param_enum! {
    /// The minimal solver of Algorithm 1 step 2: how each sample becomes a
    /// hypothesis F.
    pub enum MinimalSolver {
        /// The 8-point algorithm on `mss_size` matches, in the variant of
        /// [`crate::Params::eight_point`] (the thesis).
        EightPoint,
        /// The 7-point algorithm (Hartley & Zisserman §11.1.2): up to 3 F per
        /// sample of 7, uncalibrated.
        SevenPoint,
        /// The 5-point essential-matrix solver (Nistér 2004; Stewénius, Engels,
        /// Nistér 2006) in the coordinates `K(f)⁻¹ x` with `f` the focal prior:
        /// up to 10 E per sample of 5, each turned into `F = K⁻ᵀ E K⁻¹`. The one
        /// camera and its focal enter the hypotheses themselves.
        FivePoint,
        /// The 6-point solver for relative pose with one unknown focal length
        /// shared by both views (Stewénius, Nistér, Kahl, Schaffalitzky 2008):
        /// up to 15 (f, F) per sample of 6.
        SixPointFocal,
    }
}

impl MinimalSolver {
    /// The matches one sample of this solver holds (the 8-point's is
    /// [`crate::Params::mss_size`]).
    pub fn sample_size(self, mss_size: usize) -> usize {
        match self {
            Self::EightPoint => mss_size,
            Self::SevenPoint => geometry::SEVEN_POINT_SAMPLE,
            Self::FivePoint => geometry::FIVE_POINT_SAMPLE,
            Self::SixPointFocal => geometry::SIX_POINT_SAMPLE,
        }
    }
}

param_enum! {
    /// Which of a sample's solutions become hypotheses (minimal solvers other
    /// than the 8-point return several).
    pub enum MinimalSolutions {
        /// The solution with the most matches within `thr_px` (Sampson), first
        /// on ties: one hypothesis per sample, as RANSAC scores a sample.
        Best,
        /// Every solution: a sample gives as many hypotheses as real solutions.
        All,
        /// As `best`, but the five-point solutions are scored before their
        /// root polish and only the winner is polished (its consensus set
        /// then recounted): about 30 % less sampling time, the same choice
        /// unless two solutions tie to within the unpolished roots' error
        /// (a few 1e-6, relative) or a match lies that close to `thr_px`.
        /// The other solvers behave as with `best`.
        BestThenPolish,
        /// As `best-then-polish` without the polish: the winning five-point
        /// root as the Sturm sequence and its Newton steps give it (a few
        /// 1e-6 from its polish, relative) and the consensus set it was
        /// scored with. Refinement then refits it. The other solvers behave
        /// as with `best`.
        BestUnpolished,
    }
}

param_enum! {
    /// The focal-length solver of Algorithm 1 step 4.
    pub enum FocalSolver {
        /// The robust iterative solver of Kocur, Kyselica and Kukelova (CVPR 2024),
        /// multi-started over [`crate::Params::weight_sets`].
        Kocur,
        /// Bougnoux's closed form (Bougnoux 1998).
        Bougnoux,
        /// Answers computed outside this crate and handed in as data
        /// ([`crate::HypothesisFocals::from_answers`], then
        /// [`crate::segment_with`]); [`crate::segment`] refuses it.
        External,
    }
}

param_enum! {
    /// The local test of Algorithm 1 step 5 (Eq. 36).
    pub enum LocalTest {
        /// The thesis's Algorithm 1: a hypothesis failing Eq. 36 is discarded.
        Algorithm1,
        /// The reference code: only `f_avg <= 0` discards; the `|f1 - f2|` test
        /// only decides which focals feed the KDE, and the band decides for all.
        ReferenceCode,
    }
}

param_enum! {
    /// What the focal filter (steps 5–6) does when the scene's focal consensus
    /// is implausible: f_peak outside [`crate::PLAUSIBLE_FOCAL_RANGE`] times the
    /// focal prior (results/README.md: a consensus of degenerate tiny focals
    /// wins the KDE on scenes whose focal F cannot measure).
    pub enum ImplausibleFocal {
        /// Filter by the band around f_peak all the same (the thesis).
        Filter,
        /// Abstain: keep every refined hypothesis, so the labels are the
        /// baseline's bit for bit.
        Abstain,
    }
}

param_enum! {
    /// How step 1 draws the matches of a minimal sample.
    pub enum Sampling {
        /// Every match equally likely, distinct (the thesis).
        Uniform,
        /// NAPSAC (Nasuto & Craddock 2002; Torr et al. 2002), the neighbour
        /// sampling of J-Linkage and T-Linkage (Toldo & Fusiello 2008; Magri &
        /// Fusiello 2014) and of Progressive-X (P-NAPSAC, Barath & Matas 2019):
        /// the first match uniformly, the others uniformly among its
        /// [`crate::neighbourhood_size`] nearest matches in image 1
        /// ([`crate::MinimalSampler`]).
        Localized,
        /// The two in turn: even hypotheses uniform, odd ones localized, so
        /// that structures spread over the image and compact ones both get
        /// samples.
        Mixed,
        /// Mixed for the first batch of [`crate::Params::guided_batch`] samples;
        /// after it the even (uniform) turns are guided by the hypotheses
        /// drawn so far ([`crate::CoInlierKernel`], Multi-GS of Chin, Yu
        /// & Suter 2012), the odd ones stay localized.
        Guided,
    }
}

param_enum! {
    /// What follows the clustering and its size filter (step 9).
    pub enum FinalAssignment {
        /// Nothing: the labels are the clustering's (the thesis).
        None,
        /// Refit each cluster's F by IRLS-Tukey on its points, then give every
        /// match the cluster of smallest Sampson distance within `thr_px`, as
        /// Progressive-X (Barath & Matas, ICCV 2019) and consensus-space
        /// clustering (Barath et al., CVPR 2023) end ([`crate::reassign`]).
        Refit,
        /// Merge a cluster into a larger one whose model (its best-supported
        /// hypothesis) explains at least [`crate::MERGE_SHARE`] of its matches
        /// ([`crate::merge_explained`]); no match changes cluster otherwise.
        Merge,
        /// `Merge`, then a cluster also joins a larger one when the F
        /// refitted on the two together explains at least
        /// [`crate::MERGE_SHARE`] of each ([`crate::merge_refitted`]).
        MergeRefit,
        /// `Merge`, then a cluster also joins a larger one when the F
        /// refitted on the two together, started from the larger one's
        /// model, explains at least [`crate::MERGE_SHARE`] of each
        /// ([`crate::merge_anchored`]).
        MergeAnchored,
    }
}

param_enum! {
    /// Which kept hypotheses enter the preferences (step 7).
    pub enum DuplicateFilter {
        /// Every kept hypothesis (the thesis).
        None,
        /// A hypothesis whose inlier set (squared Sampson distance `≤ thr_px²`)
        /// equals that of an earlier kept hypothesis is dropped
        /// ([`crate::HypothesisStatus::Duplicate`]): each consensus set enters
        /// the preference matrix once, and T-Linkage has fewer columns.
        SameInliers,
    }
}

param_enum! {
    /// How the matches left out of a [`crate::Params::cluster_subset`] join
    /// the clusters ([`crate::extend_labels`]).
    pub enum SubsetExtension {
        /// By preference (Eq. 38): the cluster, or the subset's outliers,
        /// whose mean preference vector is nearest in Tanimoto distance
        /// (Eq. 39), as T-Linkage would join them.
        Preference,
        /// By model: the nearest, within `thr_px`, of each cluster's
        /// best-supported hypothesis (the model of [`crate::merge_explained`]).
        Model,
        /// By preference, as `Preference`, and an outlier unless the joined
        /// cluster's best-supported hypothesis explains it within `thr_px`.
        PreferenceExplained,
        /// As `Model`, each cluster's model the F refitted by IRLS-Tukey
        /// on the cluster's matches in the subset
        /// ([`crate::refitted_cluster_models`]).
        ModelRefit,
        /// As `PreferenceExplained`, each cluster's model the F refitted by
        /// IRLS-Tukey on the cluster's matches in the subset
        /// ([`crate::refitted_cluster_models`]).
        PreferenceRefit,
        /// By neighbours: the label most of the
        /// [`crate::EXTENSION_NEIGHBOURS`] nearest clustered matches in
        /// (x₁, y₁, x₂, y₂) have, the subset's outliers a class of their
        /// own, and an outlier unless that cluster's best-supported
        /// hypothesis explains it within `thr_px`.
        Neighbours,
    }
}

param_enum! {
    /// What becomes of the outliers once the clusters are final.
    pub enum RecoverOutliers {
        /// They stay outliers (the thesis).
        None,
        /// Each cluster's F is refitted by IRLS-Tukey on its matches; an
        /// outlier joins the cluster whose refitted F explains it best
        /// within `thr_px` ([`crate::recover_outliers`]).
        Refit,
    }
}
