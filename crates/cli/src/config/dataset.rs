//! The `[dataset]` table: which scenes an experiment runs on.

use super::ConfigError;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// The dataset an experiment runs on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum DatasetKind {
    /// The 19 AdelaideRMF fundamental-matrix sequences (`<root>/adelaidermf/F/*.mat`).
    Adelaidermf,
    /// HOPE-F in its on-disk layout (`<root>/hopef/<k>/<NNNN>/`).
    Hopef,
    /// Scenes generated in memory by the seeded synthetic generator.
    Synthetic,
    /// The user's own match files (`x1,y1,x2,y2[,label]` CSV).
    Csv,
}

/// HOPE-F split by scene index: train 0000–0799, val 0800–0899, test 0900–0999.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Split {
    /// Scenes 0000–0799.
    Train,
    /// Scenes 0800–0899.
    Val,
    /// Scenes 0900–0999.
    Test,
}

/// `[dataset]`: which scenes an experiment runs on.
///
/// Selection keys combine (a scene must pass all that are given):
/// `scenes` (names), `split` and `categories` (HOPE-F and synthetic),
/// `index_range` (inclusive `[first, last]` scene index: HOPE-F's folder
/// number, else the position in the dataset's scene list).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DatasetConfig {
    /// `adelaidermf`, `hopef`, `synthetic` or `csv`.
    pub kind: DatasetKind,
    /// Data root (below it: `adelaidermf/F`, `hopef/`); overridden by
    /// `--data-root` and by `SCTL_DATA_ROOT`; default `datasets`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub data_root: Option<PathBuf>,
    /// Scene names to run, in the dataset's order. Default: every scene.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scenes: Option<Vec<String>>,
    /// HOPE-F split (`train`, `val`, `test`). Default: every split.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub split: Option<Split>,
    /// Number of moving objects (1–4) to keep (HOPE-F, synthetic). Default: all.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub categories: Option<Vec<u32>>,
    /// Inclusive scene-index range `[first, last]`. Default: all.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub index_range: Option<[u32; 2]>,
    /// Synthetic generator preset, one of [`datasets::synthetic::Preset::ALL`] by
    /// name (`quick`, `hopef-like`, `kitti-like`, `hopef`, `kitti-real`,
    /// `adelaide-like`). Default `quick`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub preset: Option<String>,
    /// Synthetic generator seed. Default 1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub generator_seed: Option<u64>,
    /// `csv`: the match files, relative to the data root unless absolute:
    /// `.csv` (`x1,y1,x2,y2[,label]` with a header) or AdelaideRMF-style
    /// `.txt` (`x1 y1 x2 y2 [label]`), each with an optional sidecar
    /// `<file>.toml` (width, height, name, focal, principal point).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub files: Option<Vec<PathBuf>>,
    /// `csv`: image width in pixels of every file (else from each sidecar).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub width: Option<u32>,
    /// `csv`: image height in pixels of every file (else from each sidecar).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub height: Option<u32>,
}

impl DatasetConfig {
    pub(super) fn check(&self, file: &Path) -> Result<(), ConfigError> {
        let only_for = |key: &str, present: bool, kinds: &[DatasetKind]| {
            if present && !kinds.contains(&self.kind) {
                Err(ConfigError::invalid(
                    file,
                    format!("dataset.{key}"),
                    format!("does not apply to kind = \"{}\"", self.kind.name()),
                ))
            } else {
                Ok(())
            }
        };
        use DatasetKind::*;
        only_for("split", self.split.is_some(), &[Hopef, Synthetic])?;
        only_for("categories", self.categories.is_some(), &[Hopef, Synthetic])?;
        only_for("preset", self.preset.is_some(), &[Synthetic])?;
        only_for(
            "generator_seed",
            self.generator_seed.is_some(),
            &[Synthetic],
        )?;
        only_for("files", self.files.is_some(), &[Csv])?;
        only_for("width", self.width.is_some(), &[Csv])?;
        only_for("height", self.height.is_some(), &[Csv])?;
        if let Some([a, b]) = self.index_range {
            if a > b {
                return Err(ConfigError::invalid(
                    file,
                    "dataset.index_range",
                    format!("first index {a} is after last index {b}"),
                ));
            }
        }
        if let Some(cats) = &self.categories {
            if let Some(c) = cats.iter().find(|c| !(1..=4).contains(*c)) {
                return Err(ConfigError::invalid(
                    file,
                    "dataset.categories",
                    format!("category {c} is not a number of motions in 1..=4"),
                ));
            }
        }
        if self.kind == Csv {
            if self.files.as_ref().map_or(0, Vec::len) == 0 {
                return Err(ConfigError::invalid(
                    file,
                    "dataset.files",
                    "kind = \"csv\" needs a non-empty list of match files",
                ));
            }
            if self.width.is_some() != self.height.is_some() {
                return Err(ConfigError::invalid(
                    file,
                    if self.width.is_some() {
                        "dataset.height"
                    } else {
                        "dataset.width"
                    },
                    "give both width and height (or neither, and a sidecar TOML per file)",
                ));
            }
            if self.width == Some(0) || self.height == Some(0) {
                return Err(ConfigError::invalid(
                    file,
                    if self.width == Some(0) {
                        "dataset.width"
                    } else {
                        "dataset.height"
                    },
                    "must be > 0 pixels",
                ));
            }
        }
        Ok(())
    }
}

impl DatasetKind {
    /// The name used in configs.
    pub fn name(self) -> &'static str {
        match self {
            DatasetKind::Adelaidermf => "adelaidermf",
            DatasetKind::Hopef => "hopef",
            DatasetKind::Synthetic => "synthetic",
            DatasetKind::Csv => "csv",
        }
    }
}
