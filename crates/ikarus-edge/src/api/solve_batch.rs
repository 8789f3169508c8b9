//! `POST /api/solve_batch`: many goals for one arm, each solved from the same start pose with
//! the same options, through the library's batch path ([`ikarus::Solver::solve_batch`]). The
//! answer is one object of columns, goal by goal, with exactly the angles `/api/solve` gives
//! for each goal alone.

use ikarus::{Goal, Interrupt, Outcome};
use serde::{Deserialize, Serialize};

use super::bodies::load_arm;
use super::fields::{json_response, options_for, start_pose, stopped};
use super::{Limits, Problem, Reply, parse_json};
use crate::arm::ArmFile;
use crate::report::degrees;
use crate::settings::{SolverSettings, solver};

/// Goals handed to the library at once: the interrupt is checked between blocks.
const BLOCK: usize = 1024;

/// `POST /api/solve_batch`: `/api/solve`'s fields with `goals` in place of `goal`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SolveBatchReq {
    #[serde(default)]
    pub arm: Option<ArmFile>,
    #[serde(default)]
    pub start_deg: Option<Vec<f64>>,
    /// Required: `[[x, y] | [x, y, angle_deg], …]`, at most `Limits::max_goals`.
    pub goals: Vec<Vec<f64>>,
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
        _ => Err(format!("expected [x, y] or [x, y, angle_deg], got {} numbers", g.len())),
    };
    made.map_err(|m| Problem::invalid(format!("{field}: {m}")))
}

/// `POST /api/solve_batch`.
pub fn solve_batch(body: &[u8], limits: &Limits, interrupt: &Interrupt) -> Result<Reply, Problem> {
    let req: SolveBatchReq = parse_json(body)?;
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
mod tests {
    use serde_json::{Value, json};

    use super::*;
    use crate::api::{Endpoint, call, status};

    fn post(endpoint: Endpoint, body: &Value, limits: &Limits) -> Result<Value, Problem> {
        let reply = call(endpoint, body.to_string().as_bytes(), limits, &Interrupt::new())?;
        Ok(serde_json::from_slice(&reply.body).unwrap())
    }

    fn bits(v: &Value) -> Vec<u64> {
        v.as_array().unwrap().iter().map(|a| a.as_f64().unwrap().to_bits()).collect()
    }

    #[test]
    fn each_goal_gets_what_api_solve_gives_it_bit_for_bit() {
        let limits = Limits::default();
        let goals = [json!([2, 3]), json!([-3, -1]), json!([1.5, 2.5, 90]), json!([9, 9]), json!([4.5, 0.3])];
        for options in [json!({}), json!({"limits": true, "restarts": 4}), json!({"method": "dls"})] {
            let body = json!({"goals": goals, "options": options, "start_deg": [10, 20, 30]});
            let batch = post(Endpoint::SolveBatch, &body, &limits).unwrap();
            assert_eq!(batch["angles_deg"].as_array().unwrap().len(), goals.len());
            for (i, g) in goals.iter().enumerate() {
                let g = g.as_array().unwrap();
                let goal = json!({"x": g[0], "y": g[1], "angle_deg": g.get(2)});
                let one = json!({"goal": goal, "options": options, "start_deg": [10, 20, 30]});
                let one = post(Endpoint::Solve, &one, &limits).unwrap();
                assert_eq!(bits(&batch["angles_deg"][i]), bits(&one["angles_deg"]), "{options} {goal}");
                assert_eq!(batch["status"][i], one["status"], "{options} {goal}");
                assert_eq!(batch["iterations"][i], one["iterations"], "{options} {goal}");
                assert_eq!(batch["error"][i].as_f64().map(f64::to_bits), one["error"].as_f64().map(f64::to_bits));
                for k in ["arm", "method", "limits", "limit_mode", "tolerance"] {
                    assert_eq!(batch[k], one[k], "{k}");
                }
            }
        }
        let empty = post(Endpoint::SolveBatch, &json!({"goals": []}), &limits).unwrap();
        assert_eq!(empty["status"], json!([]));
    }

    #[test]
    fn caps_and_bad_goals_are_one_line_naming_the_field() {
        let limits = Limits { max_goals: 3, ..Limits::default() };
        let refused = |body: Value| post(Endpoint::SolveBatch, &body, &limits).unwrap_err();
        let e = refused(json!({"goals": [[1, 1], [1, 2], [1, 3], [1, 4]]}));
        assert_eq!(
            (e.status, e.message.as_str()),
            (status::UNPROCESSABLE_ENTITY, "goals: 4 goals, more than the cap of 3")
        );
        let e = refused(json!({"goals": [[1, 1], [1, 2, 3, 4]]}));
        assert_eq!(e.message, "goals[1]: expected [x, y] or [x, y, angle_deg], got 4 numbers");
        assert!(refused(json!({"goals": [[1, 1], [1]]})).message.starts_with("goals[1]: expected"));
        assert!(refused(json!({"goals": [[1, "a"]]})).message.contains("goals[0][1]"));
        assert!(refused(json!({})).message.contains("missing field `goals`"));
        assert!(refused(json!({"goals": [[1, 1]], "goal": {"x": 1, "y": 1}})).message.contains("unknown field `goal`"));
        assert!(refused(json!({"goals": [[1, 1]], "start_deg": [1]})).message.starts_with("start_deg: "));
        assert!(refused(json!({"goals": [[1, 1]], "options": {"tolerance": 0}})).message.starts_with("options."));
    }

    #[test]
    fn an_interrupted_batch_is_503() {
        let interrupt = Interrupt::new();
        interrupt.interrupt();
        let body = json!({"goals": [[2, 3], [1, 1]]}).to_string();
        let e = call(Endpoint::SolveBatch, body.as_bytes(), &Limits::default(), &interrupt).unwrap_err();
        assert_eq!(e.status, status::SERVICE_UNAVAILABLE);
    }
}
