//! [`plan`]: a path tracked as one search over a ladder of candidate solutions (see the
//! [module docs](super) for the method).

use std::f64::consts::PI;

use nalgebra::Vector2;

use crate::chain::Chain;
use crate::closed_form;
use crate::goal::Goal;
use crate::kinematics::end_effector;
use crate::limits::Bounds;
use crate::math;
use crate::rng::SplitMix64;
use crate::solve::{Outcome, Solver, Status};

use super::bridge::{Bridged, bridge};
use super::{
    Path, SampleStatus, Track, TrackError, TrackOptions, TrackSample, bounds, is_flip, joint_delta, joint_distance2,
    joint_step, joint_step_and_distance2, unwrap_free,
};

/// The candidate solutions of one sample: `len()` poses of `n` angles each, flat.
#[derive(Debug, Clone, Default)]
struct Rung {
    angles: Vec<f64>,
    status: Vec<SampleStatus>,
}

impl Rung {
    fn len(&self) -> usize {
        self.status.len()
    }

    fn pose(&self, j: usize, n: usize) -> &[f64] {
        &self.angles[j * n..(j + 1) * n]
    }
}

/// What building the ladder borrows.
struct Builder<'a> {
    chain: &'a Chain,
    options: &'a TrackOptions,
    bounds: Bounds<'a>,
    solver: Solver,
    out: Outcome,
    seed_pose: Vec<f64>,
}

/// Tracks `path` offline from `start` (radians): the joint path through the candidates with
/// the least flip cost and then the least joint motion, polished, and its gaps over the bound
/// bridged off the path (see the [module docs](super)): no step exceeds
/// [`TrackOptions::max_step`].
///
/// The work is bounded: at most `candidates + seeds` solves per sample (`2·candidates` for the
/// first), `candidates²` transitions per sample in the search, and `polish_passes` solves per
/// sample in the polish, each solve under the solver's iteration cap, and at most
/// [`MAX_OFF_PATH_PER_SAMPLE`](super::MAX_OFF_PATH_PER_SAMPLE) off-path poses per sample.
///
/// # Errors
/// [`TrackError::OffPathCap`] when the bound is so small that the gaps would need more
/// off-path poses; the option and solver errors of [`TrackOptions::validate`].
pub fn plan(chain: &Chain, start: &[f64], path: &Path, options: &TrackOptions) -> Result<Track, TrackError> {
    let solver = options.solver(chain, start)?;
    let bounds = bounds(chain, &options.solve);
    let n = chain.len();
    let mut builder = Builder { chain, options, bounds, solver, out: Outcome::default(), seed_pose: vec![0.0; n] };
    let mut ladder: Vec<Rung> = Vec::with_capacity(path.len());
    let interrupted = || crate::interrupt::is_set(options.solve.interrupt.as_ref());
    for (k, goal) in path.goals().iter().enumerate() {
        if interrupted() {
            return Err(TrackError::Interrupted);
        }
        let rung = builder.rung(k, goal, ladder.last(), start);
        ladder.push(rung);
    }
    let chosen = search(&ladder, start, bounds, options.max_step, n);
    let mut poses: Vec<Vec<f64>> = chosen.iter().zip(&ladder).map(|(&j, r)| r.pose(j, n).to_vec()).collect();
    let mut status: Vec<SampleStatus> = chosen.iter().zip(&ladder).map(|(&j, r)| r.status[j]).collect();
    unwrap_path(bounds, &mut poses, start);
    for _ in 0..options.polish_passes {
        if interrupted() {
            return Err(TrackError::Interrupted);
        }
        builder.polish(path.goals(), &mut poses, &mut status);
    }
    unwrap_path(bounds, &mut poses, start);
    let bridged = bridge(poses, &status, bounds, options.max_step)?;
    let samples = samples(chain, path.goals(), bridged, bounds);
    Ok(Track::new(samples, bounds, options.max_step))
}

impl Builder<'_> {
    /// Candidates kept per sample: [`TrackOptions::candidates`], and at least one per joint.
    fn cap(&self) -> usize {
        self.options.candidates.max(self.chain.len())
    }

    /// The candidates of sample `k`: the closed form's branches, or the continuations of the
    /// previous sample's candidates (of `start` for the first) and seeded solves.
    fn rung(&mut self, k: usize, goal: &Goal, previous: Option<&Rung>, start: &[f64]) -> Rung {
        let n = self.chain.len();
        let mut rung = Rung::default();
        if self.options.solve.closed_form {
            self.closed_form_branches(goal, start, &mut rung);
            if rung.len() > 0 {
                return rung;
            }
        }
        match previous {
            None => self.solve_from(goal, start, &mut rung),
            Some(p) => {
                for j in 0..p.len() {
                    self.solve_from(goal, p.pose(j, n), &mut rung);
                }
            }
        }
        let cap = self.cap();
        let seeds = if k == 0 { cap } else { self.options.seeds };
        for j in 0..seeds {
            if reached(&rung) >= cap {
                break;
            }
            let mut pose = std::mem::take(&mut self.seed_pose);
            seeded_pose(self.bounds, start, self.options.seed(), k, j, &mut pose);
            self.solve_from(goal, &pose, &mut rung);
            self.seed_pose = pose;
        }
        keep_best(&mut rung, n, cap);
        if rung.len() == 0 {
            // Only a solver error (ruled out when the solver was built) leaves nothing.
            rung.angles.extend_from_slice(previous.map_or(start, |p| p.pose(0, n)));
            rung.status.push(SampleStatus::Stalled);
        }
        rung
    }

    /// Both exact solutions where the chain and goal have a closed form, each joint moved into
    /// its bound (a branch with no equivalent inside is dropped).
    fn closed_form_branches(&self, goal: &Goal, start: &[f64], rung: &mut Rung) {
        let chain = self.chain;
        let target: Vector2<f64> = goal.target() - chain.base();
        let l = chain.lengths();
        let branches: Vec<[f64; 3]> = match (l.len(), goal.orientation()) {
            (2, None) => closed_form::two_link(l[0], l[1], target)
                .map(|b| b.iter().map(|&[a, c]| [a, c, 0.0]).collect())
                .unwrap_or_default(),
            (3, Some(phi)) => {
                closed_form::three_link_oriented([l[0], l[1], l[2]], target, phi).map(Vec::from).unwrap_or_default()
            }
            _ => Vec::new(),
        };
        let n = l.len();
        for b in branches {
            let mut pose = [0.0; 3];
            let inside = (0..n).all(|i| match self.bounds.get(i) {
                Some(lim) => lim.nearest_equivalent(b[i], start[i]).map(|a| pose[i] = a).is_some(),
                None => {
                    pose[i] = b[i];
                    true
                }
            });
            if inside {
                self.push(rung, &pose[..n], SampleStatus::Reached);
            }
        }
    }

    /// Solves for `goal` from `from` and adds the result to `rung`.
    fn solve_from(&mut self, goal: &Goal, from: &[f64], rung: &mut Rung) {
        if self.solver.solve_into(self.chain, from, goal, &mut self.out).is_ok() {
            let status = SampleStatus::from_solve(self.out.status);
            let out = std::mem::take(&mut self.out);
            self.push(rung, out.pose.angles(), status);
            self.out = out;
        }
    }

    /// Adds `pose` to `rung` unless a candidate as good lies within `max_step / 4` of it
    /// (a reached pose replaces an unreached one there).
    fn push(&self, rung: &mut Rung, pose: &[f64], status: SampleStatus) {
        let n = pose.len();
        let near = self.options.max_step / 4.0;
        for j in 0..rung.len() {
            if joint_step(self.bounds, rung.pose(j, n), pose) < near {
                if status == SampleStatus::Reached && rung.status[j] != SampleStatus::Reached {
                    rung.angles[j * n..(j + 1) * n].copy_from_slice(pose);
                    rung.status[j] = status;
                }
                return;
            }
        }
        rung.angles.extend_from_slice(pose);
        rung.status.push(status);
    }

    /// One smoothing pass: each reached sample with a predecessor and a successor on the path
    /// re-solved from the midpoint of its neighbours, kept if it reaches the goal, adds no flip
    /// and lowers the local motion. The first sample stays the search's choice: pulling it
    /// toward the start pose (which is not on the path) would only steepen the path's first
    /// steps.
    fn polish(&mut self, goals: &[Goal], poses: &mut [Vec<f64>], status: &mut [SampleStatus]) {
        let (bounds, max_step) = (self.bounds, self.options.max_step);
        let local = |prev: &[f64], q: &[f64], next: &[f64]| {
            let flips =
                flip_cost(joint_step(bounds, q, prev), max_step) + flip_cost(joint_step(bounds, next, q), max_step);
            (flips, joint_distance2(bounds, q, prev) + joint_distance2(bounds, next, q))
        };
        for k in 1..poses.len().saturating_sub(1) {
            if status[k] != SampleStatus::Reached {
                continue;
            }
            let (prev, next) = (&poses[k - 1], &poses[k + 1]);
            let mut seed = std::mem::take(&mut self.seed_pose);
            for (i, s) in seed.iter_mut().enumerate() {
                *s = prev[i] + 0.5 * joint_delta(bounds, i, next[i], prev[i]);
            }
            let solved = self.solver.solve_into(self.chain, &seed, &goals[k], &mut self.out).is_ok();
            self.seed_pose = seed;
            if !solved || self.out.status != Status::Reached {
                continue;
            }
            let mut candidate = self.out.pose.angles().to_vec();
            unwrap_free(bounds, &mut candidate, &poses[k]);
            let (old_flips, old_motion) = local(&poses[k - 1], &poses[k], &poses[k + 1]);
            let (new_flips, new_motion) = local(&poses[k - 1], &candidate, &poses[k + 1]);
            if new_flips <= old_flips && new_motion < old_motion {
                poses[k] = candidate;
            }
        }
    }
}

/// What a step of `step` radians costs the search under the flip bound `max_step`: 0 unless
/// it is a flip ([`is_flip`]), else `(step − max_step)²`. A path with no flip always wins; among
/// paths that must exceed the bound (a path sampled too coarsely for it, or one that leaves what
/// the arm can follow), many steps a little over the bound cost less than one branch jump of
/// half a turn, which counting flips alone would prefer.
pub(super) fn flip_cost(step: f64, max_step: f64) -> f64 {
    if is_flip(step, max_step) { math::square(step - max_step) } else { 0.0 }
}

/// How many candidates of `rung` reach their goal.
fn reached(rung: &Rung) -> usize {
    rung.status.iter().filter(|&&s| s == SampleStatus::Reached).count()
}

/// Keeps only the reached candidates when there are any, and at most `cap`, in order.
fn keep_best(rung: &mut Rung, n: usize, cap: usize) {
    let any = reached(rung) > 0;
    let old = std::mem::take(rung);
    for j in 0..old.len() {
        if rung.len() < cap && (!any || old.status[j] == SampleStatus::Reached) {
            rung.angles.extend_from_slice(old.pose(j, n));
            rung.status.push(old.status[j]);
        }
    }
}

/// Seeded pose `j` of sample `k`: uniform inside each joint's bound, within ±π of the start
/// angle for a free joint.
fn seeded_pose(bounds: Bounds<'_>, start: &[f64], seed: u64, k: usize, j: usize, out: &mut [f64]) {
    let mut rng = SplitMix64(seed ^ (k as u64).wrapping_mul(0xA076_1D64_78BD_642F) ^ ((j as u64 + 1) << 40));
    for (i, (o, &a)) in out.iter_mut().zip(start).enumerate() {
        *o = match bounds.get(i) {
            Some(lim) => rng.range(lim.min(), lim.max()),
            None => rng.range(a - PI, a + PI),
        };
    }
}

/// The candidate index per sample of the path through `ladder` with the least flip cost
/// ([`flip_cost`]: no flip costs 0, and a branch jump costs far more than a step just over the
/// bound), then the least `Σ‖Δq‖²`, counting the move from `start` to the first sample as
/// motion but never as a flip; ties go to the lower index.
fn search(ladder: &[Rung], start: &[f64], bounds: Bounds<'_>, max_step: f64, n: usize) -> Vec<usize> {
    let better = |a: (f64, f64), b: (f64, f64)| a.0 < b.0 || (a.0 == b.0 && a.1 < b.1);
    let mut parents: Vec<Vec<usize>> = Vec::with_capacity(ladder.len());
    let mut cost: Vec<(f64, f64)> = Vec::new();
    for (k, rung) in ladder.iter().enumerate() {
        let mut next = Vec::with_capacity(rung.len());
        let mut parent = Vec::with_capacity(rung.len());
        for j in 0..rung.len() {
            let q = rung.pose(j, n);
            if k == 0 {
                next.push((0.0, joint_distance2(bounds, q, start)));
                parent.push(0);
                continue;
            }
            let prev = &ladder[k - 1];
            let mut best = (f64::INFINITY, f64::INFINITY);
            let mut from = 0;
            for (i, &(flips, motion)) in cost.iter().enumerate() {
                let (step, distance2) = joint_step_and_distance2(bounds, q, prev.pose(i, n));
                let c = (flips + flip_cost(step, max_step), motion + distance2);
                if better(c, best) {
                    (best, from) = (c, i);
                }
            }
            next.push(best);
            parent.push(from);
        }
        cost = next;
        parents.push(parent);
    }
    let mut j = (0..cost.len()).fold(0, |b, j| if better(cost[j], cost[b]) { j } else { b });
    let mut chosen = vec![0; ladder.len()];
    for k in (0..ladder.len()).rev() {
        chosen[k] = j;
        j = parents[k][j];
    }
    chosen
}

/// Unwraps the free joints along the path: each pose nearest the one before (the first
/// nearest `start`).
fn unwrap_path(bounds: Bounds<'_>, poses: &mut [Vec<f64>], start: &[f64]) {
    for k in 0..poses.len() {
        let (before, rest) = poses.split_at_mut(k);
        let reference: &[f64] = before.last().map_or(start, Vec::as_slice);
        unwrap_free(bounds, &mut rest[0], reference);
    }
}

/// The samples of the chosen poses (and the off-path ones between them): errors by forward
/// kinematics, steps from the previous.
fn samples(chain: &Chain, goals: &[Goal], bridged: Bridged, bounds: Bounds<'_>) -> Vec<TrackSample> {
    let Bridged { poses, status, goal: goal_of } = bridged;
    let mut out: Vec<TrackSample> = Vec::with_capacity(poses.len());
    for (k, angles) in poses.into_iter().enumerate() {
        let tip = end_effector(chain, &angles);
        let goal = goals[goal_of[k]];
        let step = out.last().map_or(0.0, |p| joint_step(bounds, &angles, &p.angles));
        out.push(TrackSample {
            goal,
            status: status[k],
            error: math::distance_between(tip.position, goal.target()),
            angle_error: goal.orientation().map_or(0.0, |g| crate::angle::wrap_angle(g - tip.orientation).abs()),
            angles,
            step,
        });
    }
    out
}
