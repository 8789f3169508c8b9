//! Skeleton solves (issue 12): jointly reachable target sets on the shipped rigs are reached with
//! limits on, pins hold, priorities, the animator's controls, per-effector statuses, and the
//! one-branch skeleton against the chain. Every claim is checked by a fresh forward-kinematics
//! pass of the returned angles, not taken from the solver.

use nalgebra::Point2;

use crate::fixtures::{deg, random_rig_pose, rig};
use crate::math;
use crate::rng::SplitMix64;
use crate::skeleton::Skeleton;
use crate::{
    Bend, Goal, LimitMode, Method, Outcome, Pin, Priority, RigGoal, RigTask, RigTaskError, SolveError, SolveOptions,
    Solver, Status,
};

/// Tips and directions of `angles` by the skeleton's own forward kinematics.
fn fk(skeleton: &Skeleton, angles: &[f64]) -> (Vec<Point2<f64>>, Vec<f64>) {
    let n = skeleton.len();
    let (mut starts, mut tips, mut dirs) = (vec![Point2::origin(); n], vec![Point2::origin(); n], vec![0.0; n]);
    skeleton.forward_into(angles, &mut starts, &mut tips, &mut dirs);
    (tips, dirs)
}

fn bone(skeleton: &Skeleton, name: &str) -> usize {
    skeleton.index_of(name).unwrap_or_else(|| panic!("no bone {name}"))
}

/// The bones without children: the fingertips, hands, feet and head.
fn leaves(skeleton: &Skeleton) -> Vec<usize> {
    (0..skeleton.len()).filter(|&i| skeleton.children(i).len() == 0).collect()
}

/// Checks an outcome against its task by forward kinematics: every effector within the
/// tolerances of its target (a pin's: where it started), angles inside the limits. Returns
/// whether all are, and asserts the outcome says the same.
fn verify(skeleton: &Skeleton, start: &[f64], task: &RigTask, opts: &SolveOptions, out: &Outcome) -> bool {
    let (tips, dirs) = fk(skeleton, out.pose.angles());
    let (start_tips, start_dirs) = fk(skeleton, start);
    let mut all = true;
    let targets = task
        .goals
        .iter()
        .map(|g| (g.bone, g.goal.target(), g.goal.orientation()))
        .chain(task.pins.iter().map(|p| (p.bone, start_tips[p.bone], p.orientation.then_some(start_dirs[p.bone]))));
    for (k, (b, target, orientation)) in targets.enumerate() {
        let error = (tips[b] - target).norm();
        let angle_error = orientation.map_or(0.0, |o| crate::angle::wrap_angle(o - dirs[b]).abs());
        let within = error <= opts.tolerance * (1.0 + 1e-9) && angle_error <= opts.angle_tolerance * (1.0 + 1e-9);
        let reported = out.effectors[k];
        assert_eq!(reported.bone, b);
        assert_eq!(reported.tip, tips[b], "the reported tip is the pose's");
        // Each effector's own status says whether it is within the tolerances (it was left
        // unjudged on a reached solve in release builds once).
        assert_eq!(reported.status == Status::Reached, within, "effector {k} at {error:e}: {:?}", reported.status);
        all &= within;
    }
    let inside = skeleton.limits().iter().zip(out.pose.angles()).all(|(l, a)| l.is_none_or(|l| l.contains(*a)));
    assert!(inside || opts.limits == LimitMode::Ignore, "angles outside the limits: {:?}", out.pose.angles());
    assert_eq!(out.status == Status::Reached, all, "{:?}", out.status);
    all
}

/// Targets at `bones`' tips for a random pose inside the limits: jointly reachable.
fn reachable_task(skeleton: &Skeleton, bones: &[usize], rng: &mut SplitMix64) -> RigTask {
    let truth = random_rig_pose(skeleton, rng);
    let (tips, _) = fk(skeleton, &truth);
    let goals = bones.iter().map(|&b| RigGoal::new(b, Goal::position(tips[b].x, tips[b].y).unwrap())).collect();
    RigTask::new(goals, Vec::new())
}

#[test]
fn puppet_hands_and_feet_are_reached_together_within_the_limits() {
    let puppet = rig("puppet");
    let bones: Vec<usize> = ["right_hand", "left_hand", "right_foot", "left_foot"].map(|n| bone(&puppet, n)).to_vec();
    let mut rng = SplitMix64(12);
    for limits in [LimitMode::Lock, LimitMode::Clamp, LimitMode::NullSpace, LimitMode::Weighted] {
        let opts = SolveOptions { limits, ..SolveOptions::default() };
        let mut solver = Solver::new(opts.clone()).unwrap();
        let (mut reached, total) = (0, 100);
        for _ in 0..total {
            let task = reachable_task(&puppet, &bones, &mut rng);
            let out = solver.solve_rig(&puppet, puppet.start_angles(), &task).unwrap();
            reached += usize::from(verify(&puppet, puppet.start_angles(), &task, &opts, &out));
        }
        println!("puppet 4 effectors, {limits:?}: {reached}/{total}");
        assert!(reached >= total * 98 / 100, "{limits:?}: {reached}/{total}");
    }
}

#[test]
fn the_hand_reaches_five_fingertips() {
    let hand = rig("hand");
    let tips = leaves(&hand);
    assert_eq!(tips.len(), 5);
    let opts = SolveOptions::default();
    let mut solver = Solver::new(opts.clone()).unwrap();
    let mut rng = SplitMix64(5);
    let (mut reached, total) = (0, 100);
    for _ in 0..total {
        let task = reachable_task(&hand, &tips, &mut rng);
        let out = solver.solve_rig(&hand, hand.start_angles(), &task).unwrap();
        reached += usize::from(verify(&hand, hand.start_angles(), &task, &opts, &out));
    }
    println!("hand 5 fingertips: {reached}/{total}");
    assert!(reached >= total * 98 / 100, "{reached}/{total}");
}

/// Feet pinned (position and direction), hands sent to targets that the upper body can reach:
/// the feet do not move.
#[test]
fn pins_hold_while_the_hands_reach() {
    let puppet = rig("puppet");
    let hands = ["right_hand", "left_hand"].map(|n| bone(&puppet, n));
    let feet = ["right_foot", "left_foot"].map(|n| bone(&puppet, n));
    let legs: Vec<usize> = feet.iter().flat_map(|&f| puppet.path(f).to_vec()).collect();
    let opts = SolveOptions::default();
    let mut solver = Solver::new(opts.clone()).unwrap();
    let mut rng = SplitMix64(77);
    let start = puppet.start_angles();
    let (mut reached, total) = (0, 100);
    for _ in 0..total {
        let mut truth = random_rig_pose(&puppet, &mut rng);
        for &j in &legs {
            truth[j] = start[j];
        }
        let (tips, _) = fk(&puppet, &truth);
        let goals = hands.iter().map(|&b| RigGoal::new(b, Goal::position(tips[b].x, tips[b].y).unwrap())).collect();
        let task = RigTask::new(goals, feet.iter().map(|&f| Pin::new(f)).collect());
        let out = solver.solve_rig(&puppet, start, &task).unwrap();
        reached += usize::from(verify(&puppet, start, &task, &opts, &out));
        for e in &out.effectors[2..] {
            assert!(e.pinned && e.error <= opts.tolerance, "a pin slid by {:e}", e.error);
        }
    }
    assert!(reached >= total * 98 / 100, "{reached}/{total}");
}

fn three_bones() -> Skeleton {
    let bones = [
        crate::Bone::new("a", 1.0, 0.3),
        crate::Bone::new("b", 1.0, 0.3).with_parent("a"),
        crate::Bone::new("c", 1.0, 0.3).with_parent("b"),
    ];
    Skeleton::new([0.0, 0.0], &bones).unwrap()
}

/// A three-bone arm: the primary goal puts the tip at (1.5, 0), which leaves one degree of
/// freedom; the secondary goal asks the first joint's tip (always 1 from the base) for a point
/// it cannot reach. The primary goal is met to the tolerance whatever the secondary asks.
/// Where the secondary's best place on its circle is compatible with the primary, the solve
/// finds it (checked by brute force over the free angle). Where it is not (the best compatible
/// place is where the last two bones are straight, a singular pose), the primary still wins,
/// and with equal priority instead the two trade and the primary is missed.
#[test]
fn a_secondary_goal_moves_only_in_what_the_primary_leaves_free() {
    let arm = three_bones();
    let opts = SolveOptions { restarts: None, ..SolveOptions::default() };
    let mut solver = Solver::new(opts.clone()).unwrap();
    let tip = Point2::new(1.5, 0.0);
    let task_for = |want: Point2<f64>, priority| {
        let primary = RigGoal::new(2, Goal::position(tip.x, tip.y).unwrap());
        let secondary = RigGoal::new(0, Goal::position(want.x, want.y).unwrap()).with_priority(priority);
        RigTask::new(vec![primary, secondary], vec![])
    };
    for want in [Point2::new(0.0, 2.0), Point2::new(0.3, -3.0)] {
        let out = solver.solve_rig(&arm, arm.start_angles(), &task_for(want, Priority::Secondary)).unwrap();
        assert_eq!(out.effectors[0].status, Status::Reached, "{want}: {out:?}");
        // Brute force: the first joint's tip at angle a is feasible when the other two bones
        // reach from it to the tip (distance ≤ 2).
        let best = (0..200_000)
            .map(|k| -std::f64::consts::PI + 2.0 * std::f64::consts::PI * f64::from(k) / 200_000.0)
            .map(|a| Point2::new(math::cos(a), math::sin(a)))
            .filter(|e| (tip - e).norm() <= 2.0)
            .map(|e| (want - e).norm())
            .fold(f64::INFINITY, f64::min);
        let got = out.effectors[1].error;
        assert!(got >= best - 1e-6 && got <= best + 1e-6, "{want}: secondary {got} vs best {best}");
    }
    let want = Point2::new(-2.0, 1.0);
    let before = (want - Point2::new(math::cos(0.3f64), math::sin(0.3f64))).norm();
    let out = solver.solve_rig(&arm, arm.start_angles(), &task_for(want, Priority::Secondary)).unwrap();
    assert_eq!(out.effectors[0].status, Status::Reached, "{out:?}");
    assert!(out.effectors[1].error < before, "{out:?}");
    let traded = solver.solve_rig(&arm, arm.start_angles(), &task_for(want, Priority::Primary)).unwrap();
    assert!(traded.effectors[0].error > 1e-3, "{traded:?}");
}

/// Bend: the elbow's sign picks which of the two solutions; both reach the same target.
#[test]
fn bend_picks_the_side_of_a_two_bone_limb() {
    let arm = Skeleton::new(
        [0.0, 0.0],
        &[crate::Bone::new("upper", 1.0, 0.3), crate::Bone::new("fore", 1.0, 0.3).with_parent("upper")],
    )
    .unwrap();
    let opts = SolveOptions::default();
    let mut solver = Solver::new(opts.clone()).unwrap();
    for (bend, sign) in [(Bend::Positive, 1.0), (Bend::Negative, -1.0)] {
        let goal = RigGoal::new(1, Goal::position(1.2, 0.4).unwrap()).with_bend(bend);
        let task = RigTask::new(vec![goal], vec![]);
        let out = solver.solve_rig(&arm, arm.start_angles(), &task).unwrap();
        assert!(verify(&arm, arm.start_angles(), &task, &opts, &out), "{bend:?}: {out:?}");
        assert!(sign * out.pose.angles()[1] > 0.1, "{bend:?}: {:?}", out.pose.angles());
    }
    // A bend the joint's limits exclude is refused.
    let limited = Skeleton::new(
        [0.0, 0.0],
        &[
            crate::Bone::new("upper", 1.0, 0.3),
            crate::Bone::new("fore", 1.0, 0.3)
                .with_parent("upper")
                .with_limits(crate::JointLimits::new(0.1, 2.0).unwrap()),
        ],
    )
    .unwrap();
    let task = RigTask::new(vec![RigGoal::new(1, Goal::position(1.2, 0.4).unwrap()).with_bend(Bend::Negative)], vec![]);
    let err = solver.solve_rig(&limited, limited.start_angles(), &task).unwrap_err();
    assert!(matches!(err, SolveError::Rig(RigTaskError::BendOutsideLimits { .. })), "{err}");
    assert_eq!(err.to_string(), "goal \"fore\".bend: the joint's limits leave no angle on that side");
}

/// Mix 0 keeps the pose before; mix ½ is halfway, joint by joint.
#[test]
fn mix_blends_the_pose_before_and_the_result() {
    let puppet = rig("puppet");
    let hand = bone(&puppet, "right_hand");
    let mut rng = SplitMix64(3);
    let task = reachable_task(&puppet, &[hand], &mut rng);
    let mut solver = Solver::new(SolveOptions::default()).unwrap();
    let full = solver.solve_rig(&puppet, puppet.start_angles(), &task).unwrap();
    assert_eq!(full.status, Status::Reached);
    let none = solver.solve_rig(&puppet, puppet.start_angles(), &RigTask { mix: 0.0, ..task.clone() }).unwrap();
    assert_eq!(none.pose.angles(), puppet.start_angles());
    let half = solver.solve_rig(&puppet, puppet.start_angles(), &RigTask { mix: 0.5, ..task.clone() }).unwrap();
    for ((h, f), s) in half.pose.angles().iter().zip(full.pose.angles()).zip(puppet.start_angles()) {
        assert!((h - (s + 0.5 * (f - s))).abs() < 1e-15);
    }
    let (tips, _) = fk(&puppet, half.pose.angles());
    assert_eq!(half.effectors[0].tip, tips[hand]);
    let err = solver.solve_rig(&puppet, puppet.start_angles(), &RigTask { mix: 1.5, ..task }).unwrap_err();
    assert_eq!(err.to_string(), "mix: must be from 0 to 1, got 1.5");
}

/// Softness: a goal at full stretch is drawn in, so the limb stops short of straight; goals
/// well inside are untouched.
#[test]
fn softness_keeps_the_limb_from_snapping_straight() {
    let arm = Skeleton::new(
        [0.0, 0.0],
        &[crate::Bone::new("upper", 1.0, 0.3), crate::Bone::new("fore", 1.0, 0.3).with_parent("upper")],
    )
    .unwrap();
    let mut solver = Solver::new(SolveOptions::default()).unwrap();
    let mut last = 0.0;
    for d in [1.5, 1.8, 1.95, 2.0, 2.5] {
        let goal = RigGoal::new(1, Goal::position(d, 0.0).unwrap()).with_softness(0.3);
        let out = solver.solve_rig(&arm, arm.start_angles(), &RigTask::new(vec![goal], vec![])).unwrap();
        let target = out.effectors[0].target;
        assert_eq!(out.effectors[0].status, Status::Reached, "{d}");
        if d <= 1.7 {
            assert_eq!(target, Point2::new(d, 0.0));
        } else {
            assert!(target.x < d && target.x < 2.0 && target.x > last, "{d}: {target}");
        }
        // The elbow never straightens.
        assert!(out.pose.angles()[1].abs() > 1e-3, "{d}");
        last = target.x;
    }
}

/// One goal out of every pose's reach. With equal priority the answer is the weighted
/// least-squares best of both (the spine leans toward the unreachable goal, and the other hand
/// may miss its own); made secondary, it no longer costs the reachable goal anything: that one
/// is reached, the unreachable one is named and stretched toward.
#[test]
fn an_unreachable_goal_is_named_and_as_secondary_costs_the_others_nothing() {
    let puppet = rig("puppet");
    let (right, left) = (bone(&puppet, "right_hand"), bone(&puppet, "left_hand"));
    let mut rng = SplitMix64(8);
    let mut task = reachable_task(&puppet, &[left], &mut rng);
    task.goals.insert(0, RigGoal::new(right, Goal::position(50.0, 0.0).unwrap()));
    let opts = SolveOptions { limits: LimitMode::Ignore, ..SolveOptions::default() };
    let mut solver = Solver::new(opts.clone()).unwrap();
    let equal = solver.solve_rig(&puppet, puppet.start_angles(), &task).unwrap();
    assert_eq!(equal.status, Status::Unreachable);
    assert_eq!(equal.effectors[0].status, Status::Unreachable);
    task.goals[0].priority = Priority::Secondary;
    let out = solver.solve_rig(&puppet, puppet.start_angles(), &task).unwrap();
    assert_eq!(out.status, Status::Unreachable);
    assert_eq!(out.effectors[0].status, Status::Unreachable);
    assert_eq!(out.effectors[1].status, Status::Reached, "{out:?}");
    assert!(verify(&puppet, puppet.start_angles(), &RigTask::new(vec![task.goals[1].clone()], vec![]), &opts, &{
        let mut one = out.clone();
        one.effectors.remove(0);
        one.status = Status::Reached;
        one
    }));
    // Stretched toward (50, 0) as far as the left hand's goal allows.
    assert!(out.effectors[0].tip.x > 0.5, "{:?}", out.effectors[0]);
    assert!(out.effectors[0].error < equal.effectors[0].error + 1.0, "{out:?}");
}

/// A skeleton with one branch solves a chain's goals like the chain solver: the same statuses,
/// poses reaching the same targets.
#[test]
fn a_one_branch_skeleton_solves_like_its_chain() {
    let chain = crate::fixtures::seed_arm_limited();
    let skeleton = crate::fixtures::chain_written_as_rig(&chain);
    let mut rng = SplitMix64(21);
    // The chain's search against the skeleton's (skeletons have no region verdict).
    let opts = SolveOptions { closed_form: false, reach_verdict: false, ..SolveOptions::default() };
    let mut solver = Solver::new(opts.clone()).unwrap();
    let mut agree = 0;
    for _ in 0..200 {
        let (x, y) = (rng.range(-6.5, 6.5), rng.range(-6.5, 6.5));
        let goal = Goal::position(x, y).unwrap();
        let c = solver.solve(&chain, chain.start_pose(), &goal).unwrap();
        let task = RigTask::new(vec![RigGoal::new(chain.len() - 1, goal)], vec![]);
        let s = solver.solve_rig(&skeleton, chain.start_pose().angles(), &task).unwrap();
        agree += usize::from(c.status == s.status);
        if s.status == Status::Reached {
            assert!(s.error <= opts.tolerance);
        }
    }
    assert!(agree >= 196, "{agree}/200");
}

#[test]
fn methods_without_a_rig_solver_and_bad_tasks_are_refused_in_one_line() {
    let puppet = rig("puppet");
    let hand = bone(&puppet, "right_hand");
    let task = RigTask::new(vec![RigGoal::new(hand, Goal::position(0.5, 1.0).unwrap())], vec![]);
    for method in Method::ALL {
        let mut solver = Solver::new(SolveOptions { method, ..SolveOptions::default() }).unwrap();
        let result = solver.solve_rig(&puppet, puppet.start_angles(), &task);
        assert_eq!(result.is_ok(), method.solves_rigs(), "{method:?}");
        if let Err(e) = result {
            assert_eq!(
                e.to_string(),
                format!("method {}: solves chains only; a rig needs transpose, pinv, dls, sdls or lm", method.name())
            );
        }
    }
    let mut solver = Solver::new(SolveOptions::default()).unwrap();
    let cases: Vec<(RigTask, &str)> = vec![
        (RigTask::default(), "goals: a rig solve needs at least one goal or pin, got none"),
        (
            RigTask::new(vec![RigGoal::new(99, Goal::position(0.0, 0.0).unwrap())], vec![]),
            "goal: bone 99 does not exist (the rig has 16 bones)",
        ),
        (
            RigTask::new(vec![task.goals[0].clone()], vec![Pin::new(hand)]),
            "pin \"right_hand\": the bone already has a goal; one goal or pin per bone",
        ),
        (
            RigTask::new(vec![task.goals[0].clone().with_weight(0.0)], vec![]),
            "goal \"right_hand\".weight: must be a finite number > 0, got 0",
        ),
        (
            RigTask::new(vec![task.goals[0].clone().with_softness(-1.0)], vec![]),
            "goal \"right_hand\".softness: must be a finite number >= 0, got -1",
        ),
        (
            RigTask::new(vec![RigGoal::new(0, Goal::position(0.0, 0.0).unwrap()).with_bend(Bend::Positive)], vec![]),
            "goal \"pelvis\".bend: the bone has no parent, so no two-bone limb to bend",
        ),
    ];
    for (task, message) in cases {
        assert_eq!(solver.solve_rig(&puppet, puppet.start_angles(), &task).unwrap_err().to_string(), message);
    }
    let err = solver.solve_rig(&puppet, &[0.0; 3], &task).unwrap_err();
    assert_eq!(err.to_string(), "start: expected 16 angles (one per joint), got 3");
    let _ = deg(0.0);
}

/// The first level solved again alone, when it needs a restart, draws the restart into its own
/// buffer: it once drew into the buffer its start had been taken from, found it empty, and
/// panicked (found by the API's random rig requests: two roots, a secondary soft goal, one
/// restart, 15 iterations).
#[test]
fn the_first_level_solved_again_may_restart() {
    use crate::chain::JointLimits;
    use crate::skeleton::Bone;
    let bones = [
        Bone::new("b0", 1.7414475684369994, 0.0).with_limits(JointLimits::new(0.0, 0.0).unwrap()),
        Bone::new("arm.1", 0.1, 0.0).with_parent("b0"),
        Bone::new("b2", 0.1, 0.0).with_parent("b0"),
        Bone::new("b3", 1.4046011522229889, 0.0).with_parent("b0"),
        Bone::new("arm.4", 0.1, 0.0).with_parent("b0"),
        Bone::new("b5", 1.9432073648833526, 0.0)
            .with_parent("b0")
            .with_limits(JointLimits::new(deg(-38.31447409962215), deg(15.642333156647858)).unwrap()),
        Bone::new("b6", 1.251218630032371, deg(-64.90466514678133)),
    ];
    let skeleton = Skeleton::new([0.0, 0.0], &bones).unwrap();
    let mut soft = RigGoal::new(2, Goal::position(2.033754016391833, -2.2348167489170563).unwrap())
        .with_priority(Priority::Secondary);
    soft.softness = 1.0006867376073978;
    let task = RigTask::new(
        vec![RigGoal::new(3, Goal::position(1.9749846143471854, -1.7456543883997504).unwrap()), soft],
        vec![],
    );
    let opts = SolveOptions {
        max_iterations: 15,
        record_every: Some(17),
        restarts: Some(crate::Restarts { attempts: 1, ..crate::Restarts::default() }),
        ..SolveOptions::default()
    };
    let out = Solver::new(opts).unwrap().solve_rig(&skeleton, skeleton.start_angles(), &task).unwrap();
    assert_eq!(out.pose.angles().len(), 7);
    assert!(out.restarts >= 1, "{out:?}");
}

/// The puppet without its rest-pose preference: every bone's stiffness 0 (the solver of
/// before issue 24).
fn without_rest_pose(skeleton: &Skeleton) -> Skeleton {
    let bones: Vec<_> = skeleton.bones().into_iter().map(|b| b.with_stiffness(0.0)).collect();
    Skeleton::new([skeleton.base().x, skeleton.base().y], &bones).unwrap()
}

/// The largest turn, degrees, of the pelvis, spine, neck and head of `angles` from the rest pose.
fn torso_turn(puppet: &Skeleton, angles: &[f64]) -> f64 {
    ["pelvis", "spine", "neck", "head"]
        .iter()
        .map(|n| bone(puppet, n))
        .map(|i| (angles[i] - puppet.rest_angles()[i]).abs().to_degrees())
        .fold(0.0, f64::max)
}

/// Issue 24, point 11: with both feet pinned and the right hand sent forward and up, within
/// reach of the arm alone, the shipped puppet moves its arm and keeps its torso upright (every
/// torso bone within 3° of rest) while the hand reaches; without its stiffness the same solve
/// leaned the torso back by more than 10°.
#[test]
fn a_reach_the_arm_can_make_alone_leaves_the_torso_upright() {
    let puppet = rig("puppet");
    assert!(puppet.has_rest_pose());
    assert!(puppet.stiffness()[bone(&puppet, "spine")] > puppet.stiffness()[bone(&puppet, "right_forearm")]);
    let opts = SolveOptions { limits: LimitMode::Lock, ..SolveOptions::default() };
    let pins = vec![Pin::new(bone(&puppet, "left_foot")), Pin::new(bone(&puppet, "right_foot"))];
    let hand = bone(&puppet, "right_hand");
    // Forward and up from the shoulder (0, 0.52), within the arm's 0.79.
    for (x, y) in [(0.45, 0.9), (0.55, 0.75), (0.3, 1.1)] {
        let task = RigTask::new(vec![RigGoal::new(hand, Goal::position(x, y).unwrap())], pins.clone());
        let mut solver = Solver::new(opts.clone()).unwrap();
        let out = solver.solve_rig(&puppet, puppet.start_angles(), &task).unwrap();
        assert!(verify(&puppet, puppet.start_angles(), &task, &opts, &out), "({x}, {y}): {:?}", out.status);
        let turn = torso_turn(&puppet, out.pose.angles());
        assert!(turn < 3.0, "({x}, {y}): the torso turned {turn}°");
        let free = without_rest_pose(&puppet);
        let before = solver.solve_rig(&free, free.start_angles(), &task).unwrap();
        assert!(verify(&free, free.start_angles(), &task, &opts, &before));
        let leaned = torso_turn(&puppet, before.pose.angles());
        assert!(leaned > 10.0, "({x}, {y}): without stiffness the torso turned only {leaned}°");
    }
}

/// The pull toward the rest pose acts in what the goals leave free: from a torso leaned back
/// and a head turned, a reach the arm can make alone brings them most of the way back upright,
/// while the hand reaches and the pins hold; where the goal needs the body (the left hand
/// behind the back, out of the arm's reach), the body moves as it must.
#[test]
fn the_rest_pose_pulls_the_body_home_in_the_null_space() {
    let puppet = rig("puppet");
    let opts = SolveOptions { limits: LimitMode::Lock, ..SolveOptions::default() };
    let pins = vec![Pin::new(bone(&puppet, "left_foot")), Pin::new(bone(&puppet, "right_foot"))];
    let mut start = puppet.start_angles().to_vec();
    for (name, d) in [("pelvis", 20.0), ("spine", 20.0), ("neck", -20.0), ("head", 25.0)] {
        start[bone(&puppet, name)] += deg(d);
    }
    let leaned = torso_turn(&puppet, &start);
    let hand = bone(&puppet, "right_hand");
    let task = RigTask::new(vec![RigGoal::new(hand, Goal::position(0.2, 0.25).unwrap())], pins.clone());
    let mut solver = Solver::new(opts.clone()).unwrap();
    let out = solver.solve_rig(&puppet, &start, &task).unwrap();
    assert!(verify(&puppet, &start, &task, &opts, &out), "{:?}", out.status);
    let turn = torso_turn(&puppet, out.pose.angles());
    assert!(turn < 0.5 * leaned, "from {leaned}° the torso came back only to {turn}°");

    // Behind the back and low: the arm alone cannot reach it; the body gives what it must and
    // no more, and the neck and head (on no goal's path) stay at rest.
    let left = bone(&puppet, "left_hand");
    let task = RigTask::new(vec![RigGoal::new(left, Goal::position(-0.8, 0.4).unwrap())], pins);
    let out = solver.solve_rig(&puppet, puppet.start_angles(), &task).unwrap();
    for name in ["neck", "head"] {
        let i = bone(&puppet, name);
        assert_eq!(out.pose.angles()[i], puppet.rest_angles()[i], "{name}");
    }
}

/// Issue 25: planar robot arms with a prismatic joint (RRP: two revolute then a slide; PRR: a
/// slide first), limits on every joint, and an offset bone: every Jacobian method and limit
/// mode reaches targets put at the tip by a random pose inside the limits (pose → FK → IK →
/// FK), within the limits, the claim checked by forward kinematics.
#[test]
fn prismatic_arms_reach_what_a_random_pose_inside_the_limits_reaches() {
    use crate::{Bone, JointLimits};
    let lim = |a: f64, b: f64| JointLimits::new(a, b).unwrap();
    let rrp = Skeleton::new(
        [0.0, 0.0],
        &[
            Bone::new("shoulder", 1.0, 0.3).with_limits(lim(-2.5, 2.5)),
            Bone::new("elbow", 0.8, 0.4).with_parent("shoulder").with_limits(lim(-2.5, 2.5)),
            Bone::new("ram", 0.5, 0.0).with_parent("elbow").prismatic(0.2).with_limits(lim(0.0, 0.6)),
        ],
    )
    .unwrap();
    let prr = Skeleton::new(
        [0.0, 0.0],
        &[
            Bone::new("carriage", 0.3, 0.0).prismatic(0.5).with_slide([1.0, 0.0]).with_limits(lim(-1.0, 1.5)),
            Bone::new("upper", 1.0, 1.2).with_parent("carriage").with_offset([0.15, 0.1]).with_limits(lim(-0.5, 2.8)),
            Bone::new("lower", 0.7, -0.5).with_parent("upper").with_limits(lim(-2.5, 2.5)),
        ],
    )
    .unwrap();
    let mut reached = 0;
    let mut total = 0;
    for arm in [&rrp, &prr] {
        let mut rng = SplitMix64(25);
        for method in Method::ALL.into_iter().filter(|m| m.solves_rigs()) {
            for limits in [LimitMode::Clamp, LimitMode::Lock, LimitMode::NullSpace, LimitMode::Weighted] {
                let restarts = Some(crate::Restarts { attempts: 8, seed: 3, time_budget: None });
                let opts = SolveOptions { method, limits, restarts, max_iterations: 400, ..SolveOptions::default() };
                let mut solver = Solver::new(opts.clone()).unwrap();
                for _ in 0..6 {
                    let task = reachable_task(arm, &[2], &mut rng);
                    let out = solver.solve_rig(arm, arm.start_angles(), &task).unwrap();
                    reached += usize::from(verify(arm, arm.start_angles(), &task, &opts, &out));
                    total += 1;
                }
            }
        }
    }
    // Measured: every one (the count is exact, the run deterministic).
    assert_eq!(reached, total, "{reached}/{total}");
}

/// A method that cannot move a prismatic joint refuses the body in one line naming the joint,
/// before the rig check.
#[test]
fn ccd_fabrik_and_the_closed_forms_refuse_a_prismatic_joint() {
    use crate::Bone;
    let arm = Skeleton::new(
        [0.0, 0.0],
        &[Bone::new("base", 1.0, 0.0), Bone::new("slider", 0.5, 0.0).with_parent("base").prismatic(0.0)],
    )
    .unwrap();
    let task = RigTask::new(vec![RigGoal::new(1, Goal::position(1.0, 0.5).unwrap())], vec![]);
    for method in Method::ALL {
        let mut solver = Solver::new(SolveOptions { method, ..SolveOptions::default() }).unwrap();
        let result = solver.solve_rig(&arm, arm.start_angles(), &task);
        match result {
            Ok(_) => assert!(method.solves_rigs(), "{method:?}"),
            Err(e) => assert_eq!(
                e.to_string(),
                format!("method {} cannot move prismatic joint \"slider\" (bones[1])", method.name())
            ),
        }
    }
    // A bend on the slider is refused too.
    let bent = RigTask::new(vec![RigGoal::new(1, Goal::position(1.0, 0.5).unwrap()).with_bend(Bend::Positive)], vec![]);
    let err = Solver::new(SolveOptions::default()).unwrap().solve_rig(&arm, arm.start_angles(), &bent).unwrap_err();
    assert_eq!(err.to_string(), "goal \"slider\".bend: the bone's joint is prismatic; a bend needs a revolute joint");
}

mod chain_dispatch {
    use super::*;
    use crate::{Chain, JointLimits, Link, Restarts};
    use proptest::prelude::*;
    use std::f64::consts::PI;

    /// Random arms of 1 to 7 links (some limited) and goals around them, some with an
    /// orientation.
    fn cases() -> impl Strategy<Value = (Chain, Goal)> {
        (1usize..=7).prop_flat_map(|n| {
            (
                prop::collection::vec((0.2f64..2.0, -PI..PI, any::<bool>()), n),
                (-1.3f64..1.3, -1.3f64..1.3, prop::option::of(-PI..PI)),
            )
                .prop_map(|(links, (u, v, angle))| {
                    let links: Vec<Link> = links
                        .iter()
                        .map(|&(l, a, limited)| {
                            let link = Link::new(l, a);
                            if limited { link.with_limits(JointLimits::new(a - 1.5, a + 1.5).unwrap()) } else { link }
                        })
                        .collect();
                    let chain = Chain::new([0.1, -0.2], &links).unwrap();
                    let r = chain.max_reach();
                    let goal = match angle {
                        Some(a) => Goal::with_orientation(u * r, v * r, a),
                        None => Goal::position(u * r, v * r),
                    };
                    (chain, goal.unwrap())
                })
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 40, ..ProptestConfig::default() })]

        /// Issue 25: a chain and the same chain written as a one-branch skeleton give
        /// bit-identical answers, for every method and several limit modes.
        #[test]
        fn a_chain_and_its_one_branch_skeleton_answer_bit_for_bit((chain, goal) in cases()) {
            let skeleton = crate::fixtures::chain_written_as_rig(&chain);
            let task = RigTask::new(vec![RigGoal::new(chain.len() - 1, goal)], vec![]);
            let start = chain.start_pose().angles().to_vec();
            for method in Method::ALL {
                for limits in [LimitMode::Ignore, LimitMode::Clamp, LimitMode::Lock, LimitMode::Weighted] {
                    let restarts = Some(Restarts { attempts: 3, seed: 7, time_budget: None });
                    let opts = SolveOptions { method, limits, restarts, max_iterations: 200, ..SolveOptions::default() };
                    let mut solver = Solver::new(opts).unwrap();
                    let c = solver.solve(&chain, chain.start_pose(), &goal);
                    let s = solver.solve_rig(&skeleton, &start, &task);
                    match (c, s) {
                        (Ok(c), Ok(s)) => {
                            let bits = |a: &[f64]| a.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                            prop_assert_eq!(bits(c.pose.angles()), bits(s.pose.angles()), "{:?} {:?}", method, limits);
                            prop_assert_eq!(c.status, s.status);
                            prop_assert_eq!((c.iterations, c.restarts), (s.iterations, s.restarts));
                            prop_assert_eq!(c.error.to_bits(), s.error.to_bits());
                            prop_assert_eq!(c.angle_error.to_bits(), s.angle_error.to_bits());
                            let e = &s.effectors[0];
                            prop_assert_eq!((e.bone, e.status, e.tip), (chain.len() - 1, c.status, c.end_effector.position));
                        }
                        (Err(c), Err(s)) => prop_assert_eq!(c.to_string(), s.to_string()),
                        (c, s) => prop_assert!(false, "{:?} {:?}: chain {:?}, skeleton {:?}", method, limits, c, s),
                    }
                }
            }
        }
    }

    /// A task the chain does not mean the same way (a pin, a weight, a fork) stays on the rig
    /// path: the chain-only methods are still refused there.
    #[test]
    fn other_tasks_stay_rig_solves() {
        let chain = crate::fixtures::seed_arm_limited();
        let skeleton = crate::fixtures::chain_written_as_rig(&chain);
        let goal = Goal::position(1.0, 1.0).unwrap();
        let last = chain.len() - 1;
        let mut ccd =
            Solver::new(SolveOptions { method: Method::CyclicCoordinateDescent, ..SolveOptions::default() }).unwrap();
        let start = chain.start_pose().angles();
        assert!(ccd.solve_rig(&skeleton, start, &RigTask::new(vec![RigGoal::new(last, goal)], vec![])).is_ok());
        for task in [
            RigTask::new(vec![RigGoal::new(last, goal)], vec![Pin::new(0)]),
            RigTask::new(vec![RigGoal::new(last, goal).with_weight(2.0)], vec![]),
            RigTask::new(vec![RigGoal::new(0, goal)], vec![]),
        ] {
            let e = ccd.solve_rig(&skeleton, start, &task).unwrap_err();
            assert!(matches!(e, SolveError::ChainOnly { .. }), "{e}");
        }
    }
}
