//! The motion workflow shared by `ikarus animate` and `POST /api/animate` / `/api/render`, one
//! for both bodies: the timing rules, the stops (an arm's via points and goal, a rig's goal
//! sets) solved in turn from the pose the previous one ended at, and the poses eased into
//! frames by the library. [`MotionPlan::run`] is the workflow; what differs between an arm and
//! a rig — the library's entry point ([`ikarus::motion::through_goals`],
//! [`ikarus::motion::through_rig_tasks`]) and how a message names a joint — is the body's
//! [`MotionBody`] impl. A rig motion's JSON shape (angles and tips keyed by bone name) is
//! `crate::report::motion`'s; its picture is [`Motion::drawing`].

use ikarus::motion::{
    Animation, GoalMotion, GoalMotionError, Interpolation, MotionError, MotionOptions, Route, Timing, through_goals,
    through_rig_tasks,
};
use ikarus::number::Num;
use ikarus::{Ease, Goal, GoalError, RigTask, SolveOptions, Solver};

use crate::arm::Arm;
use crate::error::Error;
use crate::picture::{Drawing, rig_figure};
use crate::rig::Rig;

/// Frames of a motion when neither frames nor a duration is given.
pub const DEFAULT_FRAMES: u32 = 60;
/// Frame rate of a motion's duration and its GIF when none is given.
pub const DEFAULT_FPS: f64 = 30.0;

/// A timing value out of its rules; each edge words it with its own field names.
#[derive(Debug)]
pub enum TimingProblem {
    /// `field` = `value` breaks the rule `message`.
    Value {
        /// The value's name: `frames`, `duration` or `fps`.
        field: &'static str,
        /// The value as given, written for a message.
        value: String,
        /// The rule it breaks (`must be greater than 0`).
        message: &'static str,
    },
    /// Both frames and a duration were given.
    Both,
}

/// The one rule for a motion's timing: `frames` (at least 2), or `duration` (> 0 seconds) at
/// `fps` ([`DEFAULT_FPS`]), else [`DEFAULT_FRAMES`] frames; `fps` is in (0, 100].
pub fn timing(frames: Option<u32>, duration: Option<f64>, fps: Option<f64>) -> Result<Timing, TimingProblem> {
    if let Some(fps) = fps {
        if !(fps > 0.0 && fps <= 100.0) {
            let message = "must be greater than 0 and at most 100";
            return Err(TimingProblem::Value { field: "fps", value: ikarus::number::Num(fps).to_string(), message });
        }
    }
    match (frames, duration) {
        (Some(_), Some(_)) => Err(TimingProblem::Both),
        (Some(n), None) if n < 2 => Err(TimingProblem::Value {
            field: "frames",
            value: n.to_string(),
            message: "a motion needs at least 2 frames",
        }),
        (Some(n), None) => Ok(Timing::Frames(n as usize)),
        (None, Some(seconds)) if seconds <= 0.0 => Err(TimingProblem::Value {
            field: "duration",
            value: ikarus::number::Num(seconds).to_string(),
            message: "must be greater than 0",
        }),
        (None, Some(seconds)) => Ok(Timing::Duration { seconds, fps: fps.unwrap_or(DEFAULT_FPS) }),
        (None, None) => Ok(Timing::Frames(DEFAULT_FRAMES as usize)),
    }
}

/// The goals of a motion: each via point (a position), then the final goal. A bad via point
/// is reported with its index, from 0.
pub fn goals(via: &[[f64; 2]], goal: Goal) -> Result<Vec<Goal>, (usize, GoalError)> {
    let mut goals = Vec::with_capacity(via.len() + 1);
    for (i, &[x, y]) in via.iter().enumerate() {
        goals.push(Goal::position(x, y).map_err(|e| (i, e))?);
    }
    goals.push(goal);
    Ok(goals)
}

/// A body a motion moves: what it passes through, and the library's motion of it.
pub trait MotionBody {
    /// One stop: an arm's goal, a rig's goal set.
    type Stop;
    /// The library's motion: the solves and the animation.
    type Solved;

    /// Solves for each stop in turn and eases the poses, the problem in the edges' words.
    fn through(
        &self,
        solver: &mut Solver,
        start: &[f64],
        stops: &[Self::Stop],
        route: Route,
        options: MotionOptions,
    ) -> Result<Self::Solved, Error>;
}

impl MotionBody for Arm {
    type Stop = Goal;
    type Solved = GoalMotion;

    fn through(
        &self,
        solver: &mut Solver,
        start: &[f64],
        goals: &[Goal],
        route: Route,
        options: MotionOptions,
    ) -> Result<GoalMotion, Error> {
        through_goals(solver, &self.chain, start, goals, route, options)
            .map_err(|e| Error::input(describe(&e, |joint| format!("joint {}", joint + 1))))
    }
}

impl MotionBody for Rig {
    type Stop = RigTask;
    type Solved = ikarus::motion::RigMotion;

    fn through(
        &self,
        solver: &mut Solver,
        start: &[f64],
        tasks: &[RigTask],
        route: Route,
        options: MotionOptions,
    ) -> Result<ikarus::motion::RigMotion, Error> {
        let names = self.skeleton.names();
        through_rig_tasks(solver, &self.skeleton, start, tasks, route, options)
            .map_err(|e| Error::input(describe(&e, |b| format!("bone {} ({:?})", b + 1, names[b]))))
    }
}

/// What a motion request asks for once its values are checked.
pub struct MotionPlan<'a, B: MotionBody> {
    /// The arm or rig that moves.
    pub body: &'a B,
    /// The pose the motion starts from, radians, one value per joint.
    pub start: Vec<f64>,
    /// The stops in order: an arm's via points then its goal, a rig's via sets then its goal set.
    pub stops: Vec<B::Stop>,
    /// The solver's options for every stop's solve.
    pub options: SolveOptions,
    /// How many frames, or how long at what frame rate ([`timing`]).
    pub timing: Timing,
    /// The easing of time between the poses.
    pub ease: Ease,
    /// The path through the poses: spline (the default) or polyline.
    pub interpolation: Interpolation,
    /// Follow the solver's recorded path instead of moving straight between solved poses.
    pub from_solve: bool,
}

/// A computed motion, with the options and the stops it was solved with.
pub struct Motion<B: MotionBody> {
    /// The options the stops were solved with.
    pub options: SolveOptions,
    /// The stops in order, as in the plan.
    pub stops: Vec<B::Stop>,
    /// The library's motion: each stop's solve and the eased frames.
    pub motion: B::Solved,
}

impl<B: MotionBody> MotionPlan<'_, B> {
    /// Solves for each stop, each from the previous pose, and eases the poses into a motion,
    /// with the same interpolation whether the poses are the solved ones or every pose the
    /// solver recorded; a problem (a method that solves chains only, a bad stop) is bad input.
    pub fn run(self) -> Result<Motion<B>, Error> {
        let mut solver = Solver::new(self.options).map_err(|e| Error::input(e.to_string()))?;
        let route = if self.from_solve { Route::Recorded } else { Route::Keyframes };
        let options = MotionOptions::new(self.timing, self.ease).with_interpolation(self.interpolation);
        let motion = self.body.through(&mut solver, &self.start, &self.stops, route, options)?;
        Ok(Motion { options: solver.options().clone(), stops: self.stops, motion })
    }
}

/// A motion's problem in the words of the edges: a pose outside its joint's limits in degrees,
/// the joint named by `joint` (from its index: `joint 1`, `bone 2 ("spine")`), the start pose
/// (keyframe 0, the only one a request gives: the others are solved inside the limits) as
/// `start_deg`; every other problem in the library's words.
///
/// `start_deg: joint 1 at 73.6° lies outside its limits [-45°, 45°]`
pub fn describe(e: &GoalMotionError, joint: impl Fn(usize) -> String) -> String {
    match e {
        GoalMotionError::Motion(MotionError::OutsideLimits { index, joint: j, value, min, max }) => {
            let pose = if *index == 0 { "start_deg".to_owned() } else { format!("keyframes[{index}]") };
            let [lo, hi] = [limit_degrees(*min), limit_degrees(*max)];
            format!(
                "{pose}: {} at {}° lies outside its limits [{}°, {}°]",
                joint(*j),
                outside_degrees(*value, lo, hi),
                Num(lo),
                Num(hi)
            )
        }
        other => other.to_string(),
    }
}

/// A limit (radians) in degrees to a millionth of a degree: a limit given in degrees reads back
/// as given (−45, not −45.00000000000001).
fn limit_degrees(radians: f64) -> f64 {
    let d = radians.to_degrees();
    if d.abs() < 1e9 { (d * 1e6).round() / 1e6 } else { d }
}

/// An angle (radians) outside the limits `[lo, hi]` (degrees) in degrees: to a tenth of a
/// degree (73.6), or as many more places as it takes not to read as one of the limits (45.04
/// outside 45, not 45.0); huge angles in [`Num`]'s short form.
fn outside_degrees(radians: f64, lo: f64, hi: f64) -> String {
    let d = radians.to_degrees();
    if !d.is_finite() || d.abs() >= 1e9 {
        return Num(d).to_string();
    }
    for places in 1..=6 {
        let text = format!("{d:.places$}");
        let shown: f64 = text.parse().unwrap_or(d);
        if shown < lo || shown > hi {
            let text = text.trim_end_matches('0').trim_end_matches('.');
            return if text == "-0" { "0".to_owned() } else { text.to_owned() };
        }
    }
    Num(d).to_string()
}

/// The one-line caption of a motion's pictures: `method · status · iterations · error · frames, ease`.
fn caption(
    options: &SolveOptions,
    status: ikarus::Status,
    iterations: u32,
    error: f64,
    animation: &Animation,
) -> String {
    format!(
        "{} · {} · {} iterations · error {:.1e} · {} frames, {} ease",
        options.method.name(),
        status,
        iterations,
        error,
        animation.frames.len(),
        animation.ease.name()
    )
}

impl Motion<Arm> {
    /// The one-line caption of the motion's pictures.
    pub fn caption(&self) -> String {
        let solves = &self.motion.solves;
        let last = solves.last().expect("at least the goal was solved");
        let iterations: u32 = solves.iter().map(|s| s.iterations).sum();
        caption(&self.options, last.status, iterations, last.error, &self.motion.animation)
    }
}

impl Motion<Rig> {
    /// The one-line caption of the motion's pictures, after the rig's name.
    pub fn caption(&self, rig: &Rig) -> String {
        let solves = &self.motion.solves;
        let last = solves.last().expect("at least the final goal set was solved");
        let iterations: u32 = solves.iter().map(|s| s.iterations).sum();
        format!(
            "{} · {}",
            rig.name,
            caption(&self.options, last.status, iterations, last.error, &self.motion.animation)
        )
    }

    /// The drawing of the motion: the skeleton at its last pose with every goal set's goals and
    /// the final pins (SVG, PNG), or every frame (GIF) at `fps`.
    pub fn drawing<'a>(&'a self, rig: &'a Rig, fps: f64) -> Drawing<'a> {
        let last = self.motion.animation.frames.last().expect("an animation has frames");
        let task = self.stops.last().expect("at least the final goal set");
        let mut figure = rig_figure(
            rig,
            &last.angles,
            task,
            self.options.limits != ikarus::LimitMode::Ignore,
            Some(self.caption(rig)),
        );
        // The via sets' goals too, where the final set has none on the same bone.
        for via in &self.stops[..self.stops.len() - 1] {
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
}

/// An animation of one frame per pose, evenly timed over [0, 1] (a track's samples), with the
/// skeleton's points.
pub fn poses_animation(rig: &Rig, poses: &[Vec<f64>]) -> Animation {
    use ikarus::motion::Body;
    crate::picture::poses_animation(poses, |q| rig.skeleton.frame_points(q))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn timing_rules() {
        assert_eq!(timing(None, None, None).unwrap(), Timing::Frames(60));
        assert_eq!(timing(Some(5), None, Some(10.0)).unwrap(), Timing::Frames(5));
        assert_eq!(timing(None, Some(2.0), None).unwrap(), Timing::Duration { seconds: 2.0, fps: 30.0 });
        assert!(matches!(timing(Some(1), None, None), Err(TimingProblem::Value { field: "frames", .. })));
        assert!(matches!(timing(None, Some(0.0), None), Err(TimingProblem::Value { field: "duration", .. })));
        assert!(matches!(timing(None, None, Some(101.0)), Err(TimingProblem::Value { field: "fps", .. })));
        assert!(matches!(timing(Some(3), Some(1.0), None), Err(TimingProblem::Both)));
    }
}
