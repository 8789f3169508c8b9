//! `POST /api/render`: pictures of arms and rigs, motions, workspaces and ease curves, drawn
//! by `crate::picture` as the command line draws them.

use ikarus::{EaseKind, Interrupt};

use super::bodies::{load, load_arm, task};
use super::fields::{ease, goal, picture, pose_from_degrees, start_pose, stopped};
use super::figures::{BodyFigureReq, MotionFigureReq, RenderReq};
use super::jobs::{MotionFields, arm_motion};
use super::regions::reachable_area;
use super::requests::WorkspaceReq;
use super::{Limits, Problem, Reply};
use crate::body::Body;
use crate::motion::DEFAULT_FPS;
use crate::picture::{
    Drawing, MotionLayers, PictureFormat, arm_drawing, draw, motion_drawing, rig_figure, workspace_drawing,
};
use crate::rig::Rig;

/// Largest GIF, in frames × width × height pixels, so that one request cannot render for minutes.
const MAX_GIF_PIXELS: u64 = 100_000_000;
/// Picture size when the request gives none, and its range (as the command line's).
const DEFAULT_SIDE: u32 = 800;
const SIDE_RANGE: std::ops::RangeInclusive<u32> = 16..=4096;

/// `POST /api/render`: a picture of `figure` (PNG, SVG or a GIF).
#[cfg(feature = "render")]
pub fn render(body: &[u8], limits: &Limits, interrupt: &Interrupt) -> Result<Reply, Problem> {
    let req = RenderReq::parse(body)?;
    // A GIF being encoded checks the interrupt before each frame.
    let (bytes, format) = ikarus_render::with_interrupt(interrupt, || render_figure(req, limits, interrupt))?;
    Ok(Reply { content_type: format.content_type(), body: bytes })
}

pub(super) fn side(value: Option<u32>, field: &str) -> Result<u32, Problem> {
    let v = value.unwrap_or(DEFAULT_SIDE);
    if SIDE_RANGE.contains(&v) {
        Ok(v)
    } else {
        Err(Problem::invalid(format!(
            "{field} = {v}: must be between {} and {} pixels",
            SIDE_RANGE.start(),
            SIDE_RANGE.end()
        )))
    }
}

fn render_figure(req: RenderReq, limits: &Limits, interrupt: &Interrupt) -> Result<(Vec<u8>, PictureFormat), Problem> {
    let (format, width, height) = req.picture();
    let (width, height) = (side(width, "width")?, side(height, "height")?);
    let format = format.unwrap_or(PictureFormat::Png);
    if format == PictureFormat::Gif && !matches!(req, RenderReq::Motion(_)) {
        return Err(Problem::invalid("format = gif: only the figure motion animates (use png or svg)"));
    }
    let bytes = match req {
        RenderReq::Ease(r) => picture(
            draw(&Drawing::Ease(ease(r.ease.as_ref(), EaseKind::Parent)?), format, width, height, &|_, _| {}),
            interrupt,
        )?,
        RenderReq::Body(_, r) => body_figure(*r, format, width, height, limits, interrupt)?,
        RenderReq::Workspace(r) => {
            let arm = load_arm(r.arm, limits)?;
            let ws_req = WorkspaceReq::area(r.limits, r.grid, r.resolution, r.samples, r.seed);
            let area = reachable_area(&arm, &ws_req, limits, interrupt)?;
            picture(draw(&workspace_drawing(&arm, &area), format, width, height, &|_, _| {}), interrupt)?
        }
        RenderReq::Motion(r) => motion_figure(&r, format, width, height, limits, interrupt)?,
    };
    Ok((bytes, format))
}

/// The figures `arm` and `rig`: the body in a pose (its start pose by default), an arm with
/// its goal and area, a rig with its goals and pins.
fn body_figure(
    r: BodyFigureReq,
    format: PictureFormat,
    width: u32,
    height: u32,
    limits: &Limits,
    interrupt: &Interrupt,
) -> Result<Vec<u8>, Problem> {
    let body = load(r.arm.clone(), r.rig.clone(), limits)?;
    let drawn = match &body {
        Body::Chain(arm) => {
            let pose = start_pose(arm, r.pose_deg.as_deref(), "pose_deg")?;
            let goal = r.goal.as_ref().map(|g| goal(g, "goal")).transpose()?;
            let workspace = if r.workspace.unwrap_or(false) {
                let ws_req = WorkspaceReq::area(r.limits, r.grid, r.resolution, r.samples, r.seed);
                Some(reachable_area(arm, &ws_req, limits, interrupt)?)
            } else {
                None
            };
            let drawing = arm_drawing(arm, &pose, goal.map(|g| g.target()), workspace.as_ref());
            draw(&drawing, format, width, height, &|_, _| {})
        }
        Body::Rig(rig) => {
            let (goals, pins) = (r.goals.as_deref().unwrap_or_default(), r.pins.as_deref().unwrap_or_default());
            let task = task(rig, goals, pins, None, false)?;
            let pose = rig_pose(rig, r.pose_deg.as_deref())?;
            let figure = rig_figure(rig, &pose, &task, r.limits.unwrap_or(false), None);
            let figure = ikarus_render::SkeletonFigure { labels: r.labels.unwrap_or(false), ..figure };
            draw(&Drawing::Skeleton(figure), format, width, height, &|_, _| {})
        }
    };
    picture(drawn, interrupt)
}

/// A rig's pose from `pose_deg`, its start pose without. Degrees say nothing about a slide: a
/// rig with prismatic joints is drawn in the pose its bones' `angle_deg` and `extension` give.
fn rig_pose(rig: &Rig, pose_deg: Option<&[f64]>) -> Result<Vec<f64>, Problem> {
    if pose_deg.is_some() {
        for (j, joint) in rig.skeleton.joints().iter().enumerate() {
            match joint {
                ikarus::Joint::Revolute => {}
                ikarus::Joint::Prismatic { .. } => {
                    return Err(Problem::invalid(format!(
                        "pose_deg: bone {:?} is prismatic (its value is a length, not an angle); give the pose as the bones' angle_deg and extension",
                        rig.skeleton.name(j)
                    )));
                }
            }
        }
    }
    pose_from_degrees(rig.skeleton.start_angles(), rig.skeleton.limits(), pose_deg, "pose_deg")
}

/// A GIF of `frames` frames of `width` × `height` within [`MAX_GIF_PIXELS`].
pub(super) fn gif_cap(frames: usize, width: u32, height: u32) -> Result<(), Problem> {
    let pixels = frames as u64 * u64::from(width) * u64::from(height);
    if pixels > MAX_GIF_PIXELS {
        return Err(Problem::invalid(format!(
            "frames, width, height: {frames} frames of {width}×{height} is {pixels} pixels, more than the cap of {MAX_GIF_PIXELS} for a GIF"
        )));
    }
    Ok(())
}

fn motion_figure(
    r: &MotionFigureReq,
    format: PictureFormat,
    width: u32,
    height: u32,
    limits: &Limits,
    interrupt: &Interrupt,
) -> Result<Vec<u8>, Problem> {
    if r.keys.is_some() || r.rig.is_some() {
        return super::keyed::figure(r, format, width, height, limits, interrupt);
    }
    let arm = load_arm(r.arm.clone(), limits)?;
    let Some(goal_req) = &r.goal else {
        return Err(Problem::invalid("goal: required for the figure motion"));
    };
    let motion = arm_motion(&arm, &MotionFields::of_figure(r), &r.via, goal_req, limits, interrupt)?;
    stopped(interrupt)?;
    let animation = &motion.motion.animation;
    if format == PictureFormat::Gif {
        gif_cap(animation.frames.len(), width, height)?;
    }
    let area = if r.workspace {
        let on = r.limits.or_else(|| r.options.as_ref().and_then(|o| o.limits));
        let ws_req = WorkspaceReq::area(on, r.grid, r.resolution, r.samples, r.seed);
        Some(reachable_area(&arm, &ws_req, limits, interrupt)?)
    } else {
        None
    };
    let goal = Some(ikarus::Point2::new(goal_req.x, goal_req.y));
    let layers = MotionLayers::screen(area.as_ref(), r.traces.unwrap_or(true), r.ghosts);
    let fps = r.fps.unwrap_or(DEFAULT_FPS);
    let drawing = motion_drawing(&arm, animation, motion.caption(), goal, fps, layers);
    picture(draw(&drawing, format, width, height, &|_, _| {}), interrupt)
}
