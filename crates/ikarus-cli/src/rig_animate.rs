//! `ikarus animate --rig FILE` (and `ikarus render motion --rig FILE`): goal sets on a rig's
//! bones solved in turn — each `--via NAME=X,Y[;…]` set, then the `--goal NAME=X,Y …` set, the
//! `--pin NAME` bones held in each — and the poses eased into a motion; JSON, CSV or text on
//! stdout, a picture or a GIF of the skeleton with `--out`.

use std::io::Write;
use std::path::Path;

use ikarus::{EaseKind, LimitMode, RigTask};

use crate::animate::{AnimateArgs, AnimateFormat, MotionArgs, ViaArg};
use crate::error::CliError;
use crate::motion::DEFAULT_FPS;
use crate::output;
use crate::picture::{Drawing, PictureFormat, draw_for_command, report_format};
use crate::report::deg_text;
use crate::rig::Rig;
use crate::rig_args::{RigTaskArgs, Target};
use crate::rig_motion::{RigMotion, RigMotionPlan};
use crate::rig_solve::angle_columns;

/// A rig motion computed from the flags, with what its report and pictures need.
pub struct RigMotionRun {
    pub rig: Rig,
    pub motion: RigMotion,
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
        let mut targets = goals.iter().map(Target::of).collect::<Result<Vec<_>, _>>()?;
        for t in &mut targets {
            t.source = via.text();
        }
        tasks.push(plain.task(&rig.skeleton, &targets)?);
    }
    let targets = args.goal.iter().map(Target::of).collect::<Result<Vec<_>, _>>()?;
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
    let plan =
        RigMotionPlan { rig: &rig, start, tasks, options, timing, ease, interpolation, from_solve: args.from_solve };
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

pub fn run(args: &AnimateArgs, path: &Path) -> Result<(), CliError> {
    let picture = args.picture.prepare(&[PictureFormat::Svg, PictureFormat::Png, PictureFormat::Gif])?;
    let run = motion_run(&args.motion, path)?;
    let animation = &run.motion.motion.animation;
    let drew = picture.is_some();
    if let Some(out) = picture {
        let bytes = draw_for_command(&run.drawing(), out.format, &args.picture, animation.frames.len())?;
        out.commit(&bytes)?;
    }
    // With --out the picture is the result: stdout stays quiet unless a format is asked for.
    let Some(format) = report_format(args.format, drew, AnimateFormat::Text, AnimateFormat::Json) else {
        return Ok(());
    };
    output::stdout(|w| match format {
        AnimateFormat::Json => {
            serde_json::to_writer_pretty(&mut *w, &run.motion.json(&run.rig))?;
            writeln!(w)
        }
        AnimateFormat::Csv => csv(w, &run),
        AnimateFormat::Text => text(w, &run),
    })
}

/// One row per frame: `time`, every bone's angle (`NAME_deg`), every bone's tip
/// (`NAME.x,NAME.y`), in the rig's order.
fn csv(w: &mut dyn Write, run: &RigMotionRun) -> std::io::Result<()> {
    let names = run.rig.skeleton.names();
    let tips: Vec<String> = names.iter().map(|n| format!("{n}.x,{n}.y")).collect();
    writeln!(w, "time,{},{}", angle_columns(&run.rig), tips.join(","))?;
    for f in &run.motion.motion.animation.frames {
        write!(w, "{:?}", f.time)?;
        for a in &f.angles {
            write!(w, ",{:?}", a.to_degrees())?;
        }
        for p in &f.joints[1..] {
            write!(w, ",{:?},{:?}", p.x, p.y)?;
        }
        writeln!(w)?;
    }
    Ok(())
}

/// The short report: the rig, each goal set's solve, the timing, the first and last pose.
fn text(w: &mut dyn Write, run: &RigMotionRun) -> std::io::Result<()> {
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
    for (k, (solve, task)) in motion.solves.iter().zip(&run.motion.tasks).enumerate() {
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
