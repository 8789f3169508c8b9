//! The motion workflow shared by `ikarus animate` and `POST /api/animate` / `/api/render`:
//! the timing rules, via points into goals, and the library's motion through goals.

use ikarus::motion::{
    GoalMotion, GoalMotionError, Interpolation, MotionError, MotionOptions, Route, Timing, through_goals,
};
use ikarus::number::Num;
use ikarus::{Ease, Goal, GoalError, SolveOptions, Solver};

use crate::arm::Arm;
use crate::error::CliError;

/// Frames of a motion when neither frames nor a duration is given.
pub const DEFAULT_FRAMES: u32 = 60;
/// Frame rate of a motion's duration and its GIF when none is given.
pub const DEFAULT_FPS: f64 = 30.0;

/// A timing value out of its rules; each edge words it with its own field names.
#[derive(Debug)]
pub enum TimingProblem {
    /// `field` = `value` breaks the rule `message`.
    Value { field: &'static str, value: String, message: &'static str },
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

/// What a motion request asks for once its values are checked.
pub struct MotionPlan<'a> {
    pub arm: &'a Arm,
    /// The pose the motion starts from, radians.
    pub start: Vec<f64>,
    /// Via points, then the final goal.
    pub goals: Vec<Goal>,
    pub options: SolveOptions,
    pub timing: Timing,
    pub ease: Ease,
    /// The path through the poses: spline (the default) or polyline.
    pub interpolation: Interpolation,
    /// Follow the solver's recorded path instead of moving straight between solved poses.
    pub from_solve: bool,
}

/// A computed motion, with the options it was solved with.
pub struct Motion {
    pub options: SolveOptions,
    pub motion: GoalMotion,
}

impl MotionPlan<'_> {
    /// Solves for each via point, then the goal, each from the previous pose, and eases the
    /// poses into a motion ([`ikarus::motion::through_goals`]), with the same interpolation
    /// whether the poses are the solved ones or every pose the solver recorded.
    pub fn run(self) -> Result<Motion, CliError> {
        let mut solver = Solver::new(self.options).map_err(|e| CliError::input(e.to_string()))?;
        let route = if self.from_solve { Route::Recorded } else { Route::Keyframes };
        let chain = &self.arm.chain;
        let options = MotionOptions::new(self.timing, self.ease).with_interpolation(self.interpolation);
        let motion = through_goals(&mut solver, chain, &self.start, &self.goals, route, options)
            .map_err(|e| CliError::input(describe(&e, |joint| format!("joint {}", joint + 1))))?;
        Ok(Motion { options: solver.options().clone(), motion })
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

impl Motion {
    /// The one-line caption of the motion's pictures.
    pub fn caption(&self) -> String {
        let solves = &self.motion.solves;
        let animation = &self.motion.animation;
        let last = solves.last().expect("at least the goal was solved");
        let iterations: u32 = solves.iter().map(|s| s.iterations).sum();
        format!(
            "{} · {} · {} iterations · error {:.1e} · {} frames, {} ease",
            self.options.method.name(),
            last.status,
            iterations,
            last.error,
            animation.frames.len(),
            animation.ease.name()
        )
    }
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
