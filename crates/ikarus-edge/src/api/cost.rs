//! What a request's work costs at most, read from the typed request its job runs (one endpoint's
//! [`super::Request::cost`]), so that a server can tell quick requests from long ones before
//! the work starts.
//!
//! The estimate counts *link steps*: one link handled once in an iteration, tens of nanoseconds
//! (an iteration of an 8-link solve took 36 ns a link, a halving of its step less, in a release
//! build on the README's machine). It is the worst case the request's own fields allow, not a
//! guess at the usual case; what a request leaves out counts as the library's and the edge's
//! defaults (`ikarus::SolveOptions::default()`, the built-in arm, the motions' and paths'
//! defaults), read from them:
//!
//! - a solve: `links × max_iterations × (1 + restarts) × (1 + backtrack)` (every iteration may
//!   halve its step `backtrack` times, every restart may run to the cap); a rig's solve also
//!   times its goals and pins;
//! - `solve_batch`: a solve per goal; `animate`: a solve per via point and the goal, plus a pose
//!   per frame (with `keys`, one solve of its tracks and pins per frame); `track`: a solve per
//!   sample (12 in `plan`: candidates, seeds, polish);
//! - `workspace`: the grid's cells and samples × links, or for the exact region links² × 100
//!   (10 times more with limits); `reach`: that region's cost once, plus a solve per point;
//! - `render`: its pixels (times the frames of a GIF) plus the cost of what it draws;
//! - a character's job: reading its file, plus its poses (one for `pose`, a frame's for
//!   `animate` and `render`, a sample's for `track`), each costed from the character's bones
//!   and constraints ([`character`]); `rig/parse` and `arm/parse`: their bytes (a `.skel`'s
//!   bytes as the JSON text they may decode into at most: [`character::SKEL_TEXT_BYTES`]);
//!   `atlas/parse`: [`ATLAS_BYTE_COST`] a byte of its body (its page images are decoded: an
//!   atlas alone is quick, one with its images is long).

pub mod character;

use ikarus::{SolveOptions, TrackMode};

#[cfg(feature = "render")]
use super::figures::{CharacterFigureReq, MotionFigureReq, RenderReq};
use super::requests::{AnimateReq, ReachReq, SolveReq, TrackReq, WorkspaceReq};
use super::solve_batch::SolveBatchReq;
use crate::arm::ArmFile;
use crate::keys::{DEFAULT_KEY_FPS, KeysFile};
use crate::rig::RigFile;
use crate::settings::SolverSettings;
pub use character::{Character, Rules, file_bytes};

/// Link steps a byte of `/api/atlas/parse`'s body counts for: a compressed PNG byte decodes
/// into several pixels (a megabyte of images is far past a tenth of a second).
pub const ATLAS_BYTE_COST: f64 = 10.0;

/// Solves per sample of a planned track: 8 candidates, 2 seeds, 2 polish passes.
const PLAN_SOLVES: f64 = 12.0;
/// Cells per side of a sampled workspace when not given.
const GRID_RESOLUTION: f64 = 256.0;

/// The body a solve moves: its joints, and its file's `[solver]` table.
#[derive(Debug, Clone, Copy)]
pub struct Body<'a> {
    joints: f64,
    file: Option<&'a SolverSettings>,
    rig: bool,
}

impl<'a> Body<'a> {
    /// The request's body: its rig, else its arm, else the built-in arm.
    #[must_use]
    pub fn of(arm: Option<&'a ArmFile>, rig: Option<&'a RigFile>) -> Self {
        let joints = match (arm, rig) {
            (_, Some(rig)) => rig.bones.len() as f64,
            (Some(arm), None) => arm.links.len() as f64,
            (None, None) => seed_links(),
        };
        let file = arm.map(|a| &a.solver).or(rig.map(|r| &r.solver));
        Body { joints: joints.max(1.0), file, rig: rig.is_some() }
    }

    /// One solve placing every joint for each of `targets`, worst case: the iteration cap,
    /// restarts and step halvings of `options`, else of the file, else the library's defaults.
    #[must_use]
    pub fn solve_of(&self, options: Option<&SolverSettings>, targets: f64) -> f64 {
        let d = SolveOptions::default();
        let pick = |field: fn(&SolverSettings) -> Option<u32>, default: u32| {
            f64::from([options, self.file].into_iter().flatten().find_map(field).unwrap_or(default))
        };
        let iterations = pick(|s| s.max_iterations, d.max_iterations);
        let restarts = pick(|s| s.restarts, d.restarts.map_or(0, |r| r.attempts));
        let backtrack = pick(|s| s.backtrack, d.backtrack);
        self.joints * targets * iterations.max(1.0) * (1.0 + restarts) * (1.0 + backtrack)
    }

    /// One solve toward the request's goal (an arm's), or a rig's `goals` and `pins` together.
    #[must_use]
    pub fn solve(&self, options: Option<&SolverSettings>, goals: f64, pins: f64) -> f64 {
        self.solve_of(options, if self.rig { 1.0 + goals + pins } else { 1.0 })
    }

    /// The exact region of the body: joints² × 100, 10 times more with limits.
    #[must_use]
    pub fn region(&self, limits: Option<bool>) -> f64 {
        let limits = if limits == Some(true) { 10.0 } else { 1.0 };
        self.joints * self.joints * 100.0 * limits
    }

    /// The reachable area: the exact region, or the sampled grid's cells and samples × joints
    /// (the library samples 4096 · 4^k poses by default, k = min(joints − 1, 3)).
    #[must_use]
    pub fn area(&self, area: Area) -> f64 {
        if !(area.grid == Some(true) || area.resolution.is_some() || area.samples.is_some()) {
            return self.region(area.limits);
        }
        let resolution = area.resolution.map_or(GRID_RESOLUTION, f64::from);
        let n = self.joints;
        let samples = area.samples.map_or(4096.0 * 4f64.powf((n - 1.0).clamp(0.0, 3.0)), f64::from);
        resolution * resolution + samples * n
    }
}

/// A reachable area's fields (`..area` of the requests).
#[derive(Debug, Clone, Copy)]
pub struct Area {
    /// The area within the joint limits.
    pub limits: Option<bool>,
    /// The sampled grid instead of the exact region.
    pub grid: Option<bool>,
    /// The grid's cells per side.
    pub resolution: Option<u32>,
    /// The random poses sampled.
    pub samples: Option<u32>,
}

/// Links of the built-in arm (the seed's), when a request has no body.
fn seed_links() -> f64 {
    static LINKS: std::sync::LazyLock<f64> = std::sync::LazyLock::new(|| {
        crate::arm::Arm::parse(crate::arm::DEFAULT_ARM, "built-in arm").map_or(1.0, |arm| arm.chain.len() as f64)
    });
    *LINKS
}

fn count<T>(list: Option<&Vec<T>>) -> f64 {
    list.map_or(0.0, |l| l.len() as f64)
}

/// Frames of a motion: `frames`, else `duration` × `fps`, else the default's.
fn frames(frames: Option<u32>, duration: Option<f64>, fps: Option<f64>) -> f64 {
    match (frames, duration) {
        (Some(frames), _) => f64::from(frames),
        (None, Some(seconds)) => seconds * fps.unwrap_or(crate::motion::DEFAULT_FPS),
        (None, None) => f64::from(crate::motion::DEFAULT_FRAMES),
    }
    .max(0.0)
}

/// Frames of a keyed motion: the duration or the latest key time, whichever is later, × fps,
/// and one.
#[must_use]
pub fn key_frames(keys: &KeysFile) -> f64 {
    let fps = keys.fps.unwrap_or(DEFAULT_KEY_FPS).max(0.0);
    let tracks = keys.tracks.values().flatten().map(|k| k.time);
    let bends = keys.bends.values().flatten().map(|k| k.time);
    let rotations = keys.rotations.values().flatten().map(|k| k.time);
    let last = tracks.chain(bends).chain(rotations).fold(0.0f64, f64::max);
    (last.max(keys.duration.unwrap_or(0.0)) * fps).max(0.0) + 1.0
}

/// A keyed motion: one solve of its tracks and pins per frame, and a pose.
fn keyed(body: &Body<'_>, options: Option<&SolverSettings>, keys: &KeysFile) -> f64 {
    let effectors = (keys.tracks.len() + keys.pins.len()) as f64;
    key_frames(keys) * (body.solve_of(options, 1.0 + effectors) + body.joints)
}

/// `POST /api/solve`.
#[must_use]
pub fn solve(r: &SolveReq) -> f64 {
    Body::of(r.arm.as_ref(), r.rig.as_ref()).solve(r.options.as_ref(), count(r.goals.as_ref()), count(r.pins.as_ref()))
}

/// `POST /api/solve_batch`: a solve per goal.
#[must_use]
pub fn solve_batch(r: &SolveBatchReq) -> f64 {
    (r.goals.len() as f64).max(1.0) * Body::of(r.arm.as_ref(), None).solve(r.options.as_ref(), 0.0, 0.0)
}

/// `POST /api/animate` of an arm or a rig.
#[must_use]
pub fn animate<V>(r: &AnimateReq<V>) -> f64 {
    let body = Body::of(r.arm.as_ref(), r.rig.as_ref());
    if let Some(keys) = &r.keys {
        return keyed(&body, r.options.as_ref(), keys);
    }
    let solve = body.solve(r.options.as_ref(), count(r.goals.as_ref()), count(r.pins.as_ref()));
    (1.0 + r.via.len() as f64) * solve + frames(r.frames, r.duration, r.fps) * body.joints
}

/// `POST /api/track` of an arm or a rig.
#[must_use]
pub fn track(r: &TrackReq) -> f64 {
    let samples = match &r.path {
        Some(path) if !path.is_empty() => path.len() as f64,
        _ => r.samples.unwrap_or(crate::track::DEFAULT_SAMPLES) as f64,
    };
    let solves = if r.mode == Some(TrackMode::Follow) { 1.0 } else { PLAN_SOLVES };
    let body = Body::of(r.arm.as_ref(), r.rig.as_ref());
    samples * solves * body.solve(r.options.as_ref(), count(r.goals.as_ref()), count(r.pins.as_ref()))
}

/// `POST /api/workspace`.
#[must_use]
pub fn workspace(r: &WorkspaceReq) -> f64 {
    let area = Area { limits: r.limits, grid: r.grid, resolution: r.resolution, samples: r.samples };
    Body::of(r.arm.as_ref(), r.rig.as_ref()).area(area)
}

/// `POST /api/reach`: the region once, and a solve per point.
#[must_use]
pub fn reach(r: &ReachReq) -> f64 {
    let body = Body::of(r.arm.as_ref(), None);
    body.region(r.limits) + count(r.points.as_ref()).max(1.0) * body.solve(None, 0.0, 0.0)
}

#[cfg(feature = "render")]
/// `POST /api/render`: the picture's pixels, plus what it draws (a motion's solves and a
/// picture per frame of a GIF; a reachable area).
#[must_use]
pub fn render(r: &RenderReq) -> f64 {
    let (format, width, height) = r.picture();
    let side = |v: Option<u32>| f64::from(v.unwrap_or(super::render::DEFAULT_SIDE));
    let pixels = side(width) * side(height);
    let gif = format == Some(crate::picture::PictureFormat::Gif);
    let drawn = match r {
        RenderReq::Motion(m) => {
            let (motion, frames) = motion_figure(m);
            motion + if gif { frames } else { 1.0 } * pixels
        }
        RenderReq::CharacterMotion(c) => {
            let (motion, frames) = character_figure(c);
            motion + if gif { frames } else { 1.0 } * pixels
        }
        RenderReq::Body(_, b) if b.workspace == Some(true) => {
            let area = Area { limits: b.limits, grid: b.grid, resolution: b.resolution, samples: b.samples };
            Body::of(b.arm.as_ref(), b.rig.as_ref()).area(area)
        }
        RenderReq::Workspace(w) => {
            let area = Area { limits: w.limits, grid: w.grid, resolution: w.resolution, samples: w.samples };
            Body::of(w.arm.as_ref(), None).area(area)
        }
        RenderReq::Body(..) | RenderReq::Pose(_) | RenderReq::Ease(_) => 0.0,
    };
    pixels + drawn
}

/// Figure `motion` of an arm or a rig: the motion's cost and its frames.
#[cfg(feature = "render")]
fn motion_figure(m: &MotionFigureReq) -> (f64, f64) {
    let body = Body::of(m.arm.as_ref(), m.rig.as_ref());
    if let Some(keys) = &m.keys {
        return (keyed(&body, m.options.as_ref(), keys), key_frames(keys));
    }
    let frames = frames(m.frames, m.duration, m.fps);
    let solve = body.solve(m.options.as_ref(), 0.0, 0.0);
    ((1.0 + m.via.len() as f64) * solve + frames * body.joints, frames)
}

/// Figure `motion` of a character: reading it and a pose per frame, and its frames.
#[cfg(feature = "render")]
fn character_figure(c: &CharacterFigureReq) -> (f64, f64) {
    let frames = key_frames(&c.keys);
    let Some(character) = Character::of_request(c.rig.as_deref(), c.character.as_deref()) else { return (0.0, frames) };
    let rules = Rules::of(c.ik.as_deref(), 0.0, 0.0);
    (character.parse() + frames * character.pose(rules), frames)
}
