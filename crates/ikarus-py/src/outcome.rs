//! `Outcome`: the result of a solve, a chain's or a rig's, its fields those of
//! `ikarus solve --format json`; `Effector`: one goal or pin of it.

use std::sync::Arc;

use ikarus::kinematics::joint_positions;
use ikarus::{Goal, LimitMode, Outcome, SolveOptions, Status};
use numpy::{PyArray1, PyArray2, PyArray3, PyArrayMethods};
use pyo3::exceptions::{PyAttributeError, PyKeyError, PyRuntimeError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyFloat, PyList, PyString, PyTuple};
use serde_json::Value;

use crate::api::{body_call, svg};
use crate::arm::ChainData;
use crate::batch::STATUS_OF_CODE;
use crate::edge;

/// Joint positions as float64 [k, 2].
pub(crate) fn points_array<'py>(py: Python<'py>, points: &[ikarus::Point2<f64>]) -> Bound<'py, PyArray2<f64>> {
    let flat: Vec<f64> = points.iter().flat_map(|p| [p.x, p.y]).collect();
    PyArray1::from_vec(py, flat).reshape([points.len(), 2]).expect("k × 2 values")
}

/// Pairs `[x, y]` as float64 [k, 2].
fn pairs_array<'py>(py: Python<'py>, pairs: &[[f64; 2]]) -> Bound<'py, PyArray2<f64>> {
    PyArray1::from_vec(py, pairs.concat()).reshape([pairs.len(), 2]).expect("k × 2 values")
}

/// One effector of a solve: a goal on a tip (or a pin holding one), how close the tip came.
/// A chain's solve has one, named ``"tip"``; a rig's lists its goals in order, then its pins.
/// Made by the solves (``Outcome.effectors``); the fields are those of the JSON's ``effectors``
/// (``ikarus solve --rig --format json``).
#[pyclass(frozen, get_all, eq, module = "ikarus._ikarus", name = "Effector")]
#[derive(Clone, PartialEq)]
pub(crate) struct PyEffector {
    /// The bone whose tip it moves (``"tip"`` for a chain's last link).
    name: String,
    /// Whether it is a pin (the tip held where it started) rather than a goal.
    pinned: bool,
    /// ``"reached"``, … as the solve's ``status``, for this effector alone.
    status: String,
    /// Distance from the tip to its target.
    error: f64,
    /// Orientation error in degrees (0 without a direction).
    angle_error_deg: f64,
    /// Where the tip ended, ``(x, y)``.
    tip: (f64, f64),
    /// Where it was asked to be, ``(x, y)``.
    target: (f64, f64),
}

#[pymethods]
impl PyEffector {
    fn __repr__(&self, py: Python<'_>) -> PyResult<String> {
        // Python's reprs of the values (quotes, exponents), as a dataclass's repr shows them.
        let r = |v: Bound<'_, PyAny>| -> PyResult<String> { Ok(v.repr()?.to_string()) };
        let pair = |(x, y): (f64, f64)| -> PyResult<String> { r((x, y).into_pyobject(py)?.into_any()) };
        Ok(format!(
            "Effector(name={}, pinned={}, status={}, error={}, angle_error_deg={}, tip={}, target={})",
            r(PyString::new(py, &self.name).into_any())?,
            if self.pinned { "True" } else { "False" },
            r(PyString::new(py, &self.status).into_any())?,
            r(PyFloat::new(py, self.error).into_any())?,
            r(PyFloat::new(py, self.angle_error_deg).into_any())?,
            pair(self.tip)?,
            pair(self.target)?,
        ))
    }
}

/// A chain's solve: the library's outcome, read as the arrays are asked for.
pub(crate) struct ChainSolved {
    pub(crate) outcome: Outcome,
    pub(crate) goal: Goal,
    pub(crate) chain: Arc<ChainData>,
    pub(crate) options: Arc<SolveOptions>,
}

impl Drop for ChainSolved {
    /// Gives the outcome's buffers back to the chain, for its next solve.
    fn drop(&mut self) {
        self.chain.recycle(std::mem::take(&mut self.outcome));
    }
}

/// A rig's solve: the API's answer (`POST /api/solve` with `rig`), read once into typed fields.
pub(crate) struct RigSolved {
    /// The answer's JSON text, for `to_dict`.
    answer: String,
    status: Status,
    iterations: u32,
    restarts: u32,
    error: f64,
    angle_error_deg: f64,
    effectors: Vec<PyEffector>,
    /// Each bone's angle in the rig's order, degrees.
    angles_deg: Vec<f64>,
    /// The base, then each bone's tip in the rig's order.
    joints: Vec<[f64; 2]>,
    /// Each prismatic bone's displacement, in the rig's order (empty without prismatic joints).
    extensions: Vec<(String, f64)>,
    frames: Vec<Frame>,
    /// The picture's request: the rig, its goals and pins.
    picture: Value,
}

/// A recorded frame of a rig's solve: as a chain's, the angles in bone order, then the base and
/// every bone's tip.
struct Frame {
    iteration: u32,
    angles_deg: Vec<f64>,
    joints: Vec<[f64; 2]>,
}

/// A chain's or a rig's solve.
pub(crate) enum Solved {
    Chain(ChainSolved),
    Rig(RigSolved),
}

/// A field of the API's answer that is not what it should be: the facade broke its promise.
fn broken(field: &str) -> PyErr {
    PyRuntimeError::new_err(format!("solve answer: {field}: missing or of the wrong type"))
}

fn f64_of(v: &Value, field: &str) -> PyResult<f64> {
    v.get(field).and_then(Value::as_f64).ok_or_else(|| broken(field))
}

fn u32_of(v: &Value, field: &str) -> PyResult<u32> {
    v.get(field).and_then(Value::as_u64).and_then(|n| u32::try_from(n).ok()).ok_or_else(|| broken(field))
}

fn str_of<'a>(v: &'a Value, field: &str) -> PyResult<&'a str> {
    v.get(field).and_then(Value::as_str).ok_or_else(|| broken(field))
}

fn pair_of(v: &Value, field: &str) -> PyResult<[f64; 2]> {
    match v.as_array().map(|a| a.as_slice()) {
        Some([x, y]) => Ok([x.as_f64().ok_or_else(|| broken(field))?, y.as_f64().ok_or_else(|| broken(field))?]),
        _ => Err(broken(field)),
    }
}

fn status_of(name: &str) -> PyResult<Status> {
    STATUS_OF_CODE.iter().copied().find(|s| edge::status_name(*s) == name).ok_or_else(|| broken("status"))
}

impl RigSolved {
    /// Posts `request` (a rig solve's JSON) to the API and reads its answer.
    fn solve(py: Python<'_>, request: &str) -> PyResult<Self> {
        let bytes = body_call(py, "solve", request.as_bytes())?;
        let answer = String::from_utf8(bytes).map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
        let a: Value = serde_json::from_str(&answer).map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
        // The API took the request, so it is a rig with named bones.
        let req: Value = serde_json::from_str(request).map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
        let rig = req.get("rig").cloned().unwrap_or(Value::Null);
        let names: Vec<&str> = rig
            .get("bones")
            .and_then(Value::as_array)
            .map(|bones| bones.iter().filter_map(|b| b.get("name").and_then(Value::as_str)).collect())
            .unwrap_or_default();
        let base = match rig.get("base") {
            Some(b) => pair_of(b, "rig.base")?,
            None => [0.0, 0.0],
        };
        let by_name = |field: &str| a.get(field).and_then(Value::as_object).ok_or_else(|| broken(field));
        let (angles, tips) = (by_name("angles_deg")?, by_name("joints")?);
        let mut angles_deg = Vec::with_capacity(names.len());
        let mut joints = vec![base];
        for name in &names {
            angles_deg.push(angles.get(*name).and_then(Value::as_f64).ok_or_else(|| broken("angles_deg"))?);
            joints.push(pair_of(tips.get(*name).ok_or_else(|| broken("joints"))?, "joints")?);
        }
        // Only a rig with prismatic joints says `extensions`.
        let extensions = match a.get("extensions") {
            None => Vec::new(),
            Some(e) => {
                let e = e.as_object().ok_or_else(|| broken("extensions"))?;
                let value = |v: &Value| v.as_f64().ok_or_else(|| broken("extensions"));
                names
                    .iter()
                    .filter_map(|n| e.get(*n).map(|v| Ok(((*n).to_owned(), value(v)?))))
                    .collect::<PyResult<_>>()?
            }
        };
        let list = |field: &str| a.get(field).and_then(Value::as_array).ok_or_else(|| broken(field));
        let effectors = list("effectors")?.iter().map(effector_of).collect::<PyResult<_>>()?;
        let frames = list("frames")?
            .iter()
            .map(|f| {
                let numbers = f.get("angles_deg").and_then(Value::as_array).ok_or_else(|| broken("frames"))?;
                let points = f.get("joints").and_then(Value::as_array).ok_or_else(|| broken("frames"))?;
                Ok(Frame {
                    iteration: u32_of(f, "iteration")?,
                    angles_deg: numbers
                        .iter()
                        .map(|x| x.as_f64().ok_or_else(|| broken("frames")))
                        .collect::<PyResult<_>>()?,
                    joints: points.iter().map(|p| pair_of(p, "frames")).collect::<PyResult<_>>()?,
                })
            })
            .collect::<PyResult<_>>()?;
        let picture = serde_json::json!({
            "rig": rig,
            "goals": req.get("goals").cloned().unwrap_or(Value::Null),
            "pins": req.get("pins").cloned().unwrap_or(Value::Null),
        });
        Ok(Self {
            status: status_of(str_of(&a, "status")?)?,
            iterations: u32_of(&a, "iterations")?,
            restarts: u32_of(&a, "restarts")?,
            error: f64_of(&a, "error")?,
            angle_error_deg: f64_of(&a, "angle_error_deg")?,
            effectors,
            angles_deg,
            joints,
            extensions,
            frames,
            picture,
            answer,
        })
    }
}

/// One of the answer's `effectors`.
pub(crate) fn effector_of(e: &Value) -> PyResult<PyEffector> {
    let [tx, ty] = pair_of(e.get("tip").unwrap_or(&Value::Null), "effectors.tip")?;
    let [gx, gy] = pair_of(e.get("target").unwrap_or(&Value::Null), "effectors.target")?;
    Ok(PyEffector {
        name: str_of(e, "name")?.to_owned(),
        pinned: e.get("pinned").and_then(Value::as_bool).ok_or_else(|| broken("effectors.pinned"))?,
        status: str_of(e, "status")?.to_owned(),
        error: f64_of(e, "error")?,
        angle_error_deg: f64_of(e, "angle_error_deg")?,
        tip: (tx, ty),
        target: (gx, gy),
    })
}

/// The result of a solve, of :meth:`Chain.solve` or :meth:`Rig.solve`: the same fields for
/// both, equal to those of ``ikarus solve --format json`` (``--rig`` for a rig) for the same
/// inputs, degrees as there, bit for bit; arrays are made when first read. ``end_effector`` and
/// ``goal`` are a chain's alone (a rig has one tip per effector: ``effectors``).
#[pyclass(frozen, module = "ikarus._ikarus", name = "Outcome")]
pub(crate) struct PyOutcome {
    pub(crate) solved: Solved,
}

impl PyOutcome {
    fn chain_only(&self, field: &str) -> PyResult<&ChainSolved> {
        match &self.solved {
            Solved::Chain(c) => Ok(c),
            Solved::Rig(_) => Err(PyAttributeError::new_err(format!(
                "{field}: a chain's alone; a rig's solve has one tip and target per effector (Outcome.effectors)"
            ))),
        }
    }

    fn angles_deg_vec(&self) -> Vec<f64> {
        match &self.solved {
            Solved::Chain(c) => c.outcome.pose.angles().iter().map(|a| a.to_degrees()).collect(),
            Solved::Rig(r) => r.angles_deg.clone(),
        }
    }
}

/// ``_solve_rig(request)``: a rig's solve by the API (``POST /api/solve``; the request's JSON
/// text, with ``rig``), as an :class:`Outcome`.
#[pyfunction]
pub(crate) fn _solve_rig(py: Python<'_>, request: &str) -> PyResult<PyOutcome> {
    Ok(PyOutcome { solved: Solved::Rig(RigSolved::solve(py, request)?) })
}

#[pymethods]
impl PyOutcome {
    /// Why the solve ended: ``"reached"``, ``"unreachable"``, ``"stalled"``, ``"iteration_limit"``
    /// (a rig's is ``"reached"`` only when every effector is).
    #[getter]
    fn status(&self) -> &'static str {
        edge::status_name(match &self.solved {
            Solved::Chain(c) => c.outcome.status,
            Solved::Rig(r) => r.status,
        })
    }

    /// Whether the goal was reached (``status == "reached"``).
    #[getter]
    fn reached(&self) -> bool {
        self.status() == edge::status_name(Status::Reached)
    }

    /// Steps taken, over every attempt.
    #[getter]
    fn iterations(&self) -> u32 {
        match &self.solved {
            Solved::Chain(c) => c.outcome.iterations,
            Solved::Rig(r) => r.iterations,
        }
    }

    /// Restarts used (0 when the first attempt ended the solve).
    #[getter]
    fn restarts(&self) -> u32 {
        match &self.solved {
            Solved::Chain(c) => c.outcome.restarts,
            Solved::Rig(r) => r.restarts,
        }
    }

    /// Distance from the tip to the goal position (a rig's: the largest over its effectors).
    #[getter]
    fn error(&self) -> f64 {
        match &self.solved {
            Solved::Chain(c) => c.outcome.error,
            Solved::Rig(r) => r.error,
        }
    }

    /// Orientation error in degrees (0 without an orientation goal; a rig's: the largest).
    #[getter]
    fn angle_error_deg(&self) -> f64 {
        match &self.solved {
            Solved::Chain(c) => c.outcome.angle_error.to_degrees(),
            Solved::Rig(r) => r.angle_error_deg,
        }
    }

    /// With limits on, for a chain: the goal's distance from the exact reachable region (0
    /// inside); else None (always None for a rig, whose region is not computed).
    #[getter]
    fn reach_distance(&self) -> Option<f64> {
        match &self.solved {
            Solved::Chain(c) => c.outcome.reach_distance,
            Solved::Rig(_) => None,
        }
    }

    /// The solution's joint angles in degrees (a rig's in its bones' order), float64 [n].
    #[getter]
    fn angles_deg<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_vec(py, self.angles_deg_vec())
    }

    /// Each prismatic joint's displacement (length units), by bone name in the rig's order, as
    /// the JSON's ``extensions``: empty for a chain or a rig whose joints all turn.
    #[getter]
    fn extensions<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        if let Solved::Rig(r) = &self.solved {
            for (name, value) in &r.extensions {
                d.set_item(name, value)?;
            }
        }
        Ok(d)
    }

    /// Joint positions of the solution: the base, then each link's (bone's) tip: float64 [n+1, 2].
    #[getter]
    fn joints<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        match &self.solved {
            Solved::Chain(c) => points_array(py, &joint_positions(c.chain.arm.chain(), c.outcome.pose.angles())),
            Solved::Rig(r) => pairs_array(py, &r.joints),
        }
    }

    /// Each goal (then each pin), how close its tip came: a tuple of :class:`Effector`. A
    /// chain's has one, ``"tip"``.
    #[getter]
    fn effectors<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        match &self.solved {
            Solved::Chain(c) => {
                let (ex, ey, _) = self.end_effector()?;
                let t = c.goal.target();
                let tip = PyEffector {
                    name: "tip".to_owned(),
                    pinned: false,
                    status: self.status().to_owned(),
                    error: c.outcome.error,
                    angle_error_deg: self.angle_error_deg(),
                    tip: (ex, ey),
                    target: (t.x, t.y),
                };
                PyTuple::new(py, [tip])
            }
            Solved::Rig(r) => PyTuple::new(py, r.effectors.iter().cloned()),
        }
    }

    /// A chain's tip ``(x, y, angle_deg)`` (a rig's tips are in ``effectors``).
    #[getter]
    fn end_effector(&self) -> PyResult<(f64, f64, f64)> {
        let e = &self.chain_only("end_effector")?.outcome.end_effector;
        Ok((e.position.x, e.position.y, e.orientation.to_degrees()))
    }

    /// Recorded poses (every ``record_every`` iterations, 20 by default for a chain and off for
    /// a rig, plus the first and the last), in degrees: float64 [k, n].
    #[getter]
    fn frames<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let (k, n, flat): (usize, usize, Vec<f64>) = match &self.solved {
            Solved::Chain(c) => (
                c.outcome.frames.len(),
                c.chain.arm.chain().len(),
                c.outcome.frames.iter().flat_map(|f| f.angles.iter().map(|a| a.to_degrees())).collect(),
            ),
            Solved::Rig(r) => (
                r.frames.len(),
                r.angles_deg.len(),
                r.frames.iter().flat_map(|f| f.angles_deg.iter().copied()).collect(),
            ),
        };
        PyArray1::from_vec(py, flat).reshape([k, n])
    }

    /// The iteration of each recorded frame: uint32 [k].
    #[getter]
    fn frame_iterations<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<u32>> {
        let iterations = match &self.solved {
            Solved::Chain(c) => c.outcome.frames.iter().map(|f| f.iteration).collect(),
            Solved::Rig(r) => r.frames.iter().map(|f| f.iteration).collect(),
        };
        PyArray1::from_vec(py, iterations)
    }

    /// Joint positions of each recorded frame: float64 [k, n+1, 2].
    #[getter]
    fn frame_joints<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray3<f64>>> {
        let (k, n, flat): (usize, usize, Vec<f64>) = match &self.solved {
            Solved::Chain(c) => (
                c.outcome.frames.len(),
                c.chain.arm.chain().len(),
                c.outcome.frames.iter().flat_map(|f| f.joints.iter().flat_map(|p| [p.x, p.y])).collect(),
            ),
            Solved::Rig(r) => {
                (r.frames.len(), r.angles_deg.len(), r.frames.iter().flat_map(|f| f.joints.concat()).collect())
            }
        };
        PyArray1::from_vec(py, flat).reshape([k, n + 1, 2])
    }

    /// A chain's goal ``(x, y, angle_deg or None)`` as solved (the angle wrapped into
    /// (−180°, 180°]); a rig's targets are in ``effectors``.
    #[getter]
    fn goal(&self) -> PyResult<(f64, f64, Option<f64>)> {
        let goal = &self.chain_only("goal")?.goal;
        let t = goal.target();
        Ok((t.x, t.y, goal.orientation().map(f64::to_degrees)))
    }

    /// The fields of ``ikarus solve --format json`` (all but ``solve_us``), as Python values.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let c = match &self.solved {
            Solved::Chain(c) => c,
            Solved::Rig(r) => {
                let d = py.import("json")?.call_method1("loads", (&r.answer,))?.cast_into::<PyDict>()?;
                d.del_item("solve_us")?;
                return Ok(d);
            }
        };
        let d = PyDict::new(py);
        let o = &c.outcome;
        let (x, y, a) = self.goal()?;
        d.set_item("arm", &c.chain.name)?;
        d.set_item("method", c.options.method.name())?;
        d.set_item("limits", c.options.limits != LimitMode::Ignore)?;
        d.set_item("limit_mode", c.options.limits.name())?;
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
        d.set_item("tolerance", c.options.tolerance)?;
        d.set_item("reach_distance", o.reach_distance)?;
        let (ex, ey, ea) = self.end_effector()?;
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

    /// ``outcome[key]``: the field ``key`` of :meth:`to_dict`, the JSON's (as a rig's solve
    /// answered before it was typed; the attributes are the typed way).
    fn __getitem__<'py>(&self, py: Python<'py>, key: &str) -> PyResult<Bound<'py, PyAny>> {
        self.to_dict(py)?.get_item(key)?.ok_or_else(|| PyKeyError::new_err(key.to_owned()))
    }

    fn __repr__(&self) -> String {
        let angles: Vec<String> = self.angles_deg_vec().iter().map(|a| format!("{a:.3}")).collect();
        format!(
            "<ikarus.Outcome {} after {} iterations, {} restarts, error {:e}, angles_deg [{}]>",
            self.status(),
            self.iterations(),
            self.restarts(),
            self.error(),
            angles.join(", ")
        )
    }

    /// The solved pose with its goals, drawn by ikarus's renderer (SVG).
    fn _repr_svg_(&self, py: Python<'_>) -> PyResult<String> {
        let pose = self.angles_deg_vec();
        let body = match &self.solved {
            Solved::Chain(c) => {
                let t = c.goal.target();
                serde_json::json!({
                    "figure": "arm", "format": "svg", "width": 480, "height": 480,
                    "arm": c.chain.arm_json, "pose_deg": pose, "goal": {"x": t.x, "y": t.y},
                })
            }
            Solved::Rig(r) => {
                let mut body = serde_json::json!({
                    "figure": "rig", "format": "svg", "width": 480, "height": 480, "pose_deg": pose,
                });
                if let (Value::Object(body), Value::Object(picture)) = (&mut body, &r.picture) {
                    body.extend(picture.iter().filter(|(_, v)| !v.is_null()).map(|(k, v)| (k.clone(), v.clone())));
                }
                body
            }
        };
        svg(py, &body)
    }
}
