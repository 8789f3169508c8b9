//! Invariants of a solve over random valid chains, limits, goals, start poses and options:
//! ordinary chains (lengths 0.01–10) with every check of a solve's promises, and chains of
//! extreme magnitudes (lengths 1e-9 … 1e9 mixed in one chain, goals up to 1e6 reaches away,
//! every method with every limit mode it supports, `backtrack` up to its cap, stall windows up
//! to `u32::MAX`) with the checks that must hold at any scale. The long fuzz of the same
//! invariants is `examples/fuzz.rs`.

use std::f64::consts::PI;

use ikarus::kinematics::{end_effector, joint_positions};
use ikarus::{
    Chain, Goal, JointLimits, LimitMode, Link, Method, Outcome, Restarts, SolveError, SolveOptions, Solver,
    StallDetection, Status,
};
use proptest::prelude::*;
use proptest::test_runner::{Config, FileFailurePersistence, TestCaseError};

/// One joint: length, start angle, optional limits `[lo, lo + width]`.
fn link() -> impl Strategy<Value = Link> {
    (0.01f64..10.0, -2.0 * PI..2.0 * PI, prop::option::of((-4.0f64..4.0, 0.0f64..4.0))).prop_map(
        |(length, angle, limits)| match limits {
            None => Link::new(length, angle),
            Some((lo, width)) => {
                let lim = JointLimits::new(lo, lo + width).unwrap();
                Link::new(length, lim.clamp(angle)).with_limits(lim)
            }
        },
    )
}

fn chain() -> impl Strategy<Value = Chain> {
    (prop::collection::vec(link(), 1..=20), -5.0f64..5.0, -5.0f64..5.0)
        .prop_map(|(links, x, y)| Chain::new([x, y], &links).unwrap())
}

/// A goal relative to the chain's base: near or inside the reach (`radius` in units of the
/// reach, up to 1.5), or anywhere in a box far beyond it; with or without an orientation.
#[derive(Debug, Clone)]
enum GoalSpec {
    Near { radius: f64, direction: f64 },
    Far { x: f64, y: f64 },
}

fn goal_spec() -> impl Strategy<Value = (GoalSpec, Option<f64>)> {
    let spec = prop_oneof![
        3 => (0.0f64..1.5, -PI..PI).prop_map(|(radius, direction)| GoalSpec::Near { radius, direction }),
        1 => (-1e4f64..1e4, -1e4f64..1e4).prop_map(|(x, y)| GoalSpec::Far { x, y }),
    ];
    (spec, prop::option::of(-10.0f64..10.0))
}

fn make_goal(chain: &Chain, (spec, orientation): &(GoalSpec, Option<f64>)) -> Goal {
    let base = chain.base();
    let (x, y) = match *spec {
        GoalSpec::Near { radius, direction } => {
            let r = radius * chain.max_reach();
            (base.x + r * libm::cos(direction), base.y + r * libm::sin(direction))
        }
        GoalSpec::Far { x, y } => (x, y),
    };
    match orientation {
        None => Goal::position(x, y).unwrap(),
        Some(phi) => Goal::with_orientation(x, y, *phi).unwrap(),
    }
}

/// Log-uniform in `[10^lo, 10^hi]`.
fn log_uniform(lo: f64, hi: f64) -> impl Strategy<Value = f64> {
    (lo..=hi).prop_map(|e| libm::pow(10.0, e))
}

prop_compose! {
    fn options()(
        method in prop::sample::select(Method::ALL.to_vec()),
        lambda in 0.0f64..=2.0,
        tolerance in log_uniform(-9.0, -1.0),
        angle_tolerance in log_uniform(-9.0, -1.0),
        orientation_weight in log_uniform(-2.0, 1.0),
        max_iterations in 0u32..300,
        gain in 0.1f64..2.0,
        max_step in prop::option::of(0.01f64..3.0),
        backtrack in prop_oneof![Just(0u32), 1u32..12],
        singular_threshold in prop_oneof![Just(0.0), log_uniform(-12.0, -3.0)],
        stall in prop::option::of((0.0f64..1e-6, 1u32..20)),
        record_every in prop::option::of(1u32..50),
        limits in prop::sample::select(LimitMode::ALL.to_vec()),
        restarts in prop::option::of((1u32..4, any::<u64>())),
        closed_form in any::<bool>(),
    ) -> SolveOptions {
        SolveOptions {
            method,
            lambda,
            tolerance,
            angle_tolerance,
            orientation_weight,
            max_iterations,
            gain,
            max_step,
            backtrack,
            singular_threshold,
            stall: stall.map(|(epsilon, window)| StallDetection { epsilon, window }),
            record_every,
            limits,
            restarts: restarts.map(|(attempts, seed)| Restarts { attempts, seed, time_budget: None }),
            closed_form,
            ..SolveOptions::default()
        }
    }
}

/// Chain, goal, options, per-joint rates (possibly none) and a start pose that may lie outside
/// the limits (the solver clamps it).
fn case() -> impl Strategy<Value = (Chain, Goal, SolveOptions, Vec<f64>)> {
    chain().prop_flat_map(|chain| {
        let n = chain.len();
        (
            Just(chain),
            goal_spec(),
            options(),
            prop::option::of(prop::collection::vec(0.0f64..2.0, n)),
            prop::option::of(prop::collection::vec(-10.0f64..10.0, n)),
        )
            .prop_map(|(chain, goal, mut opts, rates, start)| {
                let goal = make_goal(&chain, &goal);
                opts.rates = rates.unwrap_or_default();
                let start = start.unwrap_or_else(|| chain.start_pose().angles().to_vec());
                (chain, goal, opts, start)
            })
    })
}

/// 256 cases (about two seconds in a debug build) unless `PROPTEST_CASES` says otherwise.
fn config() -> Config {
    let cases = std::env::var("PROPTEST_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(256);
    Config { cases, failure_persistence: Some(Box::new(FileFailurePersistence::Off)), ..Config::default() }
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn a_solve_keeps_its_promises((chain, goal, opts, start) in case()) {
        let mut solver = Solver::new(opts.clone()).unwrap();
        let mut out = Outcome::default();
        match solver.solve_into(&chain, &start, &goal, &mut out) {
            Ok(()) => {}
            // The closed form exists for 2 links with a position goal and 3 with an orientation.
            Err(SolveError::NoClosedForm { links, .. }) => {
                prop_assert_eq!(opts.method, Method::Analytic);
                let fits = (links == 2 && goal.orientation().is_none()) || (links == 3 && goal.orientation().is_some());
                prop_assert!(!fits);
                return Ok(());
            }
            Err(e) => prop_assert!(false, "{}", e),
        }
        let n = chain.len();
        let scale = 1.0 + chain.max_reach() + (goal.target() - chain.base()).norm();

        // Finite numbers everywhere.
        prop_assert_eq!(out.pose.angles().len(), n);
        prop_assert!(out.pose.angles().iter().all(|a| a.is_finite()), "{:?}", out.pose);
        prop_assert!(out.error.is_finite() && out.error >= 0.0);
        prop_assert!(out.angle_error.is_finite() && (0.0..=PI).contains(&out.angle_error));
        prop_assert!(out.end_effector.position.x.is_finite() && out.end_effector.position.y.is_finite());
        prop_assert!(out.end_effector.orientation.is_finite());

        // Bounded, and the numbers describe the final pose.
        let attempts = 1 + opts.restarts.map_or(0, |r| r.attempts);
        prop_assert!(out.iterations <= opts.max_iterations.max(1) * attempts, "{:?}", out);
        prop_assert!(out.restarts < attempts);
        let ee = end_effector(&chain, out.pose.angles());
        prop_assert!((ee.position - out.end_effector.position).norm() <= 1e-9 * scale);
        prop_assert!((out.error - (ee.position - goal.target()).norm()).abs() <= 1e-9 * scale);
        if goal.orientation().is_none() {
            prop_assert_eq!(out.angle_error, 0.0);
        }

        // The status tells the truth.
        let within = out.error <= opts.tolerance && out.angle_error <= opts.angle_tolerance;
        prop_assert_eq!(out.status == Status::Reached, within, "{:?}", out);
        if out.status == Status::Unreachable {
            // Out of reach even without limits, or outside the exact region under them.
            let outside = out.reach_distance.is_some_and(|d| d > opts.tolerance);
            prop_assert!(goal.is_out_of_reach(&chain, opts.tolerance) || outside);
        }

        // Every enforcing mode keeps every joint, final and recorded, within its limits.
        if opts.limits != LimitMode::Ignore {
            for frame_angles in std::iter::once(out.pose.angles()).chain(out.frames.iter().map(|f| f.angles)) {
                for (a, lim) in frame_angles.iter().zip(chain.limits()) {
                    if let Some(lim) = lim {
                        prop_assert!(lim.contains(*a), "{} outside {:?}", a, lim);
                    }
                }
            }
        }

        // Frames: none unless asked; else from 0 to the last iteration, increasing, each one's
        // joints the forward kinematics of its angles.
        match opts.record_every {
            None => prop_assert!(out.frames.is_empty()),
            Some(k) => {
                let iterations: Vec<u32> = out.frames.iter().map(|f| f.iteration).collect();
                prop_assert_eq!(iterations.first(), Some(&0));
                prop_assert_eq!(iterations.last(), Some(&out.iterations));
                prop_assert!(iterations.windows(2).all(|w| w[0] < w[1]));
                prop_assert!(iterations[..iterations.len() - 1].iter().all(|i| i % k == 0));
                let last = out.frames.get(out.frames.len() - 1).unwrap();
                prop_assert_eq!(last.angles, out.pose.angles());
                for f in out.frames.iter() {
                    prop_assert!(f.angles.iter().all(|a| a.is_finite()));
                    let fk = joint_positions(&chain, f.angles);
                    for (p, q) in f.joints.iter().zip(&fk) {
                        prop_assert!((p - q).norm() <= 1e-9 * scale);
                    }
                }
            }
        }

        // With the line search on, every accepted step lowers the task error, so the final error
        // never exceeds the (clamped) start's.
        if opts.backtrack > 0 {
            let mut first = start.clone();
            if opts.limits != LimitMode::Ignore {
                for (a, lim) in first.iter_mut().zip(chain.limits()) {
                    if let Some(lim) = lim {
                        *a = lim.clamp(*a);
                    }
                }
            }
            let task_error = |angles: &[f64]| {
                let ee = end_effector(&chain, angles);
                let d = (ee.position - goal.target()).norm();
                let turn = goal.orientation().map_or(0.0, |g| opts.orientation_weight * ikarus::solve::wrap_angle(g - ee.orientation));
                d * d + turn * turn
            };
            let (before, after) = (task_error(&first), task_error(out.pose.angles()));
            prop_assert!(after <= before * (1.0 + 1e-12) + 1e-18, "{} > {}", after, before);
        }

        // The same solve again, on the reused solver and outcome, is bit for bit the same.
        let again = solver.solve(&chain, &chain.pose_ignoring_limits(start.clone()).unwrap(), &goal).unwrap();
        prop_assert_eq!(&again, &out);
    }
}

/// The library's distance (`solve/attempt.rs`): `√(dx² + dy²)`, by `hypot` where the sum of
/// squares overflows or is subnormal, saturated at `f64::MAX`. `libm`'s `hypot`, as the
/// library's `math` module calls it, so that the two agree bit for bit on every target.
fn distance(dx: f64, dy: f64) -> f64 {
    let squared = dx * dx + dy * dy;
    let d = if squared.is_finite() && squared >= f64::MIN_POSITIVE { squared.sqrt() } else { libm::hypot(dx, dy) };
    d.min(f64::MAX)
}

/// The promises that hold at any scale: every number finite, the outcome measured on its own
/// pose by a fresh forward-kinematics pass (bit for bit) and its status judged from that,
/// `unreachable` only for goals out of reach, the iterations under the caps, every angle
/// (final and recorded) inside its limits when they are enforced, and the same solve again
/// giving the same bits.
fn check_at_any_scale(chain: &Chain, goal: &Goal, opts: &SolveOptions, start: &[f64]) -> Result<(), TestCaseError> {
    let mut out = Outcome::default();
    match Solver::new(opts.clone()).unwrap().solve_into(chain, start, goal, &mut out) {
        Ok(()) => {}
        Err(SolveError::NoClosedForm { .. }) if opts.method == Method::Analytic => return Ok(()),
        Err(e) => return Err(TestCaseError::fail(e.to_string())),
    }
    let angles = out.pose.angles();
    prop_assert!(angles.len() == chain.len() && angles.iter().all(|a| a.is_finite()), "{:?}", out);
    let ee = end_effector(chain, angles);
    prop_assert_eq!(out.end_effector, ee);
    prop_assert!(ee.position.x.is_finite() && ee.position.y.is_finite() && ee.orientation.is_finite());
    let error = distance(goal.target().x - ee.position.x, goal.target().y - ee.position.y);
    let angle_error = goal.orientation().map_or(0.0, |g| ikarus::solve::wrap_angle(g - ee.orientation).abs());
    prop_assert_eq!(out.error.to_bits(), error.to_bits(), "{} vs {}", out.error, error);
    prop_assert_eq!(out.angle_error.to_bits(), angle_error.to_bits());
    let within = error <= opts.tolerance && angle_error <= opts.angle_tolerance;
    prop_assert_eq!(out.status == Status::Reached, within, "{:?}", out.status);
    if out.status == Status::Unreachable {
        // Out of reach even without limits, or outside the exact region under them.
        let outside = out.reach_distance.is_some_and(|d| d > opts.tolerance);
        prop_assert!(goal.is_out_of_reach(chain, opts.tolerance) || outside);
    }
    let attempts = 1 + opts.restarts.map_or(0, |r| r.attempts);
    prop_assert!(out.iterations <= opts.max_iterations.max(1) * attempts);
    if opts.limits != LimitMode::Ignore {
        for frame_angles in std::iter::once(angles).chain(out.frames.iter().map(|f| f.angles)) {
            for (a, lim) in frame_angles.iter().zip(chain.limits()) {
                prop_assert!(a.is_finite() && lim.is_none_or(|l| l.contains(*a)), "{} outside {:?}", a, lim);
            }
        }
    }
    for f in out.frames.iter() {
        prop_assert!(f.joints.iter().all(|p| p.x.is_finite() && p.y.is_finite()));
    }
    // Restarts end on the best attempt: never worse than the first one alone.
    if out.status != Status::Reached && opts.restarts.is_some() {
        let task_error = |angles: &[f64]| {
            let ee = end_effector(chain, angles);
            let d = distance(goal.target().x - ee.position.x, goal.target().y - ee.position.y);
            let turn = goal
                .orientation()
                .map_or(0.0, |g| opts.orientation_weight * ikarus::solve::wrap_angle(g - ee.orientation));
            d * d + turn * turn
        };
        let once = SolveOptions { restarts: None, ..opts.clone() };
        let first = Solver::new(once)
            .unwrap()
            .solve(chain, &chain.pose_ignoring_limits(start.to_vec()).unwrap(), goal)
            .unwrap();
        let (before, after) = (task_error(first.pose.angles()), task_error(angles));
        prop_assert!(after <= before * (1.0 + 1e-12) || after <= f64::MIN_POSITIVE, "{} > {}", after, before);
    }
    let mut again = Outcome::default();
    Solver::new(opts.clone()).unwrap().solve_into(chain, start, goal, &mut again).unwrap();
    prop_assert_eq!(&again, &out);
    Ok(())
}

/// A chain of 1 to 12 links whose lengths run from 1e-9 to 1e9, mixed in one chain, with
/// optional limits (some wider than a turn, some a single angle), based anywhere within its
/// reach of the origin.
fn extreme_chain() -> impl Strategy<Value = Chain> {
    let link =
        (-9.0f64..=9.0, -PI..PI, prop::option::of((-4.0f64..4.0, prop_oneof![Just(0.0), 0.0f64..4.0, 6.3f64..20.0])))
            .prop_map(|(exponent, angle, limits)| {
                let length = libm::pow(10.0, exponent);
                match limits {
                    None => Link::new(length, angle),
                    Some((lo, width)) => {
                        let lim = JointLimits::new(lo, lo + width).unwrap();
                        Link::new(length, lim.clamp(angle)).with_limits(lim)
                    }
                }
            });
    (prop::collection::vec(link, 1..=12), -1.0f64..1.0, -1.0f64..1.0).prop_map(|(links, x, y)| {
        let reach: f64 = links.iter().map(|l| l.length).sum();
        Chain::new([x * reach, y * reach], &links).unwrap()
    })
}

/// A chain of 1 to 4 links of lengths up to 1e150 (so that its area, of order reach², is
/// still a finite number), some with limits.
fn huge_chain() -> impl Strategy<Value = Chain> {
    let link = (50.0f64..150.0, -PI..PI, prop::option::of(-2.0f64..0.0)).prop_map(|(exponent, angle, lo)| {
        let length = libm::pow(10.0, exponent) / 4.0;
        match lo {
            None => Link::new(length, angle),
            Some(lo) => {
                let lim = JointLimits::new(lo, lo + 3.0).unwrap();
                Link::new(length, lim.clamp(angle)).with_limits(lim)
            }
        }
    });
    prop::collection::vec(link, 1..=4).prop_map(|links| Chain::new([0.0, 0.0], &links).unwrap())
}

/// A method and a limit mode it supports ([`Method::supports`]), every pair equally likely.
fn method_and_mode() -> impl Strategy<Value = (Method, LimitMode)> {
    let pairs: Vec<(Method, LimitMode)> = Method::ALL
        .iter()
        .flat_map(|&m| LimitMode::ALL.iter().filter(move |&&l| m.supports(l)).map(move |&l| (m, l)))
        .collect();
    prop::sample::select(pairs)
}

prop_compose! {
    fn extreme_options(reach: f64)(
        (method, limits) in method_and_mode(),
        lambda in prop_oneof![Just(0.0), log_uniform(-4.0, 1.0)],
        // Absolute (hard at 1e9) or relative to the reach.
        tolerance in log_uniform(-12.0, -1.0),
        relative in any::<bool>(),
        angle_tolerance in log_uniform(-12.0, -1.0),
        orientation_weight in log_uniform(-3.0, 3.0),
        max_iterations in 0u32..100,
        gain in log_uniform(-3.0, 1.0),
        max_step in prop::option::of(log_uniform(-3.0, 1.0)),
        backtrack in 0u32..=ikarus::solve::MAX_BACKTRACK,
        stall in prop::option::of((prop_oneof![Just(0.0), log_uniform(-12.0, -3.0)],
            prop_oneof![1u32..20, Just(1000u32), Just(u32::MAX)])),
        record_every in prop::option::of(1u32..20),
        restarts in prop::option::of((1u32..=3, any::<u64>())),
        closed_form in any::<bool>(),
    ) -> SolveOptions {
        SolveOptions {
            method,
            lambda,
            tolerance: if relative { tolerance * reach } else { tolerance },
            angle_tolerance,
            orientation_weight,
            max_iterations,
            gain,
            max_step,
            backtrack,
            stall: stall.map(|(epsilon, window)| StallDetection { epsilon, window }),
            record_every,
            limits,
            restarts: restarts.map(|(attempts, seed)| Restarts { attempts, seed, time_budget: None }),
            closed_form,
            ..SolveOptions::default()
        }
    }
}

/// Chain of extreme magnitudes, a goal near it, far away (up to 1e6 reaches) or on its base,
/// maybe with an orientation (up to 1e6 rad), options, and a start pose: the chain's, one
/// outside the limits, or one of huge angles.
fn extreme_case() -> impl Strategy<Value = (Chain, Goal, SolveOptions, Vec<f64>)> {
    prop_oneof![3 => extreme_chain(), 1 => huge_chain()].prop_flat_map(|chain| {
        let n = chain.len();
        let reach = chain.max_reach();
        let goal = (
            prop_oneof![3 => 0.0f64..1.5, 1 => log_uniform(0.0, 6.0), 1 => Just(0.0)],
            -PI..PI,
            prop::option::of(prop_oneof![-10.0f64..10.0, log_uniform(3.0, 6.0)]),
        );
        let start = prop_oneof![
            2 => Just(chain.start_pose().angles().to_vec()),
            1 => prop::collection::vec(-10.0f64..10.0, n),
            1 => prop::collection::vec(log_uniform(3.0, 300.0), n),
        ];
        (Just(chain), goal, extreme_options(reach), start).prop_map(|(chain, (radius, direction, phi), opts, start)| {
            let b = chain.base();
            let r = radius * chain.max_reach();
            let (x, y) = (b.x + r * libm::cos(direction), b.y + r * libm::sin(direction));
            let goal = match phi {
                None => Goal::position(x, y).unwrap(),
                Some(phi) => Goal::with_orientation(x, y, phi).unwrap(),
            };
            (chain, goal, opts, start)
        })
    })
}

proptest! {
    #![proptest_config(config())]

    /// Issue 11: the status was judged on CCD's rotated joint positions, not on the pose it
    /// returned (`reached` 3.9e-6 away with a tolerance of 1e-6 on lengths from 1e-9 to 1e9),
    /// and overflowing steps returned NaN. At any scale, every promise of an outcome holds.
    #[test]
    fn extreme_solves_keep_their_promises((chain, goal, opts, start) in extreme_case()) {
        check_at_any_scale(&chain, &goal, &opts, &start)?;
    }

    /// The ordinary cases keep the scale-free promises too: the outcome is its own pose's, bit
    /// for bit, for every method with every limit mode it supports.
    #[test]
    fn ordinary_solves_are_measured_on_their_pose((chain, goal, mut opts, start) in case(), pair in method_and_mode()) {
        (opts.method, opts.limits) = pair;
        check_at_any_scale(&chain, &goal, &opts, &start)?;
    }
}

proptest! {
    #![proptest_config(config())]

    /// The workspace of any valid chain, ordinary or of extreme magnitudes, with or without its
    /// limits: no panic, finite numbers, an area within the grid, the same bits twice (and on
    /// rayon's pool as on one thread).
    #[test]
    fn any_workspace_is_finite_and_deterministic(
        chain in prop_oneof![chain(), extreme_chain(), huge_chain()],
        resolution in 8u32..=48,
        limits in any::<bool>(),
        samples in prop::option::of(1u64..=64),
        seed in any::<u64>(),
    ) {
        use ikarus::reach::{WorkspaceOptions, sample};
        let options =
            WorkspaceOptions { resolution, limits, samples: samples.or(Some(64)), seed, parallel: false, interrupt: None };
        let ws = sample(&chain, &options).unwrap();
        let h = ws.cell_size();
        prop_assert!(h.is_finite() && h > 0.0, "{}", h);
        prop_assert!(ws.origin().x.is_finite() && ws.origin().y.is_finite());
        prop_assert!(ws.occupied_cells() <= u64::from(resolution).pow(2));
        let side = h * f64::from(resolution);
        let grid_area = side * side;
        prop_assert!(ws.area().is_finite() && ws.area() >= 0.0 && ws.area() <= grid_area * (1.0 + 1e-12));
        let annulus = ws.annulus();
        prop_assert!(annulus.outer.is_finite() && annulus.inner.is_finite() && annulus.area().is_finite());
        prop_assert_eq!(&sample(&chain, &options).unwrap(), &ws);
        let parallel = WorkspaceOptions { parallel: true, ..options };
        prop_assert_eq!(&sample(&chain, &parallel).unwrap(), &ws);
    }
}
