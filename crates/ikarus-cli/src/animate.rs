//! `ikarus animate`: solve for a goal (through any via points), then turn the poses into an
//! eased motion: frames on stdout, and a picture or an animated GIF with `--out`.

use std::io::Write;
use std::path::PathBuf;

use clap::{Args, ValueEnum};
use ikarus::EaseKind;
use ikarus::motion::{Animation, Interpolation, Timing};

use crate::arm::Arm;
use crate::ease_args::EaseArgs;
use crate::error::CliError;
use crate::motion::{DEFAULT_FPS, MotionPlan, TimingProblem};
use crate::options::{named, parse_angle, parse_at_least_one, parse_finite, parse_point};
use crate::output;
use crate::picture::{Drawing, PictureArgs, PictureFormat, draw_for_command};
use crate::report::AnimateJson;
use crate::settings::SolverSettings;

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum AnimateFormat {
    /// One JSON object with the frames
    Json,
    /// One row per frame
    Csv,
}

/// Solve for a goal and turn the result into a smooth, eased motion.
#[derive(Debug, Args)]
pub struct AnimateArgs {
    /// Goal position of the tip
    #[arg(long, value_name = "X,Y", allow_hyphen_values = true, value_parser = parse_point)]
    pub goal: [f64; 2],
    /// Goal orientation of the last link at the final goal, degrees from +x
    #[arg(long, value_name = "DEG", allow_hyphen_values = true, value_parser = parse_angle)]
    pub goal_angle: Option<f64>,
    /// A point to pass through on the way, in order (repeat the flag for more)
    #[arg(long, value_name = "X,Y", allow_hyphen_values = true, value_parser = parse_point)]
    pub via: Vec<[f64; 2]>,
    /// Arm file (TOML) [default: the built-in seed arm]
    #[arg(long, value_name = "FILE")]
    pub arm: Option<PathBuf>,
    #[command(flatten)]
    pub solver: SolverSettings,
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
    /// Output format of the frames on stdout
    #[arg(long, value_enum, default_value = "json")]
    pub format: AnimateFormat,
    #[command(flatten)]
    pub picture: PictureArgs,
}

pub fn run(args: &AnimateArgs) -> Result<(), CliError> {
    let arm = Arm::load(args.arm.as_deref())?;
    let timing = timing(args)?;
    let ease = args.ease.resolve(EaseKind::Sine)?;
    let picture = args.picture.prepare(&[PictureFormat::Svg, PictureFormat::Png, PictureFormat::Gif])?;

    // Solve for each via point, then the goal, each from the previous pose.
    let record = if args.from_solve { Some(args.record_every.unwrap_or(1)) } else { None };
    let options = arm.options(&args.solver, record)?;
    let [x, y] = args.goal;
    let goal = crate::goals::make_goal(x, y, args.goal_angle).map_err(CliError::input)?;
    let goals =
        crate::motion::goals(&args.via, goal).map_err(|(i, e)| CliError::input(format!("--via #{}: {e}", i + 1)))?;
    let start = arm.chain.start_pose().angles().to_vec();
    let from_solve = args.from_solve;
    let interpolation = args.interpolation.unwrap_or_default();
    let motion = MotionPlan { arm: &arm, start, goals, options, timing, ease, interpolation, from_solve }.run()?;
    for s in &motion.motion.solves {
        if s.status != ikarus::Status::Reached {
            let target = s.goal.target();
            eprintln!(
                "ikarus: goal ({}, {}) not reached: {}, error {:.3e}; the motion ends at the best pose found",
                target.x, target.y, s.status, s.error
            );
        }
    }
    let animation = &motion.motion.animation;

    if let Some(out) = picture {
        let drawing = Drawing::Motion {
            chain: &arm.chain,
            animation,
            goal: Some(goal.target()),
            caption: motion.caption(),
            fps: args.fps.unwrap_or(DEFAULT_FPS),
        };
        let bytes =
            draw_for_command(&drawing, out.format, args.picture.width, args.picture.height, animation.frames.len())?;
        out.commit(&bytes)?;
    }

    output::stdout(|w| match args.format {
        AnimateFormat::Json => {
            serde_json::to_writer_pretty(&mut *w, &AnimateJson::new(&arm, &motion.motion))?;
            writeln!(w)
        }
        AnimateFormat::Csv => csv(w, animation, arm.chain.len()),
    })
}

/// The timing the flags ask for ([`crate::motion::timing`]).
fn timing(args: &AnimateArgs) -> Result<Timing, CliError> {
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
