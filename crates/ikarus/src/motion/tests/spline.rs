//! The spline ([`Interpolation::Spline`]): no corner at the keyframes, exact ends, limits kept,
//! the short way round, the straight segment for two keyframes.

use super::*;

fn spline(chain: &Chain, keys: &[Vec<f64>], times: Option<&[f64]>, timing: Timing, ease: Ease) -> Animation {
    let anim = animate_with(chain, keys, times, MotionOptions::new(timing, ease)).unwrap();
    check_frames(chain, &anim);
    anim
}

/// Per joint, the largest change of the frame-to-frame step `|Δ²q_i| = |q_{i+1} − 2q_i + q_{i−1}|`
/// over the frames near the keyframes (`near`: the frame nearest each keyframe and its two
/// neighbours, so every three-frame stencil that encloses the keyframe is counted), and over all
/// the other (ordinary) frames.
fn step_changes(frames: &[Vec<f64>], near: &[usize]) -> (Vec<f64>, Vec<f64>) {
    let joints = frames[0].len();
    let (mut at_keys, mut ordinary) = (vec![0.0f64; joints], vec![0.0f64; joints]);
    for i in 1..frames.len() - 1 {
        let close = near.iter().any(|&k| i.abs_diff(k) <= 1);
        for j in 0..joints {
            let change = (frames[i + 1][j] - 2.0 * frames[i][j] + frames[i - 1][j]).abs();
            let slot = if close { &mut at_keys[j] } else { &mut ordinary[j] };
            *slot = slot.max(change);
        }
    }
    (at_keys, ordinary)
}

/// The frame nearest each inner keyframe.
fn nearest_frames(frames: &[Vec<f64>], keys: &[Vec<f64>]) -> Vec<usize> {
    keys[1..keys.len() - 1]
        .iter()
        .map(|key| (0..frames.len()).min_by(|&a, &b| dist(&frames[a], key).total_cmp(&dist(&frames[b], key))).unwrap())
        .collect()
}

/// The example, `ikarus animate --goal -2,3 --via 4,2 --via 1,4 --frames 120 --ease
/// parent --k1 0.2 --k2 0.8`: the seed arm (5° per joint) solved through (4, 2), (1, 4) and
/// (−2, 3).
///
/// **The bound.** For frames `q_i = q(t_i)` a step `h` apart, Peano's kernel gives
/// `Δ²q_i = ∫_{−h}^{h} (h − |τ|)·q̈(t_i + τ) dτ` for any C¹ motion with a piecewise continuous
/// second derivative, so `|Δ²q_i| ≤ h²·sup|q̈|` over the stencil, *whether or not a keyframe
/// lies inside it*: at a keyframe the spline's q̈ may jump, but the stencil only averages the
/// values on either side, which the ordinary stencils next to it see too. So at a via point
/// each joint's step changes by at most about the most it changes anywhere else; we allow a
/// factor [`FACTOR`] for q̈ varying over the few frames between a keyframe and the nearest
/// ordinary stencils. A polyline has a corner instead: its step jumps by `h·|Δq̇|`, first order in
/// `h`, which no `h²` bound holds — the same test fails for it, by the measured factor printed.
#[test]
fn steps_change_no_more_at_via_points_than_elsewhere() {
    const FACTOR: f64 = 1.5;
    let d = deg(5.0);
    let c = Chain::new([0.0, 0.0], &[Link::new(3.0, d), Link::new(2.0, d), Link::new(1.0, d)]).unwrap();
    let goals = [(4.0, 2.0), (1.0, 4.0), (-2.0, 3.0)].map(|(x, y)| Goal::position(x, y).unwrap());
    // The keyframes: the start, then each solved pose, each solve from the one before (what
    // `through_goals` does with `Route::Keyframes`).
    let mut keys = vec![c.start_pose().angles().to_vec()];
    let mut solver = Solver::new(SolveOptions::default()).unwrap();
    let mut outcome = crate::solve::Outcome::default();
    for goal in &goals {
        let from = keys.last().unwrap().clone();
        solver.solve_into(&c, &from, goal, &mut outcome).unwrap();
        assert_eq!(outcome.status, Status::Reached);
        keys.push(outcome.pose.angles().to_vec());
    }
    let ease = Ease::parent(0.2, 0.8).unwrap();
    let mut worst = [0.0f64; 2];
    for (slot, interpolation) in Interpolation::ALL.into_iter().enumerate() {
        let options = MotionOptions::new(Timing::Frames(120), ease).with_interpolation(interpolation);
        let frames = angles(&animate_with(&c, &keys, None, options).unwrap());
        let near = nearest_frames(&frames, &keys);
        let (at_keys, ordinary) = step_changes(&frames, &near);
        let ratio = at_keys.iter().zip(&ordinary).map(|(a, o)| a / o).fold(0.0, f64::max);
        let show = |v: &[f64]| v.iter().map(|x| format!("{:.4}°", x.to_degrees())).collect::<Vec<_>>().join(", ");
        println!(
            "{interpolation}: via frames {near:?}; step change per joint at via points [{}], elsewhere [{}]; \
             worst ratio {ratio:.2}",
            show(&at_keys),
            show(&ordinary)
        );
        worst[slot] = ratio;
    }
    assert!(worst[0] <= FACTOR, "spline: a via point changes a step {:.2}× the most elsewhere", worst[0]);
    assert!(worst[1] > 4.0 * FACTOR, "linear: the test cannot tell a corner ({:.2}×)", worst[1]);
}

#[test]
fn endpoints_are_exact_and_counts_too() {
    let c = seed();
    let keys = four_keys();
    for ease in eases() {
        for timing in [Timing::Frames(7), Timing::Frames(200), Timing::Duration { seconds: 1.7, fps: 24.0 }] {
            let n = timing.frame_count().unwrap();
            for times in [None, Some(vec![0.0, 0.2, 0.45, timing.duration()])] {
                let anim = spline(&c, &keys, times.as_deref(), timing, ease);
                assert_eq!(anim.frames.len(), n);
                assert_eq!(bits(&anim.frames[0].angles), bits(&keys[0]));
                assert_eq!(bits(&anim.frames[n - 1].angles), bits(&keys[3]));
                assert_eq!(anim.frames[n - 1].time, timing.duration());
            }
        }
    }
}

/// Two keyframes: the straight segment, bit for bit the polyline's frames; so too when the other
/// keyframes repeat one of the two.
#[test]
fn two_keyframes_give_the_straight_segment() {
    let c = seed();
    let (a, b) = (vec![0.1, -0.4, 2.0], vec![1.3, 0.5, -1.0]);
    for keys in [vec![a.clone(), b.clone()], vec![a.clone(), a.clone(), b.clone(), b.clone()]] {
        for ease in eases() {
            let s = spline(&c, &keys, None, Timing::Frames(33), ease);
            let l = animate_ok(&c, &keys, None, Timing::Frames(33), ease);
            assert_eq!(s, l);
        }
    }
}

/// With times the spline passes through keyframe k at eased time times[k], exactly.
#[test]
fn explicit_times_are_met_exactly() {
    let c = seed();
    let keys = four_keys();
    let anim = spline(&c, &keys, Some(&[0.0, 0.25, 0.5, 1.0]), Timing::Frames(9), Ease::Linear);
    assert_eq!(bits(&anim.frames[2].angles), bits(&keys[1]));
    assert_eq!(bits(&anim.frames[4].angles), bits(&keys[2]));
    // Between keyframes it is not the straight line.
    let line = animate_ok(&c, &keys, Some(&[0.0, 0.25, 0.5, 1.0]), Timing::Frames(9), Ease::Linear);
    assert!(dist(&anim.frames[3].angles, &line.frames[3].angles) > 1e-3);
}

/// Keyframes at the limits and a joint that turns back at every keyframe: no frame outside.
#[test]
fn keyframes_at_the_limits_stay_inside() {
    let (lo, hi) = (deg(-170.0), deg(170.0));
    let c = chain(&[(1.0, Some((lo, hi))), (1.0, Some((-0.1, 0.3)))]);
    let keys = vec![vec![hi, -0.1], vec![lo, 0.3], vec![hi, -0.1], vec![0.3, 0.3], vec![0.29, -0.1]];
    for ease in eases() {
        for timing in [Timing::Frames(997), Timing::Duration { seconds: 3.3, fps: 29.97 }] {
            spline(&c, &keys, None, timing, ease);
            spline(&c, &keys, Some(&[0.0, 0.1, 0.7, 0.8, timing.duration()]), timing, ease);
        }
    }
}

/// 170° → −170° → −150° without limits: through 180°, monotonically, never back through 0;
/// the spline runs through the unwrapped keyframes 170°, 190°, 210°.
#[test]
fn free_joints_go_the_short_way_round() {
    let c = chain(&[(1.0, None), (1.0, None)]);
    let keys = vec![vec![deg(170.0), 0.0], vec![deg(-170.0), 0.1], vec![deg(-150.0), 0.3]];
    for ease in eases() {
        let anim = spline(&c, &keys, None, Timing::Frames(80), ease);
        assert_no_jumps(&anim);
        for w in anim.frames.windows(2) {
            let step = w[1].angles[0] - w[0].angles[0];
            assert!((0.0..=deg(3.0)).contains(&step), "{ease:?}: step {step}");
        }
        let last = anim.frames[79].angles[0];
        assert!((last - deg(210.0)).abs() <= 1e-12, "{ease:?}: ends at {}", last.to_degrees());
    }
}

/// The curve passes through the inner keyframes: with many frames one lands close to each.
#[test]
fn passes_through_every_keyframe() {
    let c = seed();
    let keys = four_keys();
    let anim = spline(&c, &keys, None, Timing::Frames(2001), Ease::Linear);
    let frames = angles(&anim);
    for (k, &i) in nearest_frames(&frames, &keys).iter().enumerate() {
        // Steps are about L/2000 ≈ 2e-3 rad long: the nearest frame is within half a step.
        assert!(dist(&frames[i], &keys[k + 1]) <= 1.5e-3, "keyframe {}: {:?}", k + 1, frames[i]);
    }
}
