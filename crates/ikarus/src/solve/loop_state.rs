//! [`LoopState`]: where an attempt's loop stands at the start of an iteration, handed over
//! by the fast path to the general loop and kept by a paused attempt for its resumption.

use super::lm::Damping;

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
