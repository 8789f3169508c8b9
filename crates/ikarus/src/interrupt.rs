//! A cancellation token: a flag shared between the code that runs a long computation and the
//! code that may want to stop it (a server's deadline, a client that went away, Ctrl-C).
//!
//! Solves ([`SolveOptions::interrupt`](crate::SolveOptions::interrupt)), the workspace sampler
//! ([`WorkspaceOptions::interrupt`](crate::WorkspaceOptions::interrupt)) and the trackers (through
//! their solve options) check it as they go and end early when it is set: a solve ends
//! [`Status::Interrupted`](crate::Status::Interrupted) with the pose it has, the sampler returns
//! [`ReachError::Interrupted`](crate::ReachError::Interrupted). Checking costs one relaxed load.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

/// A cancellation token; clones share the flag. Two tokens are equal when they share it.
#[derive(Clone, Debug, Default)]
pub struct Interrupt(Arc<AtomicBool>);

impl Interrupt {
    /// A token that is not set.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// Sets the flag: every computation checking this token (or a clone) stops soon.
    pub fn interrupt(&self) {
        self.0.store(true, Ordering::Relaxed);
    }

    /// Whether [`interrupt`](Self::interrupt) was called on this token or a clone.
    #[inline]
    #[must_use]
    pub fn is_interrupted(&self) -> bool {
        self.0.load(Ordering::Relaxed)
    }
}

impl PartialEq for Interrupt {
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.0, &other.0)
    }
}

/// Whether `token` is given and set.
#[inline]
pub(crate) fn is_set(token: Option<&Interrupt>) -> bool {
    token.is_some_and(Interrupt::is_interrupted)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clones_share_the_flag_and_compare_equal() {
        let a = Interrupt::new();
        let b = a.clone();
        assert_eq!(a, b);
        assert_ne!(a, Interrupt::new());
        assert!(!b.is_interrupted());
        a.interrupt();
        assert!(b.is_interrupted());
        assert!(is_set(Some(&b)));
        assert!(!is_set(None));
    }

    /// A solve that would run for hours (no stall detection nor line search, a tolerance no
    /// tip can meet, the largest iteration cap, restarts) ends `interrupted` once its token is set from another
    /// thread. The only wall-clock bound here is "it ends at all": the hang is the bug.
    #[test]
    fn a_solve_ends_interrupted_when_its_token_is_set() {
        use crate::{Goal, Restarts, SolveOptions, Solver, Status};
        // Out of the limited arm's reach, though within its reach without limits: no pose meets
        // the goal, so every attempt runs to its cap.
        let chain = crate::fixtures::seed_arm_limited();
        let token = Interrupt::new();
        let options = SolveOptions {
            tolerance: f64::MIN_POSITIVE,
            max_iterations: u32::MAX,
            stall: None,
            backtrack: 0,
            restarts: Some(Restarts { attempts: 64, ..Restarts::default() }),
            closed_form: false,
            interrupt: Some(token.clone()),
            // The search itself is what is interrupted (the verdict would answer at once).
            reach_verdict: false,
            ..SolveOptions::default()
        };
        let mut solver = Solver::new(options).expect("valid options");
        let goal = Goal::position(-3.0, -1.0).expect("finite goal");
        let setter = {
            let token = token.clone();
            std::thread::spawn(move || {
                std::thread::sleep(std::time::Duration::from_millis(50));
                token.interrupt();
            })
        };
        let outcome = solver.solve(&chain, chain.start_pose(), &goal).expect("solves");
        setter.join().expect("the setter thread ends");
        assert_eq!(outcome.status, Status::Interrupted);
        assert_eq!(outcome.status.as_str(), "interrupted");
        assert!(outcome.iterations > 0, "it ran until interrupted");
        assert!(outcome.error.is_finite());
    }

    /// A token set before the solve stops it at its first iteration, restarts included.
    #[test]
    fn a_solve_with_a_set_token_stops_at_once() {
        use crate::{Goal, Restarts, SolveOptions, Solver, Status};
        let chain = crate::fixtures::seed_arm_limited();
        let token = Interrupt::new();
        token.interrupt();
        let options = SolveOptions {
            restarts: Some(Restarts { attempts: 64, ..Restarts::default() }),
            interrupt: Some(token),
            closed_form: false,
            ..SolveOptions::default()
        };
        let goal = Goal::position(-3.0, -1.0).expect("finite goal");
        let outcome = Solver::new(options).expect("valid").solve(&chain, chain.start_pose(), &goal).expect("solves");
        assert_eq!(outcome.status, Status::Interrupted);
        assert_eq!((outcome.iterations, outcome.restarts), (0, 0));
    }

    #[test]
    fn the_workspace_sampler_returns_interrupted() {
        use crate::reach::{ReachError, WorkspaceOptions, sample};
        let chain = crate::fixtures::seed_arm_limited();
        let token = Interrupt::new();
        let options = WorkspaceOptions { interrupt: Some(token.clone()), ..WorkspaceOptions::default() };
        assert!(sample(&chain, &options).is_ok(), "an unset token changes nothing");
        token.interrupt();
        for parallel in [false, true] {
            let options = WorkspaceOptions { parallel, ..options.clone() };
            assert_eq!(sample(&chain, &options), Err(ReachError::Interrupted));
        }
    }

    #[test]
    fn follow_and_plan_return_interrupted() {
        use crate::{Path, SolveOptions, TrackError, TrackMode, TrackOptions, track::track};
        let chain = crate::fixtures::seed_arm();
        let path = Path::line([2.0, 3.0], [4.0, 0.0], 50).expect("valid path");
        let token = Interrupt::new();
        let options = TrackOptions {
            solve: SolveOptions { interrupt: Some(token.clone()), ..SolveOptions::default() },
            ..TrackOptions::default()
        };
        let start = chain.start_pose().angles().to_vec();
        for mode in [TrackMode::Follow, TrackMode::Plan] {
            assert!(track(&chain, &start, &path, mode, &options).is_ok());
        }
        token.interrupt();
        for mode in [TrackMode::Follow, TrackMode::Plan] {
            assert_eq!(track(&chain, &start, &path, mode, &options).unwrap_err(), TrackError::Interrupted);
        }
    }
}
