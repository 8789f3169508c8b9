//! [`Solver::solve_rig`]: a skeleton solve — input checks, the task's effectors and targets,
//! and the per-effector outcome.

use nalgebra::Point2;

use super::attempt::distance;
use super::rig::{EffectorOutcome, RigTask};
use super::{Outcome, SolveError, Solver, Status};
use crate::angle::wrap_angle;
use crate::kinematics::EndEffector;
use crate::skeleton::Skeleton;

impl Solver {
    /// Solves every goal and pin of `task` on `skeleton` together, starting from `start` (one
    /// angle per bone, radians, in the skeleton's order). See [`RigTask`].
    pub fn solve_rig(&mut self, skeleton: &Skeleton, start: &[f64], task: &RigTask) -> Result<Outcome, SolveError> {
        let mut out = Outcome::default();
        self.solve_rig_into(skeleton, start, task, &mut out)?;
        Ok(out)
    }

    /// Like [`Solver::solve_rig`], writing into `out` and reusing its buffers.
    pub fn solve_rig_into(
        &mut self,
        skeleton: &Skeleton,
        start: &[f64],
        task: &RigTask,
        out: &mut Outcome,
    ) -> Result<(), SolveError> {
        let opts = self.options();
        if !opts.method.solves_rigs() {
            return Err(SolveError::ChainOnly { method: opts.method.name() });
        }
        check_rig_input(skeleton, start, opts.rates.len())?;
        task.validate(skeleton)?;
        // Placeholder until the core solves skeletons: the start pose, measured.
        let angles = out.pose.angles_mut();
        angles.clear();
        angles.extend_from_slice(start);
        let mut points = vec![Point2::origin(); skeleton.len() + 1];
        let mut directions = vec![0.0; skeleton.len()];
        skeleton.points_into(start, &mut points, &mut directions);
        out.effectors.clear();
        for g in &task.goals {
            let tip = points[g.bone + 1];
            let phi = directions[g.bone];
            let target = g.goal.target();
            let error = distance(target.x - tip.x, target.y - tip.y);
            let angle_error = g.goal.orientation().map_or(0.0, |o| wrap_angle(o - phi).abs());
            out.effectors.push(EffectorOutcome {
                bone: g.bone,
                pinned: false,
                status: Status::IterationLimit,
                error,
                angle_error,
                tip,
                orientation: phi,
                target,
            });
        }
        for p in &task.pins {
            let tip = points[p.bone + 1];
            let phi = directions[p.bone];
            out.effectors.push(EffectorOutcome {
                bone: p.bone,
                pinned: true,
                status: Status::Reached,
                error: 0.0,
                angle_error: 0.0,
                tip,
                orientation: phi,
                target: tip,
            });
        }
        out.status = Status::IterationLimit;
        out.iterations = 0;
        out.restarts = 0;
        out.error = out.effectors.iter().fold(0.0, |m, e| m.max(e.error));
        out.angle_error = out.effectors.iter().fold(0.0, |m, e| m.max(e.angle_error));
        let first = out.effectors[0];
        out.end_effector = EndEffector { position: first.tip, orientation: first.orientation };
        out.frames = super::Frames::default();
        Ok(())
    }
}

/// One finite angle per bone, and rates one per bone or none.
fn check_rig_input(skeleton: &Skeleton, start: &[f64], rates: usize) -> Result<(), SolveError> {
    let n = skeleton.len();
    if start.len() != n {
        return Err(SolveError::PoseLength { expected: n, got: start.len() });
    }
    if let Some((index, &value)) = start.iter().enumerate().find(|(_, a)| !a.is_finite()) {
        return Err(SolveError::NonFiniteAngle { index, value });
    }
    if rates != 0 && rates != n {
        return Err(SolveError::RatesLength { expected: n, got: rates });
    }
    Ok(())
}
