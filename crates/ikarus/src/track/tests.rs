//! Unit tests of the search: the plan's cost against brute force on two-link chains.

use crate::closed_form::two_link;
use crate::math;
use crate::rng::SplitMix64;
use crate::{Chain, Goal, LimitMode, Link, SolveOptions};

use super::plan::flip_cost;
use super::{Path, SampleStatus, TrackOptions, is_flip, joint_distance2, joint_step, plan};
use crate::limits::Bounds;

/// The search's cost of a joint path from `start`: (Σ flip cost, Σ‖Δq‖², the move from `start`
/// included as motion but not as a flip), and its number of flips.
fn cost(poses: &[Vec<f64>], start: &[f64], max_step: f64) -> ((f64, f64), usize) {
    let b = Bounds::free();
    let (mut flip, mut flips) = (0.0, 0);
    let mut motion = joint_distance2(b, &poses[0], start);
    for w in poses.windows(2) {
        let step = joint_step(b, &w[1], &w[0]);
        flip += flip_cost(step, max_step);
        flips += usize::from(is_flip(step, max_step));
        motion += joint_distance2(b, &w[1], &w[0]);
    }
    ((flip, motion), flips)
}

#[test]
fn plan_matches_brute_force_on_two_links() {
    let mut rng = SplitMix64(7);
    for case in 0..40 {
        let chain = Chain::new([0.0, 0.0], &[Link::new(rng.range(0.8, 2.0), 0.3), Link::new(rng.range(0.5, 1.5), 0.4)])
            .unwrap();
        let n = 2 + case % 11;
        let reach = chain.max_reach();
        let inner = chain.min_reach();
        // Random goals inside the annulus, close enough that some steps are small and some flip.
        let mut goals = Vec::new();
        let (mut r, mut a) = (rng.range(inner, reach), rng.range(-3.0, 3.0));
        for _ in 0..n {
            r = (r + rng.range(-0.3, 0.3)).clamp(inner + 0.05, reach - 0.05);
            a += rng.range(-0.5, 0.5);
            goals.push(Goal::position(r * math::cos(a), r * math::sin(a)).unwrap());
        }
        let path = Path::new(goals.clone()).unwrap();
        let options = TrackOptions {
            solve: SolveOptions { limits: LimitMode::Ignore, ..SolveOptions::default() },
            ..TrackOptions::default()
        };
        let start = chain.start_pose().angles().to_vec();
        let track = plan(&chain, &start, &path, &options).unwrap();
        // The search's choice: the path's samples (the off-path poses bridge its flips).
        let poses: Vec<Vec<f64>> = track.on_path().map(|s| s.angles.clone()).collect();
        let (got, got_flips) = cost(&poses, &start, options.max_step);

        let branches: Vec<[[f64; 2]; 2]> = goals
            .iter()
            .map(|g| two_link(chain.lengths()[0], chain.lengths()[1], g.target().coords).unwrap())
            .collect();
        let mut best = (f64::INFINITY, f64::INFINITY);
        for mask in 0..(1u32 << n) {
            let poses: Vec<Vec<f64>> =
                branches.iter().enumerate().map(|(k, b)| b[((mask >> k) & 1) as usize].to_vec()).collect();
            let (c, _) = cost(&poses, &start, options.max_step);
            if c.0 < best.0 || (c.0 == best.0 && c.1 < best.1) {
                best = c;
            }
        }
        assert!((got.0 - best.0).abs() <= 1e-9 * (1.0 + best.0), "case {case}: {got:?} vs brute force {best:?}");
        assert!((got.1 - best.1).abs() <= 1e-9 * (1.0 + best.1), "case {case}: {got:?} vs brute force {best:?}");
        // Every flip of the chosen path is bridged by a run of off-path poses: none is left.
        let bridged = track
            .samples
            .windows(2)
            .filter(|w| w[0].status != SampleStatus::OffPath && w[1].status == SampleStatus::OffPath)
            .count();
        assert_eq!((track.summary.flips.len(), bridged), (0, got_flips), "case {case}");
    }
}

#[test]
fn bound_first_makes_the_first_sample_a_bounded_step_from_the_start() {
    let chain = crate::fixtures::seed_arm();
    let start = chain.start_pose().angles().to_vec();
    // Far from the start pose: placed, the first sample jumps; bounded, it moves by the bound.
    let path = Path::new(vec![Goal::position(-2.0, 3.0).unwrap(), Goal::position(-2.0, 3.1).unwrap()]).unwrap();
    let bound = 5f64.to_radians();
    let placed =
        super::follow(&chain, &start, &path, &TrackOptions { max_step: bound, ..TrackOptions::default() }).unwrap();
    let options = TrackOptions { max_step: bound, bound_first: true, ..TrackOptions::default() };
    let bounded = super::follow(&chain, &start, &path, &options).unwrap();
    let from_start = |t: &super::Track| joint_step(Bounds::free(), &t.samples[0].angles, &start);
    assert!(from_start(&placed) > 6.0 * bound, "placed: {}", from_start(&placed).to_degrees());
    assert_eq!(placed.samples[0].step, 0.0);
    assert!((from_start(&bounded) - bound).abs() < 1e-9, "bounded: {}", from_start(&bounded).to_degrees());
    assert!((bounded.samples[0].step - bound).abs() < 1e-9);
    assert_eq!(bounded.samples[0].status, super::SampleStatus::Limited);
    assert!(bounded.summary.flips.is_empty() && bounded.summary.max_step <= bound * (1.0 + 1e-9));
    // Every later sample stays within the bound of the one before.
    for w in bounded.samples.windows(2) {
        assert!(joint_step(Bounds::free(), &w[1].angles, &w[0].angles) <= bound * (1.0 + 1e-9));
    }
}

/// Issue 24: `ikarus track --circle 0,0,1e308` answered `"error": null` on every sample (the
/// error `|goal − tip|` overflowed in its squares) and left the arm at its start pose (no solve
/// saw its steps that far). Now, in both modes, every sample's error is the goal's finite
/// distance and the arm points at each goal: its tip `reach` out, in the goal's direction.
#[test]
fn a_path_far_beyond_reach_gives_finite_errors_and_points_the_arm_at_it() {
    let chain = Chain::new([0.0, 0.0], &[Link::new(3.0, 0.1), Link::new(2.0, 0.1), Link::new(1.0, 0.1)]).unwrap();
    for radius in [1e200, 1e308] {
        let path = Path::circle([0.0, 0.0], radius, 12).unwrap();
        for mode in super::TrackMode::ALL {
            // A bound that lets follow turn with the goal (30° a sample).
            let options = TrackOptions { max_step: 40f64.to_radians(), ..TrackOptions::default() };
            let t = super::track(&chain, chain.start_pose().angles(), &path, mode, &options).unwrap();
            for (k, s) in t.samples.iter().enumerate() {
                let tip = crate::kinematics::end_effector(&chain, &s.angles).position;
                let g = s.goal.target();
                let at = format!("{mode:?} {radius:e} sample {k}: tip {tip}, goal {g}");
                assert!(s.error.is_finite() && s.error > 0.99 * radius, "{at}: error {}", s.error);
                assert!((tip.coords.norm() - 6.0).abs() < 1e-3, "{at}: stretched out");
                let (a, b) = (math::atan2(tip.y, tip.x), math::atan2(g.y, g.x));
                assert!(crate::angle::wrap_angle(a - b).abs() < 1e-3, "{at}: pointed at the goal");
            }
            assert!(t.summary.max_error.is_finite(), "{mode:?}");
        }
    }
}

/// A follower [`reset`](super::Follower::reset) to a pose steps as a new one made there, bit for
/// bit, whatever it followed before: the restarts' seeds count steps from the reset. Goals are
/// drawn over twice the reach, so that many steps are cut by the bound, miss, and restart.
#[test]
fn a_reset_follower_steps_as_a_new_one() {
    let chain = crate::fixtures::seven_link_arm();
    let options =
        TrackOptions { max_step: 7f64.to_radians(), solve: SolveOptions::default(), ..TrackOptions::default() };
    let mut rng = SplitMix64(28);
    let mut goal = || Goal::position(rng.range(-12.0, 12.0), rng.range(-12.0, 12.0)).unwrap();
    let start = chain.start_pose().angles().to_vec();
    let mut kept = super::Follower::new(&chain, &start, &options).unwrap();
    let (mut compared, mut missed) = (0, 0);
    for round in 0..6 {
        for _ in 0..=round {
            kept.step(&goal());
        }
        let from = kept.pose().to_vec();
        let mut fresh = super::Follower::new(&chain, &from, &options).unwrap();
        kept.reset(&from).unwrap();
        for _ in 0..8 {
            let g = goal();
            let (a, b) = (kept.step(&g), fresh.step(&g));
            assert_eq!(
                (a.status, a.error.to_bits(), a.step.to_bits()),
                (b.status, b.error.to_bits(), b.step.to_bits())
            );
            assert_eq!(kept.pose(), fresh.pose(), "round {round}");
            compared += 1;
            missed += usize::from(!matches!(a.status, SampleStatus::Reached | SampleStatus::Limited));
        }
    }
    assert!(missed > 0, "no step restarted: {compared} compared");
    assert!(matches!(kept.reset(&start[1..]), Err(super::TrackError::Solve(crate::SolveError::PoseLength { .. }))));
    let mut bad = start.clone();
    bad[3] = f64::NAN;
    assert!(matches!(
        kept.reset(&bad),
        Err(super::TrackError::Solve(crate::SolveError::NonFiniteAngle { index: 3, .. }))
    ));
}
