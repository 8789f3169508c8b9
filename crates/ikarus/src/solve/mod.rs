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
//! the linearisation `J Δθ` predicts (an Armijo test; see `line_search.rs`). Pinv, DLS and SDLS try their own full
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

//! ## Files
//!
//! One concept each: `goal` (in [`crate::goal`]), `options`, `outcome`, `solver` (input checks,
//! the closed-form fast path, scratch buffers), `restarts` (the restart driver), `attempt` (the
//! iteration loop), `line_search`, `limit_modes`, `step` (`A = J Jᵀ` and the dispatch to the
//! rules), one file per step rule (`transpose`, `pinv`, `dls`, `sdls`, `lm`), `ccd`, `fabrik`,
//! `frames`, and `method` (the [`Method`] and [`LimitMode`] names).

mod algebra;
mod attempt;
mod ccd;
mod chain_model;
mod dls;
mod fabrik;
mod fast;
mod frames;
mod limit_modes;
mod line_search;
mod lm;
mod method;
mod model;
mod options;
mod outcome;
mod pinv;
mod restarts;
mod scratch;
mod sdls;
mod skeleton_bends;
mod skeleton_model;
mod skeleton_solve;
mod solver;
mod step;
mod task;
mod transpose;
mod verdict;

pub use crate::angle::wrap_angle;
pub use crate::goal::{Goal, GoalError};
pub use frames::{Frame, Frames};
pub use method::{LimitMode, Method};
pub use options::{MAX_BACKTRACK, OptionsError, Restarts, SolveOptions, StallDetection};
pub use outcome::{Outcome, SolveError, Status};
pub use solver::Solver;
pub use task::{Bend, BoneBend, EffectorOutcome, Pin, Priority, RigGoal, RigTask, RigTaskError};

#[cfg(test)]
mod tests;

#[cfg(test)]
mod bend_tests;
#[cfg(test)]
mod ccd_fabrik_tests;
#[cfg(test)]
mod limit_tests;
#[cfg(test)]
mod skeleton_tests;
#[cfg(test)]
mod test_support;
