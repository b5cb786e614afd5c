//! TOML parsing with errors that name the file, the key path and the line.

use std::path::{Path, PathBuf};
use thiserror::Error;

/// A configuration error: one line naming the file, the key and the line.
#[derive(Debug, Error)]
pub enum ConfigError {
    /// The file could not be read.
    #[error("{file}: cannot read")]
    Read {
        /// The file.
        file: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// TOML syntax error, unknown key or wrongly typed value.
    #[error("{file}{}: {key}: {message}", line.map(|l| format!(":{l}")).unwrap_or_default())]
    Invalid {
        /// The file.
        file: PathBuf,
        /// 1-based line of the offending text, when known.
        line: Option<usize>,
        /// Dotted key path, e.g. `pipeline.method`.
        key: String,
        /// What is wrong.
        message: String,
    },
}

impl ConfigError {
    pub(super) fn invalid(file: &Path, key: impl Into<String>, message: impl Into<String>) -> Self {
        ConfigError::Invalid {
            file: file.to_path_buf(),
            line: None,
            key: key.into(),
            message: message.into(),
        }
    }

    pub(super) fn with_line(self, text: &str, key_path: &str) -> Self {
        match self {
            ConfigError::Invalid {
                file,
                line: None,
                key,
                message,
            } => ConfigError::Invalid {
                file,
                line: find_key_line(text, key_path),
                key,
                message,
            },
            other => other,
        }
    }
}

/// 1-based line of the byte offset `pos` in `text`.
fn line_of(text: &str, pos: usize) -> usize {
    text[..pos.min(text.len())].matches('\n').count() + 1
}

/// Best-effort line of `section.key` in a TOML text: the first `key =` line
/// after the `[section]` header.
fn find_key_line(text: &str, key_path: &str) -> Option<usize> {
    let (section, key) = key_path.rsplit_once('.')?;
    let key = key.split('[').next()?;
    let mut in_section = false;
    for (i, line) in text.lines().enumerate() {
        let t = line.trim();
        if t.starts_with('[') {
            in_section = t.trim_start_matches('[').trim_end_matches(']').trim() == section;
            continue;
        }
        if in_section {
            if let Some((k, _)) = t.split_once('=') {
                if k.trim().trim_matches('"') == key {
                    return Some(i + 1);
                }
            }
        }
    }
    None
}

/// `text`'s non-empty lines, trimmed and joined by `; `.
fn one_line(text: &str) -> String {
    text.lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect::<Vec<_>>()
        .join("; ")
}

/// Deserializes `text` as `T`, reporting the key path and line of the first error.
pub fn parse_toml<T: serde::de::DeserializeOwned>(
    text: &str,
    file: &Path,
) -> Result<T, ConfigError> {
    let deserializer = toml::Deserializer::new(text);
    serde_path_to_error::deserialize(deserializer).map_err(|err| {
        let path = err.path().to_string();
        let inner = err.inner();
        let key = if path == "." || path.is_empty() {
            "(top level)".to_string()
        } else {
            path
        };
        ConfigError::Invalid {
            file: file.to_path_buf(),
            line: inner.span().map(|s| line_of(text, s.start)),
            key,
            message: one_line(inner.message()),
        }
    })
}
