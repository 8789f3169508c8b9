//! [`Scratch`]: the buffers one [`Solver`](super::Solver) reuses across iterations and
//! solves, so that the loop does not allocate, and [`LoopState`], an attempt's state kept there.

use super::lm::Damping;

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

/// A watched attempt paused at its cap whose merit fell below this share of the iteration
/// before's in its last step converges as Levenberg–Marquardt and damped least squares do
/// near a solution, faster than linearly (see [`LoopState::converging`]).
pub(super) const CONVERGING_SHARE: f64 = 0.25;

/// The state of an attempt's loop at the start of an iteration: all it needs to go on exactly
/// as if it had run on without stopping. Two hand-overs carry it: the fast path leaving the
/// common case ([`Taken::Resume`](super::fast::Taken::Resume), the pose in `s.best`), and a
/// watched attempt pausing (see [`Problem::pauses`](super::model::Problem::pauses)) for
/// [`resume`](super::attempt::resume) (the pose in `s.paused_pose`).
#[derive(Debug, Clone, Copy)]
pub(super) struct LoopState {
    pub(super) iteration: u32,
    pub(super) still: u32,
    pub(super) damping: Damping,
    pub(super) skip_damped: bool,
    pub(super) prev_merit: f64,
    pub(super) last_merit: f64,
    pub(super) hopeless: u32,
    /// The merit where it paused (that of the pose it paused on).
    pub(super) merit: f64,
}

impl LoopState {
    /// Where an attempt starts: iteration 0, damping μ = λ², nothing watched yet.
    pub(super) fn start(lambda: f64) -> Self {
        Self::at(0, 0, Damping::new(lambda), false)
    }

    /// At `iteration`, `still` iterations without moving, with `damping`; `damped_failed`:
    /// this iteration's damped tries were all rejected, so the loop goes on with the line
    /// search's transpose step. Nothing watched yet (the fast path does not watch).
    pub(super) fn at(iteration: u32, still: u32, damping: Damping, damped_failed: bool) -> Self {
        Self {
            iteration,
            still,
            damping,
            skip_damped: damped_failed,
            prev_merit: f64::INFINITY,
            last_merit: f64::INFINITY,
            hopeless: 0,
            merit: f64::INFINITY,
        }
    }

    /// Whether the attempt, watched, paused converging: its last step lowered the merit below
    /// [`CONVERGING_SHARE`] of what it was. On the bench's 7-link `limits-*` sets (seeds 1 and
    /// 7, 4000 goals), the first attempts that reach their goal after 13 iterations fell to
    /// 0.00 to 0.10 of it in their twelfth step, while those crawling toward a limit, which
    /// then stand pinned there, fell to 0.3 to 1.0 of it in most cases.
    pub(super) fn converging(&self) -> bool {
        self.merit < CONVERGING_SHARE * self.last_merit
    }
}
