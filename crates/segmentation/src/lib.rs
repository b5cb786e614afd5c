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
//!    guided by the hypotheses so far ([`CoInlierKernel`]), M fixed or
//!    adaptive ([`SupportTracker`]);
//! 2. the 8-point F of each (Hartley-normalised or plain, [`EightPoint`]);
//! 3. IRLS-Tukey refinement ([`generate_hypotheses`]);
//! 4. focal lengths of each F ([`estimate_hypothesis_focals`]: the robust
//!    Kocur–Kyselica–Kukelova solver or Bougnoux's formula, or answers
//!    handed in as data, [`HypothesisFocals::from_answers`]);
//! 5. the local test (Eq. 36) and 6. the KDE focal consensus and band
//!    (Eq. 37) ([`focal_filter`]) — the `semical` method; the `baseline`
//!    keeps every refined hypothesis;
//! 7. preferences (Eq. 38), 8. T-Linkage (Eqs. 39–40) or J-Linkage and
//! 9. the size filter ([`segment_with`]), optionally followed by a final
//!    assignment to refitted cluster models ([`reassign`]), merges of the
//!    clusters one model explains ([`merge_explained`], [`merge_refitted`],
//!    [`merge_anchored`]) and the outliers' recovery by refitted cluster
//!    models ([`recover_outliers`]). On a large
//!    scene steps 1–9 may run on a random subset of the matches, the
//!    others joining the clusters afterwards ([`extend_labels`]: by
//!    preference, by sampled or refitted cluster models
//!    ([`refitted_cluster_models`]) or by their nearest clustered
//!    neighbours ([`EXTENSION_NEIGHBOURS`])).
//!
//! All geometry runs in principal-point-centred pixel coordinates: every F
//! of a [`Segmentation`] satisfies `x2ᵀ F x1 = 0` for
//! `x = (x − pp_x, y − pp_y, 1)`. The labels depend on the input, the
//! parameters and [`Params::seed`] only, not on the number of threads
//! (hypotheses are computed in the caller's rayon pool).

mod adaptive;
mod assignment;
mod error;
mod filter;
mod focals;
mod guided;
mod hypotheses;
mod input;
mod mean_preference;
mod merge;
mod merge_refit;
mod minimal;
mod neighbours;
mod params;
mod profile;
mod result;
mod sampling;
mod segment;
pub mod selection;
mod subset;
mod variants;
mod weight_sets;

pub use adaptive::{SupportTracker, SUPPORT_GAIN};
pub use assignment::{reassign, recover_outliers, CLUSTER_REFIT_ITERS};
pub use error::SegmentationError;
pub use filter::{focal_filter, focal_verdict, FilterOutcome, PLAUSIBLE_FOCAL_RANGE};
pub use focal::FocalConsensus;
pub use focals::{
    estimate_focals, estimate_hypothesis_focals, focals_as_used, FocalAnswer, HypothesisFocals,
};
pub use guided::{CoInlierKernel, CoInliers};
pub use hypotheses::{centred_points, generate_hypotheses, GeneratedHypotheses};
pub use input::{image_centre, Matches};
pub use merge::{merge_explained, InlierBits, MERGE_SHARE};
pub use merge_refit::{merge_anchored, merge_refitted};
pub use neighbours::EXTENSION_NEIGHBOURS;
pub use params::{
    DuplicateFilter, EightPoint, FinalAssignment, FocalKey, FocalSolver, HypothesisKey,
    ImplausibleFocal, IrlsFit, Linkage, LocalTest, Method, MinimalSolutions, MinimalSolver,
    OnFailure, ParamError, Params, RecoverOutliers, Sampling, SizeRule, SubsetExtension,
    WeightPreset, WeightSets, PARAM_KEYS,
};
pub use profile::Profile;
pub use result::{
    ClusterModel, FocalVerdict, Hypothesis, HypothesisCounts, HypothesisStatus, Segmentation,
    StageTimings,
};
pub use sampling::{
    hypothesis_rng, minimal_sample, neighbourhood_size, splitmix64, MinimalSampler,
};
pub use segment::{fit_cluster, segment, segment_with};
pub use selection::{select, Selection, SelectionError, Strategy};
pub use subset::{extend_labels, refitted_cluster_models, subset_indices, ClusteredSubset};
