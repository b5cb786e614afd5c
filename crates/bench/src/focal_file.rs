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
///
/// ```
/// let p = bench::focal_file::focal_file_path("focals/seed{seed}.csv", 7);
/// assert_eq!(p, std::path::PathBuf::from("focals/seed7.csv"));
/// ```
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

/// Opens the focal file at `path` and finds its columns.
fn open(path: &Path) -> Result<(csv::Reader<std::fs::File>, Columns), String> {
    let shown = path.display();
    let mut reader = csv::Reader::from_path(path).map_err(|e| format!("{shown}: {e}"))?;
    let header = reader
        .headers()
        .map_err(|e| format!("{shown}: header: {e}"))?;
    let column = |name: &str| header.iter().position(|h| h == name);
    let mut required = [0; 4];
    for (slot, name) in required.iter_mut().zip(REQUIRED_COLUMNS) {
        *slot = column(name).ok_or_else(|| format!("{shown}: no column `{name}`"))?;
    }
    let model = F_COLUMNS.iter().map(|name| column(name)).collect();
    Ok((reader, Columns { required, model }))
}

/// Checks, before a run, that the focal file at `path` can be read and has
/// the [`REQUIRED_COLUMNS`].
///
/// # Errors
/// A message naming the file and what is wrong.
pub fn check_focal_file(path: &Path) -> Result<(), String> {
    open(path).map(|_| ())
}

/// The rows of `scene` in the focal file at `path`, by hypothesis index.
///
/// # Errors
/// A message naming the file, the row and the field: unreadable file,
/// missing column, unparsable number, a hypothesis listed twice.
pub fn read_scene_focals(
    path: &Path,
    scene: &str,
) -> Result<HashMap<usize, ExternalFocal>, String> {
    let shown = path.display();
    let (mut reader, columns) = open(path)?;
    let [scene_col, hyp_col, f1_col, f2_col] = columns.required;
    let mut rows = HashMap::new();
    for (i, record) in reader.records().enumerate() {
        let line = i + 2;
        let record = record.map_err(|e| format!("{shown}: line {line}: {e}"))?;
        if record.get(scene_col) != Some(scene) {
            continue;
        }
        let field = |col: usize, name: &str| -> Result<f64, String> {
            let text = record.get(col).unwrap_or("").trim();
            text.parse::<f64>().map_err(|_| {
                format!("{shown}: line {line}: field `{name}`: `{text}` is not a number")
            })
        };
        let hyp_text = record.get(hyp_col).unwrap_or("").trim();
        let hypothesis: usize = hyp_text.parse().map_err(|_| {
            format!("{shown}: line {line}: field `hypothesis`: `{hyp_text}` is not an index")
        })?;
        let model = match &columns.model {
            Some(cols) => {
                let mut m = Matrix3::zeros();
                for (k, (&col, name)) in cols.iter().zip(F_COLUMNS).enumerate() {
                    m[(k / 3, k % 3)] = field(col, name)?;
                }
                Some(m)
            }
            None => None,
        };
        let answer = ExternalFocal {
            focals: (field(f1_col, "f1")?, field(f2_col, "f2")?),
            model,
        };
        if rows.insert(hypothesis, answer).is_some() {
            return Err(format!(
                "{shown}: line {line}: scene `{scene}` hypothesis {hypothesis} is listed twice"
            ));
        }
    }
    Ok(rows)
}

/// Whether two fundamental matrices are the same up to scale and sign: the
/// largest entry difference of their unit-norm forms (sign aligned) is at
/// most `tolerance`.
///
/// ```
/// use nalgebra::Matrix3;
/// let f = Matrix3::new(0.0, -1.0, 2.0, 1.0, 0.5, -3.0, -2.0, 4.0, 0.0);
/// assert!(bench::focal_file::same_model(&f, &(-4.0 * f), 1e-12));
/// assert!(!bench::focal_file::same_model(&f, &f.transpose(), 1e-3));
/// ```
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
        let e = read_scene_focals(&path, "a").unwrap_err();
        assert!(
            e.contains("focals.csv") && e.contains("line 2") && e.contains("`f2`"),
            "{e}"
        );
        let (_d, path) = write("scene,hypothesis,f1\na,0,640\n");
        let e = read_scene_focals(&path, "a").unwrap_err();
        assert!(e.contains("no column `f2`"), "{e}");
        let (_d, path) = write("scene,hypothesis,f1,f2\na,0,1,2\na,0,1,2\n");
        let e = read_scene_focals(&path, "a").unwrap_err();
        assert!(e.contains("line 3") && e.contains("twice"), "{e}");
        let e = read_scene_focals(Path::new("no/such/file.csv"), "a").unwrap_err();
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
