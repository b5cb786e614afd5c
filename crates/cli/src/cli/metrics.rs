//! `sctl metrics`: the clustering metrics of docs/method.md "Metrics" (ME, ACC,
//! FNR, PUR, ARI, NMI) of one predicted labelling against its ground truth,
//! printed as one JSON object.

use std::path::{Path, PathBuf};

use anyhow::{bail, Context};
use metrics::{ClusteringMetrics, MetricsError};

/// Options.
#[derive(clap::Args)]
#[command(
    after_help = "Definitions as in docs/method.md \"Metrics\" (Hungarian matching for ME and FNR).\n\n\
Both files hold whitespace-separated integer labels, one per point, in the same order \
(spaces, tabs and newlines all separate). Prints one JSON object with the fractions \
me (misclassification error, ground-truth outliers excluded, a predicted outlier wrong: the thesis's), \
me_all (over all points, outliers a class of their own: the multi-model fitting literature's), acc (1 - me), fnr (false-negative rate), pur (purity), \
ari (adjusted Rand index) and nmi (normalised mutual information, arithmetic mean)."
)]
pub struct Args {
    /// Ground-truth labels: 0 = gross outlier, 1, 2, ... = rigid motions.
    #[arg(long, value_name = "GT.txt")]
    pub gt: PathBuf,
    /// Predicted labels: -1 = rejected as outlier, 0, 1, ... = predicted clusters (ids are arbitrary).
    #[arg(long, value_name = "PRED.txt")]
    pub pred: PathBuf,
}

/// Reads both label files, computes the metrics and prints them as JSON.
pub fn run(args: Args) -> anyhow::Result<()> {
    let gt = read_tokens(&args.gt, "an integer label", |t| t.parse::<i32>().ok())?;
    let pred = read_tokens(&args.pred, "an integer label", |t| t.parse::<i32>().ok())?;
    if gt.len() != pred.len() {
        bail!(
            "{} has {} labels but {} has {}: one label per point is needed in both",
            args.gt.display(),
            gt.len(),
            args.pred.display(),
            pred.len()
        );
    }
    let metrics = ClusteringMetrics::compute(&pred, &gt).map_err(|e| match e {
        MetricsError::InvalidPredictedLabel { index, label } => anyhow::anyhow!(
            "{}: token {} is {label}: predicted labels are -1 (outlier) or >= 0",
            args.pred.display(),
            index + 1
        ),
        MetricsError::InvalidGroundTruthLabel { index, label } => anyhow::anyhow!(
            "{}: token {} is {label}: ground-truth labels are 0 (outlier) or >= 1",
            args.gt.display(),
            index + 1
        ),
        other => anyhow::Error::new(other),
    })?;
    super::print_out(&format!("{}\n", serde_json::to_string(&metrics)?))?;
    Ok(())
}

/// Parses a file of whitespace-separated tokens with `parse` (`None` =
/// invalid token); `what` names a valid token with its article ("a finite
/// number").
///
/// Errors name the file, and for a bad token its 1-based position among the
/// tokens, its line and the token itself; a file without tokens is an error
/// too.
pub(crate) fn read_tokens<T>(
    path: &Path,
    what: &str,
    parse: impl Fn(&str) -> Option<T>,
) -> anyhow::Result<Vec<T>> {
    let text =
        std::fs::read_to_string(path).with_context(|| format!("cannot read {}", path.display()))?;
    let mut values = Vec::new();
    for (line_index, line) in text.lines().enumerate() {
        for token in line.split_whitespace() {
            match parse(token) {
                Some(v) => values.push(v),
                None => bail!(
                    "{}: token {} (line {}) is {token:?}, not {what}",
                    path.display(),
                    values.len() + 1,
                    line_index + 1
                ),
            }
        }
    }
    if values.is_empty() {
        bail!(
            "{}: empty (expected whitespace-separated values, each {what})",
            path.display()
        );
    }
    Ok(values)
}
