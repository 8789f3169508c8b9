//! Closed-form inverse kinematics for the two shapes that have one: a two-link chain with a
//! position goal, and a three-link chain with a position and orientation goal.
//!
//! Used as ground truth in tests and as a fast path before the iterative solvers.
//!
//! For two links of lengths `l₁`, `l₂` and a target `(x, y)` relative to the base at distance
//! `d`, the law of cosines gives the elbow angle and the shoulder follows from it:
//!
//! ```text
//! cos θ₂ = (d² − l₁² − l₂²) / (2 l₁ l₂),        θ₂ = ± acos(cos θ₂),
//! θ₁ = atan2(y, x) − atan2(l₂ sin θ₂, l₁ + l₂ cos θ₂).
//! ```
//!
//! The first solution is the one with the counter-clockwise elbow, `θ₂ ≥ 0`; the second has
//! `θ₂ ≤ 0`. On the boundary of the reachable annulus (`d = l₁ + l₂` or `d = |l₁ − l₂|`) they
//! coincide. With an orientation `φ` for the last of three links, the wrist
//! `target − l₃ (cos φ, sin φ)` is solved as a two-link target and `θ₃ = φ − θ₁ − θ₂`.
//!
//! Every function takes and returns radians; angles relative to the previous link, as in the
//! rest of the crate. Nothing here allocates or panics on finite input.

use nalgebra::Vector2;

use crate::angle::{self, wrap_angle};
use crate::chain::{Chain, JointLimits};
use crate::goal::Goal;
use crate::limits::Bounds;
use crate::math;

/// Relative slack allowed on the boundary of the reachable annulus, as a share of `l₁ + l₂`.
const BOUNDARY_SLACK: f64 = 1e-12;

/// How far, in radians, an exact solution may lie outside a joint's limits and still count as
/// inside (it is then clamped onto the limit): rounding in the formulas is far below this.
const LIMIT_SLACK: f64 = 1e-12;

/// Both solutions of a two-link chain with link lengths `l1`, `l2` whose tip reaches `target`
/// (relative to the chain's base), as `[θ₁, θ₂]` pairs, or `None` if `|target|` lies outside
/// `[|l1 − l2|, l1 + l2]` by more than `1e-12 · (l1 + l2)`.
///
/// The first solution has the counter-clockwise elbow (`θ₂ ∈ [0, π]`), the second the clockwise
/// one (`θ₂ ∈ [−π, 0]`); `θ₁` is wrapped into `[−π, π)`. On the boundary the two coincide (up
/// to the sign of a `θ₂` of ±π, the same pose). When the target is at the base and `l1 = l2`,
/// every `θ₁` works; the one returned is finite. Returns `None` too if either length is not
/// a finite number `> 0` or the target is not finite.
#[must_use]
pub fn two_link(l1: f64, l2: f64, target: Vector2<f64>) -> Option<[[f64; 2]; 2]> {
    if !(l1.is_finite() && l2.is_finite() && l1 > 0.0 && l2 > 0.0 && target.x.is_finite() && target.y.is_finite()) {
        return None;
    }
    let d = math::hypot(target.x, target.y);
    let slack = BOUNDARY_SLACK * (l1 + l2);
    if d > l1 + l2 + slack || d < (l1 - l2).abs() - slack {
        return None;
    }
    // θ₂ by its half angle: tan²(θ₂/2) = (1 − cos θ₂)/(1 + cos θ₂), with both factored so that
    // each is accurate where it is small (1 − cos θ₂ ∝ (L − d)(L + d), 1 + cos θ₂ ∝
    // (d − Δ)(d + Δ), L = l₁ + l₂, Δ = |l₁ − l₂|). Then the exact tip of the computed angles is
    // within a few ulps of reach of the target, also when d is tiny (an `acos` of the cosine
    // would be off by ε·reach²/d there). Lengths are scaled by L so nothing overflows.
    let total = l1 + l2;
    let (u, v) = (d / total, (l1 - l2).abs() / total);
    let outer = ((1.0 - u) * (1.0 + u)).max(0.0);
    let inner = ((u - v) * (u + v)).max(0.0);
    let theta2 = 2.0 * math::atan2(outer.sqrt(), inner.sqrt());
    let towards = math::atan2(target.y, target.x);
    let solve = |t2: f64| {
        let (s, c) = math::sin_cos(t2);
        let t1 = wrap_angle(towards - math::atan2(l2 * s, l1 + l2 * c));
        [t1, t2]
    };
    Some([solve(theta2), solve(-theta2)])
}

/// Both solutions of a three-link chain (link lengths `lengths`) whose tip reaches `target`
/// (relative to the chain's base) with the last link at absolute orientation `phi`, as
/// `[θ₁, θ₂, θ₃]` triples, or `None` if the wrist `target − l₃ (cos φ, sin φ)` is out of reach
/// of the first two links (see [`two_link`]).
///
/// The wrist is solved by [`two_link`] (same order: counter-clockwise elbow `θ₂ ≥ 0` first) and
/// `θ₃ = φ − θ₁ − θ₂`, wrapped into `[−π, π)`.
#[must_use]
pub fn three_link_oriented(lengths: [f64; 3], target: Vector2<f64>, phi: f64) -> Option<[[f64; 3]; 2]> {
    let [l1, l2, l3] = lengths;
    if !(phi.is_finite() && l3.is_finite() && l3 > 0.0) {
        return None;
    }
    let wrist = target - l3 * Vector2::new(math::cos(phi), math::sin(phi));
    let both = two_link(l1, l2, wrist)?;
    Some(both.map(|[t1, t2]| [t1, t2, wrap_angle(phi - t1 - t2)]))
}

/// What [`solve`] did.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ClosedForm {
    /// The chain and goal have no closed form here: not 2 links with a position goal nor 3
    /// links with an orientation goal (or the slices have the wrong length).
    NotApplicable,
    /// The shape fits but the goal is out of reach, even ignoring limits.
    OutOfReach,
    /// Every exact solution breaks a joint limit.
    OutsideLimits,
    /// `out` holds the solution.
    Solved,
}

/// The closed-form fast path.
///
/// If `chain` has 2 links and `goal` no orientation, or 3 links and `goal` an orientation,
/// writes into `out` the exact solution nearest `start` and returns [`ClosedForm::Solved`].
///
/// Each angle of each exact solution is first moved by a multiple of 2π: for a joint without
/// a bound in `bounds` to the equivalent nearest its start angle; for a joint with a bound,
/// to the equivalent inside the bound
/// nearest the start angle (a solution within 1e-12 rad of a limit counts as inside and is
/// clamped onto it). A solution with a limited joint that has no equivalent inside is dropped.
/// Of the remaining solutions the one with the smallest sum of squared differences from `start`
/// wins; on a tie, the counter-clockwise elbow.
///
/// `out` is written only when the result is [`ClosedForm::Solved`]. Returns
/// [`ClosedForm::NotApplicable`] for other shapes, and also when `start` or `out` do not hold
/// one angle per joint.
pub fn solve(chain: &Chain, goal: &Goal, start: &[f64], bounds: Bounds<'_>, out: &mut [f64]) -> ClosedForm {
    let n = chain.len();
    if start.len() != n || out.len() != n {
        return ClosedForm::NotApplicable;
    }
    let target = goal.target() - chain.base();
    let lengths = chain.lengths();
    let mut solutions = [[0.0; 3]; 2];
    let found = match (n, goal.orientation()) {
        (2, None) => two_link(lengths[0], lengths[1], target).map(|both| {
            for (dst, [t1, t2]) in solutions.iter_mut().zip(both) {
                *dst = [t1, t2, 0.0];
            }
        }),
        (3, Some(phi)) => three_link_oriented([lengths[0], lengths[1], lengths[2]], target, phi).map(|both| {
            solutions = both;
        }),
        _ => return ClosedForm::NotApplicable,
    };
    if found.is_none() {
        return ClosedForm::OutOfReach;
    }

    let mut best: Option<(f64, usize)> = None;
    for (index, solution) in solutions.iter_mut().enumerate() {
        let mut distance = 0.0;
        let mut allowed = true;
        for (i, (angle, &from)) in solution[..n].iter_mut().zip(start).enumerate() {
            match nearest_equivalent(*angle, from, bounds.get(i)) {
                Some(a) => {
                    distance += (a - from) * (a - from);
                    *angle = a;
                }
                None => allowed = false,
            }
        }
        if allowed && best.is_none_or(|(d, _)| distance < d) {
            best = Some((distance, index));
        }
    }
    match best {
        Some((_, index)) => {
            out.copy_from_slice(&solutions[index][..n]);
            ClosedForm::Solved
        }
        None => ClosedForm::OutsideLimits,
    }
}

/// `angle + 2πk` nearest `from`, restricted to `limit` (with [`LIMIT_SLACK`], then clamped onto
/// it) when there is one; `None` if no equivalent lies inside the limit.
fn nearest_equivalent(angle: f64, from: f64, limit: Option<JointLimits>) -> Option<f64> {
    let shifted = match limit {
        Some(lim) => angle::nearest_equivalent_in(angle, from, lim.min() - LIMIT_SLACK, lim.max() + LIMIT_SLACK)?,
        None => angle::nearest_equivalent(angle, from),
    };
    // Only a start angle near the end of the f64 range can push the shift out of range.
    let shifted = if shifted.is_finite() { shifted } else { angle };
    Some(match limit {
        Some(lim) => lim.clamp(shifted),
        None => shifted,
    })
}

#[cfg(test)]
mod tests {
    use std::f64::consts::{PI, TAU};

    use super::*;
    use crate::chain::Link;
    use crate::kinematics::end_effector;

    use crate::rng::SplitMix64;

    fn tip2(l1: f64, l2: f64, [t1, t2]: [f64; 2]) -> Vector2<f64> {
        Vector2::new(l1 * math::cos(t1) + l2 * math::cos(t1 + t2), l1 * math::sin(t1) + l2 * math::sin(t1 + t2))
    }

    fn chain(lengths: &[f64], limits: &[Option<(f64, f64)>]) -> Chain {
        let links: Vec<Link> = lengths
            .iter()
            .zip(limits)
            .map(|(&l, lim)| match lim {
                Some((a, b)) => Link::new(l, (a + b) / 2.0).with_limits(JointLimits::new(*a, *b).unwrap()),
                None => Link::new(l, 0.0),
            })
            .collect();
        Chain::new([0.5, -1.0], &links).unwrap()
    }

    #[test]
    fn two_link_hits_random_targets_with_two_distinct_solutions() {
        let mut rng = SplitMix64(1);
        for _ in 0..5000 {
            let (l1, l2) = (rng.range(0.1, 5.0), rng.range(0.1, 5.0));
            let reach = l1 + l2;
            // Uniform in the annulus's radius, a few exactly on its edges.
            let (inner, outer) = ((l1 - l2).abs(), l1 + l2);
            let d = match rng.next_u64() % 20 {
                0 => inner,
                1 => outer,
                _ => rng.range(inner, outer),
            };
            let a = rng.range(-PI, PI);
            let target = Vector2::new(d * math::cos(a), d * math::sin(a));
            let both = two_link(l1, l2, target).expect("inside the annulus");
            for s in both {
                assert!(s.iter().all(|x| x.is_finite()));
                let miss = (tip2(l1, l2, s) - target).norm();
                assert!(miss <= 1e-12 * reach, "{l1} {l2} {target:?} {s:?}: miss {miss:e}");
            }
            assert!(both[0][1] >= 0.0 && both[1][1] <= 0.0, "{both:?}");
            // Away from the boundary the elbows differ by 2·acos(·), well above rounding.
            let margin = (d - inner).min(outer - d) / reach;
            if margin > 1e-3 {
                assert!(both[0][1] - both[1][1] > 1e-3, "{both:?}");
            }
        }
    }

    #[test]
    fn two_link_on_the_boundary_and_at_the_centre() {
        // Stretched: θ₂ = 0 twice, θ₁ along the target.
        let both = two_link(3.0, 2.0, Vector2::new(0.0, 5.0)).unwrap();
        for [t1, t2] in both {
            assert!((t1 - PI / 2.0).abs() < 1e-12 && t2.abs() < 1e-12, "{both:?}");
        }
        // Folded: θ₂ = ±π, the same pose.
        let both = two_link(3.0, 2.0, Vector2::new(-1.0, 0.0)).unwrap();
        for s in both {
            assert!((s[1].abs() - PI).abs() < 1e-12 && (tip2(3.0, 2.0, s) - Vector2::new(-1.0, 0.0)).norm() < 1e-12);
        }
        // Slightly past the edge but within the relative slack still counts, and gives the edge.
        let both = two_link(3.0, 2.0, Vector2::new(5.0 * (1.0 + 5e-13), 0.0)).unwrap();
        assert!(both.iter().all(|s| s[0].abs() < 1e-6 && s[1].abs() < 1e-6), "{both:?}");
        assert!(two_link(3.0, 2.0, Vector2::new(5.0 * (1.0 + 1e-11), 0.0)).is_none());
        assert!(two_link(3.0, 2.0, Vector2::new(0.99, 0.0)).is_none());
        // Equal links, target at the base: any θ₁ works, θ₂ = ±π; no NaN.
        for l in [1.0, 1e-9, 1e9] {
            let both = two_link(l, l, Vector2::zeros()).unwrap();
            for s in both {
                assert!(s.iter().all(|x| x.is_finite()), "{both:?}");
                assert!((s[1].abs() - PI).abs() < 1e-12);
                assert!(tip2(l, l, s).norm() <= 1e-12 * l, "{s:?}");
            }
        }
        // Bad input gives None, not NaN.
        assert!(two_link(0.0, 1.0, Vector2::new(1.0, 0.0)).is_none());
        assert!(two_link(1.0, 1.0, Vector2::new(f64::NAN, 0.0)).is_none());
    }

    /// Nearly equal links and a target near the base: the elbow is nearly folded, where an
    /// `acos` of the law-of-cosines cosine misses by about ε·reach²/d (here ~1e-9).
    #[test]
    fn two_link_is_accurate_near_the_centre() {
        let mut rng = SplitMix64(5);
        for _ in 0..2000 {
            let l1 = rng.range(0.5, 2.0);
            let l2 = l1 * (1.0 + rng.range(-1e-6, 1e-6));
            let d = (l1 - l2).abs() + rng.range(0.0, 2e-6) * l1;
            let a = rng.range(-PI, PI);
            let target = Vector2::new(d * math::cos(a), d * math::sin(a));
            for s in two_link(l1, l2, target).unwrap() {
                let miss = (tip2(l1, l2, s) - target).norm();
                assert!(miss <= 1e-12 * (l1 + l2), "{l1} {l2} {d:e}: miss {miss:e}");
            }
        }
    }

    #[test]
    fn three_link_hits_target_and_orientation() {
        let mut rng = SplitMix64(2);
        let mut solved = 0;
        for _ in 0..4000 {
            let lengths = [rng.range(0.1, 4.0), rng.range(0.1, 4.0), rng.range(0.1, 4.0)];
            let c = Chain::new([0.0, 0.0], &lengths.map(|l| Link::new(l, 0.0))).unwrap();
            let truth = [rng.range(-PI, PI), rng.range(-PI, PI), rng.range(-PI, PI)];
            let ee = end_effector(&c, &truth);
            let target = ee.position.coords;
            let phi = ee.orientation + TAU * rng.range(-2.0, 2.0).round();
            // A pose's own tip is always reachable (up to the boundary slack).
            let Some(both) = three_link_oriented(lengths, target, phi) else {
                panic!("{lengths:?} {truth:?}: a reachable pose was reported out of reach");
            };
            solved += 1;
            for s in both {
                let got = end_effector(&c, &s);
                let reach = c.max_reach();
                assert!((got.position.coords - target).norm() <= 1e-12 * reach, "{s:?}");
                assert!(wrap_angle(got.orientation - phi).abs() <= 1e-12, "{s:?}");
                assert!(s.iter().all(|a| (-PI..PI).contains(a)));
            }
        }
        assert_eq!(solved, 4000);
        let far = Vector2::new(10.0, 0.0);
        assert!(three_link_oriented([1.0, 1.0, 1.0], far, 0.0).is_none());
        assert!(three_link_oriented([1.0, 1.0, 1.0], Vector2::new(3.0, 0.0), 0.0).is_some());
        assert!(three_link_oriented([1.0, 1.0, 1.0], Vector2::new(3.0, 0.0), 0.1).is_none());
    }

    #[test]
    fn solve_picks_the_equivalent_nearest_the_start() {
        let c = chain(&[2.0, 1.5], &[None, None]);
        let goal = Goal::position(0.5 + 1.0, -1.0 + 2.0).unwrap();
        let both = two_link(2.0, 1.5, Vector2::new(1.0, 2.0)).unwrap();
        let mut out = [0.0; 2];
        // Start near the clockwise solution shifted by whole turns.
        let start = [both[1][0] + 2.0 * TAU + 0.1, both[1][1] - TAU - 0.2];
        assert_eq!(solve(&c, &goal, &start, c.bounds(), &mut out), ClosedForm::Solved);
        assert!((out[0] - (both[1][0] + 2.0 * TAU)).abs() < 1e-12, "{out:?}");
        assert!((out[1] - (both[1][1] - TAU)).abs() < 1e-12, "{out:?}");
        // And near the counter-clockwise one.
        let start = [both[0][0] - TAU, both[0][1] + 0.3];
        assert_eq!(solve(&c, &goal, &start, c.bounds(), &mut out), ClosedForm::Solved);
        assert!((out[0] - (both[0][0] - TAU)).abs() < 1e-12 && (out[1] - both[0][1]).abs() < 1e-12, "{out:?}");
    }

    #[test]
    fn solve_is_the_nearest_of_all_equivalents_on_random_cases() {
        let mut rng = SplitMix64(3);
        for _ in 0..2000 {
            let c = chain(&[rng.range(0.5, 2.0), rng.range(0.5, 2.0)], &[None, None]);
            let angles = [rng.range(-PI, PI), rng.range(-PI, PI)];
            let tip = end_effector(&c, &angles).position;
            let goal = Goal::position(tip.x, tip.y).unwrap();
            let start = [rng.range(-20.0, 20.0), rng.range(-20.0, 20.0)];
            let mut out = [0.0; 2];
            assert_eq!(solve(&c, &goal, &start, c.bounds(), &mut out), ClosedForm::Solved);
            // Brute force over both solutions and shifts of −5..=5 turns per joint.
            let both = two_link(c.lengths()[0], c.lengths()[1], tip - c.base()).unwrap();
            let mut best = f64::INFINITY;
            for s in both {
                let mut d = 0.0;
                for (a, from) in s.iter().zip(start) {
                    d += (-5..=5).map(|k| math::square(a + TAU * f64::from(k) - from)).fold(f64::INFINITY, f64::min);
                }
                best = best.min(d);
            }
            let got: f64 = out.iter().zip(start).map(|(a, s)| math::square(a - s)).sum();
            assert!(got <= best + 1e-9, "{got} vs {best}");
            assert!((end_effector(&c, &out).position - tip).norm() < 1e-12 * c.max_reach().max(1.0) * 10.0);
        }
    }

    #[test]
    fn solve_respects_limits() {
        // The counter-clockwise elbow is nearer the start but its elbow breaks [−2, 0]; the
        // other solution is taken, shifted into [2π + 1, 2π + 2.5] for the first joint.
        let target = Vector2::new(1.0, 2.0);
        let both = two_link(2.0, 1.5, target).unwrap();
        let c = chain(&[2.0, 1.5], &[Some((TAU + 1.0, TAU + 2.5)), Some((-2.0, 0.0))]);
        assert!((1.0..2.5).contains(&both[1][0]) && both[1][1] > -2.0 && both[0][1] > 0.0, "{both:?}");
        let goal = Goal::position(0.5 + target.x, -1.0 + target.y).unwrap();
        let mut out = [9.0; 2];
        let start = [both[0][0], both[0][1]];
        assert_eq!(solve(&c, &goal, &start, c.bounds(), &mut out), ClosedForm::Solved);
        assert!((out[0] - (both[1][0] + TAU)).abs() < 1e-12 && (out[1] - both[1][1]).abs() < 1e-12, "{out:?}");
        // Ignoring limits, the nearer solution wins as it is.
        assert_eq!(solve(&c, &goal, &start, Bounds::free(), &mut out), ClosedForm::Solved);
        assert_eq!(out, [both[0][0], both[0][1]]);

        // Elbow limited to [0.1, 0.2]: neither solution fits, and `out` is left alone.
        let c = chain(&[2.0, 1.5], &[None, Some((0.1, 0.2))]);
        let mut out = [9.0; 2];
        assert_eq!(solve(&c, &goal, &start, c.bounds(), &mut out), ClosedForm::OutsideLimits);
        assert_eq!(out, [9.0; 2]);
        assert_eq!(solve(&c, &goal, &start, Bounds::free(), &mut out), ClosedForm::Solved);
    }

    #[test]
    fn solve_keeps_a_solution_on_a_limit_and_lands_exactly_on_it() {
        // Straight arm along +x from the base: θ = [0, 0], the elbow limit is [0, 1] and the
        // shoulder's [−1, 0]. Rounding may put an exact 0 at ±1e-16; it must count as inside.
        let c = chain(&[1.0, 1.0], &[Some((-1.0, 0.0)), Some((0.0, 1.0))]);
        let goal = Goal::position(0.5 + 2.0, -1.0).unwrap();
        let mut out = [9.0; 2];
        assert_eq!(solve(&c, &goal, &[-0.5, 0.5], c.bounds(), &mut out), ClosedForm::Solved);
        assert!(out.iter().zip(c.limits()).all(|(a, l)| l.unwrap().contains(*a)), "{out:?}");
        assert!(out.iter().all(|a| a.abs() < 1e-6), "{out:?}");
    }

    #[test]
    fn solve_three_links_oriented() {
        let mut rng = SplitMix64(4);
        for _ in 0..1000 {
            let c = chain(&[rng.range(0.5, 2.0), rng.range(0.5, 2.0), rng.range(0.5, 2.0)], &[None, None, None]);
            let truth = [rng.range(-PI, PI), rng.range(-PI, PI), rng.range(-PI, PI)];
            let ee = end_effector(&c, &truth);
            let goal = Goal::with_orientation(ee.position.x, ee.position.y, ee.orientation).unwrap();
            let mut out = [0.0; 3];
            let start = truth.map(|a| a + 0.01);
            assert_eq!(solve(&c, &goal, &start, c.bounds(), &mut out), ClosedForm::Solved);
            // Starting next to a solution gives that solution back.
            for (a, t) in out.iter().zip(truth) {
                assert!((a - t).abs() < 1e-6, "{out:?} vs {truth:?}");
            }
        }
    }

    #[test]
    fn solve_reports_not_applicable_and_out_of_reach() {
        let mut out = [0.0; 3];
        let two = chain(&[1.0, 1.0], &[None, None]);
        let three = chain(&[1.0, 1.0, 1.0], &[None, None, None]);
        let one = chain(&[1.0], &[None]);
        let pos = Goal::position(1.0, 0.0).unwrap();
        let oriented = Goal::with_orientation(1.0, 0.0, 0.3).unwrap();
        assert_eq!(solve(&two, &oriented, &[0.0; 2], two.bounds(), &mut out[..2]), ClosedForm::NotApplicable);
        assert_eq!(solve(&three, &pos, &[0.0; 3], three.bounds(), &mut out), ClosedForm::NotApplicable);
        assert_eq!(solve(&one, &pos, &[0.0], one.bounds(), &mut out[..1]), ClosedForm::NotApplicable);
        assert_eq!(solve(&two, &pos, &[0.0; 3], two.bounds(), &mut out[..2]), ClosedForm::NotApplicable);
        assert_eq!(solve(&two, &pos, &[0.0; 2], two.bounds(), &mut out), ClosedForm::NotApplicable);
        let far = Goal::position(0.5 + 2.5, -1.0).unwrap();
        assert_eq!(solve(&two, &far, &[0.0; 2], two.bounds(), &mut out[..2]), ClosedForm::OutOfReach);
        let far = Goal::with_orientation(0.5 + 2.5, -1.0, PI).unwrap();
        assert_eq!(solve(&three, &far, &[0.0; 3], three.bounds(), &mut out), ClosedForm::OutOfReach);
        // Huge but finite numbers: no panic, no NaN in `out`.
        let huge = Goal::position(1e300, -1e300).unwrap();
        assert_eq!(solve(&two, &huge, &[1e300, -1e300], two.bounds(), &mut out[..2]), ClosedForm::OutOfReach);
        let at_base = Goal::position(0.5, -1.0).unwrap();
        assert_eq!(solve(&two, &at_base, &[f64::MAX, -f64::MAX], two.bounds(), &mut out[..2]), ClosedForm::Solved);
        assert!(out[..2].iter().all(|a| a.is_finite()), "{out:?}");
    }
}
