//! `ease`: the ease curves of `ikarus animate --ease`, on floats and NumPy arrays.

use ikarus::EaseKind;
use ikarus::names::Named;
use ikarus::number::Num;
use numpy::PyArray1;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyFloat, PyInt};

/// ``ease(kind, t, k1=None, k2=None, velocity=False)``: an ease curve's position s(t) (or its
/// velocity) at ``t`` in [0, 1], a float or a NumPy array (the result has its shape).
///
/// ``kind`` is ``"linear"``, ``"sine"``, ``"parent"`` or ``"smoothstep"``; ``k1`` and ``k2``
/// are Parent's phases (0.3 and 0.7 by default) and belong to Parent's ease alone, as in
/// ``ikarus animate --ease parent --k1 0.3 --k2 0.7``.
#[pyfunction]
#[pyo3(signature = (kind, t, k1=None, k2=None, velocity=false))]
pub(crate) fn ease<'py>(
    py: Python<'py>,
    kind: &str,
    t: &Bound<'py, PyAny>,
    k1: Option<f64>,
    k2: Option<f64>,
    velocity: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let kind = EaseKind::parse_name(kind).map_err(|e| PyValueError::new_err(e.to_string()))?;
    if kind != EaseKind::Parent && (k1.is_some() || k2.is_some()) {
        let which = if k1.is_some() { "k1" } else { "k2" };
        return Err(PyValueError::new_err(format!("{which}: only the parent ease has phases, not {}", kind.name())));
    }
    let curve = kind.ease(k1, k2).map_err(|e| PyValueError::new_err(e.to_string()))?;
    let f = |x: f64| -> PyResult<f64> {
        if !(0.0..=1.0).contains(&x) {
            return Err(PyValueError::new_err(format!("t = {}: must be a number in [0, 1]", Num(x))));
        }
        Ok(if velocity { curve.velocity(x) } else { curve.position(x) })
    };
    if t.is_instance_of::<PyFloat>() || t.is_instance_of::<PyInt>() {
        return Ok(PyFloat::new(py, f(t.extract()?)?).into_any());
    }
    let np = py.import("numpy")?;
    let arr = np.call_method1("asarray", (t, "float64"))?;
    let shape = arr.getattr("shape")?;
    let flat: Vec<f64> = arr.call_method0("ravel")?.extract()?;
    let out: Vec<f64> = flat.into_iter().map(f).collect::<PyResult<_>>()?;
    PyArray1::from_vec(py, out).call_method1("reshape", (shape,))
}
