//! `POST /api/animate` and `POST /api/track` with `rig` in place of `arm`: the rig motion of
//! `ikarus animate --rig` (goal sets `via`, then `goals`, with `pins` held) and the rig track of
//! `ikarus track --rig` (`effector` follows the path while `goals` hold and `pins` stay), made
//! by the command line's workflows (`crate::rig_motion`, `crate::track`) under the
//! server's caps and time budget. The bodies are told apart as `POST /api/solve`'s are: `rig`
//! and `goals` make a rig's request.

use ikarus::motion::Interpolation;
use ikarus::{EaseKind, Interrupt, RigTask, TrackMode};
use serde::Deserialize;

use super::jobs::{
    MAX_RECORDED_VALUES, MAX_VIA, ease, json_response, max_step_deg, options_for, pose_from_degrees,
    recorded_values_cap, stopped, timing, track_path,
};
use super::requests::EaseReq;
use super::rig_requests::RigGoalReq;
use super::rigs::{MAX_EFFECTORS, load_rig, task};
use super::{Limits, Problem, Reply};
use crate::rig::{Rig, RigFile};
use crate::rig_motion::RigMotionPlan;
use crate::settings::SolverSettings;
use crate::track::{RigTrackJob, Shape, TrackJob, effector_index};

/// `POST /api/animate` with `rig`: goal sets solved in turn, then eased.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RigAnimateReq {
    pub rig: RigFile,
    /// One angle per bone, in the rig's order [default: the rig's start angles].
    #[serde(default)]
    pub start_deg: Option<Vec<f64>>,
    /// The final goal set.
    #[serde(default)]
    pub goals: Vec<RigGoalReq>,
    /// Bones held where they are, in every goal set.
    #[serde(default)]
    pub pins: Vec<String>,
    /// Goal sets to pass through first, in order, each a list of goals.
    #[serde(default)]
    pub via: Vec<Vec<RigGoalReq>>,
    #[serde(default)]
    pub mix: Option<f64>,
    #[serde(default)]
    pub options: Option<SolverSettings>,
    #[serde(default)]
    pub ease: Option<EaseReq>,
    #[serde(default)]
    pub frames: Option<u32>,
    #[serde(default)]
    pub duration: Option<f64>,
    #[serde(default)]
    pub fps: Option<f64>,
    #[serde(default)]
    pub interpolation: Option<Interpolation>,
    #[serde(default)]
    pub from_solve: bool,
}

/// `POST /api/track` with `rig`: the tip of `effector` follows the path (exactly one of `path`,
/// `line`, `circle`, `figure8`) while `goals` hold and `pins` stay.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RigTrackReq {
    pub rig: RigFile,
    #[serde(default)]
    pub start_deg: Option<Vec<f64>>,
    /// Required: the bone whose tip follows the path.
    #[serde(default)]
    pub effector: Option<String>,
    #[serde(default)]
    pub goals: Vec<RigGoalReq>,
    #[serde(default)]
    pub pins: Vec<String>,
    #[serde(default)]
    pub mix: Option<f64>,
    #[serde(default)]
    pub path: Option<Vec<[f64; 2]>>,
    #[serde(default)]
    pub line: Option<[f64; 4]>,
    #[serde(default)]
    pub circle: Option<[f64; 3]>,
    #[serde(default)]
    pub figure8: Option<[f64; 3]>,
    #[serde(default)]
    pub samples: Option<usize>,
    /// `follow` [default, and the only mode for a rig].
    #[serde(default)]
    pub mode: Option<TrackMode>,
    #[serde(default)]
    pub max_step_deg: Option<f64>,
    #[serde(default)]
    pub bound_first: bool,
    #[serde(default)]
    pub options: Option<SolverSettings>,
}

/// The start pose of a rig request: `start_deg`, or the rig's start angles.
fn start(rig: &Rig, start_deg: Option<&[f64]>) -> Result<Vec<f64>, Problem> {
    pose_from_degrees(rig.skeleton.start_angles(), rig.skeleton.limits(), start_deg, "start_deg")
}

/// The tasks of a rig motion: each `via[i]` set with the pins and the mix, then `goals`; a
/// problem names the field in the request's words (`via[1][0].bone`).
fn tasks(rig: &Rig, req: &RigAnimateReq) -> Result<Vec<RigTask>, Problem> {
    if req.via.len() > MAX_VIA {
        return Err(Problem::invalid(format!("via: {} goal sets, more than the cap of {MAX_VIA}", req.via.len())));
    }
    let mut tasks = Vec::with_capacity(req.via.len() + 1);
    for (i, set) in req.via.iter().enumerate() {
        let t = task(rig, set, &req.pins, req.mix, true)
            .map_err(|e| Problem { message: prefix_goals(&e.message, &format!("via[{i}]")), ..e })?;
        tasks.push(t);
    }
    tasks.push(task(rig, &req.goals, &req.pins, req.mix, true)?);
    Ok(tasks)
}

/// A task's message about `goals[…]` said about the goal set `set` (`via[1][0].bone`).
fn prefix_goals(message: &str, set: &str) -> String {
    message.replacen("goals[", &format!("{set}["), 1)
}

/// `POST /api/animate` with `rig`: the JSON of `ikarus animate --rig --format json`.
pub fn animate(req: RigAnimateReq, limits: &Limits, interrupt: &Interrupt) -> Result<Reply, Problem> {
    {
        let rig = load_rig(req.rig.clone(), limits)?;
        let tasks = tasks(&rig, &req)?;
        let timing = timing(req.frames, req.duration, req.fps, limits)?;
        let ease = ease(req.ease.as_ref(), EaseKind::Sine)?;
        let n = rig.skeleton.len();
        let record = req.from_solve.then_some(1);
        let options = options_for(&rig.solver, n, req.options.as_ref(), record, limits, interrupt)?;
        if req.from_solve {
            recorded_values_cap(n, 3 * n as u64 + 2, &options, tasks.len(), MAX_RECORDED_VALUES)?;
        }
        let start = start(&rig, req.start_deg.as_deref())?;
        let interpolation = req.interpolation.unwrap_or_default();
        let plan =
            RigMotionPlan { rig: &rig, start, tasks, options, timing, ease, interpolation, from_solve: req.from_solve };
        let motion = plan.run()?;
        stopped(interrupt)?;
        json_response(&motion.json(&rig))
    }
}

/// `POST /api/track` with `rig`: the JSON of `ikarus track --rig --format json`.
pub fn track(req: RigTrackReq, limits: &Limits, interrupt: &Interrupt) -> Result<Reply, Problem> {
    {
        let rig = load_rig(req.rig.clone(), limits)?;
        let Some(name) = &req.effector else {
            return Err(Problem::invalid("effector: required with rig: the bone whose tip follows the path"));
        };
        if let Some(mode) = req.mode.filter(|&m| m != TrackMode::Follow) {
            return Err(Problem::invalid(format!(
                "mode = {}: a rig's effector is followed online only (mode follow, the default with rig)",
                mode.name()
            )));
        }
        if req.goals.len() + req.pins.len() + 1 > MAX_EFFECTORS {
            return Err(Problem::invalid(format!(
                "goals, pins: {} effectors with the effector, more than the cap of {MAX_EFFECTORS}",
                req.goals.len() + req.pins.len() + 1
            )));
        }
        let task = task(&rig, &req.goals, &req.pins, req.mix, false)?;
        let task = RigTask { mix: req.mix.unwrap_or(1.0), ..task };
        let bone = effector_index(&rig, name, &task, "effector").map_err(Problem::invalid)?;
        let n = rig.skeleton.len();
        let solve = options_for(&rig.solver, n, req.options.as_ref(), None, limits, interrupt)?;
        let start = start(&rig, req.start_deg.as_deref())?;
        let shapes = [req.line.map(Shape::Line), req.circle.map(Shape::Circle), req.figure8.map(Shape::Figure8)];
        let path = track_path(req.path.as_deref(), shapes, req.samples, limits)?;
        let options = TrackJob::options(solve, max_step_deg(req.max_step_deg)?, req.bound_first);
        let job = RigTrackJob { rig: &rig, start, bone, task, path, options };
        let t = job.run().map_err(Problem::invalid)?;
        stopped(interrupt)?;
        json_response(&job.json(&t))
    }
}
