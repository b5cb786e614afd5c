//! A user's own matches: a CSV file or an AdelaideRMF-style `matches.txt`,
//! with the image size from the caller or from a sidecar TOML file.
//!
//! * CSV: a header row naming the columns `x1, y1, x2, y2` and optionally
//!   `label` (any order, case-insensitive), one correspondence per row. Any
//!   other column, or one named twice, is an error naming it (a misspelt
//!   `lable` would otherwise leave the file unlabelled).
//! * `matches.txt`: whitespace-separated `x1 y1 x2 y2 [label]` per line;
//!   blank lines and lines starting with `#` are skipped.
//! * Labels: `0` = gross outlier, `1..k` = motion, or the word `unknown`
//!   (any case) for a match whose truth is not known ([`UNKNOWN_LABEL`]):
//!   it is segmented but not scored. Negative numbers and empty fields are
//!   errors, so neither the outlier `0` nor a predicted outlier's `-1` can
//!   be read as "unknown".
//! * Sidecar: the data file's path with the extension `.toml`
//!   (`scene.csv` → `scene.toml`), see [`Sidecar`].
//!
//! The principal point is the image centre ((W-1)/2, (H-1)/2) unless the
//! sidecar gives one (docs/method.md, "Input").

use crate::{centre_principal_point, DatasetError, Scene, UNKNOWN_LABEL};
use serde::Deserialize;
use std::path::{Path, PathBuf};

/// Scene metadata stored beside a match file.
///
/// ```toml
/// width = 640            # pixels, required
/// height = 480           # pixels, required
/// name = "desk"          # default: the data file's stem
/// focal = 700.0          # ground-truth focal in pixels, if known
/// focal_prior = 720.0    # the focal prior (e.g. from EXIF), default max(W, H)
/// principal_point = [320.0, 240.0]   # default: ((W-1)/2, (H-1)/2)
/// ```
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Sidecar {
    /// Image width W in pixels.
    pub width: u32,
    /// Image height H in pixels.
    pub height: u32,
    /// Scene name.
    #[serde(default)]
    pub name: Option<String>,
    /// Ground-truth focal length in pixels.
    #[serde(default)]
    pub focal: Option<f64>,
    /// Principal point in pixels.
    #[serde(default)]
    pub principal_point: Option<[f64; 2]>,
    /// The focal prior in pixels, e.g. from the camera's EXIF data: the
    /// focal the five-point default solves its essential matrices at
    /// (docs/method.md, "The default"); `sctl segment --focal` overrides
    /// it. Default: max(W, H).
    #[serde(default)]
    pub focal_prior: Option<f64>,
}

/// The sidecar path of a data file: the same path with extension `.toml`.
///
/// ```
/// use std::path::Path;
/// assert_eq!(datasets::user::sidecar_path(Path::new("a/scene.csv")), Path::new("a/scene.toml"));
/// ```
pub fn sidecar_path(data_path: &Path) -> PathBuf {
    data_path.with_extension("toml")
}

/// Reads a sidecar TOML file.
pub fn read_sidecar(path: &Path) -> Result<Sidecar, DatasetError> {
    let text = std::fs::read_to_string(path).map_err(|e| DatasetError::io(path, e))?;
    let parse_err = |problem: String| DatasetError::Parse {
        path: path.to_path_buf(),
        line: None,
        problem,
    };
    let sidecar: Sidecar = toml::from_str(&text).map_err(|e| parse_err(e.to_string()))?;
    match sidecar.focal_prior {
        Some(f) if !(f.is_finite() && f > 0.0) => Err(parse_err(format!(
            "focal_prior must be a finite number of pixels > 0, got {f}"
        ))),
        _ => Ok(sidecar),
    }
}

/// Loads a CSV match file. `image_size` (W, H) overrides the sidecar's; one
/// of the two must exist.
///
/// ```
/// let dir = tempfile::tempdir().unwrap();
/// let path = dir.path().join("pair.csv");
/// let mut text = String::from("x1,y1,x2,y2,label\n");
/// for i in 0..8 {
///     text += &format!("{i},{},{},{},1\n", 2 * i, i + 5, 2 * i);
/// }
/// std::fs::write(&path, text).unwrap();
/// let scene = datasets::user::load_csv(&path, Some((640, 480)))?;
/// assert_eq!(scene.len(), 8);
/// assert_eq!(scene.points2[3], [8.0, 6.0]);
/// assert_eq!(scene.principal_point, [319.5, 239.5]);
/// # Ok::<(), datasets::DatasetError>(())
/// ```
pub fn load_csv(
    path: impl AsRef<Path>,
    image_size: Option<(u32, u32)>,
) -> Result<Scene, DatasetError> {
    let path = path.as_ref();
    let parse_err = |line: Option<u64>, problem: String| DatasetError::Parse {
        path: path.to_path_buf(),
        line,
        problem,
    };
    let mut reader = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .from_path(path)
        .map_err(|e| parse_err(None, e.to_string()))?;
    let headers = reader
        .headers()
        .map_err(|e| parse_err(Some(1), e.to_string()))?
        .clone();
    check_columns(&headers).map_err(|problem| parse_err(Some(1), problem))?;
    let column = |name: &str| headers.iter().position(|h| h.eq_ignore_ascii_case(name));
    let mut cols = [0usize; 4];
    for (slot, name) in cols.iter_mut().zip(["x1", "y1", "x2", "y2"]) {
        *slot = column(name).ok_or_else(|| DatasetError::MissingField {
            path: path.to_path_buf(),
            field: format!(
                "column `{name}` (header: {})",
                headers.iter().collect::<Vec<_>>().join(",")
            ),
        })?;
    }
    let label_col = column("label");
    let mut rows = Rows::default();
    for record in reader.records() {
        let record =
            record.map_err(|e| parse_err(e.position().map(|p| p.line()), e.to_string()))?;
        let line = record.position().map(|p| p.line());
        let field = |i: usize| record.get(i).unwrap_or("");
        let mut xy = [0.0; 4];
        for (value, (&col, name)) in xy.iter_mut().zip(cols.iter().zip(["x1", "y1", "x2", "y2"])) {
            *value = parse_coordinate(field(col)).ok_or_else(|| {
                parse_err(
                    line,
                    format!(
                        "column `{name}`: {:?} is not a number",
                        crate::echo(field(col))
                    ),
                )
            })?;
        }
        let label = match label_col {
            None => None,
            Some(col) => Some(
                parse_label(field(col))
                    .map_err(|problem| parse_err(line, format!("column `label`: {problem}")))?,
            ),
        };
        rows.push(xy, label);
    }
    finish(path, rows, image_size)
}

/// Loads an AdelaideRMF-style text file of `x1 y1 x2 y2 [label]` lines.
/// `image_size` (W, H) overrides the sidecar's; one of the two must exist.
/// Every line must have the same number of columns (4 or 5).
pub fn load_matches_txt(
    path: impl AsRef<Path>,
    image_size: Option<(u32, u32)>,
) -> Result<Scene, DatasetError> {
    let path = path.as_ref();
    let text = std::fs::read_to_string(path).map_err(|e| DatasetError::io(path, e))?;
    let mut rows = Rows::default();
    let mut width = None;
    for (i, raw) in text.lines().enumerate() {
        let line = Some(i as u64 + 1);
        let parse_err = |problem: String| DatasetError::Parse {
            path: path.to_path_buf(),
            line,
            problem,
        };
        let trimmed = raw.trim();
        if trimmed.is_empty() || trimmed.starts_with('#') {
            continue;
        }
        let fields: Vec<&str> = trimmed.split_whitespace().collect();
        if fields.len() != 4 && fields.len() != 5 {
            return Err(parse_err(format!(
                "{} columns, expected `x1 y1 x2 y2 [label]`",
                fields.len()
            )));
        }
        if *width.get_or_insert(fields.len()) != fields.len() {
            return Err(parse_err(format!(
                "{} columns, earlier lines have {}",
                fields.len(),
                width.unwrap_or(0)
            )));
        }
        let mut xy = [0.0; 4];
        for (k, value) in xy.iter_mut().enumerate() {
            *value = parse_coordinate(fields[k]).ok_or_else(|| {
                parse_err(format!(
                    "column {}: {:?} is not a number",
                    k + 1,
                    crate::echo(fields[k])
                ))
            })?;
        }
        let label = match fields.get(4) {
            None => None,
            Some(s) => {
                Some(parse_label(s).map_err(|problem| parse_err(format!("column 5: {problem}")))?)
            }
        };
        rows.push(xy, label);
    }
    finish(path, rows, image_size)
}

/// The columns a CSV match file may have; `label` is optional.
const CSV_COLUMNS: [&str; 5] = ["x1", "y1", "x2", "y2", "label"];

/// Every header names one of [`CSV_COLUMNS`] (any case), none twice.
fn check_columns(headers: &csv::StringRecord) -> Result<(), String> {
    let expected = "the columns are x1, y1, x2, y2 and optionally label";
    let mut seen = Vec::new();
    for header in headers {
        let name = header.to_ascii_lowercase();
        if !CSV_COLUMNS.contains(&name.as_str()) {
            return Err(format!("unknown column `{header}`: {expected}"));
        }
        if seen.contains(&name) {
            return Err(format!("column `{header}` appears twice: {expected}"));
        }
        seen.push(name);
    }
    Ok(())
}

/// A ground-truth label: an integer ≥ 0, or `unknown` (any case) for
/// [`UNKNOWN_LABEL`]; the error says which values are allowed.
///
/// ```
/// # use datasets::user::parse_label;
/// assert_eq!(parse_label("2"), Ok(2));
/// assert_eq!(parse_label("Unknown"), Ok(datasets::UNKNOWN_LABEL));
/// assert!(parse_label("-1").unwrap_err().contains("negative"));
/// assert!(parse_label("").is_err());
/// ```
pub fn parse_label(s: &str) -> Result<i32, String> {
    let allowed = "labels are 0 (outlier), 1, 2, … (motion) or `unknown`";
    if s.eq_ignore_ascii_case("unknown") {
        return Ok(UNKNOWN_LABEL);
    }
    match s.parse::<i32>() {
        Ok(label) if label >= 0 => Ok(label),
        Ok(label) => Err(format!("{label} is negative: {allowed}")),
        Err(_) => Err(format!(
            "{:?} is not an integer label: {allowed}",
            crate::echo(s)
        )),
    }
}

/// A finite or non-finite number; validation reports non-finite ones with
/// their index.
fn parse_coordinate(s: &str) -> Option<f64> {
    s.parse::<f64>().ok()
}

#[derive(Default)]
struct Rows {
    points1: Vec<[f64; 2]>,
    points2: Vec<[f64; 2]>,
    labels: Vec<i32>,
    labelled: bool,
}

impl Rows {
    fn push(&mut self, [x1, y1, x2, y2]: [f64; 4], label: Option<i32>) {
        self.points1.push([x1, y1]);
        self.points2.push([x2, y2]);
        if let Some(l) = label {
            self.labels.push(l);
            self.labelled = true;
        }
    }
}

fn finish(path: &Path, rows: Rows, image_size: Option<(u32, u32)>) -> Result<Scene, DatasetError> {
    let sidecar_file = sidecar_path(path);
    let sidecar = if sidecar_file.is_file() {
        Some(read_sidecar(&sidecar_file)?)
    } else {
        None
    };
    let image_size = image_size
        .or_else(|| sidecar.as_ref().map(|s| (s.width, s.height)))
        .ok_or_else(|| DatasetError::MissingField {
            path: path.to_path_buf(),
            field: format!(
                "image size: pass it explicitly or write `width` and `height` to {}",
                sidecar_file.display()
            ),
        })?;
    let stem = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let scene = Scene {
        name: sidecar
            .as_ref()
            .and_then(|s| s.name.clone())
            .unwrap_or(stem),
        points1: rows.points1,
        points2: rows.points2,
        labels: rows.labelled.then_some(rows.labels),
        image_size,
        principal_point: sidecar
            .as_ref()
            .and_then(|s| s.principal_point)
            .unwrap_or_else(|| centre_principal_point(image_size)),
        true_focal: sidecar.as_ref().and_then(|s| s.focal),
        gt_fundamentals: Vec::new(),
        images: None,
    };
    scene.validate().map_err(|e| e.in_file(path))?;
    Ok(scene)
}
