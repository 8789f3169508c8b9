//! The rig motion workflow shared by `ikarus animate --rig` and `POST /api/animate` with `rig`:
//! each goal set (via sets, then the final one) solved in turn as a rig task, from the pose the
//! previous one ended at, and the poses eased into frames by the library
//! ([`ikarus::motion::through_rig_tasks`]); its JSON shape (angles and tips keyed by bone name)
//! and its pictures (the skeleton at the last pose, or a GIF of every frame).

use ikarus::motion::{Animation, Interpolation, MotionOptions, Route, Timing, through_rig_tasks};
use ikarus::{Ease, RigTask, SolveOptions, Solver};
use serde::Serialize;

use crate::error::CliError;
use crate::picture::{Drawing, rig_figure};
use crate::report::{ByName, EffectorJson, Extensions, relative_degrees};
use crate::rig::Rig;

/// What a rig motion request asks for once its values are checked.
pub struct RigMotionPlan<'a> {
    pub rig: &'a Rig,
    /// The pose the motion starts from, radians, one per bone.
    pub start: Vec<f64>,
    /// The goal sets in order: the via sets, then the final one.
    pub tasks: Vec<RigTask>,
    pub options: SolveOptions,
    pub timing: Timing,
    pub ease: Ease,
    pub interpolation: Interpolation,
    /// Follow the solver's recorded path instead of moving through the solved poses.
    pub from_solve: bool,
}

/// A computed rig motion, with the options and tasks it was solved with.
pub struct RigMotion {
    pub options: SolveOptions,
    pub tasks: Vec<RigTask>,
    pub motion: ikarus::motion::RigMotion,
}

impl RigMotionPlan<'_> {
    /// Solves each task in turn and eases the poses into a motion; a problem (a method that
    /// solves chains only, a bad task) is bad input, in the library's words.
    pub fn run(self) -> Result<RigMotion, CliError> {
        let mut solver = Solver::new(self.options).map_err(|e| CliError::input(e.to_string()))?;
        let route = if self.from_solve { Route::Recorded } else { Route::Keyframes };
        let options = MotionOptions::new(self.timing, self.ease).with_interpolation(self.interpolation);
        let skeleton = &self.rig.skeleton;
        let names = skeleton.names();
        let motion =
            through_rig_tasks(&mut solver, skeleton, &self.start, &self.tasks, route, options).map_err(|e| {
                CliError::input(crate::motion::describe(&e, |b| format!("bone {} ({:?})", b + 1, names[b])))
            })?;
        Ok(RigMotion { options: solver.options().clone(), tasks: self.tasks, motion })
    }
}

impl RigMotion {
    /// The one-line caption of the motion's pictures.
    pub fn caption(&self, rig: &Rig) -> String {
        let solves = &self.motion.solves;
        let animation = &self.motion.animation;
        let last = solves.last().expect("at least the final goal set was solved");
        let iterations: u32 = solves.iter().map(|s| s.iterations).sum();
        format!(
            "{} · {} · {} · {} iterations · error {:.1e} · {} frames, {} ease",
            rig.name,
            self.options.method.name(),
            last.status,
            iterations,
            last.error,
            animation.frames.len(),
            animation.ease.name()
        )
    }

    /// The drawing of the motion: the skeleton at its last pose with every goal set's goals and
    /// the final pins (SVG, PNG), or every frame (GIF) at `fps`.
    pub fn drawing<'a>(&'a self, rig: &'a Rig, fps: f64) -> Drawing<'a> {
        let last = self.motion.animation.frames.last().expect("an animation has frames");
        let task = self.tasks.last().expect("at least the final goal set");
        let mut figure = rig_figure(
            rig,
            &last.angles,
            task,
            self.options.limits != ikarus::LimitMode::Ignore,
            Some(self.caption(rig)),
        );
        // The via sets' goals too, where the final set has none on the same bone.
        for via in &self.tasks[..self.tasks.len() - 1] {
            for g in &via.goals {
                figure.goals.push(ikarus_render::BoneGoal {
                    bone: g.bone,
                    position: g.goal.target(),
                    angle: g.goal.orientation(),
                });
            }
        }
        Drawing::RigMotion { figure, animation: &self.motion.animation, fps }
    }

    /// The JSON object of the motion.
    pub fn json<'a>(&'a self, rig: &'a Rig) -> RigAnimateJson<'a> {
        let s = &rig.skeleton;
        let animation = &self.motion.animation;
        RigAnimateJson {
            rig: &rig.name,
            ease: animation.ease.name(),
            duration: animation.duration,
            solves: self
                .motion
                .solves
                .iter()
                .map(|r| RigMotionSolveJson {
                    status: r.status.as_str(),
                    iterations: r.iterations,
                    error: r.error,
                    effectors: r.effectors.iter().map(|e| EffectorJson::of(s, e)).collect(),
                })
                .collect(),
            frames: animation.frames.iter().map(|f| RigFrameJson::of(s, f)).collect(),
        }
    }
}

/// How one goal set of a rig motion was solved.
#[derive(Serialize)]
pub struct RigMotionSolveJson<'a> {
    /// `reached` only if every effector is.
    pub status: &'static str,
    pub iterations: u32,
    /// The largest effector error.
    pub error: f64,
    /// The set's goals in order, then its pins.
    pub effectors: Vec<EffectorJson<'a>>,
}

/// One frame of a rig motion: bone name → angle (degrees, from its parent's direction), prismatic
/// bone name → displacement (only when the rig has prismatic joints), bone name → tip.
#[derive(Serialize)]
pub struct RigFrameJson<'a> {
    pub time: f64,
    pub angles_deg: ByName<'a, f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub extensions: Option<Extensions<'a>>,
    pub joints: ByName<'a, [f64; 2]>,
}

impl<'a> RigFrameJson<'a> {
    /// A frame whose `joints` are the base, then every bone's tip ([`ikarus::motion::Body`]).
    pub fn of(s: &'a ikarus::Skeleton, f: &ikarus::AnimationFrame) -> Self {
        let names = s.names();
        Self {
            time: f.time,
            angles_deg: ByName { names, values: relative_degrees(s, &f.angles) },
            extensions: Extensions::of(s, &f.angles),
            joints: ByName { names, values: f.joints[1..].iter().map(|p| [p.x, p.y]).collect() },
        }
    }
}

/// A rig motion: `ikarus animate --rig` (JSON) and `POST /api/animate` with `rig`.
#[derive(Serialize)]
pub struct RigAnimateJson<'a> {
    pub rig: &'a str,
    pub ease: &'static str,
    pub duration: f64,
    /// One per goal set: the via sets, then the final one.
    pub solves: Vec<RigMotionSolveJson<'a>>,
    pub frames: Vec<RigFrameJson<'a>>,
}

/// An animation of one frame per pose, evenly timed over [0, 1] (a track's samples), with the
/// skeleton's points.
pub fn poses_animation(rig: &Rig, poses: &[Vec<f64>]) -> Animation {
    use ikarus::motion::Body;
    let last = poses.len().saturating_sub(1).max(1) as f64;
    let frames = poses
        .iter()
        .enumerate()
        .map(|(k, q)| ikarus::AnimationFrame {
            time: k as f64 / last,
            angles: q.clone(),
            joints: rig.skeleton.frame_points(q),
        })
        .collect();
    Animation { frames, duration: 1.0, ease: Ease::Linear }
}
