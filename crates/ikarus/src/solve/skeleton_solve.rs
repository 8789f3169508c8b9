//! [`Solver::solve_rig`]: a skeleton solve — input checks, the task's effectors, the core's
//! loop and restarts on the [`Rig`] model, and the mix.

use super::Method;
use super::model::Problem;
use super::model::{Model, Posture};
use super::restarts::solve_with_restarts;
use super::skeleton_model::Rig;
use super::solver::{finish, measure};
use super::task::{EffectorOutcome, Priority, RigTask};
use super::{Outcome, SolveError, Solver, Status};
use crate::chain::Chain;
use crate::goal::Goal;
use crate::skeleton::{Joint, Skeleton};

impl Solver {
    /// Solves every goal and pin of `task` on `skeleton` together, starting from `start` (one
    /// finite angle per bone, radians, in the skeleton's order; clamped into the limits), with
    /// this solver's options: the same loop, step rule, line search, limit mode and restarts as
    /// a chain's solve, on the stacked task of every effector (see [`RigTask`]).
    ///
    /// The outcome's `status` is `Reached` only if every effector is; `error` and
    /// `angle_error` are the largest over them; `effectors` says how each ended. When the
    /// goals cannot all be met, the pose is the weighted least-squares best the solve found.
    /// CCD, FABRIK and the closed form solve chains only ([`SolveError::ChainOnly`]).
    ///
    /// A skeleton that is a chain ([`Skeleton::as_chain`]) with one goal on its last bone
    /// (no pins, weight 1, primary, no bend or softness, mix 1) is solved as that chain by
    /// [`Solver::solve_into`]: its fast path, closed forms, region verdict and every method,
    /// the outcome the chain's bit for bit with the goal as its one effector.
    pub fn solve_rig(&mut self, skeleton: &Skeleton, start: &[f64], task: &RigTask) -> Result<Outcome, SolveError> {
        let mut out = Outcome::default();
        self.solve_rig_into(skeleton, start, task, &mut out)?;
        Ok(out)
    }

    /// Like [`Solver::solve_rig`], writing into `out` and reusing its buffers: once they have
    /// grown to the skeleton and task, a solve allocates nothing (frames aside, as for chains).
    pub fn solve_rig_into(
        &mut self,
        skeleton: &Skeleton,
        start: &[f64],
        task: &RigTask,
        out: &mut Outcome,
    ) -> Result<(), SolveError> {
        let opts = &self.options;
        check_joints(skeleton, opts.method)?;
        check_rig_input(skeleton, start, opts.rates.len())?;
        task.validate(skeleton)?;
        if let Some(goal) = chain_goal(skeleton, task) {
            return self.solve_as_chain(skeleton, start, &goal, out);
        }
        let opts = &self.options;
        if !opts.method.solves_rigs() {
            return Err(SolveError::ChainOnly { method: opts.method.name() });
        }
        let began = opts.restarts.and_then(|r| r.time_budget).map(|_| web_time::Instant::now());
        let work = &mut self.rig_work;
        work.setup(skeleton, start, task, opts, out)?;
        let rig = Rig {
            skeleton,
            effs: &work.effs,
            limits: &work.limits,
            primary_rows: work.primary_rows,
            tolerance: opts.tolerance,
            // (Fields of `work` borrowed one by one: the first level's solve below writes
            // `work.resume`.)
            posture: (!work.rest_scale.is_empty()).then(|| Posture {
                scale: &work.rest_scale,
                pull: &work.rest_pull,
                rest: skeleton.rest_angles(),
            }),
        };
        let s = &mut self.rig_scratch;
        Model::fit(&rig, s);
        let p = Problem::with_bounds(&rig, &(), opts, rig.bounds());
        solve_with_restarts(&p, &work.start, began, s, out);
        finish(&p, s, out);
        let first_level = work.effs.iter().take_while(|e| e.primary).count();
        let missed =
            |out: &Outcome| work.effs[..first_level].iter().any(|e| out.effectors[e.slot].status != Status::Reached);
        if rig.levels() && out.status != Status::Interrupted && missed(out) {
            // Strict priority: where the secondary goals kept a primary goal or pin from its
            // tolerance (pulling against a singular pose, say), the first level is solved
            // again alone from where the solve ended, and every effector measured on that.
            let (iterations, restarts) = (out.iterations, out.restarts);
            let first = Rig { effs: &work.effs[..first_level], ..rig };
            let t = &mut self.first_level_scratch;
            Model::fit(&first, t);
            let q = Problem::with_bounds(&first, &(), opts, p.bounds);
            // (Its restarts draw their poses into `t.restart`, so the start is kept apart: it
            // once shared that buffer, emptied for the solve, and a restart there panicked.)
            work.resume.clear();
            work.resume.extend_from_slice(out.pose.angles());
            solve_with_restarts(&q, &work.resume, began, t, out);
            finish(&q, t, out);
            out.iterations += iterations;
            out.restarts += restarts;
            measure(&p, s, out);
        }
        if task.mix < 1.0 {
            for (a, &from) in out.pose.angles_mut().iter_mut().zip(start) {
                *a = from + task.mix * (*a - from);
            }
            p.bounds.clamp_into(out.pose.angles_mut());
            measure(&p, s, out);
        }
        Ok(())
    }
}

impl Solver {
    /// The chain path of [`Solver::solve_rig_into`]: the skeleton's chain view (built once
    /// per skeleton and kept), solved for `goal`, its outcome given the goal as its effector.
    fn solve_as_chain(
        &mut self,
        skeleton: &Skeleton,
        start: &[f64],
        goal: &Goal,
        out: &mut Outcome,
    ) -> Result<(), SolveError> {
        // (The rest of a chain's shape, one branch of plain revolute bones, `chain_goal` checked.)
        let same = |c: &Chain| {
            c.base() == skeleton.base()
                && c.lengths() == skeleton.lengths()
                && c.limits() == skeleton.limits()
                && c.start_pose().angles() == skeleton.start_angles()
                && c.skeleton().names() == skeleton.names()
        };
        let chain = match self.rig_chain.take() {
            Some(c) if same(&c) => c,
            _ => Box::new(skeleton.as_chain().expect("ikarus: chain_goal checked the shape")),
        };
        let result = self.solve_into(&chain, start, goal, out);
        self.rig_chain = Some(chain);
        result?;
        let (status, error, angle_error) = (out.status, out.error, out.angle_error);
        let (tip, orientation) = (out.end_effector.position, out.end_effector.orientation);
        out.effectors.clear();
        out.effectors.push(EffectorOutcome {
            bone: skeleton.len() - 1,
            pinned: false,
            status,
            error,
            angle_error,
            tip,
            orientation,
            target: goal.target(),
        });
        Ok(())
    }
}

/// The goal of a task that is a chain's: `skeleton` has a chain view and the task is one
/// goal on its last bone that the chain's solve means the same way (weight 1, primary, no
/// bend or softness), no pins, mix 1.
fn chain_goal(skeleton: &Skeleton, task: &RigTask) -> Option<Goal> {
    let [g] = task.goals.as_slice() else { return None };
    let plain_goal = g.bone + 1 == skeleton.len()
        && g.weight == 1.0
        && g.priority == Priority::Primary
        && g.bend.is_none()
        && g.softness == 0.0;
    (plain_goal && task.pins.is_empty() && task.bends.is_empty() && task.mix == 1.0 && skeleton.is_chain())
        .then_some(g.goal)
}

/// Every joint of `skeleton` is one `method` moves.
fn check_joints(skeleton: &Skeleton, method: Method) -> Result<(), SolveError> {
    for (index, &joint) in skeleton.joints().iter().enumerate() {
        if !method.moves(joint) {
            let kind = match joint {
                Joint::Revolute => "revolute",
                Joint::Prismatic { .. } => "prismatic",
            };
            let (method, name) = (method.name(), skeleton.name(index).to_owned());
            return Err(SolveError::JointKind { method, kind, name, index });
        }
    }
    Ok(())
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
