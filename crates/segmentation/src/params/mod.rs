//! The parameters of Algorithm 1 ([`Params`]), nested by stage as
//! PoseLib nests its options, and the switches between the thesis text and
//! its reference implementation ([`ReferenceCode`]).
//!
//! Every parameter of docs/method.md's "Parameters" table is a field of
//! one stage of [`Params`]; its default is the thesis's Table 1 value (or
//! the text's choice where Table 1 has none). With the `serde` feature
//! [`Params`] reads from and writes to TOML/JSON as one flat map of the
//! keys of [`KEYS`] (`num_samples = 500`), unknown keys refused by name.

mod stages;
mod table;
#[cfg(test)]
mod tests;
mod validate;

pub use stages::*;
pub use table::{key, Key, KeyType, Stage, KEYS, PARAM_KEYS};
pub use validate::ParamError;

use geometry::IrlsParams;

/// Every parameter of Algorithm 1 (docs/method.md "Parameters" and the
/// switches between the thesis text and the reference code), by stage.
///
/// The defaults are the configuration chosen by its worst validation
/// family (results/README.md, "One default"; docs/method.md, "The
/// default"): hypotheses from five-point samples as essential matrices at
/// the focal prior (the one camera enters the hypotheses; a prior at 0.5–4
/// times the true focal length costs little), no focal filter, M 1000
/// drawn by guided sampling in batches of 50 with one IRLS iteration, at
/// most 1000 matches clustered and the others joined after, and the
/// motions chosen by their a-contrario significance over every match
/// (`final_assignment = "nfa"`); the thesis's Table 1 values for
/// everything else.
/// [`Params::thesis`] gives the thesis text's semi-calibrated method; the
/// reference implementation's AdelaideRMF parameters are
/// `num_samples = 5000, thr_px = 4.5, tau_diff = 0.15, tau_range = 0.25`
/// with its variants ([`ReferenceCode`]: `eight_point = "plain"`,
/// `irls_fit = "plain"`, `focal_failure = "prior"`,
/// `truncate_focals = true`, `local_test = "reference-code"`, …).
///
/// ```
/// use segmentation::{Method, MinimalSolver, Params, SamplingParams};
/// let p = Params {
///     sampling: SamplingParams { num_samples: 500, ..Default::default() },
///     ..Default::default()
/// };
/// assert_eq!(p.refinement.thr_px, 2.5); // Table 1
/// assert_eq!((p.focal.method, p.sampling.minimal_solver), (Method::Baseline, MinimalSolver::FivePoint));
/// assert!(p.validate().is_ok());
/// let thesis = Params::thesis();
/// assert_eq!(
///     (thesis.focal.method, thesis.sampling.minimal_solver),
///     (Method::Semical, MinimalSolver::EightPoint)
/// );
/// ```
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(from = "table::FlatParams", into = "table::FlatParams")
)]
pub struct Params {
    /// Steps 1–2: samples and minimal solver.
    pub sampling: SamplingParams,
    /// Step 3: the refinement.
    pub refinement: RefinementParams,
    /// Steps 4–6: the method and its focal filter.
    pub focal: FocalParams,
    /// Steps 8–9: linkage and size filter.
    pub clustering: ClusterParams,
    /// After step 9: the final labels.
    pub selection: SelectionParams,
    /// The reference implementation's variants of steps 2–5.
    pub reference_code: ReferenceCode,
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
}

impl Default for Params {
    fn default() -> Self {
        Self::thesis().with(|p| {
            p.sampling.minimal_solver = MinimalSolver::FivePoint;
            p.sampling.minimal_solutions = MinimalSolutions::BestUnpolished;
            p.sampling.num_samples = DEFAULT_NUM_SAMPLES;
            p.sampling.sampling = Sampling::Guided;
            p.sampling.guided_batch = 50;
            p.sampling.cluster_subset = DEFAULT_CLUSTER_SUBSET;
            p.refinement.irls_iters = 1;
            p.focal.method = Method::Baseline;
            p.selection.final_assignment = FinalAssignment::Nfa;
        })
    }
}

/// M of the default (Table 1: 3000). With guided sampling M 1000 gave a
/// lower ME than M 400 and 600 on every validation family, and M 1500
/// no lower than 1000 (results/README.md, "One default").
pub const DEFAULT_NUM_SAMPLES: usize = 1000;

/// The matches the default clusters (steps 1–9); the others join the
/// clusters after (`subset_extension`), then the selection labels every
/// match. With M 1000, 1000 gave the lowest ME on three validation
/// families and was within 0.2 points of 500 on the other two; 200 lost
/// 2–4 points where movers are small (results/README.md, "One default").
/// The cost beyond it grows about linearly in N.
pub const DEFAULT_CLUSTER_SUBSET: usize = 1000;

impl Params {
    /// The thesis text's semi-calibrated T-Linkage: Algorithm 1 with the
    /// Table 1 parameters, the normalised 8-point, the robust focal solver
    /// and the focal filter (`method = "semical"`,
    /// `minimal_solver = "eight-point"`).
    pub fn thesis() -> Self {
        Self {
            sampling: SamplingParams {
                num_samples: 3000,
                mss_size: 8,
                minimal_solver: MinimalSolver::EightPoint,
                minimal_solutions: MinimalSolutions::Best,
                sampling: Sampling::Uniform,
                guided_batch: 100,
                cluster_subset: 0,
                seed: 12345,
            },
            refinement: RefinementParams {
                thr_px: 2.5,
                irls_iters: 5,
                refine: true,
            },
            focal: FocalParams {
                method: Method::Semical,
                tau_diff: 0.05,
                tau_range: 0.20,
                focal_solver: FocalSolver::Kocur,
                weight_sets: WeightSets::Preset(WeightPreset::Adelaidermf),
                max_iters: 100,
            },
            clustering: ClusterParams {
                linkage: Linkage::TLinkage,
                min_cluster_size: 8,
                size_rule: SizeRule::MinSize,
            },
            selection: SelectionParams {
                final_assignment: FinalAssignment::None,
                subset_extension: SubsetExtension::PreferenceExplained,
            },
            reference_code: ReferenceCode::text(),
            max_memory_mb: 0,
        }
    }

    /// What steps 1–3 depend on ([`crate::generate_hypotheses`]): two
    /// parameter sets with equal keys give the same hypotheses on an input.
    /// The sampling and refinement stages and the reference-code variants
    /// of steps 2–3; `guided_batch` only with guided sampling.
    pub fn hypothesis_key(&self) -> HypothesisKey {
        let mut sampling = self.sampling.clone();
        if sampling.sampling != Sampling::Guided {
            sampling.guided_batch = 0;
        }
        let variants = ReferenceCode {
            focal_failure: OnFailure::Report,
            truncate_focals: false,
            local_test: LocalTest::Algorithm1,
            ..self.reference_code.clone()
        };
        HypothesisKey(format!("{:?}", (sampling, &self.refinement, variants)))
    }

    /// What step 4 depends on besides the hypotheses and the focal prior
    /// ([`crate::estimate_hypothesis_focals`]): the focal stage but the
    /// method and filter widths, its weight sets as numbers, and the
    /// reference-code variants of step 4.
    pub fn focal_key(&self) -> FocalKey {
        let solver = FocalParams {
            method: Method::Semical,
            tau_diff: 0.0,
            tau_range: 0.0,
            weight_sets: WeightSets::Explicit(Vec::new()),
            ..self.focal.clone()
        };
        let variants = (
            self.reference_code.focal_failure,
            self.reference_code.truncate_focals,
        );
        let weights = self.focal.weight_sets.key();
        FocalKey(format!("{:?}", (solver, weights, variants)))
    }

    /// How many of `n` matches steps 1–9 run on: `n`, or
    /// [`SamplingParams::cluster_subset`] when that is smaller and not 0.
    pub fn clustered_matches(&self, n: usize) -> usize {
        match self.sampling.cluster_subset {
            0 => n,
            size => size.min(n),
        }
    }

    /// The matches drawn per minimal sample (step 1): `mss_size` for the
    /// 8-point, the solver's minimal size otherwise.
    pub fn sample_size(&self) -> usize {
        self.sampling
            .minimal_solver
            .sample_size(self.sampling.mss_size)
    }

    /// The IRLS-Tukey parameters of step 3.
    pub fn irls(&self) -> IrlsParams {
        let variants = &self.reference_code;
        IrlsParams {
            thr_px: self.refinement.thr_px,
            max_iters: self.refinement.irls_iters,
            fit: variants.irls_fit,
            unit_weight_fallback: variants.irls_unit_weight_fallback,
            sigma_offset_px: variants.irls_sigma_offset_px,
            polish: variants.irls_polish,
            ..IrlsParams::default()
        }
    }
}

impl ReferenceCode {
    /// The thesis text's choice at every switch (the default).
    pub fn text() -> Self {
        Self {
            eight_point: EightPoint::Normalized,
            irls_fit: IrlsFit::Normalized,
            irls_unit_weight_fallback: true,
            irls_sigma_offset_px: 0.0,
            irls_polish: false,
            focal_failure: OnFailure::Report,
            truncate_focals: false,
            local_test: LocalTest::Algorithm1,
        }
    }
}

/// The parameters of steps 1–3 ([`Params::hypothesis_key`]), compared
/// exactly (numbers by their shortest round-trip text).
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct HypothesisKey(String);

/// The parameters of step 4 ([`Params::focal_key`]), compared exactly.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct FocalKey(String);
