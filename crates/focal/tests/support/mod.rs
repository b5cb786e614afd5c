//! Test support shared by focal's integration tests: the reader of the
//! PoseLib fixture (`../shared/fixtures/focal/poselib_focals.csv`, written
//! by `../shared/tools/make_focal_fixtures.py`).
// Each test binary uses a subset of this module.
#![allow(dead_code)]

use std::path::PathBuf;

use focal::FocalWeights;
use nalgebra::Matrix3;

/// One row of `poselib_focals.csv`: an F with PoseLib's answers (docs/method.md
/// step 4). Empty numeric cells read as NaN.
pub struct Row {
    /// The row's id.
    pub id: usize,
    /// The kind of scene (`exact`, `noise…`, `planar`, `forward`).
    pub kind: String,
    /// Prior focal length, px.
    pub f_prior: f64,
    /// The fundamental matrix.
    pub f: Matrix3<f64>,
    /// The weight set PoseLib ran with.
    pub weights: FocalWeights,
    /// PoseLib's `max_iters`.
    pub max_iters: usize,
    /// PoseLib's Bougnoux focal lengths (NaN: none).
    pub bougnoux: [f64; 2],
    /// PoseLib's iterative focal lengths.
    pub iter_f: [f64; 2],
    /// PoseLib's iteration count.
    pub iterations: usize,
    /// `feasible`, `infeasible`, `prior` or `nan` (docs/method.md step 4).
    pub status: String,
}

/// `../shared/fixtures/focal/poselib_focals.csv` beside the repository.
pub fn fixture_path() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/fixtures/focal/poselib_focals.csv")
}

/// Every row of the fixture; panics with the path when it is missing.
pub fn load() -> Vec<Row> {
    let path = fixture_path();
    assert!(
        path.exists(),
        "missing fixture {}: the repository expects the shared directory beside it \
         (../shared/fixtures/focal/poselib_focals.csv, written by \
         ../shared/tools/make_focal_fixtures.py)",
        path.display()
    );
    let mut rdr = csv::Reader::from_path(&path).expect("readable fixture");
    let headers = rdr.headers().unwrap().clone();
    let col = |name: &str| {
        headers
            .iter()
            .position(|h| h == name)
            .unwrap_or_else(|| panic!("column {name}"))
    };
    let num = |rec: &csv::StringRecord, name: &str| -> f64 {
        let s = &rec[col(name)];
        if s.is_empty() {
            f64::NAN
        } else {
            s.parse().unwrap_or_else(|_| panic!("{name}: {s}"))
        }
    };
    rdr.records()
        .map(|rec| {
            let rec = rec.unwrap();
            let mut f = Matrix3::zeros();
            for r in 0..3 {
                for c in 0..3 {
                    f[(r, c)] = num(&rec, &format!("F{r}{c}"));
                }
            }
            Row {
                id: num(&rec, "id") as usize,
                kind: rec[col("kind")].to_string(),
                f_prior: num(&rec, "f_prior"),
                f,
                weights: FocalWeights::new(
                    num(&rec, "w_f1"),
                    num(&rec, "w_pp1"),
                    num(&rec, "w_f2"),
                    num(&rec, "w_pp2"),
                ),
                max_iters: num(&rec, "max_iters") as usize,
                bougnoux: [num(&rec, "bougnoux_f1"), num(&rec, "bougnoux_f2")],
                iter_f: [num(&rec, "iter_f1"), num(&rec, "iter_f2")],
                iterations: num(&rec, "iterations") as usize,
                status: rec[col("poselib_status")].to_string(),
            }
        })
        .collect()
}
