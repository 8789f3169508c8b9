//! `ikarus track`: the tip follows a path (a CSV file, a line, a circle or a figure-8), online
//! (`--mode follow`) or planned over the whole path (`--mode plan`, the default); per-sample
//! JSON, CSV or text on stdout, and a picture or GIF with `--out`. The job, its JSON shape and
//! its picture are shared with `POST /api/track`. With `--rig FILE --effector NAME`, the tip of
//! one bone follows the path online while the rig's other goals hold and its pins stay where
//! they start; angles and tips keyed by bone name.

use std::io::Write;
use std::path::PathBuf;

use clap::{ArgGroup, Args, ValueEnum};
use ikarus::track::{Path, PathError, Track, TrackMode};
use ikarus::{LimitMode, RigTask};
pub use ikarus_edge::track::*;

use crate::arm::Arm;
use crate::body::Body;
use crate::columns::BodyColumns;
use crate::error::Error;
use crate::goal_args::{GoalArg, RigTaskArgs, Target, parse_goal};
use crate::motion::poses_animation;
use crate::options::{named, parse_finite, parse_positive};
use crate::output;
use crate::picture::{Drawing, PictureArgs, PictureFormat, draw_for_command, report_format, rig_figure};
use crate::rig::Rig;
use crate::settings::SolverFlags;

/// Frames per second of a track's GIF: one frame per sample.
pub const TRACK_FPS: f64 = 25.0;

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum TrackFormat {
    /// One JSON object: every sample and a summary (the default when stdout is not a terminal)
    Json,
    /// One row per sample
    Csv,
    /// A short summary for people (the default on a terminal)
    Text,
    /// With a character file: the file with the motion added as a Spine animation
    Spine,
}

/// The tip follows a path.
///
/// `--max-step-deg` is the tracking bound here (a joint's largest change between samples, and
/// the flip threshold), as in the API's `max_step_deg`; the solver's per-iteration cap, which
/// other commands call `--max-step-deg`, is `--solver-max-step-deg` in this command.
#[derive(Debug, Args)]
#[command(group(ArgGroup::new("shape").required(true).multiple(false)))]
#[command(mut_arg("max_step_deg", |a| a.long("solver-max-step-deg")))]
pub struct TrackArgs {
    /// Arm file (TOML) [default: the built-in seed arm]
    #[arg(long, value_name = "FILE")]
    pub arm: Option<PathBuf>,
    /// Rig file (TOML): the tip of bone --effector NAME follows the path, online (--mode
    /// follow), while the rig's other --goal NAME=X,Y hold and its --pin NAME stay where they
    /// start
    #[arg(long, value_name = "FILE", conflicts_with = "arm")]
    pub rig: Option<PathBuf>,
    /// With --rig: the bone whose tip follows the path
    #[arg(long, value_name = "NAME", requires = "rig")]
    pub effector: Option<String>,
    /// With --rig: a goal held while the effector follows the path, NAME=X,Y[,DEG] (repeatable)
    #[arg(long, value_name = "NAME=X,Y[,DEG]", allow_hyphen_values = true, value_parser = parse_goal, requires = "rig")]
    pub goal: Vec<GoalArg>,
    #[command(flatten)]
    pub rig_task: RigTaskArgs,
    #[command(flatten)]
    pub solver: SolverFlags,
    /// The path as a CSV file: header `x,y` or `x,y,angle_deg`, one sample per row, used as given
    #[arg(long, value_name = "FILE.csv", group = "shape")]
    pub path: Option<PathBuf>,
    /// A straight line from (X0, Y0) to (X1, Y1)
    #[arg(long, value_name = "X0,Y0,X1,Y1", allow_hyphen_values = true, value_parser = parse_numbers::<4>, group = "shape")]
    pub line: Option<[f64; 4]>,
    /// A circle around (CX, CY) of radius R, counter-clockwise from (CX + R, CY), closed
    #[arg(long, value_name = "CX,CY,R", allow_hyphen_values = true, value_parser = parse_numbers::<3>, group = "shape")]
    pub circle: Option<[f64; 3]>,
    /// A figure-8 (lemniscate of Gerono) around (CX, CY), 2A wide and A high, closed
    #[arg(long, value_name = "CX,CY,A", allow_hyphen_values = true, value_parser = parse_numbers::<3>, group = "shape")]
    pub figure8: Option<[f64; 3]>,
    /// Samples of a --line, --circle or --figure8, at least 2 [default: 100]
    #[arg(long, value_name = "N", conflicts_with = "path")]
    pub samples: Option<usize>,
    /// Largest number of samples tracked, of a shape or a --path file
    #[arg(long, value_name = "N", default_value_t = DEFAULT_MAX_SAMPLES)]
    pub max_samples: usize,
    /// follow: online, every joint step within the bound; plan: a global search for the joint
    /// path without flips (or with the smallest) and least motion [default: plan; with --rig,
    /// follow, the only mode for a rig]
    #[arg(long, value_parser = named::<TrackMode>(), hide_possible_values = false)]
    pub mode: Option<TrackMode>,
    /// With --mode follow: bound the first sample too, a step of at most the bound from the start
    /// pose (by default it is placed at the solution nearest the start pose)
    #[arg(long)]
    pub bound_first: bool,
    /// The bound on any joint's change between consecutive samples, degrees: follow never
    /// exceeds it, and a larger step is a flip
    #[arg(long = "max-step-deg", id = "track_max_step_deg", value_name = "DEG", value_parser = parse_positive,
          default_value_t = DEFAULT_MAX_STEP_DEG)]
    pub max_step_deg: f64,
    /// Output format on stdout [default: text on a terminal, json otherwise; nothing with --out;
    /// with a character file, json (its frames) or spine, written to --out FILE if given]
    #[arg(long, value_enum)]
    pub format: Option<TrackFormat>,
    /// With a character file (--rig FILE.json): samples per second, one pose per sample
    /// [default: 30]
    #[arg(long, value_name = "F", value_parser = parse_finite)]
    pub fps: Option<f64>,
    /// With --format spine: the name of the animation added to the file [default: ikarus]
    #[arg(long, value_name = "NAME")]
    pub animation_name: Option<String>,
    /// With --format spine: every bone keyed at every frame, the IK constraints at mix 0 (the
    /// frame-by-frame bake), instead of the keys an animator edits
    #[arg(long)]
    pub bake: bool,
    /// With a character file: physics constraints on plays the frames as a game's frames at
    /// --fps, the physics stepping from one to the next; off leaves them out (Spine's
    /// Physics.none) [default: on]
    #[arg(long, value_enum)]
    pub physics: Option<crate::pose::PhysicsSwitch>,
    #[command(flatten)]
    pub ik: crate::pose::IkArgs,
    #[command(flatten)]
    pub picture: PictureArgs,
    #[command(flatten)]
    pub art: crate::motion_art::MotionArtArgs,
}

/// The default cap of `--samples` (and of a `--path` file's rows): 10⁶ samples, about ten
/// seconds of planning on the built-in arm.
pub const DEFAULT_MAX_SAMPLES: usize = 1_000_000;

/// `N` comma-separated finite numbers.
fn parse_numbers<const N: usize>(s: &str) -> Result<[f64; N], String> {
    let parts: Vec<&str> = s.split(',').collect();
    if parts.len() != N {
        return Err(format!("expected {N} comma-separated numbers, got {} part(s)", parts.len()));
    }
    let mut out = [0.0; N];
    for (i, (o, p)) in out.iter_mut().zip(parts).enumerate() {
        *o = parse_finite(p).map_err(|m| format!("number {}: {m}", i + 1))?;
    }
    Ok(out)
}

pub fn run(args: &TrackArgs) -> Result<(), Error> {
    if let Some(file) = crate::character_motion::character(args.rig.as_deref()) {
        return character(args, &file?);
    }
    let [ik, ik_file] = args.ik.given();
    let [atlas, art_only, skin] = args.art.given();
    crate::character_motion::refuse_without(&[
        ("--fps", args.fps.is_some()),
        atlas,
        art_only,
        skin,
        ("--animation-name", args.animation_name.is_some()),
        ("--bake", args.bake),
        ("--physics", args.physics.is_some()),
        ("--format spine", args.format == Some(TrackFormat::Spine)),
        ik,
        ik_file,
    ])?;
    match Body::load(args.arm.as_deref(), args.rig.as_deref())? {
        Body::Chain(arm) => track(args, &*arm),
        Body::Rig(rig) => track(args, &*rig),
    }
}

/// What a track asks of a body beyond the edge's [`TrackBody`]: who follows the path (from the
/// flags), its picture, its JSON, and the lines of its report that name the body.
trait Tracked: TrackBody + BodyColumns + Sized {
    /// The flags checked before the picture's: a rig's effector and mode.
    fn check(&self, args: &TrackArgs) -> Result<(), Error>;
    /// Who follows the path, from the flags.
    fn follower(&self, args: &TrackArgs) -> Result<Self::Follower, Error>;
    /// The picture of the track, the bytes `draw` makes of its drawing.
    fn draw(job: &TrackJob<Self>, t: &Track, poses: &[Vec<f64>], draw: Draw) -> Result<Vec<u8>, Error>;
    /// The JSON object of the track.
    fn json(job: &TrackJob<Self>, t: &Track, w: &mut dyn Write) -> serde_json::Result<()>;
    /// The report's first lines: the body, who follows and how.
    fn head(job: &TrackJob<Self>, w: &mut dyn Write) -> std::io::Result<()>;
    /// What the report's largest error covers.
    const ERROR_NOTE: &str;
    /// The mode without `--mode`: an arm's plan, a rig's follow (its only one).
    const MODE: TrackMode;
}

/// The bytes of a drawing of `n` frames.
type Draw<'a> = &'a dyn Fn(&Drawing, usize) -> Result<Vec<u8>, Error>;

/// The one track workflow: the flags checked, the path tracked, the picture drawn and the
/// report written, for an arm or a rig.
fn track<B: Tracked>(args: &TrackArgs, body: &B) -> Result<(), Error> {
    body.check(args)?;
    let picture = args.picture.prepare(&[PictureFormat::Svg, PictureFormat::Png, PictureFormat::Gif])?;
    let path = cli_path(args)?;
    let follower = body.follower(args)?;
    let solve = body.solve_options(&args.solver.settings(), None)?;
    if args.bound_first && args.mode.unwrap_or(B::MODE) != TrackMode::Follow {
        return Err(Error::input("--bound-first: only applies with --mode follow"));
    }
    let options = track_options(solve, args.max_step_deg, args.bound_first);
    let job = TrackJob { body, start: body.start().to_vec(), follower, path, options };
    let t = job.run()?;
    let drew = picture.is_some();
    if let Some(out) = picture {
        let poses: Vec<Vec<f64>> = t.samples.iter().map(|s| s.angles.clone()).collect();
        let bytes = B::draw(&job, &t, &poses, &|drawing, n| draw_for_command(drawing, out.format, &args.picture, n))?;
        out.commit(&bytes)?;
    }
    // With --out the picture is the result: stdout stays quiet unless a format is asked for.
    let Some(format) = report_format(args.format, drew, TrackFormat::Text, TrackFormat::Json) else { return Ok(()) };
    output::stdout(|w| match format {
        TrackFormat::Json => {
            B::json(&job, &t, &mut *w)?;
            writeln!(w)
        }
        TrackFormat::Csv => csv_with(w, &t, body.pose_columns(), &|w, q| body.write_pose(w, q)),
        TrackFormat::Text => text(w, &job, &t),
        TrackFormat::Spine => unreachable!("--format spine is refused without a character file"),
    })
}

/// `ikarus track --rig FILE.json --effector BONE …`: the bone's world origin follows the path,
/// one sample per pose at --fps, the file's IK constraints posing the rest.
fn character(args: &TrackArgs, file: &crate::character_motion::CharacterFile) -> Result<(), Error> {
    use crate::character_motion::{Output, refuse_foreign, write};
    use ikarus_edge::character::motion::{Course, DEFAULT_FPS, Motion};
    let mut foreign =
        vec![("--goal", !args.goal.is_empty()), ("--mode", args.mode.is_some()), ("--bound-first", args.bound_first)];
    foreign.extend(args.rig_task.given());
    foreign
        .extend(args.solver.given().map(|(f, g)| (if f == "--max-step-deg" { "--solver-max-step-deg" } else { f }, g)));
    refuse_foreign(&foreign)?;
    let written = crate::character_motion::written(args.format)?;
    let Some(bone) = args.effector.clone() else {
        return Err(Error::input(
            "--effector: required with a character file (the bone whose origin follows the path)",
        ));
    };
    let fps = args.fps.unwrap_or(DEFAULT_FPS);
    if fps <= 0.0 {
        return Err(Error::input(format!("--fps {fps}: must be positive")));
    }
    let points = cli_path(args)?.goals().iter().map(|g| [g.target().x, g.target().y]).collect();
    let mut motion = Motion::new(&file.loaded, Course::Path { bone, points }, fps)
        .map_err(|e| Error::input(format!("{}: {e}", file.label)))?;
    motion.ik = args.ik.choice(&file.loaded.character)?;
    motion.physics = crate::pose::PhysicsSwitch::motion(args.physics);
    motion.skin.clone_from(&args.art.skin);
    let out = Output {
        written,
        animation_name: args.animation_name.as_deref(),
        form: ikarus_edge::character::export::Form::asked(args.bake),
        picture: &args.picture,
        fewer: "fewer --samples",
        art: &args.art,
    };
    write(file, &motion, &out)
}

/// The path the flags ask for: a CSV file or a sampled shape.
pub fn cli_path(args: &TrackArgs) -> Result<Path, Error> {
    if let Some(file) = &args.path {
        let path = read_path(file)?;
        if path.len() > args.max_samples {
            return Err(Error::input(format!(
                "--path {}: {} samples, more than the cap of {} (raise it with --max-samples N)",
                file.display(),
                path.len(),
                args.max_samples
            )));
        }
        return Ok(path);
    }
    let shape = match (args.line, args.circle, args.figure8) {
        (Some(l), _, _) => Shape::Line(l),
        (_, Some(c), _) => Shape::Circle(c),
        (_, _, Some(f)) => Shape::Figure8(f),
        _ => unreachable!("clap requires one of --path, --line, --circle, --figure8"),
    };
    let samples = args.samples.unwrap_or(DEFAULT_SAMPLES);
    if samples > args.max_samples {
        return Err(Error::input(format!(
            "--samples {samples}: more than the cap of {} (raise it with --max-samples N)",
            args.max_samples
        )));
    }
    shape.path(samples).map_err(|e| match e {
        PathError::Samples { value } => Error::input(format!("--samples {value}: must be at least 2")),
        other => Error::input(format!("--{} {other}", shape.name())),
    })
}

/// A path CSV: header `x,y` or `x,y,angle_deg`, one sample per row; errors name the line and
/// the column.
fn read_path(file: &std::path::Path) -> Result<Path, Error> {
    let label = format!("--path {}", file.display());
    Path::new(crate::goals::read(file, &label)?.goals)
        .map_err(|_| Error::input(format!("{label}: no samples (expected a header and one sample per row)")))
}

/// How a sample's pose is written: `,value` for each of the pose's columns.
type PoseWriter<'a> = &'a dyn Fn(&mut dyn Write, &[f64]) -> std::io::Result<()>;

/// One row per sample, the pose under `pose_columns`, written by `pose`.
pub fn csv_with(w: &mut dyn Write, t: &Track, pose_columns: Vec<String>, pose: PoseWriter) -> std::io::Result<()> {
    let oriented = t.samples.iter().any(|s| s.goal.orientation().is_some());
    let mut header = vec!["sample", "x", "y"].into_iter().map(str::to_owned).collect::<Vec<_>>();
    if oriented {
        header.push("angle_deg".to_owned());
    }
    header.extend(["status", "error", "step_deg"].map(str::to_owned));
    header.extend(pose_columns);
    writeln!(w, "{}", header.join(","))?;
    for (k, s) in t.samples.iter().enumerate() {
        let p = s.goal.target();
        write!(w, "{k},{:?},{:?}", p.x, p.y)?;
        if oriented {
            write!(w, ",{}", s.goal.orientation().map_or(String::new(), |a| format!("{:?}", a.to_degrees())))?;
        }
        write!(w, ",{},{:?},{:?}", s.status, s.error, s.step.to_degrees())?;
        pose(w, &s.angles)?;
        writeln!(w)?;
    }
    Ok(())
}

/// The short summary: the body, who follows, the samples, flips, steps and error.
fn text<B: Tracked>(w: &mut dyn Write, job: &TrackJob<B>, t: &Track) -> std::io::Result<()> {
    let s = &t.summary;
    B::head(job, w)?;
    writeln!(
        w,
        "samples   {}: {} reached, {} limited, {} unreachable, {} stalled",
        s.samples, s.reached, s.limited, s.unreachable, s.stalled
    )?;
    if s.off_path > 0 {
        writeln!(w, "off path  {} poses between samples, within the bound", s.off_path)?;
    }
    let which = if s.flips.is_empty() { String::new() } else { format!(" at samples {:?}", s.flips) };
    writeln!(w, "flips     {}{which}", s.flips.len())?;
    writeln!(
        w,
        "steps     largest {:.3}°; acceleration {:.3}°, jerk {:.3}° per sample",
        s.max_step.to_degrees(),
        s.max_acceleration.to_degrees(),
        s.max_jerk.to_degrees()
    )?;
    writeln!(w, "error     largest {:.3e}{}", s.max_error, B::ERROR_NOTE)
}

impl Tracked for Arm {
    fn check(&self, _: &TrackArgs) -> Result<(), Error> {
        Ok(())
    }

    fn follower(&self, args: &TrackArgs) -> Result<TrackMode, Error> {
        Ok(args.mode.unwrap_or(Self::MODE))
    }

    fn draw(job: &TrackJob<Self>, t: &Track, poses: &[Vec<f64>], draw: Draw) -> Result<Vec<u8>, Error> {
        let layer = job.layer(t);
        let drawing =
            Drawing::Track { chain: &job.body.chain, poses, layer: &layer, caption: job.caption(t), fps: TRACK_FPS };
        draw(&drawing, poses.len())
    }

    fn json(job: &TrackJob<Self>, t: &Track, w: &mut dyn Write) -> serde_json::Result<()> {
        serde_json::to_writer_pretty(w, &TrackJson::new(job, t))
    }

    fn head(job: &TrackJob<Self>, w: &mut dyn Write) -> std::io::Result<()> {
        writeln!(w, "arm       {} ({} links)", job.body.name, job.body.chain.len())?;
        writeln!(w, "mode      {} (bound {}° per sample)", job.follower.name(), job.options.max_step.to_degrees())
    }

    const ERROR_NOTE: &str = "";
    const MODE: TrackMode = TrackMode::Plan;
}

impl Tracked for Rig {
    fn check(&self, args: &TrackArgs) -> Result<(), Error> {
        // An arm file's rig: its last link's tip follows the path unless --effector says otherwise.
        if args.effector.is_none() && self.tip.is_none() {
            return Err(Error::input("--effector: required with --rig: the bone whose tip follows the path"));
        }
        if let Some(mode) = args.mode.filter(|&m| m != TrackMode::Follow) {
            return Err(Error::input(format!(
                "--mode {}: a rig's effector is followed online only (--mode follow, the default with --rig)",
                mode.name()
            )));
        }
        Ok(())
    }

    fn follower(&self, args: &TrackArgs) -> Result<RigFollower, Error> {
        let tip = self.tip.map(|t| self.skeleton.name(t));
        let name = args.effector.as_deref().or(tip).unwrap_or_default();
        let targets = args.goal.iter().map(|g| Target::of(g, self)).collect::<Result<Vec<_>, _>>()?;
        let task = if targets.is_empty() && args.rig_task.pin.is_empty() {
            args.rig_task.check_against(&[])?;
            RigTask { mix: args.rig_task.mix.unwrap_or(1.0), ..RigTask::default() }
        } else {
            args.rig_task.task(&self.skeleton, &targets)?
        };
        let bone = effector_index(self, name, &task, "--effector")?;
        Ok(RigFollower { bone, task })
    }

    fn draw(job: &TrackJob<Self>, t: &Track, poses: &[Vec<f64>], draw: Draw) -> Result<Vec<u8>, Error> {
        let animation = poses_animation(job.body, poses);
        let last = poses.last().map_or(job.start.as_slice(), Vec::as_slice);
        let ranges = job.options.solve.limits != LimitMode::Ignore;
        let mut figure = rig_figure(job.body, last, &job.follower.task, ranges, Some(job.caption(t)));
        if let Some(goal) = t.samples.last().map(|s| s.goal) {
            let (bone, position, angle) = (job.follower.bone, goal.target(), goal.orientation());
            figure.goals.push(ikarus_render::BoneGoal { bone, position, angle });
        }
        draw(&Drawing::RigMotion { figure, animation: &animation, fps: TRACK_FPS }, poses.len())
    }

    fn json(job: &TrackJob<Self>, t: &Track, w: &mut dyn Write) -> serde_json::Result<()> {
        serde_json::to_writer_pretty(w, &job.json(t))
    }

    fn head(job: &TrackJob<Self>, w: &mut dyn Write) -> std::io::Result<()> {
        let sk = &job.body.skeleton;
        writeln!(w, "rig       {} ({} bones)", job.body.name, sk.len())?;
        let task = &job.follower.task;
        let held: Vec<String> = task
            .goals
            .iter()
            .map(|g| format!("{} at ({}, {})", sk.name(g.bone), g.goal.target().x, g.goal.target().y))
            .chain(task.pins.iter().map(|p| format!("{} pinned", sk.name(p.bone))))
            .collect();
        let held = if held.is_empty() { String::new() } else { format!("; held: {}", held.join(", ")) };
        writeln!(w, "effector  {}{held}", sk.name(job.follower.bone))?;
        writeln!(w, "mode      follow (bound {}° per sample)", job.options.max_step.to_degrees())
    }

    const ERROR_NOTE: &str = " (every effector: the followed tip, held goals, pins)";
    const MODE: TrackMode = TrackMode::Follow;
}
