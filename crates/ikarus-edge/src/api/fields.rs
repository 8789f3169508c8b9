//! The fields every job's request shares, checked as the command line checks its flags, in the
//! request's names (`options.lambda`, `start_deg`, `ease.k1`, `frames`, `max_step_deg`, …) and
//! under the server's caps ([`super::Limits`]); and the last steps of every answer (an
//! interrupted computation is a 503, not an answer).

use ikarus::motion::Timing;
use ikarus::{Ease, EaseKind, Goal, Interrupt, SolveOptions};

use super::requests::{EaseReq, GoalReq};
use super::wire::{Limits, Problem, Reply, status};
use crate::arm::Arm;
use crate::ease_args::{EaseProblem, choose_ease};
use crate::motion::TimingProblem;
use crate::settings::{DEFAULT_RECORD_EVERY, SolverSettings, over_cap};
use crate::track::{DEFAULT_MAX_STEP_DEG, DEFAULT_SAMPLES, Shape};

/// Most via points (or goal sets) of a motion: each is one more solve of up to `--max-iterations`.
pub(super) const MAX_VIA: usize = 100;

/// What a rig's keys replace, for the refusal of the fields they leave no room for.
pub(super) const RIG_KEYS_GIVE: &str =
    "not with keys (the keys give the targets, pins, bends and fps; the motion starts at the rig's start pose)";

/// The first field of `given` (`(name, given)`) that is given, refused as `NAME: why`.
pub(super) fn refuse_given(given: &[(&str, bool)], why: &str) -> Result<(), Problem> {
    match given.iter().find(|(_, g)| *g) {
        Some((name, _)) => Err(Problem::invalid(format!("{name}: {why}"))),
        None => Ok(()),
    }
}

#[cfg(feature = "render")]
/// A picture, or the interruption that stopped its drawing (not an internal error).
pub(super) fn picture(drawn: Result<Vec<u8>, crate::error::Error>, interrupt: &Interrupt) -> Result<Vec<u8>, Problem> {
    watched(drawn, interrupt)
}

/// The result of a computation that watches `interrupt`: 503 if the interrupt was set (an
/// error it caused is not the caller's fault nor ours), else the result as it is.
pub(super) fn watched<T>(result: Result<T, crate::error::Error>, interrupt: &Interrupt) -> Result<T, Problem> {
    stopped(interrupt)?;
    Ok(result?)
}

/// Ends a computation whose interrupt was set before it writes its answer (the pool answers
/// 503 for it; writing a large answer nobody reads would only hold the worker).
pub(super) fn stopped(interrupt: &Interrupt) -> Result<(), Problem> {
    if interrupt.is_interrupted() { Err(Problem::new(status::SERVICE_UNAVAILABLE, "interrupted")) } else { Ok(()) }
}

pub(super) fn json_response(value: &impl serde::Serialize) -> Result<Reply, Problem> {
    Reply::json(value)
}

/// Library options from the request's `options` over the body's file's `solver` table `base`
/// (an arm's or a rig's) over the defaults, for a body of `joints` joints;
/// `options.max_iterations` at most `--max-iterations`; frames every `record_every` iterations
/// unless the request or the table says otherwise (none when both are `None`). Problems name
/// the field `options.…`.
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
pub(crate) fn pose_from_degrees(
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

/// A track's `max_step_deg` (10 by default), > 0.
pub(crate) fn max_step_deg(value: Option<f64>) -> Result<f64, Problem> {
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

/// Most values (frames × (joints + 4)) a motion `from_solve` may record over all its solves:
/// each recorded pose is kept until the motion is timed. 4 million is about 100 MB at most.
pub(super) const MAX_RECORDED_VALUES: u64 = 4_000_000;
/// Most values (frames × (joints + 4)) one `/api/solve` may record: every frame goes into the
/// answer, about 60 bytes of JSON per value (1 million: about 60 MB of JSON at most).
pub(super) const MAX_SOLVE_RECORDED_VALUES: u64 = 1_000_000;

/// The frame interval of a solve whose request gives none: [`DEFAULT_RECORD_EVERY`], or more
/// when that would record more than [`MAX_SOLVE_RECORDED_VALUES`].
pub(super) fn default_record_every(joints: usize, max_iterations: u32) -> u32 {
    let per_frame = joints as u64 + 4;
    let frames = (MAX_SOLVE_RECORDED_VALUES / per_frame).saturating_sub(2).max(1);
    let every = u64::from(max_iterations).div_ceil(frames);
    u32::try_from(every).unwrap_or(u32::MAX).max(DEFAULT_RECORD_EVERY)
}

/// Refuses, before any solve, a request whose `solves` solves could record more than `cap`
/// values: each up to `max_iterations / record_every + 2` frames of `per_frame` values, on a
/// body of `joints` joints.
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
