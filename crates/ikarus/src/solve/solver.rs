//! [`Solver`]: validated options plus the scratch buffers reused across iterations and
//! solves; checks a solve's input, takes the closed form where it applies, and hands the rest
//! to the restart driver.

use super::problem::Problem;
use super::restarts::solve_with_restarts;
use super::scratch::Scratch;
use super::{Method, OptionsError, Outcome, SolveError, SolveOptions, Status};
use crate::angle::wrap_angle;
use crate::chain::{Chain, Pose};
use crate::closed_form::{self, ClosedForm};
use crate::goal::Goal;
use crate::kinematics::{EndEffector, joint_positions_into};

/// A solver: validated options plus scratch buffers. Reuse one value for many solves; once
/// its buffers have grown to the chain's size, a solve without frame recording allocates
/// only its [`Outcome`] (and nothing with [`Solver::solve_into`]).
#[derive(Debug, Clone)]
pub struct Solver {
    options: SolveOptions,
    scratch: Scratch,
}

impl Solver {
    /// Validates `options` and builds a solver.
    pub fn new(options: SolveOptions) -> Result<Self, OptionsError> {
        options.validate()?;
        Ok(Self { options, scratch: Scratch::default() })
    }

    /// The options this solver runs with.
    #[must_use]
    pub fn options(&self) -> &SolveOptions {
        &self.options
    }

    /// Solves for `goal` starting from `start`.
    pub fn solve(&mut self, chain: &Chain, start: &Pose, goal: &Goal) -> Result<Outcome, SolveError> {
        let mut out = Outcome::default();
        self.solve_into(chain, start.angles(), goal, &mut out)?;
        Ok(out)
    }

    /// Like [`Solver::solve`], but writes into `out`, reusing its buffers: after the first
    /// call with a chain of this size, no further memory is allocated (frame recording
    /// reuses the frame buffers, which grow only if a solve records more frames than any
    /// before it).
    pub fn solve_into(
        &mut self,
        chain: &Chain,
        start: &[f64],
        goal: &Goal,
        out: &mut Outcome,
    ) -> Result<(), SolveError> {
        let opts = &self.options;
        check_input(chain, start, opts)?;
        let began = opts.restarts.and_then(|r| r.time_budget).map(|_| std::time::Instant::now());
        let s = &mut self.scratch;
        s.fit(chain.len());
        let p = Problem::new(chain, goal, opts);
        if opts.closed_form || opts.method == Method::Analytic {
            match closed_form::solve(chain, goal, start, p.bounds, &mut s.trial) {
                ClosedForm::Solved => {
                    if reached_in_closed_form(&p, start, s, out) {
                        return Ok(());
                    }
                }
                ClosedForm::NotApplicable if opts.method == Method::Analytic => {
                    let goal = if goal.orientation().is_some() { "an orientation goal" } else { "a position goal" };
                    return Err(SolveError::NoClosedForm { links: chain.len(), goal });
                }
                ClosedForm::NotApplicable | ClosedForm::OutOfReach | ClosedForm::OutsideLimits => {}
            }
        }
        solve_with_restarts(&p, start, began, s, out);
        Ok(())
    }
}

/// The start pose must hold one finite angle per joint, and the rates one per joint or none
/// ([`SolveOptions::validate_for`]).
fn check_input(chain: &Chain, start: &[f64], opts: &SolveOptions) -> Result<(), SolveError> {
    let n = chain.len();
    if start.len() != n {
        return Err(SolveError::PoseLength { expected: n, got: start.len() });
    }
    if let Some((index, &value)) = start.iter().enumerate().find(|(_, a)| !a.is_finite()) {
        return Err(SolveError::NonFiniteAngle { index, value });
    }
    opts.validate_for(chain)
}

/// The closed form's answer is in `s.trial`: if it is within the tolerances, writes it into
/// `out` as a one-step solve (frames: the start pose, clamped into the bounds, and the answer)
/// and returns `true`.
fn reached_in_closed_form(p: &Problem, start: &[f64], s: &mut Scratch, out: &mut Outcome) -> bool {
    let (chain, goal, opts) = (p.chain, p.goal, p.opts);
    let n = chain.len();
    let phi = joint_positions_into(chain, &s.trial, &mut s.trial_joints);
    let tip = s.trial_joints[n];
    let error = (goal.target() - tip).norm();
    let angle_error = goal.orientation().map_or(0.0, |g| wrap_angle(g - phi).abs());
    if !(error <= opts.tolerance && angle_error <= opts.angle_tolerance) {
        return false;
    }
    // One step, from the start pose straight to the solution.
    out.frames.start(n, opts.record_every, 1);
    if opts.record_every.is_some() {
        let start_joints = &mut s.joints;
        s.restart.copy_from_slice(start);
        p.bounds.clamp_into(&mut s.restart);
        joint_positions_into(chain, &s.restart, start_joints);
        out.frames.push(0, &s.restart, start_joints);
        out.frames.push(1, &s.trial, &s.trial_joints);
    }
    let angles = out.pose.angles_mut();
    angles.clear();
    angles.extend_from_slice(&s.trial);
    out.status = Status::Reached;
    out.iterations = 1;
    out.restarts = 0;
    out.error = error;
    out.angle_error = angle_error;
    out.end_effector = EndEffector { position: tip, orientation: phi };
    true
}
