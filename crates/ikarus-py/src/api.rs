//! The API without HTTP: requests answered by the facade's `edge::call`, as `ikarus serve`.

use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use serde_json::Value;

use crate::edge::{self, Endpoint};
use crate::errors::problem;
use crate::options::limits;

pub(crate) fn svg(py: Python<'_>, body: &Value) -> PyResult<String> {
    let bytes = api_call(py, "render", body.to_string().as_bytes())?;
    String::from_utf8(bytes).map_err(|e| PyRuntimeError::new_err(e.to_string()))
}

pub(crate) fn api_call(py: Python<'_>, endpoint: &str, body: &[u8]) -> PyResult<Vec<u8>> {
    let endpoint =
        Endpoint::from_path(endpoint).ok_or_else(|| PyValueError::new_err(format!("unknown endpoint '{endpoint}'")))?;
    let body = body.to_vec();
    py.detach(move || edge::call(endpoint, &body, limits(), &ikarus::Interrupt::new())).map(|r| r.body).map_err(problem)
}

/// An API request without HTTP: ``POST /api/<endpoint>`` with a JSON body, answered by the same
/// code as ``ikarus serve`` (``edge::call``); a refusal raises ``ValueError`` with its message.
#[pyfunction]
pub(crate) fn _call(py: Python<'_>, endpoint: &str, body: &str) -> PyResult<Vec<u8>> {
    api_call(py, endpoint, body.as_bytes())
}
