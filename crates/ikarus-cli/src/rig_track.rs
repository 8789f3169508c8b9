//! `ikarus track --rig FILE --effector NAME`: the tip of one bone follows a path, online, each
//! sample solved from the previous pose, while the rig's other goals hold and its pins stay
//! where they start (the library's [`ikarus::track::follow_rig`]); per-sample JSON (angles and
//! tips keyed by bone name), CSV or text, and a picture or GIF of the skeleton with `--out`.
//! The job and its JSON are shared with `POST /api/track` with `rig`.

use std::io::Write;
use std::path::Path as FilePath;

use ikarus::track::{self, Path, Track, TrackMode, TrackOptions};
use ikarus::{LimitMode, RigTask};
use serde::Serialize;

use crate::error::CliError;
use crate::output;
use crate::picture::{Drawing, PictureFormat, draw_for_command, report_format, rig_figure};
use crate::report::degrees;
use crate::rig::Rig;
use crate::rig_args::Target;
use crate::rig_motion::poses_animation;
use crate::rig_report::ByName;
use crate::rig_solve::angle_columns;
use crate::track::{TRACK_FPS, TrackArgs, TrackFormat, TrackJob, TrackSummaryJson, cli_path, csv_with};

/// One rig track: the workflow of `ikarus track --rig` and `POST /api/track` with `rig`.
pub struct RigTrackJob<'a> {
    pub rig: &'a Rig,
    pub start: Vec<f64>,
    /// The bone whose tip follows the path.
    pub bone: usize,
    /// The goals held and the pins, without the effector.
    pub task: RigTask,
    pub path: Path,
    pub options: TrackOptions,
}

/// The index of the effector bone `name`, which must exist and have neither a goal nor a pin
/// in `task`; a problem starts with `field` and the name (`--effector hand`).
pub fn effector_index(rig: &Rig, name: &str, task: &RigTask, field: &str) -> Result<usize, String> {
    let bone = crate::rig_task::index(&rig.skeleton, name).map_err(|m| format!("{field} {name}: {m}"))?;
    if task.goals.iter().any(|g| g.bone == bone) {
        return Err(format!("{field} {name}: the bone also has a goal; the effector's goal is the path"));
    }
    if task.pins.iter().any(|p| p.bone == bone) {
        return Err(format!("{field} {name}: the bone is also pinned; a pinned tip cannot follow a path"));
    }
    Ok(bone)
}

impl RigTrackJob<'_> {
    /// Follows the path; a problem is bad input, in the library's words.
    pub fn run(&self) -> Result<Track, String> {
        let s = &self.rig.skeleton;
        track::follow_rig(s, &self.start, self.bone, &self.task, &self.path, &self.options).map_err(|e| e.to_string())
    }

    /// A one-line caption for pictures.
    pub fn caption(&self, t: &Track) -> String {
        let s = &t.summary;
        format!(
            "{} · {} follows · {} of {} reached · {} flips · largest step {:.1}°",
            self.rig.name,
            self.rig.skeleton.name(self.bone),
            s.reached,
            s.samples,
            s.flips.len(),
            s.max_step.to_degrees()
        )
    }

    /// The JSON object of a finished track.
    pub fn json<'a>(&'a self, t: &Track) -> RigTrackJson<'a> {
        let s = &self.rig.skeleton;
        let names = s.names();
        let samples = t
            .samples
            .iter()
            .map(|x| {
                let p = x.goal.target();
                let tips = crate::rig_report::tips(self.rig, &x.angles);
                RigTrackSampleJson {
                    goal: [p.x, p.y],
                    angle_deg: x.goal.orientation().map(f64::to_degrees),
                    status: x.status.as_str(),
                    error: x.error,
                    angles_deg: ByName { names, values: degrees(&x.angles) },
                    joints: ByName { names, values: tips.iter().map(|p| [p.x, p.y]).collect() },
                    step_deg: x.step.to_degrees(),
                }
            })
            .collect();
        RigTrackJson {
            rig: &self.rig.name,
            effector: s.name(self.bone),
            mode: TrackMode::Follow.name(),
            samples,
            summary: TrackSummaryJson::new(&t.summary, self.options.max_step),
        }
    }
}

/// One sample of a rig track: as an arm's, with angles and tips keyed by bone name.
#[derive(Serialize)]
pub struct RigTrackSampleJson<'a> {
    pub goal: [f64; 2],
    #[serde(skip_serializing_if = "Option::is_none")]
    pub angle_deg: Option<f64>,
    pub status: &'static str,
    /// The largest effector error: the followed tip's, the held goals' and the pins'.
    pub error: f64,
    pub angles_deg: ByName<'a, f64>,
    pub joints: ByName<'a, [f64; 2]>,
    pub step_deg: f64,
}

/// A rig track: `ikarus track --rig --format json` and `POST /api/track` with `rig`.
#[derive(Serialize)]
pub struct RigTrackJson<'a> {
    pub rig: &'a str,
    /// The bone whose tip followed the path.
    pub effector: &'a str,
    pub mode: &'static str,
    pub samples: Vec<RigTrackSampleJson<'a>>,
    pub summary: TrackSummaryJson,
}

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
    let solve = rig.options(&args.solver, None)?;
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
