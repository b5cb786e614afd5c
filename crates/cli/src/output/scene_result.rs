//! One row of `per_scene.csv` after the parameter columns, typed: the
//! struct's fields are the columns, in order, and their serde attributes
//! the number formats. Adding a column is adding a field here.

use anyhow::{Context, Result};
use metrics::ClusteringMetrics;
use segmentation::HypothesisCounts;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// Everything `per_scene.csv` records about one (combination, scene) besides
/// the parameters.
///
/// `me … nmi` are fractions (docs/method.md "Metrics", 6 decimals; empty without
/// ground truth); `frob` is Eq. 45 (empty when undefined); `f_peak` and
/// `f_true` in pixels with 3 decimals, `f_peak_error` with 6; a count
/// without ground truth is empty.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct SceneResult {
    /// The scene name.
    pub scene: String,
    /// Number of correspondences N.
    pub n: usize,
    /// Misclassification error (docs/method.md "Metrics"; the thesis's:
    /// ground-truth outliers excluded, a predicted outlier wrong).
    #[serde(with = "decimals_6")]
    pub me: Option<f64>,
    /// Misclassification error over all points, outliers a class of their
    /// own (the multi-model fitting literature's).
    #[serde(with = "decimals_6")]
    pub me_all: Option<f64>,
    /// Accuracy.
    #[serde(with = "decimals_6")]
    pub acc: Option<f64>,
    /// False-negative rate.
    #[serde(with = "decimals_6")]
    pub fnr: Option<f64>,
    /// Purity.
    #[serde(with = "decimals_6")]
    pub pur: Option<f64>,
    /// Adjusted Rand index.
    #[serde(with = "decimals_6")]
    pub ari: Option<f64>,
    /// Normalised mutual information.
    #[serde(with = "decimals_6")]
    pub nmi: Option<f64>,
    /// FROB (Eq. 45), empty when undefined.
    #[serde(with = "decimals_6")]
    pub frob: Option<f64>,
    /// Ground-truth motions (empty without ground truth).
    pub gt_motions: Option<usize>,
    /// Ground-truth gross outliers (empty without ground truth).
    pub gt_outliers: Option<usize>,
    /// Clusters kept after the size filter.
    pub motions: usize,
    /// Points labelled −1.
    pub outliers: usize,
    /// Minimal samples generated (Algorithm 1, step 1).
    pub hypotheses_generated: usize,
    /// Hypotheses refined by step 3.
    pub hypotheses_refined: usize,
    /// Hypotheses passing the local test of step 5.
    pub hypotheses_local_ok: usize,
    /// Hypotheses kept for the clustering.
    pub hypotheses_kept: usize,
    /// Failed focal solves that left a hypothesis without focals
    /// (`focal_failure = "report"`).
    pub focal_failures: usize,
    /// Hypotheses whose focals are the prior returned for a failed solve
    /// (`focal_failure = "prior"`: the multi-start kept a failed solve).
    pub focal_priors: usize,
    /// The focal consensus (Eq. 37, px; empty for the baseline).
    #[serde(with = "decimals_3")]
    pub f_peak: Option<f64>,
    /// The true focal, when known.
    #[serde(with = "decimals_3")]
    pub f_true: Option<f64>,
    /// `|f_peak − f_true| / f_true`, when both are known.
    #[serde(with = "decimals_6")]
    pub f_peak_error: Option<f64>,
    /// The focal consensus against the focal prior: `plausible` (f_peak
    /// within 0.3–3 × prior), `implausible`, `none` (no hypothesis passed
    /// the local test); empty when no focal was estimated.
    pub focal_verdict: String,
    /// `ok` (`ok (focal filter kept all)` when nothing passed the focal
    /// filter), why every point is an outlier, or `failed: REASON` when the
    /// scene could not be segmented (refused for memory, bad input): no
    /// metrics then, and the summaries leave the row out of their means.
    pub status: String,
}

/// The start of the `status` of a scene that could not be segmented.
pub const FAILED_STATUS: &str = "failed: ";

impl SceneResult {
    /// The column names, in order: the field names.
    pub fn fields() -> Vec<String> {
        let mut writer = csv::Writer::from_writer(Vec::new());
        writer
            .serialize(Self::default())
            .expect("a SceneResult serialises");
        let bytes = writer.into_inner().expect("an in-memory writer");
        let mut reader = csv::Reader::from_reader(bytes.as_slice());
        reader
            .headers()
            .expect("the header just written")
            .iter()
            .map(str::to_string)
            .collect()
    }

    /// The row of a scene that could not be segmented: its size and ground
    /// truth counts, no metrics, and `status` [`FAILED_STATUS`]`reason`.
    pub fn failed(scene: &datasets::Scene, reason: &str) -> Self {
        Self {
            scene: scene.name.clone(),
            n: scene.len(),
            gt_motions: scene.labels.as_ref().map(|_| scene.num_motions()),
            gt_outliers: scene.labels.as_ref().map(|_| scene.num_outliers()),
            status: format!("{FAILED_STATUS}{reason}"),
            ..Self::default()
        }
    }

    /// Why the scene could not be segmented, for a [`SceneResult::failed`] row.
    pub fn failure(&self) -> Option<&str> {
        self.status.strip_prefix(FAILED_STATUS)
    }

    /// Sets the label metrics (docs/method.md "Metrics").
    pub fn set_metrics(&mut self, m: &ClusteringMetrics) {
        self.me = Some(m.me);
        self.me_all = Some(m.me_all);
        self.acc = Some(m.acc);
        self.fnr = Some(m.fnr);
        self.pur = Some(m.pur);
        self.ari = Some(m.ari);
        self.nmi = Some(m.nmi);
    }

    /// Sets the hypothesis counts of Algorithm 1.
    pub fn set_hypotheses(&mut self, h: &HypothesisCounts) {
        self.hypotheses_generated = h.generated;
        self.hypotheses_refined = h.refined;
        self.hypotheses_local_ok = h.local_ok;
        self.hypotheses_kept = h.kept;
        self.focal_failures = h.focal_failures;
        self.focal_priors = h.focal_priors;
    }

    /// Sets `f_peak`, `f_true` and the relative error between them.
    pub fn set_focal(&mut self, f_peak: Option<f64>, f_true: Option<f64>) {
        self.f_peak = f_peak;
        self.f_true = f_true;
        self.f_peak_error = match (f_peak, f_true) {
            (Some(p), Some(t)) => Some((p - t).abs() / t),
            _ => None,
        };
    }

    /// The cells of the row, one per [`SceneResult::fields`].
    pub fn cells(&self) -> Vec<String> {
        let mut writer = csv::WriterBuilder::new()
            .has_headers(false)
            .from_writer(Vec::new());
        writer.serialize(self).expect("a SceneResult serialises");
        let bytes = writer.into_inner().expect("an in-memory writer");
        let mut reader = csv::ReaderBuilder::new()
            .has_headers(false)
            .from_reader(bytes.as_slice());
        let record = reader
            .records()
            .next()
            .expect("the row just written")
            .expect("a valid CSV row");
        record.iter().map(str::to_string).collect()
    }

    /// The row of `cells` (the cells after the parameter columns, named by
    /// `header`); errors name `file` and the 1-based `line`.
    pub fn from_cells(
        header: &[String],
        cells: &[String],
        file: &Path,
        line: usize,
    ) -> Result<Self> {
        let header = csv::StringRecord::from(header.to_vec());
        csv::StringRecord::from(cells.to_vec())
            .deserialize(Some(&header))
            .map_err(|e| anyhow::anyhow!("{}", deserialize_message(&e, cells)))
            .with_context(|| format!("{}: row {line}", file.display()))
    }
}

/// The message of a row's deserialisation error without csv's record
/// position (the caller names the file and row), with the 1-based field.
/// csv knows the field of its own parse errors; for a decimal cell's error
/// (which quotes the cell in backticks) it is the first cell quoted.
fn deserialize_message(err: &csv::Error, cells: &[String]) -> String {
    match err.kind() {
        csv::ErrorKind::Deserialize { err, .. } => {
            let message = err.kind().to_string();
            let field = err.field().map(|f| f as usize).or_else(|| {
                cells
                    .iter()
                    .position(|c| message.contains(&format!("`{c}`")))
            });
            match field {
                Some(field) => format!("field {}: {message}", field + 1),
                None => message,
            }
        }
        _ => err.to_string(),
    }
}

/// `Option<f64>` as a cell with a fixed number of decimals; empty for None
/// and for a value that is not finite.
macro_rules! decimals {
    ($name:ident, $decimals:expr) => {
        mod $name {
            use serde::{Deserialize, Deserializer, Serializer};

            pub fn serialize<S: Serializer>(v: &Option<f64>, s: S) -> Result<S::Ok, S::Error> {
                match v {
                    Some(x) if x.is_finite() => s.serialize_str(&format!("{x:.*}", $decimals)),
                    _ => s.serialize_str(""),
                }
            }

            pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Option<f64>, D::Error> {
                let text = String::deserialize(d)?;
                if text.is_empty() {
                    return Ok(None);
                }
                text.parse()
                    .map(Some)
                    .map_err(|_| serde::de::Error::custom(format!("`{text}` is not a number")))
            }
        }
    };
}

decimals!(decimals_3, 3);
decimals!(decimals_6, 6);

#[cfg(test)]
mod tests {
    use super::*;

    fn row() -> SceneResult {
        let mut r = SceneResult {
            scene: "a,b".into(),
            n: 10,
            gt_motions: Some(2),
            gt_outliers: Some(3),
            motions: 2,
            outliers: 4,
            status: "ok".into(),
            ..SceneResult::default()
        };
        r.set_metrics(&ClusteringMetrics {
            me: 0.1,
            me_all: 0.15,
            acc: 0.9,
            fnr: 0.2,
            pur: 0.95,
            ari: 0.5,
            nmi: 2.0 / 3.0,
        });
        r.set_hypotheses(&HypothesisCounts {
            generated: 100,
            refined: 90,
            local_ok: 40,
            kept: 35,
            focal_failures: 7,
            focal_priors: 0,
        });
        r.set_focal(Some(1000.0), Some(800.0));
        r
    }

    #[test]
    fn cells_match_the_header() {
        let fields = SceneResult::fields();
        assert_eq!(fields, super::super::test_schema::PER_SCENE_COLUMNS);
        let cells = row().cells();
        assert_eq!(cells.len(), fields.len());
        assert_eq!(cells[0], "a,b");
        assert_eq!(cells[3], "0.150000");
        assert_eq!(cells[8], "0.666667");
        assert_eq!(cells[9], "");
        assert_eq!(cells[11], "3");
        assert_eq!(cells[18], "7");
        assert_eq!(cells[19], "0");
        assert_eq!(cells[20], "1000.000");
        assert_eq!(cells[22], "0.250000");
        assert_eq!(cells[23], "");
        assert_eq!(cells[24], "ok");
    }

    #[test]
    fn rows_read_back_as_written() {
        let fields = SceneResult::fields();
        let r = row();
        let back = SceneResult::from_cells(&fields, &r.cells(), Path::new("p.csv"), 2).unwrap();
        // Written with 6 decimals: nmi comes back rounded.
        assert_eq!(back.nmi, Some(0.666667));
        assert_eq!(
            SceneResult {
                nmi: r.nmi,
                ..back.clone()
            },
            r
        );
        let mut cells = r.cells();
        cells[2] = "x".into();
        let err = SceneResult::from_cells(&fields, &cells, Path::new("p.csv"), 5)
            .unwrap_err()
            .to_string();
        assert!(err.starts_with("p.csv: row 5"), "{err}");
        let err = format!(
            "{:#}",
            SceneResult::from_cells(&fields, &cells, Path::new("p.csv"), 5).unwrap_err()
        );
        assert!(err.contains("field 3: `x` is not a number"), "{err}");
    }
}
