//! Keyword arguments to the crates' serde parameter types: every key checked,
//! every error a `ValueError` naming the key.

use crate::convert::{to_json, value_error};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use segmentation::{Params, Profile, PARAM_KEYS};
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

/// The profile named by the keyword `profile` (absent or `None`:
/// `default`); anything else is a `ValueError` naming `profile` and the
/// profiles.
pub fn profile_from(value: Option<&Bound<'_, PyAny>>) -> PyResult<Profile> {
    let Some(value) = value.filter(|v| !v.is_none()) else {
        return Ok(Profile::Default);
    };
    let name = value.extract::<String>().map_err(|_| {
        value_error(format!(
            "invalid value for `profile`: {value}; the profiles are: {}",
            Profile::names()
        ))
    })?;
    Profile::from_name(&name).ok_or_else(|| {
        value_error(format!(
            "invalid value for `profile`: {}",
            Profile::unknown(&name)
        ))
    })
}

/// [`Params`] from keyword arguments named as its fields (a missing key
/// takes the value of `profile`, [`Profile::params`]), checked by
/// [`Params::validate`].
pub fn params_from_kwargs(
    kwargs: Option<&Bound<'_, PyDict>>,
    profile: Profile,
) -> PyResult<Params> {
    let Value::Object(mut object) =
        serde_json::to_value(profile.params()).map_err(|e| value_error(e.to_string()))?
    else {
        return Err(value_error(
            "the profile's parameters are not a JSON object",
        ));
    };
    object.extend(kwargs_object(kwargs, &PARAM_KEYS)?);
    let params: Params = from_object(object)?;
    params.validate().map_err(|e| value_error(e.to_string()))?;
    Ok(params)
}

/// The parameters of `segment` on `profile` ("default" or "thesis";
/// default "default"), as a dict.
#[pyfunction]
#[pyo3(signature = (profile=None), text_signature = "(profile=\"default\")")]
pub fn default_params<'py>(
    py: Python<'py>,
    profile: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyAny>> {
    crate::convert::from_json(py, &profile_from(profile)?.params())
}
