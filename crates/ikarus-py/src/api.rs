//! The API without HTTP: requests answered by the facade's `edge::call`, as `ikarus serve`.

use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use serde_json::Value;

use crate::edge::{self, Endpoint, Problem};
use crate::errors::{problem, request_problem};
use crate::options::limits;
use crate::signals::interruptible;

pub(crate) fn svg(py: Python<'_>, body: &Value) -> PyResult<String> {
    let bytes = api_call(py, "render", body.to_string().as_bytes())?;
    String::from_utf8(bytes).map_err(|e| PyRuntimeError::new_err(e.to_string()))
}

/// `POST /api/<endpoint>` with `body`, answered by `edge::call`, or the facade's refusal; Ctrl-C
/// stops it (`signals::interruptible`: the job's token is set and `KeyboardInterrupt` raised).
fn post(py: Python<'_>, endpoint: &str, body: &[u8]) -> PyResult<Result<Vec<u8>, Problem>> {
    let endpoint =
        Endpoint::from_path(endpoint).ok_or_else(|| PyValueError::new_err(format!("unknown endpoint '{endpoint}'")))?;
    let token = ikarus::Interrupt::new();
    Ok(interruptible(py, &token, || edge::call(endpoint, body, limits(), &token))?.map(|r| r.body))
}

/// A request as `ikarus.call` makes it: a refusal is the API's line.
pub(crate) fn api_call(py: Python<'_>, endpoint: &str, body: &[u8]) -> PyResult<Vec<u8>> {
    post(py, endpoint, body)?.map_err(problem)
}

/// A request a body's method makes from its keywords: a refused option is named as the keyword
/// (`errors::request_problem`).
pub(crate) fn body_call(py: Python<'_>, endpoint: &str, body: &[u8]) -> PyResult<Vec<u8>> {
    post(py, endpoint, body)?.map_err(request_problem)
}

/// An API request without HTTP: ``POST /api/<endpoint>`` with a JSON body, answered by the same
/// code as ``ikarus serve`` (``edge::call``); a refusal raises ``ValueError`` with its message
/// (with ``keywords=True``, a refused option's line names it as a keyword of ``Chain.solve``).
#[pyfunction]
#[pyo3(signature = (endpoint, body, *, keywords=false))]
pub(crate) fn _call(py: Python<'_>, endpoint: &str, body: &str, keywords: bool) -> PyResult<Vec<u8>> {
    if keywords { body_call(py, endpoint, body.as_bytes()) } else { api_call(py, endpoint, body.as_bytes()) }
}
