#![warn(missing_docs)]
//! The semi-calibrated T-Linkage pipeline (Algorithm 1) run over datasets,
//! and the evaluation harness behind the `sctl` binary.
//!
//! The public API is what other programs need: [`cli::main`] (the whole of
//! `sctl`), the experiment file ([`config`]), the scenes of its `[dataset]`
//! table ([`dataset::load_scenes`]) and Algorithm 1 on one scene with its
//! `[pipeline]` table ([`pipeline`]). The harness (runs, reports, figures,
//! statistics) is private: it is reached through `sctl`.

pub mod cli;
mod compare;
pub mod config;
pub mod dataset;
mod evaluate;
mod experiment;
mod focal_file;
mod output;
pub mod pipeline;
mod plots;
mod quality;
mod report;
mod sweep;
mod wilcoxon;
