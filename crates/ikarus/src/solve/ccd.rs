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
//! [`SolveOptions::orientation_weight`]). Writing `δ = δ_o + e` with `e ∈ [−π, π]`,
//! `c = wrap(δ* − δ_o)` and `k = w²/A`, that is (up to a constant and the factor `2A`)
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

use std::f64::consts::PI;

use nalgebra::{Point2, Vector2};

use super::problem::Problem;
use crate::angle::{self, wrap_angle};
use crate::chain::JointLimits;

/// Levers shorter than this share of the chain's reach count as zero.
const NEGLIGIBLE: f64 = 1e-12;

/// Newton/bisection steps in the one-dimensional minimisation; bisection alone shrinks a
/// bracket of 2π below 4ε in about 55.
const MAX_ROOT_STEPS: usize = 100;

/// One CCD sweep, from the last joint to the first: each joint turns by the angle that best
/// brings the tip to the goal (and, with an orientation goal, minimises
/// `|tip − target|² + w²·(φ_tip − φ_goal)²` over that joint's rotation, `w =
/// opts.orientation_weight`, the orientation error wrapped into `[−π, π)`), kept inside its
/// bound in `p.bounds` if any (the best turn inside the limits, not the clamped best turn: see the
/// [module docs](self)). Writes the new angles into `trial` and their joint positions into
/// `trial_joints` (n+1 points), and returns the tip's absolute orientation.
///
/// `joints` must be the positions for `angles` (n+1). Joint positions are updated by rotating
/// the points beyond each joint, not recomputed, so they agree with the forward kinematics of
/// `trial` to rounding (about ε·reach per joint and sweep). Allocates nothing.
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
    let (chain, goal, opts) = (p.chain, p.goal, p.opts);
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
            let (s, c) = delta.sin_cos();
            for q in &mut trial_joints[j + 1..] {
                let v = *q - at;
                *q = at + Vector2::new(c * v.x - s * v.y, s * v.x + c * v.y);
            }
            phi += delta;
        }
    }
    phi
}

/// The cost of turning one joint, as a function of the turn `δ`, up to an increasing affine
/// change.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Aim {
    /// Every turn costs the same.
    Flat,
    /// One minimum at `δ ≡ μ`; the cost grows with the circular distance from `μ`.
    Unimodal(f64),
    /// `−cos(δ − toward) + (k/2) wrap(δ − turn)²`, `0 < k < ∞`.
    Blend { toward: f64, turn: f64, k: f64 },
}

impl Aim {
    fn new(lever: Vector2<f64>, to_goal: Vector2<f64>, turn: Option<f64>, w2: f64, tiny: f64) -> Self {
        // `hypot` rather than `norm`: no overflow for far-off goals.
        let (lt, lg) = (lever.x.hypot(lever.y), to_goal.x.hypot(to_goal.y));
        let toward =
            (lt > tiny && lg > tiny).then(|| lever.perp(&to_goal).atan2(lever.dot(&to_goal))).filter(|t| t.is_finite());
        match (toward, turn) {
            (None, None) => Aim::Flat,
            (Some(mu), None) | (None, Some(mu)) => Aim::Unimodal(mu),
            (Some(toward), Some(turn)) => {
                // k = w² / (|r_t| |r_g|), divided in two steps so that it cannot overflow early.
                let k = w2 / lt / lg;
                if k > 0.0 && k.is_finite() {
                    Aim::Blend { toward, turn, k }
                } else if k == 0.0 {
                    Aim::Unimodal(toward)
                } else {
                    Aim::Unimodal(turn)
                }
            }
        }
    }

    /// The cost of a turn `delta` (only differences matter).
    fn cost(self, delta: f64) -> f64 {
        match self {
            Aim::Flat => 0.0,
            Aim::Unimodal(mu) => wrap_angle(delta - mu).abs(),
            Aim::Blend { toward, turn, k } => {
                let e = wrap_angle(delta - turn);
                -(delta - toward).cos() + 0.5 * k * e * e
            }
        }
    }
}

/// The new angle of a joint at `angle` whose turn about its position moves the tip lever
/// `lever` against the goal lever `to_goal`, with the orientation error `turn` (goal minus tip,
/// wrapped) weighted by `w2`, restricted to `limits` if any.
fn best_angle(
    lever: Vector2<f64>,
    to_goal: Vector2<f64>,
    turn: Option<f64>,
    w2: f64,
    tiny: f64,
    angle: f64,
    limits: Option<JointLimits>,
) -> f64 {
    let aim = Aim::new(lever, to_goal, turn, w2, tiny);
    let Some(lim) = limits else {
        let delta = match aim {
            Aim::Flat => 0.0,
            Aim::Unimodal(mu) => mu,
            Aim::Blend { toward, turn, k } => blend_minima(toward, turn, k).0,
        };
        return angle + wrap_angle(delta);
    };
    let (lo, hi) = (lim.min() - angle, lim.max() - angle);
    let delta = match aim {
        Aim::Flat => 0.0f64.max(lo).min(hi),
        Aim::Unimodal(mu) => equivalent_in(mu, lo, hi).unwrap_or_else(|| angle::nearer_end(mu, lo, hi)),
        Aim::Blend { toward, turn, k } => {
            let (global, second) = blend_minima(toward, turn, k);
            let candidates = [equivalent_in(global, lo, hi), second.and_then(|s| equivalent_in(s, lo, hi))];
            let mut best = (lo, aim.cost(lo));
            for d in candidates.into_iter().flatten().chain([hi]) {
                let cost = aim.cost(d);
                if cost < best.1 {
                    best = (d, cost);
                }
            }
            best.0
        }
    };
    // The equivalence shift can round a hair past a limit.
    lim.clamp(angle + delta)
}

/// The equivalent `mu + 2πm` inside `[lo, hi]` nearest 0, if there is one.
#[inline]
fn equivalent_in(mu: f64, lo: f64, hi: f64) -> Option<f64> {
    angle::nearest_equivalent_in(mu, 0.0, lo, hi)
}

/// The global minimiser of `−cos(δ − toward) + (k/2) wrap(δ − turn)²` over the circle, and the
/// other local minimiser if there is one (see the [module docs](self)), as turns `δ` (not
/// wrapped).
fn blend_minima(toward: f64, turn: f64, k: f64) -> (f64, Option<f64>) {
    let c = wrap_angle(toward - turn);
    // Solve the mirror image for c < 0.
    let (sign, c) = if c < 0.0 { (-1.0, -c) } else { (1.0, c) };
    let slope = |e: f64| (e - c).sin() + k * e;
    let global = root(c, k, 0.0, c, c / (1.0 + k));
    // F' is concave on [−π, c − π] and peaks at c − π − acos k (when that is inside): a second
    // minimum is where F' crosses zero upwards left of the peak.
    let second = if k < 1.0 && k.acos() < c {
        let peak = c - PI - k.acos();
        (slope(-PI) < 0.0 && slope(peak) > 0.0).then(|| root(c, k, -PI, peak, 0.5 * (peak - PI)))
    } else {
        None
    };
    (turn + sign * global, second.map(|e| turn + sign * e))
}

/// The root of `F'(e) = sin(e − c) + k e` in `[lo, hi]`, where `F'(lo) ≤ 0 ≤ F'(hi)` and `F'`
/// crosses zero once, by Newton's method from `start`, falling back on bisection whenever a
/// step would leave the bracket.
fn root(c: f64, k: f64, mut lo: f64, mut hi: f64, start: f64) -> f64 {
    let mut e = start;
    for _ in 0..MAX_ROOT_STEPS {
        let (s, co) = (e - c).sin_cos();
        let g = s + k * e;
        if g == 0.0 {
            return e;
        }
        if g < 0.0 {
            lo = e;
        } else {
            hi = e;
        }
        let newton = e - g / (co + k);
        // `!(a && b)` also sends NaN to bisection.
        let next = if !(newton > lo && newton < hi) { 0.5 * (lo + hi) } else { newton };
        if (next - e).abs() <= 4.0 * f64::EPSILON || hi - lo <= 4.0 * f64::EPSILON {
            return next;
        }
        e = next;
    }
    e
}

#[cfg(test)]
mod tests {
    use std::f64::consts::TAU;

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

    /// The true cost of turning `lever` by `d` against `to_goal`, with orientation error
    /// `d − turn` weighted by `w` (plain arithmetic: the grids below evaluate it millions of
    /// times in debug builds).
    fn turn_cost(lever: Vector2<f64>, to_goal: Vector2<f64>, turn: Option<f64>, w: f64, d: f64) -> f64 {
        let (s, c) = d.sin_cos();
        let (x, y) = (c * lever.x - s * lever.y - to_goal.x, s * lever.x + c * lever.y - to_goal.y);
        let o = turn.map_or(0.0, |t| w * wrap_angle(d - t));
        x * x + y * y + o * o
    }

    /// The lowest cost on a grid over `[lo, hi]`: 2000 cells, each local minimum of the grid
    /// (and each end) refined by a grid of 200 over its two neighbouring cells.
    fn grid_min(cost: impl Fn(f64) -> f64, lo: f64, hi: f64) -> f64 {
        const COARSE: u32 = 2000;
        const FINE: u32 = 200;
        let h = (hi - lo) / f64::from(COARSE);
        let at = |i: u32| lo + h * f64::from(i);
        let values: Vec<f64> = (0..=COARSE).map(|i| cost(at(i))).collect();
        let mut best = f64::INFINITY;
        for i in 0..=COARSE {
            let left = if i == 0 { f64::INFINITY } else { values[i as usize - 1] };
            let right = if i == COARSE { f64::INFINITY } else { values[i as usize + 1] };
            let v = values[i as usize];
            if v <= left && v <= right {
                let (a, b) = ((at(i) - h).max(lo), (at(i) + h).min(hi));
                for k in 0..=FINE {
                    best = best.min(cost(a + (b - a) * f64::from(k) / f64::from(FINE)));
                }
            }
        }
        best
    }

    /// The per-joint choice is the best turn inside the limits: no point of a fine grid over
    /// the allowed turns does better, with or without orientation, for arcs that contain the
    /// optimum, arcs that do not, arcs wider than a turn, and joints that start outside.
    /// A third of the oriented cases put the orientation optimum opposite the position one,
    /// where the cost has two local minima.
    #[test]
    fn best_angle_beats_a_fine_grid() {
        let mut rng = SplitMix64(11);
        let (mut endpoint, mut second) = (0, 0);
        let total = 2000;
        for case in 0..total {
            let lever = Vector2::new(rng.range(-2.0, 2.0), rng.range(-2.0, 2.0));
            let to_goal = Vector2::new(rng.range(-3.0, 3.0), rng.range(-3.0, 3.0));
            let toward = lever.perp(&to_goal).atan2(lever.dot(&to_goal));
            let turn = match case % 3 {
                0 => None,
                1 => Some(rng.range(-PI, PI)),
                _ => Some(wrap_angle(toward + PI + rng.range(-1.0, 1.0))),
            };
            let w = [0.05, 0.3, 1.0, 3.0, 20.0][case % 5];
            let angle = rng.range(-4.0, 4.0);
            let aim = Aim::new(lever, to_goal, turn, w * w, 1e-12);
            let minima = match (turn, aim) {
                (Some(t), Aim::Blend { toward, k, .. }) => Some(blend_minima(toward, t, k)),
                _ => None,
            };
            let lim = match minima {
                // Half the time an arc around the second minimum, if there is one.
                Some((_, Some(s))) if rng.chance(0.5) => {
                    let a = angle + wrap_angle(s) - rng.range(0.0, 0.3);
                    JointLimits::new(a, a + rng.range(0.0, 0.6)).unwrap()
                }
                _ => {
                    let a = angle + rng.range(-3.0, 3.0);
                    let width = if rng.chance(0.1) { rng.range(TAU, 3.0 * TAU) } else { rng.range(0.0, 4.0) };
                    JointLimits::new(a, a + width).unwrap()
                }
            };
            let new = best_angle(lever, to_goal, turn, w * w, 1e-12, angle, Some(lim));
            assert!(lim.contains(new), "{new} outside {lim:?}");
            let cost = |d: f64| turn_cost(lever, to_goal, turn, w, d);
            let got = cost(new - angle);
            let grid = grid_min(cost, lim.min() - angle, lim.max() - angle);
            assert!(got <= grid + 1e-9, "case {case}: chose {new} (cost {got}), grid has {grid}");
            if new == lim.min() || new == lim.max() {
                endpoint += 1;
            }
            if let Some((g, Some(s))) = minima {
                if wrap_angle(new - angle - s).abs() < 1e-9 && wrap_angle(g - s).abs() > 1e-3 {
                    second += 1;
                }
            }
        }
        println!("ccd best_angle: {endpoint} of {total} at a limit, {second} at the second local minimum");
        // The cases exercise the interesting branches.
        assert!(endpoint > total / 5 && second > total / 100, "{endpoint} {second}");
    }

    /// Without limits the choice is the global minimiser over the circle and is within half a
    /// turn.
    #[test]
    fn free_joint_turn_is_global_and_short() {
        let mut rng = SplitMix64(12);
        for case in 0..2000 {
            let lever = Vector2::new(rng.range(-2.0, 2.0), rng.range(-2.0, 2.0));
            let to_goal = Vector2::new(rng.range(-3.0, 3.0), rng.range(-3.0, 3.0));
            let turn = (case % 4 != 0).then(|| rng.range(-PI, PI));
            let w = rng.range(0.01, 10.0);
            let angle = rng.range(-10.0, 10.0);
            let new = best_angle(lever, to_goal, turn, w * w, 1e-12, angle, None);
            let d = new - angle;
            assert!((-PI..=PI).contains(&d), "{d}");
            let cost = |d: f64| turn_cost(lever, to_goal, turn, w, d);
            let grid = grid_min(cost, -PI, PI);
            assert!(cost(d) <= grid + 1e-9, "case {case}: {} vs {grid}", cost(d));
        }
    }

    #[test]
    fn degenerate_levers_do_not_give_nan() {
        let lim = JointLimits::new(0.5, 1.0).unwrap();
        let z = Vector2::zeros();
        let v = Vector2::new(1.0, 0.0);
        // Flat cost: stay, or move to the nearest allowed angle.
        assert_eq!(best_angle(v, z, None, 1.0, 1e-12, 0.2, None), 0.2);
        assert_eq!(best_angle(v, z, None, 1.0, 1e-12, 0.2, Some(lim)), 0.5);
        assert_eq!(best_angle(v, z, None, 1.0, 1e-12, 0.7, Some(lim)), 0.7);
        // Orientation only: turn by the orientation error, within the limits.
        assert!((best_angle(z, v, Some(0.3), 1.0, 1e-12, 0.2, None) - 0.5).abs() < 1e-15);
        assert_eq!(best_angle(z, v, Some(3.0), 1.0, 1e-12, 0.2, Some(lim)), 1.0);
        // Huge weights and levers: finite.
        for (w2, big) in [(1e300, 1.0), (1e-300, 1e150), (0.0, 1.0)] {
            let a = best_angle(v * big, Vector2::new(0.0, big), Some(2.0), w2, 1e-12, 0.0, Some(lim));
            assert!(a.is_finite() && lim.contains(a), "{a}");
            let a = best_angle(v * big, Vector2::new(0.0, big), Some(2.0), w2, 1e-12, 0.0, None);
            assert!(a.is_finite(), "{a}");
        }
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
        assert!((-8.0 * a.cos() + 2.0 * a).abs() < 1e-12 && a > 0.0 && a < PI / 2.0, "{a}");
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
            let goal = Goal::position(5.0 * a.cos(), 5.0 * a.sin()).unwrap();
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
