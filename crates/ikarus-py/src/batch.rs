//! What `Chain.solve_batch` shares: its worker pools and its statuses as small codes.

use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;

use crate::edge;

/// Where rayon pools of a given size are kept between batches.
pub(crate) fn pool(threads: Option<i64>) -> PyResult<Option<Arc<rayon::ThreadPool>>> {
    let Some(n) = threads else { return Ok(None) };
    if !(1..=4096).contains(&n) {
        return Err(PyValueError::new_err(format!(
            "threads = {n}: must be a whole number from 1 to 4096 (or None: all cores)"
        )));
    }
    static POOLS: OnceLock<Mutex<HashMap<usize, Arc<rayon::ThreadPool>>>> = OnceLock::new();
    let n = n as usize;
    let mut pools =
        POOLS.get_or_init(Default::default).lock().map_err(|_| PyRuntimeError::new_err("thread pools poisoned"))?;
    if let Some(p) = pools.get(&n) {
        return Ok(Some(p.clone()));
    }
    let p = Arc::new(
        rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .map_err(|e| PyRuntimeError::new_err(format!("cannot start {n} threads: {e}")))?,
    );
    pools.insert(n, p.clone());
    Ok(Some(p))
}

/// The statuses' names, as NumPy's fixed-width unicode (`<U15`, the longest being `iteration_limit`).
pub(crate) const STATUS_WIDTH: usize = 15;

pub(crate) fn status_code(s: ikarus::Status) -> u8 {
    match s {
        ikarus::Status::Reached => 0,
        ikarus::Status::Unreachable => 1,
        ikarus::Status::Stalled => 2,
        ikarus::Status::IterationLimit => 3,
        _ => 4,
    }
}

pub(crate) const STATUS_OF_CODE: [ikarus::Status; 5] = [
    ikarus::Status::Reached,
    ikarus::Status::Unreachable,
    ikarus::Status::Stalled,
    ikarus::Status::IterationLimit,
    ikarus::Status::Interrupted,
];

/// The CLI's name of a status (``edge::status_name``), for tests and tools.
#[pyfunction]
pub(crate) fn _status_names() -> Vec<&'static str> {
    STATUS_OF_CODE.iter().map(|s| edge::status_name(*s)).collect()
}
