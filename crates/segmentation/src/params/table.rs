//! The one list of the parameter keys ([`KEYS`]): name, stage, type,
//! allowed values and a one-line doc of each, in the order of the output
//! columns. From it come [`PARAM_KEYS`], the flat TOML/JSON form of
//! [`Params`] (one key per field, unknown keys refused) and, in the
//! harness, the key list of `sctl run --help`, the README's key table and
//! the Python stub's `segment` signature.

#[cfg(feature = "serde")]
use super::stages::*;
// Without serde only the doc links below name it.
#[cfg_attr(not(feature = "serde"), allow(unused_imports))]
use super::Params;

/// The stage of Algorithm 1 a key belongs to: the field of [`Params`]
/// that holds it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Stage {
    /// [`Params::sampling`] (steps 1–2).
    Sampling,
    /// [`Params::refinement`] (step 3).
    Refinement,
    /// [`Params::focal`] (steps 4–6).
    Focal,
    /// [`Params::clustering`] (steps 8–9).
    Clustering,
    /// [`Params::selection`] (after step 9).
    Selection,
    /// [`Params::reference_code`] (the reference implementation's variants).
    ReferenceCode,
    /// A field of [`Params`] itself ([`Params::max_memory_mb`]).
    Limits,
}

impl Stage {
    /// The field of [`Params`] (`limits` for the top-level keys).
    pub fn name(self) -> &'static str {
        match self {
            Stage::Sampling => "sampling",
            Stage::Refinement => "refinement",
            Stage::Focal => "focal",
            Stage::Clustering => "clustering",
            Stage::Selection => "selection",
            Stage::ReferenceCode => "reference_code",
            Stage::Limits => "limits",
        }
    }
}

/// The kind of value a key takes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum KeyType {
    /// A non-negative integer.
    Int,
    /// A number.
    Float,
    /// `true` or `false`.
    Bool,
    /// One of the names of [`Key::allowed`], separated by ` | `.
    Choice,
    /// A preset name or a list of weight sets ([`WeightSets`](super::WeightSets)).
    WeightSets,
    /// A rule name or `{ relative-min = f }` ([`SizeRule`](super::SizeRule)).
    SizeRule,
}

/// One parameter key.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Key {
    /// The key in TOML, JSON and Python, and the field of its stage.
    pub name: &'static str,
    /// Its stage.
    pub stage: Stage,
    /// The kind of value.
    pub ty: KeyType,
    /// The values it takes: the names of a choice separated by ` | `, else
    /// a short range (empty when any value of the type is allowed).
    pub allowed: &'static str,
    /// What it does, in one line.
    pub doc: &'static str,
}

/// `$p.$field` for a top-level key (`limits`), `$p.$stage.$field` otherwise.
#[cfg(feature = "serde")]
macro_rules! at {
    ($p:expr, limits, $field:ident) => {
        $p.$field
    };
    ($p:expr, $stage:ident, $field:ident) => {
        $p.$stage.$field
    };
}

/// Declares [`KEYS`], [`PARAM_KEYS`] and the flat wire form of
/// [`Params`] from one list of `stage.name: Type, KeyType, allowed, doc`.
macro_rules! param_keys {
    ($($stage:ident . $name:ident : $ty:ty, $kind:ident, $allowed:literal, $doc:literal;)*) => {
        /// Every parameter key, in the order of the output columns.
        pub const KEYS: &[Key] = &[$(Key {
            name: stringify!($name),
            stage: stage_of(stringify!($stage)),
            ty: KeyType::$kind,
            allowed: $allowed,
            doc: $doc,
        }),*];

        /// [`Params`] as TOML and JSON read and write it: one flat map of
        /// [`KEYS`], a missing key taking [`Params::default`]'s value.
        #[cfg(feature = "serde")]
        #[derive(serde::Serialize, serde::Deserialize)]
        #[serde(deny_unknown_fields, default)]
        pub(super) struct FlatParams {
            $($name: $ty,)*
        }

        #[cfg(feature = "serde")]
        impl From<Params> for FlatParams {
            fn from(p: Params) -> Self {
                Self { $($name: at!(p, $stage, $name),)* }
            }
        }

        #[cfg(feature = "serde")]
        impl From<FlatParams> for Params {
            fn from(flat: FlatParams) -> Self {
                let mut p = Params::default();
                $(at!(p, $stage, $name) = flat.$name;)*
                p
            }
        }
    };
}

/// The [`Stage`] of a stage field's name (`limits` for the top level).
const fn stage_of(name: &str) -> Stage {
    match name.as_bytes() {
        b"sampling" => Stage::Sampling,
        b"refinement" => Stage::Refinement,
        b"focal" => Stage::Focal,
        b"clustering" => Stage::Clustering,
        b"selection" => Stage::Selection,
        b"reference_code" => Stage::ReferenceCode,
        b"limits" => Stage::Limits,
        _ => panic!("unknown stage"),
    }
}

param_keys! {
    focal.method: Method, Choice, "baseline | semical",
        "baseline: every refined hypothesis kept; semical: the focal filter of Algorithm 1 (steps 4-6)";
    sampling.num_samples: usize, Int, ">= 1", "M, minimal samples drawn per scene";
    sampling.mss_size: usize, Int, ">= 8", "matches per minimal sample of the 8-point";
    refinement.thr_px: f64, Float, "> 0", "inlier threshold (px); tau = thr_px^2 (Eq. 38)";
    focal.tau_diff: f64, Float, "> 0", "local test |f1 - f2| / f_avg < tau_diff (Eq. 36)";
    focal.tau_range: f64, Float, "> 0", "focal band |f_avg - f_peak| / f_peak <= tau_range (Eq. 37)";
    refinement.irls_iters: usize, Int, ">= 1 when refine", "IRLS-Tukey outer iterations (Eqs. 33-34)";
    reference_code.irls_fit: IrlsFit, Choice, "normalized | plain",
        "IRLS weighted refit: Hartley-normalised (the text) or plain (reference code)";
    reference_code.irls_unit_weight_fallback: bool, Bool, "",
        "fewer than 8 positive Tukey weights: refit with unit weights (true) or drop (false)";
    reference_code.irls_sigma_offset_px: f64, Float, ">= 0",
        "sigma = 1.4826 MAD + this (reference code: 1e-12)";
    reference_code.irls_polish: bool, Bool, "",
        "LM polish of each sample's F before IRLS (reference code)";
    refinement.refine: bool, Bool, "", "false: the raw minimal-sample F (ablation)";
    reference_code.eight_point: EightPoint, Choice, "normalized | plain",
        "8-point on Hartley-normalised (the text) or plain pixels (reference code)";
    sampling.minimal_solver: MinimalSolver, Choice, "five-point | eight-point",
        "five-point: E at the focal prior; eight-point: the thesis";
    sampling.minimal_solutions: MinimalSolutions, Choice, "best | best-unpolished",
        "a five-point sample's hypothesis: its best root, or that root unpolished (faster)";
    sampling.sampling: Sampling, Choice, "uniform | localized | guided",
        "sample draws: uniform, NAPSAC neighbours, or both in turn guided by co-inliers";
    sampling.guided_batch: usize, Int, ">= 1", "samples per batch of guided sampling (the first unguided)";
    focal.focal_solver: FocalSolver, Choice, "kocur | bougnoux | external",
        "focal solver (step 4); external: answers handed in";
    focal.weight_sets: WeightSets, WeightSets, "adelaidermf | hopef | [[w_f1, w_pp1, w_f2, w_pp2], ...]",
        "the robust focal solver's multi-start weight sets";
    focal.max_iters: usize, Int, ">= 1", "robust focal solver iterations";
    reference_code.focal_failure: OnFailure, Choice, "report | prior",
        "a failed focal solve: reported, or the priors (reference code)";
    reference_code.truncate_focals: bool, Bool, "", "f1, f2 truncated to integers (reference code)";
    reference_code.local_test: LocalTest, Choice, "algorithm1 | reference-code",
        "local test (Eq. 36): the thesis's, or the reference code's";
    clustering.linkage: Linkage, Choice, "t-linkage | j-linkage", "clustering (step 8)";
    clustering.min_cluster_size: usize, Int, "", "smaller clusters become outliers (step 9)";
    clustering.size_rule: SizeRule, SizeRule, "min-size | { relative-min = f }",
        "clusters kept: min_cluster_size alone, or also >= ceil(f N) points";
    selection.final_assignment: FinalAssignment, Choice, "nfa | merge | none",
        "nfa: the clusters whose F is significant (NFA < 1) and whose matches are coherent along the epipolar lines are the motions; merge: 80 % rule";
    sampling.cluster_subset: usize, Int, "0 or >= mss_size",
        "> 0: steps 1-9 on this many random matches, the others joined after";
    selection.subset_extension: SubsetExtension, Choice, "preference-explained | preference",
        "left-out matches join the nearest mean preference (explained: within thr_px of its model)";
    limits.max_memory_mb: u64, Int, "", "refuse a scene that would need more MB (0: the memory available)";
    sampling.seed: u64, Int, "", "sampling seed";
}

/// The keys of [`KEYS`], in order.
pub const PARAM_KEYS: [&str; KEYS.len()] = {
    let mut names = [""; KEYS.len()];
    let mut i = 0;
    while i < KEYS.len() {
        names[i] = KEYS[i].name;
        i += 1;
    }
    names
};

/// The [`Key`] called `name`.
pub fn key(name: &str) -> Option<&'static Key> {
    KEYS.iter().find(|k| k.name == name)
}

#[cfg(feature = "serde")]
impl Default for FlatParams {
    fn default() -> Self {
        Params::default().into()
    }
}
