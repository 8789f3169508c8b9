//! The best turn of one joint in a CCD sweep: the one-dimensional minimisation of the position
//! cost, the orientation cost, or their blend, over the whole circle or inside the joint's
//! limits. The derivation is in the [CCD module docs](super).

use std::f64::consts::PI;

use nalgebra::Vector2;

use crate::angle::{self, wrap_angle};
use crate::chain::JointLimits;
use crate::math;

/// Newton/bisection steps in the one-dimensional minimisation; bisection alone shrinks a
/// bracket of 2π below 4ε in about 55.
const MAX_ROOT_STEPS: usize = 100;

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
        let (lt, lg) = (math::hypot(lever.x, lever.y), math::hypot(to_goal.x, to_goal.y));
        // The angle from one lever to the other; where their cross or dot product overflows
        // (lengths beyond 1e154, and atan2(∞, ∞) is π/4), on the levers scaled to order one.
        let angle = |a: Vector2<f64>, b: Vector2<f64>| {
            let (cross, dot) = (a.perp(&b), a.dot(&b));
            if cross.is_finite() && dot.is_finite() {
                math::atan2(cross, dot)
            } else {
                let (a, b) = (a / a.amax(), b / b.amax());
                math::atan2(a.perp(&b), a.dot(&b))
            }
        };
        let toward = (lt > tiny && lg > tiny).then(|| angle(lever, to_goal)).filter(|t| t.is_finite());
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
                -math::cos(delta - toward) + 0.5 * k * e * e
            }
        }
    }
}

/// The new angle of a joint at `angle` whose turn about its position moves the tip lever
/// `lever` against the goal lever `to_goal`, with the orientation error `turn` (goal minus tip,
/// wrapped) weighted by `w2`, restricted to `limits` if any.
pub(super) fn best_angle(
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
/// other local minimiser if there is one (see the [module docs](super)), as turns `δ` (not
/// wrapped).
fn blend_minima(toward: f64, turn: f64, k: f64) -> (f64, Option<f64>) {
    let c = wrap_angle(toward - turn);
    // Solve the mirror image for c < 0.
    let (sign, c) = if c < 0.0 { (-1.0, -c) } else { (1.0, c) };
    let slope = |e: f64| math::sin(e - c) + k * e;
    let global = root(c, k, 0.0, c, c / (1.0 + k));
    // F' is concave on [−π, c − π] and peaks at c − π − acos k (when that is inside): a second
    // minimum is where F' crosses zero upwards left of the peak.
    let second = if k < 1.0 && math::acos(k) < c {
        let peak = c - PI - math::acos(k);
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
        let (s, co) = math::sin_cos(e - c);
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
    use crate::rng::SplitMix64;

    /// The true cost of turning `lever` by `d` against `to_goal`, with orientation error
    /// `d − turn` weighted by `w` (plain arithmetic: the grids below evaluate it millions of
    /// times in debug builds).
    fn turn_cost(lever: Vector2<f64>, to_goal: Vector2<f64>, turn: Option<f64>, w: f64, d: f64) -> f64 {
        let (s, c) = math::sin_cos(d);
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
            let toward = math::atan2(lever.perp(&to_goal), lever.dot(&to_goal));
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
}
