//! The handlers of the JSON API. Requests use the names of the command line and the arm files
//! (degrees at the edge); answers are the same objects the commands print (`crate::report`).

use std::time::Instant;

use axum::Json;
use axum::extract::State;
use axum::http::header;
use axum::response::{IntoResponse, Response};
use ikarus::motion::Timing;
use ikarus::reach::{Workspace, WorkspaceOptions};
use ikarus::{Ease, Goal, Outcome, SolveOptions};
use serde::Deserialize;
use serde_json::json;

use super::errors::{ApiError, ApiJson};
use super::{AppState, Limits, blocking};
use crate::arm::{Arm, ArmFile, DEFAULT_ARM, SolverTable};
use crate::ease_args::{EaseArg, EaseProblem, choose_ease};
use crate::options::SolverArgs;
use crate::report::{self, MotionRequest, SolveReport, solver_for};

/// Frames recorded by a solve when `options.record_every` is not given (as `ikarus solve`).
const SOLVE_RECORD_EVERY: u32 = 20;
/// Frames of a motion when neither `frames` nor `duration` is given (as `ikarus animate`).
const DEFAULT_FRAMES: u32 = 60;
/// Frame rate of a motion's `duration` and its GIF when `fps` is not given.
const DEFAULT_FPS: f64 = 30.0;
/// Most via points of a motion: each is one more solve of up to `--max-iterations`.
const MAX_VIA: usize = 100;
/// Most joint-space samples of a workspace.
const MAX_SAMPLES: u32 = 1_000_000;
/// Largest GIF, in frames × width × height pixels, so that one request cannot render for minutes.
const MAX_GIF_PIXELS: u64 = 100_000_000;
/// Picture size when the request gives none, and its range (as the command line's).
const DEFAULT_SIDE: u32 = 800;
const SIDE_RANGE: std::ops::RangeInclusive<u32> = 16..=4096;

/// A goal: position, and optionally the orientation of the last link.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GoalReq {
    pub x: f64,
    pub y: f64,
    #[serde(default)]
    pub angle_deg: Option<f64>,
}

/// `POST /api/solve`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SolveReq {
    #[serde(default)]
    pub arm: Option<ArmFile>,
    #[serde(default)]
    pub start_deg: Option<Vec<f64>>,
    pub goal: GoalReq,
    #[serde(default)]
    pub options: Option<SolverTable>,
}

/// An ease curve: `kind` (default sine for a motion, parent for the ease figure), `k1`, `k2`.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EaseReq {
    #[serde(default)]
    pub kind: Option<EaseArg>,
    #[serde(default)]
    pub k1: Option<f64>,
    #[serde(default)]
    pub k2: Option<f64>,
}

/// `POST /api/animate`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AnimateReq {
    #[serde(default)]
    pub arm: Option<ArmFile>,
    #[serde(default)]
    pub start_deg: Option<Vec<f64>>,
    pub goal: GoalReq,
    #[serde(default)]
    pub via: Vec<[f64; 2]>,
    #[serde(default)]
    pub options: Option<SolverTable>,
    #[serde(default)]
    pub ease: Option<EaseReq>,
    #[serde(default)]
    pub frames: Option<u32>,
    #[serde(default)]
    pub duration: Option<f64>,
    #[serde(default)]
    pub fps: Option<f64>,
    #[serde(default)]
    pub from_solve: bool,
}

/// `POST /api/workspace`.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WorkspaceReq {
    #[serde(default)]
    pub arm: Option<ArmFile>,
    #[serde(default)]
    pub limits: Option<bool>,
    #[serde(default)]
    pub resolution: Option<u32>,
    #[serde(default)]
    pub samples: Option<u32>,
    #[serde(default)]
    pub seed: Option<u64>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Figure {
    Arm,
    Motion,
    Workspace,
    Ease,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum PictureFormat {
    Png,
    Svg,
    Gif,
}

/// `POST /api/render`: the figure, its format and size, and the inputs of that figure (the
/// fields of the matching request, side by side).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RenderReq {
    pub figure: Figure,
    #[serde(default)]
    pub format: Option<PictureFormat>,
    #[serde(default)]
    pub width: Option<u32>,
    #[serde(default)]
    pub height: Option<u32>,
    #[serde(default)]
    pub arm: Option<ArmFile>,
    /// Figure `arm`: the pose drawn [default: the arm's start pose].
    #[serde(default)]
    pub pose_deg: Option<Vec<f64>>,
    #[serde(default)]
    pub goal: Option<GoalReq>,
    #[serde(default)]
    pub start_deg: Option<Vec<f64>>,
    #[serde(default)]
    pub via: Vec<[f64; 2]>,
    #[serde(default)]
    pub options: Option<SolverTable>,
    #[serde(default)]
    pub ease: Option<EaseReq>,
    #[serde(default)]
    pub frames: Option<u32>,
    #[serde(default)]
    pub duration: Option<f64>,
    #[serde(default)]
    pub fps: Option<f64>,
    #[serde(default)]
    pub from_solve: bool,
    #[serde(default)]
    pub limits: Option<bool>,
    #[serde(default)]
    pub resolution: Option<u32>,
    #[serde(default)]
    pub samples: Option<u32>,
    #[serde(default)]
    pub seed: Option<u64>,
    /// Figure `arm`: also shade the reachable area.
    #[serde(default)]
    pub workspace: bool,
}

fn json_response(value: &impl serde::Serialize) -> Result<Response, ApiError> {
    let bytes = serde_json::to_vec(value).map_err(|e| ApiError::internal(format!("cannot write JSON: {e}")))?;
    Ok(([(header::CONTENT_TYPE, "application/json")], bytes).into_response())
}

pub async fn health() -> Json<serde_json::Value> {
    Json(json!({ "status": "ok", "version": env!("CARGO_PKG_VERSION") }))
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

pub async fn default_arm() -> Result<Response, ApiError> {
    let file: ArmFile =
        toml::from_str(DEFAULT_ARM).map_err(|e| ApiError::internal(format!("the built-in arm: {e}")))?;
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

pub async fn solve(State(state): State<AppState>, ApiJson(req): ApiJson<SolveReq>) -> Result<Response, ApiError> {
    blocking(move || {
        let limits = &state.limits;
        let arm = load_arm(req.arm, limits)?;
        let options = options(&arm, req.options.as_ref(), SOLVE_RECORD_EVERY, limits)?;
        let start = start_pose(&arm, req.start_deg.as_deref(), "start_deg")?;
        let goal = goal(&req.goal, "goal")?;
        let mut solver = solver_for(&arm.chain, options)?;
        let mut outcome = Outcome::default();
        let started = Instant::now();
        solver.solve_into(&arm.chain, &start, &goal, &mut outcome).map_err(|e| ApiError::invalid(e.to_string()))?;
        let micros = started.elapsed().as_secs_f64() * 1e6;
        let report = SolveReport { arm: &arm, options: solver.options(), goal: &goal, outcome: &outcome, micros };
        json_response(&report.json())
    })
    .await
}

pub async fn animate(State(state): State<AppState>, ApiJson(req): ApiJson<AnimateReq>) -> Result<Response, ApiError> {
    blocking(move || {
        let arm = load_arm(req.arm.clone(), &state.limits)?;
        let motion = motion(&arm, &req, &state.limits)?;
        json_response(&motion.json(&arm))
    })
    .await
}

pub async fn workspace(
    State(state): State<AppState>,
    ApiJson(req): ApiJson<WorkspaceReq>,
) -> Result<Response, ApiError> {
    blocking(move || {
        let arm = load_arm(req.arm.clone(), &state.limits)?;
        let (workspace, limits) = sample_workspace(&arm, &req, &state.limits)?;
        json_response(&report::workspace_json(&arm, limits, &workspace))
    })
    .await
}

pub async fn render(State(state): State<AppState>, ApiJson(req): ApiJson<RenderReq>) -> Result<Response, ApiError> {
    blocking(move || {
        let (bytes, content_type) = render_figure(req, &state.limits)?;
        Ok(([(header::CONTENT_TYPE, content_type)], bytes).into_response())
    })
    .await
}

/// The request's arm, or the built-in seed arm; at most `--max-links` links.
fn load_arm(file: Option<ArmFile>, limits: &Limits) -> Result<Arm, ApiError> {
    match file {
        None => Ok(Arm::load(None)?),
        Some(file) => {
            if file.links.len() > limits.max_links {
                return Err(ApiError::invalid(format!(
                    "arm.links: {} links, more than the cap of {} (--max-links)",
                    file.links.len(),
                    limits.max_links
                )));
            }
            Ok(Arm::from_file(file, "arm")?)
        }
    }
}

/// The most restarts one request may ask for: each restart may run the full iteration cap.
const MAX_RESTARTS: u32 = 64;

/// Library options from the request's `options` over the arm's `solver` table over the
/// defaults; `options.max_iterations` at most `--max-iterations`.
fn options(
    arm: &Arm,
    table: Option<&SolverTable>,
    record_every: u32,
    limits: &Limits,
) -> Result<SolveOptions, ApiError> {
    let table = table.map_or_else(|| arm.solver.clone(), |t| t.over(&arm.solver));
    table.check().map_err(|m| ApiError::invalid(format!("options.{m}")))?;
    let iterations = table.max_iterations.unwrap_or(SolveOptions::default().max_iterations);
    if iterations > limits.max_iterations {
        return Err(ApiError::invalid(format!(
            "options.max_iterations = {iterations}: more than the cap of {} (--max-iterations)",
            limits.max_iterations
        )));
    }
    if let Some(restarts) = table.restarts.filter(|&r| r > MAX_RESTARTS) {
        return Err(ApiError::invalid(format!("options.restarts = {restarts}: more than the cap of {MAX_RESTARTS}")));
    }
    if let Some(rates) = &table.rates {
        if !rates.is_empty() && rates.len() != arm.chain.len() {
            return Err(ApiError::invalid(format!(
                "options.rates: expected {} values (one per joint), got {}",
                arm.chain.len(),
                rates.len()
            )));
        }
    }
    let every = table.record_every.unwrap_or(record_every);
    SolverArgs::default().resolve(&table, Some(every)).map_err(|e| ApiError::invalid(format!("options: {e}")))
}

/// A pose in radians from degrees, one angle per joint; the arm's start pose when absent.
fn start_pose(arm: &Arm, degrees: Option<&[f64]>, field: &str) -> Result<Vec<f64>, ApiError> {
    match degrees {
        None => Ok(arm.chain.start_pose().angles().to_vec()),
        Some(d) if d.len() != arm.chain.len() => Err(ApiError::invalid(format!(
            "{field}: expected {} angles (one per joint), got {}",
            arm.chain.len(),
            d.len()
        ))),
        Some(d) => Ok(d.iter().map(|a| a.to_radians()).collect()),
    }
}

fn goal(g: &GoalReq, field: &str) -> Result<Goal, ApiError> {
    crate::solve::make_goal(g.x, g.y, g.angle_deg).map_err(|m| ApiError::invalid(format!("{field}: {m}")))
}

fn ease(req: Option<&EaseReq>, default: EaseArg) -> Result<Ease, ApiError> {
    let req = req.cloned().unwrap_or_default();
    choose_ease(req.kind, req.k1, req.k2, default).map_err(|p| match p {
        EaseProblem::KWithoutParent { k1 } => {
            let field = if k1 { "ease.k1" } else { "ease.k2" };
            ApiError::invalid(format!("{field}: only applies with \"kind\": \"parent\""))
        }
        EaseProblem::Invalid(e) => ApiError::invalid(format!("ease.{e}")),
    })
}

/// The motion's timing: `frames`, or `duration` at `fps`; at most `--max-frames` frames.
fn timing(frames: Option<u32>, duration: Option<f64>, fps: Option<f64>, limits: &Limits) -> Result<Timing, ApiError> {
    if let Some(fps) = fps {
        if !(fps > 0.0 && fps <= 100.0) {
            return Err(ApiError::invalid(format!("fps = {fps}: must be greater than 0 and at most 100")));
        }
    }
    let timing = match (frames, duration) {
        (Some(_), Some(_)) => return Err(ApiError::invalid("frames, duration: give one or the other, not both")),
        (Some(n), None) if n < 2 => {
            return Err(ApiError::invalid(format!("frames = {n}: a motion needs at least 2 frames")));
        }
        (Some(n), None) => Timing::Frames(n as usize),
        (None, Some(seconds)) if seconds <= 0.0 => {
            return Err(ApiError::invalid(format!("duration = {seconds}: must be greater than 0")));
        }
        (None, Some(seconds)) => Timing::Duration { seconds, fps: fps.unwrap_or(DEFAULT_FPS) },
        (None, None) => Timing::Frames(DEFAULT_FRAMES as usize),
    };
    let n = timing.frame_count().map_err(|e| ApiError::invalid(e.to_string()))?;
    if n > limits.max_frames {
        let field = if frames.is_some() { "frames" } else { "duration" };
        return Err(ApiError::invalid(format!(
            "{field}: {n} frames, more than the cap of {} (--max-frames)",
            limits.max_frames
        )));
    }
    Ok(timing)
}

fn motion(arm: &Arm, req: &AnimateReq, limits: &Limits) -> Result<report::Motion, ApiError> {
    if req.via.len() > MAX_VIA {
        return Err(ApiError::invalid(format!("via: {} points, more than the cap of {MAX_VIA}", req.via.len())));
    }
    let timing = timing(req.frames, req.duration, req.fps, limits)?;
    let ease = ease(req.ease.as_ref(), EaseArg::Sine)?;
    let record = if req.from_solve { 1 } else { SOLVE_RECORD_EVERY };
    let options = options(arm, req.options.as_ref(), record, limits)?;
    let start = start_pose(arm, req.start_deg.as_deref(), "start_deg")?;
    let mut goals = Vec::with_capacity(req.via.len() + 1);
    for (i, [x, y]) in req.via.iter().enumerate() {
        goals.push(Goal::position(*x, *y).map_err(|e| ApiError::invalid(format!("via[{i}]: {e}")))?);
    }
    goals.push(goal(&req.goal, "goal")?);
    Ok(MotionRequest { arm, start, goals, options, timing, ease, from_solve: req.from_solve }.run()?)
}

fn sample_workspace(arm: &Arm, req: &WorkspaceReq, limits: &Limits) -> Result<(Workspace, bool), ApiError> {
    let resolution = req.resolution.unwrap_or(WorkspaceOptions::default().resolution);
    if resolution > limits.max_resolution {
        return Err(ApiError::invalid(format!(
            "resolution = {resolution}: more than the cap of {} (--max-resolution)",
            limits.max_resolution
        )));
    }
    if let Some(n) = req.samples {
        if n == 0 || n > MAX_SAMPLES {
            return Err(ApiError::invalid(format!("samples = {n}: must be between 1 and {MAX_SAMPLES}")));
        }
    }
    let enforce = req.limits.or(arm.solver.limits).unwrap_or(false);
    let options = WorkspaceOptions {
        resolution,
        limits: enforce,
        samples: req.samples.map(u64::from),
        seed: req.seed.unwrap_or(0),
        ..WorkspaceOptions::default()
    };
    let workspace = ikarus::reach::sample(&arm.chain, &options).map_err(|e| ApiError::invalid(e.to_string()))?;
    Ok((workspace, enforce))
}

fn side(value: Option<u32>, field: &str) -> Result<u32, ApiError> {
    let v = value.unwrap_or(DEFAULT_SIDE);
    if SIDE_RANGE.contains(&v) {
        Ok(v)
    } else {
        Err(ApiError::invalid(format!(
            "{field} = {v}: must be between {} and {} pixels",
            SIDE_RANGE.start(),
            SIDE_RANGE.end()
        )))
    }
}

fn render_failed(e: &impl std::fmt::Display) -> ApiError {
    ApiError::internal(format!("rendering failed: {e}"))
}

/// An SVG as SVG or PNG bytes.
fn svg_or_png(svg: String, format: PictureFormat) -> Result<(Vec<u8>, &'static str), ApiError> {
    match format {
        PictureFormat::Png => Ok((ikarus_render::svg_to_png(&svg).map_err(|e| render_failed(&e))?, "image/png")),
        _ => Ok((svg.into_bytes(), "image/svg+xml")),
    }
}

fn render_figure(req: RenderReq, limits: &Limits) -> Result<(Vec<u8>, &'static str), ApiError> {
    let (width, height) = (side(req.width, "width")?, side(req.height, "height")?);
    let format = req.format.unwrap_or(PictureFormat::Png);
    if format == PictureFormat::Gif && req.figure != Figure::Motion {
        return Err(ApiError::invalid("format = gif: only the figure motion animates (use png or svg)"));
    }
    match req.figure {
        Figure::Ease => {
            let ease = ease(req.ease.as_ref(), EaseArg::Parent)?;
            let svg = ikarus_render::ease_svg(&ease, width, height).map_err(|e| render_failed(&e))?;
            svg_or_png(svg, format)
        }
        Figure::Arm => {
            let arm = load_arm(req.arm.clone(), limits)?;
            let pose = start_pose(&arm, req.pose_deg.as_deref(), "pose_deg")?;
            let goal = req.goal.as_ref().map(|g| goal(g, "goal")).transpose()?;
            let workspace = if req.workspace {
                let ws_req = WorkspaceReq {
                    arm: None,
                    limits: req.limits,
                    resolution: req.resolution,
                    samples: req.samples,
                    seed: req.seed,
                };
                Some(sample_workspace(&arm, &ws_req, limits)?.0)
            } else {
                None
            };
            let figure = ikarus_render::ArmFigure {
                goal: goal.map(|g| g.target()),
                workspace: workspace.as_ref(),
                ..ikarus_render::ArmFigure::new(&arm.chain, &pose)
            };
            svg_or_png(ikarus_render::arm_svg(&figure, width, height).map_err(|e| render_failed(&e))?, format)
        }
        Figure::Workspace => {
            let arm = load_arm(req.arm.clone(), limits)?;
            let ws_req = WorkspaceReq {
                arm: None,
                limits: req.limits,
                resolution: req.resolution,
                samples: req.samples,
                seed: req.seed,
            };
            let (workspace, _) = sample_workspace(&arm, &ws_req, limits)?;
            let caption = report::workspace_caption(&arm, &workspace);
            let figure = ikarus_render::ArmFigure {
                workspace: Some(&workspace),
                caption: Some(caption),
                ..ikarus_render::ArmFigure::new(&arm.chain, arm.chain.start_pose().angles())
            };
            svg_or_png(ikarus_render::arm_svg(&figure, width, height).map_err(|e| render_failed(&e))?, format)
        }
        Figure::Motion => {
            let arm = load_arm(req.arm.clone(), limits)?;
            let Some(goal) = req.goal.clone() else {
                return Err(ApiError::invalid("goal: required for the figure motion"));
            };
            let fps = req.fps;
            let animate = AnimateReq {
                arm: None,
                start_deg: req.start_deg,
                goal,
                via: req.via,
                options: req.options,
                ease: req.ease,
                frames: req.frames,
                duration: req.duration,
                fps: req.fps,
                from_solve: req.from_solve,
            };
            let motion = motion(&arm, &animate, limits)?;
            let target = animate.goal;
            let goal_point = Some(ikarus::Point2::new(target.x, target.y));
            let caption = motion.caption();
            if format == PictureFormat::Gif {
                let pixels = motion.animation.frames.len() as u64 * u64::from(width) * u64::from(height);
                if pixels > MAX_GIF_PIXELS {
                    return Err(ApiError::invalid(format!(
                        "frames, width, height: {} frames of {width}×{height} is {pixels} pixels, more than the cap of {MAX_GIF_PIXELS} for a GIF",
                        motion.animation.frames.len()
                    )));
                }
                let overlay = ikarus_render::Overlay {
                    goal: goal_point,
                    workspace: None,
                    show_reach: true,
                    caption: Some(caption),
                    trail: true,
                };
                let gif = ikarus_render::animation_gif(
                    &arm.chain,
                    &motion.animation,
                    &overlay,
                    width,
                    height,
                    fps.unwrap_or(DEFAULT_FPS),
                    &|_, _| {},
                )
                .map_err(|e| render_failed(&e))?;
                Ok((gif, "image/gif"))
            } else {
                let figure = ikarus_render::ArmFigure {
                    goal: goal_point,
                    caption: Some(caption),
                    ..ikarus_render::ArmFigure::of_animation(&arm.chain, &motion.animation)
                };
                svg_or_png(ikarus_render::arm_svg(&figure, width, height).map_err(|e| render_failed(&e))?, format)
            }
        }
    }
}
