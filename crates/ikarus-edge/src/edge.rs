//! What the edges of ikarus share: the HTTP API's endpoints without HTTP ([`call`]), and the
//! typed pieces a fast edge needs (an arm, its options, a goal), all read and checked by the
//! command line's own code. `ikarus serve` answers through [`call`]; the Python package and the
//! WebAssembly build call it too, so a request gets the same bytes — or the same status and
//! one-line message — on every edge.
//!
//! ```
//! use ikarus_edge::edge::{self, Endpoint, Limits};
//!
//! let body = br#"{"goal": {"x": 2.0, "y": 1.0}}"#;
//! let reply = edge::call(Endpoint::Solve, body, &Limits::default(), &ikarus::Interrupt::new()).unwrap();
//! let answer: serde_json::Value = serde_json::from_slice(&reply.body).unwrap();
//! assert_eq!(answer["status"], "reached");
//!
//! let refused = edge::call(Endpoint::Solve, br#"{"goal": {"x": "a"}}"#, &Limits::default(), &ikarus::Interrupt::new());
//! assert_eq!(refused.unwrap_err().status, 422);
//! ```

use ikarus::{Chain, Goal, SolveOptions, Status};

pub use crate::api::{Endpoint, Intake, Limits, Problem, Reply, call, status};
use crate::arm::{ArmFile, DEFAULT_ARM};
pub use crate::error::{Error, ErrorKind, FieldPath, Segment};
pub use crate::rig::DEFAULT_MAX_BONES;
use crate::settings::SolverSettings;

/// Frames a solve records when its options give no `record_every`, as `ikarus solve`.
pub use crate::settings::DEFAULT_RECORD_EVERY;

/// A validated arm: its chain (start pose and joint ranges included) and its file's `[solver]`
/// settings, read as `--arm FILE` or the API's `arm` reads it.
#[derive(Debug, Clone)]
pub struct Arm(crate::arm::Arm);

impl Arm {
    /// The chain.
    #[must_use]
    pub fn chain(&self) -> &Chain {
        &self.0.chain
    }

    /// The start pose, radians, one angle per joint.
    #[must_use]
    pub fn start(&self) -> &[f64] {
        self.0.chain.start_pose().angles()
    }

    /// The arm's name (its file's `name`, else `arm`).
    #[must_use]
    pub fn name(&self) -> &str {
        &self.0.name
    }

    /// Whether the arm's joint ranges are enforced: `asked` over the file's `[solver] limits`,
    /// off when neither says (as `--limits`).
    #[must_use]
    pub fn limits_on(&self, asked: Option<bool>) -> bool {
        self.0.limits(asked)
    }
}

/// An arm file's text, as `--arm FILE` reads it; `label` starts every message (`arm file a.toml`).
pub fn arm_from_toml(text: &str, label: &str) -> Result<Arm, Problem> {
    Ok(Arm(crate::arm::Arm::parse(text, label)?))
}

/// The API's `arm` object (`{"links": [{"length", "angle_deg", "limits_deg"}], "solver": {…}}`);
/// messages start with `arm:` and name the field (`arm: links[0].length = -1: …`).
pub fn arm_from_json(arm: &str) -> Result<Arm, Problem> {
    let file: ArmFile = crate::api::wire::read_json(arm.as_bytes()).map_err(|e| e.from_source("arm"))?;
    Ok(Arm(crate::arm::Arm::from_file(file, "arm")?))
}

/// The built-in seed arm (`examples/arms/seed.toml`).
#[must_use]
pub fn default_arm() -> Arm {
    Arm(crate::arm::Arm::parse(DEFAULT_ARM, "built-in arm").expect("the built-in arm is valid (a test reads it)"))
}

/// The options `ikarus solve` uses for `arm`: `options`, a JSON object of settings with the
/// command line's names (`method`, `lambda`, `tolerance`, `max_iterations`, `limits`,
/// `limit_mode`, `restarts`, `record_every`, `rates`, … — the API's `options`), over the arm
/// file's `[solver]` table, over the defaults; frames every [`DEFAULT_RECORD_EVERY`] iterations
/// unless they say otherwise. `max_iterations` and `restarts` are held to `limits`. A bad value
/// is a 422 whose message names the setting and the value (`lambda = -1: …`).
pub fn solve_options(arm: &Arm, options: &str, limits: &Limits) -> Result<SolveOptions, Problem> {
    // A value of the wrong kind is named by its path (`method: unknown variant …`), without
    // the position in a JSON text the caller did not write.
    let table: SolverSettings = crate::api::wire::read_json(options.as_bytes()).map_err(|e| {
        let message = e.message().rfind(" at line ").map_or(e.message(), |at| &e.message()[..at]);
        Error::new(e.kind(), message).within(e.path().clone())
    })?;
    let arm = &arm.0;
    crate::api::fields::settings_options(
        &arm.solver,
        arm.chain.len(),
        Some(&table),
        Some(DEFAULT_RECORD_EVERY),
        limits,
        "",
    )
}

/// A goal at (`x`, `y`), the last link at `angle_deg` (degrees) when given, as `--goal X,Y
/// --goal-angle DEG` makes it.
pub fn goal(x: f64, y: f64, angle_deg: Option<f64>) -> Result<Goal, Problem> {
    crate::goal::make_goal(x, y, angle_deg).map_err(Problem::from)
}

/// The pose `start_deg` (degrees, one per joint) of `arm` as `/api/track` and `/api/solve` read
/// their `start_deg`: normalised into each joint's range like an arm file's start angles; a
/// wrong count is a 422 naming `start_deg`.
pub fn start_pose(arm: &Arm, start_deg: &[f64]) -> Result<Vec<f64>, Problem> {
    let chain = arm.chain();
    crate::api::fields::pose_from_degrees(arm.start(), chain.limits(), Some(start_deg), "start_deg")
}

/// The options of `/api/track`'s follow mode with `bound_first`, as the page follows the
/// pointer: the solve options `solve` (from [`solve_options`]) and the bound `max_step_deg`
/// (degrees; a value that is not a finite number > 0 is a 422 naming `max_step_deg`).
pub fn follow_options(solve: SolveOptions, max_step_deg: f64) -> Result<ikarus::TrackOptions, Problem> {
    let max_step_deg = crate::api::fields::max_step_deg(Some(max_step_deg))?;
    Ok(crate::track::track_options(solve, max_step_deg, true))
}

/// The command line's name of a status: `reached`, `unreachable`, `stalled`,
/// `iteration_limit` or `interrupted`.
#[must_use]
pub fn status_name(status: Status) -> &'static str {
    status.as_str()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_endpoint_is_found_by_its_path() {
        for &e in Endpoint::ALL {
            assert_eq!(Endpoint::from_path(e.path()), Some(e));
            assert_eq!(Endpoint::from_path(&e.path()["/api/".len()..]), Some(e));
        }
        assert_eq!(Endpoint::from_path("/api/nothing"), None);
        for &e in Endpoint::ALL {
            assert_eq!(Endpoint::at(e.path()), Some(e));
            assert_eq!(Endpoint::at(&e.path()["/api".len()..]), None, "only the whole path");
        }
    }

    #[test]
    fn the_default_arm_is_the_seed_arm() {
        let arm = default_arm();
        assert_eq!(arm.chain().len(), 3);
        assert_eq!(arm.start().len(), 3);
    }

    #[test]
    fn options_name_the_setting_and_the_value() {
        let arm = default_arm();
        let limits = Limits::default();
        let e = solve_options(&arm, r#"{"lambda": -1}"#, &limits).unwrap_err();
        assert_eq!(e.status, 422);
        assert!(e.message.starts_with("lambda = -1"), "{}", e.message);
        let e = solve_options(&arm, r#"{"lambada": 1}"#, &limits).unwrap_err();
        assert!(e.message.starts_with("lambada: unknown field `lambada`"), "{}", e.message);
        let e = solve_options(&arm, r#"{"method": "nope"}"#, &limits).unwrap_err();
        assert!(e.message.starts_with("method: unknown variant `nope`"), "{}", e.message);
        assert!(!e.message.contains("line 1"), "{}", e.message);
        let e = goal(1.0, f64::NAN, None).unwrap_err();
        assert!(e.message.starts_with("goal.y"), "{}", e.message);
        let e = solve_options(&arm, r#"{"rates": [1, 2]}"#, &limits).unwrap_err();
        assert!(e.message.starts_with("rates: expected 3 values"), "{}", e.message);
        let ok = solve_options(&arm, "{}", &limits).unwrap();
        assert_eq!(ok.record_every, Some(DEFAULT_RECORD_EVERY));
    }

    #[test]
    fn max_iterations_is_held_to_the_cap() {
        // Python and WebAssembly: the same cap and the same line as the API's `options.`.
        let arm = default_arm();
        let limits = Limits::default();
        let at_cap = format!(r#"{{"max_iterations": {}}}"#, limits.max_iterations);
        assert_eq!(solve_options(&arm, &at_cap, &limits).unwrap().max_iterations, limits.max_iterations);
        let over = format!(r#"{{"max_iterations": {}}}"#, limits.max_iterations + 1);
        let e = solve_options(&arm, &over, &limits).unwrap_err();
        assert_eq!(e.status, 422);
        assert_eq!(
            e.message,
            format!(
                "max_iterations = {}: more than the cap of {} (--max-iterations)",
                limits.max_iterations + 1,
                limits.max_iterations
            )
        );
    }

    #[test]
    fn an_arm_from_json_names_its_field() {
        let e = arm_from_json(r#"{"links": [{"length": -1}]}"#).unwrap_err();
        assert_eq!(e.status, 422);
        assert!(e.message.starts_with("arm: links[0].length = -1"), "{}", e.message);
        let e = arm_from_json(r#"{"links": [{"length": "x"}]}"#).unwrap_err();
        assert!(e.message.starts_with("arm: links[0].length"), "{}", e.message);
    }
}
