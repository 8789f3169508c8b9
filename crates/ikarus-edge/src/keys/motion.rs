//! The keyed motion of a rig: frame `k` at `k / fps` seconds is one rig solve, from frame
//! `k − 1`'s pose (frame 0 from the start pose), of every track's target at that time (with the
//! bends in force then) and every pin held where the start pose has it; and its answer, the
//! JSON of `ikarus animate --rig FILE --keys KEYS.json --format json` and of
//! `POST /api/animate` with `keys`.

use ikarus::motion::{Animation, Body};
use ikarus::{BoneBend, Ease, Goal, Outcome, Point2, RigGoal, RigTask, RigTaskError, SolveError, SolveOptions, Solver};
use serde::Serialize;

use super::KeyPlan;
use crate::error::Error;
use crate::report::ByName;
use crate::report::motion::RigFrameJson;
use crate::rig::Rig;

/// One solved frame: how its solve ended and where its tracks aimed.
#[derive(Debug, Clone)]
pub struct KeyedFrame {
    /// How the frame's solve ended: `reached` only if every track and pin is.
    pub status: ikarus::Status,
    /// The largest effector error of the frame's solve (the tracks' and the pins').
    pub error: f64,
    /// Each track's target, in the plan's order.
    pub targets: Vec<Point2<f64>>,
}

/// A keyed motion: the frames' solves and the animation of their poses (times in seconds).
#[derive(Debug, Clone)]
pub struct KeyedMotion {
    /// Frames per second.
    pub fps: f64,
    /// One per frame, in time order.
    pub frames: Vec<KeyedFrame>,
    /// The frames' poses and joint positions, times in seconds, eased linearly.
    pub animation: Animation,
    /// The last frame's task, for the picture.
    pub last_task: RigTask,
}

impl KeyedMotion {
    /// The motion's picture, as `ikarus animate --rig FILE --keys KEYS.json --out` and
    /// `POST /api/render` with `keys` draw it: every frame's pose (a GIF animates them), the last
    /// frame's goals and pins marked, limit wedges when `limits`.
    pub fn drawing<'a>(&'a self, rig: &'a Rig, limits: bool) -> crate::picture::Drawing<'a> {
        let animation = &self.animation;
        let last = animation.frames.last().expect("a keyed motion has frames");
        let caption = format!(
            "{} · keys · {} frames at {} fps · {} reached",
            rig.name,
            animation.frames.len(),
            self.fps,
            self.reached()
        );
        let figure = crate::picture::rig_figure(rig, &last.angles, &self.last_task, limits, Some(caption));
        crate::picture::Drawing::RigMotion { figure, animation, fps: self.fps }
    }
}

impl KeyPlan {
    /// Solves every frame on `rig` from `start` with `options`; `stop` is asked between frames
    /// whether to give up (the server's interrupt), answering its problem. A problem of the task
    /// (a bend the joint's limits leave no room for) is bad input, naming the field.
    pub fn run(
        &self,
        rig: &Rig,
        start: &[f64],
        options: SolveOptions,
        stop: &dyn Fn() -> Result<(), Error>,
    ) -> Result<KeyedMotion, Error> {
        let s = &rig.skeleton;
        let mut solver = Solver::new(options).map_err(|e| Error::input(e.to_string()))?;
        let mut task = RigTask::default();
        // The pins: goals at their tips' places and directions in the start pose, held over
        // the whole motion (a [`ikarus::Pin`] would hold a tip where each solve starts, and
        // creep by up to the tolerance per frame).
        let mut points = vec![Point2::origin(); s.len() + 1];
        let mut directions = vec![0.0; s.len()];
        s.points_into(start, &mut points, &mut directions);
        let pins: Vec<RigGoal> = self
            .pins
            .iter()
            .map(|&b| {
                let tip = points[b + 1];
                RigGoal::new(b, Goal::with_orientation(tip.x, tip.y, directions[b]).expect("a tip is finite"))
            })
            .collect();
        let mut frames = Vec::with_capacity(self.frames());
        let mut shown = Vec::with_capacity(self.frames());
        let mut out = Outcome::default();
        let mut pose = start.to_vec();
        let mut value = Vec::with_capacity(3);
        for k in 0..self.frames() {
            stop()?;
            let time = self.time(k);
            task.goals.clear();
            let mut targets = Vec::with_capacity(self.tracks.len());
            for t in &self.tracks {
                t.track.at(time, &mut value);
                let goal = match t.oriented {
                    true => Goal::with_orientation(value[0], value[1], value[2]),
                    false => Goal::position(value[0], value[1]),
                }
                .expect("keys are finite");
                targets.push(goal.target());
                task.goals.push(RigGoal::new(t.bone, goal));
            }
            task.goals.extend(pins.iter().cloned());
            task.bends.clear();
            task.bends.extend(self.bends.iter().filter_map(|(bone, keys)| {
                keys.iter().rev().find(|(f, _)| *f <= k).map(|&(_, bend)| BoneBend { bone: *bone, bend })
            }));
            solver.solve_rig_into(s, &pose, &task, &mut out).map_err(|e| self.problem(s, k, e))?;
            pose.clear();
            pose.extend_from_slice(out.pose.angles());
            frames.push(KeyedFrame { status: out.status, error: out.error, targets });
            shown.push(ikarus::AnimationFrame { time, angles: pose.clone(), joints: s.frame_points(&pose) });
        }
        let animation = Animation { frames: shown, duration: self.duration(), ease: Ease::Linear };
        Ok(KeyedMotion { fps: self.fps, frames, animation, last_task: task })
    }

    /// A solve's problem at frame `k` in the keys' words: a bend outside its joint's limits
    /// names the bend key in force.
    fn problem(&self, s: &ikarus::Skeleton, k: usize, e: SolveError) -> Error {
        if let SolveError::Rig(RigTaskError::BendOutsideLimits { name }) = &e {
            if let Some((_, keys)) = self.bends.iter().find(|(b, _)| s.name(*b) == name) {
                let i = keys.iter().rposition(|(f, _)| *f <= k).unwrap_or(0);
                let side = if keys[i].1 == ikarus::Bend::Positive { "ccw" } else { "cw" };
                return Error::input(format!(
                    "keys.bends.{name}[{i}].bend = {side}: the joint's limits leave no angle on that side"
                ));
            }
        }
        Error::input(format!("keys: frame {k}: {e}"))
    }
}

/// One frame of a keyed motion's answer: the rig motion's frame (time, angles, extensions,
/// tips by bone name), its solve's status and largest error, and each track's target.
#[derive(Serialize)]
pub struct KeyedFrameJson<'a> {
    /// The frame's time, pose and tips, written as this object's own fields.
    #[serde(flatten)]
    pub frame: RigFrameJson<'a>,
    /// How the frame's solve ended: `reached` only if every track and pin is.
    pub status: &'static str,
    /// The largest effector error of the frame's solve (the tracks' and the pins').
    pub error: f64,
    /// Tracked bone → its target at this frame.
    pub targets: ByName<'a, [f64; 2]>,
}

/// A keyed motion: `ikarus animate --rig FILE --keys KEYS.json --format json`, and
/// `POST /api/animate` with `keys`.
#[derive(Serialize)]
pub struct KeyedJson<'a> {
    /// The rig's name.
    pub rig: &'a str,
    /// Frames per second.
    pub fps: f64,
    /// The motion's length, seconds: the last frame's time.
    pub duration: f64,
    /// One per frame, frame `k` at `k / fps` seconds.
    pub frames: Vec<KeyedFrameJson<'a>>,
}

impl KeyedMotion {
    /// The answer's JSON object; `names` the tracked bones' names in the plan's order
    /// ([`KeyPlan::track_names`]).
    pub fn json<'a>(&'a self, rig: &'a Rig, names: &'a [String]) -> KeyedJson<'a> {
        let frames = self
            .frames
            .iter()
            .zip(&self.animation.frames)
            .map(|(f, a)| KeyedFrameJson {
                frame: RigFrameJson::of(&rig.skeleton, a),
                status: f.status.as_str(),
                error: f.error,
                targets: ByName { names, values: f.targets.iter().map(|p| [p.x, p.y]).collect() },
            })
            .collect();
        KeyedJson { rig: &rig.name, fps: self.fps, duration: self.animation.duration, frames }
    }

    /// How many frames' solves reached every effector.
    pub fn reached(&self) -> usize {
        self.frames.iter().filter(|f| f.status == ikarus::Status::Reached).count()
    }

    /// The largest error over the frames.
    pub fn max_error(&self) -> f64 {
        self.frames.iter().map(|f| f.error).fold(0.0, f64::max)
    }
}

impl KeyPlan {
    /// The tracked bones' names, in the plan's order.
    pub fn track_names(&self, s: &ikarus::Skeleton) -> Vec<String> {
        self.tracks.iter().map(|t| s.name(t.bone).to_owned()).collect()
    }
}
