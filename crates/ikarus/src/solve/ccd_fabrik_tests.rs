//! The tests CCD and FABRIK share, each run over a table with one row per method; a row
//! carries what differs between the two (seeds, caps, tolerances, counts, and the checks only
//! one of them passes). Tests of one method only sit beside it, in `ccd.rs` and `fabrik.rs`.

use std::f64::consts::PI;

use nalgebra::Vector2;

use super::test_support::{self, problem, random_chain, random_pose, step_of};
use super::{Goal, Method, SolveOptions, wrap_angle};
use crate::chain::{Chain, Link};
use crate::closed_form;
use crate::kinematics::{end_effector, joint_positions};
use crate::math;
use crate::rng::SplitMix64;

const CCD: Method = Method::CyclicCoordinateDescent;
const FABRIK: Method = Method::Fabrik;

/// Runs `method`'s iterations (see [`test_support::drive`]) with the chain's limits enforced,
/// to `tol`.
fn drive(
    method: Method,
    chain: &Chain,
    goal: &Goal,
    opts: &SolveOptions,
    start: &[f64],
    max: usize,
    tol: f64,
) -> (Vec<f64>, usize, bool) {
    test_support::drive(step_of(method), &problem(chain, goal, opts, true), start, max, tol)
}

// ---------------------------------------------------------------------------------------------
// Success rates

/// One method's exact counts of goals reached for [`test_support::success_rates`] (200 goals for
/// each of 3, 7 and 20 links; the comments give the mean iterations of the goals reached, CCD
/// counting sweeps, FABRIK iterations). The run is deterministic: a change in either method
/// that reaches one goal more or fewer shows here, and the counts are then re-measured.
struct Rates {
    method: Method,
    /// The generators are seeded `seed + links`.
    seed: u64,
    free_position: [u32; 3],
    limited_position: [u32; 3],
    free_orientation: [u32; 3],
    limited_orientation: [u32; 3],
}

const RATES: [Rates; 2] = [
    Rates {
        method: CCD,
        seed: 100,
        // 3 links 99.5%, 7 links 100%, 20 links 100% (mean 47, 29, 14 sweeps).
        free_position: [199, 200, 200],
        // 3 links 93%, 7 links 92%, 20 links 98% (mean 215, 77, 77 sweeps).
        limited_position: [186, 184, 196],
        // 3 links 82.5%, 7 links 100%, 20 links 100% (mean 362, 105, 39 sweeps). The 3-link
        // misses are nearly all slow convergence, not local minima: with 50 000 sweeps 96% get
        // there, and of the rest 6 of 8 are within 1e-6 in cost.
        free_orientation: [165, 200, 200],
        // 3 links 58%, 7 links 80.5%, 20 links 93.5% (mean 670, 261, 163 sweeps).
        limited_orientation: [116, 161, 187],
    },
    Rates {
        method: FABRIK,
        seed: 200,
        // 3 links 100%, 7 links 100%, 20 links 100% (mean 21, 4, 1 iterations).
        free_position: [200, 200, 200],
        // 3 links 78%, 7 links 78%, 20 links 86% (mean 87, 25, 39 iterations). Limits applied
        // in the forward pass only can hold the chain where the backward pass keeps undoing it.
        limited_position: [156, 156, 172],
        // 3 links 97%, 7 links 100%, 20 links 100% (mean 86, 6, 1 iterations).
        free_orientation: [194, 200, 200],
        // 3 links 79.5%, 7 links 51.5%, 20 links 48% (mean 136, 25, 26 iterations): with the
        // last link fixed, the wrist must be reached by links whose limits the backward pass
        // ignores.
        limited_orientation: [159, 103, 96],
    },
];

#[test]
fn success_rate_free_position() {
    for row in &RATES {
        test_support::success_rates(row.method, row.seed, false, false, 200, row.free_position);
    }
}

#[test]
fn success_rate_limited_position() {
    for row in &RATES {
        test_support::success_rates(row.method, row.seed, true, false, 200, row.limited_position);
    }
}

#[test]
fn success_rate_free_orientation() {
    for row in &RATES {
        test_support::success_rates(row.method, row.seed, false, true, 200, row.free_orientation);
    }
}

#[test]
fn success_rate_limited_orientation() {
    for row in &RATES {
        test_support::success_rates(row.method, row.seed, true, true, 200, row.limited_orientation);
    }
}

// ---------------------------------------------------------------------------------------------
// Extreme goals, goals out of reach

/// Goals at the far ends of the f64 range leave every angle finite (20 iterations, limits and
/// none, with and without an orientation). FABRIK also still points a free arm at a far
/// position goal.
#[test]
fn extreme_goals_give_finite_angles() {
    // (method, seed, a free arm points at far position goals)
    for (method, seed, points_at_far_goals) in [(CCD, 17, false), (FABRIK, 24, true)] {
        let mut rng = SplitMix64(seed);
        for limited in [false, true] {
            let chain = random_chain(&mut rng, 5, limited);
            for (x, y) in [(1e300, -1e300), (-1e-300, 1e-300), (1e154, 1e154), (f64::MAX, f64::MIN)] {
                for goal in [Goal::position(x, y).unwrap(), Goal::with_orientation(x, y, 1e10).unwrap()] {
                    let start = random_pose(&mut rng, &chain);
                    let (angles, _, _) = drive(method, &chain, &goal, &SolveOptions::default(), &start, 20, 1e-6);
                    assert!(angles.iter().all(|a| a.is_finite()), "{method:?} {goal:?}: {angles:?}");
                    if points_at_far_goals && !limited && goal.orientation().is_none() && x.abs() > 1.0 {
                        let tip = end_effector(&chain, &angles).position - chain.base();
                        let off = wrap_angle(math::atan2(tip.y, tip.x) - math::atan2(y, x));
                        assert!(off.abs() < 1e-12, "{method:?} {goal:?}: {angles:?}");
                    }
                }
            }
        }
    }
}

/// One method's run at goals out of reach.
struct OutOfReach {
    method: Method,
    seed: u64,
    cases: usize,
    /// The goal's distance from the base, in multiples of the reach.
    beyond: (f64, f64),
    /// Iterations allowed.
    max: usize,
    /// How close the tip must end to the stretched arm's.
    tip_tolerance: f64,
    /// Also checks an orientation goal whose wrist is out of reach (drawing its angle from the
    /// generator for chains of more than one link).
    wrist: bool,
}

/// A goal out of reach: the arm ends stretched towards it, the tip on the segment from the base
/// to the goal at distance `max_reach` (CCD within 5000 sweeps, FABRIK after one iteration).
/// For FABRIK, with an orientation whose wrist is out of reach, the other links stretch towards
/// the wrist and the last link points along the orientation.
#[test]
fn stretches_towards_a_goal_out_of_reach() {
    let table = [
        OutOfReach {
            method: CCD,
            seed: 14,
            cases: 100,
            beyond: (1.01, 3.0),
            max: 5000,
            tip_tolerance: 1e-6,
            wrist: false,
        },
        OutOfReach {
            method: FABRIK,
            seed: 22,
            cases: 200,
            beyond: (1.001, 3.0),
            max: 1,
            tip_tolerance: 1e-9,
            wrist: true,
        },
    ];
    let opts = SolveOptions::default();
    for row in table {
        let method = row.method;
        let mut rng = SplitMix64(row.seed);
        for _ in 0..row.cases {
            let n = 1 + (rng.next_u64() % 8) as usize;
            let chain = random_chain(&mut rng, n, false);
            let dir = rng.range(-PI, PI);
            let unit = Vector2::new(math::cos(dir), math::sin(dir));
            let target = chain.base() + chain.max_reach() * rng.range(row.beyond.0, row.beyond.1) * unit;
            let goal = Goal::position(target.x, target.y).unwrap();
            let start = random_pose(&mut rng, &chain);
            let (angles, _, ok) = drive(method, &chain, &goal, &opts, &start, row.max, 1e-6);
            assert!(!ok);
            let tip = end_effector(&chain, &angles).position;
            let want = chain.base() + chain.max_reach() * unit;
            assert!((tip - want).norm() <= row.tip_tolerance, "{method:?}, {n} links: tip {tip}, want {want}");

            if row.wrist && n > 1 {
                let phi = rng.range(-PI, PI);
                let goal = Goal::with_orientation(target.x, target.y, phi).unwrap();
                let (angles, _, _) = drive(method, &chain, &goal, &opts, &start, row.max, 1e-6);
                let joints = joint_positions(&chain, &angles);
                let last = chain.lengths()[n - 1];
                let wrist = target - last * Vector2::new(math::cos(phi), math::sin(phi));
                let arm: f64 = chain.lengths()[..n - 1].iter().sum();
                if (wrist - chain.base()).norm() > arm {
                    let want = chain.base() + arm * (wrist - chain.base()).normalize();
                    assert!((joints[n - 1] - want).norm() <= 1e-9, "{method:?}, {n} links");
                }
                assert!(wrap_angle(angles.iter().sum::<f64>() - phi).abs() < 1e-12, "{method:?}");
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Degenerate goals

/// One method's run at targets on the base.
struct OnTheBase {
    method: Method,
    /// Starts of three equal links based at (1, 2), target on the base: the start, the
    /// iterations allowed, and whether the method gets there.
    starts: &'static [(&'static [f64], usize, bool)],
    /// Iterations a single link gets to point at a target.
    single_link: usize,
    /// A single link also points at a target with an orientation goal.
    single_link_oriented: bool,
    /// How far a single link may turn when its target is on its base (strictly less than
    /// this; `None`: not at all).
    stays_within: Option<f64>,
}

/// Three equal links can reach their base: both methods get there from the start pose
/// (measured: CCD in 11 sweeps, FABRIK in 6 iterations), and nothing is NaN along the way. From
/// a straight arm (joints at 0) or one folded back (0, π, 0) every line to the goal runs along
/// the arm: both keep it on that line (measured: they fold it to 0, 0, −π, or keep 0, π, 0),
/// where the tip is at best 1 from the base (1 ± 1 ± 1), so they do not get there.
///
/// A single link points at the target whatever its distance (CCD in 3 sweeps; FABRIK in one
/// iteration, with an orientation goal too), and keeps its direction when the target is on its
/// base (CCD exactly).
#[test]
fn target_at_the_base_and_single_links() {
    const START: &[f64] = &[0.1, 0.2, 0.3];
    const STRAIGHT: &[f64] = &[0.0; 3];
    const FOLDED: &[f64] = &[0.0, PI, 0.0];
    let table = [
        OnTheBase {
            method: CCD,
            starts: &[(START, 2000, true), (STRAIGHT, 50, false)],
            single_link: 3,
            single_link_oriented: false,
            stays_within: None,
        },
        OnTheBase {
            method: FABRIK,
            starts: &[(START, 2000, true), (STRAIGHT, 2000, false), (FOLDED, 2000, false)],
            single_link: 1,
            single_link_oriented: true,
            stays_within: Some(1e-12),
        },
    ];
    let opts = SolveOptions::default();
    let chain = Chain::new([1.0, 2.0], &[Link::new(1.0, 0.1), Link::new(1.0, 0.2), Link::new(1.0, 0.3)]).unwrap();
    assert_eq!(chain.start_pose().angles(), START);
    let goal = Goal::position(1.0, 2.0).unwrap();
    let one = Chain::new([0.0, 0.0], &[Link::new(2.0, 0.0)]).unwrap();
    for row in table {
        let method = row.method;
        for &(start, max, reaches) in row.starts {
            let (angles, it, ok) = drive(method, &chain, &goal, &opts, start, max, 1e-6);
            assert!(angles.iter().all(|a| a.is_finite()), "{method:?} from {start:?}: {angles:?}");
            assert_eq!(ok, reaches, "{method:?} from {start:?}: {angles:?} after {it}");
            if !reaches {
                // Still on the line y = 2 through the base, the tip 1 from it.
                let joints = joint_positions(&chain, &angles);
                assert!(joints.iter().all(|j| (j.y - 2.0).abs() <= 1e-12), "{method:?} from {start:?}: {joints:?}");
                let tip = (joints[3] - chain.base()).norm();
                assert!((tip - 1.0).abs() <= 1e-12, "{method:?} from {start:?}: tip {tip} from the base");
            }
        }
        for (x, y) in [(0.0, 5.0), (-0.5, 0.0), (1.0, 1.0)] {
            let goals = [Goal::position(x, y).unwrap(), Goal::with_orientation(x, y, 1.0).unwrap()];
            for goal in &goals[..if row.single_link_oriented { 2 } else { 1 }] {
                let (angles, _, _) = drive(method, &one, goal, &opts, &[0.0], row.single_link, 1e-6);
                assert!(wrap_angle(angles[0] - math::atan2(y, x)).abs() < 1e-12, "{method:?}: {angles:?}");
            }
        }
        let (angles, _, _) = drive(method, &one, &Goal::position(0.0, 0.0).unwrap(), &opts, &[0.4], 3, 1e-6);
        match row.stays_within {
            None => assert_eq!(angles, [0.4], "{method:?}"),
            Some(tol) => assert!((angles[0] - 0.4).abs() < tol, "{method:?}: {angles:?}"),
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Ground truth

/// On two links both methods converge to one of the two closed-form solutions (mod 2π); on
/// three links with an orientation goal, to one of the two oriented ones; and the runs that
/// converge to 1e-11 within 20 000 iterations are counted exactly (the run is deterministic):
/// CCD 353 of 353, FABRIK 335 of 335.
#[test]
fn agrees_with_the_closed_forms() {
    // FABRIK reads no option; CCD reads only the orientation weight (the default).
    let opts = SolveOptions { tolerance: 1e-11, ..SolveOptions::default() };
    // (method, seed, runs checked and converged)
    for (method, seed, want) in [(CCD, 15, (353, 353)), (FABRIK, 23, (335, 335))] {
        let mut rng = SplitMix64(seed);
        let (mut checked, mut converged) = (0, 0);
        for case in 0..400 {
            let n = 2 + case % 2;
            let oriented = n == 3;
            let chain = random_chain(&mut rng, n, false);
            let truth = random_pose(&mut rng, &chain);
            // Keep away from the elbow singularity, where angles are ill-conditioned.
            if math::sin(truth[1]).abs() < 0.2 {
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
            let (angles, _, ok) = drive(method, &chain, &goal, &opts, &start, 20_000, 1e-11);
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
            assert!(solutions.iter().any(matches), "{method:?} case {case}: {angles:?} vs {solutions:?}");
        }
        println!("{} vs closed forms: {converged} of {checked} converged to 1e-11", method.name());
        assert_eq!((checked, converged), want, "{method:?}: (checked, converged)");
    }
}
