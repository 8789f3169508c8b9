//! `plan` never steps over its bound: over random limited chains and paths that cross what the
//! limits (or the reach) exclude, consecutive poses differ by at most `max_step` on every joint,
//! the poses stay inside the limits, and the path's samples are all there, in order; where the
//! arm left the path the poses say so (`off_path`).

use std::f64::consts::PI;

use ikarus::track::{self, Path, SampleStatus, TrackOptions};
use ikarus::{Chain, Goal, JointLimits, LimitMode, Link, SolveOptions};
use proptest::prelude::*;
use proptest::test_runner::{Config, FileFailurePersistence};

/// A joint: length 0.3–3, limits `[lo, lo + width]` (most joints) or free.
fn link() -> impl Strategy<Value = Link> {
    (0.3f64..3.0, prop::option::weighted(0.8, (-2.5f64..0.5, 0.3f64..3.0))).prop_map(|(length, limits)| match limits {
        None => Link::new(length, 0.0),
        Some((lo, width)) => {
            let lim = JointLimits::new(lo, lo + width).unwrap();
            Link::new(length, lim.clamp(0.1)).with_limits(lim)
        }
    })
}

fn chain() -> impl Strategy<Value = Chain> {
    prop::collection::vec(link(), 2..=5).prop_map(|links| Chain::new([0.0, 0.0], &links).unwrap())
}

/// An arc around the base: radius a share of the reach (up to beyond it), from one direction
/// through up to 1.3 turns, so that it crosses what limited joints cannot reach.
fn arc() -> impl Strategy<Value = (f64, f64, f64, usize)> {
    (0.2f64..1.15, -PI..PI, 0.5f64..8.0, 2usize..80)
}

proptest! {
    #![proptest_config(Config {
        cases: 48,
        failure_persistence: Some(Box::new(FileFailurePersistence::Off)),
        ..Config::default()
    })]

    #[test]
    fn no_plan_step_exceeds_the_bound(
        chain in chain(),
        (radius, from, turn, n) in arc(),
        bound_deg in 2.0f64..30.0,
        limits in prop_oneof![Just(LimitMode::Lock), Just(LimitMode::Clamp), Just(LimitMode::Ignore)],
    ) {
        let r = radius * chain.max_reach();
        let goals: Vec<Goal> = (0..n)
            .map(|k| {
                let a = from + turn * k as f64 / (n - 1) as f64;
                Goal::position(r * libm::cos(a), r * libm::sin(a)).unwrap()
            })
            .collect();
        let path = Path::new(goals.clone()).unwrap();
        let options = TrackOptions {
            max_step: bound_deg.to_radians(),
            solve: SolveOptions { limits, ..SolveOptions::default() },
            ..TrackOptions::default()
        };
        let t = track::plan(&chain, chain.start_pose().angles(), &path, &options).unwrap();
        let bound = options.max_step * (1.0 + 1e-9);
        let enforced = limits != LimitMode::Ignore;
        for (k, w) in t.samples.windows(2).enumerate() {
            for (i, (&b, &a)) in w[1].angles.iter().zip(&w[0].angles).enumerate() {
                // Free joints the short way round (the poses are unwrapped along the path).
                let d = if enforced && chain.limits()[i].is_some() { b - a } else { ikarus::angle::wrap_angle(b - a) };
                prop_assert!(d.abs() <= bound, "poses {k}→{}: joint {i} moves {}° > {bound_deg}°", k + 1, d.abs().to_degrees());
            }
            prop_assert!(w[1].step <= bound);
        }
        prop_assert!(t.summary.flips.is_empty(), "{:?}", t.summary);
        prop_assert!(t.summary.max_step <= bound);
        if enforced {
            for s in &t.samples {
                for (a, l) in s.angles.iter().zip(chain.limits()) {
                    if let Some(l) = l {
                        prop_assert!(l.contains(*a), "{a} outside {l:?}: {s:?}");
                    }
                }
            }
        }
        let on_path: Vec<Goal> = t.on_path().map(|s| s.goal).collect();
        prop_assert_eq!(&on_path[..], path.goals());
        prop_assert_eq!(t.summary.samples, n);
        prop_assert_eq!(t.summary.off_path, t.samples.len() - n);
        prop_assert_eq!(t.samples.iter().filter(|s| s.status == SampleStatus::OffPath).count(), t.summary.off_path);
        prop_assert!(t.samples.first().is_some_and(|s| s.status != SampleStatus::OffPath));
        prop_assert!(t.samples.last().is_some_and(|s| s.status != SampleStatus::OffPath));
    }
}
