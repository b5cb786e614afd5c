//! `sctl.load_adelaidermf` and `sctl.load_hopef`: one scene of each dataset
//! as numpy arrays (the `datasets` crate's loaders, errors naming the file).

use crate::convert::{array1, matrices_array, points_array, value_error};
use datasets::{DatasetError, LoadOptions, Scene};
use numpy::ndarray::Array3;
use numpy::IntoPyArray;
use pyo3::exceptions::{PyFileNotFoundError, PyOSError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::{Path, PathBuf};

/// A loader error as a Python exception: `FileNotFoundError` or `OSError`
/// for a file that cannot be read, `ValueError` for bad content.
fn dataset_error(e: DatasetError) -> PyErr {
    match &e {
        DatasetError::Io { source, .. } if source.kind() == std::io::ErrorKind::NotFound => {
            PyFileNotFoundError::new_err(e.to_string())
        }
        DatasetError::Io { .. } => PyOSError::new_err(e.to_string()),
        _ => value_error(e.to_string()),
    }
}

/// RGB pixels `(W, H)` as an (H, W, 3) uint8 array.
fn image_array(py: Python<'_>, (w, h): (u32, u32), raw: Vec<u8>) -> Bound<'_, PyAny> {
    Array3::from_shape_vec((h as usize, w as usize, 3), raw)
        .expect("an RGB image holds 3 bytes per pixel")
        .into_pyarray(py)
        .into_any()
}

/// A scene as a dict of numpy arrays.
fn scene_dict(py: Python<'_>, scene: Scene) -> PyResult<Bound<'_, PyDict>> {
    let dict = PyDict::new(py);
    dict.set_item("name", &scene.name)?;
    dict.set_item("x1", points_array(py, &scene.points1))?;
    dict.set_item("x2", points_array(py, &scene.points2))?;
    dict.set_item("labels", scene.labels.map(|l| array1(py, l)))?;
    dict.set_item("image_size", scene.image_size)?;
    dict.set_item(
        "principal_point",
        array1(py, scene.principal_point.to_vec()),
    )?;
    dict.set_item("true_focal", scene.true_focal)?;
    dict.set_item("F", matrices_array(py, &scene.gt_fundamentals))?;
    let images = scene.images.map(|(a, b)| {
        (
            image_array(py, a.dimensions(), a.into_raw()),
            image_array(py, b.dimensions(), b.into_raw()),
        )
    });
    dict.set_item("images", images)?;
    Ok(dict)
}

/// Runs a loader without the GIL and converts its scene.
fn load<'py>(
    py: Python<'py>,
    path: &Path,
    images: bool,
    loader: fn(&Path, LoadOptions) -> Result<Scene, DatasetError>,
) -> PyResult<Bound<'py, PyDict>> {
    let scene = py
        .detach(|| loader(path, LoadOptions { images }))
        .map_err(dataset_error)?;
    scene_dict(py, scene)
}

/// Loads one AdelaideRMF scene (a MATLAB v5 ``.mat`` file of the
/// dataset's "Fundamental Matrix Data").
///
/// Parameters
/// ----------
/// path : str or os.PathLike
///     The ``.mat`` file, e.g. ``.../adelaidermf/F/biscuitbook.mat``.
/// images : bool, default False
///     Also decode the image pair into ``images``.
///
/// Returns
/// -------
/// dict
///     ``name`` (file stem), ``x1``, ``x2`` ((N, 2) float64, pixels),
///     ``labels`` ((N,) int32, 0 = outlier, 1..k = motion), ``image_size``
///     ((W, H)), ``principal_point`` ((2,), the image centre),
///     ``true_focal`` (None), ``F`` ((0, 3, 3): no ground-truth F) and
///     ``images`` (two (H, W, 3) uint8 arrays, or None).
///
/// Raises
/// ------
/// FileNotFoundError, OSError
///     When the file cannot be read.
/// ValueError
///     When its content is not a valid scene (the message names the file and
///     the variable).
#[pyfunction]
#[pyo3(signature = (path, *, images=false))]
pub fn load_adelaidermf(
    py: Python<'_>,
    path: PathBuf,
    images: bool,
) -> PyResult<Bound<'_, PyDict>> {
    load(py, &path, images, |p, o| {
        datasets::adelaidermf::load_scene_with(p, o)
    })
}

/// Loads one HOPE-F scene folder (``<root>/<k>/<NNNN>``, holding
/// ``features_and_ground_truth.npz`` and ``camera_parameters.npz``), or a
/// folder of the same layout written by ``sctl synth``.
///
/// Parameters
/// ----------
/// folder : str or os.PathLike
///     The scene folder.
/// images : bool, default False
///     Also decode ``render0.png`` / ``render1.png`` into ``images`` when
///     present.
///
/// Returns
/// -------
/// dict
///     ``name`` (``"<k>/<NNNN>"``), ``x1``, ``x2`` ((N, 2) float64,
///     pixels), ``labels`` ((N,) int32, 0 = outlier, 1..k = motion),
///     ``image_size`` ((W, H)), ``principal_point`` ((2,), from K),
///     ``true_focal`` (K[0, 0]), ``F`` ((k, 3, 3) ground-truth matrices,
///     ``F[j]`` for label j + 1) and ``images`` (or None).
///
/// Raises
/// ------
/// FileNotFoundError, OSError
///     When a file cannot be read.
/// ValueError
///     When an archive or array is invalid (the message names the file and
///     the array).
#[pyfunction]
#[pyo3(signature = (folder, *, images=false))]
pub fn load_hopef(py: Python<'_>, folder: PathBuf, images: bool) -> PyResult<Bound<'_, PyDict>> {
    load(py, &folder, images, |p, o| {
        datasets::hopef::load_scene_with(p, o)
    })
}
