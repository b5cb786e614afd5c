//! Keyword arguments to the crates' serde parameter types: every key checked,
//! every error a `ValueError` naming the key.

use crate::convert::{to_json, value_error};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use segmentation::{Params, PARAM_KEYS};
use serde::de::DeserializeOwned;
use serde_json::{Map, Value};

/// Deserialises a JSON object into `T`; a bad value is a `ValueError`
/// naming its key (the path to it: `weight_sets[1][0]`).
pub fn from_object<T: DeserializeOwned>(object: Map<String, Value>) -> PyResult<T> {
    serde_path_to_error::deserialize(Value::Object(object))
        .map_err(|e| value_error(format!("invalid value for `{}`: {}", e.path(), e.inner())))
}

/// The keyword arguments as a JSON object, each key checked against
/// `known` (an unknown key is a `ValueError` listing the known ones).
pub fn kwargs_object(
    kwargs: Option<&Bound<'_, PyDict>>,
    known: &[&str],
) -> PyResult<Map<String, Value>> {
    let mut object = Map::new();
    let Some(kwargs) = kwargs else {
        return Ok(object);
    };
    for (key, value) in kwargs.iter() {
        let key: String = key.extract()?;
        if !known.contains(&key.as_str()) {
            return Err(value_error(format!(
                "unknown parameter `{key}`; the parameters are: {}",
                known.join(", ")
            )));
        }
        let value = to_json(&value, &key)?;
        object.insert(key, value);
    }
    Ok(object)
}

/// [`Params`] from keyword arguments named as its fields (a missing key
/// takes its default), checked by [`Params::validate`].
pub fn params_from_kwargs(kwargs: Option<&Bound<'_, PyDict>>) -> PyResult<Params> {
    let params: Params = from_object(kwargs_object(kwargs, &PARAM_KEYS)?)?;
    params.validate().map_err(|e| value_error(e.to_string()))?;
    Ok(params)
}

/// The default parameters of `segment`, as a dict.
#[pyfunction]
pub fn default_params(py: Python<'_>) -> PyResult<Bound<'_, PyAny>> {
    crate::convert::from_json(py, &Params::default())
}
