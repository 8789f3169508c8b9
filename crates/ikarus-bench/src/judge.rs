//! How every solve is judged: from its final joint angles alone, by forward kinematics, with
//! the same function for ikarus and for KDL, so that no solver is taken at its word.

use std::f64::consts::TAU;

use ikarus::SolveOptions;
use ikarus::kinematics::end_effector;
use ikarus::solve::wrap_angle;

use super::sets::{BenchGoal, GoalSet, SetName};

/// Rounding slack added to the position and angle tolerances when judging: the solvers
/// compute the error with their own arithmetic, which may differ in the last bits.
const ROUNDING_SLACK: f64 = 1e-12;

/// A joint counts as inside its limits within this many radians of them.
const LIMIT_SLACK: f64 = 1e-9;

/// How one solve is judged.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Verdict {
    /// Whether the solve counts as reached (see [`judge`]).
    pub reached: bool,
    /// The position error: the tip's distance from the goal; for the `unreachable` set, its
    /// distance beyond the best possible one (the closest the arm can get).
    pub error: f64,
    /// The orientation error `|wrap(φ − φ_goal)|`, radians, for oriented sets.
    pub angle_error: Option<f64>,
}

/// Judges the final `angles` of a solve of `goal` from `set`, by forward kinematics.
///
/// Reached means: the position error is at most the tolerance; for oriented sets the
/// orientation error is at most the angle tolerance; for limits sets every limited joint is
/// inside its limits modulo 2π (`angle + 2πk ∈ [min − 1e-9, max + 1e-9]` for some `k`: a
/// solver that returns unwrapped angles is not penalised for it). For the `unreachable` set the
/// position error may exceed the tolerance by the distance from the goal to the closest point
/// the arm can reach (`|goal − base| − max_reach`, or `min_reach − |goal − base|` in the inner
/// hole). The tolerances get a slack of 1e-12 for rounding.
pub fn judge(set: &GoalSet, goal: &BenchGoal, angles: &[f64]) -> Verdict {
    let opts = SolveOptions::default();
    let chain = &set.chain;
    let tip = end_effector(chain, angles);
    let mut error = (tip.position.x - goal.x).hypot(tip.position.y - goal.y);
    if set.set == SetName::Unreachable {
        let d = (goal.x - chain.base().x).hypot(goal.y - chain.base().y);
        let best = (d - chain.max_reach()).max(chain.min_reach() - d).max(0.0);
        error -= best;
    }
    let mut reached = error <= opts.tolerance + ROUNDING_SLACK;
    let angle_error = set.set.oriented().then(|| wrap_angle(tip.orientation - goal.phi).abs());
    if let Some(a) = angle_error {
        reached &= a <= opts.angle_tolerance + ROUNDING_SLACK;
    }
    if set.set.limited() {
        reached &= angles.iter().zip(chain.limits()).all(|(&a, lim)| lim.is_none_or(|l| within(a, l.min(), l.max())));
    }
    Verdict { reached, error: if error.is_nan() { f64::INFINITY } else { error }, angle_error }
}

/// Whether `angle + 2πk` lies in `[min − slack, max + slack]` for some whole `k`.
pub(crate) fn within(angle: f64, min: f64, max: f64) -> bool {
    if !angle.is_finite() {
        return false;
    }
    let (lo, hi) = (min - LIMIT_SLACK, max + LIMIT_SLACK);
    let k = ((lo - angle) / TAU).ceil();
    // The neighbours too, in case the division rounded across a whole number.
    [k - 1.0, k, k + 1.0].iter().any(|k| (lo..=hi).contains(&(angle + k * TAU)))
}

#[cfg(test)]
mod tests {
    use std::f64::consts::PI;

    use ikarus::{Chain, Link};

    use super::*;
    use crate::sets::{ArmName, generate};

    fn seed_set(set: SetName) -> GoalSet {
        generate("seed", &ArmName::Seed.load().unwrap().chain, set, 20, 1)
    }

    /// A goal generated from `config` on the set's chain.
    fn goal_of(set: &GoalSet, config: &[f64]) -> BenchGoal {
        let tip = end_effector(&set.chain, config);
        BenchGoal { x: tip.position.x, y: tip.position.y, phi: wrap_angle(tip.orientation), config: config.to_vec() }
    }

    #[test]
    fn the_generating_configuration_reaches() {
        for kind in SetName::ALL.into_iter().filter(|&s| s != SetName::Unreachable) {
            let set = seed_set(kind);
            for g in &set.goals {
                let v = judge(&set, g, &g.config);
                assert!(v.reached, "{kind:?}: {v:?}");
                assert_eq!(v.error, 0.0);
                assert_eq!(v.angle_error.is_some(), kind.oriented());
            }
            // The start pose is somewhere else.
            let v = judge(&set, &set.goals[0], &set.start);
            assert!(!v.reached && v.error > 1e-3, "{v:?}");
        }
    }

    #[test]
    fn a_limit_broken_by_a_micro_radian_is_not_reached() {
        let set = seed_set(SetName::LimitsOriented);
        let max = set.chain.limits()[1].unwrap().max();
        let on_limit = [0.1, max, -0.2];
        let goal = goal_of(&set, &on_limit);
        assert!(judge(&set, &goal, &on_limit).reached);
        let beyond = [0.1, max + 1e-6, -0.2];
        let goal = goal_of(&set, &beyond);
        let v = judge(&set, &goal, &beyond);
        assert!(!v.reached, "{v:?}");
        assert!(v.error == 0.0 && v.angle_error.unwrap() < 1e-12, "only the limit is broken: {v:?}");
        // The same pose reaches on a set whose limits are off.
        let free = seed_set(SetName::FreeOriented);
        assert!(judge(&free, &goal, &beyond).reached);
        // The slack is a nanoradian.
        let min = set.chain.limits()[0].unwrap().min();
        let barely = [min - 1e-10, 0.3, 0.0];
        assert!(judge(&set, &goal_of(&set, &barely), &barely).reached);
    }

    #[test]
    fn a_limit_plus_a_turn_is_reached() {
        let set = seed_set(SetName::LimitsPosition);
        let (lo, hi) = (set.chain.limits()[0].unwrap().min(), set.chain.limits()[2].unwrap().max());
        let config = [lo, 0.5, hi];
        let goal = goal_of(&set, &config);
        for turned in [[lo + TAU, 0.5, hi], [lo, 0.5, hi + TAU], [lo - 2.0 * TAU, 0.5 + TAU, hi - TAU]] {
            let v = judge(&set, &goal, &turned);
            assert!(v.reached, "{turned:?}: {v:?}");
            assert!(v.error < 1e-12);
        }
        // Half a turn off is outside (joint 0 allows only ±45°).
        assert!(!judge(&set, &goal, &[lo + PI, 0.5, hi]).reached);
        assert!(!judge(&set, &goal, &[f64::NAN, 0.5, hi]).reached);
    }

    #[test]
    fn oriented_goals_need_the_orientation() {
        let set = seed_set(SetName::FreeOriented);
        let goal = goal_of(&set, &[0.3, 0.4, 0.5]);
        // Same tip position, other elbow: the orientation differs.
        let tip = end_effector(&set.chain, &[0.3, 0.4, 0.5]).position;
        let pos = seed_set(SetName::FreePosition);
        let mut other = [0.3, 0.4, 0.5 + 2e-6];
        assert!(!judge(&set, &goal, &other).reached);
        other[2] = 0.5 + 5e-7;
        let v = judge(&set, &goal, &other);
        assert!(v.angle_error.unwrap() < 1e-6 && v.error < 1e-6 && v.reached, "{v:?}");
        assert!(judge(&pos, &BenchGoal { x: tip.x, y: tip.y, phi: 3.0, config: vec![] }, &[0.3, 0.4, 0.5]).reached);
    }

    #[test]
    fn unreachable_goals_are_reached_by_the_best_pose() {
        let set = seed_set(SetName::Unreachable);
        let reach = set.chain.max_reach();
        let goal = BenchGoal { x: 1.5 * reach, y: 0.0, phi: 0.0, config: vec![] };
        let v = judge(&set, &goal, &[0.0, 0.0, 0.0]);
        assert!(v.reached && v.error.abs() < 1e-12, "{v:?}");
        let v = judge(&set, &goal, &[0.01, 0.0, 0.0]);
        assert!(!v.reached && v.error > 1e-4, "{v:?}");
        // Limits are off: a stretched arm pointing backwards is fine.
        let behind = BenchGoal { x: -1.5 * reach, y: 0.0, phi: PI, config: vec![] };
        assert!(judge(&set, &behind, &[PI, 0.0, 0.0]).reached);

        // The inner hole of a lopsided arm: the best pose folds back.
        let chain = Chain::new([0.0, 0.0], &[Link::new(5.0, 0.0), Link::new(1.0, 0.0)]).unwrap();
        let hole = generate("lopsided", &chain, SetName::Unreachable, 2, 1);
        let goal = BenchGoal { x: 1.0, y: 0.0, phi: 0.0, config: vec![] };
        let v = judge(&hole, &goal, &[0.0, PI]);
        assert!(v.reached && v.error.abs() < 1e-12, "{v:?}");
        assert!(!judge(&hole, &goal, &[0.0, PI - 0.01]).reached);
    }
}
