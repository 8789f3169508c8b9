//! [`follow`]: a path tracked online, sample by sample, and the [`Follower`] that does it one
//! goal at a time (see the [module docs](super) for the method).

use crate::chain::Chain;
use crate::goal::Goal;
use crate::math;
use crate::rng::SplitMix64;
use crate::skeleton::Skeleton;
use crate::solve::{Outcome, RigTask, Solver, Status};

use super::{
    Path, RigEffector, SampleStatus, Track, TrackBody, TrackError, TrackOptions, TrackSample, joint_delta, joint_step,
    unwrap_free,
};

/// What one [`Follower`] step did; the pose is [`Follower::pose`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Step {
    /// How the sample ended.
    pub status: SampleStatus,
    /// Distance from the tip to the goal's position, at the new pose.
    pub error: f64,
    /// Absolute orientation error at the new pose, radians in [0, π]; 0 without an
    /// orientation goal.
    pub angle_error: f64,
    /// The largest joint change of this step, radians (free joints the short way round).
    pub step: f64,
}

/// Follows goals one at a time, as a pointer or a stream gives them: each goal solved from the
/// current pose, the solution nearest it taken, and no joint moved more than
/// [`TrackOptions::max_step`] per call of [`Follower::step`].
///
/// It owns its body, solver and buffers: after the first step, a step allocates nothing.
/// The same goals from the same pose give the same poses, bit for bit.
///
/// The body is a [`Chain`] (the default: its tip follows) or a [`RigEffector`] (one bone tip
/// of a skeleton follows while the rest of a rig task holds; [`Follower::rig`]).
#[derive(Debug, Clone)]
pub struct Follower<B: TrackBody = Chain> {
    body: B,
    options: TrackOptions,
    solver: Solver,
    pose: Vec<f64>,
    out: Outcome,
    /// The best solution found by the current step, and a restart's start pose.
    best: Vec<f64>,
    seed_pose: Vec<f64>,
    /// Steps taken: a restart's seed depends on it.
    count: u64,
}

impl Follower<RigEffector> {
    /// A follower of the tip of `bone` of `skeleton` at the pose `start` (radians, one per
    /// bone), the goals and pins of `task` held (see [`RigEffector`]).
    pub fn rig(
        skeleton: &Skeleton,
        start: &[f64],
        bone: usize,
        task: &RigTask,
        options: &TrackOptions,
    ) -> Result<Self, TrackError> {
        Follower::new(&RigEffector::new(skeleton, start, bone, task)?, start, options)
    }
}

impl Follower<Chain> {
    /// The chain followed.
    #[must_use]
    pub fn chain(&self) -> &Chain {
        &self.body
    }
}

impl<B: TrackBody> Follower<B> {
    /// A follower of `body` (a chain, or a [`RigEffector`]) at the pose `start` (radians, one
    /// per joint).
    pub fn new(body: &B, start: &[f64], options: &TrackOptions) -> Result<Self, TrackError> {
        let solver = body.track_solver(options, start)?;
        let n = body.angle_count();
        Ok(Self {
            body: body.clone(),
            options: options.clone(),
            solver,
            pose: start.to_vec(),
            out: Outcome::default(),
            best: vec![0.0; n],
            seed_pose: vec![0.0; n],
            count: 0,
        })
    }

    /// Puts the follower at the pose `start` (radians, one per joint) as if it were new: its
    /// later steps are those of [`Follower::new`] with the same body, options and `start`, bit
    /// for bit, and it keeps its solver and buffers (no allocation). A pointer that one follower
    /// follows from poses set elsewhere (an edited pose, another motion) needs no new one.
    ///
    /// # Errors
    /// A `start` of the wrong length, or with an angle that is not finite.
    pub fn reset(&mut self, start: &[f64]) -> Result<(), TrackError> {
        super::check_start(self.pose.len(), start)?;
        self.pose.copy_from_slice(start);
        self.count = 0;
        Ok(())
    }

    /// The current pose, radians.
    #[must_use]
    pub fn pose(&self) -> &[f64] {
        &self.pose
    }

    /// The body followed.
    #[must_use]
    pub fn body(&self) -> &B {
        &self.body
    }

    /// Moves the arm toward `goal`: to the solution nearest the current pose if no joint
    /// moves more than [`TrackOptions::max_step`], else that far along the straight joint-space
    /// line toward it ([`SampleStatus::Limited`], unless the goal is out of reach).
    pub fn step(&mut self, goal: &Goal) -> Step {
        self.advance(goal, true)
    }

    /// Moves the arm straight to the solution nearest the current pose, without the step bound:
    /// the first sample of a path, or a jump the caller wants.
    pub fn place(&mut self, goal: &Goal) -> Step {
        self.advance(goal, false)
    }

    fn advance(&mut self, goal: &Goal, bounded: bool) -> Step {
        let status = self.solve_near(goal);
        let bounds = self.body.track_bounds(&self.options.solve);
        unwrap_free(bounds, &mut self.best, &self.pose);
        let largest = joint_step(bounds, &self.best, &self.pose);
        let max_step = self.options.max_step;
        let (status, step) = if bounded && largest > max_step {
            let scale = max_step / largest;
            for (i, (q, &target)) in self.pose.iter_mut().zip(&self.best).enumerate() {
                *q += scale * joint_delta(bounds, i, target, *q);
            }
            let status = if status == SampleStatus::Unreachable { status } else { SampleStatus::Limited };
            (status, max_step)
        } else {
            self.pose.copy_from_slice(&self.best);
            (status, largest)
        };
        self.count += 1;
        let (error, angle_error) = self.body.errors(&self.pose, goal);
        Step { status, error, angle_error, step }
    }

    /// Solves for `goal` from the current pose and, if that does not reach it, from seeded
    /// poses near it; leaves the best solution in `self.best` and returns its status.
    fn solve_near(&mut self, goal: &Goal) -> SampleStatus {
        let body = &mut self.body;
        let opts = &self.options;
        if body.solve_from(&mut self.solver, &self.pose, goal, &mut self.out).is_err() {
            // The body, pose and options were checked when the follower was built.
            self.best.copy_from_slice(&self.pose);
            return SampleStatus::Stalled;
        }
        self.best.copy_from_slice(self.out.pose.angles());
        let mut status = self.out.status;
        let tolerance = opts.solve.tolerance;
        if status == Status::Reached || body.out_of_reach(goal, tolerance) {
            return SampleStatus::from_solve(status);
        }
        let mut best_error = task_error(opts, &self.out);
        let (attempts, seed) = (opts.solve.restarts.map_or(0, |r| r.attempts), opts.seed());
        for k in 1..=attempts {
            let mut rng = SplitMix64(seed ^ self.count.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ u64::from(k) << 32);
            let bounds = body.track_bounds(&opts.solve);
            for (i, (s, &q)) in self.seed_pose.iter_mut().zip(&self.pose).enumerate() {
                *s = bounds.clamp(i, q + opts.radius * (2.0 * rng.unit() - 1.0));
            }
            if body.solve_from(&mut self.solver, &self.seed_pose, goal, &mut self.out).is_err() {
                break;
            }
            let error = task_error(opts, &self.out);
            if self.out.status == Status::Reached || error < best_error {
                best_error = error;
                status = self.out.status;
                self.best.copy_from_slice(self.out.pose.angles());
            }
            if status == Status::Reached {
                break;
            }
        }
        SampleStatus::from_solve(status)
    }
}

/// The squared task error of an outcome, as the solvers minimise it.
fn task_error(opts: &TrackOptions, out: &Outcome) -> f64 {
    out.error * out.error + math::square(opts.solve.orientation_weight * out.angle_error)
}

/// Tracks `path` online from `start` (radians): the first sample is solved from `start`
/// taking the solution nearest it (no step bound: placing the arm on the path), each later one
/// by [`Follower::step`]. No step after the first exceeds [`TrackOptions::max_step`], so a
/// follow has no flips.
pub fn follow(chain: &Chain, start: &[f64], path: &Path, options: &TrackOptions) -> Result<Track, TrackError> {
    follow_with(Follower::new(chain, start, options)?, path, options)
}

/// [`follow`] for one effector of a skeleton: the tip of `bone` follows `path` from `start`
/// (radians, one per bone), each sample solved from the previous pose, while the goals of
/// `task` hold and its pins stay where they are at `start` (see [`RigEffector`]). The same
/// method as a chain's: warm-started, restarts near the previous pose, no bone turning more
/// than [`TrackOptions::max_step`] per sample after the first. A sample's `error` is the
/// largest effector error, and its status the whole solve's.
///
/// # Errors
/// As [`follow`], and a task that does not fit the skeleton, or a method that solves chains
/// only ([`SolveError::ChainOnly`](crate::SolveError::ChainOnly)).
pub fn follow_rig(
    skeleton: &Skeleton,
    start: &[f64],
    bone: usize,
    task: &RigTask,
    path: &Path,
    options: &TrackOptions,
) -> Result<Track, TrackError> {
    follow_with(Follower::rig(skeleton, start, bone, task, options)?, path, options)
}

/// The samples of `path` followed by `follower`, from its pose.
fn follow_with<B: TrackBody>(
    mut follower: Follower<B>,
    path: &Path,
    options: &TrackOptions,
) -> Result<Track, TrackError> {
    let mut samples = Vec::with_capacity(path.len());
    for (k, goal) in path.goals().iter().enumerate() {
        if crate::interrupt::is_set(options.solve.interrupt.as_ref()) {
            return Err(TrackError::Interrupted);
        }
        let placed = k == 0 && !options.bound_first;
        let step = if placed { follower.place(goal) } else { follower.step(goal) };
        samples.push(TrackSample {
            goal: *goal,
            status: step.status,
            error: step.error,
            angle_error: step.angle_error,
            angles: follower.pose().to_vec(),
            step: if placed { 0.0 } else { step.step },
        });
    }
    Ok(Track::new(samples, follower.body.track_bounds(&options.solve), options.max_step))
}
