//! What a chain holds, shared by `Chain` and the `Outcome`s of its solves: the validated arm,
//! its API form, and a solver with the default options.

use std::sync::{Arc, Mutex};

use ikarus::{Outcome, SolveOptions, Solver};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use serde_json::Value;

use crate::edge::{self, Arm};
use crate::errors::{option_problem, problem};
use crate::options::{limits, options_json};

/// What a chain holds: the validated arm, its API form, and a solver with the default options.
pub(crate) struct ChainData {
    pub(crate) arm: Arm,
    /// The API's `arm` object (the arm file as JSON).
    pub(crate) arm_json: Value,
    pub(crate) name: String,
    /// The arm file's text it was made from (None for the built-in arm), for pickling.
    pub(crate) toml: Option<String>,
    /// The options of a solve without keywords, and a solver with them (taken while in use).
    pub(crate) options: Arc<SolveOptions>,
    pub(crate) solver: Mutex<Solver>,
    /// Outcomes of this chain's solves that Python has let go of, their buffers kept for the
    /// next solves (at most [`SPARE_OUTCOMES`]): a solve then allocates nothing of its own.
    spare: Mutex<Vec<Outcome>>,
}

/// How many dropped outcomes a chain keeps for reuse.
const SPARE_OUTCOMES: usize = 4;

impl ChainData {
    pub(crate) fn new(arm: Arm, arm_json: Value) -> PyResult<Self> {
        let name = arm.name().to_owned();
        let options = edge::solve_options(&arm, "{}", limits()).map_err(problem)?;
        let solver = Solver::new(options.clone()).map_err(|e| PyValueError::new_err(e.to_string()))?;
        Ok(Self {
            arm,
            arm_json,
            name,
            toml: None,
            options: Arc::new(options),
            solver: Mutex::new(solver),
            spare: Mutex::default(),
        })
    }

    pub(crate) fn from_toml(text: &str, label: &str) -> PyResult<Self> {
        let arm = edge::arm_from_toml(text, label).map_err(problem)?;
        // The arm is valid, so its numbers are finite and the file is JSON as well.
        let json: Value = toml::from_str(text).map_err(|e| PyRuntimeError::new_err(format!("{label}: {e}")))?;
        Ok(Self { toml: Some(text.to_owned()), ..Self::new(arm, json)? })
    }

    pub(crate) fn options(&self, kwargs: Option<&Bound<'_, PyDict>>) -> PyResult<SolveOptions> {
        match kwargs {
            Some(k) if !k.is_empty() => {
                edge::solve_options(&self.arm, &options_json(Some(k))?, limits()).map_err(option_problem)
            }
            _ => Ok(SolveOptions::clone(&self.options)),
        }
    }

    /// An outcome to solve into: a dropped one's buffers when there is one, else a new one.
    /// (`Solver::solve_into` sets every field, so what it held before never shows.)
    pub(crate) fn outcome(&self) -> Outcome {
        self.spare.try_lock().ok().and_then(|mut spare| spare.pop()).unwrap_or_default()
    }

    /// Keeps a dropped outcome's buffers for the next solve.
    pub(crate) fn recycle(&self, outcome: Outcome) {
        if let Ok(mut spare) = self.spare.try_lock() {
            if spare.len() < SPARE_OUTCOMES {
                spare.push(outcome);
            }
        }
    }

    /// Runs `f` with the cached default solver, in place (or with a fresh one while another
    /// thread holds it).
    pub(crate) fn with_default_solver<T>(&self, f: impl FnOnce(&mut Solver) -> T) -> PyResult<T> {
        if let Ok(mut cached) = self.solver.try_lock() {
            return Ok(f(&mut cached));
        }
        let mut solver =
            Solver::new(SolveOptions::clone(&self.options)).map_err(|e| PyValueError::new_err(e.to_string()))?;
        Ok(f(&mut solver))
    }
}
