//! Keyword options: Python values as the JSON of the API's `options`, and the caps of this edge.

use std::sync::OnceLock;

use ikarus::number::Num;
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyString};
use serde_json::{Map, Value};

use crate::edge::{self, Limits};

/// The caps this edge holds requests to. A Python session is local, as the command line is, so
/// the caps are the library's and the command line's, not the server's (which exist to keep a
/// shared server answering).
pub(crate) fn limits() -> &'static Limits {
    static LIMITS: OnceLock<Limits> = OnceLock::new();
    LIMITS.get_or_init(|| Limits {
        max_body_bytes: 1 << 30,
        max_links: 100_000,
        max_bones: edge::DEFAULT_MAX_BONES,
        max_iterations: u32::MAX,
        max_frames: 100_000,
        max_samples: 1_000_000,
        max_resolution: 4096,
        max_restarts: 10_000,
        ..Limits::default()
    })
}

/// One Python value of a keyword option as JSON, for `edge::solve_options` and the API's requests.
/// JSON has no NaN or infinity, so a non-finite number is refused here, naming the field.
pub(crate) fn to_json(field: &str, v: &Bound<'_, PyAny>) -> PyResult<Value> {
    if v.is_none() {
        return Ok(Value::Null);
    }
    if let Ok(b) = v.cast::<PyBool>() {
        return Ok(Value::Bool(b.is_true()));
    }
    if v.is_instance_of::<PyInt>() {
        if let Ok(i) = v.extract::<i64>() {
            return Ok(Value::from(i));
        }
        if let Ok(u) = v.extract::<u64>() {
            return Ok(Value::from(u));
        }
        return Err(PyValueError::new_err(format!("{field} = {v}: out of range")));
    }
    if v.is_instance_of::<PyString>() {
        return Ok(Value::String(v.extract()?));
    }
    if v.is_instance_of::<PyFloat>() || v.hasattr("__float__")? && !v.hasattr("__len__")? {
        let x: f64 = v.extract()?;
        if !x.is_finite() {
            return Err(PyValueError::new_err(format!("{field} = {}: must be a finite number", Num(x))));
        }
        return Ok(Value::from(x));
    }
    if let Ok(d) = v.cast::<PyDict>() {
        let mut map = Map::new();
        for (k, item) in d.iter() {
            let key: String = k.extract().map_err(|_| PyTypeError::new_err(format!("{field}: keys must be str")))?;
            let value = to_json(&format!("{field}.{key}"), &item)?;
            if !value.is_null() {
                map.insert(key, value);
            }
        }
        return Ok(Value::Object(map));
    }
    if v.hasattr("__len__")? && v.hasattr("__getitem__")? {
        let mut out = Vec::new();
        for (i, item) in v.try_iter()?.enumerate() {
            out.push(to_json(&format!("{field}[{i}]"), &item?)?);
        }
        return Ok(Value::Array(out));
    }
    Err(PyTypeError::new_err(format!("{field}: cannot use a {} here", v.get_type().name()?)))
}

/// Keyword options as the JSON object of the CLI's names. `lambda` is a Python keyword, so
/// `lambda_` stands for it; `None` means the default (the key is left out).
pub(crate) fn options_json(kwargs: Option<&Bound<'_, PyDict>>) -> PyResult<String> {
    let mut map = Map::new();
    if let Some(kwargs) = kwargs {
        for (k, v) in kwargs.iter() {
            let key: String = k.extract()?;
            let key = if key == "lambda_" { "lambda".to_owned() } else { key };
            let value = to_json(&key, &v)?;
            if !value.is_null() {
                map.insert(key, value);
            }
        }
    }
    Ok(Value::Object(map).to_string())
}
