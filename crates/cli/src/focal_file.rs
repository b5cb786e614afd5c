//! Focal lengths computed outside this project (`focal_solver = "external"`),
//! e.g. by PoseLib as the reference implementation calls it
//! (`scripts/poselib_focals.py`), for the hypotheses that `sctl hypotheses`
//! wrote.
//!
//! The file is a CSV with the columns `scene`, `hypothesis`, `f1`, `f2` and,
//! optionally, `F00` … `F22` (the hypothesis's F, row-major, any scale).
//! When F is there, every hypothesis is checked against it, so a file made
//! for other hypotheses (another seed, M or threshold) is an error, not a
//! silent mismatch. Other columns are ignored.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use nalgebra::Matrix3;
use thiserror::Error;

/// Why a focal file cannot give the answers of a scene. Every variant names
/// the file (and, where there is one, the line and the field).
#[derive(Debug, Error)]
pub enum FocalFileError {
    /// The file cannot be opened or its header read.
    #[error("{}: {cause}", file.display())]
    Open {
        /// The file.
        file: PathBuf,
        /// The reader's error.
        cause: csv::Error,
    },
    /// The header lacks one of the `REQUIRED_COLUMNS`.
    #[error("{}: no column `{column}`", file.display())]
    MissingColumn {
        /// The file.
        file: PathBuf,
        /// The column.
        column: &'static str,
    },
    /// A record cannot be read.
    #[error("{}: line {line}: {cause}", file.display())]
    Record {
        /// The file.
        file: PathBuf,
        /// 1-based line.
        line: usize,
        /// The reader's error.
        cause: csv::Error,
    },
    /// A field is not a number (or `hypothesis` not an index).
    #[error("{}: line {line}: field `{field}`: `{text}` is not {expected}", file.display())]
    BadField {
        /// The file.
        file: PathBuf,
        /// 1-based line.
        line: usize,
        /// The column.
        field: &'static str,
        /// The cell.
        text: String,
        /// `a number` or `an index`.
        expected: &'static str,
    },
    /// A hypothesis of a scene is listed twice.
    #[error("{}: line {line}: scene `{scene}` hypothesis {hypothesis} is listed twice", file.display())]
    Duplicate {
        /// The file.
        file: PathBuf,
        /// 1-based line of the second row.
        line: usize,
        /// The scene.
        scene: String,
        /// The hypothesis index.
        hypothesis: usize,
    },
    /// A hypothesis with a model has no row.
    #[error("{}: no row for hypothesis {hypothesis} (write the hypotheses of this config with `sctl hypotheses`)", file.display())]
    MissingHypothesis {
        /// The file.
        file: PathBuf,
        /// The hypothesis index.
        hypothesis: usize,
    },
    /// The file's F of a hypothesis is not the one this config generates.
    #[error(
        "{}: hypothesis {hypothesis} has another F than this config generates \
         (the file was made for other hypotheses: seed, M, thr_px, ...?)",
        file.display()
    )]
    OtherModel {
        /// The file.
        file: PathBuf,
        /// The hypothesis index.
        hypothesis: usize,
    },
}

/// The column names of a fundamental matrix in a CSV, row-major: `F00`,
/// `F01`, …, `F22` (entry `k` is `F[(k / 3, k % 3)]`).
pub const F_COLUMNS: [&str; 9] = [
    "F00", "F01", "F02", "F10", "F11", "F12", "F20", "F21", "F22",
];

/// The answer of the external solver for one hypothesis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ExternalFocal {
    /// `(f1, f2)` as given (may be non-finite).
    pub focals: (f64, f64),
    /// The hypothesis's F when the file has the `F00` … `F22` columns.
    pub model: Option<Matrix3<f64>>,
}

/// The file of a configuration: `template` with `{seed}` replaced by `seed`.
pub fn focal_file_path(template: &str, seed: u64) -> PathBuf {
    PathBuf::from(template.replace("{seed}", &seed.to_string()))
}

/// The columns every focal file has.
pub const REQUIRED_COLUMNS: [&str; 4] = ["scene", "hypothesis", "f1", "f2"];

/// Where the columns of a focal file are.
struct Columns {
    /// Of [`REQUIRED_COLUMNS`], in that order.
    required: [usize; 4],
    /// Of [`F_COLUMNS`], when the file has all of them.
    model: Option<Vec<usize>>,
}

/// A focal file opened, its columns found.
struct FocalFileReader {
    reader: csv::Reader<std::fs::File>,
    columns: Columns,
}

/// Opens the focal file at `path` and finds its columns.
fn open(path: &Path) -> Result<FocalFileReader, FocalFileError> {
    let opening = |cause| FocalFileError::Open {
        file: path.to_path_buf(),
        cause,
    };
    let mut reader = csv::Reader::from_path(path).map_err(opening)?;
    let header = reader.headers().map_err(opening)?;
    let column = |name: &str| header.iter().position(|h| h == name);
    let mut required = [0; 4];
    for (slot, name) in required.iter_mut().zip(REQUIRED_COLUMNS) {
        *slot = column(name).ok_or_else(|| FocalFileError::MissingColumn {
            file: path.to_path_buf(),
            column: name,
        })?;
    }
    let model = F_COLUMNS.iter().map(|name| column(name)).collect();
    Ok(FocalFileReader {
        reader,
        columns: Columns { required, model },
    })
}

/// Checks, before a run, that the focal file at `path` can be read and has
/// the [`REQUIRED_COLUMNS`].
pub fn check_focal_file(path: &Path) -> Result<(), FocalFileError> {
    open(path).map(|_| ())
}

/// Field `field` of `record` (in column `col`) as a number.
fn number(
    record: &csv::StringRecord,
    col: usize,
    field: &'static str,
    path: &Path,
    line: usize,
) -> Result<f64, FocalFileError> {
    let text = record.get(col).unwrap_or("").trim();
    text.parse::<f64>().map_err(|_| FocalFileError::BadField {
        file: path.to_path_buf(),
        line,
        field,
        text: text.to_string(),
        expected: "a number",
    })
}

/// The answer of one record: its hypothesis index and focal lengths (and F
/// when the file has it).
fn answer(
    record: &csv::StringRecord,
    columns: &Columns,
    path: &Path,
    line: usize,
) -> Result<(usize, ExternalFocal), FocalFileError> {
    let [_, hyp_col, f1_col, f2_col] = columns.required;
    let hyp_text = record.get(hyp_col).unwrap_or("").trim();
    let hypothesis: usize = hyp_text.parse().map_err(|_| FocalFileError::BadField {
        file: path.to_path_buf(),
        line,
        field: "hypothesis",
        text: hyp_text.to_string(),
        expected: "an index",
    })?;
    let model = match &columns.model {
        Some(cols) => {
            let mut m = Matrix3::zeros();
            for (k, (&col, name)) in cols.iter().zip(F_COLUMNS).enumerate() {
                m[(k / 3, k % 3)] = number(record, col, name, path, line)?;
            }
            Some(m)
        }
        None => None,
    };
    let focals = (
        number(record, f1_col, "f1", path, line)?,
        number(record, f2_col, "f2", path, line)?,
    );
    Ok((hypothesis, ExternalFocal { focals, model }))
}

/// The rows of `scene` in the focal file at `path`, by hypothesis index.
///
/// # Errors
/// A [`FocalFileError`] naming the file, the line and the field: unreadable
/// file, missing column, unparsable number, a hypothesis listed twice.
pub fn read_scene_focals(
    path: &Path,
    scene: &str,
) -> Result<HashMap<usize, ExternalFocal>, FocalFileError> {
    let FocalFileReader {
        mut reader,
        columns,
    } = open(path)?;
    let scene_col = columns.required[0];
    let mut rows = HashMap::new();
    for (i, record) in reader.records().enumerate() {
        let line = i + 2;
        let record = record.map_err(|cause| FocalFileError::Record {
            file: path.to_path_buf(),
            line,
            cause,
        })?;
        if record.get(scene_col) != Some(scene) {
            continue;
        }
        let (hypothesis, answer) = answer(&record, &columns, path, line)?;
        if rows.insert(hypothesis, answer).is_some() {
            return Err(FocalFileError::Duplicate {
                file: path.to_path_buf(),
                line,
                scene: scene.to_string(),
                hypothesis,
            });
        }
    }
    Ok(rows)
}

/// Whether two fundamental matrices are the same up to scale and sign: the
/// largest entry difference of their unit-norm forms (sign aligned) is at
/// most `tolerance`.
pub fn same_model(a: &Matrix3<f64>, b: &Matrix3<f64>, tolerance: f64) -> bool {
    let (a, b) = (a / a.norm(), b / b.norm());
    let sign = if a.dot(&b) < 0.0 { -1.0 } else { 1.0 };
    (a - b * sign).amax() <= tolerance
}

#[cfg(test)]
mod tests {
    use super::*;

    fn write(text: &str) -> (tempfile::TempDir, PathBuf) {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("focals.csv");
        std::fs::write(&path, text).unwrap();
        (dir, path)
    }

    #[test]
    fn reads_the_rows_of_one_scene() {
        let (_d, path) =
            write("scene,hypothesis,f1,f2,iterations\na,0,640,640,1\nb,0,1,2,3\na,2,600.5,NaN,4\n");
        let rows = read_scene_focals(&path, "a").unwrap();
        assert_eq!(rows.len(), 2);
        assert_eq!(rows[&0].focals, (640.0, 640.0));
        assert_eq!(rows[&2].focals.0, 600.5);
        assert!(rows[&2].focals.1.is_nan());
        assert!(rows[&0].model.is_none());
    }

    #[test]
    fn errors_name_the_file_the_line_and_the_field() {
        let (_d, path) = write("scene,hypothesis,f1,f2\na,0,640,x\n");
        let e = read_scene_focals(&path, "a").unwrap_err().to_string();
        assert!(
            e.contains("focals.csv") && e.contains("line 2") && e.contains("`f2`"),
            "{e}"
        );
        let (_d, path) = write("scene,hypothesis,f1\na,0,640\n");
        let e = read_scene_focals(&path, "a").unwrap_err().to_string();
        assert!(e.contains("no column `f2`"), "{e}");
        let (_d, path) = write("scene,hypothesis,f1,f2\na,0,1,2\na,0,1,2\n");
        let e = read_scene_focals(&path, "a").unwrap_err().to_string();
        assert!(e.contains("line 3") && e.contains("twice"), "{e}");
        let e = read_scene_focals(Path::new("no/such/file.csv"), "a")
            .unwrap_err()
            .to_string();
        assert!(e.contains("no/such/file.csv"), "{e}");
    }

    #[test]
    fn reads_the_model_when_present() {
        let (_d, path) = write("scene,hypothesis,f1,f2,F00,F01,F02,F10,F11,F12,F20,F21,F22\na,1,1,2,1,2,3,4,5,6,7,8,9\n");
        let rows = read_scene_focals(&path, "a").unwrap();
        let m = rows[&1].model.unwrap();
        assert_eq!(m, Matrix3::new(1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0));
    }
}

/// The examples once in the documentation of this module's items.
#[cfg(test)]
mod examples {
    #[test]
    fn focal_file_path_example() {
        let p = crate::focal_file::focal_file_path("focals/seed{seed}.csv", 7);
        assert_eq!(p, std::path::PathBuf::from("focals/seed7.csv"));
    }

    #[test]
    fn same_model_example() {
        use nalgebra::Matrix3;
        let f = Matrix3::new(0.0, -1.0, 2.0, 1.0, 0.5, -3.0, -2.0, 4.0, 0.0);
        assert!(crate::focal_file::same_model(&f, &(-4.0 * f), 1e-12));
        assert!(!crate::focal_file::same_model(&f, &f.transpose(), 1e-3));
    }
}
