//! `sctl._sctl`, the compiled core of the `sctl` Python package: numpy
//! bindings (PyO3) of the workspace crates.
//!
//! - `segment::segment`: Algorithm 1 (semi-calibrated T-Linkage) through
//!   `segmentation::segment`, with every `Params` key as a keyword;
//! - `focal::focals_from_fundamental`, `focal::bougnoux`: the focal
//!   solvers of docs/method.md step 4 (crate `focal`);
//! - `tools::t_linkage`, `tools::sampson_distances`, `tools::metrics`:
//!   crates `clustering`, `geometry`, `metrics`;
//! - `datasets::load_adelaidermf`, `datasets::load_hopef`: crate
//!   `datasets`.
//!
//! Every computation runs without the GIL; bad input is a Python exception
//! (`ValueError` naming the argument or key, `FileNotFoundError` / `OSError`
//! naming the file), never a panic.

mod convert;
mod datasets;
mod focal;
mod interrupt;
mod params;
mod segment;
mod tools;

use pyo3::prelude::*;

/// Two-view motion segmentation with semi-calibrated cameras
/// (semi-calibrated T-Linkage), from numpy.
#[pymodule]
fn _sctl(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(segment::segment, m)?)?;
    m.add_class::<segment::Segmentation>()?;
    m.add(
        "SegmentationWarning",
        m.py().get_type::<segment::SegmentationWarning>(),
    )?;
    m.add_function(wrap_pyfunction!(params::default_params, m)?)?;
    m.add_function(wrap_pyfunction!(focal::focals_from_fundamental, m)?)?;
    m.add_function(wrap_pyfunction!(focal::bougnoux, m)?)?;
    m.add_function(wrap_pyfunction!(tools::t_linkage, m)?)?;
    m.add_function(wrap_pyfunction!(tools::sampson_distances, m)?)?;
    m.add_function(wrap_pyfunction!(tools::metrics, m)?)?;
    m.add_function(wrap_pyfunction!(datasets::load_adelaidermf, m)?)?;
    m.add_function(wrap_pyfunction!(datasets::load_hopef, m)?)?;
    Ok(())
}
