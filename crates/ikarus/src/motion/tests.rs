use std::f64::consts::{PI, TAU};

use super::*;
use crate::chain::{JointLimits, Link};
use crate::math;
use crate::solve::{Goal, Method, SolveOptions, Solver, Status, wrap_angle};

// Validation errors, the property tests and the spline's tests, with the helpers below.
mod properties;
mod spline;
mod validation;

fn deg(x: f64) -> f64 {
    x.to_radians()
}

/// A chain with the given lengths and optional limits (radians), every start angle 0.
fn chain(links: &[(f64, Option<(f64, f64)>)]) -> Chain {
    let links: Vec<Link> = links
        .iter()
        .map(|&(l, lim)| match lim {
            Some((a, b)) => Link::new(l, 0.0).with_limits(JointLimits::new(a, b).unwrap()),
            None => Link::new(l, 0.0),
        })
        .collect();
    Chain::new([0.0, 0.0], &links).unwrap()
}

/// The seed arm without limits: lengths 3, 2, 1.
fn seed() -> Chain {
    chain(&[(3.0, None), (2.0, None), (1.0, None)])
}

fn eases() -> Vec<Ease> {
    vec![Ease::Linear, Ease::Sine, Ease::Smoothstep, Ease::parent(0.3, 0.7).unwrap(), Ease::parent(0.0, 0.5).unwrap()]
}

fn bits(v: &[f64]) -> Vec<u64> {
    v.iter().map(|x| x.to_bits()).collect()
}

/// Invariants of every animation: times from 0 to the duration, strictly increasing; joints by
/// forward kinematics of the angles; limited joints inside their limits.
fn check_frames(chain: &Chain, anim: &Animation) {
    let frames = &anim.frames;
    assert_eq!(frames[0].time, 0.0);
    assert_eq!(frames[frames.len() - 1].time, anim.duration);
    for w in frames.windows(2) {
        assert!(w[1].time > w[0].time, "times {} then {}", w[0].time, w[1].time);
    }
    for (i, f) in frames.iter().enumerate() {
        assert_eq!(f.joints, crate::kinematics::joint_positions(chain, &f.angles), "frame {i}");
        for (j, (&a, lim)) in f.angles.iter().zip(chain.limits()).enumerate() {
            assert!(a.is_finite());
            if let Some(lim) = lim {
                assert!(lim.contains(a), "frame {i} joint {j}: {a} outside [{}, {}]", lim.min(), lim.max());
            }
        }
    }
}

/// No joint turns by more than π between consecutive frames (a wrap would show as ≈ 2π).
fn assert_no_jumps(anim: &Animation) {
    for (i, w) in anim.frames.windows(2).enumerate() {
        for (j, (a, b)) in w[0].angles.iter().zip(&w[1].angles).enumerate() {
            assert!((b - a).abs() <= PI, "frame {i} → {}: joint {j} jumps from {a} to {b}", i + 1);
        }
    }
}

/// The polyline ([`Interpolation::Linear`]) through `keys`, checked by [`check_frames`] and
/// [`assert_no_jumps`]: most tests in this file are about the path as a polyline.
fn animate_ok(chain: &Chain, keys: &[Vec<f64>], times: Option<&[f64]>, timing: Timing, ease: Ease) -> Animation {
    let options = MotionOptions::new(timing, ease).with_interpolation(Interpolation::Linear);
    let anim = animate_with(chain, keys, times, options).unwrap();
    check_frames(chain, &anim);
    assert_no_jumps(&anim);
    anim
}

fn dist(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| math::square(y - x)).sum::<f64>().sqrt()
}

/// Path length travelled up to each frame: locates every frame on the polyline through `keys`
/// (unwrapped), never going back along it, and measures from the start. Where the path doubles
/// back the earliest consistent place is taken, which is never after the true one. Panics if a
/// frame lies off the path or behind the previous frame.
fn arc_positions(keys: &[Vec<f64>], frames: &[Vec<f64>]) -> Vec<f64> {
    let starts: Vec<f64> = std::iter::once(0.0)
        .chain(keys.windows(2).scan(0.0, |acc, w| {
            *acc += dist(&w[0], &w[1]);
            Some(*acc)
        }))
        .collect();
    let (mut k, mut previous) = (0, 0.0);
    let mut out = Vec::new();
    for (i, p) in frames.iter().enumerate() {
        if keys.len() == 1 {
            assert!(dist(p, &keys[0]) <= 1e-12, "frame {i} lies off the path: {p:?}");
            out.push(0.0);
            continue;
        }
        let found = (k..keys.len() - 1).find_map(|j| {
            let (a, b) = (&keys[j], &keys[j + 1]);
            let at = starts[j] + dist(a, p);
            let on = dist(a, p) + dist(p, b) - (starts[j + 1] - starts[j]) <= 1e-12;
            (on && at >= previous - 1e-12).then_some((j, at))
        });
        let (j, at) = found.unwrap_or_else(|| panic!("frame {i} lies off the path or behind the frame before: {p:?}"));
        (k, previous) = (j, at);
        out.push(at);
    }
    out
}

/// Step lengths along the path and the largest change between consecutive steps.
fn steps(arc: &[f64]) -> (Vec<f64>, f64) {
    let d: Vec<f64> = arc.windows(2).map(|w| w[1] - w[0]).collect();
    let change = d.windows(2).map(|w| (w[1] - w[0]).abs()).fold(0.0, f64::max);
    (d, change)
}

/// max |s''| of an ease. Sine: s = (1 − cos πt)/2, s'' = (π²/2) cos πt, max π²/2. Parent: the
/// unnormalised velocity is sin(πt/2k1), 1, cos(π(t − k2)/2(1 − k2)), so s'' peaks at
/// π/(2·k1·f) and π/(2·(1 − k2)·f). Cross-checked against difference quotients of the velocity.
fn max_acceleration(ease: Ease) -> f64 {
    let m = match ease {
        Ease::Sine => PI * PI / 2.0,
        Ease::Parent(p) => {
            let f = 2.0 * p.k1() / PI + (p.k2() - p.k1()) + 2.0 * (1.0 - p.k2()) / PI;
            PI / (2.0 * f * p.k1().min(1.0 - p.k2()))
        }
        other => panic!("no bound for {other:?}"),
    };
    let h = 1e-5;
    let numeric = (0..100_000)
        .map(|i| f64::from(i) * h)
        .map(|t| (ease.velocity(t + h) - ease.velocity(t)).abs() / h)
        .fold(0.0, f64::max);
    assert!(numeric <= m * (1.0 + 1e-6) && numeric >= 0.99 * m, "{ease:?}: {numeric} vs {m}");
    m
}

/// The seed's mistake: the ease applied per segment, each segment given an equal share of time.
fn per_segment(keys: &[Vec<f64>], n: usize, ease: Ease) -> Vec<Vec<f64>> {
    let segments = keys.len() - 1;
    (0..n)
        .map(|i| {
            let x = i as f64 / (n - 1) as f64 * segments as f64;
            let k = (x.floor() as usize).min(segments - 1);
            let e = ease.position(x - k as f64);
            keys[k].iter().zip(&keys[k + 1]).map(|(a, b)| a + e * (b - a)).collect()
        })
        .collect()
}

fn angles(anim: &Animation) -> Vec<Vec<f64>> {
    anim.frames.iter().map(|f| f.angles.clone()).collect()
}

/// Four keyframes of the seed arm with unequal segments (lengths ≈ 1.08, 1.24, 1.20) and
/// corners; no joint moves by π or more between keyframes.
fn four_keys() -> Vec<Vec<f64>> {
    vec![vec![0.0, 0.0, 0.0], vec![0.8, 0.6, -0.4], vec![1.2, 1.6, 0.2], vec![2.0, 1.2, 1.0]]
}

// ---------------------------------------------------------------------------------------------
// Endpoints, frame counts, times

#[test]
fn endpoints_are_exact() {
    let c = seed();
    let keys = four_keys();
    for ease in eases() {
        for timing in [Timing::Frames(2), Timing::Frames(7), Timing::Duration { seconds: 1.3, fps: 24.0 }] {
            for times in [None, Some(&[0.0, 0.2, 0.5, timing.duration()][..])] {
                let anim = animate_ok(&c, &keys, times, timing, ease);
                let (first, last) = (&anim.frames[0], &anim.frames[anim.frames.len() - 1]);
                assert_eq!(bits(&first.angles), bits(&keys[0]), "{ease:?} {timing:?}");
                assert_eq!(bits(&last.angles), bits(&keys[3]), "{ease:?} {timing:?}");
            }
        }
    }
}

/// A last keyframe a turn away from the short way round ends a whole turn from where it was
/// given: the same pose.
#[test]
fn unwrapped_last_keyframe_is_the_same_pose() {
    let c = seed();
    let keys = vec![vec![deg(170.0), 0.1, 0.0], vec![deg(-170.0), 0.2, 7.0]];
    let anim = animate_ok(&c, &keys, None, Timing::Frames(30), Ease::Sine);
    let last = &anim.frames[29];
    assert_eq!(bits(&anim.frames[0].angles), bits(&keys[0]));
    assert!((last.angles[0] - deg(190.0)).abs() <= 1e-12, "{:?}", last.angles);
    assert_eq!(last.angles[1], 0.2);
    assert!((last.angles[2] - (7.0 - TAU)).abs() <= 1e-12);
    let given = crate::kinematics::joint_positions(&c, &keys[1]);
    for (p, q) in last.joints.iter().zip(&given) {
        assert!((p - q).norm() <= 1e-12, "{p} vs {q}");
    }
}

#[test]
fn frame_counts_and_times_are_exact() {
    let c = seed();
    let keys = four_keys();
    for n in [2, 3, 60, 1000] {
        let anim = animate_ok(&c, &keys, None, Timing::Frames(n), Ease::Sine);
        assert_eq!(anim.frames.len(), n);
        assert_eq!(anim.duration, 1.0);
        for (i, f) in anim.frames.iter().enumerate() {
            assert_eq!(f.time, i as f64 / (n - 1) as f64);
        }
        assert_eq!(anim.frames[n - 1].time, 1.0);
    }
    // 2 s at 30 fps: 61 frames, 1/30 s apart, the last at 2 s.
    let anim = animate_ok(&c, &keys, None, Timing::Duration { seconds: 2.0, fps: 30.0 }, Ease::Sine);
    assert_eq!(anim.frames.len(), 61);
    assert_eq!(anim.duration, 2.0);
    assert_eq!(anim.frames[1].time, 1.0 / 30.0);
    assert_eq!(anim.frames[60].time, 2.0);
    // 0.1 s at 24 fps: round(2.4) + 1 = 3 frames, the last interval shorter.
    let anim = animate_ok(&c, &keys, None, Timing::Duration { seconds: 0.1, fps: 24.0 }, Ease::Sine);
    let times: Vec<f64> = anim.frames.iter().map(|f| f.time).collect();
    assert_eq!(times, [0.0, 1.0 / 24.0, 0.1]);
    // 0.13 s at 10 fps: round(1.3) + 1 = 2 frames; 0.05 s at 10 fps rounds up to 2 as well.
    assert_eq!(Timing::Duration { seconds: 0.13, fps: 10.0 }.frame_count(), Ok(2));
    assert_eq!(Timing::Duration { seconds: 0.05, fps: 10.0 }.frame_count(), Ok(2));
    assert_eq!(Timing::Frames(MAX_FRAMES).frame_count(), Ok(MAX_FRAMES));
    assert_eq!(Timing::Duration { seconds: 1000.0, fps: 99.999 }.frame_count(), Ok(MAX_FRAMES));
}

// ---------------------------------------------------------------------------------------------
// Limits and wrapping

/// 160° → −160°: limited to [−170°, 170°] the joint goes the long way, through 0; without limits
/// it goes the short way, through 180°.
#[test]
fn limited_joints_go_the_long_way_and_free_joints_the_short_way() {
    let c = chain(&[(2.0, Some((deg(-170.0), deg(170.0)))), (1.0, None)]);
    let keys = vec![vec![deg(160.0), deg(160.0)], vec![deg(-160.0), deg(-160.0)]];
    for ease in eases() {
        let anim = animate_ok(&c, &keys, None, Timing::Frames(101), ease);
        let limited: Vec<f64> = anim.frames.iter().map(|f| f.angles[0]).collect();
        let free: Vec<f64> = anim.frames.iter().map(|f| f.angles[1]).collect();
        assert!(limited.windows(2).all(|w| w[1] <= w[0]), "{ease:?}: not monotone {limited:?}");
        assert!(free.windows(2).all(|w| w[1] >= w[0]), "{ease:?}: not monotone {free:?}");
        assert!(limited.iter().any(|a| a.abs() <= deg(10.0)), "{ease:?}: never near 0 {limited:?}");
        assert!(free.iter().all(|&a| (deg(160.0)..=deg(200.0) + 1e-12).contains(&a)), "{ease:?}: {free:?}");
        assert!(free.iter().any(|&a| (a - PI).abs() <= deg(10.0)), "{ease:?}: never near 180° {free:?}");
        assert_eq!(limited[100], deg(-160.0));
    }
}

/// Keyframes exactly at the limits: no frame steps outside by rounding.
#[test]
fn keyframes_at_the_limits_stay_inside() {
    let (lo, hi) = (deg(-170.0), deg(170.0));
    let c = chain(&[(1.0, Some((lo, hi))), (1.0, Some((-0.1, 0.3)))]);
    let keys = vec![vec![hi, -0.1], vec![lo, 0.3], vec![hi, -0.1], vec![0.3, 0.3]];
    for ease in eases() {
        for timing in [Timing::Frames(997), Timing::Duration { seconds: 3.3, fps: 29.97 }] {
            animate_ok(&c, &keys, None, timing, ease);
            animate_ok(&c, &keys, Some(&[0.0, 0.1, 0.7, timing.duration()]), timing, ease);
        }
    }
}

/// 170° → −170° without limits: 20° through 180°, never a turn back through 0.
#[test]
fn free_joint_crossing_180_degrees_does_not_jump() {
    let c = chain(&[(1.0, None)]);
    for ease in eases() {
        let anim = animate_ok(&c, &[vec![deg(170.0)], vec![deg(-170.0)]], None, Timing::Frames(50), ease);
        for (i, w) in anim.frames.windows(2).enumerate() {
            let step = w[1].angles[0] - w[0].angles[0];
            assert!((0.0..=deg(20.0)).contains(&step), "{ease:?}: step {i} is {step}");
        }
        let total = anim.frames[49].angles[0] - anim.frames[0].angles[0];
        assert!((total - deg(20.0)).abs() <= 1e-12, "{ease:?}: moved {total}");
    }
}

/// Unwrapping follows the previous *unwrapped* keyframe: a joint spinning on by 120° per
/// keyframe keeps turning the same way rather than falling back after half a turn.
#[test]
fn unwrapping_accumulates_over_keyframes() {
    let c = chain(&[(1.0, None)]);
    let keys: Vec<Vec<f64>> = (0..7).map(|k| vec![wrap_angle(deg(120.0) * f64::from(k))]).collect();
    let anim = animate_ok(&c, &keys, None, Timing::Frames(200), Ease::Linear);
    let last = anim.frames[199].angles[0];
    assert!((last - deg(720.0)).abs() <= 1e-12, "{last}");
    assert!(anim.frames.windows(2).all(|w| w[1].angles[0] > w[0].angles[0]));
}

// ---------------------------------------------------------------------------------------------
// Speed

/// With the linear ease and arc-length timing every frame travels the same path length,
/// L/(n − 1), zero-length segments included (they are skipped, not waited on).
#[test]
fn linear_ease_gives_equal_steps() {
    let c = seed();
    let mut keys = four_keys();
    keys.insert(2, keys[1].clone());
    let n = 200;
    let anim = animate_ok(&c, &keys, None, Timing::Frames(n), Ease::Linear);
    let arc = arc_positions(&keys, &angles(&anim));
    let total: f64 = keys.windows(2).map(|w| dist(&w[0], &w[1])).sum();
    assert!((arc[n - 1] - total).abs() <= 1e-12);
    let (d, _) = steps(&arc);
    let want = total / (n - 1) as f64;
    let worst = d.iter().map(|s| (s - want).abs()).fold(0.0, f64::max);
    println!("linear: step {want}, largest deviation {worst:e}");
    assert!(worst <= 1e-12, "{worst}");
}

/// Speed continuity across keyframes, measured as path length travelled per frame.
///
/// Frame i sits at path length s_i = L·e(u_i), u_i = i·h, h = 1/(n − 1), so the steps
/// Δ_i = s_{i+1} − s_i change by Δ_{i+1} − Δ_i = L·(e(u_{i+2}) − 2e(u_{i+1}) + e(u_i)), a second
/// difference: |Δ_{i+1} − Δ_i| ≤ L·max|e''|·h² (for Parent, whose e' is only piecewise smooth,
/// because e' is Lipschitz with that constant), plus 1e-12 for rounding in locating the frames.
/// Keyframes add nothing to it. Applying the ease per segment, as the seed did, breaks it: each
/// segment accelerates from rest over a third of the time, so its e'' is scaled by 3², and the
/// arm stops at every keyframe, which shows most at the steps around the keyframes.
///
/// Path length, not the straight-line (chord) distance between frames: a chord that cuts one of
/// these keyframe corners (up to 74° of turn) is up to 1 − cos(37°) ≈ 20 % shorter than the path
/// travelled, a geometric effect of the corner that says nothing about the speed; the per-segment
/// ease, which stops at the corners, even has the steadier chords.
#[test]
fn speed_is_continuous_across_keyframes() {
    let c = seed();
    let keys = four_keys();
    let n = 200;
    let h = 1.0 / (n - 1) as f64;
    let lengths: Vec<f64> = keys.windows(2).map(|w| dist(&w[0], &w[1])).collect();
    let total: f64 = lengths.iter().sum();
    let corners: Vec<f64> = lengths.iter().scan(0.0, |acc, l| Some(std::mem::replace(acc, *acc + l) + l)).collect();
    for ease in [Ease::Sine, Ease::parent(0.3, 0.7).unwrap()] {
        let bound = total * max_acceleration(ease) * h * h + 1e-12;
        let measure = |frames: &[Vec<f64>]| {
            let arc = arc_positions(&keys, frames);
            let (_, change) = steps(&arc);
            // The largest change over steps whose three frames enclose an inner keyframe.
            let at_keys = (0..arc.len() - 2)
                .filter(|&i| corners[..corners.len() - 1].iter().any(|&c| arc[i] < c && c < arc[i + 2]))
                .map(|i| ((arc[i + 2] - arc[i + 1]) - (arc[i + 1] - arc[i])).abs())
                .fold(0.0, f64::max);
            (change, at_keys)
        };
        let anim = animate_ok(&c, &keys, None, Timing::Frames(n), ease);
        let (change, at_keys) = measure(&angles(&anim));
        let (seg_change, seg_at_keys) = measure(&per_segment(&keys, n, ease));
        println!(
            "{}: L = {total:.6}, bound {bound:.4e}; whole path {change:.4e}, at keyframes {at_keys:.4e}; \
             per segment {seg_change:.4e}, at keyframes {seg_at_keys:.4e}",
            ease.name(),
        );
        assert!(change <= bound, "{ease:?}: {change} > {bound}");
        assert!(seg_change > 2.0 * bound && seg_at_keys > 2.0 * bound, "{ease:?}: {seg_change}, {seg_at_keys}");
    }
}

// ---------------------------------------------------------------------------------------------
// Explicit times, still animations

/// Keyframe k is reached when the eased time is times[k].
#[test]
fn explicit_times_place_keyframes() {
    let c = seed();
    let keys = vec![vec![0.0, 0.0, 0.0], vec![1.0, -0.5, 0.25], vec![1.5, 0.5, 0.25]];
    // Linear ease: frame 1 of 5 is at t = 0.25 = times[1].
    let anim = animate_ok(&c, &keys, Some(&[0.0, 0.25, 1.0]), Timing::Frames(5), Ease::Linear);
    assert_eq!(bits(&anim.frames[1].angles), bits(&keys[1]));
    // Then the second segment, three times as long in time: a third of the way at t = 0.5.
    for (a, (k1, k2)) in anim.frames[2].angles.iter().zip(keys[1].iter().zip(&keys[2])) {
        assert!((a - (k1 + (k2 - k1) / 3.0)).abs() <= 1e-15);
    }
    // Sine ease: e(1/3) = (1 − cos(π/3))/2 = 1/4, so frame 1 of 4 reaches keyframe 1.
    let anim = animate_ok(&c, &keys, Some(&[0.0, 0.25, 1.0]), Timing::Frames(4), Ease::Sine);
    for (a, k) in anim.frames[1].angles.iter().zip(&keys[1]) {
        assert!((a - k).abs() <= 1e-12, "{:?}", anim.frames[1].angles);
    }
    // Seconds: 2 s at 10 fps, keyframe 1 at 0.5 s is frame 5.
    let timing = Timing::Duration { seconds: 2.0, fps: 10.0 };
    let anim = animate_ok(&c, &keys, Some(&[0.0, 0.5, 2.0]), timing, Ease::Linear);
    assert_eq!(anim.frames[5].time, 0.5);
    assert_eq!(bits(&anim.frames[5].angles), bits(&keys[1]));
}

#[test]
fn one_keyframe_or_identical_keyframes_stand_still() {
    let c = seed();
    let pose = vec![0.3, -0.2, 1.0];
    for keys in [vec![pose.clone()], vec![pose.clone(), pose.clone(), pose.clone()]] {
        let anim = animate_ok(&c, &keys, None, Timing::Frames(10), Ease::Sine);
        assert!(anim.frames.iter().all(|f| bits(&f.angles) == bits(&pose)));
    }
    // A whole turn is no motion for a free joint.
    let turned = vec![0.3 + TAU, -0.2, 1.0];
    let anim = animate_ok(&c, &[pose.clone(), turned], None, Timing::Frames(10), Ease::Sine);
    assert!(anim.frames.iter().all(|f| dist(&f.angles, &pose) <= 1e-15), "{anim:?}");
}

// ---------------------------------------------------------------------------------------------
// From a solve

/// The seed arm (5° per joint) solving for (−4, 1) with the Jacobian transpose at gain 0.01
/// takes 1863 small steps (at gain 1 its line search gets there in 35); 60 frames remain, from
/// the first recorded pose to the last.
#[test]
fn a_long_solve_becomes_sixty_frames() {
    let d = deg(5.0);
    let c = Chain::new([0.0, 0.0], &[Link::new(3.0, d), Link::new(2.0, d), Link::new(1.0, d)]).unwrap();
    let options = SolveOptions {
        method: Method::Transpose,
        gain: 0.01,
        record_every: Some(1),
        max_iterations: 10_000,
        ..SolveOptions::default()
    };
    let outcome = Solver::new(options).unwrap().solve(&c, c.start_pose(), &Goal::position(-4.0, 1.0).unwrap()).unwrap();
    let recorded = &outcome.frames;
    println!(
        "transpose solve: {:?} after {} iterations, {} frames",
        outcome.status,
        outcome.iterations,
        recorded.len()
    );
    // Measured: reached after 1863 iterations, one frame each plus the start.
    assert_eq!(outcome.status, Status::Reached, "{outcome:?}");
    assert_eq!(recorded.len(), outcome.iterations as usize + 1);
    assert!(recorded.len() > 200, "{} frames", recorded.len());
    for (ease, interpolation) in eases().into_iter().flat_map(|e| Interpolation::ALL.map(|i| (e, i))) {
        let options = MotionOptions::new(Timing::Frames(60), ease).with_interpolation(interpolation);
        let anim = animate_solve_with(&c, recorded, options).unwrap();
        check_frames(&c, &anim);
        assert_no_jumps(&anim);
        assert_eq!(anim.frames.len(), 60);
        let (first, last) = (recorded.get(0).unwrap(), recorded.get(recorded.len() - 1).unwrap());
        assert_eq!(bits(&anim.frames[0].angles), bits(first.angles));
        assert_eq!(bits(&anim.frames[59].angles), bits(last.angles));
        assert_eq!(anim.frames[0].joints, first.joints);
        assert_eq!(anim.frames[59].joints, last.joints);
        assert_eq!(anim.frames[59].angles, outcome.pose.angles());
    }
    // Recorded frames lie on the path, so the linear ease spreads the frames evenly along it.
    let keys: Vec<Vec<f64>> = recorded.iter().map(|f| f.angles.to_vec()).collect();
    let linear = MotionOptions::new(Timing::Frames(60), Ease::Linear).with_interpolation(Interpolation::Linear);
    let anim = animate_solve_with(&c, recorded, linear).unwrap();
    let (d, _) = steps(&arc_positions(&keys, &angles(&anim)));
    let want = d.iter().sum::<f64>() / d.len() as f64;
    assert!(d.iter().all(|s| (s - want).abs() <= 1e-12), "{d:?}");
}
