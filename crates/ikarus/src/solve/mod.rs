//! Inverse-kinematics solvers: one shared loop, one step rule per method, limit modes and
//! restarts.
//!
//! Every iteration computes the joint positions, the task error `e` (position, and the
//! weighted orientation error when the goal has one), the Jacobian `J`, and `A = J Jᵀ`.
//! A Jacobian [`Method`] then picks a task-space vector `y` and the joint update is `Δθ = Jᵀ y`:
//!
//! | method | `y` |
//! | --- | --- |
//! | [`Method::Transpose`] | `α e`, with `α = ⟨e, A e⟩ / ⟨A e, A e⟩` (Buss 2004) |
//! | [`Method::PseudoInverse`] | `A⁺ e`, singular directions below [`SolveOptions::singular_threshold`] dropped |
//! | [`Method::DampedLeastSquares`] | `(A + λ² I)⁻¹ e` |
//! | [`Method::LevenbergMarquardt`] | `(A + μ I)⁻¹ e`, μ adapted after every step (Nielsen 1999) |
//!
//! [`Method::SelectivelyDamped`] (Buss & Kim 2005) clamps the step of each singular direction
//! separately. [`Method::CyclicCoordinateDescent`] and [`Method::Fabrik`] move one joint, or
//! one pass of joint positions, at a time, without `J`; [`Method::Analytic`] is the closed form
//! of [`crate::closed_form`], which every method also takes first where it applies
//! ([`SolveOptions::closed_form`]).
//!
//! `Δθ` is scaled by [`SolveOptions::gain`] and the per-joint [`SolveOptions::rates`], capped
//! by [`SolveOptions::max_step`], added to the angles, and clamped into the joint limits. How a
//! step treats the limits before that clamp is the [`LimitMode`]: [`LimitMode::Lock`] re-solves
//! the step without the joints that would cross a limit, [`LimitMode::NullSpace`] adds a push
//! toward mid-range in the null space of `J`, and [`LimitMode::Weighted`] weights each joint's
//! column by how near its limit it is moving (the weighted pseudoinverse
//! `W Jᵀ (J W Jᵀ)⁻¹` with `W` diagonal, computed as the method's rule on `J W^½`).
//!
//! A step is accepted only if it lowers the task error `‖e‖²` by at least a tenth of what
//! the linearisation `J Δθ` predicts (an Armijo test). Pinv, DLS and SDLS try their own full
//! step once; LM raises its damping and tries again; if that fails, the steepest-descent
//! (transpose) step is tried instead, halved up to [`SolveOptions::backtrack`] times, since
//! Gauss–Newton directions are poor where `J` is nearly singular. The transpose method halves
//! its own step. If nothing passes, the pose cannot improve and the solve ends
//! [`Status::Stalled`]. The textbook iteration (`backtrack: 0`) takes every step as computed;
//! from a nearly straight arm it turns joints by whole revolutions, and it oscillates around
//! goals out of reach. The trial pose's forward kinematics is the next iteration's, so an
//! accepted first try costs nothing extra.
//!
//! The loop stops when the goal is reached, when the pose has stopped moving (stall
//! detection), or at the iteration cap; with [`SolveOptions::restarts`] a solve that did not
//! reach the goal starts again from other poses. Not reaching a goal is not an error: the
//! [`Outcome`] says why in its [`Status`] and carries the best pose found.

mod ccd;
mod dls;
mod fabrik;
mod frames;
mod method;
mod pinv;
mod sdls;
mod transpose;

use nalgebra::{Matrix3, Matrix3xX, Point2, Vector3};
use thiserror::Error;

use crate::chain::{Chain, Pose, annulus_inner};
use crate::closed_form::{self, ClosedForm};
use crate::kinematics::{EndEffector, jacobian_from_joints, joint_positions_into};
use crate::rng::SplitMix64;

pub use frames::{Frame, Frames};
pub use method::{LimitMode, Method};

/// What the end effector should reach: a position, and optionally an absolute orientation
/// of the last link.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Goal {
    position: Point2<f64>,
    orientation: Option<f64>,
}

/// Why a [`Goal`] is invalid.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum GoalError {
    /// A coordinate or the angle is NaN or infinite.
    #[error("goal.{field}: must be a finite number, got {value}")]
    NonFinite {
        /// `"x"`, `"y"` or `"angle"`.
        field: &'static str,
        /// The offending value.
        value: f64,
    },
}

impl Goal {
    /// A position goal `(x, y)`.
    pub fn position(x: f64, y: f64) -> Result<Self, GoalError> {
        finite("x", x)?;
        finite("y", y)?;
        Ok(Self { position: Point2::new(x, y), orientation: None })
    }

    /// A position goal with an absolute orientation `angle` (radians from +x) for the last link.
    pub fn with_orientation(x: f64, y: f64, angle: f64) -> Result<Self, GoalError> {
        let mut g = Self::position(x, y)?;
        finite("angle", angle)?;
        g.orientation = Some(angle);
        Ok(g)
    }

    /// The target position.
    #[must_use]
    pub fn target(&self) -> Point2<f64> {
        self.position
    }

    /// The target orientation, if any, radians.
    #[must_use]
    pub fn orientation(&self) -> Option<f64> {
        self.orientation
    }

    /// Whether no pose of `chain` can reach this goal even with its limits ignored, by more
    /// than `tolerance`.
    ///
    /// Free joints reach exactly the annulus `min_reach ≤ |p − base| ≤ max_reach`. With an
    /// orientation φ the last link is fixed, so the wrist `p − l_N (cos φ, sin φ)` must lie in
    /// the annulus of the other links (or on the base, for a single link).
    #[must_use]
    pub fn is_out_of_reach(&self, chain: &Chain, tolerance: f64) -> bool {
        let base = chain.base();
        match self.orientation {
            None => {
                let d = (self.position - base).norm();
                d > chain.max_reach() + tolerance || d < chain.min_reach() - tolerance
            }
            Some(phi) => {
                let lengths = chain.lengths();
                let (last, rest) = lengths.split_last().expect("a chain has at least one link");
                let wrist = self.position - *last * nalgebra::Vector2::new(phi.cos(), phi.sin());
                let d = (wrist - base).norm();
                let outer: f64 = rest.iter().sum();
                let inner = if rest.is_empty() { 0.0 } else { annulus_inner(rest) };
                d > outer + tolerance || d < inner - tolerance
            }
        }
    }
}

fn finite(field: &'static str, value: f64) -> Result<(), GoalError> {
    if value.is_finite() { Ok(()) } else { Err(GoalError::NonFinite { field, value }) }
}

/// Restarts from other start poses when a solve stalls or runs out of iterations (each attempt
/// has the full iteration cap).
///
/// Attempt `k` (1-based) starts from `start + (k / attempts)·(r − start)`, clamped into the
/// limits, where `r` is a pose drawn uniformly inside the limits (free joints: [−π, π)) by a
/// generator seeded with `seed`: early attempts start near the original start pose, so the
/// first goal reached tends to be near it too and an animation does not jump. The first attempt
/// that reaches the goal wins; if none does, the outcome is the attempt with the smallest error.
/// The same `seed` gives the same attempts, bit for bit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Restarts {
    /// Most restarts after the first solve, ≥ 1.
    pub attempts: u32,
    /// Seed of the start poses.
    pub seed: u64,
    /// No new attempt starts once this much time has passed since the solve began. A solve
    /// stopped by its budget depends on the machine's speed, so it is the one case that is not
    /// deterministic; `None` (the default) keeps every solve deterministic.
    pub time_budget: Option<std::time::Duration>,
}

impl Default for Restarts {
    fn default() -> Self {
        Self { attempts: 16, seed: 0, time_budget: None }
    }
}

/// Stop when no joint has moved by more than `epsilon` radians for `window` consecutive
/// iterations (the seed program's "penalty").
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StallDetection {
    /// Largest per-joint change, radians, that still counts as "not moving".
    pub epsilon: f64,
    /// How many consecutive still iterations end the solve.
    pub window: u32,
}

impl Default for StallDetection {
    fn default() -> Self {
        Self { epsilon: 1e-9, window: 10 }
    }
}

/// Options of a solve. Start from [`SolveOptions::default`] and change what you need.
#[derive(Debug, Clone, PartialEq)]
pub struct SolveOptions {
    /// The step rule.
    pub method: Method,
    /// Damping λ of [`Method::DampedLeastSquares`], and the starting damping of
    /// [`Method::LevenbergMarquardt`], ≥ 0, in length units.
    pub lambda: f64,
    /// The goal counts as reached when the tip is within this distance, > 0.
    pub tolerance: f64,
    /// With an orientation goal, the orientation must also be within this many radians, > 0.
    pub angle_tolerance: f64,
    /// Length units per radian of orientation error when position and orientation are
    /// solved together, > 0.
    pub orientation_weight: f64,
    /// Iteration cap.
    pub max_iterations: u32,
    /// Multiplies every step, > 0.
    pub gain: f64,
    /// Per-joint step multipliers (the seed's a, b, c), each ≥ 0; empty means all 1.
    pub rates: Vec<f64>,
    /// Largest angle change of any joint in one iteration, radians; the whole step is scaled
    /// down to respect it, keeping its direction. The default, 0.5 rad (≈ 29°), stops pinv and
    /// DLS from turning joints by whole revolutions when they start near a singular pose (on
    /// 300 random 3-link round trips without it, 32 pinv solves travelled more than a turn; with
    /// it none did, for about one iteration more on average). `None` removes the cap.
    pub max_step: Option<f64>,
    /// How many times the line search may halve a step that fails the sufficient-decrease
    /// test (see the [module docs](self)); when none passes, the solve ends
    /// [`Status::Stalled`]. `0` takes every step as computed: the textbook iteration, which can
    /// jump by whole turns near singular poses and oscillate around goals out of reach.
    pub backtrack: u32,
    /// Singular values of `J` below this are treated as zero by [`Method::PseudoInverse`].
    pub singular_threshold: f64,
    /// Stall detection; `None` runs to the goal or the iteration cap.
    pub stall: Option<StallDetection>,
    /// Record a frame every this many iterations (plus always the first and the last);
    /// `None` records nothing.
    pub record_every: Option<u32>,
    /// How joint limits are enforced.
    pub limits: LimitMode,
    /// Restarts when a solve stalls; `None` solves once.
    pub restarts: Option<Restarts>,
    /// Use the closed form where it applies (two links with a position goal, three links with
    /// an orientation goal) instead of iterating: exact, and about a hundred times faster. The
    /// iteration still runs when the closed form has no answer within the limits or the goal is
    /// out of reach, to find the best pose.
    pub closed_form: bool,
}

impl Default for SolveOptions {
    fn default() -> Self {
        Self {
            method: Method::LevenbergMarquardt,
            lambda: 0.1,
            tolerance: 1e-6,
            angle_tolerance: 1e-6,
            orientation_weight: 1.0,
            max_iterations: 1000,
            gain: 1.0,
            rates: Vec::new(),
            max_step: Some(0.5),
            backtrack: 10,
            singular_threshold: 1e-6,
            stall: Some(StallDetection::default()),
            record_every: None,
            limits: LimitMode::Lock,
            restarts: Some(Restarts::default()),
            closed_form: true,
        }
    }
}

/// Why [`SolveOptions`] are invalid. Every variant names the field and the value.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum OptionsError {
    /// A number is out of its range (the message says which range).
    #[error("{field}: must be {expected}, got {value}")]
    OutOfRange {
        /// The option's name.
        field: &'static str,
        /// The allowed range, in words.
        expected: &'static str,
        /// The offending value.
        value: f64,
    },
    /// A per-joint rate is out of range.
    #[error("rates[{index}]: must be a finite number ≥ 0, got {value}")]
    Rate {
        /// Joint index, from 0.
        index: usize,
        /// The offending value.
        value: f64,
    },
}

impl SolveOptions {
    /// Checks every field; the error names the first bad one.
    pub fn validate(&self) -> Result<(), OptionsError> {
        let positive = |field, value: f64| {
            if value.is_finite() && value > 0.0 {
                Ok(())
            } else {
                Err(OptionsError::OutOfRange { field, expected: "a finite number > 0", value })
            }
        };
        let non_negative = |field, value: f64| {
            if value.is_finite() && value >= 0.0 {
                Ok(())
            } else {
                Err(OptionsError::OutOfRange { field, expected: "a finite number ≥ 0", value })
            }
        };
        non_negative("lambda", self.lambda)?;
        positive("tolerance", self.tolerance)?;
        positive("angle_tolerance", self.angle_tolerance)?;
        positive("orientation_weight", self.orientation_weight)?;
        positive("gain", self.gain)?;
        non_negative("singular_threshold", self.singular_threshold)?;
        if let Some(m) = self.max_step {
            positive("max_step", m)?;
        }
        if let Some(s) = self.stall {
            non_negative("stall.epsilon", s.epsilon)?;
            if s.window == 0 {
                return Err(OptionsError::OutOfRange { field: "stall.window", expected: "at least 1", value: 0.0 });
            }
        }
        if let Some(r) = self.restarts {
            if r.attempts == 0 {
                return Err(OptionsError::OutOfRange {
                    field: "restarts.attempts",
                    expected: "at least 1",
                    value: 0.0,
                });
            }
        }
        if self.record_every == Some(0) {
            return Err(OptionsError::OutOfRange { field: "record_every", expected: "at least 1", value: 0.0 });
        }
        for (index, &value) in self.rates.iter().enumerate() {
            if !(value.is_finite() && value >= 0.0) {
                return Err(OptionsError::Rate { index, value });
            }
        }
        Ok(())
    }
}

/// Why a solve ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Status {
    /// The tip is within tolerance of the goal (and of its orientation, if any).
    Reached,
    /// No pose can reach the goal, even with limits ignored; the pose is the best found
    /// (for a position goal: the arm stretched towards it).
    Unreachable,
    /// The pose stopped moving before reaching the goal: a local minimum, or joints held at
    /// their limits.
    Stalled,
    /// The iteration cap was hit while the pose was still moving.
    IterationLimit,
}

impl Status {
    /// `reached`, `unreachable`, `stalled` or `iteration_limit`.
    #[must_use]
    pub fn as_str(self) -> &'static str {
        match self {
            Status::Reached => "reached",
            Status::Unreachable => "unreachable",
            Status::Stalled => "stalled",
            Status::IterationLimit => "iteration_limit",
        }
    }
}

impl std::fmt::Display for Status {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// The result of a solve.
#[derive(Debug, Clone, PartialEq)]
pub struct Outcome {
    /// The final pose. With backtracking on (the default) every accepted step lowers the
    /// error, so it is also the best pose of the solve; with `backtrack: 0` it is simply where
    /// the last step landed.
    pub pose: Pose,
    /// Why the solve ended.
    pub status: Status,
    /// Steps taken, over every attempt.
    pub iterations: u32,
    /// Restarts used (see [`SolveOptions::restarts`]); 0 when the first attempt ended it.
    pub restarts: u32,
    /// Final distance from the tip to the goal position.
    pub error: f64,
    /// Final absolute orientation error in radians, wrapped to [0, π]; 0 without an
    /// orientation goal.
    pub angle_error: f64,
    /// Final tip position and orientation.
    pub end_effector: EndEffector,
    /// Recorded frames (empty unless [`SolveOptions::record_every`] is set).
    pub frames: Frames,
}

impl Default for Outcome {
    fn default() -> Self {
        Self {
            pose: Pose::default(),
            status: Status::IterationLimit,
            iterations: 0,
            restarts: 0,
            error: f64::INFINITY,
            angle_error: 0.0,
            end_effector: EndEffector { position: Point2::origin(), orientation: 0.0 },
            frames: Frames::default(),
        }
    }
}

/// Why a solve could not start.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum SolveError {
    /// The start pose has a different number of angles than the chain has joints.
    #[error("start: expected {expected} angles (one per joint), got {got}")]
    PoseLength {
        /// Joints in the chain.
        expected: usize,
        /// Angles given.
        got: usize,
    },
    /// A start angle is NaN or infinite.
    #[error("start[{index}]: must be a finite number, got {value}")]
    NonFiniteAngle {
        /// Joint index, from 0.
        index: usize,
        /// The offending value.
        value: f64,
    },
    /// [`Method::Analytic`] was asked for a chain and goal without a closed form.
    #[error(
        "method analytic: needs 2 links with a position goal or 3 links with an orientation goal, \
         got {links} links with {goal}"
    )]
    NoClosedForm {
        /// Links in the chain.
        links: usize,
        /// `"a position goal"` or `"an orientation goal"`.
        goal: &'static str,
    },
    /// [`SolveOptions::rates`] is neither empty nor one per joint.
    #[error("rates: expected {expected} values (one per joint) or none, got {got}")]
    RatesLength {
        /// Joints in the chain.
        expected: usize,
        /// Rates given.
        got: usize,
    },
}

/// The share of the linearly predicted error decrease a backtracking step must achieve.
const SUFFICIENT_DECREASE: f64 = 0.1;

/// Per iteration, [`LimitMode::NullSpace`] asks each limited joint to cover this share of its
/// distance to the middle of its range (before the projection into the null space).
const NULLSPACE_GAIN: f64 = 0.3;

/// The null-space push fades linearly once the task error is below this share of the reach.
const NULLSPACE_FADE: f64 = 0.1;

/// Scratch space reused across iterations and solves.
#[derive(Debug, Clone, Default)]
struct Scratch {
    joints: Vec<Point2<f64>>,
    trial_joints: Vec<Point2<f64>>,
    /// `J`, its orientation row scaled by the orientation weight (zero without an orientation
    /// goal).
    jacobian: Matrix3xX<f64>,
    /// `J` with column `i` scaled by `scale[i]` (zero for a locked joint).
    weighted: Matrix3xX<f64>,
    /// Square roots of the joint weights of [`LimitMode::Weighted`]; 1 otherwise.
    scale: Vec<f64>,
    /// Joints locked at a limit this iteration ([`LimitMode::Lock`], [`LimitMode::NullSpace`]).
    locked: Vec<bool>,
    /// The method's step in weighted coordinates.
    step: Vec<f64>,
    delta: Vec<f64>,
    trial: Vec<f64>,
    /// The best pose of a non-descent method (CCD, FABRIK).
    best: Vec<f64>,
    /// The start pose of a restart.
    restart: Vec<f64>,
}

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
        let n = chain.len();
        if start.len() != n {
            return Err(SolveError::PoseLength { expected: n, got: start.len() });
        }
        if let Some((index, &value)) = start.iter().enumerate().find(|(_, a)| !a.is_finite()) {
            return Err(SolveError::NonFiniteAngle { index, value });
        }
        let opts = &self.options;
        if !opts.rates.is_empty() && opts.rates.len() != n {
            return Err(SolveError::RatesLength { expected: n, got: opts.rates.len() });
        }
        let began = opts.restarts.and_then(|r| r.time_budget).map(|_| std::time::Instant::now());

        let s = &mut self.scratch;
        s.joints.resize(n + 1, Point2::origin());
        s.trial_joints.resize(n + 1, Point2::origin());
        for v in [&mut s.scale, &mut s.step, &mut s.delta, &mut s.trial, &mut s.best, &mut s.restart] {
            v.resize(n, 0.0);
        }
        s.locked.resize(n, false);
        if s.jacobian.ncols() != n {
            s.jacobian = Matrix3xX::zeros(n);
            s.weighted = Matrix3xX::zeros(n);
        }
        let clamp = opts.limits != LimitMode::Ignore && chain.has_limits();

        if opts.closed_form || opts.method == Method::Analytic {
            match closed_form::solve(chain, goal, start, clamp, &mut s.trial) {
                ClosedForm::Solved => {
                    let phi = joint_positions_into(chain, &s.trial, &mut s.trial_joints);
                    let tip = s.trial_joints[n];
                    let error = (goal.target() - tip).norm();
                    let angle_error = goal.orientation().map_or(0.0, |g| wrap_angle(g - phi).abs());
                    if error <= opts.tolerance && angle_error <= opts.angle_tolerance {
                        // One step, from the start pose straight to the solution.
                        out.frames.start(n, opts.record_every, 1);
                        if opts.record_every.is_some() {
                            let start_joints = &mut s.joints;
                            s.restart.copy_from_slice(start);
                            if clamp {
                                chain.clamp_into(&mut s.restart);
                            }
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
                        return Ok(());
                    }
                }
                ClosedForm::NotApplicable if opts.method == Method::Analytic => {
                    let goal = if goal.orientation().is_some() { "an orientation goal" } else { "a position goal" };
                    return Err(SolveError::NoClosedForm { links: n, goal });
                }
                _ => {}
            }
        }

        let mut status = attempt(chain, start, goal, opts, clamp, s, out);
        let mut iterations = out.iterations;
        let mut restarts = 0;
        // A solve that stalled or ran out of iterations restarts (one crawling at the cap, as
        // weighted least norm does against a limit, is as stuck as one standing still); restarts
        // go on until one reaches the goal. Goals out of reach even without limits do not.
        let stuck = |st| st != Status::Reached;
        if let Some(r) = opts.restarts {
            if stuck(status) && !goal.is_out_of_reach(chain, opts.tolerance) {
                let mut best = (task_error(opts, out), 0);
                let mut last = 0;
                for k in 1..=r.attempts {
                    if let (Some(began), Some(budget)) = (began, r.time_budget) {
                        if began.elapsed() >= budget {
                            break;
                        }
                    }
                    restart_pose(chain, start, clamp, r, k, &mut s.restart);
                    let from = std::mem::take(&mut s.restart);
                    status = attempt(chain, &from, goal, opts, clamp, s, out);
                    s.restart = from;
                    iterations += out.iterations;
                    restarts = k;
                    last = k;
                    if !stuck(status) {
                        break;
                    }
                    let err = task_error(opts, out);
                    if err < best.0 {
                        best = (err, k);
                    }
                }
                if stuck(status) && best.1 != last {
                    // No attempt reached the goal: run the best one again (solves are
                    // deterministic, so this reproduces it) to leave its pose in `out`.
                    if best.1 == 0 {
                        s.restart.copy_from_slice(start);
                    } else {
                        restart_pose(chain, start, clamp, r, best.1, &mut s.restart);
                    }
                    let from = std::mem::take(&mut s.restart);
                    status = attempt(chain, &from, goal, opts, clamp, s, out);
                    s.restart = from;
                }
                if restarts > 0 && opts.record_every.is_some() {
                    // The frames of a restart begin elsewhere: keep the motion from the
                    // caller's start pose to the result, without the jump, numbered by the
                    // iterations of every attempt.
                    let n_frames = out.frames.len();
                    let last = out.frames.get(n_frames - 1).expect("the last frame is always recorded");
                    let (end_angles, end_joints) = (last.angles.to_vec(), last.joints.to_vec());
                    out.frames.start(n, opts.record_every, 1);
                    let mut start_angles = start.to_vec();
                    if clamp {
                        chain.clamp_into(&mut start_angles);
                    }
                    joint_positions_into(chain, &start_angles, &mut s.joints);
                    out.frames.push(0, &start_angles, &s.joints);
                    out.frames.push_final(iterations, &end_angles, &end_joints);
                }
            }
        }
        out.iterations = iterations;
        out.restarts = restarts;
        out.status = if status != Status::Reached && goal.is_out_of_reach(chain, opts.tolerance) {
            Status::Unreachable
        } else {
            status
        };
        Ok(())
    }
}

/// The squared task error of an outcome, as the solvers minimise it.
fn task_error(opts: &SolveOptions, out: &Outcome) -> f64 {
    out.error * out.error + (opts.orientation_weight * out.angle_error).powi(2)
}

/// The start pose of restart `k` (see [`Restarts`]).
fn restart_pose(chain: &Chain, start: &[f64], clamp: bool, r: Restarts, k: u32, out: &mut [f64]) {
    use std::f64::consts::PI;
    let mut rng = SplitMix64(r.seed ^ u64::from(k).wrapping_mul(0xA076_1D64_78BD_642F));
    let f = f64::from(k) / f64::from(r.attempts);
    for (i, (o, &a)) in out.iter_mut().zip(start).enumerate() {
        let u = rng.unit();
        let limits = if clamp { chain.limits()[i] } else { None };
        let (lo, hi) = limits.map_or((a - PI, a + PI), |l| (l.min(), l.max()));
        let target = lo + u * (hi - lo);
        let next = a + f * (target - a);
        *o = limits.map_or(next, |l| l.clamp(next));
    }
}

/// One solve from `start` (the loop of the [module docs](self)); writes everything in `out`
/// except the final status relabelling and the restart count, and returns how it ended.
fn attempt(
    chain: &Chain,
    start: &[f64],
    goal: &Goal,
    opts: &SolveOptions,
    clamp: bool,
    s: &mut Scratch,
    out: &mut Outcome,
) -> Status {
    let n = chain.len();
    let angles = out.pose.angles_mut();
    angles.clear();
    angles.extend_from_slice(start);
    if clamp {
        chain.clamp_into(angles);
    }
    out.frames.start(n, opts.record_every, opts.max_iterations);

    let method = if opts.method == Method::Analytic { Method::DampedLeastSquares } else { opts.method };
    let mode = if clamp { opts.limits } else { LimitMode::Ignore };
    let target = goal.target();
    let weight = opts.orientation_weight;
    let mut phi = joint_positions_into(chain, angles, &mut s.joints);
    let mut iteration: u32 = 0;
    let mut still: u32 = 0;
    // Levenberg–Marquardt's damping μ (= λ²) and its growth factor ν (Nielsen 1999).
    let mut mu = opts.lambda * opts.lambda;
    let mut nu = 2.0;
    let mut best_error = f64::INFINITY;
    let status;
    loop {
        let tip = s.joints[n];
        let (dx, dy) = (target.x - tip.x, target.y - tip.y);
        let turn = goal.orientation().map(|g| wrap_angle(g - phi));
        let error = (dx * dx + dy * dy).sqrt();
        let angle_error = turn.map_or(0.0, f64::abs);
        out.error = error;
        out.angle_error = angle_error;
        out.end_effector = EndEffector { position: tip, orientation: phi };
        if let Some(k) = opts.record_every {
            if iteration % k == 0 {
                out.frames.push(iteration, angles, &s.joints);
            }
        }

        if error <= opts.tolerance && angle_error <= opts.angle_tolerance {
            status = Status::Reached;
            break;
        }
        if opts.stall.is_some_and(|st| still >= st.window) {
            status = Status::Stalled;
            break;
        }
        if iteration >= opts.max_iterations {
            status = Status::IterationLimit;
            break;
        }

        let trial_phi = if method.uses_jacobian() {
            // Task error and J, embedded in three dimensions: without an orientation goal the
            // third row of J and e is zero.
            jacobian_from_joints(&s.joints, &mut s.jacobian);
            let e = Vector3::new(dx, dy, turn.map_or(0.0, |t| weight * t));
            let row_scale = if turn.is_some() { weight } else { 0.0 };
            for mut col in s.jacobian.column_iter_mut() {
                col[2] *= row_scale;
            }
            let current = e.norm_squared();
            let Some(trial_phi) =
                jacobian_step(chain, goal, opts, method, mode, clamp, &e, current, &mut mu, &mut nu, angles, s)
            else {
                // No step along this direction lowers the error: the pose cannot move, and the
                // same pose would give the same direction again.
                status = Status::Stalled;
                break;
            };
            trial_phi
        } else {
            let e2 = error * error + (weight * angle_error).powi(2);
            if e2 < best_error {
                best_error = e2;
                s.best.copy_from_slice(angles);
            }
            match method {
                Method::Fabrik => {
                    fabrik::iterate(chain, goal, opts, clamp, angles, &s.joints, &mut s.trial, &mut s.trial_joints)
                }
                _ => ccd::sweep(chain, goal, opts, clamp, angles, &s.joints, &mut s.trial, &mut s.trial_joints),
            }
        };
        let moved = angles.iter().zip(&s.trial).fold(0.0f64, |m, (a, t)| m.max((t - a).abs()));
        std::mem::swap(angles, &mut s.trial);
        std::mem::swap(&mut s.joints, &mut s.trial_joints);
        phi = trial_phi;
        iteration += 1;
        match opts.stall {
            Some(st) if moved <= st.epsilon => still += 1,
            _ => still = 0,
        }
    }

    if !method.uses_jacobian() && status != Status::Reached {
        // CCD and FABRIK do not check for descent; end on the best pose they visited.
        let final_error = out.error.powi(2) + (weight * out.angle_error).powi(2);
        if best_error < final_error {
            angles.copy_from_slice(&s.best);
            phi = joint_positions_into(chain, angles, &mut s.joints);
            let tip = s.joints[n];
            out.error = (target - tip).norm();
            out.angle_error = goal.orientation().map_or(0.0, |g| wrap_angle(g - phi).abs());
            out.end_effector = EndEffector { position: tip, orientation: phi };
        }
    }
    out.iterations = iteration;
    if opts.record_every.is_some() {
        out.frames.push_final(iteration, angles, &s.joints);
    }
    status
}

/// One step of a Jacobian method with its line search (see the [module docs](self)). On
/// success the new pose is in `s.trial` and `s.trial_joints` and its tip orientation is
/// returned; `None` means no step lowers the error enough.
#[allow(clippy::too_many_arguments)]
fn jacobian_step(
    chain: &Chain,
    goal: &Goal,
    opts: &SolveOptions,
    method: Method,
    mode: LimitMode,
    clamp: bool,
    e: &Vector3<f64>,
    current: f64,
    mu: &mut f64,
    nu: &mut f64,
    angles: &[f64],
    s: &mut Scratch,
) -> Option<f64> {
    let oriented = goal.orientation().is_some();
    let mut rule = method;
    loop {
        if rule == Method::LevenbergMarquardt {
            // Levenberg–Marquardt: a rejected step raises the damping instead of halving.
            for _ in 0..=opts.backtrack {
                let scale = compute_delta(chain, opts, rule, mode, oriented, e, *mu, angles, s);
                let (trial_error, expected, trial_phi) = try_pose(chain, goal, opts, clamp, e, scale, angles, s);
                if opts.backtrack == 0 {
                    return Some(trial_phi);
                }
                let decrease = current - trial_error;
                if trial_error < current && decrease >= SUFFICIENT_DECREASE * expected {
                    let rho = if expected > 0.0 { decrease / expected } else { 1.0 };
                    *mu *= (1.0 - (2.0 * rho - 1.0).powi(3)).max(1.0 / 3.0);
                    *nu = 2.0;
                    return Some(trial_phi);
                }
                *mu *= *nu;
                *nu *= 2.0;
            }
        } else {
            let mut scale = compute_delta(chain, opts, rule, mode, oriented, e, *mu, angles, s);
            // Gauss–Newton directions get one full try; the transpose step is halved.
            let halvings = if rule == method && rule != Method::Transpose { 0 } else { opts.backtrack };
            for attempt in 0..=halvings {
                let (trial_error, expected, trial_phi) = try_pose(chain, goal, opts, clamp, e, scale, angles, s);
                if opts.backtrack == 0 {
                    return Some(trial_phi);
                }
                if trial_error < current && current - trial_error >= SUFFICIENT_DECREASE * expected {
                    return Some(trial_phi);
                }
                if attempt < halvings {
                    scale *= 0.5;
                }
            }
        }
        if rule == Method::Transpose || opts.backtrack == 0 {
            return None;
        }
        // The method's own step falls short: Gauss–Newton directions (pinv, DLS with small λ)
        // are poor where J is nearly singular, as on the way to a goal out of reach. Search the
        // steepest-descent (transpose) direction instead.
        rule = Method::Transpose;
    }
}

/// Fills `s.delta` with the joint step of `rule` under the limit `mode`, scaled by the gain
/// and the rates, and returns the factor that brings it within [`SolveOptions::max_step`].
#[allow(clippy::too_many_arguments)]
fn compute_delta(
    chain: &Chain,
    opts: &SolveOptions,
    rule: Method,
    mode: LimitMode,
    oriented: bool,
    e: &Vector3<f64>,
    mu: f64,
    angles: &[f64],
    s: &mut Scratch,
) -> f64 {
    let n = chain.len();
    // Weighted least norm: slow down a joint that the task moves toward a limit.
    s.scale.fill(1.0);
    if mode == LimitMode::Weighted {
        for (i, lim) in chain.limits().iter().enumerate() {
            if let Some(lim) = lim {
                let (lo, hi, th) = (lim.min(), lim.max(), angles[i]);
                let g = s.jacobian.column(i).dot(e);
                let toward = (g > 0.0 && 2.0 * th > lo + hi) || (g < 0.0 && 2.0 * th < lo + hi);
                if toward {
                    let gap = (hi - th) * (th - lo);
                    let w = if gap > 0.0 {
                        let dh = (hi - lo).powi(2) * (2.0 * th - hi - lo) / (4.0 * gap * gap);
                        1.0 / (1.0 + dh.abs())
                    } else {
                        0.0
                    };
                    s.scale[i] = w.sqrt();
                }
            }
        }
    }
    let locking = matches!(mode, LimitMode::Lock | LimitMode::NullSpace);
    s.locked.fill(false);
    let mut task = *e;
    let fade =
        if mode == LimitMode::NullSpace { (e.norm() / (NULLSPACE_FADE * chain.max_reach())).min(1.0) } else { 0.0 };
    for round in 0..=n {
        // Until a joint is locked or weighted, J itself is the weighted Jacobian.
        let plain = round == 0 && mode != LimitMode::Weighted;
        if !plain {
            for (i, (mut w, col)) in s.weighted.column_iter_mut().zip(s.jacobian.column_iter()).enumerate() {
                let k = if s.locked[i] { 0.0 } else { s.scale[i] };
                w.copy_from(&(col * k));
            }
        }
        let weighted = if plain { &s.jacobian } else { &s.weighted };
        let a = gram(weighted, oriented);
        method_step(rule, opts, &a, weighted, &task, mu, &mut s.step);
        for i in 0..n {
            if !s.locked[i] {
                let rate = opts.rates.get(i).copied().unwrap_or(1.0);
                s.delta[i] = opts.gain * rate * s.scale[i] * s.step[i];
            }
        }
        if mode == LimitMode::NullSpace {
            // z pulls limited joints toward the middle; remove what the task would see of it:
            // Δθ += z − Jᵀ (J Jᵀ)⁺ J z, over the free (unlocked) joints. It fades as the goal
            // nears, so that it does not slow the final convergence.
            let mut jz = Vector3::zeros();
            for (i, lim) in chain.limits().iter().enumerate() {
                s.step[i] = match lim {
                    Some(l) if !s.locked[i] => -NULLSPACE_GAIN * fade * (angles[i] - 0.5 * (l.min() + l.max())),
                    _ => 0.0,
                };
                jz += weighted.column(i) * s.step[i];
            }
            let y = pinv::task_step(&a, &jz, opts.singular_threshold);
            for i in 0..n {
                if !s.locked[i] {
                    s.delta[i] += s.step[i] - weighted.column(i).dot(&y);
                }
            }
        }
        if !locking {
            break;
        }
        // Clamp and lock: a free joint whose step crosses its limit goes only to the limit
        // and is held there; the rest of the task is solved again by the other joints.
        let mut newly = false;
        for (i, lim) in chain.limits().iter().enumerate() {
            let Some(l) = lim else { continue };
            if s.locked[i] {
                continue;
            }
            let next = angles[i] + s.delta[i];
            if next > l.max() || next < l.min() {
                let d = l.clamp(next) - angles[i];
                s.delta[i] = d;
                s.locked[i] = true;
                task -= s.jacobian.column(i) * d;
                newly = true;
            }
        }
        if !newly {
            break;
        }
    }
    let largest = s.delta.iter().fold(0.0f64, |m, d| m.max(d.abs()));
    match opts.max_step {
        Some(cap) if largest > cap => cap / largest,
        _ => 1.0,
    }
}

/// `A = J Jᵀ`, summed column by column (the 3×3 product written out: this runs every iteration
/// and nalgebra's general product of a 3×N matrix with its transpose is several times slower).
/// Without an orientation goal the third row of `J` is zero and `A`'s unused diagonal entry is
/// set to 1, so that every rule's third component of `y` is exactly 0.
fn gram(j: &Matrix3xX<f64>, oriented: bool) -> Matrix3<f64> {
    let (mut xx, mut xy, mut xz, mut yy, mut yz, mut zz) = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    for c in j.column_iter() {
        let (x, y, z) = (c[0], c[1], c[2]);
        xx += x * x;
        xy += x * y;
        xz += x * z;
        yy += y * y;
        yz += y * z;
        zz += z * z;
    }
    if !oriented {
        zz = 1.0;
    }
    Matrix3::new(xx, xy, xz, xy, yy, yz, xz, yz, zz)
}

/// The step of a Jacobian `rule` in weighted joint coordinates: `J_wᵀ y` for the task-space
/// rules, the selectively damped step for SDLS.
fn method_step(
    rule: Method,
    opts: &SolveOptions,
    a: &Matrix3<f64>,
    weighted: &Matrix3xX<f64>,
    e: &Vector3<f64>,
    mu: f64,
    out: &mut [f64],
) {
    let y = match rule {
        Method::Transpose => transpose::task_step(a, e),
        Method::PseudoInverse => pinv::task_step(a, e, opts.singular_threshold),
        Method::LevenbergMarquardt => dls::task_step(a, e, mu.sqrt(), opts.singular_threshold),
        Method::SelectivelyDamped => return sdls::joint_step(a, weighted, e, opts.singular_threshold, out),
        _ => dls::task_step(a, e, opts.lambda, opts.singular_threshold),
    };
    for (o, col) in out.iter_mut().zip(weighted.column_iter()) {
        *o = col.dot(&y);
    }
}

/// Tries `angles + scale·Δθ` (clamped into the limits when `clamp`): the trial pose goes to
/// `s.trial` and `s.trial_joints`. Returns its squared task error, the decrease the
/// linearisation `J Δθ` predicts, and its tip orientation.
#[allow(clippy::too_many_arguments)]
fn try_pose(
    chain: &Chain,
    goal: &Goal,
    opts: &SolveOptions,
    clamp: bool,
    e: &Vector3<f64>,
    scale: f64,
    angles: &[f64],
    s: &mut Scratch,
) -> (f64, f64, f64) {
    let n = chain.len();
    let target = goal.target();
    let mut predicted = *e;
    for (i, ((t, a), (d, col))) in
        s.trial.iter_mut().zip(angles).zip(s.delta.iter().zip(s.jacobian.column_iter())).enumerate()
    {
        let mut next = a + scale * d;
        if clamp {
            if let Some(lim) = chain.limits()[i] {
                next = lim.clamp(next);
            }
        }
        predicted -= col * (next - a);
        *t = next;
    }
    let trial_phi = joint_positions_into(chain, &s.trial, &mut s.trial_joints);
    let tip = s.trial_joints[n];
    let turn = goal.orientation().map_or(0.0, |g| opts.orientation_weight * wrap_angle(g - trial_phi));
    let trial_error = (target.x - tip.x).powi(2) + (target.y - tip.y).powi(2) + turn * turn;
    let expected = (e.norm_squared() - predicted.norm_squared()).max(0.0);
    (trial_error, expected, trial_phi)
}

/// `angle` wrapped into [−π, π).
#[must_use]
pub fn wrap_angle(angle: f64) -> f64 {
    use std::f64::consts::{PI, TAU};
    (angle + PI).rem_euclid(TAU) - PI
}

#[cfg(test)]
mod tests;

#[cfg(test)]
mod limit_tests;
#[cfg(test)]
mod test_support;
