#![warn(missing_docs)]
//! Two-view motion segmentation with semi-calibrated cameras: Algorithm 1 of
//! the thesis ("Two-View Motion Segmentation with Semi-Calibrated Cameras via
//! Hypothesis Filtering") as a library.
//!
//! Given point matches between two images taken by one camera of unknown
//! focal length, [`segment`] splits them into rigid motions (labels 0, 1, …)
//! and outliers (−1):
//!
//! 1. M minimal samples, drawn per hypothesis from its own random stream,
//!    uniformly ([`minimal_sample`]), localized ([`MinimalSampler`]) or
//!    guided by the hypotheses so far ([`CoInlierKernel`]);
//! 2. the 8-point F of each (Hartley-normalised or plain, [`EightPoint`]),
//!    or the five-point E at the focal prior ([`MinimalSolver`]);
//! 3. IRLS-Tukey refinement ([`generate_hypotheses`]);
//! 4. focal lengths of each F ([`estimate_hypothesis_focals`]: the robust
//!    Kocur–Kyselica–Kukelova solver or Bougnoux's formula, or answers
//!    handed in as data, [`HypothesisFocals::from_answers`]);
//! 5. the local test (Eq. 36) and 6. the KDE focal consensus and band
//!    (Eq. 37) ([`focal_filter`]) — the `semical` method; the `baseline`
//!    keeps every refined hypothesis;
//! 7. preferences (Eq. 38), 8. T-Linkage (Eqs. 39–40) or J-Linkage and
//! 9. the size filter ([`segment_with`]), optionally followed by merges of
//!    the clusters one model explains ([`merge_explained`]). On a large
//!    scene steps 1–9 may run on a random subset of the matches, the
//!    others joining the clusters afterwards by preference, optionally
//!    checked against each cluster's model ([`extend_labels`]).
//!
//! All geometry runs in principal-point-centred pixel coordinates: every F
//! of a [`Segmentation`] satisfies `x2ᵀ F x1 = 0` for
//! `x = (x − pp_x, y − pp_y, 1)`. The labels depend on the input, the
//! parameters and [`SamplingParams::seed`] only, not on the number of threads
//! (hypotheses are computed in the caller's rayon pool).

mod assignment;
mod control;
mod error;
mod filter;
mod focals;
mod guided;
mod hypotheses;
mod input;
mod input_check;
mod mean_preference;
mod memory_guard;
mod merge;
mod minimal;
mod params;
mod profile;
mod result;
mod sampling;
mod segment;
pub mod selection;
mod subset;
mod variants;
mod weight_sets;

pub use control::Cancel;
pub use error::SegmentationError;
pub use filter::{focal_filter, focal_verdict, FilterOutcome, PLAUSIBLE_FOCAL_RANGE};
pub use focal::FocalConsensus;
pub use focals::{
    estimate_focals, estimate_hypothesis_focals, focals_as_used, FocalAnswer, HypothesisFocals,
};
pub use guided::{CoInlierKernel, CoInliers};
pub use hypotheses::{
    centred_points, generate_hypotheses, generate_hypotheses_cancellable, GeneratedHypotheses,
};
pub use input::{image_centre, Matches};
pub use input_check::{check_matches, InputWarning, MAX_COORDINATE_PX, OUTSIDE_MARGIN_IMAGES};
pub use memory_guard::{
    available_memory, check_available_memory, mem_available, memory_need, MemoryNeed,
};
pub use merge::{merge_explained, InlierBits, MERGE_SHARE};
pub use params::{
    key, ClusterParams, EightPoint, FinalAssignment, FocalKey, FocalParams, FocalSolver,
    HypothesisKey, IrlsFit, Key, KeyType, Linkage, LocalTest, Method, MinimalSolutions,
    MinimalSolver, OnFailure, ParamError, Params, ReferenceCode, RefinementParams, Sampling,
    SamplingParams, SelectionParams, SizeRule, Stage, SubsetExtension, WeightPreset, WeightSets,
    KEYS, PARAM_KEYS,
};
pub use profile::Profile;
pub use result::{
    ClusterModel, FocalVerdict, Hypothesis, HypothesisCounts, HypothesisStatus, Segmentation,
    StageTimings,
};
pub use sampling::{
    hypothesis_rng, minimal_sample, neighbourhood_size, splitmix64, MinimalSampler,
};
pub use segment::{
    check_memory, fit_cluster, segment, segment_cancellable, segment_with, segment_with_cancellable,
};
pub use selection::{select, Selection, SelectionError};
pub use subset::{extend_labels, subset_indices, ClusteredSubset};
