//! The answers of a single solve for people and for CSV: an arm's ([`ChainReport`]) and a
//! rig's ([`rig_csv`], [`rig_text`]), and a rig's pose columns, which `animate` and `track`
//! write too.

use std::io::Write;

use ikarus::{Goal, LimitMode, Outcome, RigTask, SolveOptions};

use crate::arm::Arm;
use crate::report::{SolveJson, SolveReport, deg_text};
use crate::rig::Rig;

// Floats in CSV are written with `{:?}`: the shortest text that reads back to the same
// number, in scientific notation where that is shorter (1.2e-7, not 0.00000012).

/// A finished single solve of an arm and what it needs to be described.
pub(super) struct ChainReport<'a> {
    pub(super) arm: &'a Arm,
    pub(super) options: &'a SolveOptions,
    pub(super) goal: &'a Goal,
    pub(super) outcome: &'a Outcome,
    pub(super) micros: f64,
}

impl ChainReport<'_> {
    pub(super) fn json(&self) -> SolveJson<'_> {
        SolveReport { body: (self.arm, self.goal), options: self.options, outcome: self.outcome, micros: self.micros }
            .json()
    }

    pub(super) fn csv(&self, w: &mut dyn Write) -> std::io::Result<()> {
        let n = self.arm.chain.len();
        let mut header = vec!["iteration".to_owned()];
        header.extend((1..=n).map(|i| format!("theta{i}_deg")));
        for k in 0..=n {
            header.push(format!("x{k}"));
            header.push(format!("y{k}"));
        }
        writeln!(w, "{}", header.join(","))?;
        for f in self.outcome.frames.iter() {
            write!(w, "{}", f.iteration)?;
            for a in f.angles {
                write!(w, ",{:?}", a.to_degrees())?;
            }
            for p in f.joints {
                write!(w, ",{:?},{:?}", p.x, p.y)?;
            }
            writeln!(w)?;
        }
        Ok(())
    }

    pub(super) fn text(&self, w: &mut dyn Write) -> std::io::Result<()> {
        let o = self.outcome;
        let opts = self.options;
        let target = self.goal.target();
        let goal_angle = self.goal.orientation().map_or(String::new(), |a| format!(" at {}", deg_text(a, 3)));
        let limits = match (opts.limits, self.arm.chain.has_limits()) {
            (ikarus::LimitMode::Ignore, true) => "off (the arm has ranges: --limits enforces them)".to_owned(),
            (ikarus::LimitMode::Ignore, false) => "off".to_owned(),
            (mode, _) => format!("on ({})", mode.name()),
        };
        writeln!(
            w,
            "arm       {} ({} links, reach {})",
            self.arm.name,
            self.arm.chain.len(),
            self.arm.chain.max_reach()
        )?;
        writeln!(w, "goal      ({}, {}){goal_angle}", target.x, target.y)?;
        writeln!(w, "method    {}   limits {limits}", opts.method.name())?;
        let restarts = match o.restarts {
            0 => String::new(),
            1 => ", 1 restart".to_owned(),
            k => format!(", {k} restarts"),
        };
        match o.reach_distance {
            Some(d) if o.status == ikarus::Status::Unreachable && d > 0.0 => writeln!(
                w,
                "status    unreachable: {d:.6} outside the reachable region, the tip at its nearest point ({:.1} µs)",
                self.micros
            )?,
            _ => writeln!(
                w,
                "status    {} after {} iterations{restarts} ({:.1} µs)",
                o.status, o.iterations, self.micros
            )?,
        }
        write!(w, "error     {:.3e} (tolerance {:e})", o.error, opts.tolerance)?;
        if self.goal.orientation().is_some() {
            write!(w, ", orientation {:.3e}°", o.angle_error.to_degrees())?;
        }
        writeln!(w)?;
        let tip = o.end_effector;
        writeln!(
            w,
            "tip       ({:.6}, {:.6}) pointing {}",
            tip.position.x,
            tip.position.y,
            deg_text(tip.orientation, 3)
        )?;
        let angles: Vec<String> = o.pose.angles().iter().map(|&a| deg_text(a, 3)).collect();
        writeln!(w, "angles    {}", angles.join(", "))?;
        let joints = ikarus::kinematics::joint_positions(&self.arm.chain, o.pose.angles());
        let joints: Vec<String> = joints.iter().map(|p| format!("({:.3}, {:.3})", p.x, p.y)).collect();
        writeln!(w, "joints    {}", joints.join(" → "))?;
        if let Some(k) = opts.record_every {
            writeln!(
                w,
                "frames    {} recorded (every {k} iterations; --format json or csv lists them)",
                o.frames.len()
            )?;
        }
        Ok(())
    }
}

/// The CSV header of a rig's pose: `NAME_deg` per bone, then `NAME_ext` per prismatic bone,
/// in the rig's order ([`crate::report::pose_columns`]).
pub fn angle_columns(rig: &Rig) -> String {
    crate::report::pose_columns(&rig.skeleton).join(",")
}

/// `,value` for every column of [`angle_columns`] at joint values `q`.
pub fn write_pose(w: &mut dyn Write, rig: &Rig, q: &[f64]) -> std::io::Result<()> {
    for v in crate::report::pose_values(&rig.skeleton, q) {
        write!(w, ",{v:?}")?;
    }
    Ok(())
}

/// One row: `status,iterations,error` and every bone's angle (then every prismatic bone's
/// displacement).
pub(super) fn rig_csv(w: &mut dyn Write, rig: &Rig, o: &Outcome) -> std::io::Result<()> {
    writeln!(w, "status,iterations,error,{}", angle_columns(rig))?;
    write!(w, "{},{},{:?}", o.status, o.iterations, o.error)?;
    write_pose(w, rig, o.pose.angles())?;
    writeln!(w)
}

/// A report for people: the rig, the solve, one line per effector, the angles.
pub(super) fn rig_text(
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
