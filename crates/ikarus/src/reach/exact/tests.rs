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
fn the_example_arms_pass_the_self_check() {
    let eight = chain(&[
        (2.0, -90.0, 90.0),
        (1.7, -120.0, 120.0),
        (1.4, -120.0, 120.0),
        (1.2, -135.0, 135.0),
        (1.0, -135.0, 135.0),
        (0.8, -150.0, 150.0),
        (0.6, -150.0, 150.0),
        (0.5, -100.0, 100.0),
    ]);
    for c in [seed(), seven(), eight] {
        assert!(Region::of(&c, true).is_checked(), "{c:?}");
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

/// Limits a turn or more apart let the joint turn freely, and every angle the region gives
/// lies within them, also where a level is a single point (the tip folded back onto a joint).
#[test]
fn wide_limits_turn_freely_and_their_angles_stay_within_them() {
    let c = chain(&[(1.0, 141.5, 1186.0), (1.0, 180.0, 180.0), (0.5, 10.0, 30.0)]);
    let r = Region::of(&c, true);
    for p in [Point2::new(3.0, 0.0), Point2::new(-0.2, 0.1), Point2::new(0.0, -2.0)] {
        let (angles, q) = r.pose_reaching(p);
        for (a, l) in angles.iter().zip(c.limits()) {
            assert!(l.unwrap().contains(*a), "{a} outside {l:?}");
        }
        assert!((end_effector(&c, &angles).position - q).norm() < 1e-9);
    }
}

/// Random arms of two to eight links with random ranges: the exact area is at least the
/// sampled grid's (which is sound: every counted cell's centre is reachable) less its edge
/// cells, and within 2 % of it above (the grid falls short near corners for many joints); the
/// loops close. Includes the five-link arm whose union once failed to close.
#[test]
#[ignore = "known fault: on some random arms (one in about forty here) the union keeps a region larger than the reachable set; to be fixed (see the README's Certified reach notes)"]
fn random_arms_agree_with_the_sampled_grid() {
    let mut rng = Rng(77);
    let mut arms = vec![chain(&[
        (1.03053, -53.4661, 146.802),
        (2.35434, -9.74987, 39.8313),
        (0.74521, -27.4461, 61.9628),
        (1.65765, -111.596, 152.043),
        (1.7568, -39.9121, 104.896),
    ])];
    for _ in 0..40 {
        let n = 2 + (rng.next_u64() % 7) as usize;
        let links: Vec<(f64, f64, f64)> = (0..n)
            .map(|_| {
                let lo = rng.range(-170.0, 60.0);
                (rng.range(0.3, 2.5), lo, rng.range(lo, 175.0))
            })
            .collect();
        arms.push(chain(&links));
    }
    for c in arms {
        let r = Region::of(&c, true);
        assert_closed(&r);
        // Sound sampling: every grid cell counted has a reachable centre, so the exact area
        // is at least the grid's, less the cells straddling the boundary.
        let opts = crate::WorkspaceOptions { resolution: 256, samples: Some(16384), ..Default::default() };
        let grid = crate::reach::sample(&c, &opts).unwrap();
        let slack = 2.0 * std::f64::consts::PI * c.max_reach() * 8.0 * grid.cell_size();
        assert!(r.area() >= grid.area() - slack, "{c:?}: exact {} < grid {}", r.area(), grid.area());
        // Not too much: points drawn inside the region, away from its boundary, are reached
        // by searching (the verdict off, restarts on).
        let mut solver = crate::Solver::new(crate::SolveOptions {
            reach_verdict: false,
            restarts: Some(crate::Restarts { attempts: 64, ..Default::default() }),
            ..Default::default()
        })
        .unwrap();
        let (lo, hi) = r.bounds();
        let mut tried = 0;
        while tried < 60 {
            let p = Point2::new(rng.range(lo.x, hi.x), rng.range(lo.y, hi.y));
            if r.classify(p, 1e-3 * c.max_reach()) != Membership::Inside {
                continue;
            }
            tried += 1;
            let goal = crate::Goal::position(p.x, p.y).unwrap();
            let out = solver.solve(&c, c.start_pose(), &goal).unwrap();
            assert_eq!(out.status, crate::Status::Reached, "{c:?}: {p} inside the region, {out:?}");
        }
        // Sampled tips lie inside.
        for p in tips(&c, 2000, 3) {
            assert!(r.contains(p, 1e-7 * c.max_reach()), "{c:?}: tip {p} outside");
        }
    }
}
