//! What `ikarus animate` asks of each body beyond the edge's [`MotionBody`]: its stops from the
//! flags (an arm's via points and goal, a rig's via sets and goal set), its warnings, its JSON,
//! its picture, and the lines and columns that name its joints (by index, by bone name).

use std::io::Write;

use ikarus::motion::{Animation, AnimationFrame as Frame};
use ikarus::number::Num;
use ikarus::{Goal, RigTask};

use super::{MotionArgs, MotionRun, ViaArg};
use crate::arm::Arm;
use crate::columns::BodyColumns;
use crate::error::Error;
use crate::goal_args::{GoalArg, RigTaskArgs, Target};
use crate::motion::MotionBody;
use crate::picture::{Drawing, MotionLayers, motion_drawing};
use crate::report::{AnimateJson, deg_text};
use crate::rig::Rig;

/// A body `ikarus animate` moves.
pub trait Animated: MotionBody + BodyColumns + Sized {
    /// The first of the animation's points in the CSV: an arm's base (0), a rig's first tip (1).
    const FIRST_POINT: usize;
    /// The stops the flags ask for.
    fn stops(&self, args: &MotionArgs) -> Result<Vec<Self::Stop>, Error>;
    /// The animation of the library's motion.
    fn animation(motion: &Self::Solved) -> &Animation;
    /// Reports each unreached stop on stderr.
    fn warn_unreached(motion: &Self::Solved);
    /// The JSON object of the motion.
    fn json(run: &MotionRun<Self>, w: &mut dyn Write) -> serde_json::Result<()>;
    /// The drawing of the motion.
    fn drawing(run: &MotionRun<Self>) -> Drawing<'_>;
    /// The report's first line: the body.
    fn head(&self) -> String;
    /// The report's line for each solve.
    fn solve_lines(run: &MotionRun<Self>, w: &mut dyn Write) -> std::io::Result<()>;
    /// A pose in the report, degrees.
    fn pose_text(&self, q: &[f64]) -> String;
    /// The report's lines after the last pose.
    fn end_lines(last: &Frame, w: &mut dyn Write) -> std::io::Result<()>;
    /// The CSV columns of the animation's points from [`Self::FIRST_POINT`].
    fn point_columns(&self) -> Vec<String>;
}

impl Animated for Arm {
    const FIRST_POINT: usize = 0;

    fn stops(&self, args: &MotionArgs) -> Result<Vec<Goal>, Error> {
        let goal = arm_goal(args)?;
        let via = args
            .via
            .iter()
            .map(|v| match v {
                ViaArg::Point(p) => Ok(*p),
                ViaArg::Set(_) => {
                    Err(Error::input(format!("{}: a goal set on named bones needs --rig FILE", v.text())))
                }
            })
            .collect::<Result<Vec<_>, _>>()?;
        crate::motion::goals(&via, goal).map_err(|(i, e)| Error::input(format!("--via #{}: {e}", i + 1)))
    }

    fn animation(motion: &Self::Solved) -> &Animation {
        &motion.animation
    }

    fn warn_unreached(motion: &Self::Solved) {
        for s in motion.solves.iter().filter(|s| s.status != ikarus::Status::Reached) {
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

    fn json(run: &MotionRun<Self>, w: &mut dyn Write) -> serde_json::Result<()> {
        serde_json::to_writer_pretty(w, &AnimateJson::new(&run.body, &run.motion.motion))
    }

    fn drawing(run: &MotionRun<Self>) -> Drawing<'_> {
        let (animation, caption) = (&run.motion.motion.animation, run.motion.caption());
        let goal = run.motion.stops.last().map(Goal::target);
        motion_drawing(&run.body, animation, caption, goal, run.fps, MotionLayers::default())
    }

    fn head(&self) -> String {
        format!("arm       {} ({} links, reach {})", self.name, self.chain.len(), self.chain.max_reach())
    }

    fn solve_lines(run: &MotionRun<Self>, w: &mut dyn Write) -> std::io::Result<()> {
        let solves = &run.motion.motion.solves;
        for (i, s) in solves.iter().enumerate() {
            let what = if i + 1 == solves.len() { "goal" } else { "via" };
            let target = s.goal.target();
            let angle = s.goal.orientation().map_or(String::new(), |a| format!(" at {}", deg_text(a, 3)));
            writeln!(
                w,
                "{what:<9} ({}, {}){angle}: {} after {} iterations, error {:.3e}",
                target.x, target.y, s.status, s.iterations, s.error
            )?;
        }
        Ok(())
    }

    fn pose_text(&self, q: &[f64]) -> String {
        q.iter().map(|&a| deg_text(a, 3)).collect::<Vec<_>>().join(", ")
    }

    fn end_lines(last: &Frame, w: &mut dyn Write) -> std::io::Result<()> {
        match last.joints.last() {
            Some(tip) => writeln!(w, "tip       ({:.6}, {:.6})", tip.x, tip.y),
            None => Ok(()),
        }
    }

    fn point_columns(&self) -> Vec<String> {
        (0..=self.chain.len()).map(|k| format!("x{k},y{k}")).collect()
    }
}

/// The one goal of an arm: `--goal X,Y` given once (with `--goal-angle`).
fn arm_goal(args: &MotionArgs) -> Result<Goal, Error> {
    match &args.goal[..] {
        [GoalArg::Point([x, y])] => crate::goals::make_goal(*x, *y, args.goal_angle),
        [named @ GoalArg::Named { .. }] => {
            Err(Error::input(format!("{}: a goal on a named bone needs --rig FILE", named.text())))
        }
        goals => Err(Error::input(format!(
            "--goal: an arm has one tip, so one --goal X,Y, got {} (points on the way are --via X,Y; several goals need --rig FILE)",
            goals.len()
        ))),
    }
}

impl Animated for Rig {
    const FIRST_POINT: usize = 1;

    /// Each `--via` set (with the pins and the mix), then the `--goal` set (with every per-goal
    /// control).
    fn stops(&self, args: &MotionArgs) -> Result<Vec<RigTask>, Error> {
        let plain =
            RigTaskArgs { pin: args.body.rig_task.pin.clone(), mix: args.body.rig_task.mix, ..RigTaskArgs::default() };
        let mut tasks = Vec::with_capacity(args.via.len() + 1);
        for via in &args.via {
            let ViaArg::Set(goals) = via else {
                return Err(Error::input(format!(
                    "{}: a rig's via is a goal set on named bones: --via NAME=X,Y[,DEG][;NAME=X,Y…]",
                    via.text()
                )));
            };
            let mut targets = goals.iter().map(|g| Target::of(g, self)).collect::<Result<Vec<_>, _>>()?;
            for t in &mut targets {
                t.source = via.text();
            }
            tasks.push(plain.task(&self.skeleton, &targets)?);
        }
        let targets = args.goal.iter().map(|g| Target::of(g, self)).collect::<Result<Vec<_>, _>>()?;
        tasks.push(args.body.rig_task.task(&self.skeleton, &targets)?);
        Ok(tasks)
    }

    fn animation(motion: &Self::Solved) -> &Animation {
        &motion.animation
    }

    fn warn_unreached(motion: &Self::Solved) {
        let count = motion.solves.len();
        for (k, s) in motion.solves.iter().enumerate().filter(|(_, s)| s.status != ikarus::Status::Reached) {
            let which = if k + 1 == count { "the goal set".to_owned() } else { format!("via set #{}", k + 1) };
            eprintln!(
                "ikarus: {which} not reached: {}, largest error {:.3e}; the motion goes on from the best pose found",
                s.status, s.error
            );
        }
    }

    fn json(run: &MotionRun<Self>, w: &mut dyn Write) -> serde_json::Result<()> {
        serde_json::to_writer_pretty(w, &run.motion.json(&run.body))
    }

    fn drawing(run: &MotionRun<Self>) -> Drawing<'_> {
        run.motion.drawing(&run.body, run.fps)
    }

    fn head(&self) -> String {
        format!("rig       {} ({} bones)", self.name, self.skeleton.len())
    }

    fn solve_lines(run: &MotionRun<Self>, w: &mut dyn Write) -> std::io::Result<()> {
        let s = &run.body.skeleton;
        let solves = &run.motion.motion.solves;
        for (k, (solve, task)) in solves.iter().zip(&run.motion.stops).enumerate() {
            let what = if k + 1 == solves.len() { "goals" } else { "via" };
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
        Ok(())
    }

    fn pose_text(&self, q: &[f64]) -> String {
        let names = self.skeleton.names();
        names.iter().zip(q).map(|(n, &a)| format!("{n} {}", deg_text(a, 3))).collect::<Vec<_>>().join(", ")
    }

    fn end_lines(_: &Frame, _: &mut dyn Write) -> std::io::Result<()> {
        Ok(())
    }

    fn point_columns(&self) -> Vec<String> {
        self.skeleton.names().iter().map(|n| format!("{n}.x,{n}.y")).collect()
    }
}
