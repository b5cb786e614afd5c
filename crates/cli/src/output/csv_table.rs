//! CSV files held as text cells: read, written atomically, appended row by row.

use anyhow::{bail, Context, Result};
use std::fs::{File, OpenOptions};
use std::io::{BufWriter, Write as _};
use std::path::{Path, PathBuf};

/// A CSV file held as text cells: a header and rows.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CsvTable {
    /// Column names.
    pub header: Vec<String>,
    /// Rows, each as long as the header.
    pub rows: Vec<Vec<String>>,
}

impl CsvTable {
    /// Reads a CSV file with a header. A last line without its newline (a
    /// run killed while writing it) is dropped: it was never complete.
    pub fn read(path: &Path) -> Result<Self> {
        let mut text = std::fs::read_to_string(path)
            .with_context(|| format!("{}: cannot read", path.display()))?;
        if !text.is_empty() && !text.ends_with('\n') {
            let keep = text.rfind('\n').map_or(0, |i| i + 1);
            text.truncate(keep);
        }
        Self::parse(&text, path)
    }

    /// Parses CSV text with a header; `path` only names the source in errors.
    pub fn parse(text: &str, path: &Path) -> Result<Self> {
        let mut reader = csv::ReaderBuilder::new()
            .has_headers(true)
            .from_reader(text.as_bytes());
        let header: Vec<String> = reader
            .headers()
            .with_context(|| format!("{}: bad CSV header", path.display()))?
            .iter()
            .map(str::to_string)
            .collect();
        if header.is_empty() || header.iter().all(String::is_empty) {
            bail!("{}: empty CSV file (no header)", path.display());
        }
        let mut rows = Vec::new();
        for (i, record) in reader.records().enumerate() {
            let record = record.with_context(|| format!("{}: row {}", path.display(), i + 2))?;
            rows.push(record.iter().map(str::to_string).collect());
        }
        Ok(Self { header, rows })
    }

    /// Position of column `name`.
    pub fn column(&self, name: &str) -> Option<usize> {
        self.header.iter().position(|h| h == name)
    }

    /// Position of column `name`, or an error naming `file`.
    pub fn require_column(&self, name: &str, file: &Path) -> Result<usize> {
        self.column(name)
            .with_context(|| format!("{}: no column `{name}`", file.display()))
    }

    /// The CSV text, `\n`-terminated lines.
    pub fn to_csv(&self) -> Result<String> {
        let mut writer = csv::WriterBuilder::new()
            .terminator(csv::Terminator::Any(b'\n'))
            .from_writer(Vec::new());
        writer.write_record(&self.header)?;
        for row in &self.rows {
            writer.write_record(row)?;
        }
        let bytes = writer.into_inner().map_err(|e| anyhow::anyhow!("{e}"))?;
        Ok(String::from_utf8(bytes)?)
    }

    /// Writes the table to `path` through a temporary file and a rename, so
    /// that a crash leaves either the old or the new file.
    pub fn write_atomic(&self, path: &Path) -> Result<()> {
        write_atomic(path, &self.to_csv()?)
    }
}

/// The temporary file a write of `path` goes through: hidden, in the same
/// directory (so that the rename is atomic), named after `path` and this
/// process, with `path`'s extension kept (the figure writers choose the
/// format by it): `dir/.NAME.PID.tmp.EXT`.
fn temp_path(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let ext = path
        .extension()
        .map(|e| format!(".{}", e.to_string_lossy()))
        .unwrap_or_default();
    path.with_file_name(format!(".{name}.{}.tmp{ext}", std::process::id()))
}

/// Writes `text` to `path` through a temporary file, synced, and a rename
/// ([`write_bytes_atomic`]); the error names `path`.
pub fn write_atomic(path: &Path, text: &str) -> Result<()> {
    write_bytes_atomic(path, text.as_bytes())
        .with_context(|| format!("{}: cannot write", path.display()))
}

/// Writes `bytes` to `path` through its [`temp_path`], synced, and a
/// rename: a failure (a full disk, a file-size limit, a crash) leaves the
/// old file or none, never a partial one, and removes the temporary file.
pub fn write_bytes_atomic(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let tmp = temp_path(path);
    let result = File::create(&tmp)
        .and_then(|mut file| {
            file.write_all(bytes)?;
            file.sync_all()
        })
        .and_then(|()| std::fs::rename(&tmp, path));
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

/// Appends CSV rows to a file, flushing after every row.
pub struct CsvAppender {
    path: PathBuf,
    writer: csv::Writer<BufWriter<File>>,
}

impl CsvAppender {
    /// Opens `path` for appending; writes `header` first when the file is
    /// new or empty, and checks it against the file's header otherwise.
    pub fn open(path: &Path, header: &[String]) -> Result<Self> {
        let existing = path.exists() && std::fs::metadata(path)?.len() > 0;
        if existing {
            let table = CsvTable::read(path)?;
            if table.header != header {
                bail!(
                    "{}: its columns ({}) are not this run's ({}); use another --out directory",
                    path.display(),
                    table.header.join(","),
                    header.join(",")
                );
            }
            // Drop an incomplete last line before appending after it.
            let text = table.to_csv()?;
            if std::fs::read_to_string(path)? != text {
                write_atomic(path, &text)?;
            }
        }
        let file = OpenOptions::new()
            .create(true)
            .append(true)
            .open(path)
            .with_context(|| format!("{}: cannot open for appending", path.display()))?;
        let mut writer = csv::WriterBuilder::new()
            .terminator(csv::Terminator::Any(b'\n'))
            .from_writer(BufWriter::new(file));
        if !existing {
            writer.write_record(header)?;
            writer.flush()?;
        }
        Ok(Self {
            path: path.to_path_buf(),
            writer,
        })
    }

    /// Appends one row and flushes it to the file (`csv::Writer::flush`
    /// also flushes the buffered file).
    pub fn append(&mut self, row: &[String]) -> Result<()> {
        self.writer
            .write_record(row)
            .with_context(|| format!("{}: cannot append", self.path.display()))?;
        self.writer
            .flush()
            .with_context(|| format!("{}: cannot flush", self.path.display()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn appender_writes_header_once_and_drops_a_torn_line() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("x.csv");
        let header: Vec<String> = vec!["a".into(), "b".into()];
        {
            let mut w = CsvAppender::open(&path, &header).unwrap();
            w.append(&["1".into(), "x,y".into()]).unwrap();
        }
        // A killed writer leaves half a line.
        let mut text = std::fs::read_to_string(&path).unwrap();
        text.push_str("2,unfinis");
        std::fs::write(&path, &text).unwrap();
        {
            let mut w = CsvAppender::open(&path, &header).unwrap();
            w.append(&["3".into(), "z".into()]).unwrap();
        }
        assert_eq!(
            std::fs::read_to_string(&path).unwrap(),
            "a,b\n1,\"x,y\"\n3,z\n"
        );
        let other: Vec<String> = vec!["a".into(), "c".into()];
        let err = CsvAppender::open(&path, &other).err().unwrap().to_string();
        assert!(err.contains("are not this run's"), "{err}");
    }
}
