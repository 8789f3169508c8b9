//! Goals from Python: one `(x, y[, angle_deg])`, or an array of them for a batch.

use ikarus::Goal;
use numpy::PyArray2;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyTuple;

use crate::edge;
use crate::errors::goal_problem;

/// A goal from Python: `(x, y)` or `(x, y, angle_deg)`.
pub(crate) fn goal_of(goal: &Bound<'_, PyAny>) -> PyResult<Goal> {
    // The common case, `(x, y)` or `(x, y, angle_deg)`, read without a vector.
    if let Ok(t) = goal.cast::<PyTuple>() {
        let n = t.len();
        if n == 2 || n == 3 {
            let mut v = [0.0; 3];
            for (i, item) in t.iter().enumerate() {
                v[i] = item.extract::<f64>()?;
            }
            return edge::goal(v[0], v[1], (n == 3).then_some(v[2])).map_err(|p| goal_problem(p, None));
        }
    }
    let values: Vec<f64> = if let Ok(t) = goal.cast::<PyTuple>() {
        t.iter().map(|v| v.extract::<f64>()).collect::<PyResult<_>>()?
    } else {
        goal.extract()
            .map_err(|_| PyValueError::new_err("goal: expected (x, y) or (x, y, angle_deg), numbers".to_owned()))?
    };
    match values[..] {
        [x, y] => edge::goal(x, y, None),
        [x, y, a] => edge::goal(x, y, Some(a)),
        _ => {
            return Err(PyValueError::new_err(format!(
                "goal: expected (x, y) or (x, y, angle_deg), got {} values",
                values.len()
            )));
        }
    }
    .map_err(|p| goal_problem(p, None))
}

/// What `Chain.solve_batch` takes as goals, for its messages.
pub(crate) const GOALS_EXPECTED: &str = "goals: expected an array of numbers of shape (N, 2) or (N, 3)";

/// `goals` as a float64 array of two dimensions: a float64 array as it is; any other array of
/// integers or floats (int64, uint8, float32, …), or nested sequences of numbers, converted as
/// NumPy's `asarray(goals).astype(float64)` does. Anything else (strings, objects, booleans,
/// complex numbers, ragged lists, another number of dimensions) is refused in one line naming
/// its shape and dtype.
pub(crate) fn goals_array<'py>(goals: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyArray2<f64>>> {
    if let Ok(array) = goals.cast::<PyArray2<f64>>() {
        return Ok(array.clone());
    }
    let py = goals.py();
    let kind_of = |what: String| PyValueError::new_err(format!("{GOALS_EXPECTED}, got {what}"));
    let type_name = || goals.get_type().name().map(|n| n.to_string()).unwrap_or_default();
    let raw = py.import("numpy")?.call_method1("asarray", (goals,)).map_err(|_| kind_of(type_name()))?;
    let shape = raw.getattr("shape").map(|s| s.to_string()).unwrap_or_else(|_| type_name());
    let dtype = raw.getattr("dtype")?;
    let kind: String = dtype.getattr("kind")?.extract()?;
    // Signed and unsigned integers and real floats; not booleans ("b"), complex ("c"), strings,
    // objects, dates.
    if !matches!(kind.as_str(), "i" | "u" | "f") {
        return Err(kind_of(format!("{shape} of {dtype}")));
    }
    let converted = raw.call_method1("astype", ("float64",))?;
    converted.cast_into::<PyArray2<f64>>().map_err(|_| kind_of(shape))
}
