//! `Chain`: an arm (a one-branch body of revolute joints), its properties, `solve` and
//! `solve_batch`.

use std::sync::Arc;

use ikarus::kinematics::joint_positions;
use ikarus::number::Num;
use ikarus::{Outcome, Solver};
use numpy::{PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rayon::prelude::*;
use serde_json::Value;

use crate::api::svg;
use crate::arm::ChainData;
use crate::batch::{STATUS_OF_CODE, STATUS_WIDTH, pool, status_code};
use crate::edge::{self, Endpoint};
use crate::errors::{goal_problem, problem};
use crate::goals::{GOALS_EXPECTED, goal_of, goals_array};
use crate::options::limits;
use crate::outcome::{ChainSolved, PyOutcome, Solved, points_array};
use crate::signals::{interruptible, may_run_long};

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
pub(crate) struct PyChain {
    pub(crate) data: Arc<ChainData>,
}

/// A float as TOML text: exact (shortest round trip), with TOML's names for the non-finite.
pub(crate) fn toml_float(x: f64) -> toml::Value {
    toml::Value::Float(x)
}

pub(crate) fn arm_toml(
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
        let start = chain.start_pose().angles();
        let mut outcome = data.outcome();
        let result = match options {
            Some(k) if !k.is_empty() => {
                let mut opts = data.options(Some(k))?;
                let token = ikarus::Interrupt::new();
                let long = may_run_long(&opts);
                if long {
                    opts.interrupt = Some(token.clone());
                }
                let mut solver = Solver::new(opts).map_err(|e| PyValueError::new_err(e.to_string()))?;
                let run = || {
                    let result = solver.solve_into(chain, start, &goal, &mut outcome);
                    result.map(|()| {
                        let mut options = solver.options().clone();
                        options.interrupt = None;
                        Arc::new(options)
                    })
                };
                if long { interruptible(py, &token, run)? } else { py.detach(run) }
            }
            _ => data.with_default_solver(|solver| {
                py.detach(|| solver.solve_into(chain, start, &goal, &mut outcome)).map(|()| data.options.clone())
            })?,
        };
        let options = result.map_err(|e| PyValueError::new_err(e.to_string()))?;
        Ok(PyOutcome { solved: Solved::Chain(ChainSolved { outcome, goal, chain: self.data.clone(), options }) })
    }

    /// Solves many goals in parallel, each from the chain's start pose (``ikarus solve --batch``),
    /// in blocks through the library's batch path.
    ///
    /// ``goals`` is an array [N, 2] (x, y) or [N, 3] (x, y, angle_deg) of numbers (integers and
    /// float32 are converted to float64, as NumPy's ``astype`` does). ``threads`` (keyword-only): the
    /// number of worker threads (``None``: all cores). Options are those of :meth:`solve`.
    /// The GIL is released while solving; the results are in input order and the same bit for
    /// bit whatever ``threads`` is. Returns a dict of NumPy arrays: ``angles_deg`` float64
    /// [N, n], ``status`` ``<U15`` [N] (``"reached"``, …), ``error`` float64 [N] and
    /// ``iterations`` uint32 [N] — the rows of ``ikarus solve --batch``'s CSV.
    #[pyo3(signature = (goals, *, threads=None, **options))]
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
        // Ctrl-C stops the batch: every solve checks the token (`signals::interruptible`).
        let token = ikarus::Interrupt::new();
        opts.interrupt = Some(token.clone());
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
        interruptible(py, &token, || match &pool {
            Some(p) => p.install(run),
            None => run(),
        })?
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
