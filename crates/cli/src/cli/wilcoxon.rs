//! `sctl wilcoxon`: the paired Wilcoxon signed-rank test of docs/method.md
//! "Wilcoxon signed-rank test" on two files of per-scene values, printed as
//! one JSON object.

use std::path::PathBuf;

use crate::wilcoxon::{wilcoxon, Alternative, Mode};
use anyhow::bail;

use super::metrics::read_tokens;

/// The alternative hypothesis, with the baseline as the first sample.
#[derive(Clone, Copy, Debug, clap::ValueEnum)]
pub enum AlternativeArg {
    /// H1: the baseline's values are larger than the method's (e.g. its error is larger).
    Greater,
    /// H1: the baseline's values are smaller than the method's.
    Less,
    /// H1: the paired differences are not centred on zero.
    TwoSided,
}

/// How the null distribution of the statistic is obtained.
#[derive(Clone, Copy, Debug, clap::ValueEnum)]
pub enum ModeArg {
    /// Exact distribution when n <= 50 without ties or zero differences; exact sign-flip permutation when there are ties or zeros and n <= 13; else the normal approximation.
    Auto,
    /// Exact null distribution of the rank sum for untied ranks (a tied statistic is rounded conservatively).
    Exact,
    /// Normal approximation with tie-corrected variance, no continuity correction.
    Approx,
}

/// Options.
#[derive(clap::Args)]
#[command(
    after_help = "Paired Wilcoxon signed-rank test (docs/method.md \"Wilcoxon signed-rank test\"), as \
scipy.stats.wilcoxon(baseline, method, zero_method='wilcox', correction=False).\n\n\
Both files hold whitespace-separated numbers, one per scene, in the same scene order. \
Differences d = baseline - method; zero differences are dropped; |d| is ranked with ties \
averaged. Prints one JSON object: statistic (sum of the ranks of positive differences; \
min(T+, T-) for two-sided), p_value, mode_used (exact | permutation | approx), n (non-zero \
differences) and n_zero (dropped zero differences)."
)]
pub struct Args {
    /// Per-scene values of the baseline (the first sample, x).
    #[arg(long, value_name = "A.txt")]
    pub baseline: PathBuf,
    /// Per-scene values of the method under test (the second sample, y), in the same scene order.
    #[arg(long, value_name = "B.txt")]
    pub method: PathBuf,
    /// Alternative hypothesis about baseline - method.
    #[arg(long, value_enum, default_value = "greater")]
    pub alternative: AlternativeArg,
    /// Null distribution: auto, exact or approx.
    #[arg(long, value_enum, default_value = "auto")]
    pub mode: ModeArg,
}

/// Reads both files, runs the test and prints the result as JSON.
pub fn run(args: Args) -> anyhow::Result<()> {
    let finite = |t: &str| t.parse::<f64>().ok().filter(|v| v.is_finite());
    let baseline = read_tokens(&args.baseline, "a finite number", finite)?;
    let method = read_tokens(&args.method, "a finite number", finite)?;
    if baseline.len() != method.len() {
        bail!(
            "{} has {} values but {} has {}: the samples must be paired value by value",
            args.baseline.display(),
            baseline.len(),
            args.method.display(),
            method.len()
        );
    }
    let alternative = match args.alternative {
        AlternativeArg::Greater => Alternative::Greater,
        AlternativeArg::Less => Alternative::Less,
        AlternativeArg::TwoSided => Alternative::TwoSided,
    };
    let mode = match args.mode {
        ModeArg::Auto => Mode::Auto,
        ModeArg::Exact => Mode::Exact,
        ModeArg::Approx => Mode::Approx,
    };
    let result = wilcoxon(&baseline, &method, alternative, mode).map_err(|e| {
        anyhow::anyhow!(
            "{} against {}: {e}",
            args.baseline.display(),
            args.method.display()
        )
    })?;
    super::print_out(&format!("{}\n", serde_json::to_string(&result)?))?;
    Ok(())
}
