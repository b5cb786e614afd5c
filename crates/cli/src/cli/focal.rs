//! `sctl focal`: focal lengths of fundamental matrices read from a CSV file,
//! by Bougnoux's closed form and by the robust iterative solver (docs/method.md
//! step 4), printed as CSV.

use std::io::Write;
use std::path::{Path, PathBuf};

use crate::focal_file::F_COLUMNS;
use anyhow::{bail, Context};
use focal::{bougnoux_per_image, robust_focals, FocalWeights, RobustFocalParams};
use nalgebra::Matrix3;

/// Options.
#[derive(clap::Args)]
#[command(
    after_help = "Input: a CSV file with a header row holding at least the columns \
F00, F01, ..., F22 (F row-major, pixel coordinates with the principal points at the origin, \
x2^T F x1 = 0) and optionally f_prior, w_f1, w_pp1, w_f2, w_pp2, max_iters (defaults 1000, \
5e-4, 1, 5e-4, 1, 50; an empty cell takes the default). Other columns are ignored.\n\n\
Output (stdout): one CSV row per input row, \
row,bougnoux_f1,bougnoux_f2,iter_f1,iter_f2,iterations,iter_status. row is the 0-based data \
row; bougnoux_f1/f2 are Bougnoux's focal lengths of image 1 and 2 (empty when f^2 <= 0 or \
the formula is singular); iter_f1/f2 and iterations are the robust solver's answer and its \
iteration count, iter_status is ok or failed (the three cells are empty when it failed)."
)]
pub struct Args {
    /// CSV file of fundamental matrices (columns F00..F22).
    #[arg(long, value_name = "F.csv")]
    pub input: PathBuf,
}

/// Reads the matrices, runs both solvers on each and prints the CSV.
pub fn run(args: Args) -> anyhow::Result<()> {
    let rows = read_rows(&args.input)?;
    let mut out = csv::Writer::from_writer(Vec::new());
    out.write_record([
        "row",
        "bougnoux_f1",
        "bougnoux_f2",
        "iter_f1",
        "iter_f2",
        "iterations",
        "iter_status",
    ])?;
    for (i, row) in rows.iter().enumerate() {
        let [b1, b2] = bougnoux_per_image(&row.f, [0.0, 0.0], [0.0, 0.0]);
        let cell = |r: &Result<f64, focal::FocalFailure>| match r {
            Ok(v) => v.to_string(),
            Err(_) => String::new(),
        };
        let (iter_f1, iter_f2, iterations, status) = match robust_focals(&row.f, &row.params) {
            Ok(e) => (
                e.f1.to_string(),
                e.f2.to_string(),
                e.iterations.to_string(),
                "ok",
            ),
            Err(_) => (String::new(), String::new(), String::new(), "failed"),
        };
        out.write_record([
            i.to_string(),
            cell(&b1),
            cell(&b2),
            iter_f1,
            iter_f2,
            iterations,
            status.to_string(),
        ])?;
    }
    let bytes = out.into_inner().context("formatting the output")?;
    let mut stdout = std::io::stdout().lock();
    match stdout.write_all(&bytes).and_then(|()| stdout.flush()) {
        // A closed pipe (e.g. `| head`) is not an error of this command.
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        other => other.context("writing to stdout"),
    }
}

/// One input row: F and the solver's parameters.
struct InputRow {
    f: Matrix3<f64>,
    params: RobustFocalParams,
}

/// The column indices of the input file.
struct Columns {
    f: [usize; 9],
    f_prior: Option<usize>,
    w_f1: Option<usize>,
    w_pp1: Option<usize>,
    w_f2: Option<usize>,
    w_pp2: Option<usize>,
    max_iters: Option<usize>,
}

fn find_columns(path: &Path, headers: &csv::StringRecord) -> anyhow::Result<Columns> {
    let find = |name: &str| headers.iter().position(|h| h.trim() == name);
    let mut f = [0usize; 9];
    for (slot, name) in f.iter_mut().zip(F_COLUMNS) {
        *slot = match find(name) {
            Some(i) => i,
            None => bail!(
                "{}: missing column {name} (the header must name F00, F01, ..., F22)",
                path.display()
            ),
        };
    }
    Ok(Columns {
        f,
        f_prior: find("f_prior"),
        w_f1: find("w_f1"),
        w_pp1: find("w_pp1"),
        w_f2: find("w_f2"),
        w_pp2: find("w_pp2"),
        max_iters: find("max_iters"),
    })
}

fn read_rows(path: &Path) -> anyhow::Result<Vec<InputRow>> {
    let mut reader = csv::ReaderBuilder::new()
        .flexible(false)
        .from_path(path)
        .with_context(|| format!("{}: cannot open", path.display()))?;
    let headers = reader
        .headers()
        .with_context(|| format!("{}: cannot read the header row", path.display()))?
        .clone();
    let cols = find_columns(path, &headers)?;
    let mut rows = Vec::new();
    for (row, record) in reader.records().enumerate() {
        let record =
            record.with_context(|| format!("{}: row {row}: malformed CSV", path.display()))?;
        let line = record.position().map_or(0, |p| p.line());
        let at = |name: &str| format!("{}: row {row} (line {line}), column {name}", path.display());
        let number = |idx: usize, name: &str| -> anyhow::Result<Option<f64>> {
            let cell = record.get(idx).unwrap_or("").trim();
            if cell.is_empty() {
                return Ok(None);
            }
            let value: f64 = cell
                .parse()
                .map_err(|_| anyhow::anyhow!("{}: '{cell}' is not a number", at(name)))?;
            if !value.is_finite() {
                bail!("{}: '{cell}' is not a finite number", at(name));
            }
            Ok(Some(value))
        };
        let mut f = Matrix3::zeros();
        for (k, (&idx, name)) in cols.f.iter().zip(F_COLUMNS).enumerate() {
            f[(k / 3, k % 3)] =
                number(idx, name)?.ok_or_else(|| anyhow::anyhow!("{}: empty cell", at(name)))?;
        }
        let positive = |col: Option<usize>, name: &str, default: f64| -> anyhow::Result<f64> {
            match col {
                None => Ok(default),
                Some(idx) => match number(idx, name)? {
                    None => Ok(default),
                    Some(v) if v > 0.0 => Ok(v),
                    Some(v) => bail!("{}: {v} must be > 0", at(name)),
                },
            }
        };
        let defaults = RobustFocalParams::default();
        let max_iters = match cols.max_iters {
            None => defaults.max_iters,
            Some(idx) => {
                let cell = record.get(idx).unwrap_or("").trim();
                if cell.is_empty() {
                    defaults.max_iters
                } else {
                    cell.parse::<usize>().map_err(|_| {
                        anyhow::anyhow!(
                            "{}: '{cell}' is not a non-negative integer",
                            at("max_iters")
                        )
                    })?
                }
            }
        };
        let params = RobustFocalParams {
            f_prior: positive(cols.f_prior, "f_prior", defaults.f_prior)?,
            weights: FocalWeights::new(
                positive(cols.w_f1, "w_f1", defaults.weights.f1)?,
                positive(cols.w_pp1, "w_pp1", defaults.weights.pp1)?,
                positive(cols.w_f2, "w_f2", defaults.weights.f2)?,
                positive(cols.w_pp2, "w_pp2", defaults.weights.pp2)?,
            ),
            max_iters,
        };
        rows.push(InputRow { f, params });
    }
    Ok(rows)
}
