//! The API's jobs: `POST /api/solve`, `/api/animate` and `/api/track`, each one workflow over
//! the body of its request (an arm or a rig, [`super::bodies`]), matching on it only where the
//! two differ: the goal (an arm's one `goal`, a rig's `goals`, `pins` and `mix`), the solver's
//! entry point and the answer's shape (angles by index, or by bone name). The answers are the
//! objects the commands print (`crate::report`, `crate::motion`, `crate::track`), made by the
//! same workflows, under the server's caps and time budget.

use ikarus::motion::Interpolation;
use ikarus::{EaseKind, Interrupt, Outcome, RigTask, TrackMode};
use web_time::Instant;

use super::bodies::{self, AnimateBody, ArmVia, RigVia, load, task, task_named};
use super::fields::{
    MAX_RECORDED_VALUES, MAX_SOLVE_RECORDED_VALUES, MAX_VIA, default_record_every, ease, goal, json_response,
    max_step_deg, options_for, pose_from_degrees, recorded_values_cap, stopped, timing, track_path,
};
use super::requests::{AnimateReq, EaseReq, GoalReq, SolveReq, TrackReq};
use super::wire::{Limits, Problem, Reply};
use crate::arm::Arm;
use crate::body::{Aimed, Body, Jointed};
use crate::error::FieldPath;
use crate::goal::Field;
use crate::motion::{Motion, MotionBody, MotionPlan};
use crate::report::{AnimateJson, RigSolveReport, SolveReport};
use crate::settings::{DEFAULT_RECORD_EVERY, SolverSettings, solver};
use crate::track::{RigFollower, Shape, TrackJob, TrackJson, effector_index, track_options};

/// What a request aims its body at: an arm's `goal`, a rig's `goals`, `pins` and `mix`
/// (`need_one`: a goal or a pin).
fn aimed<'a>(
    body: &'a Body,
    goal_req: Option<&GoalReq>,
    rig: (&[super::requests::RigGoalReq], &[String], Option<f64>),
) -> Result<Aimed<'a>, Problem> {
    match (body, goal_req) {
        (Body::Chain(arm), g) => {
            let g = g.ok_or_else(|| Problem::internal("an arm's request without its goal"))?;
            Ok(Aimed::Chain(arm, goal(g, "goal")?))
        }
        // An arm with offsets or slides (a rig with a tip): its one goal on its last link.
        (Body::Rig(r), Some(g)) => {
            let tip = r.tip.ok_or_else(|| Problem::internal("a rig's request with an arm's goal"))?;
            let on_tip = super::requests::RigGoalReq {
                bone: r.skeleton.name(tip).to_owned(),
                x: g.x,
                y: g.y,
                angle_deg: g.angle_deg,
                weight: None,
                priority: None,
                bend: None,
                softness: None,
                bones: None,
            };
            Ok(Aimed::Rig(r, task(r, &[on_tip], &[], None, true)?))
        }
        (Body::Rig(r), None) => {
            let (goals, pins, mix) = rig;
            Ok(Aimed::Rig(r, task(r, goals, pins, mix, true)?))
        }
    }
}

/// `POST /api/solve`: the JSON of `ikarus solve --format json` (with `--rig`, of a rig).
pub fn solve(req: SolveReq, limits: &Limits, interrupt: &Interrupt) -> Result<Reply, Problem> {
    let loaded = load(req.arm, req.rig, limits)?;
    let (goals, pins) = (req.goals.unwrap_or_default(), req.pins.unwrap_or_default());
    let aimed = aimed(&loaded, req.goal.as_ref(), (&goals, &pins, req.mix))?;
    let body = loaded.jointed();
    let mut options = options_for(body.solver(), body.joints(), req.options.as_ref(), None, limits, interrupt)?;
    // An arm's frames every DEFAULT_RECORD_EVERY iterations (or more, under the cap) unless
    // asked otherwise; a rig's none unless asked.
    if let (Body::Chain(_), None) = (&loaded, options.record_every) {
        options.record_every = Some(default_record_every(body.joints(), options.max_iterations));
    }
    recorded_values_cap(body.joints(), body.frame_values(), &options, 1, MAX_SOLVE_RECORDED_VALUES)?;
    let start = pose_from_degrees(body.start(), body.limits(), req.start_deg.as_deref(), "start_deg")?;
    let mut solver = solver(options)?;
    let mut outcome = Outcome::default();
    let started = Instant::now();
    aimed.solve_into(&mut solver, &start, &mut outcome).map_err(|e| Problem::invalid(e.to_string()))?;
    stopped(interrupt)?;
    let micros = started.elapsed().as_secs_f64() * 1e6;
    let options = solver.options();
    match aimed {
        Aimed::Chain(arm, goal) => {
            json_response(&SolveReport { body: (arm, &goal), options, outcome: &outcome, micros }.json())
        }
        Aimed::Rig(rig, _) => json_response(&RigSolveReport { body: rig, options, outcome: &outcome, micros }.json()),
    }
}

/// `POST /api/animate`: the JSON of `ikarus animate --format json` (with `--rig`, of a rig):
/// the body's stops (an arm's via points and goal, a rig's via sets and goal set), then the
/// one motion workflow (`motion`).
pub fn animate(req: AnimateBody, limits: &Limits, interrupt: &Interrupt) -> Result<Reply, Problem> {
    match req {
        AnimateBody::Arm(req) => {
            if let Some(keys) = &req.keys {
                let rig = bodies::load_arm_as_rig(req.arm.clone(), limits)?;
                return super::keyed::animate(&rig, keys, &req, limits, interrupt);
            }
            let arm = bodies::load_arm(req.arm.clone(), limits)?;
            let goal_req = req.goal.as_ref().ok_or_else(|| Problem::internal("an arm's motion without its goal"))?;
            let motion = arm_motion(&arm, &MotionFields::of_animate(&req), &req.via, goal_req, limits, interrupt)?;
            stopped(interrupt)?;
            json_response(&AnimateJson::new(&arm, &motion.motion))
        }
        AnimateBody::Rig(req) => {
            let file = req.rig.clone().ok_or_else(|| Problem::internal("a rig's motion without its rig"))?;
            let rig = bodies::load_rig(file, limits)?;
            if let Some(keys) = &req.keys {
                return super::keyed::animate(&rig, keys, &req, limits, interrupt);
            }
            let tasks = tasks(&rig, &req)?;
            let motion = motion(&rig, tasks, &MotionFields::of_animate(&req), None, limits, interrupt)?;
            stopped(interrupt)?;
            json_response(&motion.json(&rig))
        }
    }
}

/// The tasks of a rig motion: each `via[i]` set with the pins and the mix, then `goals`; a
/// problem names the field in the request's words (`via[1][0].bone`).
fn tasks(rig: &crate::rig::Rig, req: &AnimateReq<RigVia>) -> Result<Vec<RigTask>, Problem> {
    if req.via.len() > MAX_VIA {
        return Err(Problem::invalid(format!("via: {} goal sets, more than the cap of {MAX_VIA}", req.via.len())));
    }
    let pins = req.pins.as_deref().unwrap_or_default();
    let mut tasks = Vec::with_capacity(req.via.len() + 1);
    for (i, set) in req.via.iter().enumerate() {
        let via = |f: Field| f.path_in(FieldPath::new().field("via").index(i)).to_string();
        let t = task_named(rig, set, pins, req.mix, true, &via)?;
        tasks.push(t);
    }
    tasks.push(task(rig, req.goals.as_deref().unwrap_or_default(), pins, req.mix, true)?);
    Ok(tasks)
}

/// `POST /api/track`: the work of `ikarus track` (with `--rig`, of a rig's effector), under
/// `--max-samples` and the solver caps.
pub fn track(req: TrackReq, limits: &Limits, interrupt: &Interrupt) -> Result<Reply, Problem> {
    let loaded = load(req.arm.clone(), req.rig.clone(), limits)?;
    let body = loaded.jointed();
    let rig = match &loaded {
        Body::Chain(_) => None,
        Body::Rig(rig) => Some((rig, rig_follower(rig, &req)?)),
    };
    // An arm's solves record frames every DEFAULT_RECORD_EVERY iterations, a rig's none,
    // unless asked (a track keeps none either way).
    let record = match &loaded {
        Body::Chain(_) => Some(DEFAULT_RECORD_EVERY),
        Body::Rig(_) => None,
    };
    let solve = options_for(body.solver(), body.joints(), req.options.as_ref(), record, limits, interrupt)?;
    let start = pose_from_degrees(body.start(), body.limits(), req.start_deg.as_deref(), "start_deg")?;
    let shapes = [req.line.map(Shape::Line), req.circle.map(Shape::Circle), req.figure8.map(Shape::Figure8)];
    let path = track_path(req.path.as_deref(), shapes, req.samples, limits)?;
    let max_step_deg = max_step_deg(req.max_step_deg)?;
    let options = track_options(solve, max_step_deg, req.bound_first);
    match (&loaded, rig) {
        (_, Some((rig, (bone, task)))) => {
            let job = TrackJob { body: &**rig, start, follower: RigFollower { bone, task }, path, options };
            let t = job.run().map_err(Problem::from)?;
            stopped(interrupt)?;
            json_response(&job.json(&t))
        }
        (Body::Chain(arm), None) => {
            let mode = req.mode.unwrap_or(TrackMode::Plan);
            if req.bound_first && mode != TrackMode::Follow {
                return Err(Problem::invalid("bound_first: only applies with mode follow"));
            }
            let job = TrackJob { body: &**arm, start, follower: mode, path, options };
            let t = job.run().map_err(Problem::from)?;
            stopped(interrupt)?;
            json_response(&TrackJson::new(&job, &t))
        }
        (Body::Rig(_), None) => Err(Problem::internal("a rig's track without its effector")),
    }
}

/// A rig track's effector bone and the task held while it follows: `effector` (required),
/// `mode` follow only, `goals` and `pins` with the effector at most [`bodies::MAX_EFFECTORS`].
fn rig_follower(rig: &crate::rig::Rig, req: &TrackReq) -> Result<(usize, RigTask), Problem> {
    // An arm with offsets or slides follows the path with its last link.
    let tip = rig.tip.map(|t| rig.skeleton.name(t).to_owned());
    let Some(name) = req.effector.as_ref().or(tip.as_ref()) else {
        return Err(Problem::invalid("effector: required with rig: the bone whose tip follows the path"));
    };
    if let Some(mode) = req.mode.filter(|&m| m != TrackMode::Follow) {
        return Err(Problem::invalid(format!(
            "mode = {}: a rig's effector is followed online only (mode follow, the default with rig)",
            mode.name()
        )));
    }
    let (goals, pins) = (req.goals.as_deref().unwrap_or_default(), req.pins.as_deref().unwrap_or_default());
    if goals.len() + pins.len() + 1 > bodies::MAX_EFFECTORS {
        return Err(Problem::invalid(format!(
            "goals, pins: {} effectors with the effector, more than the cap of {}",
            goals.len() + pins.len() + 1,
            bodies::MAX_EFFECTORS
        )));
    }
    let task = task(rig, goals, pins, req.mix, false)?;
    let task = RigTask { mix: req.mix.unwrap_or(1.0), ..task };
    let bone = effector_index(rig, name, &task, "effector").map_err(Problem::from)?;
    Ok((bone, task))
}

/// The fields of a motion that both bodies share, from `/api/animate` or the figure `motion`
/// of `/api/render`.
pub(super) struct MotionFields<'a> {
    start_deg: Option<&'a [f64]>,
    options: Option<&'a SolverSettings>,
    ease: Option<&'a EaseReq>,
    frames: Option<u32>,
    duration: Option<f64>,
    fps: Option<f64>,
    interpolation: Option<Interpolation>,
    from_solve: bool,
}

impl<'a> MotionFields<'a> {
    fn of_animate<V>(r: &'a AnimateReq<V>) -> Self {
        Self {
            start_deg: r.start_deg.as_deref(),
            options: r.options.as_ref(),
            ease: r.ease.as_ref(),
            frames: r.frames,
            duration: r.duration,
            fps: r.fps,
            interpolation: r.interpolation,
            from_solve: r.from_solve,
        }
    }

    #[cfg(feature = "render")]
    pub(super) fn of_figure(r: &'a super::figures::MotionFigureReq) -> Self {
        Self {
            start_deg: r.start_deg.as_deref(),
            options: r.options.as_ref(),
            ease: r.ease.as_ref(),
            frames: r.frames,
            duration: r.duration,
            fps: r.fps,
            interpolation: r.interpolation,
            from_solve: r.from_solve,
        }
    }
}

/// An arm's motion through its `via` points to `goal_req` (the figure `motion` draws it too).
pub(super) fn arm_motion(
    arm: &Arm,
    req: &MotionFields<'_>,
    via: &[ArmVia],
    goal_req: &GoalReq,
    limits: &Limits,
    interrupt: &Interrupt,
) -> Result<Motion<Arm>, Problem> {
    if via.len() > MAX_VIA {
        return Err(Problem::invalid(format!("via: {} points, more than the cap of {MAX_VIA}", via.len())));
    }
    let goals = crate::motion::goals(via, goal(goal_req, "goal")?)
        .map_err(|(i, e)| Problem::invalid(format!("via[{i}]: {e}")))?;
    motion(arm, goals, req, Some(DEFAULT_RECORD_EVERY), limits, interrupt)
}

/// The one motion workflow of the API: `stops` on `body` with the request's timing, ease,
/// options and start pose, under the caps. Without `from_solve`, the solves record frames every
/// `record` iterations unless asked (an arm's, as ever; a rig's none).
fn motion<B: MotionBody + Jointed>(
    body: &B,
    stops: Vec<B::Stop>,
    req: &MotionFields<'_>,
    record: Option<u32>,
    limits: &Limits,
    interrupt: &Interrupt,
) -> Result<Motion<B>, Problem> {
    let timing = timing(req.frames, req.duration, req.fps, limits)?;
    let ease = ease(req.ease, EaseKind::Sine)?;
    let record = if req.from_solve { Some(1) } else { record };
    let options = options_for(body.solver(), body.joints(), req.options, record, limits, interrupt)?;
    if req.from_solve {
        recorded_values_cap(body.joints(), body.frame_values(), &options, stops.len(), MAX_RECORDED_VALUES)?;
    }
    let start = pose_from_degrees(body.start(), body.limits(), req.start_deg, "start_deg")?;
    let interpolation = req.interpolation.unwrap_or_default();
    let from_solve = req.from_solve;
    Ok(MotionPlan { body, start, stops, options, timing, ease, interpolation, from_solve }.run()?)
}
