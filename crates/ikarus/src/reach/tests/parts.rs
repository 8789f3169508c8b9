//! The pieces: sample plans, sectors, the reduced chain, the annulus.

use super::*;
use crate::math;

/// The joint-space samples: grids with both ends of a limited range, balanced 2D grids, and
/// the warped R_d sequence within its ranges with the special angles at the intended rate.
#[test]
fn sampling_plans() {
    let limited = Range { lo: -1.0, span: 2.5, full: false };
    let turn = Range { lo: 0.0, span: TAU, full: true };
    let seg = |range, lever| Segment { range, w: [1.0, 0.0], gamma: 0.0, lever };

    let plan = Plan::new(&[seg(limited, 3.0), seg(turn, 2.0), seg(turn, 1.0)], 11, 0);
    assert_eq!(plan, Plan::Grid1 { n: 11 });
    assert_eq!((plan.angle(limited, 0, 0), plan.angle(limited, 0, 10)), (-1.0, 1.5));
    assert!((plan.angle(turn, 0, 10) - TAU * 10.0 / 11.0).abs() <= 1e-15);

    // Tip steps lever·span/n: 6·2π/n₀ against 2·2.5/n₁ → n₀/n₁ ≈ 7.5.
    let plan = Plan::new(&[seg(turn, 6.0), seg(limited, 2.0), seg(turn, 1.0), seg(turn, 0.5)], 1000, 0);
    let Plan::Grid2 { n0, n1 } = plan else { panic!("{plan:?}") };
    assert_eq!((n0, n1), (87, 11));
    let angles: Vec<(f64, f64)> =
        (0..plan.count()).map(|i| (plan.angle(turn, 0, i), plan.angle(limited, 1, i))).collect();
    assert_eq!(angles[0], (0.0, -1.0));
    assert_eq!(angles[10], (0.0, 1.5));
    assert!((angles[11].0 - TAU / 87.0).abs() <= 1e-15 && angles[11].1 == -1.0);

    let segments = vec![seg(limited, 1.0); 7];
    let plan = Plan::new(&segments, 20_000, 9);
    assert_eq!(plan, Plan::new(&segments, 20_000, 9));
    assert_ne!(plan, Plan::new(&segments, 20_000, 10));
    let Plan::Kronecker { special, .. } = plan else { panic!("{plan:?}") };
    assert!((special - 0.4).abs() <= 1e-15);
    for k in 0..5 {
        let values: Vec<f64> = (0..20_000).map(|i| plan.angle(limited, k, i)).collect();
        assert!(values.iter().all(|&v| (-1.0..=1.5).contains(&v)));
        let count = |x: f64| values.iter().filter(|&&v| v == x).count() as f64 / 20_000.0;
        for x in [-1.0, 1.5, 0.0] {
            assert!((count(x) - special / 3.0).abs() < 0.01, "joint {k}: {x} drawn {}", count(x));
        }
        // The rest is even: half of it below the middle of the range.
        let below = values.iter().filter(|&&v| v > -1.0 && v < 0.25 && v != 0.0).count() as f64 / 20_000.0;
        assert!((below - (1.0 - special) / 2.0).abs() < 0.01, "joint {k}: {below}");
    }
}

#[test]
fn annulus_hand_values() {
    let seed = Annulus::of(&seed_arm());
    assert_eq!((seed.inner, seed.outer), (0.0, 6.0));
    assert!((seed.area() - 36.0 * PI).abs() <= 1e-12);
    let long = Annulus::of(&free(&[5.0, 1.0, 1.0]));
    assert_eq!((long.inner, long.outer), (3.0, 7.0));
    assert!((long.area() - 40.0 * PI).abs() <= 1e-12);
    assert!(long.contains(Point2::new(0.0, 3.0)) && long.contains(Point2::new(-7.0, 0.0)));
    assert!(!long.contains(Point2::new(2.9, 0.0)) && !long.contains(Point2::new(0.0, 7.01)));
    let single = Annulus::of(&free(&[2.0]));
    assert_eq!((single.inner, single.outer, single.area()), (2.0, 2.0, 0.0));
}

#[test]
fn sectors_agree_with_atan2() {
    let mut rng = Rng(1);
    let spans = [0.0, 0.3, PI / 2.0, 2.0, PI, 4.0, 5.9, TAU - 1e-3, TAU, 10.0];
    let mut checked = 0;
    for &span in &spans {
        for _ in 0..400 {
            let lo = rng.range(-10.0, 10.0);
            let sector = Sector::new(lo, span);
            let v = dir(rng.range(-PI, PI));
            let scale = rng.range(0.1, 10.0);
            let (want, margin) = in_range(math::atan2(v[1], v[0]), lo, lo + span);
            if margin < 1e-9 {
                continue;
            }
            assert_eq!(sector.contains([v[0] * scale, v[1] * scale]), want, "lo {lo} span {span} v {v:?}");
            checked += 1;
        }
    }
    // No direction of this seed lies within 1e-9 of a sector's edge: all 10 × 400 are checked.
    assert_eq!(checked, 4000, "directions checked");
    // A zero-width sector does not hold the opposite direction.
    assert!(!Sector::new(1.0, 0.0).contains(dir(1.0 + PI)));
}

/// Forward kinematics through the reduced chain matches the chain's, locked joints included.
#[test]
fn reduced_chain_matches_forward_kinematics() {
    let chain = Chain::new(
        [0.5, -1.0],
        &[
            Link::new(1.0, 23f64.to_radians()).with_limits(lim(23.0, 23.0)),
            Link::new(2.0, 0.0).with_limits(lim(-60.0, 60.0)),
            Link::new(1.5, -30f64.to_radians()).with_limits(lim(-30.0, -30.0)),
            Link::new(0.7, 40f64.to_radians()).with_limits(lim(40.0, 40.0)),
            Link::new(1.2, 0.0),
            Link::new(0.9, -10f64.to_radians()).with_limits(lim(-10.0, -10.0)),
        ],
    )
    .unwrap();
    let reduced = Reduced::new(&chain, true, 1e-12);
    assert_eq!(reduced.segments.len(), 2, "{reduced:?}");
    let mut rng = Rng(7);
    for _ in 0..200 {
        let mut angles = random_pose(&chain, &mut rng);
        angles[4] = rng.range(-PI, PI);
        let want = end_effector(&chain, &angles).position;
        let movable = [angles[1], angles[4]];
        let [mut x, mut y] = reduced.start;
        let mut phi = reduced.phi0;
        for (seg, theta) in reduced.segments.iter().zip(movable) {
            phi += theta;
            let (s, c) = math::sin_cos(phi);
            x += c * seg.w[0] - s * seg.w[1];
            y += s * seg.w[0] + c * seg.w[1];
            phi += seg.gamma;
        }
        assert!((x - want.x).abs() <= 1e-12 && (y - want.y).abs() <= 1e-12, "{x} {y} vs {want:?}");
    }
}
