//! What a finished run derives from its `per_scene.csv`: `summary.csv`
//! (mean ± std per combination), `wilcoxon.csv` (each combination against
//! its reference) and `report.md` (tables in the style of the thesis's
//! Tables 2–4) and the run-level figures under `plots/`
//! ([`write_run_plots`]).
//!
//! Everything here reads the per-scene values back from the CSV text, so a
//! resumed or merged run derives exactly the bytes of an uninterrupted one.
//!
//! One file per job: [`stats`] (the values by combination and their mean ±
//! std), [`tables`] (`summary.csv`, `wilcoxon.csv`), [`markdown`]
//! (`report.md`), [`console`] (the end-of-run table and timings) and
//! [`figures`] (the data of the run-level figures).

mod console;
mod figures;
mod markdown;
mod stats;
mod tables;
#[cfg(test)]
mod tests;

pub use console::{console_summary, mean_timings};
pub use figures::{clear_run_plots, write_run_plots};
pub use markdown::{render_report, ReportContext};
pub use stats::{lower_is_better, summary_scale, RunValues, SUMMARY_METRICS};
pub use tables::{paired, summary_table, wilcoxon_rows, wilcoxon_table};
