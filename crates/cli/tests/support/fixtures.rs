//! The oracle fixtures of `shared/fixtures/` (beside the repository), for
//! the integration tests and the unit tests that include this file by path.
#![allow(dead_code)]

use std::path::PathBuf;

/// `shared/fixtures/<relative>`, checked to exist.
pub fn shared_fixture(relative: &str) -> PathBuf {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/fixtures")
        .join(relative);
    assert!(
        path.exists(),
        "missing fixture {}: the repository expects the shared directory beside it \
         (../shared/fixtures/{relative})",
        path.display()
    );
    path
}

/// The cases of the JSON fixture `shared/fixtures/stats/<name>`: a
/// non-empty list.
pub fn load_fixture<T: serde::de::DeserializeOwned>(name: &str) -> Vec<T> {
    let path = shared_fixture(&format!("stats/{name}"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| {
        panic!(
            "the oracle fixture is missing: expected it at {} (shared/fixtures/stats/{name} beside the repository): {e}",
            path.display()
        )
    });
    let cases: Vec<T> = serde_json::from_str(&text)
        .unwrap_or_else(|e| panic!("{} does not parse as a list of cases: {e}", path.display()));
    assert!(!cases.is_empty(), "{} holds no cases", path.display());
    cases
}

/// The PoseLib focal lengths of `shared/fixtures/focal/poselib_focals.csv`:
/// one row per fundamental matrix, with PoseLib's answers.
pub struct PoseLibFocals {
    /// The file.
    pub path: PathBuf,
    header: csv::StringRecord,
    /// The rows, in file order.
    pub rows: Vec<csv::StringRecord>,
}

impl PoseLibFocals {
    /// Reads the fixture.
    pub fn read() -> Self {
        let path = shared_fixture("focal/poselib_focals.csv");
        let mut reader = csv::Reader::from_path(&path).unwrap();
        let header = reader.headers().unwrap().clone();
        let rows = reader.records().map(|r| r.unwrap()).collect();
        Self { path, header, rows }
    }

    /// The cell of column `name` in row `row`, as text.
    pub fn text<'a>(&self, row: &'a csv::StringRecord, name: &str) -> &'a str {
        let col = self.header.iter().position(|h| h == name);
        &row[col.unwrap_or_else(|| panic!("{}: no column {name}", self.path.display()))]
    }

    /// The cell of column `name` in row `row` as a number; None when empty
    /// or `nan`.
    pub fn value(&self, row: &csv::StringRecord, name: &str) -> Option<f64> {
        number(self.text(row, name))
    }
}

/// A CSV cell as a number: None when empty or `nan`.
pub fn number(cell: &str) -> Option<f64> {
    if cell.is_empty() || cell == "nan" {
        None
    } else {
        Some(cell.parse().unwrap())
    }
}
