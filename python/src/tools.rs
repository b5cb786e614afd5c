//! The stages of Algorithm 1 a user may want on their own: T-Linkage of a
//! preference matrix, Sampson distances, and the segmentation metrics.

use crate::convert::{array1, labels, matrices, matrix, point_pairs, value_error};
use ::metrics::ClusteringMetrics;
use clustering::PreferenceMatrix;
use geometry::Correspondences;
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// A count given as a Python int: `>= 0`, or a `ValueError` naming it.
fn count(value: i64, name: &str) -> PyResult<usize> {
    usize::try_from(value).map_err(|_| value_error(format!("{name}: must be >= 0, got {value}")))
}

/// T-Linkage (thesis Eqs. 39-40) of a continuous preference matrix, then the
/// size filter (docs/method.md steps 8-9).
///
/// Parameters
/// ----------
/// preferences : array_like, shape (N, M)
///     Preference of point i for hypothesis j, in [0, 1] (Eq. 38:
///     exp(-r / tau) for r <= 5 tau, else 0).
/// min_cluster_size : int, default 8
///     Clusters with fewer points become outliers.
///
/// Returns
/// -------
/// numpy.ndarray of int32, shape (N,)
///     0, 1, ... for the clusters (ordered by their smallest point index),
///     -1 for outliers.
///
/// The computation releases the GIL.
#[pyfunction]
#[pyo3(signature = (preferences, min_cluster_size=8))]
pub fn t_linkage<'py>(
    py: Python<'py>,
    preferences: &Bound<'py, PyAny>,
    min_cluster_size: i64,
) -> PyResult<Bound<'py, PyArray1<i32>>> {
    let min_cluster_size = count(min_cluster_size, "min_cluster_size")?;
    let (values, n, m) = matrix(preferences, "preferences")?;
    let rows: Vec<Vec<f64>> = (0..n)
        .map(|i| values[i * m..(i + 1) * m].to_vec())
        .collect();
    let prefs =
        PreferenceMatrix::from_rows(&rows).map_err(|e| value_error(format!("preferences: {e}")))?;
    let clustering = py.detach(|| clustering::t_linkage(&prefs, min_cluster_size));
    Ok(array1(py, clustering.labels))
}

/// Sampson distance (thesis Eq. 23) of each match to a fundamental matrix.
///
/// Parameters
/// ----------
/// F : array_like, shape (3, 3)
///     Fundamental matrix, ``x2' F x1 = 0`` in the coordinates of x1, x2.
/// x1, x2 : array_like, shape (N, 2)
///     The matches.
/// squared : bool, default False
///     Return the squared distances (Eq. 23 itself, px**2).
///
/// Returns
/// -------
/// numpy.ndarray, shape (N,)
///     ``|x2' F x1| / sqrt(a**2 + b**2 + c**2 + d**2)`` in px, where
///     (a, b) and (c, d) are the first two entries of F x1 and F' x2.
#[pyfunction]
#[pyo3(signature = (F, x1, x2, *, squared=false))]
#[allow(non_snake_case)]
pub fn sampson_distances<'py>(
    py: Python<'py>,
    F: &Bound<'py, PyAny>,
    x1: &Bound<'py, PyAny>,
    x2: &Bound<'py, PyAny>,
    squared: bool,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let (stack, single) = matrices(F, "F")?;
    if !single {
        return Err(value_error("F: expected one 3 x 3 matrix"));
    }
    let (p1, p2) = point_pairs(x1, x2)?;
    let points = Correspondences::new(&p1, &p2).map_err(|e| value_error(e.to_string()))?;
    let mut out = vec![0.0; points.len()];
    geometry::sampson_distances_squared(&stack[0], &points, &mut out);
    if !squared {
        out.iter_mut().for_each(|d| *d = d.sqrt());
    }
    Ok(array1(py, out))
}

/// The segmentation metrics of docs/method.md "Metrics" for one scene.
///
/// Parameters
/// ----------
/// pred : array_like of int, shape (N,)
///     Predicted labels: -1 for an outlier, any id >= 0 for a cluster.
/// gt : array_like of int, shape (N,)
///     Ground truth: 0 for a gross outlier, 1..k for the motions.
///
/// Returns
/// -------
/// dict
///     ``me`` (misclassification error, ground-truth outliers excluded, a
///     predicted outlier wrong: the thesis's), ``me_all`` (over all points,
///     outliers a class of their own: the multi-model fitting literature's),
///     ``acc`` (1 - me), ``fnr`` (false
///     negative rate), ``pur`` (purity), ``ari`` (adjusted Rand index) and
///     ``nmi`` (normalised mutual information), as fractions.
#[pyfunction]
pub fn metrics<'py>(
    py: Python<'py>,
    pred: &Bound<'py, PyAny>,
    gt: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyDict>> {
    let (pred, gt) = (labels(pred, "pred")?, labels(gt, "gt")?);
    let m = ClusteringMetrics::compute(&pred, &gt).map_err(|e| value_error(e.to_string()))?;
    let dict = PyDict::new(py);
    for (key, value) in [
        ("me", m.me),
        ("me_all", m.me_all),
        ("acc", m.acc),
        ("fnr", m.fnr),
        ("pur", m.pur),
        ("ari", m.ari),
        ("nmi", m.nmi),
    ] {
        dict.set_item(key, value)?;
    }
    Ok(dict)
}
