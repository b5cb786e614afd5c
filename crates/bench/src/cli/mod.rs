//! One module per `sctl` subcommand: its clap `Args` and its `run` function.

pub mod compare;
pub mod filter_quality;
pub mod focal;
pub mod gt_focals;
pub mod hypotheses;
pub mod inspect;
pub mod merge;
pub mod metrics;
pub mod run;
pub mod segment;
pub mod synth;
pub mod tlinkage;
pub mod wilcoxon;
