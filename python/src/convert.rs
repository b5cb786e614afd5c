//! Conversions between Python objects and the crates' types: numpy arrays in
//! and out (every input checked, errors naming the argument), and keyword
//! arguments to serde values.

use nalgebra::Matrix3;
use numpy::ndarray::{Array1, Array2, Array3};
use numpy::{IntoPyArray, PyArray1, PyArray2, PyArray3, PyArrayDyn, PyArrayMethods};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};

/// A `ValueError` with `message`.
pub fn value_error(message: impl Into<String>) -> PyErr {
    PyValueError::new_err(message.into())
}

/// `numpy.asarray(obj, dtype)` or a `ValueError` naming the argument.
fn asarray<'py>(obj: &Bound<'py, PyAny>, name: &str, dtype: &str) -> PyResult<Bound<'py, PyAny>> {
    let np = obj.py().import("numpy")?;
    let kwargs = PyDict::new(obj.py());
    kwargs.set_item("dtype", np.getattr(dtype)?)?;
    np.call_method("asarray", (obj,), Some(&kwargs))
        .map_err(|e| value_error(format!("{name}: not an array of numbers ({e})")))
}

/// The shape of an array as a Python-style tuple, for messages.
fn shape_text(shape: &[usize]) -> String {
    match shape {
        [n] => format!("({n},)"),
        _ => format!(
            "({})",
            shape
                .iter()
                .map(usize::to_string)
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}

/// A float array of any shape, its shape and its values in C order, every
/// value finite.
fn finite_floats(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<(Vec<usize>, Vec<f64>)> {
    let array = asarray(obj, name, "float64")?.cast_into::<PyArrayDyn<f64>>()?;
    let view = array.readonly();
    let view = view.as_array();
    let shape = view.shape().to_vec();
    let values: Vec<f64> = view.iter().copied().collect();
    if let Some(i) = values.iter().position(|v| !v.is_finite()) {
        let width = shape.iter().skip(1).product::<usize>().max(1);
        return Err(value_error(format!(
            "{name}: non-finite value {} at row {}",
            values[i],
            i / width
        )));
    }
    Ok((shape, values))
}

/// A `TypeError` for `None` given as, or inside, the array `name` (numpy
/// would read it as NaN).
fn no_none(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<()> {
    let none = |at: String| {
        PyTypeError::new_err(format!(
            "{name}: expected an (N, 2) array of pixel coordinates, got None{at}"
        ))
    };
    if obj.is_none() {
        return Err(none(String::new()));
    }
    let np = obj.py().import("numpy")?;
    // A ragged list is reported by the numeric conversion that follows.
    let Ok(array) = np.call_method1("asarray", (obj,)) else {
        return Ok(());
    };
    let kind: String = array.getattr("dtype")?.getattr("kind")?.extract()?;
    if kind != "O" {
        return Ok(());
    }
    let at = np.call_method1(
        "argwhere",
        (np.call_method1("equal", (&array, obj.py().None()))?,),
    )?;
    if at.len()? == 0 {
        return Ok(());
    }
    let index: Vec<usize> = at.get_item(0)?.extract()?;
    Err(none(format!(" at row {}", index[0])))
}

/// An (N, 2) array of finite pixel coordinates.
pub fn points(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<Points> {
    no_none(obj, name)?;
    let (shape, values) = finite_floats(obj, name)?;
    if shape.len() != 2 || shape[1] != 2 {
        return Err(value_error(format!(
            "{name}: expected an (N, 2) array of pixel coordinates, got shape {}",
            shape_text(&shape)
        )));
    }
    Ok(values.chunks_exact(2).map(|p| [p[0], p[1]]).collect())
}

/// Points in pixels, one `[x, y]` per match.
pub type Points = Vec<[f64; 2]>;

/// Two (N, 2) arrays of matching points, of equal length.
pub fn point_pairs(x1: &Bound<'_, PyAny>, x2: &Bound<'_, PyAny>) -> PyResult<(Points, Points)> {
    let (p1, p2) = (points(x1, "x1")?, points(x2, "x2")?);
    if p1.len() != p2.len() {
        return Err(value_error(format!(
            "x1 has {} points but x2 has {}: one row per match in each",
            p1.len(),
            p2.len()
        )));
    }
    Ok((p1, p2))
}

/// One finite 3 × 3 matrix or a stack (K, 3, 3): the matrices and whether a
/// single one was given.
pub fn matrices(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<(Vec<Matrix3<f64>>, bool)> {
    let (shape, values) = finite_floats(obj, name)?;
    let single = match shape.as_slice() {
        [3, 3] => true,
        [_, 3, 3] => false,
        _ => {
            return Err(value_error(format!(
                "{name}: expected a 3 x 3 matrix or a (K, 3, 3) stack, got shape {}",
                shape_text(&shape)
            )))
        }
    };
    let stack = values
        .chunks_exact(9)
        .map(Matrix3::from_row_slice)
        .collect();
    Ok((stack, single))
}

/// A finite (N, M) matrix as its row-major values and its shape.
pub fn matrix(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<(Vec<f64>, usize, usize)> {
    let (shape, values) = finite_floats(obj, name)?;
    match shape.as_slice() {
        &[n, m] => Ok((values, n, m)),
        _ => Err(value_error(format!(
            "{name}: expected a 2-D (N, M) array, got shape {}",
            shape_text(&shape)
        ))),
    }
}

/// A 1-D array of integer labels that fit in `i32`.
pub fn labels(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<Vec<i32>> {
    let np = obj.py().import("numpy")?;
    let raw = np.call_method1("asarray", (obj,))?;
    let kind: String = raw.getattr("dtype")?.getattr("kind")?.extract()?;
    if !matches!(kind.as_str(), "i" | "u" | "b") {
        let dtype = raw.getattr("dtype")?.str()?.to_string();
        return Err(value_error(format!(
            "{name}: labels must be integers, got dtype {dtype}"
        )));
    }
    let array = asarray(&raw, name, "int64")?.cast_into::<PyArrayDyn<i64>>()?;
    let view = array.readonly();
    let view = view.as_array();
    if view.ndim() != 1 {
        return Err(value_error(format!(
            "{name}: expected a 1-D array of labels, got shape {}",
            shape_text(view.shape())
        )));
    }
    view.iter()
        .enumerate()
        .map(|(i, &l)| {
            i32::try_from(l)
                .map_err(|_| value_error(format!("{name}[{i}] = {l} does not fit in 32 bits")))
        })
        .collect()
}

/// The image size `(W, H)`: two positive integers.
pub fn image_size(obj: &Bound<'_, PyAny>) -> PyResult<(u32, u32)> {
    let bad = || {
        value_error(format!(
            "image_size: expected (width, height) in pixels, two positive integers, got {}",
            obj.repr().map(|r| r.to_string()).unwrap_or_default()
        ))
    };
    let (w, h): (i64, i64) = obj.extract().map_err(|_| bad())?;
    match (u32::try_from(w), u32::try_from(h)) {
        (Ok(w), Ok(h)) if w > 0 && h > 0 => Ok((w, h)),
        _ => Err(bad()),
    }
}

/// An (x, y) pair of finite numbers.
pub fn pair(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<[f64; 2]> {
    let (shape, values) = finite_floats(obj, name)?;
    if shape != [2] {
        return Err(value_error(format!(
            "{name}: expected two numbers (x, y), got shape {}",
            shape_text(&shape)
        )));
    }
    Ok([values[0], values[1]])
}

/// A 1-D numpy array.
pub fn array1<T: numpy::Element>(py: Python<'_>, values: Vec<T>) -> Bound<'_, PyArray1<T>> {
    Array1::from(values).into_pyarray(py)
}

/// An (N, 2) numpy array of point pairs.
pub fn points_array<'py>(py: Python<'py>, points: &[[f64; 2]]) -> Bound<'py, PyArray2<f64>> {
    let flat: Vec<f64> = points.iter().flatten().copied().collect();
    Array2::from_shape_vec((points.len(), 2), flat)
        .expect("two values per point")
        .into_pyarray(py)
}

/// A 3 × 3 numpy array (row-major, as F is written).
pub fn matrix_array<'py>(py: Python<'py>, m: &Matrix3<f64>) -> Bound<'py, PyArray2<f64>> {
    Array2::from_shape_fn((3, 3), |(i, j)| m[(i, j)]).into_pyarray(py)
}

/// A (K, 3, 3) numpy array.
pub fn matrices_array<'py>(py: Python<'py>, ms: &[Matrix3<f64>]) -> Bound<'py, PyArray3<f64>> {
    Array3::from_shape_fn((ms.len(), 3, 3), |(k, i, j)| ms[k][(i, j)]).into_pyarray(py)
}

/// A Python value (None, bool, int, float, str, sequence, mapping, numpy
/// array or scalar) as a JSON value; `key` names it in errors. NaN and
/// infinities have no JSON form and are refused here.
pub fn to_json(obj: &Bound<'_, PyAny>, key: &str) -> PyResult<serde_json::Value> {
    use serde_json::Value;
    if obj.is_none() {
        return Ok(Value::Null);
    }
    if obj.is_instance_of::<PyBool>() {
        return Ok(Value::Bool(obj.extract()?));
    }
    if obj.is_instance_of::<PyInt>() {
        if let Ok(v) = obj.extract::<i64>() {
            return Ok(Value::from(v));
        }
        return obj
            .extract::<u64>()
            .map(Value::from)
            .map_err(|_| value_error(format!("`{key}`: integer {obj} is out of range")));
    }
    if obj.is_instance_of::<PyFloat>() {
        let v: f64 = obj.extract()?;
        return serde_json::Number::from_f64(v)
            .map(Value::Number)
            .ok_or_else(|| value_error(format!("`{key}`: must be a finite number, got {v}")));
    }
    if obj.is_instance_of::<PyString>() {
        return Ok(Value::String(obj.extract()?));
    }
    if let Ok(dict) = obj.cast::<PyDict>() {
        let mut map = serde_json::Map::new();
        for (k, v) in dict.iter() {
            let k: String = k
                .extract()
                .map_err(|_| value_error(format!("`{key}`: mapping keys must be strings")))?;
            let value = to_json(&v, &format!("{key}.{k}"))?;
            map.insert(k, value);
        }
        return Ok(Value::Object(map));
    }
    if obj.is_instance_of::<PyList>() || obj.is_instance_of::<PyTuple>() {
        let items = obj
            .try_iter()?
            .enumerate()
            .map(|(i, item)| to_json(&item?, &format!("{key}[{i}]")))
            .collect::<PyResult<Vec<_>>>()?;
        return Ok(Value::Array(items));
    }
    // numpy arrays and scalars: their Python equivalents.
    if obj.hasattr("tolist")? {
        return to_json(&obj.call_method0("tolist")?, key);
    }
    Err(value_error(format!(
        "`{key}`: unsupported value of type {}",
        obj.get_type().name()?
    )))
}

/// A serde value as a Python object (through the `json` module: JSON maps
/// onto dict, list, str, int, float, bool and None).
pub fn from_json<'py>(
    py: Python<'py>,
    value: &impl serde::Serialize,
) -> PyResult<Bound<'py, PyAny>> {
    let text = serde_json::to_string(value).map_err(|e| value_error(e.to_string()))?;
    py.import("json")?.call_method1("loads", (text,))
}
