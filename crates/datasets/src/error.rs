//! The error type of every loader and writer in this crate.

use crate::mat::MatError;
use crate::npz::NpzError;
use std::path::{Path, PathBuf};

/// Where to get a dataset that is not found: part of the
/// [`DatasetError::DatasetMissing`] message.
pub const DATASET_HINT: &str =
    "run scripts/link-datasets.sh, or see datasets/README.md for where to download it";

/// Everything that can go wrong loading, validating or writing a scene.
/// Messages name the file, the scene and the field at fault.
#[derive(Debug, thiserror::Error)]
pub enum DatasetError {
    /// Reading or writing a file failed.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file or directory.
        path: PathBuf,
        /// The underlying error.
        #[source]
        source: std::io::Error,
    },
    /// A `.mat` file could not be parsed.
    #[error("{}: not a readable MAT v5 file: {source}", path.display())]
    Mat {
        /// The `.mat` file.
        path: PathBuf,
        /// What the MAT reader found wrong.
        #[source]
        source: MatError,
    },
    /// A `.npz` archive or one of its arrays could not be parsed.
    #[error("{}: {}{source}", path.display(), array.as_ref().map(|a| format!("array `{a}`: ")).unwrap_or_else(|| "not a readable .npz archive: ".to_string()))]
    Npz {
        /// The `.npz` file.
        path: PathBuf,
        /// The array being read, if the archive itself was readable.
        array: Option<String>,
        /// What the reader found wrong.
        #[source]
        source: NpzError,
    },
    /// A required variable, array or column is absent.
    #[error("{}: missing {field}", path.display())]
    MissingField {
        /// The file.
        path: PathBuf,
        /// Which field, e.g. "array `labels`" or "variable `data`".
        field: String,
    },
    /// A field is present but has the wrong shape, type or value.
    #[error("{}: {field}: {problem}", path.display())]
    BadField {
        /// The file.
        path: PathBuf,
        /// Which field, e.g. "array `points1`".
        field: String,
        /// What is wrong with it.
        problem: String,
    },
    /// A scene failed [`crate::Scene::validate`].
    #[error("{}scene `{scene}`: field `{field}`{}: {problem}",
        path.as_ref().map(|p| format!("{}: ", p.display())).unwrap_or_default(),
        index.map(|i| format!(" at index {i}")).unwrap_or_default())]
    InvalidScene {
        /// The file the scene came from, when known.
        path: Option<PathBuf>,
        /// Scene name.
        scene: String,
        /// The [`crate::Scene`] field at fault (`points1`, `labels`, …).
        field: &'static str,
        /// The offending element, when there is one.
        index: Option<usize>,
        /// What is wrong.
        problem: String,
    },
    /// A line of a text file (CSV, `matches.txt`, TOML) could not be parsed.
    #[error("{}{}: {problem}", path.display(), line.map(|l| format!(": line {l}")).unwrap_or_default())]
    Parse {
        /// The file.
        path: PathBuf,
        /// 1-based line number, when known.
        line: Option<u64>,
        /// What is wrong.
        problem: String,
    },
    /// A PNG image could not be read or written.
    #[error("{}: image: {source}", path.display())]
    Image {
        /// The image file.
        path: PathBuf,
        /// The decoder's error.
        #[source]
        source: image::ImageError,
    },
    /// The dataset directory does not exist.
    #[error("{what} not found at {}: {DATASET_HINT}", path.display())]
    DatasetMissing {
        /// Which dataset (e.g. "AdelaideRMF").
        what: &'static str,
        /// The directory that was looked for.
        path: PathBuf,
    },
    /// A scene name that the dataset does not have.
    #[error("{dataset}: no scene named `{name}`{}", if known.is_empty() { String::new() } else { format!(" (known: {})", known.join(", ")) })]
    UnknownScene {
        /// Dataset name.
        dataset: &'static str,
        /// The requested name.
        name: String,
        /// Valid names, when the list is short enough to print.
        known: Vec<String>,
    },
    /// Synthetic-generator parameters out of range.
    #[error("synthetic parameters: `{field}`: {problem}")]
    InvalidParams {
        /// The parameter.
        field: &'static str,
        /// Why it is rejected.
        problem: String,
    },
    /// The generator could not place the requested objects in view.
    #[error("synthetic scene `{scene}`: {problem}")]
    Generation {
        /// Scene name.
        scene: String,
        /// What failed.
        problem: String,
    },
}

impl DatasetError {
    /// Attaches the file a scene came from to an [`DatasetError::InvalidScene`]
    /// (other variants already carry their path and are returned unchanged).
    pub fn in_file(self, file: &Path) -> Self {
        match self {
            DatasetError::InvalidScene {
                path: None,
                scene,
                field,
                index,
                problem,
            } => DatasetError::InvalidScene {
                path: Some(file.to_path_buf()),
                scene,
                field,
                index,
                problem,
            },
            other => other,
        }
    }

    pub(crate) fn io(path: &Path, source: std::io::Error) -> Self {
        DatasetError::Io {
            path: path.to_path_buf(),
            source,
        }
    }
}
