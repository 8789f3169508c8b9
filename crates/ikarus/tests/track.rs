//! Tracking paths: `plan` is continuous where a continuous joint path exists, `follow` never
//! steps over its bound, and both say sample by sample where the path leaves the reach.

mod common;

use std::f64::consts::TAU;

use common::SplitMix64;
use common::fixtures::{deg, seed_arm, seed_arm_limited, seven_link_arm};
use ikarus::kinematics::end_effector;
use ikarus::track::{self, Follower, Path, PathError, SampleStatus, Track, TrackOptions};
use ikarus::{Chain, Goal, LimitMode, SolveOptions};

/// A smooth joint trajectory inside the limits (each joint a sine around the middle of its
/// range, at most 0.7 of the half-range, or ±1 rad for a free joint), sampled `n` times, and
/// the path its tip draws: a continuous solution exists by construction.
fn generated(chain: &Chain, n: usize, phase: f64) -> (Vec<Vec<f64>>, Path) {
    let poses: Vec<Vec<f64>> = (0..n)
        .map(|k| {
            let t = k as f64 / (n - 1) as f64;
            chain
                .limits()
                .iter()
                .enumerate()
                .map(|(i, l)| {
                    let (mid, amp) = l.map_or((0.3, 1.0), |l| (0.5 * (l.min() + l.max()), 0.35 * (l.max() - l.min())));
                    mid + amp * libm::sin(TAU * t * (1.0 + 0.3 * i as f64) + phase + i as f64)
                })
                .collect()
        })
        .collect();
    let goals = poses
        .iter()
        .map(|q| {
            let p = end_effector(chain, q).position;
            Goal::position(p.x, p.y).unwrap()
        })
        .collect();
    (poses, Path::new(goals).unwrap())
}

fn largest_step(poses: &[Vec<f64>]) -> f64 {
    poses.windows(2).flat_map(|w| w[1].iter().zip(&w[0]).map(|(a, b)| (a - b).abs())).fold(0.0, f64::max)
}

fn options(limits: bool) -> TrackOptions {
    let limits = if limits { LimitMode::Lock } else { LimitMode::Ignore };
    TrackOptions { solve: SolveOptions { limits, ..SolveOptions::default() }, ..TrackOptions::default() }
}

fn assert_within_limits(chain: &Chain, t: &Track) {
    for (k, s) in t.samples.iter().enumerate() {
        for (i, (a, l)) in s.angles.iter().zip(chain.limits()).enumerate() {
            if let Some(l) = l {
                assert!(l.contains(*a), "sample {k} joint {i}: {a} outside {l:?}");
            }
        }
    }
}

#[test]
fn plan_is_continuous_and_reaches_every_sample_of_generated_paths() {
    let arms = [
        ("seed", seed_arm(), false),
        ("seed limited", seed_arm_limited(), true),
        ("seven", seven_link_arm(), true),
        ("seven free", seven_link_arm().without_limits(), false),
    ];
    let mut rng = SplitMix64(3);
    for (name, chain, limits) in arms {
        for phase in [0.0, 1.0, rng.range(0.0, TAU)] {
            let (truth, path) = generated(&chain, 100, phase);
            let t = track::plan(&chain, chain.start_pose().angles(), &path, &options(limits)).unwrap();
            let s = &t.summary;
            assert_eq!(s.flips, Vec::<usize>::new(), "{name} phase {phase}: {s:?}");
            assert_eq!(s.reached, 100, "{name} phase {phase}: {s:?}");
            assert!(s.max_error <= 1e-6, "{name} phase {phase}: {s:?}");
            assert!(s.max_step <= deg(10.0), "{name} phase {phase}: {s:?}");
            // The bench target: at most twice the generating trajectory's largest step.
            assert!(
                s.max_step <= 2.0 * largest_step(&truth),
                "{name} phase {phase}: {} vs {}",
                s.max_step,
                largest_step(&truth)
            );
            if limits {
                assert_within_limits(&chain, &t);
            }
        }
    }
}

#[test]
fn follow_never_steps_over_the_bound_and_catches_up_after_a_fast_stretch() {
    let chain = seed_arm_limited();
    // Slow, then a jump of the goal across the workspace, then still: the arm must take
    // several limited samples and then reach the goal again.
    let mut points: Vec<[f64; 2]> = (0..20).map(|k| [4.0, 1.0 + 0.02 * k as f64]).collect();
    points.extend((0..40).map(|_| [1.0, 4.5]));
    let path = Path::from_points(&points).unwrap();
    let opts = options(true);
    let t = track::follow(&chain, chain.start_pose().angles(), &path, &opts).unwrap();
    for s in &t.samples {
        assert!(s.step <= opts.max_step * (1.0 + 1e-9), "{s:?}");
    }
    assert!(t.summary.flips.is_empty());
    assert!(t.summary.limited >= 3, "{:?}", t.summary);
    let last = t.samples.last().unwrap();
    assert_eq!(last.status, SampleStatus::Reached);
    assert!(last.error <= 1e-6);
    // Limited samples come in one run right after the jump, then it is reached again.
    let first_limited = t.samples.iter().position(|s| s.status == SampleStatus::Limited).unwrap();
    assert_eq!(first_limited, 20);
    assert_within_limits(&chain, &t);
}

#[test]
fn a_path_across_the_unreachable_region_is_reported_sample_by_sample_without_a_teleport() {
    let chain = seed_arm();
    // Out beyond the reach (6) and back.
    let mut points: Vec<[f64; 2]> = (0..=40).map(|k| [2.0 + 0.2 * k as f64, 1.0]).collect();
    points.extend((0..=40).map(|k| [10.0 - 0.2 * k as f64, 1.0]));
    let path = Path::from_points(&points).unwrap();
    for mode in [track::TrackMode::Follow, track::TrackMode::Plan] {
        let opts = options(false);
        let t = track::track(&chain, chain.start_pose().angles(), &path, mode, &opts).unwrap();
        assert_eq!(t.on_path().count(), points.len());
        for (k, (s, p)) in t.on_path().zip(&points).enumerate() {
            let out = libm::hypot(p[0], p[1]) > chain.max_reach() + 1e-6;
            assert_eq!(s.status == SampleStatus::Unreachable, out, "{mode:?} sample {k}: {s:?}");
            if out {
                // The best pose: stretched toward the goal (follow may still be on its way).
                let gap = libm::hypot(p[0], p[1]) - chain.max_reach();
                assert!(s.error >= gap - 1e-9, "{mode:?} {k}: {s:?}");
                if mode == track::TrackMode::Plan {
                    assert!(s.error - gap < 1e-6, "{mode:?} {k}: {s:?}");
                }
            } else if mode == track::TrackMode::Plan {
                assert_eq!(s.status, SampleStatus::Reached, "{mode:?} sample {k}");
            } else {
                // Near the boundary the joints straighten fast: follow may lag a few samples.
                assert!(matches!(s.status, SampleStatus::Reached | SampleStatus::Limited), "sample {k}: {s:?}");
            }
        }
        assert_eq!(t.samples.last().unwrap().status, SampleStatus::Reached);
        // Neither mode ever steps over the bound: where the arm must straighten faster than
        // the samples allow (the path crosses the reach boundary), plan leaves the path for a
        // few off-path poses between two samples near the boundary.
        assert!(t.summary.flips.is_empty(), "{mode:?}: {:?}", t.summary);
        for (k, s) in t.samples.iter().enumerate() {
            assert!(s.step <= opts.max_step * (1.0 + 1e-9), "{mode:?} pose {k}: {s:?}");
        }
        let mut sample = 0;
        for s in &t.samples {
            if s.status == SampleStatus::OffPath {
                assert_eq!(mode, track::TrackMode::Plan);
                let d = libm::hypot(points[sample][0], points[sample][1]);
                assert!((d - chain.max_reach()).abs() < 0.5, "off the path before sample {sample}, {d} from the base");
            } else {
                sample += 1;
            }
        }
    }
}

#[test]
fn plan_with_limits_moves_between_the_reachable_pieces_of_a_path_within_the_bound() {
    // The playground fault: a stroke on a circle of radius 4 from 0° to 216° with the
    // seed's limits (shoulder ±45°) is reachable at its start and at its end, not between; the
    // plan jumped from the top to the bottom in one step of 180°.
    let chain = seed_arm_limited();
    let points: Vec<[f64; 2]> = (0..200)
        .map(|k| {
            let a = deg(216.0) * k as f64 / 199.0;
            [4.0 * libm::cos(a), 4.0 * libm::sin(a)]
        })
        .collect();
    let path = Path::from_points(&points).unwrap();
    for limits in [LimitMode::Lock, LimitMode::Clamp] {
        let opts =
            TrackOptions { solve: SolveOptions { limits, ..SolveOptions::default() }, ..TrackOptions::default() };
        let t = track::plan(&chain, chain.start_pose().angles(), &path, &opts).unwrap();
        let s = &t.summary;
        assert!(s.flips.is_empty() && s.max_step <= opts.max_step * (1.0 + 1e-9), "{limits:?}: {s:?}");
        assert_eq!(s.samples, 200);
        assert!(s.reached > 40 && s.reached < 200, "{limits:?}: {s:?}");
        assert!(s.off_path >= 3, "{limits:?}: the arm leaves the path to cross over: {s:?}");
        assert_eq!(s.samples + s.off_path, t.samples.len());
        assert!(
            t.samples
                .windows(2)
                .all(|w| largest_step(&[w[0].angles.clone(), w[1].angles.clone()]) <= opts.max_step * (1.0 + 1e-9))
        );
        assert_within_limits(&chain, &t);
        // The path's samples in order, each with its own goal; an off-path pose carries the next one's.
        let goals: Vec<_> = t.on_path().map(|x| x.goal).collect();
        assert_eq!(goals, path.goals());
        for (k, x) in t.samples.iter().enumerate() {
            if x.status == SampleStatus::OffPath {
                assert_eq!(x.goal, t.samples[k + 1..].iter().find(|y| y.status != SampleStatus::OffPath).unwrap().goal);
            }
        }
    }
}

#[test]
fn follow_with_limits_across_what_the_limits_cannot_reach_never_jumps() {
    // The playground fault: the pointer crosses the region the limits exclude (behind
    // the seed arm, whose shoulder is limited to ±45°).
    let chain = seed_arm_limited();
    let points: Vec<[f64; 2]> = (0..=120)
        .map(|k| {
            let a = deg(90.0) + deg(180.0) * k as f64 / 120.0;
            [4.0 * libm::cos(a), 4.0 * libm::sin(a)]
        })
        .collect();
    let path = Path::from_points(&points).unwrap();
    let opts = options(true);
    let t = track::follow(&chain, chain.start_pose().angles(), &path, &opts).unwrap();
    for s in &t.samples[1..] {
        assert!(s.step <= opts.max_step * (1.0 + 1e-9), "{s:?}");
    }
    assert!(t.summary.reached < 121, "some of the half circle lies outside the limits: {:?}", t.summary);
    assert_within_limits(&chain, &t);
}

#[test]
fn a_figure8_and_a_circle_are_traced() {
    let chain = seed_arm();
    for path in [Path::figure8([2.0, 1.0], 2.0, 200).unwrap(), Path::circle([2.5, 1.5], 1.5, 150).unwrap()] {
        let opts = options(false);
        let planned = track::plan(&chain, chain.start_pose().angles(), &path, &opts).unwrap();
        assert_eq!(planned.summary.reached, path.len());
        assert!(planned.summary.flips.is_empty(), "{:?}", planned.summary);
        let followed = track::follow(&chain, chain.start_pose().angles(), &path, &opts).unwrap();
        assert!(followed.summary.flips.is_empty());
        assert_eq!(followed.summary.reached, path.len(), "{:?}", followed.summary);
    }
    let seven = seven_link_arm();
    let path = Path::figure8([3.0, 2.0], 2.0, 100).unwrap();
    let t = track::plan(&seven, seven.start_pose().angles(), &path, &options(true)).unwrap();
    assert_eq!((t.summary.reached, t.summary.flips.len()), (100, 0), "{:?}", t.summary);
}

#[test]
fn tracks_are_deterministic() {
    let chain = seven_link_arm();
    let (_, path) = generated(&chain, 60, 0.7);
    for mode in [track::TrackMode::Follow, track::TrackMode::Plan] {
        let a = track::track(&chain, chain.start_pose().angles(), &path, mode, &options(true)).unwrap();
        let b = track::track(&chain, chain.start_pose().angles(), &path, mode, &options(true)).unwrap();
        assert_eq!(a, b);
    }
}

#[test]
fn a_follower_streams_what_follow_computes() {
    let chain = seed_arm();
    let path = Path::circle([2.0, 2.0], 1.0, 50).unwrap();
    let opts = options(false);
    let batch = track::follow(&chain, chain.start_pose().angles(), &path, &opts).unwrap();
    let mut f = Follower::new(&chain, chain.start_pose().angles(), &opts).unwrap();
    for (k, goal) in path.goals().iter().enumerate() {
        let step = if k == 0 { f.place(goal) } else { f.step(goal) };
        assert_eq!(f.pose(), batch.samples[k].angles.as_slice());
        assert_eq!(step.status, batch.samples[k].status);
    }
}

#[test]
fn bad_paths_and_options_name_the_field_and_value() {
    assert_eq!(Path::new(vec![]).unwrap_err().to_string(), "path: needs at least one sample, got none");
    assert_eq!(Path::line([0.0, 0.0], [1.0, 1.0], 1).unwrap_err(), PathError::Samples { value: 1 });
    assert_eq!(Path::circle([0.0, 0.0], 1.0, 0).unwrap_err().to_string(), "samples: must be at least 2, got 0");
    assert_eq!(
        Path::circle([0.0, 0.0], -1.0, 5).unwrap_err().to_string(),
        "radius: must be a finite number > 0, got -1"
    );
    assert_eq!(Path::figure8([f64::NAN, 0.0], 1.0, 5).unwrap_err().to_string(), "cx: must be a finite number, got NaN");
    assert_eq!(
        Path::from_points(&[[0.0, 0.0], [f64::INFINITY, 1.0]]).unwrap_err().to_string(),
        "path[1].x: must be a finite number, got inf"
    );
    let chain = seed_arm();
    let path = Path::line([1.0, 1.0], [2.0, 2.0], 5).unwrap();
    let bad = TrackOptions { max_step: 0.0, ..TrackOptions::default() };
    assert_eq!(
        track::plan(&chain, chain.start_pose().angles(), &path, &bad).unwrap_err().to_string(),
        "max_step: must be a finite number > 0, got 0"
    );
    assert_eq!(
        track::follow(&chain, &[0.0, 0.0], &path, &TrackOptions::default()).unwrap_err().to_string(),
        "start: expected 3 angles (one per joint), got 2"
    );
}

#[test]
fn plan_does_not_steepen_the_first_steps_toward_the_start_pose() {
    // Slow trajectories far from the start pose (5°, 5°, 5°): the path's first steps must be as
    // gentle as the trajectory's, not steepened to shorten the approach from the start, which
    // is not on the path (found by `ikarus bench --paths`: seed arm, limits on, seed 1, path 20,
    // first step 5.3° where the trajectory's largest is 1.2°).
    let chain = seed_arm_limited();
    for (centre, phase) in [([-30.0, 50.0, 15.0], 0.0), ([15.0, -35.0, -50.0], 2.0), ([5.0, -40.0, -50.0], 4.0)] {
        let truth: Vec<Vec<f64>> = (0..100)
            .map(|k| {
                let t = k as f64 / 99.0;
                (0..3)
                    .map(|i| deg(centre[i] + 10.0 * libm::sin(TAU * t * (0.7 + 0.3 * i as f64) + phase + i as f64)))
                    .collect()
            })
            .collect();
        let goals = truth.iter().map(|q| end_effector(&chain, q).position).map(|p| Goal::position(p.x, p.y).unwrap());
        let path = Path::new(goals.collect()).unwrap();
        let t = track::plan(&chain, chain.start_pose().angles(), &path, &options(true)).unwrap();
        assert!(t.summary.flips.is_empty() && t.summary.reached == 100, "{centre:?}: {:?}", t.summary);
        let first = t.samples[..10].iter().map(|s| s.step).fold(0.0, f64::max);
        let want = largest_step(&truth);
        assert!(
            first <= 2.0 * want,
            "{centre:?}: first steps up to {:.2}° vs the trajectory's {:.2}°",
            first.to_degrees(),
            want.to_degrees()
        );
    }
}

#[test]
fn a_path_sampled_too_coarsely_is_followed_continuously_and_bridged_within_the_bound() {
    // 40 samples of this figure-8 need about 17° per sample somewhere: more than the 10° bound.
    // Counting flips alone, the search preferred 8 flips with two branch jumps of 141° and 160°
    // to 12 flips of at most 17°; the flip cost makes it take the continuous path, and each step
    // over the bound is bridged by one pose off the path (never a step over the bound).
    let chain = seed_arm();
    let path = Path::figure8([0.5, 2.5], 3.0, 40).unwrap();
    let options = TrackOptions::default();
    let t = track::plan(&chain, chain.start_pose().angles(), &path, &options).unwrap();
    assert_eq!(t.summary.reached, 40);
    assert!(t.summary.flips.is_empty() && t.summary.max_step <= options.max_step * (1.0 + 1e-9), "{:?}", t.summary);
    assert!(t.summary.off_path >= 1 && t.summary.off_path <= 24, "{:?}", t.summary);
    let on_path: Vec<Vec<f64>> = t.on_path().map(|s| s.angles.clone()).collect();
    assert!(
        largest_step(&on_path) < deg(20.0),
        "largest step between samples {}°",
        largest_step(&on_path).to_degrees()
    );
    // The same figure-8 sampled finely enough has no flip at all.
    let fine = Path::figure8([0.5, 2.5], 3.0, 80).unwrap();
    let t = track::plan(&chain, chain.start_pose().angles(), &fine, &TrackOptions::default()).unwrap();
    assert!(t.summary.flips.is_empty() && t.summary.reached == 80, "{:?}", t.summary);
}
