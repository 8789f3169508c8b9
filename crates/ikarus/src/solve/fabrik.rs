//! FABRIK, forward and backward reaching inverse kinematics (Aristidou & Lasenby 2011), in the
//! plane, with angular limits.
//!
//! FABRIK works on joint positions. The backward pass puts the end of the chain on the goal
//! and walks to the base, placing each joint at its link's length from the next one, on the
//! line to where that joint was. The forward pass pins the base back in place and walks to the
//! tip, placing each joint at its link's length from the previous one, on the line towards
//! where the backward pass put it. Positions are then turned back into relative angles.
//!
//! - **Limits.** In the forward pass, when clamping, the direction of link `i` relative to link
//!   `i − 1` (to +x for the first link) is held inside `[min_i, max_i]`: if no 2π-equivalent of
//!   it lies inside, it goes to the limit nearer around the circle, and the rest of the pass
//!   continues from the clamped link, so the angles are exactly the ones the pass used.
//! - **Goals out of reach** (farther from the base than the chain is long): the backward pass is
//!   skipped and every link points at the goal (the arm stretched towards it, when the limits
//!   allow).
//! - **Orientation goals**: the last link's direction is fixed to `φ_goal`, so FABRIK runs on
//!   the first `n − 1` links towards the wrist `target − l_n (cos φ, sin φ)`, and the last
//!   joint's angle is then set so that the last link points along `φ` (clamped into its limits
//!   when needed). [`SolveOptions::orientation_weight`] plays no part: the orientation is met
//!   exactly whenever the last joint's limits allow it. A single link has no wrist to move and
//!   just points at the target.
//! - **Angles.** Joints without limits (or when not clamping) take the 2π-equivalent nearest
//!   their previous angle, so they never jump by a whole turn; joints with limits take the one
//!   inside the limits, nearest the previous angle if several are.
//! - **Degenerate geometry.** Where a direction is undefined (two points closer than `1e-12` of
//!   the chain's reach), the link keeps the direction it had in the previous pose.

use nalgebra::{Point2, Vector2};

use super::problem::Problem;
use crate::angle;
use crate::chain::JointLimits;
use crate::kinematics::joint_positions_into;

/// Distances shorter than this share of the chain's reach count as zero.
const NEGLIGIBLE: f64 = 1e-12;

/// One FABRIK iteration (a backward pass from the goal and a forward pass from the base), then
/// conversion of the joint positions back to relative angles, each kept inside its bound in
/// `p.bounds` if any (FABRIK's angular constraint: in the forward pass, the direction of link i relative
/// to link i−1 (or to +x for the first link) is limited to [min_i, max_i]). Writes `trial` and
/// `trial_joints` (recomputed by forward kinematics from `trial`, so they are consistent),
/// returns the tip orientation.
///
/// `joints` must be the positions for `angles` (n+1). See the [module docs](self) for goals out
/// of reach, orientation goals and how angles are chosen. Allocates nothing: `trial_joints` is
/// the working buffer of the passes.
///
/// # Panics
/// If `angles` or `trial` do not hold `chain.len()` angles, or `joints` or `trial_joints` not
/// `chain.len() + 1` points.
pub(super) fn iterate(
    p: &Problem,
    angles: &[f64],
    joints: &[Point2<f64>],
    trial: &mut [f64],
    trial_joints: &mut [Point2<f64>],
) -> f64 {
    // FABRIK meets an orientation exactly through the last link; it has nothing to weigh, so
    // it reads no option.
    let (chain, goal, bounds) = (p.chain, p.goal, p.bounds);
    let n = chain.len();
    let lengths = chain.lengths();
    let base = chain.base();
    let tiny = NEGLIGIBLE * chain.max_reach();
    trial.copy_from_slice(angles);
    trial_joints.copy_from_slice(joints);

    // The links FABRIK moves, and where their end must go.
    let (m, end) = match goal.orientation() {
        Some(phi) if n > 1 => (n - 1, goal.target() - lengths[n - 1] * Vector2::new(phi.cos(), phi.sin())),
        _ => (n, goal.target()),
    };
    let reachable = (end - base).x.hypot((end - base).y) <= lengths[..m].iter().sum::<f64>();

    if reachable {
        // Backward pass: q_m = end, then each joint on the line to where it was.
        trial_joints[m] = end;
        for i in (0..m).rev() {
            let next = trial_joints[i + 1];
            let back = unit_or(trial_joints[i] - next, joints[i] - joints[i + 1], tiny);
            trial_joints[i] = next + lengths[i] * back;
        }
    }

    // Forward pass from the base, towards the backward pass's joints (or straight at the goal
    // when it is out of reach). Only angles are written; positions come from them below.
    let mut at = base;
    let mut direction = 0.0;
    for i in 0..m {
        let aim = if reachable { trial_joints[i + 1] } else { end };
        let d = unit_or(aim - at, joints[i + 1] - joints[i], tiny);
        let relative = pick(d.y.atan2(d.x) - direction, angles[i], bounds.get(i));
        trial[i] = relative;
        direction += relative;
        at += lengths[i] * Vector2::new(direction.cos(), direction.sin());
    }
    if let (true, Some(phi)) = (m < n, goal.orientation()) {
        trial[n - 1] = pick(phi - direction, angles[n - 1], bounds.get(n - 1));
    }
    joint_positions_into(chain, trial, trial_joints)
}

/// `v` normalised, or `fallback` normalised if `v` is shorter than `tiny`, or +x if both are.
/// Lengths by `hypot`, and vectors scaled down before normalising, so that points far apart
/// (up to the end of the f64 range) still give their direction.
fn unit_or(v: Vector2<f64>, fallback: Vector2<f64>, tiny: f64) -> Vector2<f64> {
    let unit = |v: Vector2<f64>| {
        let scaled = v / v.x.abs().max(v.y.abs());
        scaled / scaled.x.hypot(scaled.y)
    };
    if v.x.hypot(v.y) > tiny && v.iter().all(|c| c.is_finite()) {
        return unit(v);
    }
    if fallback.x.hypot(fallback.y) > 0.0 && fallback.iter().all(|c| c.is_finite()) {
        unit(fallback)
    } else {
        Vector2::new(1.0, 0.0)
    }
}

/// The joint angle for the relative direction `raw` (any 2π-equivalent): inside `limits` if
/// any (the equivalent inside nearest `previous`, or the limit nearer `raw` around the circle
/// if none is inside), else the equivalent nearest `previous`.
fn pick(raw: f64, previous: f64, limits: Option<JointLimits>) -> f64 {
    match limits {
        None => {
            let nearest = angle::nearest_equivalent(raw, previous);
            if nearest.is_finite() { nearest } else { raw }
        }
        // The equivalent is clamped onto the limits: the shift can round a hair past one.
        Some(lim) => lim.nearest_equivalent(raw, previous).unwrap_or_else(|| lim.nearer_end(raw)),
    }
}

#[cfg(test)]
mod tests {
    use std::f64::consts::{PI, TAU};

    use super::*;
    use crate::angle::wrap_angle;
    use crate::chain::{Chain, Link};
    use crate::closed_form;
    use crate::goal::Goal;
    use crate::kinematics::{end_effector, joint_positions};
    use crate::solve::SolveOptions;

    use crate::rng::SplitMix64;
    use crate::solve::test_support::{self, problem, random_chain, random_pose};

    /// Runs iterations (see [`test_support::drive`]) to `tol`.
    fn drive(chain: &Chain, goal: &Goal, clamp: bool, start: &[f64], max: usize, tol: f64) -> (Vec<f64>, usize, bool) {
        test_support::drive(iterate, &problem(chain, goal, &SolveOptions::default(), clamp), start, max, tol)
    }

    #[test]
    fn pick_chooses_the_equivalent_and_clamps_around_the_circle() {
        let lim = |a: f64, b: f64| Some(JointLimits::new(a, b).unwrap());
        // Free: nearest the previous angle.
        assert!((pick(0.5, 13.0, None) - (0.5 + 2.0 * TAU)).abs() < 1e-12);
        assert!((pick(0.5 + TAU, -0.2, None) - 0.5).abs() < 1e-12);
        // Limited: the equivalent inside, even far from [−π, π).
        assert!((pick(-0.5, 0.0, lim(5.0, 6.0)) - (TAU - 0.5)).abs() < 1e-12);
        // Several inside: nearest the previous angle.
        assert!((pick(0.5, 6.0, lim(-10.0, 10.0)) - (0.5 + TAU)).abs() < 1e-12);
        // None inside: the nearer limit around the circle. 3.0 is nearer −3.0 (0.28 apart
        // across ±π) than 1.0.
        assert_eq!(pick(3.0, 0.0, lim(-3.0, 1.0)), -3.0);
        assert_eq!(pick(1.5, 0.0, lim(-3.0, 1.0)), 1.0);
        assert_eq!(pick(-3.1 + TAU, 0.0, lim(-3.0, 1.0)), -3.0);
        // Huge numbers: finite.
        assert!(pick(1e300, -1e300, None).is_finite());
        assert!(lim(-1.0, 1.0).unwrap().contains(pick(1e300, -1e300, lim(-1.0, 1.0))));
    }

    /// Goals at the far ends of the f64 range leave every angle finite, and a far goal is
    /// still pointed at.
    #[test]
    fn extreme_goals_give_finite_angles() {
        let mut rng = SplitMix64(24);
        for limited in [false, true] {
            let chain = random_chain(&mut rng, 5, limited);
            for (x, y) in [(1e300, -1e300), (-1e-300, 1e-300), (1e154, 1e154), (f64::MAX, f64::MIN)] {
                for goal in [Goal::position(x, y).unwrap(), Goal::with_orientation(x, y, 1e10).unwrap()] {
                    let start = random_pose(&mut rng, &chain);
                    let (angles, _, _) = drive(&chain, &goal, true, &start, 20, 1e-6);
                    assert!(angles.iter().all(|a| a.is_finite()), "{goal:?}: {angles:?}");
                    if !limited && goal.orientation().is_none() && x.abs() > 1.0 {
                        let tip = end_effector(&chain, &angles).position - chain.base();
                        assert!(wrap_angle(tip.y.atan2(tip.x) - y.atan2(x)).abs() < 1e-12, "{goal:?}: {angles:?}");
                    }
                }
            }
        }
    }

    /// The joint positions are the forward kinematics of the angles, limits hold when clamping
    /// (even from outside), free joints move by at most half a turn, with an orientation goal
    /// a free last joint meets it exactly, and nothing is NaN.
    #[test]
    fn iterate_is_consistent() {
        let mut rng = SplitMix64(21);
        for case in 0..2000 {
            let n = 1 + (rng.next_u64() % 12) as usize;
            let limited = rng.chance(0.5);
            let chain = random_chain(&mut rng, n, limited);
            let clamp = rng.chance(0.8);
            let oriented = rng.chance(0.5);
            let target = chain.base() + Vector2::new(rng.range(-1.5, 1.5), rng.range(-1.5, 1.5)) * chain.max_reach();
            let goal = if oriented {
                Goal::with_orientation(target.x, target.y, rng.range(-10.0, 10.0)).unwrap()
            } else {
                Goal::position(target.x, target.y).unwrap()
            };
            let angles: Vec<f64> = if rng.chance(0.8) {
                random_pose(&mut rng, &chain)
            } else {
                (0..n).map(|_| rng.range(-20.0, 20.0)).collect()
            };
            let joints = joint_positions(&chain, &angles);
            let (mut trial, mut trial_joints) = (vec![0.0; n], vec![Point2::origin(); n + 1]);
            let opts = SolveOptions::default();
            let phi = iterate(&problem(&chain, &goal, &opts, clamp), &angles, &joints, &mut trial, &mut trial_joints);
            assert!(trial.iter().all(|a| a.is_finite()), "case {case}: {trial:?}");
            assert_eq!(joint_positions(&chain, &trial), trial_joints, "case {case}");
            assert_eq!(phi, end_effector(&chain, &trial).orientation);
            for ((new, old), lim) in trial.iter().zip(&angles).zip(chain.limits()) {
                match lim {
                    Some(l) if clamp => assert!(l.contains(*new), "case {case}: {new} outside {l:?}"),
                    _ => assert!((new - old).abs() <= PI + 1e-9, "case {case}: {old} -> {new}"),
                }
            }
            if let (Some(g), true) = (goal.orientation(), n > 1 && (!clamp || !limited)) {
                assert!(wrap_angle(phi - g).abs() < 1e-9, "case {case}: {phi} vs {g}");
            }
        }
    }

    /// See [`test_support::success_rates`].
    fn success_rates(limited: bool, oriented: bool, total: u32, floors: [f64; 3]) {
        test_support::success_rates("fabrik", iterate, 200, limited, oriented, total, floors);
    }

    /// Measured: 3 links 100%, 7 links 100%, 20 links 100% (mean 21, 4, 1 iterations).
    #[test]
    fn success_rate_free_position() {
        success_rates(false, false, 200, [0.97, 0.97, 0.97]);
    }

    /// Measured: 3 links 78%, 7 links 78%, 20 links 86% (mean 87, 25, 39 iterations). Limits
    /// applied in the forward pass only can hold the chain where the backward pass keeps
    /// undoing it.
    #[test]
    fn success_rate_limited_position() {
        success_rates(true, false, 200, [0.72, 0.72, 0.80]);
    }

    /// Measured: 3 links 97%, 7 links 100%, 20 links 100% (mean 86, 6, 1 iterations).
    #[test]
    fn success_rate_free_orientation() {
        success_rates(false, true, 200, [0.92, 0.97, 0.97]);
    }

    /// Measured: 3 links 79.5%, 7 links 51.5%, 20 links 48% (mean 136, 25, 26 iterations):
    /// with the last link fixed, the wrist must be reached by links whose limits the backward
    /// pass ignores.
    #[test]
    fn success_rate_limited_orientation() {
        success_rates(true, true, 200, [0.73, 0.45, 0.42]);
    }

    /// A goal out of reach: after one iteration the arm is stretched towards it, the tip on the
    /// segment from the base to the goal at distance `max_reach`. With an orientation whose
    /// wrist is out of reach, the other links stretch towards the wrist and the last link
    /// points along the orientation.
    #[test]
    fn stretches_towards_a_goal_out_of_reach() {
        let mut rng = SplitMix64(22);
        for _ in 0..200 {
            let n = 1 + (rng.next_u64() % 8) as usize;
            let chain = random_chain(&mut rng, n, false);
            let dir = rng.range(-PI, PI);
            let unit = Vector2::new(dir.cos(), dir.sin());
            let target = chain.base() + chain.max_reach() * rng.range(1.001, 3.0) * unit;
            let goal = Goal::position(target.x, target.y).unwrap();
            let start = random_pose(&mut rng, &chain);
            let (angles, _, ok) = drive(&chain, &goal, true, &start, 1, 1e-6);
            assert!(!ok);
            let tip = end_effector(&chain, &angles).position;
            let want = chain.base() + chain.max_reach() * unit;
            assert!((tip - want).norm() <= 1e-9, "{n} links: tip {tip}, want {want}");

            if n > 1 {
                let phi = rng.range(-PI, PI);
                let goal = Goal::with_orientation(target.x, target.y, phi).unwrap();
                let (angles, _, _) = drive(&chain, &goal, true, &start, 1, 1e-6);
                let joints = joint_positions(&chain, &angles);
                let last = chain.lengths()[n - 1];
                let wrist = target - last * Vector2::new(phi.cos(), phi.sin());
                let arm: f64 = chain.lengths()[..n - 1].iter().sum();
                if (wrist - chain.base()).norm() > arm {
                    let want = chain.base() + arm * (wrist - chain.base()).normalize();
                    assert!((joints[n - 1] - want).norm() <= 1e-9, "{n} links");
                }
                assert!(wrap_angle(angles.iter().sum::<f64>() - phi).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn target_at_the_base_and_single_links() {
        // Three equal links can reach their base; nothing is NaN along the way, also from a
        // straight arm, where every line to the goal runs along the arm.
        let chain = Chain::new([1.0, 2.0], &[Link::new(1.0, 0.1), Link::new(1.0, 0.2), Link::new(1.0, 0.3)]).unwrap();
        let goal = Goal::position(1.0, 2.0).unwrap();
        for start in [chain.start_pose().angles(), &[0.0; 3][..], &[0.0, PI, 0.0][..]] {
            let (angles, it, ok) = drive(&chain, &goal, true, start, 2000, 1e-6);
            assert!(angles.iter().all(|a| a.is_finite()), "{angles:?}");
            println!("fabrik, target at the base of 3 equal links from {start:?}: reached {ok} in {it}");
        }
        // A single link points at the target, whatever its distance, with or without an
        // orientation goal ...
        let one = Chain::new([0.0, 0.0], &[Link::new(2.0, 0.0)]).unwrap();
        for (x, y) in [(0.0, 5.0), (-0.5, 0.0), (1.0, 1.0)] {
            for goal in [Goal::position(x, y).unwrap(), Goal::with_orientation(x, y, 1.0).unwrap()] {
                let (angles, _, _) = drive(&one, &goal, true, &[0.0], 1, 1e-6);
                assert!(wrap_angle(angles[0] - y.atan2(x)).abs() < 1e-12, "{angles:?}");
            }
        }
        // ... and keeps its direction when the target is on the base.
        let (angles, _, _) = drive(&one, &Goal::position(0.0, 0.0).unwrap(), true, &[0.4], 3, 1e-6);
        assert!((angles[0] - 0.4).abs() < 1e-12, "{angles:?}");
        // Two links, target on the base with an orientation: the wrist is out of reach of the
        // first link unless the lengths match.
        let two = Chain::new([0.0, 0.0], &[Link::new(1.0, 0.0), Link::new(1.0, 0.0)]).unwrap();
        let goal = Goal::with_orientation(0.0, 0.0, 0.7).unwrap();
        let (angles, _, ok) = drive(&two, &goal, true, &[0.0, 0.0], 10, 1e-9);
        assert!(ok, "{angles:?}");
    }

    /// On two links FABRIK converges to one of the two closed-form solutions (mod 2π); on
    /// three links with an orientation goal, to one of the two oriented ones.
    #[test]
    fn agrees_with_the_closed_forms() {
        let mut rng = SplitMix64(23);
        let (mut checked, mut converged) = (0, 0);
        for case in 0..400 {
            let n = 2 + case % 2;
            let oriented = n == 3;
            let chain = random_chain(&mut rng, n, false);
            let truth = random_pose(&mut rng, &chain);
            if truth[1].sin().abs() < 0.2 {
                continue;
            }
            let ee = end_effector(&chain, &truth);
            let goal = if oriented {
                Goal::with_orientation(ee.position.x, ee.position.y, ee.orientation).unwrap()
            } else {
                Goal::position(ee.position.x, ee.position.y).unwrap()
            };
            checked += 1;
            let start = random_pose(&mut rng, &chain);
            let (angles, _, ok) = drive(&chain, &goal, true, &start, 20_000, 1e-11);
            if !ok {
                continue;
            }
            converged += 1;
            let rel = ee.position - chain.base();
            let l = chain.lengths();
            let solutions: Vec<Vec<f64>> = if oriented {
                closed_form::three_link_oriented([l[0], l[1], l[2]], rel, ee.orientation)
                    .unwrap()
                    .iter()
                    .map(|s| s.to_vec())
                    .collect()
            } else {
                closed_form::two_link(l[0], l[1], rel).unwrap().iter().map(|s| s.to_vec()).collect()
            };
            let matches = |s: &Vec<f64>| s.iter().zip(&angles).all(|(a, b)| wrap_angle(a - b).abs() <= 1e-6);
            assert!(solutions.iter().any(matches), "case {case}: {angles:?} vs {solutions:?}");
        }
        println!("fabrik vs closed forms: {converged} of {checked} converged to 1e-11");
        assert!(converged * 10 >= checked * 9, "{converged} of {checked}");
    }
}
