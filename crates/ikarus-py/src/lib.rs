//! `ikarus._ikarus`: the Python bindings of ikarus (re-exported by the `ikarus` package).
//!
//! One workflow per job: arms, settings, defaults, messages and JSON answers come from the shared
//! facade `ikarus_edge::edge`, as for the command line and the server. The hot path
//! (`Chain.solve`, `Chain.solve_batch`) uses its typed pieces and `ikarus::Solver` directly; the
//! rest (animate, track, workspace, reach, pictures) posts the API's request to `edge::call` and
//! hands its JSON answer to the Python side (`python/ikarus/__init__.py`), which turns it into
//! Python objects and NumPy arrays. Angles are degrees at this edge, as in the CLI.

use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

use ikarus::kinematics::joint_positions;
use ikarus::names::Named;
use ikarus::number::Num;
use ikarus::{EaseKind, Goal, LimitMode, Outcome, SolveOptions, Solver};
use ikarus_edge::edge::{self, Arm, Endpoint, Limits, Problem};
use numpy::{PyArray1, PyArray2, PyArray3, PyArrayMethods, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::exceptions::{PyRuntimeError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};
use rayon::prelude::*;
use serde_json::{Map, Value};

/// A refused request as Python sees it: a bad value (422) or malformed request (400) is a
/// `ValueError` with the facade's one line; anything else (500) a `RuntimeError`.
fn problem(p: Problem) -> PyErr {
    if (400..500).contains(&p.status) { PyValueError::new_err(p.message) } else { PyRuntimeError::new_err(p.message) }
}

/// A refused option: the facade's line, without what only its JSON form had (an `options: `
/// before a field of a malformed value, the ` at line 1 column N` of the JSON text this edge
/// made from the keywords), so that it names the keyword and the value.
fn option_problem(p: Problem) -> PyErr {
    let mut message = p.message.strip_prefix("options: ").unwrap_or(&p.message).to_owned();
    if let Some(at) = message.rfind(" at line ") {
        let tail = &message[at + " at line ".len()..];
        let mut parts = tail.split(" column ");
        let digits = |s: Option<&str>| s.is_some_and(|s| !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit()));
        if digits(parts.next()) && digits(parts.next()) && parts.next().is_none() {
            message.truncate(at);
        }
    }
    problem(Problem { message, ..p })
}

/// A refused goal: the facade's line (`goal: goal.y: must be a finite number, got NaN`) with
/// the field once (`goal.y: …`), or for row `row` of a batch, `goals[row].y: …`.
fn goal_problem(p: Problem, row: Option<usize>) -> PyErr {
    let detail = p.message.strip_prefix("goal: ").unwrap_or(&p.message);
    let detail = if detail.starts_with("goal.") || detail.starts_with("goal:") { detail } else { &p.message };
    let message = match row {
        None => detail.to_owned(),
        Some(i) => match detail.strip_prefix("goal") {
            Some(rest) => format!("goals[{i}]{rest}"),
            None => format!("goals[{i}]: {detail}"),
        },
    };
    problem(Problem { message, ..p })
}

/// The caps this edge holds requests to. A Python session is local, as the command line is, so
/// the caps are the library's and the command line's, not the server's (which exist to keep a
/// shared server answering).
fn limits() -> &'static Limits {
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
fn to_json(field: &str, v: &Bound<'_, PyAny>) -> PyResult<Value> {
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
fn options_json(kwargs: Option<&Bound<'_, PyDict>>) -> PyResult<String> {
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

/// A goal from Python: `(x, y)` or `(x, y, angle_deg)`.
fn goal_of(goal: &Bound<'_, PyAny>) -> PyResult<Goal> {
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

/// What a chain holds: the validated arm, its API form, and a solver with the default options.
struct ChainData {
    arm: Arm,
    /// The API's `arm` object (the arm file as JSON).
    arm_json: Value,
    name: String,
    /// The arm file's text it was made from (None for the built-in arm), for pickling.
    toml: Option<String>,
    /// The options of a solve without keywords, and a solver with them (taken while in use).
    options: Arc<SolveOptions>,
    solver: Mutex<Solver>,
}

/// A planar chain: links joined by revolute joints, with optional joint ranges.
///
/// ``Chain(lengths, angles_deg=None, limits_deg=None, base=(0.0, 0.0), name=None)`` builds
/// one from link lengths (base to tip), start angles in degrees (each relative to the previous
/// link, the first to +x; default 0) and joint ranges in degrees (one ``(lo, hi)`` or ``None``
/// per joint); ``Chain()`` is the built-in seed arm (lengths 3, 2, 1, start angles 5°, the
/// seed's ranges), as the CLI without ``--arm``; ``Chain.from_toml(path)`` reads an arm file
/// (``--arm FILE``) and ``Chain(toml=text)`` its text. Bad values raise ``ValueError`` with the
/// CLI's one-line message (``links[1].length = -2: must be greater than 0``).
#[pyclass(subclass, frozen, module = "ikarus._ikarus", name = "Chain")]
struct PyChain {
    data: Arc<ChainData>,
}

/// A float as TOML text: exact (shortest round trip), with TOML's names for the non-finite.
fn toml_float(x: f64) -> toml::Value {
    toml::Value::Float(x)
}

fn arm_toml(
    lengths: &[f64],
    angles: Option<Vec<f64>>,
    limits: Option<Vec<Option<(f64, f64)>>>,
    base: Option<(f64, f64)>,
    name: Option<&str>,
) -> PyResult<String> {
    let n = lengths.len();
    if let Some(a) = &angles {
        if a.len() != n {
            return Err(PyValueError::new_err(format!(
                "angles_deg: expected {n} angles (one per link), got {}",
                a.len()
            )));
        }
    }
    if let Some(l) = &limits {
        if l.len() != n {
            return Err(PyValueError::new_err(format!(
                "limits_deg: expected {n} ranges (one per link, or None), got {}",
                l.len()
            )));
        }
    }
    let mut file = toml::Table::new();
    if let Some(name) = name {
        file.insert("name".into(), toml::Value::String(name.to_owned()));
    }
    if let Some((x, y)) = base {
        file.insert("base".into(), toml::Value::Array(vec![toml_float(x), toml_float(y)]));
    }
    let links = (0..n)
        .map(|i| {
            let mut link = toml::Table::new();
            link.insert("length".into(), toml_float(lengths[i]));
            if let Some(a) = &angles {
                link.insert("angle_deg".into(), toml_float(a[i]));
            }
            if let Some(Some((lo, hi))) = limits.as_ref().map(|l| l[i]) {
                link.insert("limits_deg".into(), toml::Value::Array(vec![toml_float(lo), toml_float(hi)]));
            }
            toml::Value::Table(link)
        })
        .collect();
    file.insert("links".into(), toml::Value::Array(links));
    toml::to_string(&file).map_err(|e| PyRuntimeError::new_err(format!("arm: {e}")))
}

impl ChainData {
    fn new(arm: Arm, arm_json: Value) -> PyResult<Self> {
        let name = arm.name().to_owned();
        let options = edge::solve_options(&arm, "{}", limits()).map_err(problem)?;
        let solver = Solver::new(options.clone()).map_err(|e| PyValueError::new_err(e.to_string()))?;
        Ok(Self { arm, arm_json, name, toml: None, options: Arc::new(options), solver: Mutex::new(solver) })
    }

    fn from_toml(text: &str, label: &str) -> PyResult<Self> {
        let arm = edge::arm_from_toml(text, label).map_err(problem)?;
        // The arm is valid, so its numbers are finite and the file is JSON as well.
        let json: Value = toml::from_str(text).map_err(|e| PyRuntimeError::new_err(format!("{label}: {e}")))?;
        Ok(Self { toml: Some(text.to_owned()), ..Self::new(arm, json)? })
    }

    fn options(&self, kwargs: Option<&Bound<'_, PyDict>>) -> PyResult<SolveOptions> {
        match kwargs {
            Some(k) if !k.is_empty() => {
                edge::solve_options(&self.arm, &options_json(Some(k))?, limits()).map_err(option_problem)
            }
            _ => Ok(SolveOptions::clone(&self.options)),
        }
    }

    /// Runs `f` with the cached default solver, in place (or with a fresh one while another
    /// thread holds it).
    fn with_default_solver<T>(&self, f: impl FnOnce(&mut Solver) -> T) -> PyResult<T> {
        if let Ok(mut cached) = self.solver.try_lock() {
            return Ok(f(&mut cached));
        }
        let mut solver =
            Solver::new(SolveOptions::clone(&self.options)).map_err(|e| PyValueError::new_err(e.to_string()))?;
        Ok(f(&mut solver))
    }
}

/// Where rayon pools of a given size are kept between batches.
fn pool(threads: Option<i64>) -> PyResult<Option<Arc<rayon::ThreadPool>>> {
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
const STATUS_WIDTH: usize = 15;

fn status_code(s: ikarus::Status) -> u8 {
    match s {
        ikarus::Status::Reached => 0,
        ikarus::Status::Unreachable => 1,
        ikarus::Status::Stalled => 2,
        ikarus::Status::IterationLimit => 3,
        _ => 4,
    }
}

const STATUS_OF_CODE: [ikarus::Status; 5] = [
    ikarus::Status::Reached,
    ikarus::Status::Unreachable,
    ikarus::Status::Stalled,
    ikarus::Status::IterationLimit,
    ikarus::Status::Interrupted,
];

#[pymethods]
impl PyChain {
    #[new]
    #[pyo3(signature = (lengths=None, angles_deg=None, limits_deg=None, base=None, name=None, *, toml=None, label=None))]
    fn new(
        lengths: Option<Vec<f64>>,
        angles_deg: Option<Vec<f64>>,
        limits_deg: Option<Vec<Option<(f64, f64)>>>,
        base: Option<(f64, f64)>,
        name: Option<String>,
        toml: Option<String>,
        label: Option<String>,
    ) -> PyResult<Self> {
        let data = match (lengths, toml) {
            (Some(_), Some(_)) => {
                return Err(PyValueError::new_err("Chain: give lengths or toml, not both"));
            }
            (None, Some(text)) => {
                if angles_deg.is_some() || limits_deg.is_some() || base.is_some() || name.is_some() {
                    return Err(PyValueError::new_err(
                        "Chain: toml gives the whole arm (angles_deg, limits_deg, base and name belong to lengths)",
                    ));
                }
                ChainData::from_toml(&text, label.as_deref().unwrap_or("arm text"))?
            }
            (Some(lengths), None) => {
                let text = arm_toml(&lengths, angles_deg, limits_deg, base, name.as_deref())?;
                ChainData::from_toml(&text, label.as_deref().unwrap_or("Chain"))?
            }
            (None, None) => {
                if angles_deg.is_some() || limits_deg.is_some() || base.is_some() || name.is_some() {
                    return Err(PyValueError::new_err(
                        "Chain: lengths: required with angles_deg, limits_deg, base or name",
                    ));
                }
                let reply =
                    edge::call(Endpoint::ArmDefault, b"", limits(), &ikarus::Interrupt::new()).map_err(problem)?;
                let json: Value =
                    serde_json::from_slice(&reply.body).map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
                ChainData::new(edge::default_arm(), json)?
            }
        };
        Ok(Self { data: Arc::new(data) })
    }

    /// The arm's name (``"seed"`` for the built-in arm, ``"arm"`` when none was given).
    #[getter]
    fn name(&self) -> &str {
        &self.data.name
    }

    /// The arm file's text the chain was made from (None for the built-in arm).
    #[getter]
    fn _toml(&self) -> Option<&str> {
        self.data.toml.as_deref()
    }

    /// Number of links (and joints).
    fn __len__(&self) -> usize {
        self.data.arm.chain().len()
    }

    /// Link lengths, base to tip (float64 [n]).
    #[getter]
    fn lengths<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, self.data.arm.chain().lengths())
    }

    /// Start angles in degrees as the chain took them (normalised as the CLI does), float64 [n].
    #[getter]
    fn angles_deg<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let deg: Vec<f64> = self.data.arm.start().iter().map(|a| a.to_degrees()).collect();
        PyArray1::from_vec(py, deg)
    }

    /// Joint ranges in degrees: one ``(lo, hi)`` or ``None`` per joint.
    #[getter]
    fn limits_deg(&self) -> Vec<Option<(f64, f64)>> {
        self.data.arm.chain().limits().iter().map(|l| l.map(|l| (l.min().to_degrees(), l.max().to_degrees()))).collect()
    }

    /// The base's position ``(x, y)``.
    #[getter]
    fn base(&self) -> (f64, f64) {
        let b = self.data.arm.chain().base();
        (b.x, b.y)
    }

    /// The distance the tip reaches at most (sum of lengths, from the base).
    #[getter]
    fn max_reach(&self) -> f64 {
        self.data.arm.chain().max_reach()
    }

    /// The arm as the API's ``arm`` object (the arm file as JSON text), for requests.
    #[getter]
    fn _arm_json(&self) -> String {
        self.data.arm_json.to_string()
    }

    /// Joint positions of a pose (degrees, one per joint), base first, tip last: float64 [n+1, 2].
    #[pyo3(signature = (angles_deg=None))]
    fn joints<'py>(&self, py: Python<'py>, angles_deg: Option<Vec<f64>>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let chain = self.data.arm.chain();
        let angles: Vec<f64> = match angles_deg {
            None => self.data.arm.start().to_vec(),
            Some(a) => {
                if a.len() != chain.len() {
                    return Err(PyValueError::new_err(format!(
                        "angles_deg: expected {} angles (one per joint), got {}",
                        chain.len(),
                        a.len()
                    )));
                }
                if let Some((i, x)) = a.iter().enumerate().find(|(_, x)| !x.is_finite()) {
                    return Err(PyValueError::new_err(format!(
                        "angles_deg[{i}] = {}: must be a finite number",
                        Num(*x)
                    )));
                }
                a.iter().map(|d| d.to_radians()).collect()
            }
        };
        Ok(points_array(py, &joint_positions(chain, &angles)))
    }

    /// Solves for a goal from the chain's start pose, as ``ikarus solve`` does.
    ///
    /// ``goal`` is ``(x, y)`` or ``(x, y, angle_deg)`` (the last link's heading, degrees from
    /// +x). Options are keywords with the CLI's names (``ikarus solve --help``), as the API's
    /// ``options``: ``method`` (``"lm"``, ``"dls"``, ``"pinv"``, ``"sdls"``, ``"transpose"``,
    /// ``"ccd"``, ``"fabrik"``, ``"analytic"``), ``lambda_`` (or ``**{"lambda": 0.1}``, since
    /// ``lambda`` is a Python keyword), ``tolerance``, ``angle_tolerance_deg``,
    /// ``max_iterations``, ``gain``, ``rates``, ``max_step_deg``, ``backtrack``,
    /// ``stall_window``, ``stall_epsilon_deg``, ``limits`` (bool), ``limit_mode``, ``restarts``,
    /// ``restart_seed``, ``time_budget_ms``, ``no_closed_form``, ``record_every``. They go over
    /// the arm file's ``[solver]`` table, over the defaults. As in the API, ``limit_mode`` does
    /// not imply ``limits=True`` (the CLI's ``--limit-mode`` does). An unknown name or a bad
    /// value raises ``ValueError`` with one line naming it (the API's, less ``options.``).
    ///
    /// Returns an :class:`Outcome` whose fields equal ``ikarus solve --format json``'s for the
    /// same inputs, bit for bit. Not reaching the goal is a status, not an exception.
    #[pyo3(signature = (goal, **options))]
    fn solve(
        &self,
        py: Python<'_>,
        goal: &Bound<'_, PyAny>,
        options: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<PyOutcome> {
        let goal = goal_of(goal)?;
        let data = &self.data;
        let chain = data.arm.chain();
        let result = match options {
            Some(k) if !k.is_empty() => {
                let opts = data.options(Some(k))?;
                let mut solver = Solver::new(opts).map_err(|e| PyValueError::new_err(e.to_string()))?;
                py.detach(|| {
                    solver.solve(chain, chain.start_pose(), &goal).map(|o| (o, Arc::new(solver.options().clone())))
                })
            }
            _ => data.with_default_solver(|solver| {
                py.detach(|| solver.solve(chain, chain.start_pose(), &goal)).map(|o| (o, data.options.clone()))
            })?,
        };
        let (outcome, options) = result.map_err(|e| PyValueError::new_err(e.to_string()))?;
        Ok(PyOutcome { outcome, goal, chain: self.data.clone(), options })
    }

    /// Solves many goals in parallel, each from the chain's start pose (``ikarus solve --batch``),
    /// in blocks through the library's batch path.
    ///
    /// ``goals`` is an array [N, 2] (x, y) or [N, 3] (x, y, angle_deg) of numbers (integers and
    /// float32 are converted to float64, as NumPy's ``astype`` does). ``threads``: the
    /// number of worker threads (``None``: all cores). Options are those of :meth:`solve`.
    /// The GIL is released while solving; the results are in input order and the same bit for
    /// bit whatever ``threads`` is. Returns a dict of NumPy arrays: ``angles_deg`` float64
    /// [N, n], ``status`` ``<U15`` [N] (``"reached"``, …), ``error`` float64 [N] and
    /// ``iterations`` uint32 [N] — the rows of ``ikarus solve --batch``'s CSV.
    #[pyo3(signature = (goals, threads=None, **options))]
    fn solve_batch<'py>(
        &self,
        py: Python<'py>,
        goals: &Bound<'py, PyAny>,
        threads: Option<i64>,
        options: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let array = goals_array(goals)?;
        let readonly: PyReadonlyArray2<f64> = array.readonly();
        let shape = readonly.shape().to_vec();
        let (count, width) = (shape[0], shape[1]);
        if width != 2 && width != 3 {
            return Err(PyValueError::new_err(format!("{GOALS_EXPECTED}, got ({count}, {width})")));
        }
        let values: Vec<f64> = match readonly.as_slice() {
            Ok(s) => s.to_vec(),
            Err(_) => readonly.as_array().iter().copied().collect(),
        };
        drop(readonly);
        let mut parsed = Vec::with_capacity(count);
        for (i, row) in values.chunks_exact(width).enumerate() {
            let g = edge::goal(row[0], row[1], row.get(2).copied()).map_err(|p| goal_problem(p, Some(i)))?;
            parsed.push(g);
        }
        let mut opts = self.data.options(options)?;
        // A batch records no frames, as `ikarus solve --batch`.
        opts.record_every = None;
        let solver = Solver::new(opts).map_err(|e| PyValueError::new_err(e.to_string()))?;
        let pool = pool(threads)?;
        let chain = self.data.arm.chain();
        let n = chain.len();
        let mut angles = vec![0.0; count * n];
        let mut error = vec![0.0; count];
        let mut iterations = vec![0u32; count];
        let mut codes = vec![0u8; count];
        let mut run = || -> Result<(), ikarus::SolveError> {
            // Blocks of goals, each solved by one call of the library's batch path (fastest on
            // many goals at once) on a rayon worker with its own solver and outcomes; about four
            // blocks per worker, so that a block of slow goals does not leave the others idle.
            let block = count.div_ceil(4 * rayon::current_num_threads()).clamp(16, 1024);
            let start = chain.start_pose().angles();
            angles
                .par_chunks_mut(block * n.max(1))
                .zip(error.par_chunks_mut(block))
                .zip(iterations.par_chunks_mut(block))
                .zip(codes.par_chunks_mut(block))
                .zip(parsed.par_chunks(block))
                .try_for_each_init(
                    || (solver.clone(), Vec::<Outcome>::new()),
                    |(solver, outs), ((((a, e), it), c), g)| {
                        solver.solve_batch(chain, start, g, outs)?;
                        for (k, out) in outs.iter().enumerate() {
                            for (dst, src) in a[k * n..(k + 1) * n].iter_mut().zip(out.pose.angles()) {
                                *dst = src.to_degrees();
                            }
                            e[k] = out.error;
                            it[k] = out.iterations;
                            c[k] = status_code(out.status);
                        }
                        Ok(())
                    },
                )
        };
        py.detach(|| match &pool {
            Some(p) => p.install(run),
            None => run(),
        })
        .map_err(|e| PyValueError::new_err(e.to_string()))?;

        let out = PyDict::new(py);
        let angles = PyArray1::from_vec(py, angles).reshape([count, n])?;
        out.set_item("angles_deg", angles)?;
        // The statuses as `<U15`: UCS-4 code points, 15 per row, viewed as strings.
        let mut ucs = vec![0u32; count * STATUS_WIDTH];
        for (row, c) in ucs.chunks_exact_mut(STATUS_WIDTH).zip(&codes) {
            for (dst, b) in row.iter_mut().zip(edge::status_name(STATUS_OF_CODE[*c as usize]).bytes()) {
                *dst = u32::from(b);
            }
        }
        let ucs = PyArray1::from_vec(py, ucs);
        let status = ucs.call_method1("view", (format!("<U{STATUS_WIDTH}"),))?;
        out.set_item("status", status)?;
        out.set_item("error", PyArray1::from_vec(py, error))?;
        out.set_item("iterations", PyArray1::from_vec(py, iterations))?;
        Ok(out)
    }

    fn __repr__(&self) -> String {
        let chain = self.data.arm.chain();
        let lengths: Vec<String> = chain.lengths().iter().map(|l| format!("{l:?}")).collect();
        format!("<ikarus.Chain {:?}: {} links, lengths [{}]>", self.data.name, chain.len(), lengths.join(", "))
    }

    /// The chain in its start pose, drawn by ikarus's renderer (``POST /api/render``, SVG).
    fn _repr_svg_(&self, py: Python<'_>) -> PyResult<String> {
        let body = serde_json::json!({
            "figure": "arm", "format": "svg", "width": 480, "height": 480,
            "arm": self.data.arm_json,
        });
        svg(py, &body)
    }
}

fn svg(py: Python<'_>, body: &Value) -> PyResult<String> {
    let bytes = api_call(py, "render", body.to_string().as_bytes())?;
    String::from_utf8(bytes).map_err(|e| PyRuntimeError::new_err(e.to_string()))
}

fn api_call(py: Python<'_>, endpoint: &str, body: &[u8]) -> PyResult<Vec<u8>> {
    let endpoint =
        Endpoint::from_path(endpoint).ok_or_else(|| PyValueError::new_err(format!("unknown endpoint '{endpoint}'")))?;
    let body = body.to_vec();
    py.detach(move || edge::call(endpoint, &body, limits(), &ikarus::Interrupt::new())).map(|r| r.body).map_err(problem)
}

/// What `Chain.solve_batch` takes as goals, for its messages.
const GOALS_EXPECTED: &str = "goals: expected an array of numbers of shape (N, 2) or (N, 3)";

/// `goals` as a float64 array of two dimensions: a float64 array as it is; any other array of
/// integers or floats (int64, uint8, float32, …), or nested sequences of numbers, converted as
/// NumPy's `asarray(goals).astype(float64)` does. Anything else (strings, objects, booleans,
/// complex numbers, ragged lists, another number of dimensions) is refused in one line naming
/// its shape and dtype.
fn goals_array<'py>(goals: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyArray2<f64>>> {
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

/// Joint positions as float64 [k, 2].
fn points_array<'py>(py: Python<'py>, points: &[ikarus::Point2<f64>]) -> Bound<'py, PyArray2<f64>> {
    let flat: Vec<f64> = points.iter().flat_map(|p| [p.x, p.y]).collect();
    PyArray1::from_vec(py, flat).reshape([points.len(), 2]).expect("k × 2 values")
}

/// The result of :meth:`Chain.solve`. Its fields equal those of ``ikarus solve --format json``
/// for the same inputs (degrees, as there), bit for bit; arrays are made when first read.
#[pyclass(frozen, module = "ikarus._ikarus", name = "Outcome")]
struct PyOutcome {
    outcome: Outcome,
    goal: Goal,
    chain: Arc<ChainData>,
    options: Arc<SolveOptions>,
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

/// ``ease(kind, t, k1=None, k2=None, velocity=False)``: an ease curve's position s(t) (or its
/// velocity) at ``t`` in [0, 1], a float or a NumPy array (the result has its shape).
///
/// ``kind`` is ``"linear"``, ``"sine"``, ``"parent"`` or ``"smoothstep"``; ``k1`` and ``k2``
/// are Parent's phases (0.3 and 0.7 by default) and belong to Parent's ease alone, as in
/// ``ikarus animate --ease parent --k1 0.3 --k2 0.7``.
#[pyfunction]
#[pyo3(signature = (kind, t, k1=None, k2=None, velocity=false))]
fn ease<'py>(
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

/// The CLI's name of a status (``edge::status_name``), for tests and tools.
#[pyfunction]
fn _status_names() -> Vec<&'static str> {
    STATUS_OF_CODE.iter().map(|s| edge::status_name(*s)).collect()
}

/// An API request without HTTP: ``POST /api/<endpoint>`` with a JSON body, answered by the same
/// code as ``ikarus serve`` (``edge::call``); a refusal raises ``ValueError`` with its message.
#[pyfunction]
fn _call(py: Python<'_>, endpoint: &str, body: &str) -> PyResult<Vec<u8>> {
    api_call(py, endpoint, body.as_bytes())
}

#[pymodule]
fn _ikarus(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyChain>()?;
    m.add_class::<PyOutcome>()?;
    m.add_function(wrap_pyfunction!(ease, m)?)?;
    m.add_function(wrap_pyfunction!(_status_names, m)?)?;
    m.add_function(wrap_pyfunction!(_call, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
