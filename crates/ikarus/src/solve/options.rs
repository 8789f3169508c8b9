//! The options of a solve ([`SolveOptions`], with [`Restarts`] and [`StallDetection`]) and
//! their validation: on their own ([`SolveOptions::validate`], [`OptionsError`]) and against
//! the chain they are used with ([`SolveOptions::validate_for`]).

use crate::number::Num;
use thiserror::Error;

use super::{LimitMode, Method, SolveError};
use crate::chain::Chain;

/// Restarts from other start poses when a solve stalls or runs out of iterations (each attempt
/// has the full iteration cap).
///
/// Attempt `k` (1-based) starts from `start + (k / attempts)·(r − start)`, clamped into the
/// limits, where `r` is a pose drawn uniformly inside the limits (free joints: [−π, π)) by a
/// generator seeded with `seed`: early attempts start near the original start pose, so the
/// first goal reached tends to be near it too and an animation does not jump. The first attempt
/// that reaches the goal wins; if none does, the outcome is the attempt with the smallest error.
/// The same `seed` gives the same attempts, bit for bit.
///
/// A goal that the certified-reach verdict ([`SolveOptions::reach_verdict`]) judged reachable
/// also gets a start pose from the region: the first attempt (with Levenberg–Marquardt or damped
/// least squares) is a probe of at most 12 iterations,
/// and one cut short with a joint held at a limit is followed by restart 1 from the pose the
/// exact region reads off for the goal (with the cap less the probe's 12; it reached every goal
/// of the bench's `limits-*` sets whose probe did not), which then runs the first attempt again
/// whole if it did not reach; a probe cut short with no joint at a limit runs again whole at
/// once. Restart 1 of any other seeded solve starts from the region's pose; the poses above
/// follow.
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

/// The largest [`SolveOptions::backtrack`].
pub const MAX_BACKTRACK: u32 = 64;

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
    /// test (see the [module docs](super)); when none passes, the solve ends
    /// [`Status::Stalled`](super::Status::Stalled). `0` takes every step as computed: the textbook iteration, which can
    /// jump by whole turns near singular poses and oscillate around goals out of reach. At
    /// most [`MAX_BACKTRACK`]: every halving costs a forward-kinematics pass, and past 64 the
    /// step is below any tolerance.
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
    /// Stops the solve when set (checked every iteration and between restarts): it ends
    /// [`Status::Interrupted`](super::Status::Interrupted) with the pose it has. `None` never
    /// stops early.
    pub interrupt: Option<crate::Interrupt>,
    /// With limits enforced, judge the goal against the exact reachable region first
    /// ([`Region`](crate::reach::Region)): a goal outside it by more than the tolerance ends
    /// [`Status::Unreachable`](super::Status::Unreachable) at once, with the pose reaching the
    /// nearest reachable point and [`Outcome::reach_distance`](super::Outcome::reach_distance)
    /// set (see the `verdict` notes in the [module docs](super)). `false` searches as if no
    /// region were known (for comparison). Default `true`.
    pub reach_verdict: bool,
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
            interrupt: None,
            reach_verdict: true,
        }
    }
}

/// Why [`SolveOptions`] are invalid. Every variant names the field and the value.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum OptionsError {
    /// A number is out of its range (the message says which range).
    #[error("{field}: must be {expected}, got {}", Num(*.value))]
    OutOfRange {
        /// The option's name.
        field: &'static str,
        /// The allowed range, in words.
        expected: &'static str,
        /// The offending value.
        value: f64,
    },
    /// A per-joint rate is out of range.
    #[error("rates[{index}]: must be a finite number ≥ 0, got {}", Num(*.value))]
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
        if self.backtrack > MAX_BACKTRACK {
            return Err(OptionsError::OutOfRange {
                field: "backtrack",
                expected: "at most 64 (a step halved 64 times is 5e-20 of itself)",
                value: f64::from(self.backtrack),
            });
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

    /// Checks the options against `chain`: [`SolveOptions::rates`] is empty or has one value
    /// per joint ([`SolveError::RatesLength`] otherwise).
    ///
    /// [`Solver::solve`](super::Solver::solve) runs this check on every solve; the edges (the
    /// command line, the HTTP API) also call it once, when they build options, so that a
    /// mismatch is reported before any work or output starts, in the same words as the solve
    /// would report it.
    pub fn validate_for(&self, chain: &Chain) -> Result<(), SolveError> {
        let n = chain.len();
        if !self.rates.is_empty() && self.rates.len() != n {
            return Err(SolveError::RatesLength { expected: n, got: self.rates.len() });
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use crate::{Chain, Link, SolveError, SolveOptions};

    #[test]
    fn rates_are_none_or_one_per_joint() {
        let chain = Chain::new([0.0, 0.0], &[Link::new(1.0, 0.0), Link::new(1.0, 0.0)]).unwrap();
        assert_eq!(SolveOptions::default().validate_for(&chain), Ok(()));
        let two = SolveOptions { rates: vec![1.0, 0.5], ..SolveOptions::default() };
        assert_eq!(two.validate_for(&chain), Ok(()));
        let three = SolveOptions { rates: vec![1.0; 3], ..SolveOptions::default() };
        assert_eq!(three.validate_for(&chain), Err(SolveError::RatesLength { expected: 2, got: 3 }));
    }
}
