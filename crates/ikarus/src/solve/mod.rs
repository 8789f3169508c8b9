//! Iterative inverse-kinematics solvers: one shared loop, one step rule per method.
//!
//! Every iteration computes the joint positions, the task error `e` (position, and the
//! weighted orientation error when the goal has one), the Jacobian `J`, and `A = J Jᵀ`.
//! The [`Method`] then picks a task-space vector `y` and the joint update is `Δθ = Jᵀ y`:
//!
//! | method | `y` |
//! | --- | --- |
//! | [`Method::Transpose`] | `α e`, with `α = ⟨e, A e⟩ / ⟨A e, A e⟩` (Buss 2004) |
//! | [`Method::PseudoInverse`] | `A⁺ e`, singular directions below [`SolveOptions::singular_threshold`] dropped |
//! | [`Method::DampedLeastSquares`] | `(A + λ² I)⁻¹ e` |
//!
//! `Δθ` is then scaled by [`SolveOptions::gain`] and the per-joint [`SolveOptions::rates`],
//! capped by [`SolveOptions::max_step`], added to the angles, and the result is clamped into the
//! joint limits ([`LimitMode::Clamp`]).
//!
//! A step is accepted only if it lowers the task error `‖e‖²` by at least a tenth of what the
//! linearisation `J Δθ` predicts (an Armijo test). Pinv and DLS try their own full step once;
//! if it fails, the steepest-descent (transpose) step is tried instead, halved up to
//! [`SolveOptions::backtrack`] times, since Gauss–Newton directions are poor where `J` is
//! nearly singular. The transpose method halves its own step. If nothing passes, the pose
//! cannot improve and the solve ends [`Status::Stalled`]. The textbook iteration
//! (`backtrack: 0`) takes every step as computed; from a nearly straight arm it turns joints by
//! whole revolutions, and it oscillates around goals out of reach. The trial pose's forward
//! kinematics is the next iteration's, so an accepted first try costs nothing extra.
//!
//! The loop stops when the goal is reached, when the pose has stopped moving (stall
//! detection), or at the iteration cap. Not reaching a goal is not an error: the [`Outcome`]
//! says why in its [`Status`] and carries the best pose found.

mod dls;
mod frames;
mod pinv;
mod transpose;

use nalgebra::{Matrix3, Matrix3xX, Point2, Vector3};
use thiserror::Error;

use crate::chain::{Chain, Pose, annulus_inner};
use crate::kinematics::{EndEffector, jacobian_from_joints, joint_positions_into};

pub use frames::{Frame, Frames};

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

/// The step rule of a solve. See the [module docs](self) for the formulas.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[non_exhaustive]
pub enum Method {
    /// Jacobian transpose with the step length that minimises the linearised error.
    Transpose,
    /// Jacobian pseudoinverse `Jᵀ (J Jᵀ)⁺`, via the eigen-decomposition of `J Jᵀ`.
    PseudoInverse,
    /// Damped least squares `Jᵀ (J Jᵀ + λ² I)⁻¹`, λ = [`SolveOptions::lambda`].
    #[default]
    DampedLeastSquares,
}

impl Method {
    /// Every method, in a stable order.
    pub const ALL: [Method; 3] = [Method::Transpose, Method::PseudoInverse, Method::DampedLeastSquares];

    /// The short name used at the edges: `transpose`, `pinv`, `dls`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Method::Transpose => "transpose",
            Method::PseudoInverse => "pinv",
            Method::DampedLeastSquares => "dls",
        }
    }
}

/// How joint limits are enforced.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[non_exhaustive]
pub enum LimitMode {
    /// Limits are not enforced.
    Ignore,
    /// After every step, each limited joint is clamped into its range (the seed program's
    /// method). Simple, but a joint pinned at a limit can hold the chain in a dead end.
    #[default]
    Clamp,
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
    /// Damping λ of [`Method::DampedLeastSquares`], ≥ 0, in length units.
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
}

impl Default for SolveOptions {
    fn default() -> Self {
        Self {
            method: Method::DampedLeastSquares,
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
            limits: LimitMode::Clamp,
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
    /// Steps taken.
    pub iterations: u32,
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

/// Scratch space reused across iterations and solves.
#[derive(Debug, Clone, Default)]
struct Scratch {
    joints: Vec<Point2<f64>>,
    trial_joints: Vec<Point2<f64>>,
    jacobian: Matrix3xX<f64>,
    delta: Vec<f64>,
    trial: Vec<f64>,
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

        let s = &mut self.scratch;
        s.joints.resize(n + 1, Point2::origin());
        s.trial_joints.resize(n + 1, Point2::origin());
        s.delta.resize(n, 0.0);
        s.trial.resize(n, 0.0);
        if s.jacobian.ncols() != n {
            s.jacobian = Matrix3xX::zeros(n);
        }

        let angles = out.pose.angles_mut();
        angles.clear();
        angles.extend_from_slice(start);
        let clamp = opts.limits == LimitMode::Clamp && chain.has_limits();
        if clamp {
            chain.clamp_into(angles);
        }
        out.frames.start(n, opts.record_every, opts.max_iterations);

        let target = goal.target();
        let weight = opts.orientation_weight;
        let mut phi = joint_positions_into(chain, angles, &mut s.joints);
        let mut iteration: u32 = 0;
        let mut still: u32 = 0;
        let status;
        loop {
            let tip = s.joints[n];
            let (dx, dy) = (target.x - tip.x, target.y - tip.y);
            let turn = goal.orientation().map(|g| wrap_angle(g - phi));
            let error = dx.hypot(dy);
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

            // Task error and A = J Jᵀ, embedded in three dimensions: without an orientation
            // goal the third row of J and e is zero and A's unused diagonal entry is 1, so the
            // third component of y is exactly 0 for every rule.
            jacobian_from_joints(&s.joints, &mut s.jacobian);
            let e = Vector3::new(dx, dy, turn.map_or(0.0, |t| weight * t));
            let row_scale = if turn.is_some() { weight } else { 0.0 };
            let mut a = Matrix3::zeros();
            for mut col in s.jacobian.column_iter_mut() {
                col[2] *= row_scale;
                a.ger(1.0, &col, &col, 1.0);
            }
            if turn.is_none() {
                a[(2, 2)] = 1.0;
            }
            // Δθ = Jᵀ y, scaled by gain and rates, capped; then the line search. If the
            // method's own full step falls short of the sufficient decrease, the steepest-descent
            // (transpose) step is searched too: Gauss–Newton directions (pinv, DLS with small λ)
            // are poor where J is nearly singular, as on the way to a goal out of reach.
            let current = e.norm_squared();
            let mut accepted;
            let mut rule = opts.method;
            loop {
                let y = match rule {
                    Method::Transpose => transpose::task_step(&a, &e),
                    Method::PseudoInverse => pinv::task_step(&a, &e, opts.singular_threshold),
                    Method::DampedLeastSquares => dls::task_step(&a, &e, opts.lambda, opts.singular_threshold),
                };
                let mut largest: f64 = 0.0;
                for (i, (d, col)) in s.delta.iter_mut().zip(s.jacobian.column_iter()).enumerate() {
                    let rate = opts.rates.get(i).copied().unwrap_or(1.0);
                    *d = opts.gain * rate * col.dot(&y);
                    largest = largest.max(d.abs());
                }
                let scale = match opts.max_step {
                    Some(cap) if largest > cap => cap / largest,
                    _ => 1.0,
                };
                let halvings = if rule == opts.method && rule != Method::Transpose { 0 } else { opts.backtrack };
                accepted = line_search(chain, goal, opts, clamp, &e, current, scale, halvings, angles, s);
                if accepted.is_some() || rule == Method::Transpose || opts.backtrack == 0 {
                    break;
                }
                rule = Method::Transpose;
            }
            let Some(trial_phi) = accepted else {
                // No step along this direction lowers the error: the pose cannot move, and the
                // same pose would give the same direction again.
                status = Status::Stalled;
                break;
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

        out.iterations = iteration;
        out.status = if status != Status::Reached && goal.is_out_of_reach(chain, opts.tolerance) {
            Status::Unreachable
        } else {
            status
        };
        if opts.record_every.is_some() {
            out.frames.push_final(iteration, angles, &s.joints);
        }
        Ok(())
    }
}

/// Tries `angles + scale·Δθ` (clamped into the limits when `clamp`), halving `scale` up to
/// `halvings` times until the task error drops below `current` by at least
/// [`SUFFICIENT_DECREASE`] of the decrease the linearisation `J Δθ` predicts. On success the
/// trial pose is in `s.trial` and `s.trial_joints`, and its tip orientation is returned.
/// With `opts.backtrack == 0` the first trial is taken as it is.
#[allow(clippy::too_many_arguments)]
fn line_search(
    chain: &Chain,
    goal: &Goal,
    opts: &SolveOptions,
    clamp: bool,
    e: &Vector3<f64>,
    current: f64,
    mut scale: f64,
    halvings: u32,
    angles: &[f64],
    s: &mut Scratch,
) -> Option<f64> {
    let n = chain.len();
    let target = goal.target();
    for attempt in 0..=halvings {
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
        if opts.backtrack == 0 {
            return Some(trial_phi);
        }
        let tip = s.trial_joints[n];
        let turn = goal.orientation().map_or(0.0, |g| opts.orientation_weight * wrap_angle(g - trial_phi));
        let trial_error = (target.x - tip.x).powi(2) + (target.y - tip.y).powi(2) + turn * turn;
        let expected = (current - predicted.norm_squared()).max(0.0);
        if trial_error < current && current - trial_error >= SUFFICIENT_DECREASE * expected {
            return Some(trial_phi);
        }
        if attempt < halvings {
            scale *= 0.5;
        }
    }
    None
}

/// `angle` wrapped into [−π, π).
#[must_use]
pub fn wrap_angle(angle: f64) -> f64 {
    use std::f64::consts::{PI, TAU};
    (angle + PI).rem_euclid(TAU) - PI
}

#[cfg(test)]
mod tests;
