//! The exact region against what it must equal: the annulus with limits off, dense sampling of
//! joint space for the area and for membership, and forward kinematics for the poses it gives.

use std::f64::consts::PI;

use nalgebra::Point2;

use super::{BoundarySegment, Membership, Region};
use crate::chain::{Chain, Link};
use crate::kinematics::end_effector;
use crate::math;
use crate::rng::SplitMix64 as Rng;

use crate::fixtures::{limited_arm as chain, seed_arm_limited as seed, seven_link_arm as seven};

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
            center + radius * nalgebra::Vector2::new(math::cos(from_angle), math::sin(from_angle)),
            center + radius * nalgebra::Vector2::new(math::cos(to_angle), math::sin(to_angle)),
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
    let corner = Point2::new(3.0 * math::cos(PI / 4.0), 3.0 * math::sin(PI / 4.0));
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

/// A pose reaching `p` (within 1e-4 of the reach), found without the solver's search: joint by joint, the angle whose
/// turn puts the rest of the goal nearest the region of the rest of the chain (scanned over the
/// range), then a polish by Levenberg–Marquardt from that pose. The oracle for "every point of
/// the region is reachable", where the solver's random restarts can miss thin families of poses.
fn witness(links: &[(f64, f64, f64)], p: Point2<f64>) -> Option<Vec<f64>> {
    let n = links.len();
    let rests: Vec<Region> = (1..n).map(|k| Region::of(&chain(&links[k..]), true)).collect();
    let mut angles = Vec::with_capacity(n);
    let mut q = p;
    for k in 0..n {
        let (lo, hi) = (links[k].1.to_radians(), links[k].2.to_radians());
        let at = |t: f64| {
            let (s, c) = math::sin_cos(t);
            Point2::new(c * q.x + s * q.y - links[k].0, -s * q.x + c * q.y)
        };
        let t = if k + 1 == n {
            let a = math::atan2(q.y, q.x);
            crate::angle::nearest_equivalent_in(a, 0.5 * (lo + hi), lo, hi)
                .unwrap_or_else(|| crate::angle::nearer_end(a, lo, hi))
        } else {
            let m = 4000;
            (0..=m)
                .map(|i| lo + (hi - lo) * f64::from(i) / f64::from(m))
                .min_by(|&a, &b| rests[k].distance(at(a)).total_cmp(&rests[k].distance(at(b))))
                .unwrap()
        };
        angles.push(t);
        q = at(t);
    }
    // The scan's step leaves the tip a little off (1e-5 here); the polish closes the gap unless
    // the joints sit on their limits, where a tip within 1e-4 of the reach is taken as the
    // witness (the points tried are 1e-3 of the reach inside the region).
    let c = chain(links);
    let tip = end_effector(&c, &angles).position;
    if (tip - p).norm() <= 1e-4 * c.max_reach() {
        return Some(angles);
    }
    let mut polish =
        crate::Solver::new(crate::SolveOptions { reach_verdict: false, restarts: None, ..Default::default() }).unwrap();
    let out = polish.solve(&c, &c.pose(angles).ok()?, &crate::Goal::position(p.x, p.y).unwrap()).unwrap();
    (out.status == crate::Status::Reached).then(|| out.pose.angles().to_vec())
}

/// Random arms of two to eight links with random ranges: the exact area is at least that of the
/// sampled grid (which is sound: every counted cell's centre is reachable) less its edge cells;
/// every sampled tip is inside; every point drawn inside, away from the boundary, is reached
/// (by the solver, or else by the joint-by-joint witness). The five-link arm whose union once
/// failed to close, and the seven-link arm where 64 restarts miss a thin family of poses, are in.
#[test]
fn random_arms_agree_with_sampling_and_with_poses() {
    let mut rng = Rng(77);
    let deg = |t: f64| t.to_degrees();
    let mut arms: Vec<Vec<(f64, f64, f64)>> = vec![
        vec![
            (1.03053, -53.4661, 146.802),
            (2.35434, -9.74987, 39.8313),
            (0.74521, -27.4461, 61.9628),
            (1.65765, -111.596, 152.043),
            (1.7568, -39.9121, 104.896),
        ],
        vec![
            (1.0546966377347726, deg(-1.236460575121601), deg(0.15348095717171498)),
            (1.5080328621115573, deg(-2.8555456218882904), deg(-0.14926581901666466)),
            (0.9782913919247787, deg(-2.5864934557195998), deg(-2.257512979122097)),
            (0.32475171134480385, deg(-1.4561840637061723), deg(2.962283653022996)),
            (0.38853711304497196, deg(-0.8170843301953803), deg(2.5020141097976696)),
            (2.3778581876686977, deg(0.4678112626522594), deg(1.2852163589317191)),
            (1.7037902624447885, deg(-1.3343687357485456), deg(0.46039055167380954)),
        ],
    ];
    for _ in 0..40 {
        let n = 2 + (rng.next_u64() % 7) as usize;
        let links: Vec<(f64, f64, f64)> = (0..n)
            .map(|_| {
                let lo = rng.range(-170.0, 60.0);
                (rng.range(0.3, 2.5), lo, rng.range(lo, 175.0))
            })
            .collect();
        arms.push(links);
    }
    let mut solver = crate::Solver::new(crate::SolveOptions { reach_verdict: false, ..Default::default() }).unwrap();
    let mut by_witness = 0;
    for links in arms {
        let c = chain(&links);
        let r = Region::of(&c, true);
        assert_closed(&r);
        assert!(r.is_checked(), "{c:?}");
        let opts = crate::WorkspaceOptions { resolution: 256, samples: Some(16384), ..Default::default() };
        let grid = crate::reach::sample(&c, &opts).unwrap();
        let slack = 2.0 * std::f64::consts::PI * c.max_reach() * 8.0 * grid.cell_size();
        assert!(r.area() >= grid.area() - slack, "{c:?}: exact {} < grid {}", r.area(), grid.area());
        for p in tips(&c, 2000, 3) {
            assert!(r.contains(p, 1e-7 * c.max_reach()), "{c:?}: tip {p} outside");
        }
        if !r.has_area() {
            continue;
        }
        let (lo, hi) = r.bounds();
        let mut tried = 0;
        while tried < 25 {
            let p = Point2::new(rng.range(lo.x, hi.x), rng.range(lo.y, hi.y));
            if r.classify(p, 1e-3 * c.max_reach()) != Membership::Inside {
                continue;
            }
            tried += 1;
            let out = solver.solve(&c, c.start_pose(), &crate::Goal::position(p.x, p.y).unwrap()).unwrap();
            if out.status != crate::Status::Reached {
                assert!(
                    witness(&links, p).is_some(),
                    "{c:?}: {p} inside the region, reached neither by the solver ({out:?}) nor by the witness"
                );
                by_witness += 1;
            }
        }
    }
    println!("{by_witness} points reached only by the witness");
}

/// A set interrupt stops the construction at its first check: one unit of work per piece of
/// the first level, not the whole sweep.
#[test]
fn a_set_interrupt_stops_the_construction_at_once() {
    use super::work::{Stop, Work};
    use super::{RegionError, RegionOptions};
    let token = crate::Interrupt::new();
    token.interrupt();
    for c in [seed(), seven(), crate::fixtures::spread_arm()] {
        let mut work = Work::new(u64::MAX, Some(&token));
        let stopped = Region::build(&c, true, &mut work).map(|_| ()).unwrap_err();
        assert_eq!(stopped, (Stop::Interrupted, c.len() - 1), "it stops sweeping the last joint");
        assert!(work.spent <= 1, "{} units spent", work.spent);
        let options = RegionOptions { interrupt: Some(token.clone()), ..RegionOptions::default() };
        assert_eq!(Region::try_of(&c, &options).map(|_| ()), Err(RegionError::Interrupted));
        assert_eq!(Region::try_wrist(&c, &options).map(|_| ()), Err(RegionError::Interrupted));
    }
}

/// Issue 24: the 64-link arm whose lengths spread from 1e-9 to 1e9 ran for minutes. Its
/// construction now stops when the interrupt is set from another thread (the only wall-clock
/// bound: it ends at all), and runs out of its work cap in bounded work otherwise.
#[test]
fn the_spread_arm_is_interrupted_or_over_its_cap() {
    use super::{RegionError, RegionOptions};
    let c = crate::fixtures::spread_arm();
    let token = crate::Interrupt::new();
    let setter = {
        let token = token.clone();
        std::thread::spawn(move || {
            std::thread::sleep(std::time::Duration::from_millis(50));
            token.interrupt();
        })
    };
    let options = RegionOptions { max_work: u64::MAX - 1, interrupt: Some(token), ..RegionOptions::default() };
    assert_eq!(Region::try_of(&c, &options).map(|_| ()), Err(RegionError::Interrupted));
    setter.join().unwrap();
    let capped = RegionOptions { max_work: 2_000_000, ..RegionOptions::default() };
    let err = Region::try_of(&c, &capped).unwrap_err();
    assert!(matches!(err, RegionError::TooComplex { links: 64, cap: 2_000_000, .. }), "{err:?}");
    let message = err.to_string();
    assert!(
        message.starts_with("links: the exact region of these 64 links needs more than 2000000 steps"),
        "{message}"
    );
}

/// The arms of the tests and the benches spend a small share of the default cap.
#[test]
fn ordinary_arms_stay_far_below_the_work_cap() {
    use super::work::Work;
    let sixty_four = chain(&[(0.1, -60.0, 60.0); 64]);
    for (c, most) in [(seed(), 20_000), (seven(), 200_000), (sixty_four, Region::MAX_WORK / 4)] {
        let mut work = Work::unbounded();
        let region = Region::build(&c, true, &mut work).unwrap();
        assert!(work.spent < most, "{} links: {} units", c.len(), work.spent);
        println!("{} links: {} units, {} pieces", c.len(), work.spent, region.pieces());
    }
}

/// Issue 24: a link of 5e-324 (subnormal) beside a link of 1 made the exact region fail (the
/// server answered 500). A link far shorter than the rounding of the reach sweeps nothing
/// wider than a rounding error: the region is a curve (the arcs the other joint traces), it
/// passes its self-check, every sampled tip lies on it, and the poses it reads off reach it.
#[test]
fn links_below_the_rounding_of_the_reach_give_a_checked_curve() {
    for lengths in [[1.0, 5e-324], [5e-324, 1.0], [1.0, 1e-310], [1e-310, 1.0], [1e150, 1e-150], [1e-150, 1e150]] {
        for limits in [true, false] {
            let c = chain(&[(lengths[0], -60.0, 60.0), (lengths[1], -90.0, 90.0)]);
            let r = Region::of(&c, limits);
            assert!(r.is_checked() && r.pieces() > 0, "{lengths:?} limits {limits}: {r:?}");
            assert_eq!(r.area(), 0.0, "{lengths:?}");
            let scale = c.max_reach();
            for p in tips(&c, 500, 9) {
                assert!(r.contains(p, 1e-9 * scale), "{lengths:?} limits {limits}: tip {p} off the curve");
                let (angles, q) = r.pose_reaching(p);
                assert!((q - p).norm() <= 1e-9 * scale, "{lengths:?}: nearest {q} to {p}");
                let tip = end_effector(&c, &angles).position;
                assert!((tip - q).norm() <= 1e-9 * scale, "{lengths:?}: the pose reaches {tip}, not {q}");
            }
        }
    }
}
