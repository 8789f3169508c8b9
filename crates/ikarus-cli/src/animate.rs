//! `ikarus animate`: solve for a goal (through any via points), then turn the poses into an
//! eased motion: frames on stdout, and a picture or an animated GIF with `--out`. With
//! `--rig FILE` (and `ikarus render motion --rig FILE`): goal sets on a rig's bones solved in
//! turn — each `--via NAME=X,Y[;…]` set, then the `--goal NAME=X,Y …` set, the `--pin NAME`
//! bones held in each — and the poses eased into a motion of the skeleton.

use std::io::Write;

use clap::{Args, ValueEnum};
use ikarus::motion::{Interpolation, Timing};
use ikarus::{EaseKind, LimitMode};

use crate::body::Body;
use crate::body_args::{BodyArgs, BodyHelp};
use crate::ease_args::EaseArgs;
use crate::error::Error;
use crate::goal_args::{GoalArg, parse_goal};
use crate::motion::{DEFAULT_FPS, Motion, MotionBody, MotionPlan, TimingProblem};
use crate::options::{named, parse_angle, parse_at_least_one, parse_finite, parse_point};
use crate::output;
use crate::picture::{Drawing, PictureArgs, PictureFormat, draw_for_command, report_format};

mod bodies;
mod character;
mod keyed;

pub use bodies::Animated;

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum AnimateFormat {
    /// One JSON object with the frames (the default when stdout is not a terminal)
    Json,
    /// One row per frame
    Csv,
    /// A short report for people (the default on a terminal)
    Text,
    /// With a character file: the file with the motion added as a Spine animation
    Spine,
}

/// What a motion is made of: the goal, the via points, the arm (or rig), the solver, the
/// timing and the ease. Shared by `ikarus animate` and `ikarus render motion`.
#[derive(Debug, Args)]
pub struct MotionArgs {
    /// Goal position of the tip; with --rig, NAME=X,Y[,DEG]: the tip of bone NAME at X,Y (and
    /// pointing DEG degrees from +x), repeatable: the final goal set
    #[arg(long, value_name = "X,Y", allow_hyphen_values = true, value_parser = parse_goal,
          required_unless_present_any = ["rig", "keys"])]
    pub goal: Vec<GoalArg>,
    /// Goal orientation of the last link at the final goal, degrees from +x
    #[arg(long, value_name = "DEG", allow_hyphen_values = true, value_parser = parse_angle, conflicts_with = "rig")]
    pub goal_angle: Option<f64>,
    /// A point to pass through on the way, in order (repeat the flag for more); with --rig, a
    /// goal set to pass through, NAME=X,Y[,DEG] goals separated by ';' (the pins hold in each)
    #[arg(long, value_name = "X,Y", allow_hyphen_values = true, value_parser = parse_via)]
    pub via: Vec<ViaArg>,
    #[command(flatten)]
    pub body: BodyArgs<AnimateBody>,
    /// Number of frames of the motion [default: 60]
    #[arg(long, value_name = "N", value_parser = parse_at_least_one, conflicts_with = "duration")]
    pub frames: Option<u32>,
    /// Length of the motion in seconds (with --fps) [default with a character file: 1]
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
    /// With --rig: keyframes per effector, a KEYS JSON file (`{"fps": 30, "tracks": {"BONE":
    /// [{"time": 0, "x": …, "y": …, "ease": "sine"}, …]}, "bends": {…}, "pins": […]}`); every
    /// frame is one rig solve of the tracks' targets at its time
    #[arg(long, value_name = "KEYS.json", conflicts_with_all = KEYS_CONFLICT)]
    pub keys: Option<std::path::PathBuf>,
}

/// The help of `ikarus animate`'s (and `ikarus render motion`'s) `--arm` and `--rig`.
#[derive(Debug)]
pub struct AnimateBody;

impl BodyHelp for AnimateBody {
    const ARM: &'static str = "Arm file (TOML) [default: the built-in seed arm]";
    const RIG: &'static str = "Rig file (TOML): a tree of named bones; the motion solves its goal sets (--via, then \
                               --goal NAME=X,Y …, with --pin NAME held) in turn and eases the pose through them";
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
pub fn parse_via(s: &str) -> Result<ViaArg, Error> {
    if !s.contains('=') {
        return parse_point(s).map(ViaArg::Point);
    }
    s.split(';')
        .map(|part| match parse_goal(part.trim())? {
            g @ GoalArg::Named { .. } => Ok(g),
            GoalArg::Point(_) => Err(Error::input(format!("'{}': expected NAME=X,Y[,DEG] in a goal set", part.trim()))),
        })
        .collect::<Result<Vec<_>, _>>()
        .map(ViaArg::Set)
}

/// Solve for a goal and turn the result into a smooth, eased motion.
#[derive(Debug, Args)]
pub struct AnimateArgs {
    #[command(flatten)]
    pub motion: MotionArgs,
    /// With a character file (--rig FILE.json): the bone's world origin at X,Y at the end,
    /// eased from where the setup pose has it, the file's IK constraints following, BONE=X,Y
    /// (repeatable)
    #[arg(long, value_name = "BONE=X,Y", allow_hyphen_values = true, value_parser = crate::pose::parse_target)]
    pub target: Vec<(String, [f64; 2])>,
    /// Output format on stdout [default: text on a terminal, json otherwise; nothing with --out;
    /// with a character file, json (its frames) or spine, written to --out FILE if given]
    #[arg(long, value_enum)]
    pub format: Option<AnimateFormat>,
    /// With --format spine: the name of the animation added to the file [default: ikarus]
    #[arg(long, value_name = "NAME")]
    pub animation_name: Option<String>,
    /// With --format spine: every bone keyed at every frame, the IK constraints at mix 0 (the
    /// frame-by-frame bake), instead of the keys an animator edits
    #[arg(long)]
    pub bake: bool,
    /// With a character file and --keys: the clip posed under the keyed targets, at the same
    /// time (looping when the keys run longer)
    #[arg(long, value_name = "NAME", requires = "keys")]
    pub animation: Option<String>,
    /// With a character file: physics constraints on plays the frames as a game's frames at
    /// --fps (the keys' fps with --keys), the physics stepping from one to the next; off leaves
    /// them out (Spine's Physics.none) [default: on]
    #[arg(long, value_enum)]
    pub physics: Option<crate::pose::PhysicsSwitch>,
    #[command(flatten)]
    pub ik: crate::pose::IkArgs,
    #[command(flatten)]
    pub picture: PictureArgs,
    #[command(flatten)]
    pub art: crate::motion_art::MotionArtArgs,
}

/// The flags `--keys` replaces: its file gives the targets, pins, bends and fps.
const KEYS_CONFLICT: [&str; 18] = [
    "ease",
    "k1",
    "k2",
    "goal",
    "goal_angle",
    "via",
    "frames",
    "duration",
    "fps",
    "from_solve",
    "record_every",
    "interpolation",
    "pin",
    "bend",
    "weight",
    "secondary",
    "softness",
    "mix",
];

/// A motion computed from the flags, with the body it moves and what its pictures need.
pub struct MotionRun<B: MotionBody> {
    pub body: B,
    pub motion: Motion<B>,
    /// Frames per second of a GIF.
    pub fps: f64,
}

impl MotionArgs {
    /// The timing the flags ask for ([`crate::motion::timing`]).
    pub fn timing(&self) -> Result<Timing, Error> {
        crate::motion::timing(self.frames, self.duration, self.fps).map_err(|p| match p {
            TimingProblem::Value { field, value, message } => Error::input(format!("--{field} {value}: {message}")),
            TimingProblem::Both => Error::input("--frames, --duration: give one or the other, not both"),
        })
    }
}

impl<B: Animated> MotionRun<B> {
    /// Solves `body` for each stop of the flags (an arm's via points and goal, a rig's via sets
    /// and goal set), each from the previous pose, and eases the poses into a motion; an
    /// unreached stop is reported on stderr (the motion goes on from the best pose found).
    pub fn of(args: &MotionArgs, body: B) -> Result<Self, Error> {
        let timing = args.timing()?;
        let ease = args.ease.resolve(EaseKind::Sine)?;
        let record = if args.from_solve { Some(args.record_every.unwrap_or(1)) } else { None };
        let options = body.solve_options(&args.body.solver.settings(), record)?;
        let stops = body.stops(args)?;
        let start = body.start().to_vec();
        let interpolation = args.interpolation.unwrap_or_default();
        let from_solve = args.from_solve;
        let motion =
            MotionPlan { body: &body, start, stops, options, timing, ease, interpolation, from_solve }.run()?;
        B::warn_unreached(&motion.motion);
        Ok(MotionRun { body, motion, fps: args.fps.unwrap_or(DEFAULT_FPS) })
    }
}

/// A motion of an arm or a rig, as its commands show it.
pub trait ShownMotion {
    /// The drawing of the motion.
    fn drawing(&self) -> Drawing<'_>;
    /// The number of frames.
    fn frames(&self) -> usize;
    /// The report on stdout in `format`.
    fn write(&self, w: &mut dyn Write, format: AnimateFormat) -> std::io::Result<()>;
}

/// The motion the flags ask for: keyed (`--keys`), of the rig (`--rig FILE`), or of the arm
/// (`--arm`, or the built-in arm).
pub fn motion(args: &MotionArgs) -> Result<Box<dyn ShownMotion>, Error> {
    if let Some(keys) = &args.keys {
        return Ok(Box::new(keyed::KeyedRun::of(args, keys)?));
    }
    Ok(match args.body.load()? {
        Body::Chain(arm) => Box::new(MotionRun::of(args, *arm)?),
        Body::Rig(rig) => Box::new(MotionRun::of(args, *rig)?),
    })
}

impl<B: Animated> ShownMotion for MotionRun<B> {
    fn drawing(&self) -> Drawing<'_> {
        B::drawing(self)
    }

    fn frames(&self) -> usize {
        B::animation(&self.motion.motion).frames.len()
    }

    fn write(&self, w: &mut dyn Write, format: AnimateFormat) -> std::io::Result<()> {
        match format {
            AnimateFormat::Json => {
                B::json(self, &mut *w)?;
                writeln!(w)
            }
            AnimateFormat::Csv => csv(w, self),
            AnimateFormat::Text => text(w, self),
            AnimateFormat::Spine => unreachable!("--format spine is refused without a character file"),
        }
    }
}

pub fn run(args: &AnimateArgs) -> Result<(), Error> {
    if let Some(file) = crate::character_motion::character(args.motion.body.rig.as_deref()) {
        return character::run(args, &file?);
    }
    let [ik, ik_file] = args.ik.given();
    let [atlas, art_only, skin] = args.art.given();
    crate::character_motion::refuse_without(&[
        ("--target", !args.target.is_empty()),
        atlas,
        art_only,
        skin,
        ("--animation", args.animation.is_some()),
        ("--animation-name", args.animation_name.is_some()),
        ("--bake", args.bake),
        ("--physics", args.physics.is_some()),
        ("--format spine", args.format == Some(AnimateFormat::Spine)),
        ik,
        ik_file,
    ])?;
    let picture = args.picture.prepare(&[PictureFormat::Svg, PictureFormat::Png, PictureFormat::Gif])?;
    let run = motion(&args.motion)?;
    let drew = picture.is_some();
    if let Some(out) = picture {
        let bytes = draw_for_command(&run.drawing(), out.format, &args.picture, run.frames())?;
        out.commit(&bytes)?;
    }

    // With --out the picture is the result: stdout stays quiet unless a format is asked for.
    let Some(format) = report_format(args.format, drew, AnimateFormat::Text, AnimateFormat::Json) else {
        return Ok(());
    };
    output::stdout(|w| run.write(w, format))
}

/// The short report: the body, each solve, the motion's timing, and its first and last pose.
fn text<B: Animated>(w: &mut dyn Write, run: &MotionRun<B>) -> std::io::Result<()> {
    let options = &run.motion.options;
    let animation = B::animation(&run.motion.motion);
    writeln!(w, "{}", run.body.head())?;
    let limits = match options.limits {
        LimitMode::Ignore => "off".to_owned(),
        mode => format!("on ({})", mode.name()),
    };
    writeln!(w, "method    {}   limits {limits}", options.method.name())?;
    B::solve_lines(run, w)?;
    let frames = animation.frames.len();
    writeln!(w, "motion    {frames} frames over {} s, {} ease", animation.duration, animation.ease.name())?;
    if let (Some(first), Some(last)) = (animation.frames.first(), animation.frames.last()) {
        writeln!(w, "start     {}", run.body.pose_text(&first.angles))?;
        writeln!(w, "end       {}", run.body.pose_text(&last.angles))?;
        B::end_lines(last, w)?;
    }
    writeln!(w, "frames    --format json or csv lists them; --out draws them (.svg, .png, .gif)")
}

/// One row per frame: `time`, the pose's columns, then the body's points (an arm's from its
/// base, `x0,y0`; a rig's every bone's tip, `NAME.x,NAME.y`).
fn csv<B: Animated>(w: &mut dyn Write, run: &MotionRun<B>) -> std::io::Result<()> {
    let mut header = vec!["time".to_owned()];
    header.extend(run.body.pose_columns());
    header.extend(run.body.point_columns());
    writeln!(w, "{}", header.join(","))?;
    for f in &B::animation(&run.motion.motion).frames {
        write!(w, "{:?}", f.time)?;
        run.body.write_pose(w, &f.angles)?;
        for p in &f.joints[B::FIRST_POINT..] {
            write!(w, ",{:?},{:?}", p.x, p.y)?;
        }
        writeln!(w)?;
    }
    Ok(())
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
        assert_eq!(parse_via("1,2,3"), Err(Error::input("expected two numbers X,Y, got 3 part(s)")));
        assert_eq!(parse_via("hand=1,2;3,4"), Err(Error::input("'3,4': expected NAME=X,Y[,DEG] in a goal set")));
        assert_eq!(parse_via("hand=1,x"), Err(Error::input("hand: y: 'x' is not a number")));
    }
}
