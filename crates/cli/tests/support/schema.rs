//! The documented schemas of the run files, for the integration tests and
//! the unit tests of `src/output` (which include this file by path).
#![allow(dead_code)]

/// The columns of `per_scene.csv` after the parameter columns, as the
/// README documents them.
pub const PER_SCENE_COLUMNS: [&str; 25] = [
    "scene",
    "n",
    "me",
    "me_all",
    "acc",
    "fnr",
    "pur",
    "ari",
    "nmi",
    "frob",
    "gt_motions",
    "gt_outliers",
    "motions",
    "outliers",
    "hypotheses_generated",
    "hypotheses_refined",
    "hypotheses_local_ok",
    "hypotheses_kept",
    "focal_failures",
    "focal_priors",
    "f_peak",
    "f_true",
    "f_peak_error",
    "focal_verdict",
    "status",
];
