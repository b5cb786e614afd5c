//! One module per `sctl` subcommand: its clap `Args` and its `run` function.

pub mod focal;
pub mod inspect;
pub mod metrics;
pub mod synth;
pub mod tlinkage;
pub mod wilcoxon;
