//! The exact region against what it must equal: the annulus with limits off, dense sampling of
//! joint space for the area and for membership, and forward kinematics for the poses it gives.

use std::f64::consts::PI;

use nalgebra::Point2;

use super::{BoundarySegment, Membership, Region};
use crate::chain::{Chain, JointLimits, Link};
use crate::kinematics::end_effector;
use crate::rng::SplitMix64 as Rng;

fn chain(links: &[(f64, f64, f64)]) -> Chain {
    let links: Vec<Link> = links
        .iter()
        .map(|&(l, lo, hi)| {
            let (lo, hi) = (lo.to_radians(), hi.to_radians());
            Link::new(l, 0.5 * (lo + hi)).with_limits(JointLimits::new(lo, hi).unwrap())
        })
        .collect();
    Chain::new([0.0, 0.0], &links).unwrap()
}

fn seed() -> Chain {
    chain(&[(3.0, -45.0, 45.0), (2.0, -90.0, 90.0), (1.0, -170.0, 170.0)])
}

fn seven() -> Chain {
    chain(&[
        (2.0, -90.0, 90.0),
        (1.7, -120.0, 120.0),
        (1.4, -120.0, 120.0),
        (1.2, -135.0, 135.0),
        (1.0, -135.0, 135.0),
        (0.8, -150.0, 150.0),
        (0.6, -150.0, 150.0),
    ])
}

/// Tips of `n` uniformly random poses within the limits.
fn tips(c: &Chain, n: usize, seed: u64) -> Vec<Point2<f64>> {
    let mut rng = Rng(seed);
    (0..n)
        .map(|_| {
            let angles: Vec<f64> = c
                .limits()
                .iter()
                .map(|l| {
                    let (lo, hi) = l.map_or((-PI, PI), |l| (l.min(), l.max()));
                    rng.range(lo, hi)
                })
                .collect();
            end_effector(c, &angles).position
        })
        .collect()
}

/// Every boundary loop is closed: each piece starts where the one before it ends.
fn assert_closed(r: &Region) {
    let ends = |s: &BoundarySegment| match *s {
        BoundarySegment::Line { from, to } => (from, to),
        BoundarySegment::Arc { center, radius, from_angle, to_angle } => (
            center + radius * nalgebra::Vector2::new(from_angle.cos(), from_angle.sin()),
            center + radius * nalgebra::Vector2::new(to_angle.cos(), to_angle.sin()),
        ),
    };
    for l in r.boundary() {
        for k in 0..l.len() {
            let (_, end) = ends(&l[k]);
            let (start, _) = ends(&l[(k + 1) % l.len()]);
            assert!((end - start).norm() < 1e-7, "gap {} in loop {l:?}", (end - start).norm());
        }
    }
}

#[test]
fn with_limits_off_the_region_is_the_annulus() {
    for lengths in [vec![3.0, 2.0, 1.0], vec![5.0, 1.0, 1.0], vec![1.0, 1.0], vec![0.5; 7], vec![2.0, 0.3, 0.4, 0.2]] {
        let links: Vec<Link> = lengths.iter().map(|&l| Link::new(l, 0.1)).collect();
        let c = Chain::new([0.5, -1.0], &links).unwrap();
        let r = Region::of(&c, false);
        let a = crate::reach::Annulus::of(&c);
        assert!((r.area() - a.area()).abs() < 1e-9 * a.area(), "{lengths:?}: {} vs {}", r.area(), a.area());
        assert_closed(&r);
        let mut rng = Rng(7);
        for _ in 0..2000 {
            let p = Point2::new(rng.range(-7.0, 7.0), rng.range(-7.0, 7.0)) + c.base().coords;
            let d = (p - a.center).norm();
            if (d - a.inner).abs() > 1e-9 && (d - a.outer).abs() > 1e-9 {
                assert_eq!(r.contains(p, 0.0), a.contains(p), "{lengths:?} at {p}");
            }
        }
    }
}

#[test]
fn the_seed_arms_area_agrees_with_dense_sampling() {
    let c = seed();
    let r = Region::of(&c, true);
    assert_closed(&r);
    // Monte Carlo over the bounding box: the standard error of the estimate is about
    // box·sqrt(p(1−p)/n), 0.05 for n = 400 000 here; allow four of them.
    let (lo, hi) = r.bounds();
    let n = 400_000;
    let mut rng = Rng(3);
    let sampled = tips(&c, 200_000, 11);
    let mut inside = 0;
    for _ in 0..n {
        let p = Point2::new(rng.range(lo.x, hi.x), rng.range(lo.y, hi.y));
        if r.contains(p, 0.0) {
            inside += 1;
        }
    }
    let box_area = (hi.x - lo.x) * (hi.y - lo.y);
    let estimate = box_area * f64::from(inside) / f64::from(n);
    assert!((estimate - r.area()).abs() < 0.2, "area {} vs Monte Carlo {estimate}", r.area());
    // And against the fine occupancy grid of the sampler (exact for two-joint slices).
    let grid = crate::reach::sample(&c, &crate::WorkspaceOptions { resolution: 1024, ..Default::default() }).unwrap();
    assert!((grid.area() - r.area()).abs() < 0.01 * r.area(), "area {} vs grid {}", r.area(), grid.area());
    // Every sampled tip is inside (or on the boundary).
    for p in sampled {
        assert!(r.contains(p, 1e-9), "{p} reachable but outside");
    }
}

#[test]
fn membership_agrees_with_brute_force_away_from_the_boundary() {
    for (name, c) in [("seed", seed()), ("seven", seven())] {
        let r = Region::of(&c, true);
        assert_closed(&r);
        let cloud = tips(&c, if name == "seed" { 300_000 } else { 600_000 }, 5);
        let mut rng = Rng(9);
        let reach = c.max_reach();
        let margin = 0.05 * reach;
        let mut checked = 0;
        for _ in 0..3000 {
            let p = Point2::new(rng.range(-reach, reach), rng.range(-reach, reach));
            let v = r.verdict(p, 0.0);
            let boundary_d = r.pose_reaching(p).1 - p;
            if boundary_d.norm() < margin {
                continue;
            }
            checked += 1;
            // Nearest sampled tip: inside points have sampled tips near them; outside points have
            // none closer than the region's distance.
            let nearest_sample = cloud.iter().map(|q| (q - p).norm()).fold(f64::INFINITY, f64::min);
            if v.reachable {
                assert!(nearest_sample < margin, "{name}: {p} inside but no sampled tip within {margin}");
            } else {
                assert!(
                    nearest_sample >= v.distance - 1e-9,
                    "{name}: {p} sampled tip at {nearest_sample} < {}",
                    v.distance
                );
            }
        }
        assert!(checked > 1000, "{name}: {checked}");
    }
}

#[test]
fn the_nearest_point_is_on_the_boundary_and_reached_by_its_pose() {
    for c in [seed(), seven(), chain(&[(1.0, 0.0, 180.0), (1.0, -60.0, 60.0), (1.0, -60.0, 60.0), (1.0, -60.0, 60.0)])]
    {
        let r = Region::of(&c, true);
        let mut rng = Rng(13);
        let reach = c.max_reach() * 1.3;
        for _ in 0..500 {
            let p = Point2::new(rng.range(-reach, reach), rng.range(-reach, reach));
            let (angles, q) = r.pose_reaching(p);
            for (k, (&a, l)) in angles.iter().zip(c.limits()).enumerate() {
                let l = l.unwrap();
                assert!(l.contains(a), "joint {k}: {a} outside {l:?}");
            }
            let tip = end_effector(&c, &angles).position;
            assert!((tip - q).norm() < 1e-9 * c.max_reach(), "tip {tip} vs boundary point {q}");
            assert_eq!(r.classify(q, 1e-9), Membership::Boundary);
            let v = r.verdict(p, 0.0);
            if !v.reachable {
                assert!((v.nearest - q).norm() < 1e-12);
            }
        }
    }
}

#[test]
fn a_region_without_area_is_its_curve() {
    // The first joint alone moves: an arc of radius 3 from −45° to 45°.
    let c = chain(&[(1.0, -45.0, 45.0), (2.0, 0.0, 0.0)]);
    let r = Region::of(&c, true);
    assert!(!r.has_area());
    assert_eq!(r.area(), 0.0);
    assert!(r.boundary().is_empty());
    assert_eq!(r.classify(Point2::new(3.0, 0.0), 1e-9), Membership::Boundary);
    assert_eq!(r.classify(Point2::new(2.0, 0.0), 1e-9), Membership::Outside);
    let v = r.verdict(Point2::new(0.0, 5.0), 1e-9);
    let corner = Point2::new(3.0 * (PI / 4.0).cos(), 3.0 * (PI / 4.0).sin());
    assert!((v.nearest - corner).norm() < 1e-12, "{v:?}");
    let (angles, _) = r.pose_reaching(Point2::new(0.0, 5.0));
    assert!((end_effector(&c, &angles).position - corner).norm() < 1e-12);
}

#[test]
fn a_chain_with_every_joint_fixed_reaches_one_point() {
    let c = chain(&[(1.0, -49.0, -49.0)]);
    let r = Region::of(&c, true);
    let tip = end_effector(&c, &[-49f64.to_radians()]).position;
    assert_eq!(r.classify(tip, 1e-9), Membership::Boundary);
    let v = r.verdict(Point2::new(0.3, -0.7), 0.1);
    assert!(!v.reachable && (v.nearest - tip).norm() < 1e-12, "{v:?}");
    assert_eq!(r.pose_reaching(Point2::new(5.0, 5.0)).0, vec![-49f64.to_radians()]);
}
