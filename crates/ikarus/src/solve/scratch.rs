//! [`Scratch`]: the buffers one [`Solver`](super::Solver) reuses across iterations and
//! solves, so that the loop does not allocate (with a paused attempt's [`LoopState`](super::loop_state::LoopState)).

use super::loop_state::LoopState;

/// Scratch space reused across iterations and solves, for a body whose forward kinematics
/// writes a `P` (a chain's joint points) and whose task space is the algebra `A`.
#[derive(Debug, Clone, Default)]
pub(super) struct Scratch<P, A> {
    pub(super) joints: P,
    pub(super) trial_joints: P,
    /// The task error, Jacobian and their products (see [`super::algebra`]).
    pub(super) alg: A,
    /// Square roots of the joint weights of [`LimitMode::Weighted`](super::LimitMode::Weighted);
    /// 1 otherwise.
    pub(super) scale: Vec<f64>,
    /// Joints locked at a limit this iteration (lock and null-space modes).
    pub(super) locked: Vec<bool>,
    /// The method's step in weighted coordinates.
    pub(super) step: Vec<f64>,
    pub(super) delta: Vec<f64>,
    /// The rest pose's pull of this step (a body with a [`Posture`](super::model::Posture)).
    pub(super) pull: Vec<f64>,
    pub(super) trial: Vec<f64>,
    /// The best pose of a non-descent method (CCD, FABRIK).
    pub(super) best: Vec<f64>,
    /// The start pose of a restart.
    pub(super) restart: Vec<f64>,
    /// The final pose of the best attempt so far, when a solve restarts.
    pub(super) best_attempt: Vec<f64>,
    /// The position-only fast path's state (a chain's; see [`super::fast`]).
    pub(super) fast: super::fast::Buffers<f64>,
    /// Whether the last attempt gave up pinned and hopeless (see
    /// [`attempt`](super::attempt::attempt)).
    pub(super) gave_up: bool,
    /// The attempt paused for [`resume`](super::attempt::resume), if one is (see
    /// [`Problem::pauses`](super::model::Problem::pauses)), and its pose.
    pub(super) paused: Option<LoopState>,
    pub(super) paused_pose: Vec<f64>,
}

impl<P, A: super::algebra::Algebra> Scratch<P, A> {
    /// Sizes the joint-indexed buffers for `n` joints and the algebra's; the caller sizes the
    /// points. No allocation once they have grown to it.
    pub(super) fn fit_joints(&mut self, n: usize) {
        for v in [
            &mut self.scale,
            &mut self.step,
            &mut self.delta,
            &mut self.pull,
            &mut self.trial,
            &mut self.best,
            &mut self.restart,
            &mut self.best_attempt,
            &mut self.paused_pose,
        ] {
            v.resize(n, 0.0);
        }
        self.locked.resize(n, false);
        self.alg.fit(n);
    }
}
