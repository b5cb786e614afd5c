//! The files of a run directory and their exact CSV schemas.
//!
//! * `per_scene.csv`: the parameter columns of the sweep (`method` first),
//!   then [`PER_SCENE_FIELDS`]: `scene, n`, the metrics as fractions
//!   (`me, acc, fnr, pur, ari, nmi, frob`), the hypothesis counts, the focal
//!   columns and `status`.
//! * `timings.csv`: the parameter columns, then [`TIMING_FIELDS`]
//!   (`scene, n`, per-stage wall times in seconds). Timings live only here,
//!   so every other file is byte-identical across reruns and thread counts.
//!
//! Numbers are written with a fixed number of decimals (see each field).
//! Rows are appended and flushed as each (scene, combination) finishes, and
//! rewritten in run order when the run ends.

use crate::metrics::ClusteringMetrics;
use anyhow::{bail, Context, Result};
use std::fs::{File, OpenOptions};
use std::io::BufWriter;
use std::path::{Path, PathBuf};

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
///
/// ```
/// assert_eq!(bench::output::file_safe("2/0900"), "2_0900");
/// assert_eq!(bench::output::file_safe("[1; 2]"), "_1__2_");
/// ```
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
///
/// ```
/// let name = bench::output::params_file_name(&[("method", "semical"), ("tau_range", "0.1")]);
/// assert_eq!(name, "method-semical__tau_range-0.1");
/// ```
pub fn params_file_name(params: &[(&str, &str)]) -> String {
    params
        .iter()
        .map(|(k, v)| file_safe(&format!("{k}-{v}")))
        .collect::<Vec<_>>()
        .join("__")
}

/// Columns of `per_scene.csv` after the parameter columns.
///
/// `me … nmi` are fractions (method.md "Metrics", 6 decimals; empty without
/// ground truth); `frob` is Eq. 45 (empty when undefined); `gt_motions` and
/// `gt_outliers` count the ground-truth motions and gross outliers; `motions`
/// the clusters kept after the size filter; `outliers` the points labelled
/// −1; `hypotheses_*` the counts of Algorithm 1 (generated minimal samples,
/// refined by step 3, passing the local test of step 5, kept for the
/// clustering); `focal_failures` the failed focal solves that left a
/// hypothesis without focals (`focal_failure = "report"`); `focal_priors` the
/// hypotheses whose focals are the prior returned for a failed solve
/// (`focal_failure = "prior"`: the multi-start kept a failed solve); `f_peak` the focal
/// consensus (Eq. 37, px, 3 decimals; empty for the baseline); `f_true` the
/// true focal when known; `f_peak_error` `|f_peak − f_true| / f_true`;
/// `status` `ok` (`ok (focal filter kept all)` when nothing passed the focal
/// filter) or why every point is an outlier.
pub const PER_SCENE_FIELDS: [&str; 23] = [
    "scene",
    "n",
    "me",
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
    "status",
];

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

pub use segmentation::{HypothesisCounts, StageTimings};

/// Everything `per_scene.csv` records about one (scene, combination) besides
/// the parameters and the scene name.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneResult {
    /// Number of correspondences N.
    pub n: usize,
    /// Label metrics (None when the scene has no ground truth).
    pub metrics: Option<ClusteringMetrics>,
    /// FROB (Eq. 45), None when undefined.
    pub frob: Option<f64>,
    /// Ground-truth motions (None without ground truth).
    pub gt_motions: Option<usize>,
    /// Ground-truth gross outliers (None without ground truth).
    pub gt_outliers: Option<usize>,
    /// Clusters kept after the size filter.
    pub motions: usize,
    /// Points labelled −1.
    pub outliers: usize,
    /// Hypothesis counts.
    pub hypotheses: HypothesisCounts,
    /// Focal consensus f_peak (None for the baseline or without consensus).
    pub f_peak: Option<f64>,
    /// True focal length, when known.
    pub f_true: Option<f64>,
    /// `ok`, or why the segmentation is all outliers.
    pub status: String,
}

fn fixed(v: Option<f64>, decimals: usize) -> String {
    match v {
        Some(x) if x.is_finite() => format!("{x:.decimals$}"),
        _ => String::new(),
    }
}

fn count(v: Option<usize>) -> String {
    v.map(|x| x.to_string()).unwrap_or_default()
}

impl SceneResult {
    /// The [`PER_SCENE_FIELDS`] cells after `scene`.
    pub fn fields(&self) -> Vec<String> {
        let m = self.metrics.as_ref();
        let f_peak_error = match (self.f_peak, self.f_true) {
            (Some(p), Some(t)) => Some((p - t).abs() / t),
            _ => None,
        };
        vec![
            self.n.to_string(),
            fixed(m.map(|m| m.me), 6),
            fixed(m.map(|m| m.acc), 6),
            fixed(m.map(|m| m.fnr), 6),
            fixed(m.map(|m| m.pur), 6),
            fixed(m.map(|m| m.ari), 6),
            fixed(m.map(|m| m.nmi), 6),
            fixed(self.frob, 6),
            count(self.gt_motions),
            count(self.gt_outliers),
            self.motions.to_string(),
            self.outliers.to_string(),
            self.hypotheses.generated.to_string(),
            self.hypotheses.refined.to_string(),
            self.hypotheses.local_ok.to_string(),
            self.hypotheses.kept.to_string(),
            self.hypotheses.focal_failures.to_string(),
            self.hypotheses.focal_priors.to_string(),
            fixed(self.f_peak, 3),
            fixed(self.f_true, 3),
            fixed(f_peak_error, 6),
            self.status.clone(),
        ]
    }
}

/// Header of `per_scene.csv` for the parameter `columns`.
pub fn per_scene_header(columns: &[String]) -> Vec<String> {
    columns
        .iter()
        .cloned()
        .chain(PER_SCENE_FIELDS.iter().map(|s| s.to_string()))
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

/// A CSV file held as text cells: a header and rows.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CsvTable {
    /// Column names.
    pub header: Vec<String>,
    /// Rows, each as long as the header.
    pub rows: Vec<Vec<String>>,
}

impl CsvTable {
    /// Reads a CSV file with a header. A last line without its newline (a
    /// run killed while writing it) is dropped: it was never complete.
    pub fn read(path: &Path) -> Result<Self> {
        let mut text = std::fs::read_to_string(path)
            .with_context(|| format!("{}: cannot read", path.display()))?;
        if !text.is_empty() && !text.ends_with('\n') {
            let keep = text.rfind('\n').map_or(0, |i| i + 1);
            text.truncate(keep);
        }
        Self::parse(&text, path)
    }

    /// Parses CSV text with a header; `path` only names the source in errors.
    pub fn parse(text: &str, path: &Path) -> Result<Self> {
        let mut reader = csv::ReaderBuilder::new()
            .has_headers(true)
            .from_reader(text.as_bytes());
        let header: Vec<String> = reader
            .headers()
            .with_context(|| format!("{}: bad CSV header", path.display()))?
            .iter()
            .map(str::to_string)
            .collect();
        if header.is_empty() || header.iter().all(String::is_empty) {
            bail!("{}: empty CSV file (no header)", path.display());
        }
        let mut rows = Vec::new();
        for (i, record) in reader.records().enumerate() {
            let record = record.with_context(|| format!("{}: row {}", path.display(), i + 2))?;
            rows.push(record.iter().map(str::to_string).collect());
        }
        Ok(Self { header, rows })
    }

    /// Position of column `name`.
    pub fn column(&self, name: &str) -> Option<usize> {
        self.header.iter().position(|h| h == name)
    }

    /// Position of column `name`, or an error naming `file`.
    pub fn require_column(&self, name: &str, file: &Path) -> Result<usize> {
        self.column(name)
            .with_context(|| format!("{}: no column `{name}`", file.display()))
    }

    /// The CSV text, `\n`-terminated lines.
    pub fn to_csv(&self) -> Result<String> {
        let mut writer = csv::WriterBuilder::new()
            .terminator(csv::Terminator::Any(b'\n'))
            .from_writer(Vec::new());
        writer.write_record(&self.header)?;
        for row in &self.rows {
            writer.write_record(row)?;
        }
        let bytes = writer.into_inner().map_err(|e| anyhow::anyhow!("{e}"))?;
        Ok(String::from_utf8(bytes)?)
    }

    /// Writes the table to `path` through a temporary file and a rename, so
    /// that a crash leaves either the old or the new file.
    pub fn write_atomic(&self, path: &Path) -> Result<()> {
        write_atomic(path, &self.to_csv()?)
    }
}

/// Writes `text` to `path` through `path.tmp` and a rename.
pub fn write_atomic(path: &Path, text: &str) -> Result<()> {
    let tmp = path.with_extension("tmp");
    std::fs::write(&tmp, text).with_context(|| format!("{}: cannot write", tmp.display()))?;
    std::fs::rename(&tmp, path)
        .with_context(|| format!("{}: cannot replace with {}", path.display(), tmp.display()))
}

/// Appends CSV rows to a file, flushing after every row.
pub struct CsvAppender {
    path: PathBuf,
    writer: csv::Writer<BufWriter<File>>,
}

impl CsvAppender {
    /// Opens `path` for appending; writes `header` first when the file is
    /// new or empty, and checks it against the file's header otherwise.
    pub fn open(path: &Path, header: &[String]) -> Result<Self> {
        let existing = path.exists() && std::fs::metadata(path)?.len() > 0;
        if existing {
            let table = CsvTable::read(path)?;
            if table.header != header {
                bail!(
                    "{}: its columns ({}) are not this run's ({}); use another --out directory",
                    path.display(),
                    table.header.join(","),
                    header.join(",")
                );
            }
            // Drop an incomplete last line before appending after it.
            let text = table.to_csv()?;
            if std::fs::read_to_string(path)? != text {
                write_atomic(path, &text)?;
            }
        }
        let file = OpenOptions::new()
            .create(true)
            .append(true)
            .open(path)
            .with_context(|| format!("{}: cannot open for appending", path.display()))?;
        let mut writer = csv::WriterBuilder::new()
            .terminator(csv::Terminator::Any(b'\n'))
            .from_writer(BufWriter::new(file));
        if !existing {
            writer.write_record(header)?;
            writer.flush()?;
        }
        Ok(Self {
            path: path.to_path_buf(),
            writer,
        })
    }

    /// Appends one row and flushes it to the file (`csv::Writer::flush`
    /// also flushes the buffered file).
    pub fn append(&mut self, row: &[String]) -> Result<()> {
        self.writer
            .write_record(row)
            .with_context(|| format!("{}: cannot append", self.path.display()))?;
        self.writer
            .flush()
            .with_context(|| format!("{}: cannot flush", self.path.display()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fields_match_the_header() {
        let r = SceneResult {
            n: 10,
            metrics: Some(ClusteringMetrics {
                me: 0.1,
                me_all: 0.15,
                acc: 0.9,
                fnr: 0.2,
                pur: 0.95,
                ari: 0.5,
                nmi: 2.0 / 3.0,
            }),
            frob: None,
            gt_motions: Some(2),
            gt_outliers: Some(3),
            motions: 2,
            outliers: 4,
            hypotheses: HypothesisCounts {
                generated: 100,
                refined: 90,
                local_ok: 40,
                kept: 35,
                focal_failures: 7,
                focal_priors: 0,
            },
            f_peak: Some(1000.0),
            f_true: Some(800.0),
            status: "ok".into(),
        };
        let fields = r.fields();
        assert_eq!(fields.len() + 1, PER_SCENE_FIELDS.len());
        assert_eq!(fields[6], "0.666667");
        assert_eq!(fields[7], "");
        assert_eq!(fields[9], "3");
        assert_eq!(fields[16], "7");
        assert_eq!(fields[17], "0");
        assert_eq!(fields[18], "1000.000");
        assert_eq!(fields[20], "0.250000");
        assert_eq!(fields[21], "ok");
    }

    #[test]
    fn appender_writes_header_once_and_drops_a_torn_line() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("x.csv");
        let header: Vec<String> = vec!["a".into(), "b".into()];
        {
            let mut w = CsvAppender::open(&path, &header).unwrap();
            w.append(&["1".into(), "x,y".into()]).unwrap();
        }
        // A killed writer leaves half a line.
        let mut text = std::fs::read_to_string(&path).unwrap();
        text.push_str("2,unfinis");
        std::fs::write(&path, &text).unwrap();
        {
            let mut w = CsvAppender::open(&path, &header).unwrap();
            w.append(&["3".into(), "z".into()]).unwrap();
        }
        assert_eq!(
            std::fs::read_to_string(&path).unwrap(),
            "a,b\n1,\"x,y\"\n3,z\n"
        );
        let other: Vec<String> = vec!["a".into(), "c".into()];
        let err = CsvAppender::open(&path, &other).err().unwrap().to_string();
        assert!(err.contains("are not this run's"), "{err}");
    }
}
