#![warn(missing_docs)]
//! The semi-calibrated T-Linkage pipeline (Algorithm 1) as a library, and the
//! evaluation harness behind the `sctl` binary.

pub mod compare;
pub mod config;
pub mod dataset;
pub mod evaluate;
pub mod experiment;
pub mod focal_file;
pub use metrics;
pub mod output;
pub mod pipeline;
pub mod plots;
pub mod quality;
pub mod report;
pub mod sweep;
pub mod wilcoxon;
