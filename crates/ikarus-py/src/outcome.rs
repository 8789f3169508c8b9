//! `Outcome`: the result of a solve, its fields those of `ikarus solve --format json`.

use std::sync::Arc;

use ikarus::kinematics::joint_positions;
use ikarus::{Goal, LimitMode, Outcome, SolveOptions};
use numpy::{PyArray1, PyArray2, PyArray3, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use crate::api::svg;
use crate::chain::ChainData;
use crate::edge;

/// Joint positions as float64 [k, 2].
pub(crate) fn points_array<'py>(py: Python<'py>, points: &[ikarus::Point2<f64>]) -> Bound<'py, PyArray2<f64>> {
    let flat: Vec<f64> = points.iter().flat_map(|p| [p.x, p.y]).collect();
    PyArray1::from_vec(py, flat).reshape([points.len(), 2]).expect("k × 2 values")
}

/// The result of :meth:`Chain.solve`. Its fields equal those of ``ikarus solve --format json``
/// for the same inputs (degrees, as there), bit for bit; arrays are made when first read.
#[pyclass(frozen, module = "ikarus._ikarus", name = "Outcome")]
pub(crate) struct PyOutcome {
    pub(crate) outcome: Outcome,
    pub(crate) goal: Goal,
    pub(crate) chain: Arc<ChainData>,
    pub(crate) options: Arc<SolveOptions>,
}

#[pymethods]
impl PyOutcome {
    /// Why the solve ended: ``"reached"``, ``"unreachable"``, ``"stalled"``, ``"iteration_limit"``.
    #[getter]
    fn status(&self) -> &'static str {
        edge::status_name(self.outcome.status)
    }

    /// Whether the goal was reached (``status == "reached"``).
    #[getter]
    fn reached(&self) -> bool {
        self.outcome.status == ikarus::Status::Reached
    }

    /// Steps taken, over every attempt.
    #[getter]
    fn iterations(&self) -> u32 {
        self.outcome.iterations
    }

    /// Restarts used (0 when the first attempt ended the solve).
    #[getter]
    fn restarts(&self) -> u32 {
        self.outcome.restarts
    }

    /// Distance from the tip to the goal position.
    #[getter]
    fn error(&self) -> f64 {
        self.outcome.error
    }

    /// Orientation error in degrees (0 without an orientation goal).
    #[getter]
    fn angle_error_deg(&self) -> f64 {
        self.outcome.angle_error.to_degrees()
    }

    /// With limits on: the goal's distance from the exact reachable region (0 inside); else None.
    #[getter]
    fn reach_distance(&self) -> Option<f64> {
        self.outcome.reach_distance
    }

    /// The solution's joint angles in degrees, float64 [n].
    #[getter]
    fn angles_deg<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_vec(py, self.outcome.pose.angles().iter().map(|a| a.to_degrees()).collect())
    }

    /// Joint positions of the solution, base first, tip last: float64 [n+1, 2].
    #[getter]
    fn joints<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        points_array(py, &joint_positions(self.chain.arm.chain(), self.outcome.pose.angles()))
    }

    /// The tip ``(x, y, angle_deg)``.
    #[getter]
    fn end_effector(&self) -> (f64, f64, f64) {
        let e = &self.outcome.end_effector;
        (e.position.x, e.position.y, e.orientation.to_degrees())
    }

    /// Recorded poses (every ``record_every`` iterations, 20 by default, plus the first and the
    /// last), in degrees: float64 [k, n].
    #[getter]
    fn frames<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let n = self.chain.arm.chain().len();
        let flat: Vec<f64> = self.outcome.frames.iter().flat_map(|f| f.angles.iter().map(|a| a.to_degrees())).collect();
        PyArray1::from_vec(py, flat).reshape([self.outcome.frames.len(), n])
    }

    /// The iteration of each recorded frame: uint32 [k].
    #[getter]
    fn frame_iterations<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<u32>> {
        PyArray1::from_vec(py, self.outcome.frames.iter().map(|f| f.iteration).collect())
    }

    /// Joint positions of each recorded frame: float64 [k, n+1, 2].
    #[getter]
    fn frame_joints<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray3<f64>>> {
        let n = self.chain.arm.chain().len();
        let flat: Vec<f64> =
            self.outcome.frames.iter().flat_map(|f| f.joints.iter().flat_map(|p| [p.x, p.y])).collect();
        PyArray1::from_vec(py, flat).reshape([self.outcome.frames.len(), n + 1, 2])
    }

    /// The goal ``(x, y, angle_deg or None)`` as solved (the angle wrapped into (−180°, 180°]).
    #[getter]
    fn goal(&self) -> (f64, f64, Option<f64>) {
        let t = self.goal.target();
        (t.x, t.y, self.goal.orientation().map(f64::to_degrees))
    }

    /// The fields of ``ikarus solve --format json`` (all but ``solve_us``), as Python values.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        let o = &self.outcome;
        let (x, y, a) = self.goal();
        d.set_item("arm", &self.chain.name)?;
        d.set_item("method", self.options.method.name())?;
        d.set_item("limits", self.options.limits != LimitMode::Ignore)?;
        d.set_item("limit_mode", self.options.limits.name())?;
        let goal = PyDict::new(py);
        goal.set_item("x", x)?;
        goal.set_item("y", y)?;
        goal.set_item("angle_deg", a)?;
        d.set_item("goal", goal)?;
        d.set_item("status", self.status())?;
        d.set_item("iterations", o.iterations)?;
        d.set_item("restarts", o.restarts)?;
        d.set_item("error", o.error)?;
        d.set_item("angle_error_deg", self.angle_error_deg())?;
        d.set_item("tolerance", self.options.tolerance)?;
        d.set_item("reach_distance", o.reach_distance)?;
        let (ex, ey, ea) = self.end_effector();
        let tip = PyDict::new(py);
        tip.set_item("x", ex)?;
        tip.set_item("y", ey)?;
        tip.set_item("angle_deg", ea)?;
        d.set_item("end_effector", tip)?;
        d.set_item("angles_deg", self.angles_deg(py))?;
        d.set_item("joints", self.joints(py))?;
        let frames = PyList::empty(py);
        for f in o.frames.iter() {
            let fd = PyDict::new(py);
            fd.set_item("iteration", f.iteration)?;
            fd.set_item("angles_deg", PyArray1::from_vec(py, f.angles.iter().map(|a| a.to_degrees()).collect()))?;
            fd.set_item("joints", points_array(py, f.joints))?;
            frames.append(fd)?;
        }
        d.set_item("frames", frames)?;
        Ok(d)
    }

    fn __repr__(&self) -> String {
        let o = &self.outcome;
        let angles: Vec<String> = o.pose.angles().iter().map(|a| format!("{:.3}", a.to_degrees())).collect();
        format!(
            "<ikarus.Outcome {} after {} iterations, {} restarts, error {:e}, angles_deg [{}]>",
            self.status(),
            o.iterations,
            o.restarts,
            o.error,
            angles.join(", ")
        )
    }

    /// The solved pose with its goal, drawn by ikarus's renderer (SVG).
    fn _repr_svg_(&self, py: Python<'_>) -> PyResult<String> {
        let t = self.goal.target();
        let pose: Vec<f64> = self.outcome.pose.angles().iter().map(|a| a.to_degrees()).collect();
        let body = serde_json::json!({
            "figure": "arm", "format": "svg", "width": 480, "height": 480,
            "arm": self.chain.arm_json, "pose_deg": pose, "goal": {"x": t.x, "y": t.y},
        });
        svg(py, &body)
    }
}
