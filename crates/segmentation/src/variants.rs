//! The named switches of [`crate::Params`]: which method, which 8-point,
//! which minimal solver and which of its solutions, which focal solver,
//! which local test, how samples are drawn and what follows the clustering.

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
        /// [`crate::ReferenceCode::eight_point`] (the thesis).
        EightPoint,
        /// The 5-point essential-matrix solver (Nistér 2004; Stewénius, Engels,
        /// Nistér 2006) in the coordinates `K(f)⁻¹ x` with `f` the focal prior:
        /// up to 10 E per sample of 5, each turned into `F = K⁻ᵀ E K⁻¹`. The one
        /// camera and its focal enter the hypotheses themselves.
        FivePoint,
    }
}

impl MinimalSolver {
    /// The matches one sample of this solver holds (the 8-point's is
    /// [`crate::SamplingParams::mss_size`]).
    pub fn sample_size(self, mss_size: usize) -> usize {
        match self {
            Self::EightPoint => mss_size,
            Self::FivePoint => geometry::FIVE_POINT_SAMPLE,
        }
    }
}

param_enum! {
    /// Which of a five-point sample's solutions becomes its hypothesis (the
    /// solver returns up to 10).
    pub enum MinimalSolutions {
        /// The solution with the most matches within `thr_px` (Sampson), first
        /// on ties: one hypothesis per sample, as RANSAC scores a sample.
        Best,
        /// As `best`, but the five-point solutions are scored before their
        /// root polish and the winner is left unpolished: the root as the
        /// Sturm sequence and its Newton steps give it (a few 1e-6 from its
        /// polish, relative) and the consensus set it was scored with.
        /// Refinement then refits it. The 8-point behaves as with `best`.
        BestUnpolished,
    }
}

param_enum! {
    /// The focal-length solver of Algorithm 1 step 4.
    pub enum FocalSolver {
        /// The robust iterative solver of Kocur, Kyselica and Kukelova (CVPR 2024),
        /// multi-started over [`crate::FocalParams::weight_sets`].
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
        /// For the first batch of [`crate::SamplingParams::guided_batch`] samples,
        /// even hypotheses uniform and odd ones localized; after it the even
        /// (uniform) turns are guided by the hypotheses
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
        /// Merge a cluster into a larger one whose model (its best-supported
        /// hypothesis) explains at least [`crate::MERGE_SHARE`] of its matches
        /// ([`crate::merge_explained`]); no match changes cluster otherwise.
        Merge,
        /// A-contrario model selection over every match
        /// ([`crate::selection::select_groups`]): a cluster is a motion when
        /// the number of false alarms of its F is below 1 given the motions
        /// detected before it (Moisan & Stival 2004; AC-RANSAC, Moisan,
        /// Moulon & Monasse 2012; MAC-RANSAC, Rabin et al. 2010); the
        /// other clusters join the detected F that explains most of their
        /// matches; matches of no cluster (the clustering's outliers and
        /// those left out of a `cluster_subset`) take the nearest detected
        /// F within `thr_px`; the rest are outliers.
        Nfa,
    }
}

param_enum! {
    /// How the matches left out of a [`crate::SamplingParams::cluster_subset`] join
    /// the clusters ([`crate::extend_labels`]).
    pub enum SubsetExtension {
        /// By preference (Eq. 38): the cluster, or the subset's outliers,
        /// whose mean preference vector is nearest in Tanimoto distance
        /// (Eq. 39), as T-Linkage would join them.
        Preference,
        /// By preference, as `Preference`, and an outlier unless the joined
        /// cluster's best-supported hypothesis (the model of
        /// [`crate::merge_explained`]) explains it within `thr_px`.
        PreferenceExplained,
    }
}
