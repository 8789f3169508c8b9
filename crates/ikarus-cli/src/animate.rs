//! `ikarus animate`: solve for a goal (through any via points), then turn the poses into an
//! eased motion: frames on stdout, and a picture or an animated GIF with `--out`. With
//! `--rig FILE` (and `ikarus render motion --rig FILE`): goal sets on a rig's bones solved in
//! turn — each `--via NAME=X,Y[;…]` set, then the `--goal NAME=X,Y …` set, the `--pin NAME`
//! bones held in each — and the poses eased into a motion of the skeleton.

use std::io::Write;
use std::path::{Path, PathBuf};

use clap::{Args, ValueEnum};
use ikarus::motion::{Animation, Interpolation, Timing};
use ikarus::number::Num;
use ikarus::{EaseKind, Goal, LimitMode, RigTask};

use crate::arm::Arm;
use crate::ease_args::EaseArgs;
use crate::error::CliError;
use crate::goal_args::{GoalArg, RigTaskArgs, Target, parse_goal};
use crate::motion::{DEFAULT_FPS, Motion, MotionPlan, TimingProblem};
use crate::options::{named, parse_angle, parse_at_least_one, parse_finite, parse_point};
use crate::output;
use crate::picture::{
    Drawing, MotionLayers, PictureArgs, PictureFormat, draw_for_command, motion_drawing, report_format,
};
use crate::report::{AnimateJson, deg_text};
use crate::rig::Rig;
use crate::settings::SolverFlags;
use crate::solve::{angle_columns, write_pose};

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum AnimateFormat {
    /// One JSON object with the frames (the default when stdout is not a terminal)
    Json,
    /// One row per frame
    Csv,
    /// A short report for people (the default on a terminal)
    Text,
}

/// What a motion is made of: the goal, the via points, the arm (or rig), the solver, the
/// timing and the ease. Shared by `ikarus animate` and `ikarus render motion`.
#[derive(Debug, Args)]
pub struct MotionArgs {
    /// Goal position of the tip; with --rig, NAME=X,Y[,DEG]: the tip of bone NAME at X,Y (and
    /// pointing DEG degrees from +x), repeatable: the final goal set
    #[arg(long, value_name = "X,Y", allow_hyphen_values = true, value_parser = parse_goal,
          required_unless_present = "rig")]
    pub goal: Vec<GoalArg>,
    /// Goal orientation of the last link at the final goal, degrees from +x
    #[arg(long, value_name = "DEG", allow_hyphen_values = true, value_parser = parse_angle, conflicts_with = "rig")]
    pub goal_angle: Option<f64>,
    /// A point to pass through on the way, in order (repeat the flag for more); with --rig, a
    /// goal set to pass through, NAME=X,Y[,DEG] goals separated by ';' (the pins hold in each)
    #[arg(long, value_name = "X,Y", allow_hyphen_values = true, value_parser = parse_via)]
    pub via: Vec<ViaArg>,
    /// Arm file (TOML) [default: the built-in seed arm]
    #[arg(long, value_name = "FILE")]
    pub arm: Option<PathBuf>,
    /// Rig file (TOML): a tree of named bones; the motion solves its goal sets (--via, then
    /// --goal NAME=X,Y …, with --pin NAME held) in turn and eases the pose through them
    #[arg(long, value_name = "FILE", conflicts_with = "arm")]
    pub rig: Option<PathBuf>,
    #[command(flatten)]
    pub rig_task: RigTaskArgs,
    #[command(flatten)]
    pub solver: SolverFlags,
    /// Number of frames of the motion [default: 60]
    #[arg(long, value_name = "N", value_parser = parse_at_least_one, conflicts_with = "duration")]
    pub frames: Option<u32>,
    /// Length of the motion in seconds (with --fps)
    #[arg(long, value_name = "SECONDS", value_parser = parse_finite)]
    pub duration: Option<f64>,
    /// Frames per second, for --duration and the GIF [default: 30]
    #[arg(long, value_name = "F", value_parser = parse_finite)]
    pub fps: Option<f64>,
    #[command(flatten)]
    pub ease: EaseArgs,
    /// Path through the keyframes in joint space [default: spline]
    #[arg(long, value_parser = named::<Interpolation>(), hide_possible_values = false)]
    pub interpolation: Option<Interpolation>,
    /// Follow the solver's own path (its recorded frames), re-timed and interpolated the same
    /// way, instead of the path through the solved poses
    #[arg(long)]
    pub from_solve: bool,
    /// Record a solver frame every K iterations for --from-solve [default: 1]
    #[arg(long, value_name = "K", value_parser = parse_at_least_one)]
    pub record_every: Option<u32>,
}

/// A `--via`: an arm's point `X,Y`, or a rig's goal set `NAME=X,Y[,DEG][;NAME=X,Y[,DEG]…]`.
#[derive(Debug, Clone, PartialEq)]
pub enum ViaArg {
    Point([f64; 2]),
    Set(Vec<GoalArg>),
}

impl ViaArg {
    /// The flag as written, for messages.
    pub fn text(&self) -> String {
        match self {
            ViaArg::Point([x, y]) => format!("--via {x},{y}"),
            ViaArg::Set(goals) => {
                let parts: Vec<String> =
                    goals.iter().map(|g| g.text().trim_start_matches("--goal ").to_owned()).collect();
                format!("--via {}", parts.join(";"))
            }
        }
    }
}

/// Parses `X,Y`, or goals `NAME=X,Y[,DEG]` separated by `;`.
pub fn parse_via(s: &str) -> Result<ViaArg, String> {
    if !s.contains('=') {
        return parse_point(s).map(ViaArg::Point);
    }
    s.split(';')
        .map(|part| match parse_goal(part.trim())? {
            g @ GoalArg::Named { .. } => Ok(g),
            GoalArg::Point(_) => Err(format!("'{}': expected NAME=X,Y[,DEG] in a goal set", part.trim())),
        })
        .collect::<Result<Vec<_>, _>>()
        .map(ViaArg::Set)
}

/// Solve for a goal and turn the result into a smooth, eased motion.
#[derive(Debug, Args)]
pub struct AnimateArgs {
    #[command(flatten)]
    pub motion: MotionArgs,
    /// Output format on stdout [default: text on a terminal, json otherwise; nothing with --out]
    #[arg(long, value_enum)]
    pub format: Option<AnimateFormat>,
    #[command(flatten)]
    pub picture: PictureArgs,
}

/// A motion computed from the flags, with what its report and pictures need.
pub struct MotionRun {
    pub arm: Arm,
    pub goal: Goal,
    pub motion: Motion<Arm>,
    /// Frames per second of a GIF.
    pub fps: f64,
}

impl MotionArgs {
    /// Loads the arm, solves for each via point and the goal, and eases the poses into a
    /// motion; an unreached goal is reported on stderr (the motion ends at the best pose).
    pub fn run(&self) -> Result<MotionRun, CliError> {
        let arm = Arm::load(self.arm.as_deref())?;
        let timing = timing(self)?;
        let ease = self.ease.resolve(EaseKind::Sine)?;
        // Solve for each via point, then the goal, each from the previous pose.
        let record = if self.from_solve { Some(self.record_every.unwrap_or(1)) } else { None };
        let options = arm.options(&self.solver.settings(), record)?;
        let goal = self.arm_goal()?;
        let via = self
            .via
            .iter()
            .map(|v| match v {
                ViaArg::Point(p) => Ok(*p),
                ViaArg::Set(_) => {
                    Err(CliError::input(format!("{}: a goal set on named bones needs --rig FILE", v.text())))
                }
            })
            .collect::<Result<Vec<_>, _>>()?;
        let goals =
            crate::motion::goals(&via, goal).map_err(|(i, e)| CliError::input(format!("--via #{}: {e}", i + 1)))?;
        let start = arm.chain.start_pose().angles().to_vec();
        let interpolation = self.interpolation.unwrap_or_default();
        let from_solve = self.from_solve;
        let motion =
            MotionPlan { body: &arm, start, stops: goals, options, timing, ease, interpolation, from_solve }.run()?;
        for s in &motion.motion.solves {
            if s.status != ikarus::Status::Reached {
                let target = s.goal.target();
                eprintln!(
                    "ikarus: goal ({}, {}) not reached: {}, error {:.3e}; the motion ends at the best pose found",
                    Num(target.x),
                    Num(target.y),
                    s.status,
                    s.error
                );
            }
        }
        Ok(MotionRun { arm, goal, motion, fps: self.fps.unwrap_or(DEFAULT_FPS) })
    }

    /// The one goal of an arm: `--goal X,Y` given once (with `--goal-angle`).
    fn arm_goal(&self) -> Result<Goal, CliError> {
        match &self.goal[..] {
            [GoalArg::Point([x, y])] => crate::goals::make_goal(*x, *y, self.goal_angle).map_err(CliError::input),
            [named @ GoalArg::Named { .. }] => {
                Err(CliError::input(format!("{}: a goal on a named bone needs --rig FILE", named.text())))
            }
            goals => Err(CliError::input(format!(
                "--goal: an arm has one tip, so one --goal X,Y, got {} (points on the way are --via X,Y; several goals need --rig FILE)",
                goals.len()
            ))),
        }
    }

    /// The timing the flags ask for.
    pub fn timing(&self) -> Result<Timing, CliError> {
        timing(self)
    }
}

impl MotionRun {
    /// The drawing of the motion (the one the API's figure `motion` draws).
    pub fn drawing(&self) -> Drawing<'_> {
        let (animation, caption) = (&self.motion.motion.animation, self.motion.caption());
        motion_drawing(&self.arm, animation, caption, Some(self.goal.target()), self.fps, MotionLayers::default())
    }
}

/// A motion of an arm or a rig, computed from the flags.
pub enum BodyMotion {
    Chain(Box<MotionRun>),
    Rig(Box<RigMotionRun>),
}

impl BodyMotion {
    /// The arm's motion (`--arm`, or the built-in arm), or the rig's (`--rig FILE`).
    pub fn of(args: &MotionArgs) -> Result<Self, CliError> {
        match &args.rig {
            Some(path) => Ok(Self::Rig(Box::new(motion_run(args, path)?))),
            None => Ok(Self::Chain(Box::new(args.run()?))),
        }
    }

    /// The drawing of the motion.
    pub fn drawing(&self) -> Drawing<'_> {
        match self {
            Self::Chain(run) => run.drawing(),
            Self::Rig(run) => run.drawing(),
        }
    }

    /// The number of frames.
    pub fn frames(&self) -> usize {
        match self {
            Self::Chain(run) => run.motion.motion.animation.frames.len(),
            Self::Rig(run) => run.motion.motion.animation.frames.len(),
        }
    }
}

pub fn run(args: &AnimateArgs) -> Result<(), CliError> {
    let picture = args.picture.prepare(&[PictureFormat::Svg, PictureFormat::Png, PictureFormat::Gif])?;
    let run = BodyMotion::of(&args.motion)?;
    let drew = picture.is_some();
    if let Some(out) = picture {
        let bytes = draw_for_command(&run.drawing(), out.format, &args.picture, run.frames())?;
        out.commit(&bytes)?;
    }

    // With --out the picture is the result: stdout stays quiet unless a format is asked for.
    let Some(format) = report_format(args.format, drew, AnimateFormat::Text, AnimateFormat::Json) else {
        return Ok(());
    };
    output::stdout(|w| match (format, &run) {
        (AnimateFormat::Json, BodyMotion::Chain(run)) => {
            serde_json::to_writer_pretty(&mut *w, &AnimateJson::new(&run.arm, &run.motion.motion))?;
            writeln!(w)
        }
        (AnimateFormat::Json, BodyMotion::Rig(run)) => {
            serde_json::to_writer_pretty(&mut *w, &run.motion.json(&run.rig))?;
            writeln!(w)
        }
        (AnimateFormat::Csv, BodyMotion::Chain(run)) => csv(w, &run.motion.motion.animation, run.arm.chain.len()),
        (AnimateFormat::Csv, BodyMotion::Rig(run)) => rig_csv(w, run),
        (AnimateFormat::Text, BodyMotion::Chain(run)) => text(w, run),
        (AnimateFormat::Text, BodyMotion::Rig(run)) => rig_text(w, run),
    })
}

/// The short report: the arm, each solve, the motion's timing, and its first and last pose.
fn text(w: &mut dyn Write, run: &MotionRun) -> std::io::Result<()> {
    let arm = &run.arm;
    let options = &run.motion.options;
    let motion = &run.motion.motion;
    let animation = &motion.animation;
    writeln!(w, "arm       {} ({} links, reach {})", arm.name, arm.chain.len(), arm.chain.max_reach())?;
    let limits = match options.limits {
        ikarus::LimitMode::Ignore => "off".to_owned(),
        mode => format!("on ({})", mode.name()),
    };
    writeln!(w, "method    {}   limits {limits}", options.method.name())?;
    for (i, s) in motion.solves.iter().enumerate() {
        let what = if i + 1 == motion.solves.len() { "goal" } else { "via" };
        let target = s.goal.target();
        let angle = s.goal.orientation().map_or(String::new(), |a| format!(" at {}", deg_text(a, 3)));
        writeln!(
            w,
            "{what:<9} ({}, {}){angle}: {} after {} iterations, error {:.3e}",
            target.x, target.y, s.status, s.iterations, s.error
        )?;
    }
    let frames = animation.frames.len();
    writeln!(w, "motion    {frames} frames over {} s, {} ease", animation.duration, animation.ease.name())?;
    let pose = |angles: &[f64]| angles.iter().map(|&a| deg_text(a, 3)).collect::<Vec<_>>().join(", ");
    if let (Some(first), Some(last)) = (animation.frames.first(), animation.frames.last()) {
        writeln!(w, "start     {}", pose(&first.angles))?;
        writeln!(w, "end       {}", pose(&last.angles))?;
        if let Some(tip) = last.joints.last() {
            writeln!(w, "tip       ({:.6}, {:.6})", tip.x, tip.y)?;
        }
    }
    writeln!(w, "frames    --format json or csv lists them; --out draws them (.svg, .png, .gif)")
}

/// The timing the flags ask for ([`crate::motion::timing`]).
fn timing(args: &MotionArgs) -> Result<Timing, CliError> {
    crate::motion::timing(args.frames, args.duration, args.fps).map_err(|p| match p {
        TimingProblem::Value { field, value, message } => CliError::input(format!("--{field} {value}: {message}")),
        TimingProblem::Both => CliError::input("--frames, --duration: give one or the other, not both"),
    })
}

fn csv(w: &mut dyn Write, animation: &Animation, n: usize) -> std::io::Result<()> {
    let mut header = vec!["time".to_owned()];
    header.extend((1..=n).map(|i| format!("theta{i}_deg")));
    for k in 0..=n {
        header.push(format!("x{k}"));
        header.push(format!("y{k}"));
    }
    writeln!(w, "{}", header.join(","))?;
    for f in &animation.frames {
        write!(w, "{:?}", f.time)?;
        for a in &f.angles {
            write!(w, ",{:?}", a.to_degrees())?;
        }
        for p in &f.joints {
            write!(w, ",{:?},{:?}", p.x, p.y)?;
        }
        writeln!(w)?;
    }
    Ok(())
}

/// A rig motion computed from the flags, with what its report and pictures need.
pub struct RigMotionRun {
    pub rig: Rig,
    pub motion: Motion<Rig>,
    /// Frames per second of a GIF.
    pub fps: f64,
}

impl RigMotionRun {
    /// The drawing of the motion.
    pub fn drawing(&self) -> Drawing<'_> {
        self.motion.drawing(&self.rig, self.fps)
    }
}

/// The goal sets of the flags: each `--via` set (with the pins and the mix), then the `--goal`
/// set (with every per-goal control).
fn tasks(args: &MotionArgs, rig: &Rig) -> Result<Vec<RigTask>, CliError> {
    let plain = RigTaskArgs { pin: args.rig_task.pin.clone(), mix: args.rig_task.mix, ..RigTaskArgs::default() };
    let mut tasks = Vec::with_capacity(args.via.len() + 1);
    for via in &args.via {
        let ViaArg::Set(goals) = via else {
            return Err(CliError::input(format!(
                "{}: a rig's via is a goal set on named bones: --via NAME=X,Y[,DEG][;NAME=X,Y…]",
                via.text()
            )));
        };
        let mut targets = goals.iter().map(|g| Target::of(g, rig)).collect::<Result<Vec<_>, _>>()?;
        for t in &mut targets {
            t.source = via.text();
        }
        tasks.push(plain.task(&rig.skeleton, &targets)?);
    }
    let targets = args.goal.iter().map(|g| Target::of(g, rig)).collect::<Result<Vec<_>, _>>()?;
    tasks.push(args.rig_task.task(&rig.skeleton, &targets)?);
    Ok(tasks)
}

/// Loads the rig, solves each goal set and eases the poses into a motion; an unreached set is
/// reported on stderr (the motion goes on from the best pose found).
pub fn motion_run(args: &MotionArgs, path: &Path) -> Result<RigMotionRun, CliError> {
    let rig = Rig::load(path)?;
    let timing = args.timing()?;
    let ease = args.ease.resolve(EaseKind::Sine)?;
    let record = if args.from_solve { Some(args.record_every.unwrap_or(1)) } else { None };
    let options = rig.options(&args.solver.settings(), record)?;
    let tasks = tasks(args, &rig)?;
    let start = rig.skeleton.start_angles().to_vec();
    let interpolation = args.interpolation.unwrap_or_default();
    let plan = MotionPlan {
        body: &rig,
        start,
        stops: tasks,
        options,
        timing,
        ease,
        interpolation,
        from_solve: args.from_solve,
    };
    let motion = plan.run()?;
    let count = motion.motion.solves.len();
    for (k, s) in motion.motion.solves.iter().enumerate() {
        if s.status != ikarus::Status::Reached {
            let which = if k + 1 == count { "the goal set".to_owned() } else { format!("via set #{}", k + 1) };
            eprintln!(
                "ikarus: {which} not reached: {}, largest error {:.3e}; the motion goes on from the best pose found",
                s.status, s.error
            );
        }
    }
    Ok(RigMotionRun { rig, motion, fps: args.fps.unwrap_or(DEFAULT_FPS) })
}

/// One row per frame: `time`, every bone's angle (`NAME_deg`), every prismatic bone's
/// displacement (`NAME_ext`), every bone's tip (`NAME.x,NAME.y`), in the rig's order.
fn rig_csv(w: &mut dyn Write, run: &RigMotionRun) -> std::io::Result<()> {
    let names = run.rig.skeleton.names();
    let tips: Vec<String> = names.iter().map(|n| format!("{n}.x,{n}.y")).collect();
    writeln!(w, "time,{},{}", angle_columns(&run.rig), tips.join(","))?;
    for f in &run.motion.motion.animation.frames {
        write!(w, "{:?}", f.time)?;
        write_pose(w, &run.rig, &f.angles)?;
        for p in &f.joints[1..] {
            write!(w, ",{:?},{:?}", p.x, p.y)?;
        }
        writeln!(w)?;
    }
    Ok(())
}

/// The short report: the rig, each goal set's solve, the timing, the first and last pose.
fn rig_text(w: &mut dyn Write, run: &RigMotionRun) -> std::io::Result<()> {
    let s = &run.rig.skeleton;
    let options = &run.motion.options;
    let motion = &run.motion.motion;
    let animation = &motion.animation;
    writeln!(w, "rig       {} ({} bones)", run.rig.name, s.len())?;
    let limits = match options.limits {
        LimitMode::Ignore => "off".to_owned(),
        mode => format!("on ({})", mode.name()),
    };
    writeln!(w, "method    {}   limits {limits}", options.method.name())?;
    for (k, (solve, task)) in motion.solves.iter().zip(&run.motion.stops).enumerate() {
        let what = if k + 1 == motion.solves.len() { "goals" } else { "via" };
        let goals: Vec<String> = task
            .goals
            .iter()
            .map(|g| {
                let t = g.goal.target();
                let angle = g.goal.orientation().map_or(String::new(), |a| format!(" at {}", deg_text(a, 3)));
                format!("{} ({}, {}){angle}", s.name(g.bone), t.x, t.y)
            })
            .chain(task.pins.iter().map(|p| format!("{} pinned", s.name(p.bone))))
            .collect();
        writeln!(
            w,
            "{what:<9} {}: {} after {} iterations, largest error {:.3e}",
            goals.join(", "),
            solve.status,
            solve.iterations,
            solve.error
        )?;
    }
    writeln!(
        w,
        "motion    {} frames over {} s, {} ease",
        animation.frames.len(),
        animation.duration,
        animation.ease.name()
    )?;
    let pose = |angles: &[f64]| {
        s.names().iter().zip(angles).map(|(n, &a)| format!("{n} {}", deg_text(a, 3))).collect::<Vec<_>>().join(", ")
    };
    if let (Some(first), Some(last)) = (animation.frames.first(), animation.frames.last()) {
        writeln!(w, "start     {}", pose(&first.angles))?;
        writeln!(w, "end       {}", pose(&last.angles))?;
    }
    writeln!(w, "frames    --format json or csv lists them; --out draws them (.svg, .png, .gif)")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_via_is_a_point_or_a_goal_set() {
        assert_eq!(parse_via("1,-2"), Ok(ViaArg::Point([1.0, -2.0])));
        let named = |bone: &str, x, y, angle_deg| GoalArg::Named { bone: bone.into(), x, y, angle_deg };
        assert_eq!(parse_via("hand=1,2"), Ok(ViaArg::Set(vec![named("hand", 1.0, 2.0, None)])));
        let set = parse_via("hand=1,2; foot=0,-1,90").unwrap();
        assert_eq!(set, ViaArg::Set(vec![named("hand", 1.0, 2.0, None), named("foot", 0.0, -1.0, Some(90.0))]));
        assert_eq!(set.text(), "--via hand=1,2;foot=0,-1,90");
        assert_eq!(parse_via("1,2,3"), Err("expected two numbers X,Y, got 3 part(s)".into()));
        assert_eq!(parse_via("hand=1,2;3,4"), Err("'3,4': expected NAME=X,Y[,DEG] in a goal set".into()));
        assert_eq!(parse_via("hand=1,x"), Err("hand: y: 'x' is not a number".into()));
    }
}
