//! `ikarus track --rig FILE --effector NAME`: the tip of one bone follows a path, online, each
//! sample solved from the previous pose, while the rig's other goals hold and its pins stay
//! where they start (the library's [`ikarus::track::follow_rig`]); per-sample JSON (angles and
//! tips keyed by bone name), CSV or text, and a picture or GIF of the skeleton with `--out`.
//! The job and its JSON are shared with `POST /api/track` with `rig`.

use std::io::Write;
use std::path::Path as FilePath;

use ikarus::track::{Track, TrackMode};
use ikarus::{LimitMode, RigTask};

use crate::error::CliError;
use crate::output;
use crate::picture::{Drawing, PictureFormat, draw_for_command, report_format, rig_figure};
use crate::rig::Rig;
use crate::rig_args::Target;
use crate::rig_motion::poses_animation;
use crate::rig_solve::angle_columns;
use crate::track::{TRACK_FPS, TrackArgs, TrackFormat, TrackJob, cli_path, csv_with};

pub use ikarus_edge::rig_track::*;

pub fn run(args: &TrackArgs, file: &FilePath) -> Result<(), CliError> {
    let rig = Rig::load(file)?;
    let Some(name) = &args.effector else {
        return Err(CliError::input("--effector: required with --rig: the bone whose tip follows the path"));
    };
    if let Some(mode) = args.mode.filter(|&m| m != TrackMode::Follow) {
        return Err(CliError::input(format!(
            "--mode {}: a rig's effector is followed online only (--mode follow, the default with --rig)",
            mode.name()
        )));
    }
    let picture = args.picture.prepare(&[PictureFormat::Svg, PictureFormat::Png, PictureFormat::Gif])?;
    let path = cli_path(args)?;
    let targets = args.goal.iter().map(Target::of).collect::<Result<Vec<_>, _>>()?;
    let task = if targets.is_empty() && args.rig_task.pin.is_empty() {
        args.rig_task.check_against(&[])?;
        RigTask { mix: args.rig_task.mix.unwrap_or(1.0), ..RigTask::default() }
    } else {
        args.rig_task.task(&rig.skeleton, &targets)?
    };
    let bone = effector_index(&rig, name, &task, "--effector").map_err(CliError::input)?;
    let solve = rig.options(&args.solver.settings(), None)?;
    let options = TrackJob::options(solve, args.max_step_deg, args.bound_first);
    let start = rig.skeleton.start_angles().to_vec();
    let job = RigTrackJob { rig: &rig, start, bone, task, path, options };
    let t = job.run().map_err(CliError::input)?;
    let drew = picture.is_some();
    if let Some(out) = picture {
        let poses: Vec<Vec<f64>> = t.samples.iter().map(|s| s.angles.clone()).collect();
        let animation = poses_animation(&rig, &poses);
        let last = poses.last().map_or(job.start.as_slice(), Vec::as_slice);
        let ranges = job.options.solve.limits != LimitMode::Ignore;
        let mut figure = rig_figure(&rig, last, &job.task, ranges, Some(job.caption(&t)));
        if let Some(goal) = t.samples.last().map(|s| s.goal) {
            figure.goals.push(ikarus_render::BoneGoal { bone, position: goal.target(), angle: goal.orientation() });
        }
        let drawing = Drawing::RigMotion { figure, animation: &animation, fps: TRACK_FPS };
        let bytes = draw_for_command(&drawing, out.format, &args.picture, poses.len())?;
        out.commit(&bytes)?;
    }
    // With --out the picture is the result: stdout stays quiet unless a format is asked for.
    let Some(format) = report_format(args.format, drew, TrackFormat::Text, TrackFormat::Json) else { return Ok(()) };
    output::stdout(|w| match format {
        TrackFormat::Json => {
            serde_json::to_writer_pretty(&mut *w, &job.json(&t))?;
            writeln!(w)
        }
        TrackFormat::Csv => {
            let columns = angle_columns(&rig).split(',').map(str::to_owned).collect();
            csv_with(w, &t, columns)
        }
        TrackFormat::Text => text(w, &job, &t),
    })
}

fn text(w: &mut dyn Write, job: &RigTrackJob, t: &Track) -> std::io::Result<()> {
    let s = &t.summary;
    let sk = &job.rig.skeleton;
    writeln!(w, "rig       {} ({} bones)", job.rig.name, sk.len())?;
    let held: Vec<String> = job
        .task
        .goals
        .iter()
        .map(|g| format!("{} at ({}, {})", sk.name(g.bone), g.goal.target().x, g.goal.target().y))
        .chain(job.task.pins.iter().map(|p| format!("{} pinned", sk.name(p.bone))))
        .collect();
    let held = if held.is_empty() { String::new() } else { format!("; held: {}", held.join(", ")) };
    writeln!(w, "effector  {}{held}", sk.name(job.bone))?;
    writeln!(w, "mode      follow (bound {}° per sample)", job.options.max_step.to_degrees())?;
    writeln!(
        w,
        "samples   {}: {} reached, {} limited, {} unreachable, {} stalled",
        s.samples, s.reached, s.limited, s.unreachable, s.stalled
    )?;
    let which = if s.flips.is_empty() { String::new() } else { format!(" at samples {:?}", s.flips) };
    writeln!(w, "flips     {}{which}", s.flips.len())?;
    writeln!(
        w,
        "steps     largest {:.3}°; acceleration {:.3}°, jerk {:.3}° per sample",
        s.max_step.to_degrees(),
        s.max_acceleration.to_degrees(),
        s.max_jerk.to_degrees()
    )?;
    writeln!(w, "error     largest {:.3e} (every effector: the followed tip, held goals, pins)", s.max_error)
}
