//! `sctl tlinkage`: T-Linkage (or J-Linkage) clustering of a preference
//! matrix read from CSV (docs/method.md steps 8–9).

use anyhow::{bail, Context};
use clustering::{j_linkage, t_linkage, BinaryPreferenceMatrix, PreferenceMatrix};
use std::io::Write;
use std::path::{Path, PathBuf};

/// Options of `sctl tlinkage`.
#[derive(clap::Args, Debug)]
#[command(after_long_help = "\
INPUT: one row per point, one comma-separated value per hypothesis, no header; \
every row must have the same number of values. Blank lines are ignored; rows and \
columns in error messages are counted from 1.

  T-Linkage (default): the values are preferences phi_ij in [0, 1], e.g. \
exp(-r_ij / tau) for r_ij <= 5 tau, else 0 (Eq. 38). Points are merged by \
Tanimoto distance (Eq. 39), preference vectors by element-wise minimum (Eq. 40).

  J-Linkage (--jlinkage --tau T): the values are residuals r_ij >= 0 (e.g. \
squared Sampson distances in px^2; inf allowed) and point i prefers hypothesis \
j when r_ij <= T. Points are merged by Jaccard distance, preference sets by \
intersection.

OUTPUT: one label per line, in input order: clusters numbered 0, 1, ... in \
ascending order of their first point; -1 for points of clusters with fewer than \
K points.")]
pub struct Args {
    /// CSV file with the N x M matrix (see INPUT below): preferences in [0, 1],
    /// or residuals with --jlinkage.
    #[arg(long, value_name = "FILE")]
    pub input: PathBuf,
    /// Clusters with fewer than K points are outliers (label -1); 0 or 1 keeps
    /// every cluster.
    #[arg(long, value_name = "K", default_value_t = 0)]
    pub min_cluster_size: usize,
    /// Run J-Linkage instead of T-Linkage; the input holds residuals and
    /// --tau is required.
    #[arg(long, requires = "tau")]
    pub jlinkage: bool,
    /// J-Linkage inlier threshold: point i prefers hypothesis j when
    /// r_ij <= T (same unit as the residuals, e.g. px^2).
    #[arg(
        long,
        value_name = "T",
        requires = "jlinkage",
        allow_negative_numbers = true
    )]
    pub tau: Option<f64>,
}

/// What the CSV values are, which decides what is a valid value.
#[derive(Clone, Copy)]
enum ValueKind {
    /// A preference in `[0, 1]`.
    Preference,
    /// A residual `>= 0` (`inf` allowed).
    Residual,
}

/// Checks one parsed value; `Err` holds the reason it is rejected.
fn check_value(value: f64, kind: ValueKind) -> Result<(), String> {
    if value.is_nan() {
        return Err("NaN is not allowed".into());
    }
    match kind {
        ValueKind::Preference if value < 0.0 => Err(format!(
            "negative preference {value} (preferences must lie in [0, 1])"
        )),
        ValueKind::Preference if value > 1.0 => Err(format!(
            "preference {value} is above 1 (preferences must lie in [0, 1])"
        )),
        ValueKind::Residual if value < 0.0 => Err(format!(
            "negative residual {value} (residuals must be >= 0)"
        )),
        _ => Ok(()),
    }
}

/// Parses the N × M matrix of `text` (read from `path`), one row per
/// non-blank line.
fn parse_matrix(path: &Path, text: &str, kind: ValueKind) -> anyhow::Result<Vec<Vec<f64>>> {
    let file = path.display();
    let mut rows: Vec<Vec<f64>> = Vec::new();
    for (line_index, line) in text.lines().enumerate() {
        if line.trim().is_empty() {
            continue;
        }
        let (row, line_number) = (rows.len() + 1, line_index + 1);
        let mut values = Vec::with_capacity(rows.first().map_or(0, Vec::len));
        for (column, field) in line.split(',').enumerate() {
            let field = field.trim();
            let value: f64 = match field.parse() {
                Ok(v) => v,
                Err(_) if field.is_empty() => bail!(
                    "{file}: row {row} (line {line_number}), column {}: empty value",
                    column + 1
                ),
                Err(_) => bail!(
                    "{file}: row {row} (line {line_number}), column {}: '{field}' is not a number",
                    column + 1
                ),
            };
            if let Err(reason) = check_value(value, kind) {
                bail!(
                    "{file}: row {row} (line {line_number}), column {}: {reason}",
                    column + 1
                );
            }
            values.push(value);
        }
        if let Some(first) = rows.first() {
            if values.len() != first.len() {
                bail!(
                    "{file}: row {row} (line {line_number}) has {} values, expected {} as in row 1",
                    values.len(),
                    first.len()
                );
            }
        }
        rows.push(values);
    }
    if rows.is_empty() {
        bail!("{file}: no rows (the file is empty)");
    }
    Ok(rows)
}

/// Runs the subcommand: reads the matrix, clusters it, prints the labels.
pub fn run(args: Args) -> anyhow::Result<()> {
    let text = std::fs::read_to_string(&args.input)
        .with_context(|| format!("cannot read {}", args.input.display()))?;
    let labels = match args.tau {
        Some(tau) if args.jlinkage => {
            if !(tau.is_finite() && tau > 0.0) {
                bail!("--tau {tau}: the threshold must be finite and > 0");
            }
            let rows = parse_matrix(&args.input, &text, ValueKind::Residual)?;
            let preferences =
                BinaryPreferenceMatrix::from_residuals(rows.len(), rows[0].len(), tau, |i, j| {
                    rows[i][j]
                })
                .with_context(|| args.input.display().to_string())?;
            j_linkage(&preferences, args.min_cluster_size).labels
        }
        _ => {
            let rows = parse_matrix(&args.input, &text, ValueKind::Preference)?;
            let preferences = PreferenceMatrix::from_rows(&rows)
                .with_context(|| args.input.display().to_string())?;
            t_linkage(&preferences, args.min_cluster_size).labels
        }
    };
    let mut out = std::io::BufWriter::new(std::io::stdout().lock());
    for label in labels {
        writeln!(out, "{label}")?;
    }
    out.flush()?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_rows_and_rejects_bad_values() {
        let path = Path::new("p.csv");
        let rows = parse_matrix(path, "1, 0.5\n\n0,0\r\n", ValueKind::Preference).unwrap();
        assert_eq!(rows, vec![vec![1.0, 0.5], vec![0.0, 0.0]]);
        let err = |text: &str, kind| parse_matrix(path, text, kind).unwrap_err().to_string();
        assert_eq!(
            err("1,0\n0,x\n", ValueKind::Preference),
            "p.csv: row 2 (line 2), column 2: 'x' is not a number"
        );
        assert_eq!(
            err("1,0\n\n0,1,1\n", ValueKind::Preference),
            "p.csv: row 2 (line 3) has 3 values, expected 2 as in row 1"
        );
        assert!(err("0.5,NaN\n", ValueKind::Preference).contains("column 2: NaN is not allowed"));
        assert!(err("0.5,-1\n", ValueKind::Preference).contains("negative preference -1"));
        assert!(err("0.5,2\n", ValueKind::Preference).contains("above 1"));
        assert!(err("0.5,,1\n", ValueKind::Preference).contains("column 2: empty value"));
        assert!(err("3,-1\n", ValueKind::Residual).contains("negative residual -1"));
        assert_eq!(
            err("\n \n", ValueKind::Residual),
            "p.csv: no rows (the file is empty)"
        );
        assert_eq!(
            parse_matrix(path, "3,inf\n", ValueKind::Residual).unwrap(),
            vec![vec![3.0, f64::INFINITY]]
        );
    }
}
