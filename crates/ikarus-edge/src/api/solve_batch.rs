//! `POST /api/solve_batch`: many goals for one arm, each solved from the same start pose with
//! the same options, through the library's batch path ([`ikarus::Solver::solve_batch`]). The
//! answer is one object of columns, goal by goal, with exactly the angles `/api/solve` gives
//! for each goal alone.

use ikarus::{Goal, Interrupt, Outcome};

use crate::error::Error;
use serde::{Deserialize, Serialize};

use super::bodies::load_arm;
use super::fields::{json_response, options_for, start_pose, stopped};
use super::wire::{Limits, Problem, Reply};
use crate::arm::ArmFile;
use crate::report::degrees;
use crate::settings::{SolverSettings, solver};

/// Goals handed to the library at once: the interrupt is checked between blocks.
const BLOCK: usize = 1024;

/// `POST /api/solve_batch`: `/api/solve`'s fields with `goals` in place of `goal`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SolveBatchReq {
    /// The arm [default: the built-in arm].
    #[serde(default)]
    pub arm: Option<ArmFile>,
    /// One start angle per joint, degrees [default: the arm's start pose].
    #[serde(default)]
    pub start_deg: Option<Vec<f64>>,
    /// Required: `[[x, y] | [x, y, angle_deg], …]`, at most `Limits::max_goals`.
    pub goals: Vec<Vec<f64>>,
    /// The solver's settings, as `/api/solve` takes them.
    #[serde(default)]
    pub options: Option<SolverSettings>,
}

/// The answer: what was solved, then one entry per goal in each column, in the goals' order.
#[derive(Debug, Serialize)]
struct SolveBatchJson<'a> {
    arm: &'a str,
    method: &'static str,
    limits: bool,
    limit_mode: &'static str,
    tolerance: f64,
    /// Each solve's status (`reached`, `unreachable`, …).
    status: Vec<&'static str>,
    iterations: Vec<u32>,
    /// The tip's distance from each goal.
    error: Vec<f64>,
    /// Each final pose, degrees.
    angles_deg: Vec<Vec<f64>>,
}

/// The goal `goals[i]`: `[x, y]` or `[x, y, angle_deg]`.
fn goal(i: usize, g: &[f64]) -> Result<Goal, Problem> {
    let field = format!("goals[{i}]");
    let made = match *g {
        [x, y] => crate::goal::make_goal(x, y, None),
        [x, y, angle_deg] => crate::goal::make_goal(x, y, Some(angle_deg)),
        _ => Err(Error::input(format!("expected [x, y] or [x, y, angle_deg], got {} numbers", g.len()))),
    };
    made.map_err(|m| Problem::invalid(format!("{field}: {m}")))
}

/// `POST /api/solve_batch`.
pub fn solve_batch(req: SolveBatchReq, limits: &Limits, interrupt: &Interrupt) -> Result<Reply, Problem> {
    if req.goals.len() > limits.max_goals {
        return Err(Problem::invalid(format!(
            "goals: {} goals, more than the cap of {}",
            req.goals.len(),
            limits.max_goals
        )));
    }
    let arm = load_arm(req.arm, limits)?;
    let mut options = options_for(&arm.solver, arm.chain.len(), req.options.as_ref(), None, limits, interrupt)?;
    // The answer has no frames: recording them would only cost time.
    options.record_every = None;
    let start = start_pose(&arm, req.start_deg.as_deref(), "start_deg")?;
    let goals = req.goals.iter().enumerate().map(|(i, g)| goal(i, g)).collect::<Result<Vec<_>, _>>()?;
    let mut solver = solver(options)?;
    let n = goals.len();
    let mut answer = SolveBatchJson {
        arm: &arm.name,
        method: solver.options().method.name(),
        limits: solver.options().limits != ikarus::LimitMode::Ignore,
        limit_mode: solver.options().limits.name(),
        tolerance: solver.options().tolerance,
        status: Vec::with_capacity(n),
        iterations: Vec::with_capacity(n),
        error: Vec::with_capacity(n),
        angles_deg: Vec::with_capacity(n),
    };
    let mut outcomes: Vec<Outcome> = Vec::new();
    for block in goals.chunks(BLOCK) {
        stopped(interrupt)?;
        solver.solve_batch(&arm.chain, &start, block, &mut outcomes).map_err(|e| Problem::invalid(e.to_string()))?;
        for o in &outcomes {
            answer.status.push(o.status.as_str());
            answer.iterations.push(o.iterations);
            answer.error.push(o.error);
            answer.angles_deg.push(degrees(o.pose.angles()));
        }
    }
    stopped(interrupt)?;
    json_response(&answer)
}

#[cfg(test)]
#[path = "solve_batch_tests.rs"]
mod tests;
