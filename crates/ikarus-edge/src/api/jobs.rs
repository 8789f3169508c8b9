//! The handlers of the JSON API. Requests (`super::requests`) use the names of the command
//! line and the arm files (degrees at the edge); answers are the same objects the commands print
//! (`crate::report`), made by the same workflows (`crate::settings`, `crate::motion`,
//! `crate::picture`, `crate::area`, `crate::reach`).

use ikarus::motion::{Interpolation, Timing};
use ikarus::reach::WorkspaceOptions;
use ikarus::{Ease, EaseKind, Goal, Interrupt, Outcome, SolveOptions};
use web_time::Instant;

use super::requests::{AnimateReq, EaseReq, GoalReq, ReachReq, SolveReq, TrackReq, WorkspaceReq};
use super::{Limits, Problem, Reply, parse_json, status};
use crate::area::{self, Effector, GridRequest, ReachableArea};
use crate::arm::{Arm, ArmFile, DEFAULT_ARM};
use crate::body::Body;
use crate::ease_args::{EaseProblem, choose_ease};
use crate::motion::{Motion, MotionPlan, TimingProblem};
use crate::reach::ReachRequest;
use crate::report::{self, AnimateJson, SolveReport, VerdictJson};
use crate::rig::{BoneCap, Rig};
use crate::settings::{DEFAULT_RECORD_EVERY, SolverSettings, over_cap, solver};
use crate::track::{DEFAULT_MAX_STEP_DEG, DEFAULT_SAMPLES, Shape, TrackJob, TrackJson};

/// Most via points of a motion: each is one more solve of up to `--max-iterations`.
pub(super) const MAX_VIA: usize = 100;
/// Most joint-space samples of a workspace.
const MAX_SAMPLES: u32 = 1_000_000;

#[cfg(feature = "render")]
/// A picture, or the interruption that stopped its drawing (not an internal error).
pub(super) fn picture(
    drawn: Result<Vec<u8>, crate::error::CliError>,
    interrupt: &Interrupt,
) -> Result<Vec<u8>, Problem> {
    watched(drawn, interrupt)
}

/// The result of a computation that watches `interrupt`: 503 if the interrupt was set (an
/// error it caused is not the caller's fault nor ours), else the result as it is.
pub(super) fn watched<T>(result: Result<T, crate::error::CliError>, interrupt: &Interrupt) -> Result<T, Problem> {
    stopped(interrupt)?;
    Ok(result?)
}

/// Ends a computation whose interrupt was set before it writes its answer (the pool answers
/// 503 for it; writing a large answer nobody reads would only hold the worker).
pub(super) fn stopped(interrupt: &Interrupt) -> Result<(), Problem> {
    if interrupt.is_interrupted() {
        Err(Problem { status: status::SERVICE_UNAVAILABLE, message: "interrupted".to_owned() })
    } else {
        Ok(())
    }
}

pub(super) fn json_response(value: &impl serde::Serialize) -> Result<Reply, Problem> {
    Reply::json(value)
}

#[derive(serde::Serialize)]
struct LinkJson {
    length: f64,
    angle_deg: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    limits_deg: Option<[f64; 2]>,
}

#[derive(serde::Serialize)]
struct ArmJson {
    name: String,
    base: [f64; 2],
    links: Vec<LinkJson>,
}

/// `GET /api/arm/default`: the built-in arm.
pub fn default_arm() -> Result<Reply, Problem> {
    let file: ArmFile = toml::from_str(DEFAULT_ARM).map_err(|e| Problem::internal(format!("the built-in arm: {e}")))?;
    json_response(&ArmJson {
        name: file.name.clone().unwrap_or_else(|| "arm".to_owned()),
        base: file.base.unwrap_or([0.0, 0.0]),
        links: file
            .links
            .iter()
            .map(|l| LinkJson { length: l.length, angle_deg: l.angle_deg, limits_deg: l.limits_deg })
            .collect(),
    })
}

/// `POST /api/solve` with `arm`: the JSON of `ikarus solve --format json`.
pub fn solve(req: SolveReq, limits: &Limits, interrupt: &Interrupt) -> Result<Reply, Problem> {
    {
        let arm = load_arm(req.arm, limits)?;
        let mut options = options(&arm, req.options.as_ref(), DEFAULT_RECORD_EVERY, limits, interrupt)?;
        let asked = req.options.as_ref().and_then(|o| o.record_every).or(arm.solver.record_every);
        if asked.is_none() {
            options.record_every = Some(default_record_every(&arm, options.max_iterations));
        }
        recorded_cap(&arm, &options, 1, MAX_SOLVE_RECORDED_VALUES)?;
        let start = start_pose(&arm, req.start_deg.as_deref(), "start_deg")?;
        let goal = goal(&req.goal, "goal")?;
        let mut solver = solver(options)?;
        let mut outcome = Outcome::default();
        let started = Instant::now();
        solver.solve_into(&arm.chain, &start, &goal, &mut outcome).map_err(|e| Problem::invalid(e.to_string()))?;
        stopped(interrupt)?;
        let micros = started.elapsed().as_secs_f64() * 1e6;
        let report = SolveReport { arm: &arm, options: solver.options(), goal: &goal, outcome: &outcome, micros };
        json_response(&report.json())
    }
}

/// `POST /api/animate` with `arm`: the JSON of `ikarus animate --format json`.
pub fn animate(req: AnimateReq, limits: &Limits, interrupt: &Interrupt) -> Result<Reply, Problem> {
    let arm = load_arm(req.arm.clone(), limits)?;
    let fields = MotionFields::of_animate(&req);
    let motion = motion(&arm, &fields, &req.goal, limits, interrupt)?;
    stopped(interrupt)?;
    json_response(&AnimateJson::new(&arm, &motion.motion))
}

/// `POST /api/track`: the work of `ikarus track`, under `--max-samples` and the solver caps.
pub fn track(req: TrackReq, limits: &Limits, interrupt: &Interrupt) -> Result<Reply, Problem> {
    {
        let arm = load_arm(req.arm.clone(), limits)?;
        let solve = options(&arm, req.options.as_ref(), DEFAULT_RECORD_EVERY, limits, interrupt)?;
        let start = start_pose(&arm, req.start_deg.as_deref(), "start_deg")?;
        let shapes = [req.line.map(Shape::Line), req.circle.map(Shape::Circle), req.figure8.map(Shape::Figure8)];
        let path = track_path(req.path.as_deref(), shapes, req.samples, limits)?;
        let max_step_deg = max_step_deg(req.max_step_deg)?;
        let mode = req.mode.unwrap_or(ikarus::TrackMode::Plan);
        if req.bound_first && mode != ikarus::TrackMode::Follow {
            return Err(Problem::invalid("bound_first: only applies with mode follow"));
        }
        let options = TrackJob::options(solve, max_step_deg, req.bound_first);
        let job = TrackJob { arm: &arm, start, path, mode, options };
        let t = job.run().map_err(Problem::invalid)?;
        stopped(interrupt)?;
        json_response(&TrackJson::new(&job, &t))
    }
}

/// A track's `max_step_deg` (10 by default), > 0.
pub(super) fn max_step_deg(value: Option<f64>) -> Result<f64, Problem> {
    let max_step_deg = value.unwrap_or(DEFAULT_MAX_STEP_DEG);
    if !(max_step_deg.is_finite() && max_step_deg > 0.0) {
        return Err(Problem::invalid(format!(
            "max_step_deg = {}: must be a finite number > 0",
            ikarus::number::Num(max_step_deg)
        )));
    }
    Ok(max_step_deg)
}

/// The path of a track request: its `path`, or its shape (`line`, `circle`, `figure8`: one
/// given) sampled at `samples` points.
pub(super) fn track_path(
    path: Option<&[[f64; 2]]>,
    shapes: [Option<Shape>; 3],
    samples: Option<usize>,
    limits: &Limits,
) -> Result<ikarus::Path, Problem> {
    let cap = limits.max_samples;
    let given = usize::from(path.is_some()) + shapes.iter().flatten().count();
    if given != 1 {
        return Err(Problem::invalid(format!("path, line, circle, figure8: give exactly one, got {given}")));
    }
    if let Some(points) = path {
        if samples.is_some() {
            return Err(Problem::invalid("samples: only applies with line, circle or figure8"));
        }
        if points.len() > cap {
            return Err(Problem::invalid(format!(
                "path: {} samples, more than the cap of {cap} (--max-samples)",
                points.len()
            )));
        }
        return ikarus::Path::from_points(points).map_err(|e| Problem::invalid(e.to_string()));
    }
    let shape = shapes.into_iter().flatten().next().expect("one shape, counted above");
    let samples = samples.unwrap_or(DEFAULT_SAMPLES);
    if samples > cap {
        return Err(Problem::invalid(format!("samples = {samples}: more than the cap of {cap} (--max-samples)")));
    }
    shape.path(samples).map_err(|e| match e {
        ikarus::PathError::Samples { value } => Problem::invalid(format!("samples = {value}: must be at least 2")),
        other => Problem::invalid(format!("{}: {other}", shape.name())),
    })
}

/// `POST /api/workspace`: the JSON of `ikarus workspace --format json`.
pub fn workspace(body: &[u8], limits: &Limits, interrupt: &Interrupt) -> Result<Reply, Problem> {
    let req: WorkspaceReq = parse_json(body)?;
    if req.rig.is_some() || req.bone.is_some() || req.arm.as_ref().is_some_and(|a| a.joint_key().is_some()) {
        return body_workspace(req, limits, interrupt);
    }
    let arm = load_arm(req.arm.clone(), limits)?;
    let area = reachable_area(&arm, &req, limits, interrupt)?;
    stopped(interrupt)?;
    json_response(&report::workspace_json(&arm, &area))
}

/// `POST /api/reach`: the verdict on `point`, or on each of `points` (at most `--max-samples`),
/// read off the exact region built once, as `ikarus reach --format json` prints them.
pub fn reach(body: &[u8], limits: &Limits, interrupt: &Interrupt) -> Result<Reply, Problem> {
    let req: ReachReq = parse_json(body)?;
    {
        let arm = load_arm(req.arm, limits)?;
        if let Some(t) = req.tolerance {
            crate::options::positive(t).map_err(|m| Problem::invalid(format!("tolerance = {m}")))?;
        }
        let request = ReachRequest { limits: req.limits, tolerance: req.tolerance };
        match (req.point, req.points) {
            (Some(p), None) => {
                let region = watched(request.region(&arm, Some(interrupt)), interrupt)?;
                json_response(&VerdictJson::of(&crate::reach::verdict(&region, p, request.tolerance(&arm))))
            }
            (None, Some(points)) => {
                if points.len() > limits.max_samples {
                    return Err(Problem::invalid(format!(
                        "points: {} points, more than the cap of {} (--max-samples)",
                        points.len(),
                        limits.max_samples
                    )));
                }
                let region = watched(request.region(&arm, Some(interrupt)), interrupt)?;
                let tolerance = request.tolerance(&arm);
                let mut answers = Vec::with_capacity(points.len());
                // A verdict walks every boundary piece: about 10⁶ pieces between two checks.
                let chunk = ((1 << 20) / region.pieces().max(1)).clamp(1, 1024);
                for chunk in points.chunks(chunk) {
                    stopped(interrupt)?;
                    answers
                        .extend(chunk.iter().map(|&p| VerdictJson::of(&crate::reach::verdict(&region, p, tolerance))));
                }
                json_response(&answers)
            }
            (Some(_), Some(_)) => Err(Problem::invalid("point, points: give one or the other, not both")),
            (None, None) => Err(Problem::invalid("point or points: required (a point [x, y], or [[x, y], …])")),
        }
    }
}

/// The request's arm, or the built-in seed arm; at most `--max-links` links.
pub(super) fn load_arm(file: Option<ArmFile>, limits: &Limits) -> Result<Arm, Problem> {
    match file {
        None => Ok(Arm::load(None)?),
        Some(file) => {
            links_cap(&file, limits)?;
            Ok(Arm::from_file(file, "arm")?)
        }
    }
}

/// At most `--max-links` links in a request's arm.
fn links_cap(file: &ArmFile, limits: &Limits) -> Result<(), Problem> {
    if file.links.len() > limits.max_links {
        return Err(Problem::invalid(format!(
            "arm.links: {} links, more than the cap of {} (--max-links)",
            file.links.len(),
            limits.max_links
        )));
    }
    Ok(())
}

/// Library options from the request's `options` over the arm's `solver` table over the
/// defaults; `options.max_iterations` at most `--max-iterations`.
fn options(
    arm: &Arm,
    table: Option<&SolverSettings>,
    record_every: u32,
    limits: &Limits,
    interrupt: &Interrupt,
) -> Result<SolveOptions, Problem> {
    options_for(&arm.solver, arm.chain.len(), table, Some(record_every), limits, interrupt)
}

/// [`options`] for a body of `joints` joints whose file's `solver` table is `base` (an arm's or
/// a rig's); frames every `record_every` iterations unless the request or the table says
/// otherwise (none when both are `None`). Problems name the field `options.…`.
pub(super) fn options_for(
    base: &SolverSettings,
    joints: usize,
    table: Option<&SolverSettings>,
    record_every: Option<u32>,
    limits: &Limits,
    interrupt: &Interrupt,
) -> Result<SolveOptions, Problem> {
    let mut options = settings_options(base, joints, table, record_every, limits, "options.")?;
    options.interrupt = Some(interrupt.clone());
    Ok(options)
}

/// The options of `table` over `base` over the defaults, under the caps of `limits`; problems
/// name a field `{prefix}field` (`options.lambda` for a request, `lambda` for Python's keywords).
pub(crate) fn settings_options(
    base: &SolverSettings,
    joints: usize,
    table: Option<&SolverSettings>,
    record_every: Option<u32>,
    limits: &Limits,
    prefix: &str,
) -> Result<SolveOptions, Problem> {
    let table = table.map_or_else(|| base.clone(), |t| t.over(base));
    table.check().map_err(|m| Problem::invalid(format!("{prefix}{m}")))?;
    let iterations = table.max_iterations.unwrap_or(SolveOptions::default().max_iterations);
    if iterations > limits.max_iterations {
        return Err(Problem::invalid(over_cap(
            &format!("{prefix}max_iterations = {iterations}"),
            limits.max_iterations,
            "--max-iterations",
        )));
    }
    if let Some(restarts) = table.restarts.filter(|&r| r > limits.max_restarts) {
        return Err(Problem::invalid(format!(
            "{prefix}restarts = {restarts}: more than the cap of {}",
            limits.max_restarts
        )));
    }
    let every = table.record_every.or(record_every);
    table.to_options_for(joints, every).map_err(|e| {
        let message = e.describe(|field| format!("{prefix}{field}"));
        match e {
            crate::settings::SettingsError::Options(_) if !prefix.is_empty() => {
                Problem::invalid(format!("{}: {message}", prefix.trim_end_matches('.')))
            }
            _ => Problem::invalid(message),
        }
    })
}

/// A pose in radians from degrees, one angle per joint; the arm's start pose when absent.
pub(super) fn start_pose(arm: &Arm, degrees: Option<&[f64]>, field: &str) -> Result<Vec<f64>, Problem> {
    pose_from_degrees(arm.chain.start_pose().angles(), arm.chain.limits(), degrees, field)
}

/// A pose in radians from degrees, one angle per joint (`limits` has one entry per joint);
/// `default` when absent.
pub(super) fn pose_from_degrees(
    default: &[f64],
    limits: &[Option<ikarus::JointLimits>],
    degrees: Option<&[f64]>,
    field: &str,
) -> Result<Vec<f64>, Problem> {
    match degrees {
        None => Ok(default.to_vec()),
        Some(d) if d.len() != default.len() => Err(Problem::invalid(format!(
            "{field}: expected {} angles (one per joint), got {}",
            default.len(),
            d.len()
        ))),
        // Normalised like an arm file's start angles (`arm.rs`), the limits being the chain's.
        Some(d) => Ok(d
            .iter()
            .zip(limits)
            .map(|(&a, lim)| match lim {
                _ if !a.is_finite() => a.to_radians(),
                Some(l) => ikarus::angle::degrees_within(a, l.min().to_degrees(), l.max().to_degrees())
                    .unwrap_or(a)
                    .to_radians(),
                None => ikarus::angle::radians_from_degrees(a),
            })
            .collect()),
    }
}

pub(super) fn goal(g: &GoalReq, field: &str) -> Result<Goal, Problem> {
    crate::goal::make_goal(g.x, g.y, g.angle_deg).map_err(|m| Problem::invalid(format!("{field}: {m}")))
}

pub(super) fn ease(req: Option<&EaseReq>, default: EaseKind) -> Result<Ease, Problem> {
    let req = req.cloned().unwrap_or_default();
    choose_ease(req.kind, req.k1, req.k2, default).map_err(|p| match p {
        EaseProblem::KWithoutParent { k1 } => {
            let field = if k1 { "ease.k1" } else { "ease.k2" };
            Problem::invalid(format!("{field}: only applies with \"kind\": \"parent\""))
        }
        EaseProblem::Invalid(e) => Problem::invalid(format!("ease.{e}")),
    })
}

/// The motion's timing ([`crate::motion::timing`]); at most `--max-frames` frames.
pub(super) fn timing(
    frames: Option<u32>,
    duration: Option<f64>,
    fps: Option<f64>,
    limits: &Limits,
) -> Result<Timing, Problem> {
    let timing = crate::motion::timing(frames, duration, fps).map_err(|p| match p {
        TimingProblem::Value { field, value, message } => Problem::invalid(format!("{field} = {value}: {message}")),
        TimingProblem::Both => Problem::invalid("frames, duration: give one or the other, not both"),
    })?;
    let n = timing.frame_count().map_err(|e| Problem::invalid(e.to_string()))?;
    if n > limits.max_frames {
        let field = if frames.is_some() { "frames" } else { "duration" };
        return Err(Problem::invalid(format!(
            "{field}: {n} frames, more than the cap of {} (--max-frames)",
            limits.max_frames
        )));
    }
    Ok(timing)
}

/// The fields of a motion, from `/api/animate` or the figure `motion` of `/api/render`.
pub(super) struct MotionFields<'a> {
    start_deg: Option<&'a [f64]>,
    via: &'a [[f64; 2]],
    options: Option<&'a SolverSettings>,
    ease: Option<&'a EaseReq>,
    frames: Option<u32>,
    duration: Option<f64>,
    fps: Option<f64>,
    interpolation: Option<Interpolation>,
    from_solve: bool,
}

impl<'a> MotionFields<'a> {
    fn of_animate(r: &'a AnimateReq) -> Self {
        Self {
            start_deg: r.start_deg.as_deref(),
            via: &r.via,
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
    pub(super) fn of_figure(r: &'a super::requests::MotionFigureReq) -> Self {
        Self {
            start_deg: r.start_deg.as_deref(),
            via: &r.via,
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

pub(super) fn motion(
    arm: &Arm,
    req: &MotionFields<'_>,
    goal_req: &GoalReq,
    limits: &Limits,
    interrupt: &Interrupt,
) -> Result<Motion, Problem> {
    if req.via.len() > MAX_VIA {
        return Err(Problem::invalid(format!("via: {} points, more than the cap of {MAX_VIA}", req.via.len())));
    }
    let timing = timing(req.frames, req.duration, req.fps, limits)?;
    let ease = ease(req.ease, EaseKind::Sine)?;
    let record = if req.from_solve { 1 } else { DEFAULT_RECORD_EVERY };
    let options = options(arm, req.options, record, limits, interrupt)?;
    if req.from_solve {
        recorded_cap(arm, &options, req.via.len() + 1, MAX_RECORDED_VALUES)?;
    }
    let start = start_pose(arm, req.start_deg, "start_deg")?;
    let goals = crate::motion::goals(req.via, goal(goal_req, "goal")?)
        .map_err(|(i, e)| Problem::invalid(format!("via[{i}]: {e}")))?;
    let interpolation = req.interpolation.unwrap_or_default();
    Ok(MotionPlan { arm, start, goals, options, timing, ease, interpolation, from_solve: req.from_solve }.run()?)
}

/// Most values (frames × (joints + 4)) a motion `from_solve` may record over all its solves:
/// each recorded pose is kept until the motion is timed. 4 million is about 100 MB at most.
pub(super) const MAX_RECORDED_VALUES: u64 = 4_000_000;
/// Most values (frames × (joints + 4)) one `/api/solve` may record: every frame goes into the
/// answer, about 60 bytes of JSON per value (1 million: about 60 MB of JSON at most).
pub(super) const MAX_SOLVE_RECORDED_VALUES: u64 = 1_000_000;

/// The frame interval of a solve whose request gives none: [`DEFAULT_RECORD_EVERY`], or more
/// when that would record more than [`MAX_SOLVE_RECORDED_VALUES`].
fn default_record_every(arm: &Arm, max_iterations: u32) -> u32 {
    let per_frame = arm.chain.len() as u64 + 4;
    let frames = (MAX_SOLVE_RECORDED_VALUES / per_frame).saturating_sub(2).max(1);
    let every = u64::from(max_iterations).div_ceil(frames);
    u32::try_from(every).unwrap_or(u32::MAX).max(DEFAULT_RECORD_EVERY)
}

/// Refuses, before any solve, a request whose `solves` solves could record more than `cap`
/// values: each up to `max_iterations / record_every + 2` frames.
fn recorded_cap(arm: &Arm, options: &SolveOptions, solves: usize, cap: u64) -> Result<(), Problem> {
    recorded_values_cap(arm.chain.len(), arm.chain.len() as u64 + 4, options, solves, cap)
}

/// [`recorded_cap`] for a body of `joints` joints whose frames hold `per_frame` values each.
pub(super) fn recorded_values_cap(
    joints: usize,
    per_frame: u64,
    options: &SolveOptions,
    solves: usize,
    cap: u64,
) -> Result<(), Problem> {
    let Some(every) = options.record_every else { return Ok(()) };
    let every = every.max(1);
    let per_solve = u64::from(options.max_iterations / every) + 2;
    let frames = per_solve.saturating_mul(solves as u64);
    let values = frames.saturating_mul(per_frame);
    if values > cap {
        let what = if solves == 1 { "the solve".to_owned() } else { format!("with from_solve, {solves} solves") };
        return Err(Problem::invalid(format!(
            "options.max_iterations = {}, options.record_every = {every}: {what} could record {frames} frames of {} joints, more than the cap of {cap} values; raise record_every, lower max_iterations or give fewer via points",
            options.max_iterations, joints
        )));
    }
    Ok(())
}

/// The reachable area a workspace request asks for: the exact region, or the grid
/// ([`GridRequest::of`]) sampled under `--max-resolution` and the samples' cap.
/// The grid a request asks for (`None`: the exact region), within the server's caps.
fn grid_of(req: &WorkspaceReq, limits: &Limits) -> Result<Option<GridRequest>, Problem> {
    let grid =
        GridRequest::of(req.grid, req.resolution, req.samples, req.seed, |field, value| format!("{field} = {value}"))
            .map_err(Problem::invalid)?;
    if let Some(grid) = &grid {
        if grid.resolution > limits.max_resolution {
            return Err(Problem::invalid(format!(
                "resolution = {}: more than the cap of {} (--max-resolution)",
                grid.resolution, limits.max_resolution
            )));
        }
        if let Some(n) = grid.samples.filter(|&n| n == 0 || n > MAX_SAMPLES) {
            return Err(Problem::invalid(format!("samples = {n}: must be between 1 and {MAX_SAMPLES}")));
        }
    }
    Ok(grid)
}

/// `POST /api/workspace` with `rig`, `bone` or an arm with slides: the region of the bone's tip
/// ([`Effector::of`]): a chain's as an arm's, else sampled (`"exact": false`).
fn body_workspace(req: WorkspaceReq, limits: &Limits, interrupt: &Interrupt) -> Result<Reply, Problem> {
    let body = match (req.arm.clone(), req.rig.clone()) {
        (Some(_), Some(_)) => return Err(Problem::invalid("arm, rig: give one or the other, not both")),
        (_, Some(rig)) => Body::Rig(Box::new(Rig::from_file(rig, "rig", BoneCap::flag(limits.max_bones))?)),
        (Some(arm), None) => {
            links_cap(&arm, limits)?;
            Body::from_arm_file(arm, "arm")?
        }
        (None, None) => Body::Chain(Box::new(Arm::load(None)?)),
    };
    let (rig, bone) = match Effector::of(body, req.bone.as_deref(), |name| format!("bone = {name:?}"))? {
        Effector::Chain(arm) => {
            let area = reachable_area(&arm, &req, limits, interrupt)?;
            stopped(interrupt)?;
            return json_response(&report::workspace_json(&arm, &area));
        }
        Effector::Bone(rig, bone) => (rig, bone),
    };
    let grid = grid_of(&req, limits)?;
    let on = req.limits.or(rig.solver.limits).unwrap_or(false);
    let run = WorkspaceOptions {
        limits: on,
        parallel: false,
        interrupt: Some(interrupt.clone()),
        ..WorkspaceOptions::default()
    };
    let workspace = area::sampled(&rig, bone, grid, run).map_err(Problem::invalid)?;
    stopped(interrupt)?;
    json_response(&report::rig_workspace_json(&rig, bone, workspace))
}

pub(super) fn reachable_area(
    arm: &Arm,
    req: &WorkspaceReq,
    limits: &Limits,
    interrupt: &Interrupt,
) -> Result<ReachableArea, Problem> {
    let on = arm.limits(req.limits);
    let Some(grid) = grid_of(req, limits)? else { return watched(area::exact(arm, on, Some(interrupt)), interrupt) };
    // Sequential on its worker: rayon's global pool is shared by every request, so a small
    // request would wait behind a large one; the server's workers give the parallelism.
    let options = WorkspaceOptions { parallel: false, interrupt: Some(interrupt.clone()), ..grid.options(on) };
    let workspace = ikarus::reach::sample_with_progress(&arm.chain, &options, &|_, _| {})
        .map_err(|e| Problem::invalid(e.to_string()))?;
    Ok(ReachableArea::Grid(workspace))
}
