//! `ikarus animate`: solve for a goal (through any via points), then turn the poses into an
//! eased motion: frames on stdout, and a picture or an animated GIF with `--out`.

use std::io::Write;
use std::path::PathBuf;

use clap::{Args, ValueEnum};
use ikarus::Goal;
use ikarus::motion::{Animation, Timing};

use crate::arm::Arm;
use crate::ease_args::{EaseArg, EaseArgs};
use crate::error::CliError;
use crate::options::{SolverArgs, parse_angle, parse_at_least_one, parse_finite, parse_point};
use crate::output;
use crate::picture::{PictureArgs, PictureFormat, progress_bar, render_failed};
use crate::report::MotionRequest;

/// Frames of a motion when neither --frames nor --duration is given.
const DEFAULT_FRAMES: u32 = 60;
/// GIF frame rate when --fps is not given.
const DEFAULT_FPS: f64 = 30.0;

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
    pub solver: SolverArgs,
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
    /// Follow the solver's own path (its recorded frames), re-timed, instead of moving
    /// straight between the solved poses in joint space
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
    let ease = args.ease.resolve(EaseArg::Sine)?;
    let fps = args.fps.unwrap_or(DEFAULT_FPS);
    let picture = args.picture.prepare(&[PictureFormat::Svg, PictureFormat::Png, PictureFormat::Gif])?;

    // Solve for each via point, then the goal, each from the previous pose.
    let record = if args.from_solve { Some(args.record_every.unwrap_or(1)) } else { None };
    let options = args.solver.resolve(&arm.solver, record)?;
    let mut goals: Vec<Goal> = Vec::with_capacity(args.via.len() + 1);
    for (i, [x, y]) in args.via.iter().enumerate() {
        goals.push(Goal::position(*x, *y).map_err(|e| CliError::input(format!("--via #{}: {e}", i + 1)))?);
    }
    let [x, y] = args.goal;
    goals.push(crate::solve::make_goal(x, y, args.goal_angle).map_err(CliError::input)?);
    let motion = MotionRequest {
        arm: &arm,
        start: arm.chain.start_pose().angles().to_vec(),
        goals: goals.clone(),
        options,
        timing,
        ease,
        from_solve: args.from_solve,
    }
    .run()?;
    for s in &motion.solves {
        if s.status != ikarus::Status::Reached.as_str() {
            eprintln!(
                "ikarus: goal ({}, {}) not reached: {}, error {:.3e}; the motion ends at the best pose found",
                s.goal[0], s.goal[1], s.status, s.error
            );
        }
    }
    let animation = &motion.animation;

    if let Some(out) = picture {
        let goal = goals.last().map(Goal::target);
        let caption = motion.caption();
        let bytes = match out.format {
            PictureFormat::Gif => {
                let overlay = ikarus_render::Overlay {
                    goal,
                    workspace: None,
                    show_reach: true,
                    caption: Some(caption),
                    trail: true,
                };
                let bar = progress_bar(animation.frames.len() as u64, "rendering frames");
                let report = |done: usize, total: usize| {
                    if let Some(bar) = &bar {
                        bar.set_length(total as u64);
                        bar.set_position(done as u64);
                    }
                };
                let (w, h) = (args.picture.width, args.picture.height);
                let gif = ikarus_render::animation_gif(&arm.chain, animation, &overlay, w, h, fps, &report)
                    .map_err(|e| render_failed(&e))?;
                if let Some(bar) = bar {
                    bar.finish_and_clear();
                }
                gif
            }
            format => {
                let figure = ikarus_render::ArmFigure {
                    goal,
                    caption: Some(caption),
                    ..ikarus_render::ArmFigure::of_animation(&arm.chain, animation)
                };
                let svg = ikarus_render::arm_svg(&figure, args.picture.width, args.picture.height)
                    .map_err(|e| render_failed(&e))?;
                if format == PictureFormat::Png {
                    ikarus_render::svg_to_png(&svg).map_err(|e| render_failed(&e))?
                } else {
                    svg.into_bytes()
                }
            }
        };
        out.commit(&bytes)?;
    }

    output::stdout(|w| match args.format {
        AnimateFormat::Json => {
            serde_json::to_writer_pretty(&mut *w, &motion.json(&arm))?;
            writeln!(w)
        }
        AnimateFormat::Csv => csv(w, animation, arm.chain.len()),
    })
}

fn timing(args: &AnimateArgs) -> Result<Timing, CliError> {
    if let Some(fps) = args.fps {
        if !(fps > 0.0 && fps <= 100.0) {
            return Err(CliError::input(format!("--fps {fps}: must be greater than 0 and at most 100")));
        }
    }
    match (args.frames, args.duration) {
        (Some(n), _) if n < 2 => Err(CliError::input(format!("--frames {n}: a motion needs at least 2 frames"))),
        (Some(n), _) => Ok(Timing::Frames(n as usize)),
        (None, Some(seconds)) if seconds <= 0.0 => {
            Err(CliError::input(format!("--duration {seconds}: must be greater than 0")))
        }
        (None, Some(seconds)) => Ok(Timing::Duration { seconds, fps: args.fps.unwrap_or(DEFAULT_FPS) }),
        (None, None) => Ok(Timing::Frames(DEFAULT_FRAMES as usize)),
    }
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
