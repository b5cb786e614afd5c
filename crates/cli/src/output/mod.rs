//! The files of a run directory and their exact CSV schemas.
//!
//! * `per_scene.csv`: the parameter columns of the sweep (`method` first),
//!   then the fields of [`SceneResult`]: `scene, n`, the metrics as fractions
//!   (`me, acc, fnr, pur, ari, nmi, frob`), the hypothesis counts, the focal
//!   columns and `status`.
//! * `timings.csv`: the parameter columns, then [`TIMING_FIELDS`]
//!   (`scene, n`, per-stage wall times in seconds). Timings live only here,
//!   so every other file is byte-identical across reruns and thread counts.
//!
//! Numbers are written with a fixed number of decimals (see each field).
//! Rows are appended and flushed as each (scene, combination) finishes, and
//! rewritten in run order when the run ends.

mod csv_table;
mod scene_result;
#[cfg(test)]
#[path = "../../tests/support/schema.rs"]
mod test_schema;

pub use csv_table::{write_atomic, write_bytes_atomic, CsvAppender, CsvTable};
pub use datasets::echo;
pub use scene_result::SceneResult;

/// Per-scene results, one row per (combination, scene).
pub const PER_SCENE_FILE: &str = "per_scene.csv";
/// Per-stage wall times, one row per (combination, scene).
pub const TIMINGS_FILE: &str = "timings.csv";
/// Mean ± std per combination.
pub const SUMMARY_FILE: &str = "summary.csv";
/// Wilcoxon tests of each combination against its reference.
pub const WILCOXON_FILE: &str = "wilcoxon.csv";
/// Markdown tables in the style of the thesis's Tables 2–4.
pub const REPORT_FILE: &str = "report.md";
/// The resolved experiment configuration.
pub const CONFIG_FILE: &str = "config.toml";
/// The directory of the figures inside a run directory: run-level figures
/// directly in it, per-scene figures in one subdirectory per combination.
pub const PLOTS_DIR: &str = "plots";

/// `text` usable as one file-name component: ASCII letters, digits, `-`,
/// `_` and `.` are kept, every other character becomes `_`.
pub fn file_safe(text: &str) -> String {
    text.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || matches!(c, '-' | '_' | '.') {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// Parameter `(column, value)` pairs as a file-name component:
/// `column-value` pairs joined by `__`, each made [`file_safe`]; empty for
/// no pairs.
pub fn params_file_name(params: &[(&str, &str)]) -> String {
    params
        .iter()
        .map(|(k, v)| file_safe(&format!("{k}-{v}")))
        .collect::<Vec<_>>()
        .join("__")
}

/// Columns of `timings.csv` after the parameter columns: wall seconds of each
/// stage of Algorithm 1 (6 decimals).
pub const TIMING_FIELDS: [&str; 10] = [
    "scene",
    "n",
    "sampling_s",
    "refine_s",
    "focal_s",
    "consensus_s",
    "preferences_s",
    "clustering_s",
    "cluster_fit_s",
    "total_s",
];

pub use segmentation::StageTimings;

/// Header of `per_scene.csv` for the parameter `columns`: them, then
/// [`SceneResult::fields`].
pub fn per_scene_header(columns: &[String]) -> Vec<String> {
    columns
        .iter()
        .cloned()
        .chain(SceneResult::fields())
        .collect()
}

/// Header of `timings.csv` for the parameter `columns`.
pub fn timings_header(columns: &[String]) -> Vec<String> {
    columns
        .iter()
        .cloned()
        .chain(TIMING_FIELDS.iter().map(|s| s.to_string()))
        .collect()
}

/// A `timings.csv` row after the parameter columns and `scene`.
pub fn timing_fields(n: usize, timings: &StageTimings) -> Vec<String> {
    std::iter::once(n.to_string())
        .chain(timings.values().iter().map(|v| format!("{v:.6}")))
        .collect()
}

/// The examples once in the documentation of this module's items.
#[cfg(test)]
mod examples {
    #[test]
    fn file_safe_example() {
        assert_eq!(crate::output::file_safe("2/0900"), "2_0900");
        assert_eq!(crate::output::file_safe("[1; 2]"), "_1__2_");
    }

    #[test]
    fn params_file_name_example() {
        let name = crate::output::params_file_name(&[("method", "semical"), ("tau_range", "0.1")]);
        assert_eq!(name, "method-semical__tau_range-0.1");
    }
}
