//! The semi-calibrated T-Linkage pipeline (Algorithm 1) as a library, and the
//! evaluation harness behind the `sctl` binary.

pub mod metrics;
pub mod wilcoxon;
