//! [`Model`]: what the solver core asks of the body it moves — forward kinematics into its
//! scratch, the Jacobian, the limits, the reach, the reachability of a goal and the
//! non-Jacobian steppers — so that one core can serve chains and skeletons — and [`Problem`],
//! what one solve borrows. The bodies' implementations live beside their data
//! (`chain_model`, `skeleton_model`), so this file imports none of the steppers that use it.
//!
//! The core is generic over the model and monomorphised per model: for a [`Chain`] every
//! method is today's chain function, inlined, so the chain path is the same machine code as
//! before the abstraction (no dynamic dispatch, no branch on the kind of body).

use nalgebra::Point2;

use super::algebra::Algebra;
use super::fast::Taken;
use super::scratch::Scratch;
use super::{LimitMode, Outcome, SolveOptions};
use crate::chain::{Chain, JointLimits};
use crate::limits::Bounds;

/// The scratch of a model's solves.
pub(super) type ScratchOf<M> = Scratch<<M as Model>::Points, <M as Model>::Alg>;

/// A body's rest-pose preference, one entry per joint (see `limit_modes::pull_to_rest`):
/// joint `i` turns `1 / scale[i]²` times less readily than a joint of scale 1, and is pulled
/// back toward `rest[i]` at the share `pull[i]` of its gain, in the null space of the task.
#[derive(Debug, Clone, Copy)]
pub(super) struct Posture<'a> {
    /// `1 / √(1 + stiffness)`: the weight of the joint's column.
    pub(super) scale: &'a [f64],
    /// `stiffness / (1 + stiffness)`: the pull's share, the natural gradient of
    /// `½ Σ stiffness (θ − rest)²` in the metric `1 + stiffness`.
    pub(super) pull: &'a [f64],
    /// The rest angles.
    pub(super) rest: &'a [f64],
}

/// A kinematic body the solver core can move, with what it is asked to reach: angles in,
/// points, the task error and the Jacobian out.
pub(super) trait Model: Sized {
    /// What the body is asked to reach ([`Goal`] for a chain).
    type Goal;
    /// What its forward kinematics writes (a chain's `len() + 1` joint points).
    type Points: Default + Clone + std::fmt::Debug;
    /// Its task-space algebra.
    type Alg: Algebra;
    /// A body whose accepted steps lower the task's merit by no more than this share of it
    /// counts as standing still (as a pose that moves by less than the stall's epsilon does);
    /// `None`: only the pose's movement counts.
    const PROGRESS_FLOOR: Option<f64>;
    /// Whether an attempt of this body may give up once pinned and hopeless, when its
    /// [`Problem::gives_up_pinned`] asks (see [`attempt`](super::attempt::attempt)); bodies
    /// whose answers were fixed before that rule keep to the stall window alone.
    const GIVES_UP_PINNED: bool = false;
    /// The number of angles (joints).
    fn len(&self) -> usize;
    /// Sizes the scratch for this body.
    fn fit(&self, s: &mut ScratchOf<Self>);
    /// The largest distance from the base any point can reach.
    fn max_reach(&self) -> f64;
    /// The joint limits, one entry per angle.
    fn limits(&self) -> &[Option<JointLimits>];
    /// The limits as [`Bounds`].
    fn bounds(&self) -> Bounds<'_>;
    /// The body's rest-pose preference, if it has one (a skeleton with stiff bones; a chain
    /// has none, and its steps are the rules' own).
    #[inline]
    fn posture(&self) -> Option<Posture<'_>> {
        None
    }
    /// Forward kinematics of `angles` into `points`; returns the end effector's orientation
    /// (a chain's; for other bodies some number that is finite exactly when every angle is).
    fn forward_into(&self, angles: &[f64], points: &mut Self::Points) -> f64;
    /// The points a recorded frame keeps: the base, then every joint's tip.
    fn frame_points(points: &Self::Points) -> &[Point2<f64>];
    /// Measures the pose whose `points` and `phi` are given against `goal`: writes
    /// `out.error`, `out.angle_error` (the largest over the effectors) and `out.end_effector`
    /// (and a skeleton's effectors), and the task error `e` into `alg`.
    fn measure(
        &self,
        goal: &Self::Goal,
        opts: &SolveOptions,
        points: &Self::Points,
        phi: f64,
        out: &mut Outcome,
        alg: &mut Self::Alg,
    );
    /// The task Jacobian at the pose whose `points` are given, rows scaled as `e`'s, into `alg`.
    fn jacobian(&self, goal: &Self::Goal, opts: &SolveOptions, points: &Self::Points, alg: &mut Self::Alg);
    /// `‖e‖²` of the pose whose `points` and `phi` are given.
    fn trial_error(&self, goal: &Self::Goal, opts: &SolveOptions, points: &Self::Points, phi: f64) -> f64;
    /// The squared task error that CCD, FABRIK and the restarts compare poses by, of the pose
    /// `out` was measured on.
    fn best_key(&self, opts: &SolveOptions, out: &Outcome, alg: &Self::Alg) -> f64;
    /// Whether `goal` is out of reach even without limits (by more than `tolerance`).
    fn is_out_of_reach(&self, goal: &Self::Goal, tolerance: f64) -> bool;
    /// After the final measurement and status: each effector's own status (a skeleton's).
    fn judge(&self, goal: &Self::Goal, opts: &SolveOptions, out: &mut Outcome);
    /// Restart `k`'s start pose `restart`, drawn for every joint by [`restart_pose`], after an
    /// attempt that ended in `out`: a body with several effectors redraws it its own way
    /// (`scratch`: one flag per joint, as work space). A chain keeps it.
    ///
    /// [`restart_pose`]: super::restarts::restart_pose
    fn settle_restart(&self, p: &Problem<'_, Self>, k: u32, out: &Outcome, restart: &mut [f64], scratch: &mut [bool]);
    /// The attempt on the position-only fast path ([`super::fast`]), where it applies and
    /// runs: to the end (it wrote what [`attempt`](super::attempt::attempt) writes), or to
    /// the iteration where the general loop takes over. None but a chain's has one.
    #[inline]
    fn fast_attempt(_p: &Problem<'_, Self>, _start: &[f64], _s: &mut ScratchOf<Self>, _out: &mut Outcome) -> Taken {
        Taken::No
    }
    /// One CCD sweep (see `ccd::sweep`); returns the trial pose's end orientation.
    fn ccd_sweep(
        p: &Problem<'_, Self>,
        angles: &[f64],
        points: &Self::Points,
        trial: &mut [f64],
        trial_points: &mut Self::Points,
    ) -> f64;
    /// One FABRIK iteration (see `fabrik::iterate`); returns the trial pose's end orientation.
    fn fabrik_iterate(
        p: &Problem<'_, Self>,
        angles: &[f64],
        points: &Self::Points,
        trial: &mut [f64],
        trial_points: &mut Self::Points,
    ) -> f64;
}

/// One solve's borrowed context, for a body of type `M` (a [`Chain`] unless said otherwise).
pub(super) struct Problem<'a, M: Model = Chain> {
    pub(super) model: &'a M,
    pub(super) goal: &'a M::Goal,
    pub(super) opts: &'a SolveOptions,
    /// The limits the solve enforces: the model's, or none when the options ignore them or
    /// the model has none.
    pub(super) bounds: Bounds<'a>,
    /// The limit mode in effect: [`LimitMode::Ignore`] whenever `bounds` is free.
    pub(super) mode: LimitMode,
    /// The iteration cap of an attempt: [`SolveOptions::max_iterations`], or less for the
    /// probe of a seeded solve (see `restarts`).
    pub(super) max_iterations: u32,
    /// The attempt gives up when it stands pinned at a limit and hopeless (see
    /// [`attempt`](super::attempt::attempt)): only the first attempt run whole after a probe
    /// that was still converging, whose whole run is owed if it gives up (see `restarts`).
    pub(super) gives_up_pinned: bool,
    /// The attempt, of a Jacobian method, keeps its state where it stops at its cap or gives
    /// up, for [`resume`](super::attempt::resume) to go on from: only the first attempt of a
    /// seeded solve (see `restarts`).
    pub(super) pauses: bool,
}

// By hand: derived impls would ask `M: Clone`/`M: Copy`, and only references are copied.
impl<M: Model> Clone for Problem<'_, M> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<M: Model> Copy for Problem<'_, M> {}

impl<'a, M: Model> Problem<'a, M> {
    /// The context of a solve of `model` for `goal` under `opts`.
    pub(super) fn new(model: &'a M, goal: &'a M::Goal, opts: &'a SolveOptions) -> Self {
        let bounds = match opts.limits {
            LimitMode::Ignore => Bounds::free(),
            LimitMode::Clamp | LimitMode::Lock | LimitMode::NullSpace | LimitMode::Weighted => model.bounds(),
        };
        Self::with_bounds(model, goal, opts, bounds)
    }

    /// The context with explicit `bounds` (the mode of `opts` applies unless they are free).
    pub(super) fn with_bounds(model: &'a M, goal: &'a M::Goal, opts: &'a SolveOptions, bounds: Bounds<'a>) -> Self {
        let mode = if bounds.is_free() { LimitMode::Ignore } else { opts.limits };
        Self {
            model,
            goal,
            opts,
            bounds,
            mode,
            max_iterations: opts.max_iterations,
            gives_up_pinned: false,
            pauses: false,
        }
    }
}
