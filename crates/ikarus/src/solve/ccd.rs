//! Cyclic coordinate descent (Wang & Chen 1991): turn one joint at a time, from the last to
//! the first, by the angle that is best for the goal with every other joint held still.
//!
//! Turning joint `j` by `δ` rotates the tip about the joint's position `p`. With the lever
//! `r_t = tip − p` and the goal lever `r_g = target − p`,
//!
//! ```text
//! |R(δ) r_t − r_g|² = |r_t|² + |r_g|² − 2A cos(δ − δ*),   A = |r_t| |r_g|,
//! δ* = atan2(r_t × r_g, r_t · r_g),
//! ```
//!
//! so the position-only optimum is `δ*`. With an orientation goal the tip's orientation error
//! after the turn is `wrap(δ − δ_o)`, `δ_o = wrap(φ_goal − φ_tip)`, and the joint minimises the
//! same cost the solvers measure, `|tip − target|² + w² wrap(δ − δ_o)²` (`w` =
//! [`SolveOptions::orientation_weight`](super::SolveOptions::orientation_weight)). Writing
//! `δ = δ_o + e` with `e ∈ [−π, π]`, `c = wrap(δ* − δ_o)` and `k = w²/A`, that is (up to a
//! constant and the factor `2A`)
//!
//! ```text
//! F(e) = −cos(e − c) + (k/2) e²,     F'(e) = sin(e − c) + k e.
//! ```
//!
//! **The global minimiser lies between 0 and `c` and is the only stationary point there.** Take
//! `c ≥ 0` (the other sign is the mirror image). For `e ∈ (c, π]`, `F(e) ≥ −1 + k e²/2 >
//! −1 + k c²/2 = F(c)`; for `e ∈ [−π, 0)`, `F(−e) − F(e) = −2 sin|e| sin c ≤ 0`. So the minimum
//! is in `[0, c]`, where `F'(0) = −sin c ≤ 0 ≤ k c = F'(c)` and `F'` is convex (`F''' =
//! −sin(e − c) ≥ 0` for `e − c ∈ [−π, 0]`): `F'` crosses zero once, upwards. The sweep finds that
//! root by Newton's method from the blend `e₀ = c / (1 + k)` (the minimiser of the quadratic
//! model `(e − c)²/2 + k e²/2`), safeguarded by bisection on the bracket `[0, c]`, which it keeps
//! up to date from the sign of `F'`; it stops when a step is below 4ε.
//!
//! **Limits.** When the joint's new angle must stay inside `[min, max]`, the allowed turns are
//! an interval; shorter than 2π, it is an arc of the circle of turns. The position cost alone
//! (and the orientation cost alone) has one minimum and one maximum on the circle and grows with
//! the circular distance from its minimum `μ`, so if no equivalent of `μ` is allowed, the best
//! allowed turn is the end of the arc nearer `μ` around the circle. The combined cost can have a
//! second local minimum: on `[−π, c − π]` (for `c ≥ 0`) `F'` is concave and `F'(c − π) ≤ 0`, so
//! there `F'` crosses zero upwards at most once, left of the maximum of `F'` at
//! `e = c − π − acos k`; `F` decreases on `[c − π, 0]` and increases on `[c, π]`, and the kink
//! at `e = ±π` (where the wrapped orientation error jumps sign) is never a minimum. The best
//! allowed turn is therefore one of: the global minimiser, the second minimiser if any, or an end
//! of the arc; the sweep evaluates the cost at those that are allowed and takes the lowest.
//!
//! Without limits the turn is wrapped into `[−π, π)`, so a free joint never moves by more than
//! half a turn in one sweep. Where a lever is shorter than `1e-12` of the chain's reach (the goal
//! on the joint, or the tip on the joint), the position cost does not depend on the turn: the
//! joint then only serves the orientation, or, without one, stays (or moves to the nearest
//! allowed angle if it starts outside its limits).
//!
//! Each joint's step lowers (never raises) the cost, so a sweep started inside the limits never
//! increases `|tip − target|² + w² wrap(φ_tip − φ_goal)²`.

use nalgebra::{Point2, Vector2};

use super::model::Problem;
use crate::angle::wrap_angle;
use crate::kinematics::joint_positions_into;
use crate::math;

mod turn;

use turn::best_angle;

/// Levers shorter than this share of the chain's reach count as zero.
const NEGLIGIBLE: f64 = 1e-12;

/// One CCD sweep, from the last joint to the first: each joint turns by the angle that best
/// brings the tip to the goal (and, with an orientation goal, minimises
/// `|tip − target|² + w²·(φ_tip − φ_goal)²` over that joint's rotation, `w =
/// opts.orientation_weight`, the orientation error wrapped into `[−π, π)`), kept inside its
/// bound in `p.bounds` if any (the best turn inside the limits, not the clamped best turn: see the
/// [module docs](self)). Writes the new angles into `trial` and their joint positions into
/// `trial_joints` (n+1 points), and returns the tip's absolute orientation.
///
/// `joints` must be the positions for `angles` (n+1). Within the sweep, the tip is updated by
/// turning it about each joint that turns; at the sweep's end every joint position is
/// recomputed by forward kinematics from `trial`, so that the loop judges the pose it returns.
/// Rotated points drift from it by about ε·reach per joint and sweep, which adds up: on a chain
/// of lengths from 1e-9 to 1e9 a solve reported `reached` 3.9e-6 away with a tolerance of 1e-6,
/// and its best pose was chosen on drifted errors. Allocates nothing.
///
/// # Panics
/// If `angles` or `trial` do not hold `chain.len()` angles, or `joints` or `trial_joints` not
/// `chain.len() + 1` points.
pub(super) fn sweep(
    p: &Problem,
    angles: &[f64],
    joints: &[Point2<f64>],
    trial: &mut [f64],
    trial_joints: &mut [Point2<f64>],
) -> f64 {
    let (chain, goal, opts) = (p.model, p.goal, p.opts);
    let n = chain.len();
    trial.copy_from_slice(angles);
    trial_joints.copy_from_slice(joints);
    let mut phi = angles.iter().fold(0.0, |sum, a| sum + a);
    let target = goal.target();
    let tiny = NEGLIGIBLE * chain.max_reach();
    let w2 = opts.orientation_weight * opts.orientation_weight;
    for j in (0..n).rev() {
        let at = trial_joints[j];
        let lever = trial_joints[n] - at;
        let to_goal = target - at;
        let turn = goal.orientation().map(|g| wrap_angle(g - phi));
        let limits = p.bounds.get(j);
        let old = trial[j];
        let new = best_angle(lever, to_goal, turn, w2, tiny, old, limits);
        let delta = new - old;
        trial[j] = new;
        if delta != 0.0 {
            // Only the tip is read again in this sweep (the joints below j do not move when j
            // turns, and those above it are not read): turn it about joint j.
            let (s, c) = math::sin_cos(delta);
            let v = trial_joints[n] - at;
            trial_joints[n] = at + Vector2::new(c * v.x - s * v.y, s * v.x + c * v.y);
            phi += delta;
        }
    }
    // Every joint afresh from the new angles: rotated points drift from the forward kinematics
    // by rounding, sweep after sweep.
    joint_positions_into(chain, trial, trial_joints)
}

#[cfg(test)]
mod tests {
    use std::f64::consts::PI;

    use super::*;
    use crate::chain::{Chain, Link};
    use crate::goal::Goal;
    use crate::kinematics::{end_effector, joint_positions, joint_positions_into};
    use crate::solve::SolveOptions;

    use crate::rng::SplitMix64;
    use crate::solve::test_support::{problem, random_chain, random_pose};

    /// The cost a sweep minimises.
    fn cost(chain: &Chain, goal: &Goal, w: f64, angles: &[f64]) -> f64 {
        let ee = end_effector(chain, angles);
        let turn = goal.orientation().map_or(0.0, |g| w * wrap_angle(ee.orientation - g));
        (ee.position - goal.target()).norm_squared() + turn * turn
    }

    /// The rotated joint positions are the forward kinematics of the new angles, the returned
    /// orientation is their sum, limits hold when clamping (even from outside), free joints
    /// move by at most half a turn, and the cost never rises from a pose inside the limits.
    #[test]
    fn sweep_is_consistent_and_monotone() {
        let mut rng = SplitMix64(13);
        for case in 0..2000 {
            let n = 1 + (rng.next_u64() % 12) as usize;
            let limited = rng.chance(0.5);
            let chain = random_chain(&mut rng, n, limited);
            let clamp = rng.chance(0.8);
            let oriented = rng.chance(0.5);
            let w = rng.range(0.1, 5.0);
            let opts = SolveOptions { orientation_weight: w, ..SolveOptions::default() };
            let target = chain.base() + Vector2::new(rng.range(-1.5, 1.5), rng.range(-1.5, 1.5)) * chain.max_reach();
            let goal = if oriented {
                Goal::with_orientation(target.x, target.y, rng.range(-10.0, 10.0)).unwrap()
            } else {
                Goal::position(target.x, target.y).unwrap()
            };
            let inside = rng.chance(0.8);
            let angles: Vec<f64> =
                if inside { random_pose(&mut rng, &chain) } else { (0..n).map(|_| rng.range(-7.0, 7.0)).collect() };
            let joints = joint_positions(&chain, &angles);
            let (mut trial, mut trial_joints) = (vec![0.0; n], vec![Point2::origin(); n + 1]);
            let phi = sweep(&problem(&chain, &goal, &opts, clamp), &angles, &joints, &mut trial, &mut trial_joints);
            let fk = joint_positions(&chain, &trial);
            let scale = chain.max_reach().max(1.0);
            for (a, b) in fk.iter().zip(&trial_joints) {
                assert!((a - b).norm() <= 1e-12 * scale, "case {case}: {a} vs {b}");
            }
            assert!((phi - trial.iter().sum::<f64>()).abs() <= 1e-12, "case {case}");
            for ((new, old), lim) in trial.iter().zip(&angles).zip(chain.limits()) {
                match lim {
                    Some(l) if clamp => assert!(l.contains(*new), "case {case}: {new} outside {l:?}"),
                    _ => assert!((new - old).abs() <= PI + 1e-12, "case {case}: {old} -> {new}"),
                }
            }
            if inside || !clamp {
                let (before, after) = (cost(&chain, &goal, w, &angles), cost(&chain, &goal, w, &trial));
                assert!(after <= before + 1e-12 * before.max(1.0), "case {case}: {before} -> {after}");
            }
        }
    }

    /// A single link with an orientation goal (w = 1) minimises the weighted cost in one
    /// sweep, and a second sweep changes nothing. Target (0, 2), φ_goal = 0: the cost is
    /// |2 (cos θ, sin θ) − (0, 2)|² + θ² = 8 − 8 sin θ + θ², stationary where −8 cos θ + 2θ = 0.
    /// (The position-only cases of single links are in `ccd_fabrik_tests.rs`.)
    #[test]
    fn single_link_meets_the_weighted_cost_in_one_sweep() {
        let opts = SolveOptions::default();
        let one = Chain::new([0.0, 0.0], &[Link::new(2.0, 0.0)]).unwrap();
        let goal = Goal::with_orientation(0.0, 2.0, 0.0).unwrap();
        let mut trial = [0.0];
        let mut trial_joints = [Point2::origin(); 2];
        let mut joints = [Point2::origin(); 2];
        joint_positions_into(&one, &[0.0], &mut joints);
        sweep(&problem(&one, &goal, &opts, true), &[0.0], &joints, &mut trial, &mut trial_joints);
        let a = trial[0];
        assert!((-8.0 * math::cos(a) + 2.0 * a).abs() < 1e-12 && a > 0.0 && a < PI / 2.0, "{a}");
        let before = trial;
        joint_positions_into(&one, &before, &mut joints);
        sweep(&problem(&one, &goal, &opts, true), &before, &joints, &mut trial, &mut trial_joints);
        assert!((trial[0] - before[0]).abs() < 1e-12);
    }

    /// Chained sweeps keep rotating the joint positions they are given; over many sweeps the
    /// rounding does not build up beyond a few ulps of reach per sweep.
    #[test]
    fn chained_sweeps_stay_close_to_forward_kinematics() {
        let mut rng = SplitMix64(16);
        let chain = random_chain(&mut rng, 20, false);
        let n = chain.len();
        let opts = SolveOptions::default();
        let mut angles = random_pose(&mut rng, &chain);
        let mut joints = joint_positions(&chain, &angles);
        let (mut trial, mut trial_joints) = (vec![0.0; n], vec![Point2::origin(); n + 1]);
        let mut worst: f64 = 0.0;
        for i in 0..1000 {
            // A new far-off goal every sweep keeps every joint turning.
            let a = f64::from(i) * 2.4;
            let goal = Goal::position(5.0 * math::cos(a), 5.0 * math::sin(a)).unwrap();
            sweep(&problem(&chain, &goal, &opts, true), &angles, &joints, &mut trial, &mut trial_joints);
            std::mem::swap(&mut angles, &mut trial);
            std::mem::swap(&mut joints, &mut trial_joints);
            let fk = joint_positions(&chain, &angles);
            worst = fk.iter().zip(&joints).fold(worst, |m, (a, b)| m.max((a - b).norm()));
        }
        println!("ccd: drift of rotated joints from FK after 1000 chained sweeps: {worst:e}");
        assert!(worst <= 1e-10 * chain.max_reach(), "{worst:e}");
    }
}
