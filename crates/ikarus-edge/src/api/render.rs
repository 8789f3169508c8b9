//! `POST /api/render`: pictures of arms and rigs, motions (a character's keyed motion too),
//! workspaces and ease curves, drawn by `crate::picture` as the command line draws them.

use ikarus::{EaseKind, Interrupt};

use super::bodies::{load, load_arm, task};
use super::character_motion::keyed_motion;
use super::fields::{RIG_KEYS_GIVE, ease, goal, picture, pose_from_degrees, refuse_given, start_pose, stopped};
use super::figures::{BodyFigureReq, CharacterFigureReq, MotionFigureReq, RenderReq};
use super::jobs::{MotionFields, arm_motion};
use super::regions::reachable_area;
use super::requests::WorkspaceReq;
use super::wire::{Limits, Problem, Reply};
use crate::body::Body;
use crate::character::motion_art::{self, MotionArtError};
use crate::character::motion_files;
use crate::motion::DEFAULT_FPS;
use crate::picture::{
    Drawing, MotionLayers, PictureFormat, arm_drawing, draw, motion_drawing, rig_figure, workspace_drawing,
};
use crate::rig::Rig;
use ikarus_render::ArtPlacement;

/// Largest GIF, in frames × width × height pixels, so that one request cannot render for minutes.
const MAX_GIF_PIXELS: u64 = 100_000_000;
/// Picture size when the request gives none, and its range (as the command line's).
pub(super) const DEFAULT_SIDE: u32 = 800;
const SIDE_RANGE: std::ops::RangeInclusive<u32> = 16..=4096;

/// `POST /api/render`: a picture of `figure` (PNG, SVG or a GIF).
#[cfg(feature = "render")]
pub fn render(req: RenderReq, limits: &Limits, interrupt: &Interrupt) -> Result<Reply, Problem> {
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

/// A picture's format and size in pixels, checked: what every figure is drawn at.
#[derive(Debug, Clone, Copy)]
pub(super) struct Canvas {
    pub format: PictureFormat,
    pub width: u32,
    pub height: u32,
}

impl Canvas {
    /// `drawing` drawn on the canvas, stopped by `interrupt`.
    fn draw(self, drawing: &Drawing<'_>, interrupt: &Interrupt) -> Result<Vec<u8>, Problem> {
        picture(draw(drawing, self.format, self.width, self.height, &|_, _| {}), interrupt)
    }

    /// A GIF of `frames` frames on the canvas within [`gif_cap`]; any other format passes.
    fn gif_within_cap(self, frames: usize) -> Result<(), Problem> {
        if self.format == PictureFormat::Gif { gif_cap(frames, self.width, self.height) } else { Ok(()) }
    }
}

fn render_figure(req: RenderReq, limits: &Limits, interrupt: &Interrupt) -> Result<(Vec<u8>, PictureFormat), Problem> {
    let (format, width, height) = req.picture();
    let (width, height) = (side(width, "width")?, side(height, "height")?);
    let format = format.unwrap_or(PictureFormat::Png);
    if format == PictureFormat::Gif && !req.animates() {
        return Err(Problem::invalid("format = gif: only the figure motion animates (use png or svg)"));
    }
    let canvas = Canvas { format, width, height };
    let bytes = match req {
        RenderReq::Ease(r) => canvas.draw(&Drawing::Ease(ease(r.ease.as_ref(), EaseKind::Parent)?), interrupt)?,
        RenderReq::Body(_, r) => body_figure(*r, canvas, limits, interrupt)?,
        RenderReq::Workspace(r) => {
            let arm = load_arm(r.arm, limits)?;
            let ws_req = WorkspaceReq::area(r.limits, r.grid, r.resolution, r.samples, r.seed);
            let area = reachable_area(&arm, &ws_req, limits, interrupt)?;
            canvas.draw(&workspace_drawing(&arm, &area), interrupt)?
        }
        RenderReq::Motion(r) => motion_figure(&r, canvas, limits, interrupt)?,
        RenderReq::CharacterMotion(r) => character_figure(&r, canvas, limits, interrupt)?,
        RenderReq::Pose(r) => super::pose_figure::pose_figure(*r, (format, width, height), limits, interrupt)?,
    };
    Ok((bytes, format))
}

/// The figures `arm` and `rig`: the body in a pose (its start pose by default), an arm with
/// its goal and area, a rig with its goals and pins.
fn body_figure(r: BodyFigureReq, canvas: Canvas, limits: &Limits, interrupt: &Interrupt) -> Result<Vec<u8>, Problem> {
    let body = load(r.arm.clone(), r.rig.clone(), limits)?;
    match &body {
        Body::Chain(arm) => {
            let pose = start_pose(arm, r.pose_deg.as_deref(), "pose_deg")?;
            let goal = r.goal.as_ref().map(|g| goal(g, "goal")).transpose()?;
            let workspace = if r.workspace.unwrap_or(false) {
                let ws_req = WorkspaceReq::area(r.limits, r.grid, r.resolution, r.samples, r.seed);
                Some(reachable_area(arm, &ws_req, limits, interrupt)?)
            } else {
                None
            };
            canvas.draw(&arm_drawing(arm, &pose, goal.map(|g| g.target()), workspace.as_ref()), interrupt)
        }
        Body::Rig(rig) => {
            let (goals, pins) = (r.goals.as_deref().unwrap_or_default(), r.pins.as_deref().unwrap_or_default());
            let task = task(rig, goals, pins, None, false)?;
            let pose = rig_pose(rig, r.pose_deg.as_deref())?;
            let figure = rig_figure(rig, &pose, &task, r.limits.unwrap_or(false), None);
            let figure = ikarus_render::SkeletonFigure { labels: r.labels.unwrap_or(false), ..figure };
            canvas.draw(&Drawing::Skeleton(figure), interrupt)
        }
    }
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
    canvas: Canvas,
    limits: &Limits,
    interrupt: &Interrupt,
) -> Result<Vec<u8>, Problem> {
    if r.keys.is_some() || r.rig.is_some() {
        return keyed_figure(r, canvas, limits, interrupt);
    }
    let arm = load_arm(r.arm.clone(), limits)?;
    let Some(goal_req) = &r.goal else {
        return Err(Problem::invalid("goal: required for the figure motion"));
    };
    let motion = arm_motion(&arm, &MotionFields::of_figure(r), &r.via, goal_req, limits, interrupt)?;
    stopped(interrupt)?;
    let animation = &motion.motion.animation;
    canvas.gif_within_cap(animation.frames.len())?;
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
    canvas.draw(&motion_drawing(&arm, animation, motion.caption(), goal, fps, layers), interrupt)
}

/// Figure `motion` of `POST /api/render` with a rig and its `keys`: the keyed motion drawn as
/// `ikarus render motion --rig FILE --keys KEYS.json --out` draws it; the fields of an arm's
/// motion and of its area refused, naming them.
fn keyed_figure(
    r: &MotionFigureReq,
    canvas: Canvas,
    limits: &Limits,
    interrupt: &Interrupt,
) -> Result<Vec<u8>, Problem> {
    let Some(keys) = &r.keys else {
        return Err(Problem::invalid("rig: the figure motion draws a rig's keyed motion: give its keys"));
    };
    let given = [
        ("goal", r.goal.is_some()),
        ("via", !r.via.is_empty()),
        ("start_deg", r.start_deg.is_some()),
        ("frames", r.frames.is_some()),
        ("duration", r.duration.is_some()),
        ("fps", r.fps.is_some()),
        ("ease", r.ease.is_some()),
        ("interpolation", r.interpolation.is_some()),
        ("from_solve", r.from_solve),
        ("workspace", r.workspace),
        ("limits", r.limits.is_some()),
        ("grid", r.grid.is_some()),
        ("resolution", r.resolution.is_some()),
        ("samples", r.samples.is_some()),
        ("seed", r.seed.is_some()),
        ("traces", r.traces.is_some()),
        ("ghosts", r.ghosts),
    ];
    refuse_given(&given, RIG_KEYS_GIVE)?;
    let rig = match &r.rig {
        Some(file) => super::bodies::load_rig(file.clone(), limits)?,
        None => super::bodies::load_arm_as_rig(r.arm.clone(), limits)?,
    };
    let (motion, _, limits_on) = super::keyed::keyed_motion(&rig, keys, r.options.as_ref(), limits, interrupt)?;
    canvas.gif_within_cap(motion.animation.frames.len())?;
    canvas.draw(&motion.drawing(&rig, limits_on), interrupt)
}

/// Figure `motion` of `POST /api/render` with a character and its `keys`: the keyed motion
/// drawn as `ikarus animate --rig FILE.json --keys KEYS.json [--animation A] [--skin S] [--atlas
/// FILE.atlas [--art-only]] --out` draws it, the same bytes: with `atlas` (sent with its page
/// images), every frame's art under its bones, or alone with `art_only`
/// ([`crate::character::motion_art`]).
fn character_figure(
    r: &CharacterFigureReq,
    canvas: Canvas,
    limits: &Limits,
    interrupt: &Interrupt,
) -> Result<Vec<u8>, Problem> {
    let stored = super::pose::stored_character(r.rig.as_deref(), r.character.as_deref(), limits)?;
    let loaded = &stored.loaded;
    let atlas = r.atlas.as_deref().map(super::atlases::stored_atlas).transpose()?;
    let art_only = r.art_only.unwrap_or(false);
    super::atlases::drawable(atlas.as_deref(), art_only)?;
    let ik = (r.ik.as_deref(), r.ik_file.as_deref());
    let mut motion = keyed_motion(loaded, &r.keys, r.animation.clone(), ik, (limits, interrupt))?;
    motion.physics = super::character_motion::physics(r.physics);
    motion.skin.clone_from(&r.skin);
    canvas.gif_within_cap(motion.frame_count())?;
    let Some(atlas) = atlas else {
        let poses = super::character_motion::posed(motion.poses(), &motion)?;
        return canvas.draw(&motion_files::drawing(&motion, &poses), interrupt);
    };
    let drawn = motion_art::posed_with_art(&motion, &atlas.art).map_err(|e| match e {
        MotionArtError::Pose(m) => {
            motion.interrupt.as_ref().and_then(|i| stopped(i).err()).unwrap_or_else(|| Problem::from(m))
        }
        MotionArtError::Art(m) => Problem::invalid(format!("atlas: {m}")),
        MotionArtError::Cap(m) => Problem::invalid(format!("keys: {m} (keys that end sooner or a lower fps)")),
    })?;
    let placement = if art_only { ArtPlacement::Alone } else { ArtPlacement::UnderBones };
    canvas.draw(&motion_art::art_drawing(&motion, &drawn.poses, drawn.arts, placement), interrupt)
}

#[cfg(test)]
#[path = "render_art_tests.rs"]
mod art_tests;
