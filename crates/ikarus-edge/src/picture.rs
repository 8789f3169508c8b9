//! Pictures, shared by the commands and the API: what to draw ([`Drawing`]) and the one path
//! that draws it ([`draw`]).

use ikarus::motion::Animation;
use ikarus::{Chain, Ease, Point2, RigTask};
use serde::Deserialize;

use crate::area::ReachableArea;
use crate::arm::Arm;
use crate::error::Error;
use crate::rig::Rig;

/// What a picture holds: from a file's extension, or a request's `format`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum PictureFormat {
    /// A PNG image.
    Png,
    /// An SVG drawing.
    Svg,
    /// An animated GIF: a motion's frames in turn.
    Gif,
}

impl PictureFormat {
    /// The media type of the bytes.
    pub fn content_type(self) -> &'static str {
        match self {
            PictureFormat::Png => "image/png",
            PictureFormat::Svg => "image/svg+xml",
            PictureFormat::Gif => "image/gif",
        }
    }

    /// The file extension, with its dot.
    pub fn extension(self) -> &'static str {
        match self {
            PictureFormat::Png => ".png",
            PictureFormat::Svg => ".svg",
            PictureFormat::Gif => ".gif",
        }
    }
}

/// What to draw.
pub enum Drawing<'a> {
    /// An arm in one pose, with an optional goal, shaded reachable area and caption.
    Arm {
        /// The arm.
        chain: &'a Chain,
        /// Its joint angles, radians.
        pose: &'a [f64],
        /// The goal, marked.
        goal: Option<Point2<f64>>,
        /// The reachable area, shaded under the arm.
        workspace: Option<ikarus_render::Reachable<'a>>,
        /// A line of text under the figure.
        caption: Option<String>,
    },
    /// A motion: its poses overlaid (SVG, PNG), or animated (GIF) at `fps`, with `layers`.
    Motion {
        /// The arm.
        chain: &'a Chain,
        /// Its frames, joint angles in radians.
        animation: &'a Animation,
        /// The final goal, marked.
        goal: Option<Point2<f64>>,
        /// A line of text under the figure.
        caption: String,
        /// The GIF's frames a second.
        fps: f64,
        /// What is drawn besides the arm and the goal.
        layers: MotionLayers<'a>,
    },
    /// A tracked path: the wanted path, the tip's trace, flips, and the poses as ghosts (SVG,
    /// PNG) or animated one per sample (GIF) at `fps`.
    Track {
        /// The arm.
        chain: &'a Chain,
        /// One pose per sample, joint angles in radians.
        poses: &'a [Vec<f64>],
        /// The wanted path, the tip's trace and the flips.
        layer: &'a ikarus_render::PathLayer,
        /// A line of text under the figure.
        caption: String,
        /// The GIF's frames a second.
        fps: f64,
    },
    /// An ease curve's position and velocity.
    Ease(Ease),
    /// A rig in one pose, with its goals, pins and (optionally) limit wedges.
    Skeleton(ikarus_render::SkeletonFigure<'a>),
    /// A rig's motion or track: the figure (its goals, pins, ranges) at the last frame's pose
    /// (SVG, PNG), or at every frame's (GIF) at `fps`.
    RigMotion {
        /// The rig with its goals, pins and ranges, drawn in the frames' poses.
        figure: ikarus_render::SkeletonFigure<'a>,
        /// Its frames, one angle per bone in radians.
        animation: &'a Animation,
        /// The GIF's frames a second.
        fps: f64,
    },
    /// A character's motion: its frames overlaid, the earlier as ghosts (SVG, PNG), or
    /// animated (GIF) at `fps`.
    CharacterMotion {
        /// The character's frames.
        figure: ikarus_render::CharacterMotionFigure<'a>,
        /// The GIF's frames a second.
        fps: f64,
    },
    /// A character's motion with its art (under the bones or alone): every frame animated
    /// (GIF) at `fps`, or the last frame's art under every frame's bones (SVG, PNG).
    CharacterArtMotion {
        /// The character's frames and art.
        figure: ikarus_render::CharacterArtMotion<'a>,
        /// The GIF's frames a second.
        fps: f64,
    },
}

/// What a motion's picture shows besides the arm and the goal. The command line's: no area,
/// the joints' traces with a cross per frame, no ghosts in a GIF ([`MotionLayers::default`]);
/// the playground's screen ([`MotionLayers::screen`], its GIF from `POST /api/render`): the
/// area it shades, the traces as lines, the ghosts, each as shown.
#[derive(Debug, Clone, Copy)]
pub struct MotionLayers<'a> {
    /// The reachable area to shade.
    pub workspace: Option<ikarus_render::Reachable<'a>>,
    /// The joints' traces, in this style; none when `None`.
    pub traces: Option<ikarus_render::TrailStyle>,
    /// Earlier poses as ghosts in a GIF, as the screen draws them.
    pub ghosts: bool,
}

impl Default for MotionLayers<'_> {
    fn default() -> Self {
        Self { workspace: None, traces: Some(ikarus_render::TrailStyle::Marks), ghosts: false }
    }
}

impl<'a> MotionLayers<'a> {
    /// The screen's layers: the area when it is shaded, the traces (as lines) and the ghosts
    /// when they are shown.
    pub fn screen(workspace: Option<&'a ReachableArea>, traces: bool, ghosts: bool) -> Self {
        Self {
            workspace: workspace.map(ReachableArea::layer),
            traces: traces.then_some(ikarus_render::TrailStyle::Lines),
            ghosts,
        }
    }
}

/// Draws `drawing` as `format`, `width` × `height` pixels; `progress(done, total)` hears about
/// the frames of a GIF. Only a motion animates: a GIF of anything else is the caller's bug.
pub fn draw(
    drawing: &Drawing<'_>,
    format: PictureFormat,
    width: u32,
    height: u32,
    progress: &dyn Fn(usize, usize),
) -> Result<Vec<u8>, Error> {
    let svg = match drawing {
        Drawing::Motion { chain, animation, goal, caption, fps, layers } if format == PictureFormat::Gif => {
            let overlay = ikarus_render::Overlay {
                goal: *goal,
                workspace: layers.workspace,
                show_reach: true,
                caption: Some(caption.clone()),
                trail: layers.traces.is_some(),
                trail_style: layers.traces.unwrap_or_default(),
                ghosts: layers.ghosts,
                path: None,
            };
            return ikarus_render::animation_gif(chain, animation, &overlay, width, height, *fps, progress)
                .map_err(|e| render_failed(&e));
        }
        Drawing::Motion { chain, animation, goal, caption, layers, .. } => {
            let figure = ikarus_render::ArmFigure {
                goal: *goal,
                caption: Some(caption.clone()),
                workspace: layers.workspace,
                traces: layers.traces.is_some(),
                ..ikarus_render::ArmFigure::of_animation(chain, animation)
            };
            ikarus_render::arm_svg(&figure, width, height)
        }
        Drawing::Track { chain, poses, layer, caption, fps } if format == PictureFormat::Gif => {
            let animation = poses_animation(poses, |q| ikarus::kinematics::joint_positions(chain, q));
            let overlay = ikarus_render::Overlay {
                show_reach: true,
                caption: Some(caption.clone()),
                path: Some(layer),
                ..ikarus_render::Overlay::default()
            };
            return ikarus_render::animation_gif(chain, &animation, &overlay, width, height, *fps, progress)
                .map_err(|e| render_failed(&e));
        }
        Drawing::Track { chain, poses, layer, caption, .. } => {
            let Some(last) = poses.last() else { return Err(render_failed(&"a track without samples")) };
            let every = poses.len().div_ceil(ikarus_render::MAX_ANIMATION_GHOSTS).max(1);
            let figure = ikarus_render::ArmFigure {
                ghosts: poses[..poses.len() - 1].iter().step_by(every).map(Vec::as_slice).collect(),
                caption: Some(caption.clone()),
                path: Some(layer),
                ..ikarus_render::ArmFigure::new(chain, last)
            };
            ikarus_render::arm_svg(&figure, width, height)
        }
        Drawing::Arm { chain, pose, goal, workspace, caption } => {
            let figure = ikarus_render::ArmFigure {
                goal: *goal,
                workspace: *workspace,
                caption: caption.clone(),
                // A reachable area within the limits shows the ranges that shape it.
                ranges: workspace.is_some_and(|w| w.limits()),
                ..ikarus_render::ArmFigure::new(chain, pose)
            };
            ikarus_render::arm_svg(&figure, width, height)
        }
        Drawing::Ease(ease) => ikarus_render::ease_svg(ease, width, height),
        Drawing::Skeleton(figure) => ikarus_render::skeleton_svg(figure, width, height),
        Drawing::RigMotion { figure, animation, fps } if format == PictureFormat::Gif => {
            return ikarus_render::skeleton_gif(figure, animation, width, height, *fps, progress)
                .map_err(|e| render_failed(&e));
        }
        Drawing::CharacterMotion { figure, fps } if format == PictureFormat::Gif => {
            return ikarus_render::character_gif(figure, width, height, *fps, progress).map_err(|e| render_failed(&e));
        }
        Drawing::CharacterMotion { figure, .. } => ikarus_render::character_motion_svg(figure, width, height),
        Drawing::CharacterArtMotion { figure, fps } => {
            return match format {
                PictureFormat::Gif => ikarus_render::character_art_gif(figure, width, height, *fps, progress),
                PictureFormat::Png => ikarus_render::character_art_motion_png(figure, width, height),
                PictureFormat::Svg => {
                    ikarus_render::character_art_motion_svg(figure, width, height).map(String::into_bytes)
                }
            }
            .map_err(|e| render_failed(&e));
        }
        Drawing::RigMotion { figure, animation, .. } => match animation.frames.last() {
            Some(last) => ikarus_render::skeleton_svg(
                &ikarus_render::SkeletonFigure { pose: &last.angles, ..figure.clone() },
                width,
                height,
            ),
            None => return Err(render_failed(&"a motion without frames")),
        },
    }
    .map_err(|e| render_failed(&e))?;
    match format {
        PictureFormat::Png => ikarus_render::svg_to_png(&svg).map_err(|e| render_failed(&e)),
        PictureFormat::Svg | PictureFormat::Gif => Ok(svg.into_bytes()),
    }
}

/// One animation frame per pose (a track's samples), evenly timed over [0, 1], each with the
/// points `joints` gives for it (an arm's joints, a rig's base and tips).
pub fn poses_animation(poses: &[Vec<f64>], joints: impl Fn(&[f64]) -> Vec<Point2<f64>>) -> Animation {
    let last = poses.len().saturating_sub(1).max(1) as f64;
    let frames = poses
        .iter()
        .enumerate()
        .map(|(k, q)| ikarus::AnimationFrame { time: k as f64 / last, angles: q.clone(), joints: joints(q) })
        .collect();
    Animation { frames, duration: 1.0, ease: Ease::Linear }
}

/// The figure `arm`: the arm in `pose`, with an optional goal and shaded workspace (the
/// API's figure `arm` and `ikarus render arm`).
pub fn arm_drawing<'a>(
    arm: &'a Arm,
    pose: &'a [f64],
    goal: Option<Point2<f64>>,
    workspace: Option<&'a ReachableArea>,
) -> Drawing<'a> {
    Drawing::Arm { chain: &arm.chain, pose, goal, workspace: workspace.map(ReachableArea::layer), caption: None }
}

/// The figure `workspace`: the arm in its start pose over its reachable area, with a caption
/// (the API's figure `workspace`, `ikarus workspace --out` and `ikarus render workspace`).
pub fn workspace_drawing<'a>(arm: &'a Arm, area: &'a ReachableArea) -> Drawing<'a> {
    Drawing::Arm {
        chain: &arm.chain,
        pose: arm.chain.start_pose().angles(),
        goal: None,
        workspace: Some(area.layer()),
        caption: Some(workspace_caption(arm, area)),
    }
}

/// The figure `motion`: an arm's motion (its `animation`, with its `caption`) towards `goal`,
/// animated at `fps` in a GIF, with `layers` (the API's figure `motion`, `ikarus animate --out`
/// and `ikarus render motion`). It takes what it draws, not the motion, which draws a rig's
/// motion itself (`crate::motion::Motion::drawing`).
pub fn motion_drawing<'a>(
    arm: &'a Arm,
    animation: &'a Animation,
    caption: String,
    goal: Option<Point2<f64>>,
    fps: f64,
    layers: MotionLayers<'a>,
) -> Drawing<'a> {
    Drawing::Motion { chain: &arm.chain, animation, goal, caption, fps, layers }
}

/// The figure of a rig at `pose` with the goals and pins of `task`, the limit wedges when
/// `ranges` (`ikarus solve --rig --out`, `ikarus render rig` and the API's figure `rig`).
pub fn rig_figure<'a>(
    rig: &'a Rig,
    pose: &'a [f64],
    task: &RigTask,
    ranges: bool,
    caption: Option<String>,
) -> ikarus_render::SkeletonFigure<'a> {
    let goals = task
        .goals
        .iter()
        .map(|g| ikarus_render::BoneGoal { bone: g.bone, position: g.goal.target(), angle: g.goal.orientation() })
        .collect();
    ikarus_render::SkeletonFigure {
        goals,
        pins: task.pins.iter().map(|p| p.bone).collect(),
        ranges,
        caption,
        ..ikarus_render::SkeletonFigure::new(&rig.skeleton, pose)
    }
}

/// The one-line caption of a workspace picture.
pub fn workspace_caption(arm: &Arm, area: &ReachableArea) -> String {
    let limits = if area.limits() && arm.chain.has_limits() { "with limits" } else { "no limits" };
    let how = match area {
        ReachableArea::Exact(_) => "exact",
        ReachableArea::Grid(_) => "sampled",
    };
    let annulus = ikarus::reach::Annulus::of(&arm.chain).area();
    format!("{} · {limits} · reachable area {:.2} of {annulus:.2} ({how})", arm.name, area.area())
}

/// Maps a render error to the CLI's run-time error.
pub fn render_failed(e: &impl std::fmt::Display) -> Error {
    Error::runtime(format!("rendering failed: {e}"))
}

/// A pose picture's failure: a number the picture cannot hold (a bone so far away that the
/// view overflows) or a size out of range is the input's; anything else is the drawing's.
#[must_use]
pub fn pose_drawn(e: ikarus_render::RenderError) -> Error {
    match e {
        ikarus_render::RenderError::NonFinite { .. } | ikarus_render::RenderError::Size { .. } => {
            Error::input(format!("cannot draw the pose: {e}"))
        }
        _ => Error::runtime(format!("cannot draw the pose: {e}")),
    }
}
