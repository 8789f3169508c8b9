//! Test helpers shared by the CCD and FABRIK unit tests: random chains, poses and goals, a
//! driver that runs one method's iterations, and success-rate checks (used by the tables of
//! `ccd_fabrik_tests.rs` and by the tests beside each method).

use nalgebra::Point2;

use super::model::Problem;
use super::{Goal, Method, SolveOptions, wrap_angle};
use crate::chain::Chain;
use crate::kinematics::joint_positions;
use crate::limits::Bounds;
use crate::rng::SplitMix64;

/// One iteration of a method without the Jacobian: [`super::ccd::sweep`] or
/// [`super::fabrik::iterate`].
pub(super) type Step = fn(&Problem, &[f64], &[Point2<f64>], &mut [f64], &mut [Point2<f64>]) -> f64;

/// The iteration of a method without the Jacobian.
///
/// # Panics
/// For a method that has one (it has no iteration of this shape).
pub(super) fn step_of(method: Method) -> Step {
    match method {
        Method::CyclicCoordinateDescent => super::ccd::sweep,
        Method::Fabrik => super::fabrik::iterate,
        Method::Transpose
        | Method::PseudoInverse
        | Method::DampedLeastSquares
        | Method::SelectivelyDamped
        | Method::LevenbergMarquardt
        | Method::Analytic => panic!("{method:?} has no Jacobian-free iteration"),
    }
}

/// The problem of `chain`, `goal` and `opts`, with the chain's limits enforced when `clamp`.
pub(super) fn problem<'a>(chain: &'a Chain, goal: &'a Goal, opts: &'a SolveOptions, clamp: bool) -> Problem<'a> {
    Problem::with_bounds(chain, goal, opts, if clamp { chain.bounds() } else { Bounds::free() })
}

pub(super) use crate::fixtures::{random_chain, random_goal, random_pose};

/// Runs `step` until the tip is within `tol` of the goal (and the orientation within `tol`), or
/// `max` iterations, or until an iteration moves no joint by more than 1e-13. Returns the
/// angles, the iterations taken, and whether it got there.
pub(super) fn drive(step: Step, p: &Problem, start: &[f64], max: usize, tol: f64) -> (Vec<f64>, usize, bool) {
    let (chain, goal) = (p.model, p.goal);
    let n = chain.len();
    let mut angles = start.to_vec();
    let mut joints = joint_positions(chain, &angles);
    let mut phi = angles.iter().sum::<f64>();
    let (mut trial, mut trial_joints) = (vec![0.0; n], vec![Point2::origin(); n + 1]);
    for it in 0..=max {
        let pos = (joints[n] - goal.target()).norm();
        let ang = goal.orientation().map_or(0.0, |g| wrap_angle(g - phi).abs());
        if pos <= tol && ang <= tol {
            return (angles, it, true);
        }
        if it == max {
            break;
        }
        phi = step(p, &angles, &joints, &mut trial, &mut trial_joints);
        // Stuck: nothing moves any more (saves time on the misses).
        if angles.iter().zip(&trial).all(|(a, t)| (a - t).abs() <= 1e-13) {
            break;
        }
        std::mem::swap(&mut angles, &mut trial);
        std::mem::swap(&mut joints, &mut trial_joints);
    }
    (angles, max, false)
}

/// Success counts of `method` on reachable goals (the tip of a random pose inside the limits),
/// from another random pose inside the limits, within 1e-6 (and 1e-6 rad) in 2000 iterations,
/// for chains of 3, 7 and 20 links (generator seeded `seed + n`); asserts each count of goals
/// reached is exactly `expected` (the run is deterministic, so any change shows, better or
/// worse), and every final pose within the limits.
pub(super) fn success_rates(method: Method, seed: u64, limited: bool, oriented: bool, total: u32, expected: [u32; 3]) {
    let (name, step) = (method.name(), step_of(method));
    let opts = SolveOptions::default();
    for (n, want) in [3, 7, 20].into_iter().zip(expected) {
        let mut rng = SplitMix64(seed + n as u64);
        let mut reached = 0;
        let mut iterations = 0;
        for _ in 0..total {
            let chain = random_chain(&mut rng, n, limited);
            let goal = random_goal(&mut rng, &chain, oriented);
            let start = random_pose(&mut rng, &chain);
            let (angles, it, ok) = drive(step, &problem(&chain, &goal, &opts, true), &start, 2000, 1e-6);
            for (a, l) in angles.iter().zip(chain.limits()) {
                assert!(l.is_none_or(|l| l.contains(*a)));
            }
            if ok {
                reached += 1;
                iterations += it;
            }
        }
        println!(
            "{name} n={n} limits={limited} orientation={oriented}: {reached}/{total} ({:.1}%), mean {:.0} iterations",
            100.0 * f64::from(reached) / f64::from(total),
            iterations as f64 / f64::from(reached.max(1))
        );
        assert_eq!(reached, want, "{name} n={n} limits={limited} orientation={oriented}: goals reached of {total}");
    }
}

/// A pose inside `chain`'s limits (a free joint in [−3, 3)) as the solver's restart tests draw
/// their goals' poses. Each joint draws a free angle first, whether it is limited or not, so a
/// limited joint takes two numbers from `rng`: the goal sets are the ones those tests were
/// written and measured with.
pub(super) fn pose_within_limits(chain: &Chain, rng: &mut SplitMix64) -> Vec<f64> {
    chain
        .limits()
        .iter()
        .map(|l| {
            let free = rng.range(-3.0, 3.0);
            l.map_or(free, |l| rng.range(l.min(), l.max()))
        })
        .collect()
}
