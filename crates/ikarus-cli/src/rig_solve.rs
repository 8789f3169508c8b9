//! `ikarus solve --rig FILE`: goals on the tips of a rig's bones and pins, solved together from
//! the rig's start pose and reported as JSON, CSV (one row) or text, with a picture on `--out`;
//! or a batch of target sets ([`crate::rig_batch`]).

use std::io::Write;
use std::path::Path;
use std::time::Instant;

use ikarus::{LimitMode, Outcome, RigTask, SolveOptions};

use crate::error::CliError;
use crate::output;
use crate::picture::{Drawing, draw, report_format, rig_figure};
use crate::report::deg_text;
use crate::rig::Rig;
use crate::rig_args::Target;
use crate::rig_report::RigSolveReport;
use crate::settings::solver;
use crate::solve::{Format, SolveArgs};

pub fn run(args: &SolveArgs, path: &Path) -> Result<(), CliError> {
    let rig = Rig::load(path)?;
    if let Some(batch) = &args.batch {
        return crate::rig_batch::run(args, &rig, batch);
    }
    let targets = args.goal.iter().map(Target::of).collect::<Result<Vec<_>, _>>()?;
    let task = args.rig_task.task(&rig.skeleton, &targets)?;
    // No frames unless asked for: a rig's frames are one point per bone each.
    let every = args.record_every.or(rig.solver.record_every);
    let mut solver = solver(rig.options(&args.solver.settings(), every)?)?;
    let picture = args.picture.prepare()?;
    let started = Instant::now();
    let outcome = solver
        .solve_rig(&rig.skeleton, rig.skeleton.start_angles(), &task)
        .map_err(|e| CliError::input(e.to_string()))?;
    let micros = started.elapsed().as_secs_f64() * 1e6;
    let options = solver.options();
    // With --out the picture is the result: stdout stays quiet unless a format is asked for.
    if let Some(format) = report_format(args.format, picture.is_some(), Format::Text, Format::Json) {
        output::stdout(|w| match format {
            Format::Json => {
                let report = RigSolveReport { rig: &rig, options, outcome: &outcome, micros };
                serde_json::to_writer_pretty(&mut *w, &report.json())?;
                writeln!(w)
            }
            Format::Csv => csv(w, &rig, &outcome),
            Format::Text => text(w, &rig, &task, options, &outcome, micros),
        })?;
    }
    if let Some(out) = picture {
        let caption = format!("{} · {} after {} iterations", rig.name, outcome.status, outcome.iterations);
        let figure = rig_figure(&rig, outcome.pose.angles(), &task, options.limits != LimitMode::Ignore, Some(caption));
        let bytes = draw(&Drawing::Skeleton(figure), out.format, args.picture.width, args.picture.height, &|_, _| {})?;
        out.commit(&bytes)?;
    }
    Ok(())
}

/// The CSV header of a rig's angles: `NAME_deg` per bone, in the rig's order.
pub fn angle_columns(rig: &Rig) -> String {
    rig.skeleton.names().iter().map(|n| format!("{n}_deg")).collect::<Vec<_>>().join(",")
}

/// One row: `status,iterations,error` and every bone's angle.
fn csv(w: &mut dyn Write, rig: &Rig, o: &Outcome) -> std::io::Result<()> {
    writeln!(w, "status,iterations,error,{}", angle_columns(rig))?;
    write!(w, "{},{},{:?}", o.status, o.iterations, o.error)?;
    for a in o.pose.angles() {
        write!(w, ",{:?}", a.to_degrees())?;
    }
    writeln!(w)
}

/// A report for people: the rig, the solve, one line per effector, the angles.
fn text(
    w: &mut dyn Write,
    rig: &Rig,
    task: &RigTask,
    opts: &SolveOptions,
    o: &Outcome,
    micros: f64,
) -> std::io::Result<()> {
    let s = &rig.skeleton;
    let limits = match (opts.limits, s.has_limits()) {
        (LimitMode::Ignore, true) => "off (the rig has ranges: --limits enforces them)".to_owned(),
        (LimitMode::Ignore, false) => "off".to_owned(),
        (mode, _) => format!("on ({})", mode.name()),
    };
    writeln!(w, "rig       {} ({} bones)", rig.name, s.len())?;
    writeln!(w, "method    {}   limits {limits}", opts.method.name())?;
    if task.mix < 1.0 {
        writeln!(w, "mix       {} of the way from the start pose to the solution", task.mix)?;
    }
    let restarts = match o.restarts {
        0 => String::new(),
        1 => ", 1 restart".to_owned(),
        k => format!(", {k} restarts"),
    };
    writeln!(w, "status    {} after {} iterations{restarts} ({micros:.1} µs)", o.status, o.iterations)?;
    writeln!(w, "error     {:.3e} (the largest; tolerance {:e})", o.error, opts.tolerance)?;
    let width = o.effectors.iter().map(|e| s.name(e.bone).chars().count()).max().unwrap_or(0);
    for (k, e) in o.effectors.iter().enumerate() {
        let what = if e.pinned {
            "pinned".to_owned()
        } else {
            let g = &task.goals[k].goal;
            let t = g.target();
            let angle = g.orientation().map_or(String::new(), |a| format!(" at {}", deg_text(a, 3)));
            format!("goal ({}, {}){angle}", t.x, t.y)
        };
        let mut line = format!(
            "  {:width$}  {what}: {} · error {:.3e} · tip ({:.6}, {:.6})",
            s.name(e.bone),
            e.status,
            e.error,
            e.tip.x,
            e.tip.y
        );
        if e.pinned || task.goals[k].goal.orientation().is_some() {
            line.push_str(&format!(" pointing {}", deg_text(e.orientation, 3)));
        }
        writeln!(w, "{}", line.trim_end())?;
    }
    let angles: Vec<String> =
        s.names().iter().zip(o.pose.angles()).map(|(n, &a)| format!("{n} {}", deg_text(a, 3))).collect();
    writeln!(w, "angles    {}", angles.join(", "))?;
    if let Some(k) = opts.record_every {
        writeln!(w, "frames    {} recorded (every {k} iterations; --format json lists them)", o.frames.len())?;
    }
    Ok(())
}
