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
//!   when needed). [`SolveOptions::orientation_weight`](super::SolveOptions::orientation_weight)
//!   plays no part: the orientation is met exactly whenever the last joint's limits allow it. A
//!   single link has no wrist to move and just points at the target.
//! - **Angles.** Joints without limits (or when not clamping) take the 2π-equivalent nearest
//!   their previous angle, so they never jump by a whole turn; joints with limits take the one
//!   inside the limits, nearest the previous angle if several are.
//! - **Degenerate geometry.** Where a direction is undefined (two points closer than `1e-12` of
//!   the chain's reach), the link keeps the direction it had in the previous pose.

use nalgebra::{Point2, Vector2};

use super::model::Problem;
use crate::angle;
use crate::chain::JointLimits;
use crate::kinematics::joint_positions_into;
use crate::math;

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
    let (chain, goal, bounds) = (p.model, p.goal, p.bounds);
    let n = chain.len();
    let lengths = chain.lengths();
    let base = chain.base();
    let tiny = NEGLIGIBLE * chain.max_reach();
    trial.copy_from_slice(angles);
    trial_joints.copy_from_slice(joints);

    // The links FABRIK moves, and where their end must go.
    let (m, end) = match goal.orientation() {
        Some(phi) if n > 1 => (n - 1, goal.target() - lengths[n - 1] * Vector2::new(math::cos(phi), math::sin(phi))),
        _ => (n, goal.target()),
    };
    let reachable = math::hypot((end - base).x, (end - base).y) <= lengths[..m].iter().sum::<f64>();

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
        let relative = pick(math::atan2(d.y, d.x) - direction, angles[i], bounds.get(i));
        trial[i] = relative;
        direction += relative;
        at += lengths[i] * Vector2::new(math::cos(direction), math::sin(direction));
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
        scaled / math::hypot(scaled.x, scaled.y)
    };
    if math::hypot(v.x, v.y) > tiny && v.iter().all(|c| c.is_finite()) {
        return unit(v);
    }
    if math::hypot(fallback.x, fallback.y) > 0.0 && fallback.iter().all(|c| c.is_finite()) {
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

    /// Two links, target on the base with an orientation: the wrist is out of reach of the
    /// first link unless the lengths match; with equal lengths FABRIK gets there. (The other
    /// targets on the base, and single links, are in `ccd_fabrik_tests.rs`.)
    #[test]
    fn two_links_reach_their_base_with_an_orientation() {
        let two = Chain::new([0.0, 0.0], &[Link::new(1.0, 0.0), Link::new(1.0, 0.0)]).unwrap();
        let goal = Goal::with_orientation(0.0, 0.0, 0.7).unwrap();
        let (angles, _, ok) = drive(&two, &goal, true, &[0.0, 0.0], 10, 1e-9);
        assert!(ok, "{angles:?}");
    }
}
