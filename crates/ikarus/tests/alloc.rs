//! Hot loops do not allocate: once a [`Solver`] and an [`Outcome`] have been used for a chain of
//! this size, `solve_into` allocates nothing, however many iterations it runs, and with frame
//! recording when the outcome's frame buffers are already large enough.
//!
//! A counting global allocator (a thin wrapper over the system allocator) counts the calls that
//! obtain memory, per thread, so tests running in parallel do not disturb each other.

// The one place in the workspace that needs `unsafe`: implementing `GlobalAlloc`.
#![allow(unsafe_code)]

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

// The shared fixtures (the character's bones, constraint and clip), without the rest of `common`.
#[path = "common/fixtures.rs"]
mod fixtures;

use ikarus::{Chain, Goal, Link, Method, Outcome, SolveOptions, Solver, Status};

struct Counting;

thread_local! {
    // A const-initialised `Cell` needs no allocation and no destructor, so the allocator may
    // touch it at any time.
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

fn count() {
    // `try_with`: during thread teardown the slot may be gone; those calls are not ours.
    let _ = ALLOCATIONS.try_with(|c| c.set(c.get() + 1));
}

// SAFETY: every method forwards to `System` with the caller's arguments unchanged, so the
// `GlobalAlloc` contract is upheld exactly as `System` upholds it; counting touches no memory
// that the allocator hands out.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count();
        // SAFETY: forwarded unchanged.
        unsafe { System.alloc(layout) }
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        count();
        // SAFETY: forwarded unchanged.
        unsafe { System.alloc_zeroed(layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count();
        // SAFETY: forwarded unchanged.
        unsafe { System.realloc(ptr, layout, new_size) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: forwarded unchanged.
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// Allocations made by this thread while running `f`.
fn allocations_in<R>(f: impl FnOnce() -> R) -> (usize, R) {
    let before = ALLOCATIONS.with(Cell::get);
    let r = f();
    (ALLOCATIONS.with(Cell::get) - before, r)
}

/// A 7-link arm of unit links, folded a little at every joint.
fn seven_links() -> Chain {
    let links: Vec<Link> = (0..7).map(|i| Link::new(1.0, if i % 2 == 0 { 0.3 } else { -0.2 })).collect();
    Chain::new([0.0, 0.0], &links).unwrap()
}

/// Options that run exactly 500 iterations on a goal out of reach: no stall detection, no line
/// search (which would stop once no step helps).
fn long_solve(method: Method, record_every: Option<u32>) -> SolveOptions {
    SolveOptions {
        method,
        tolerance: f64::MIN_POSITIVE,
        angle_tolerance: f64::MIN_POSITIVE,
        max_iterations: 500,
        stall: None,
        backtrack: 0,
        record_every,
        ..SolveOptions::default()
    }
}

/// Every method that iterates (the closed form has its own shapes).
fn iterative() -> impl Iterator<Item = Method> {
    Method::ALL.into_iter().filter(|&m| m != Method::Analytic)
}

#[test]
fn the_counter_sees_allocations() {
    let (n, v) = allocations_in(|| vec![1u8; 64]);
    assert_eq!(v.len(), 64);
    assert!(n >= 1, "the counting allocator is not in use");
}

/// A warmed-up solver and outcome: 500 iterations on 7 links allocate nothing, for every method.
#[test]
fn many_iterations_allocate_nothing() {
    let chain = seven_links();
    let goal = Goal::position(9.0, 1.0).unwrap(); // the reach is 7
    for method in iterative() {
        let mut solver = Solver::new(long_solve(method, None)).unwrap();
        let mut out = Outcome::default();
        solver.solve_into(&chain, chain.start_pose().angles(), &goal, &mut out).unwrap(); // warm-up
        let (n, r) = allocations_in(|| solver.solve_into(&chain, chain.start_pose().angles(), &goal, &mut out));
        r.unwrap();
        assert_eq!(out.iterations, 500, "{method:?}: {out:?}");
        assert_eq!(out.status, Status::Unreachable);
        assert_eq!(n, 0, "{method:?}: {n} allocations in a warmed-up solve");

        // A reachable goal with an orientation, from another start: still nothing.
        let other = Goal::with_orientation(-2.0, 4.0, 1.0).unwrap();
        let (n, r) = allocations_in(|| solver.solve_into(&chain, &[0.1; 7], &other, &mut out));
        r.unwrap();
        assert_eq!(n, 0, "{method:?}: {n} allocations for another goal");
    }
}

/// The line search (on by default) shares the scratch buffers: nothing either.
#[test]
fn the_line_search_allocates_nothing() {
    let chain = seven_links();
    for method in iterative() {
        let opts = SolveOptions { backtrack: 10, ..long_solve(method, None) };
        let mut solver = Solver::new(opts).unwrap();
        let mut out = Outcome::default();
        // Out of reach, so steps keep failing the sufficient-decrease test and get halved.
        let goal = Goal::position(9.0, 1.0).unwrap();
        solver.solve_into(&chain, chain.start_pose().angles(), &goal, &mut out).unwrap();
        let (n, r) = allocations_in(|| solver.solve_into(&chain, chain.start_pose().angles(), &goal, &mut out));
        r.unwrap();
        assert!(out.iterations > 0);
        assert_eq!(n, 0, "{method:?}: {n} allocations with the line search");
    }
}

/// Recording frames reuses the outcome's frame buffers: after an identical solve (501 frames),
/// recording every iteration allocates nothing.
#[test]
fn recording_frames_into_grown_buffers_allocates_nothing() {
    let chain = seven_links();
    let goal = Goal::position(9.0, 1.0).unwrap();
    for every in [1, 7] {
        let mut solver = Solver::new(long_solve(Method::Transpose, Some(every))).unwrap();
        let mut out = Outcome::default();
        // The first solve grows the buffers, and the counter sees it.
        let (cold, r) = allocations_in(|| solver.solve_into(&chain, chain.start_pose().angles(), &goal, &mut out));
        r.unwrap();
        assert!(cold > 0);
        let (n, r) = allocations_in(|| solver.solve_into(&chain, chain.start_pose().angles(), &goal, &mut out));
        r.unwrap();
        assert_eq!(out.frames.len(), 500 / every as usize + 1 + usize::from(500 % every != 0));
        assert_eq!(n, 0, "record_every {every}: {n} allocations");
    }
}

/// Every limit mode, with restarts and the closed form on: a warmed-up solver allocates nothing,
/// for goals that are reached, reached after restarts, and put out of reach by the limits.
#[test]
fn limit_modes_and_restarts_allocate_nothing() {
    use ikarus::{JointLimits, LimitMode, Restarts};
    let limited = |n: usize| {
        let links: Vec<Link> =
            (0..n).map(|i| Link::new(1.0, 0.1 * i as f64).with_limits(JointLimits::new(-1.5, 1.5).unwrap())).collect();
        Chain::new([0.0, 0.0], &links).unwrap()
    };
    let goals = [
        Goal::position(1.0, 1.5).unwrap(),
        Goal::position(-0.5, -1.8).unwrap(),
        Goal::position(-2.5, -0.1).unwrap(),
        Goal::with_orientation(1.2, 0.8, 1.0).unwrap(),
    ];
    let mut restarted = 0;
    for chain in [limited(2), limited(3), limited(7)] {
        for method in iterative() {
            for limits in LimitMode::ALL {
                let opts = SolveOptions {
                    method,
                    limits,
                    restarts: Some(Restarts { attempts: 3, ..Restarts::default() }),
                    max_iterations: 200,
                    ..SolveOptions::default()
                };
                let mut solver = Solver::new(opts).unwrap();
                let mut out = Outcome::default();
                for goal in &goals {
                    solver.solve_into(&chain, chain.start_pose().angles(), goal, &mut out).unwrap();
                    let (n, r) =
                        allocations_in(|| solver.solve_into(&chain, chain.start_pose().angles(), goal, &mut out));
                    r.unwrap();
                    assert_eq!(n, 0, "{method:?} {limits:?} {goal:?}: {n} allocations ({} restarts)", out.restarts);
                    restarted += usize::from(out.restarts > 0);
                }
            }
        }
    }
    // The restart path is exercised: an exact count of the solves that restarted (the run is
    // deterministic; a method or limit mode more or fewer changes it).
    assert_eq!(restarted, 19, "solves that restarted");
}

/// Issue 12: a skeleton's forward kinematics and stacked Jacobian, into buffers of the right
/// shape, allocate nothing (the solver's iterations will call both).
#[test]
fn skeleton_kinematics_allocate_nothing() {
    use ikarus::{Bone, Effector, Point2, Skeleton};
    let bones = [
        Bone::new("pelvis", 0.2, 1.5),
        Bone::new("spine", 0.5, 0.1).with_parent("pelvis"),
        Bone::new("arm", 0.6, -2.5).with_parent("spine"),
        Bone::new("hand", 0.2, 0.3).with_parent("arm"),
        Bone::new("leg", 0.9, -1.5),
        Bone::new("foot", 0.2, 1.5).with_parent("leg"),
    ];
    let s = Skeleton::new([0.0, 0.0], &bones).unwrap();
    let n = s.len();
    let (mut starts, mut tips, mut dirs) = (vec![Point2::origin(); n], vec![Point2::origin(); n], vec![0.0; n]);
    let effectors = [Effector::with_orientation(3), Effector::position(5)];
    let mut j = nalgebra::DMatrix::zeros(5, n);
    let angles = [0.1, 0.2, 0.3, 0.4, 0.5, 0.6];
    let (count, ()) = allocations_in(|| {
        for _ in 0..100 {
            s.forward_into(&angles, &mut starts, &mut tips, &mut dirs);
            s.jacobian_into(&starts, &tips, &dirs, &effectors, &mut j);
        }
    });
    assert_eq!(count, 0, "{count} allocations");
    assert!(j[(0, 0)] != 0.0 && j[(3, 4)] != 0.0 && j[(3, 0)] == 0.0);
}

/// Issue 12: a warmed-up skeleton solve — several effectors, a pin, an orientation, limits,
/// restarts, every rig method and limit mode, two priority levels — allocates nothing, however
/// many iterations and restarts it runs.
#[test]
fn skeleton_solves_allocate_nothing() {
    use ikarus::{Bone, JointLimits, LimitMode, Pin, Priority, RigGoal, RigTask, Skeleton};
    let lim = JointLimits::new(-1.2, 1.2).unwrap();
    let bones = [
        Bone::new("pelvis", 0.2, 1.5).with_limits(JointLimits::new(1.0, 2.0).unwrap()),
        Bone::new("spine", 0.5, 0.1).with_parent("pelvis").with_limits(lim),
        Bone::new("arm", 0.6, -2.5).with_parent("spine"),
        Bone::new("fore", 0.5, 0.3).with_parent("arm").with_limits(JointLimits::new(0.0, 2.5).unwrap()),
        Bone::new("hand", 0.2, 0.3).with_parent("fore").with_limits(lim),
        Bone::new("head", 0.2, 0.0).with_parent("spine").with_limits(lim),
        Bone::new("leg", 0.9, -1.5),
        Bone::new("foot", 0.2, 1.0).with_parent("leg").with_limits(lim),
    ];
    let s = Skeleton::new([0.0, 0.0], &bones).unwrap();
    // Issue 25: the same body with a prismatic forearm (limited slide across the arm) and a
    // head that starts beside the spine's middle.
    let mut sliding = bones.clone();
    sliding[3] = Bone::new("fore", 0.5, 0.3)
        .with_parent("arm")
        .with_slide([1.0, 0.5])
        .with_limits(JointLimits::new(-0.3, 0.4).unwrap());
    sliding[5] = sliding[5].clone().with_offset([0.25, 0.1]);
    let p = Skeleton::new([0.0, 0.0], &sliding).unwrap();
    assert!(p.has_prismatic() && !p.is_plain());
    let tasks = [
        RigTask::new(
            vec![
                RigGoal::new(4, Goal::with_orientation(0.3, 0.9, 0.5).unwrap()),
                RigGoal::new(5, Goal::position(-0.2, 0.9).unwrap()),
            ],
            vec![Pin::new(7)],
        ),
        RigTask::new(
            vec![
                RigGoal::new(4, Goal::position(3.0, 3.0).unwrap()),
                RigGoal::new(5, Goal::position(-0.3, 0.8).unwrap()).with_priority(Priority::Secondary),
            ],
            vec![Pin::new(7)],
        ),
    ];
    for (s, (t, task)) in [&s, &p].into_iter().flat_map(|s| tasks.iter().enumerate().map(move |t| (s, t))) {
        for method in iterative().filter(|m| m.solves_rigs()) {
            for limits in LimitMode::ALL {
                let mut solver = Solver::new(SolveOptions { method, limits, ..SolveOptions::default() }).unwrap();
                let mut out = Outcome::default();
                solver.solve_rig_into(s, s.start_angles(), task, &mut out).unwrap();
                solver.solve_rig_into(s, s.start_angles(), task, &mut out).unwrap();
                let (n, r) = allocations_in(|| solver.solve_rig_into(s, s.start_angles(), task, &mut out));
                r.unwrap();
                assert_eq!(
                    n,
                    0,
                    "{} task {t}, {method:?} {limits:?}: {n} allocations ({} iterations, {:?})",
                    if s.is_plain() { "plain" } else { "prismatic" },
                    out.iterations,
                    out.status
                );
            }
        }
    }
}

/// Issue 12: a skeleton's effector following a path — one rig solve per sample from the
/// previous pose (and restarts near it), the step bounded, every effector measured —
/// allocates nothing once its follower has taken a step, as a chain's follower.
#[test]
fn a_rig_follower_step_allocates_nothing() {
    use ikarus::track::{Follower, Path, TrackOptions};
    use ikarus::{Bone, Pin, RigTask, Skeleton};
    let bones = [
        Bone::new("trunk", 1.0, 1.5),
        Bone::new("left_upper", 1.0, 1.2).with_parent("trunk"),
        Bone::new("left_lower", 1.0, 0.3).with_parent("left_upper"),
        Bone::new("right_upper", 1.0, -1.2).with_parent("trunk"),
        Bone::new("right_lower", 1.0, -0.3).with_parent("right_upper"),
    ];
    let s = Skeleton::new([0.0, 0.0], &bones).unwrap();
    let task = RigTask::new(vec![], vec![Pin::new(4)]);
    let mut f = Follower::rig(&s, s.start_angles(), 2, &task, &TrackOptions::default()).unwrap();
    let path = Path::circle([-1.3, 1.8], 0.3, 40).unwrap();
    f.place(&path.goals()[0]); // warm-up
    let (count, ()) = allocations_in(|| {
        for goal in &path.goals()[1..] {
            let step = f.step(goal);
            assert!(step.error < 1e-5, "{step:?}");
        }
    });
    assert_eq!(count, 0, "{count} allocations in 39 steps");
}

/// Issue 26: posing a character (setup, a clip with Bézier and IK keys, a target, two- and
/// one-bone constraints) allocates nothing once its `Posed` has grown to the character.
#[test]
fn posing_a_character_allocates_nothing() {
    use fixtures::{character_bone as bone, rotate_clip, spine_ik};
    use ikarus::character::{
        Character, CharacterParts, Constraint, ConstraintKeys, ConstraintTimeline, IkBones, IkKey, IkSettings,
        Interpolation, PoseRequest, Posed,
    };
    let ik = |bones: IkBones, target: usize, order: u32| {
        spine_ik(&format!("ik{order}"), order, bones, target, IkSettings { softness: 1.0, ..IkSettings::default() })
    };
    let bezier = Interpolation::Bezier { c1: [0.2, 0.1], c2: [0.6, 0.9] };
    let c = Character::new(CharacterParts {
        bones: vec![
            bone("root", None, 0.0, 0.0),
            bone("thigh", Some(0), 0.0, -1.5),
            bone("shin", Some(1), 10.0, 0.3),
            bone("foot", Some(2), 10.0, 0.0),
            bone("target", Some(0), 5.0, 0.0),
        ],
        constraints: vec![
            Constraint::Ik(ik(IkBones::Two { parent: 1, child: 2 }, 4, 1)),
            Constraint::Ik(ik(IkBones::One(3), 0, 0)),
        ],
        clips: vec![rotate_clip(
            1,
            [(0.0, 0.0), (1.0, 1.0)],
            bezier,
            vec![ConstraintTimeline {
                constraint: 0,
                keys: ConstraintKeys::Ik(vec![
                    IkKey { time: 0.0, settings: IkSettings::default(), curves: [bezier; 2] },
                    IkKey {
                        time: 1.0,
                        settings: IkSettings { mix: 0.5, ..IkSettings::default() },
                        curves: [bezier; 2],
                    },
                ]),
            }],
        )],
        ..CharacterParts::default()
    })
    .unwrap();
    let mut out = Posed::default();
    let targets = [(4, [3.0, -12.0])];
    c.pose(&PoseRequest { clip: Some((0, 0.1)), targets: &targets, bends: &[], turns: &[], skin: None }, &mut out)
        .unwrap(); // warm-up
    let (count, ()) = allocations_in(|| {
        for i in 0..100 {
            let time = i as f64 / 100.0;
            c.pose(
                &PoseRequest { clip: Some((0, time)), targets: &targets, bends: &[], turns: &[], skin: None },
                &mut out,
            )
            .unwrap();
        }
    });
    assert_eq!(count, 0, "{count} allocations in 100 poses");
    assert!(out.tip(2)[0].is_finite());
}

/// Issue 27: the shipped spineboy and raptor, posed by the runtime's rules — the setup pose,
/// the walk at times going forward (and wrapping), the walk with targets moved — allocate
/// nothing once their `Posed` has grown (one `Posed` for both characters and every kind).
#[test]
fn posing_the_shipped_characters_allocates_nothing() {
    use ikarus::character::{PoseRequest, Posed};
    let read = |file: &str| {
        let path = format!("{}/../../examples/characters/{file}", env!("CARGO_MANIFEST_DIR"));
        let text = std::fs::read_to_string(&path).unwrap();
        ikarus_edge::character::load(&text, file).unwrap().character
    };
    // Stretchyman's `sneak` deforms the paths its path constraints follow.
    let characters = [
        (read("spine-spineboy-pro.json"), "walk"),
        (read("spine-raptor-pro.json"), "walk"),
        (read("spine-stretchyman-pro.json"), "sneak"),
    ];
    let mut out = Posed::default();
    for (c, clip) in &characters {
        let walk = c.clip_index(clip).unwrap();
        let duration = c.clips()[walk].duration;
        let target = (c.ik(0).unwrap().target, [30.0, -20.0]);
        let targets = [target];
        let requests = |i: usize| {
            let time = (i as f64 / 60.0) % duration;
            [
                PoseRequest::default(),
                PoseRequest { clip: Some((walk, time)), targets: &[], bends: &[], turns: &[], skin: None },
                PoseRequest { clip: Some((walk, time)), targets: &targets, bends: &[], turns: &[], skin: None },
            ]
        };
        for r in requests(0) {
            c.pose(&r, &mut out).unwrap(); // warm-up: grows `out` to this character
        }
        for (kind, name) in ["setup", "walk", "walk with a target"].iter().enumerate() {
            let (count, ()) = allocations_in(|| {
                for i in 0..300 {
                    c.pose(&requests(i)[kind], &mut out).unwrap();
                }
            });
            assert_eq!(count, 0, "{} bones, {name}: {count} allocations in 300 poses", c.bones().len());
        }
        assert!(out.tip(c.bones().len() - 1)[0].is_finite());
    }
}

/// A path constraint follows the path the chosen skin gives it, and the deform timeline of that
/// path: stretchyman with a skin `own` holding its own copy of the front leg's path and of its
/// `sneak` deform, posed with that skin and with the default one in turns, allocates nothing
/// once warmed up (the path is picked by the skin's index, no name looked up).
#[test]
fn posing_with_a_skins_own_path_allocates_nothing() {
    use ikarus::character::{PoseRequest, Posed};
    let path = format!("{}/../../examples/characters/spine-stretchyman-pro.json", env!("CARGO_MANIFEST_DIR"));
    let mut tree: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let slot = "front-leg-path";
    let own = tree["skins"][0]["attachments"][slot][slot].clone();
    tree["skins"].as_array_mut().unwrap().push(serde_json::json!({"name": "own", "attachments": {slot: {slot: own}}}));
    let deform = tree["animations"]["sneak"]["attachments"]["default"][slot].clone();
    tree["animations"]["sneak"]["attachments"]["own"] = serde_json::json!({ slot: deform });
    let c = ikarus_edge::character::load(&tree.to_string(), "own.json").unwrap().character;
    let sneak = c.clip_index("sneak").unwrap();
    let [default, own] = [c.skin_index("default"), c.skin_index("own")];
    let request = |i: usize| PoseRequest {
        clip: Some((sneak, (i as f64 / 60.0) % c.clips()[sneak].duration)),
        skin: if i % 2 == 0 { own } else { default },
        ..PoseRequest::default()
    };
    let mut out = Posed::default();
    c.pose(&request(0), &mut out).unwrap();
    c.pose(&request(1), &mut out).unwrap();
    let (count, ()) = allocations_in(|| {
        for i in 0..300 {
            c.pose(&request(i), &mut out).unwrap();
        }
    });
    assert_eq!(count, 0, "{count} allocations in 300 poses");
}

/// Issue 27: the shipped puppet (four limbs, stiff trunk: the rest pose's pull projects every
/// step) and hand (five fingertips on one wrist), solved with the defaults — restarts, limits
/// locked — for many reachable target sets in a row, allocate nothing once the solver and
/// the outcome have been used on the rig.
#[test]
fn the_shipped_rigs_solve_without_allocating() {
    use ikarus::{RigGoal, RigTask};
    let read = |file: &str, bones: &[&str]| {
        let path = format!("{}/../../examples/rigs/{file}", env!("CARGO_MANIFEST_DIR"));
        let text = std::fs::read_to_string(&path).unwrap();
        let s = ikarus_edge::rig::Rig::parse(&text, file).unwrap().skeleton;
        let bones: Vec<usize> = bones.iter().map(|b| s.index_of(b).unwrap()).collect();
        (s, bones)
    };
    let rigs = [
        read("puppet.toml", &["left_hand", "right_hand", "left_foot", "right_foot"]),
        read("hand.toml", &["thumb_distal", "index_distal", "middle_distal", "ring_distal", "little_distal"]),
    ];
    let mut state = 0x2701_u64;
    let mut unit = move || {
        state = state.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    for (s, bones) in &rigs {
        let n = s.len();
        // Targets where a random pose inside the limits puts the effectors.
        let (mut points, mut dirs) = (vec![nalgebra::Point2::origin(); n + 1], vec![0.0; n]);
        let mut tasks = Vec::new();
        for _ in 0..40 {
            let pose: Vec<f64> = s
                .limits()
                .iter()
                .map(|l| {
                    let u = unit();
                    l.map_or(-3.0 + 6.0 * u, |l| l.min() + u * (l.max() - l.min()))
                })
                .collect();
            s.points_into(&pose, &mut points, &mut dirs);
            let goals =
                bones.iter().map(|&b| RigGoal::new(b, Goal::position(points[b + 1].x, points[b + 1].y).unwrap()));
            tasks.push(RigTask::new(goals.collect(), vec![]));
        }
        let mut solver = Solver::new(SolveOptions::default()).unwrap();
        let mut out = Outcome::default();
        solver.solve_rig_into(s, s.start_angles(), &tasks[0], &mut out).unwrap();
        let (count, ()) = allocations_in(|| {
            for task in &tasks {
                solver.solve_rig_into(s, s.start_angles(), task, &mut out).unwrap();
            }
        });
        assert_eq!(count, 0, "{} bones: {count} allocations in {} solves", n, tasks.len());
    }
}

/// Issue 40: drawing the shipped spineboy and raptor (world vertices, UVs, triangles of every
/// slot) into a reused `DrawList` allocates nothing once it has grown.
#[test]
fn drawing_the_shipped_characters_allocates_nothing() {
    use ikarus::character::{DrawList, PoseRequest, Posed};
    let read = |file: &str| {
        let path = format!("{}/../../examples/characters/{file}", env!("CARGO_MANIFEST_DIR"));
        std::fs::read_to_string(&path).unwrap()
    };
    let mut list = DrawList::default();
    let mut out = Posed::default();
    for (skeleton, atlas) in [("spine-spineboy-pro.json", "spineboy.atlas"), ("spine-raptor-pro.json", "raptor.atlas")]
    {
        let c = ikarus_edge::character::load(&read(skeleton), skeleton).unwrap().character;
        let regions = ikarus_edge::character::atlas::read(&read(atlas)).unwrap().lookup();
        let walk = c.clip_index("walk").unwrap();
        let skin = c.default_skin();
        let request = |i: usize| PoseRequest { clip: Some((walk, i as f64 / 60.0)), skin, ..PoseRequest::default() };
        c.pose(&request(0), &mut out).unwrap();
        c.draw_list(&out, skin, &regions, &mut list); // warm-up: grows `list` to this character
        let (count, ()) = allocations_in(|| {
            for i in 0..60 {
                c.pose(&request(i), &mut out).unwrap();
                c.draw_list(&out, skin, &regions, &mut list);
            }
        });
        assert_eq!(count, 0, "{skeleton}: {count} allocations in 60 drawings");
        assert!(list.items.len() > 10 && list.vertices.iter().flatten().all(|v| v.is_finite()), "{skeleton}");
    }
}

/// Issue 40: drawing clips with slot timelines (spineboy's `shoot`: attachments and colours;
/// `hoverboard`: mesh deforms; the raptor's `jump`: the draw order) with `draw_list_at` into a
/// reused `DrawList` allocates nothing once a first pass over the same frames has grown it.
#[test]
fn drawing_slot_timelines_allocates_nothing() {
    use ikarus::character::{DrawList, PoseRequest, Posed};
    let read = |file: &str| {
        let path = format!("{}/../../examples/characters/{file}", env!("CARGO_MANIFEST_DIR"));
        std::fs::read_to_string(&path).unwrap()
    };
    let mut list = DrawList::default();
    let mut out = Posed::default();
    for (skeleton, atlas, clip) in [
        ("spine-spineboy-pro.json", "spineboy.atlas", "shoot"),
        ("spine-spineboy-pro.json", "spineboy.atlas", "hoverboard"),
        ("spine-raptor-pro.json", "raptor.atlas", "jump"),
    ] {
        let c = ikarus_edge::character::load(&read(skeleton), skeleton).unwrap().character;
        let regions = ikarus_edge::character::atlas::read(&read(atlas)).unwrap().lookup();
        let index = c.clip_index(clip).unwrap();
        let skin = c.default_skin();
        let at = |i: usize| Some((index, i as f64 / 30.0));
        let pass = |out: &mut Posed, list: &mut DrawList| {
            for i in 0..30 {
                c.pose(&PoseRequest { clip: at(i), skin, ..PoseRequest::default() }, out).unwrap();
                c.draw_list_at(out, skin, at(i), &regions, list).unwrap();
            }
        };
        pass(&mut out, &mut list); // warm-up over the same frames
        let (count, ()) = allocations_in(|| pass(&mut out, &mut list));
        assert_eq!(count, 0, "{skeleton} {clip}: {count} allocations in 30 drawings");
        assert!(list.items.len() > 10, "{skeleton} {clip}");
    }
}

/// Issue 41: the stand-in skeleton's frame, sampling the clip's locals and posing from given
/// locals and settings ([`Character::sample`], [`Character::pose_given`]), allocates nothing once
/// its `Posed` has grown (spineboy's walk; stretchyman's sneak, whose deform the given pose keeps).
#[test]
fn sampling_and_posing_from_given_locals_allocate_nothing() {
    use ikarus::character::{GivenPose, LocalTransform, PhysicsMode, PoseRequest, Posed, Settings};
    let read = |file: &str| {
        let path = format!("{}/../../examples/characters/{file}", env!("CARGO_MANIFEST_DIR"));
        let text = std::fs::read_to_string(&path).unwrap();
        ikarus_edge::character::load(&text, file).unwrap().character
    };
    for (file, clip) in [("spine-spineboy-pro.json", "walk"), ("spine-stretchyman-pro.json", "sneak")] {
        let c = read(file);
        let clip = c.clip_index(clip).unwrap();
        let mut out = Posed::default();
        let mut local = vec![LocalTransform::default(); c.bones().len()];
        let mut settings: Vec<Settings> = c.constraints().iter().map(|k| k.setup()).collect();
        let mut frame = |i: usize, out: &mut Posed| {
            let request =
                PoseRequest { clip: Some((clip, i as f64 / 60.0)), skin: c.default_skin(), ..PoseRequest::default() };
            c.sample(&request, out).unwrap();
            for (j, l) in local.iter_mut().enumerate() {
                *l = out.local(j);
            }
            for (k, s) in settings.iter_mut().enumerate() {
                *s = out.settings(k);
            }
            let given = GivenPose {
                local: &local,
                settings: &settings,
                placement: c.placement(),
                skin: c.default_skin(),
                physics: PhysicsMode::None,
                clock: 0.0,
            };
            c.pose_given(&given, out).unwrap();
        };
        // Warm-up: two frames, as `Character::pose` itself needs for stretchyman (its second pose
        // of the sneak at 0 s still allocates twice, in the clip's part, then never again).
        frame(0, &mut out);
        frame(0, &mut out);
        let (count, ()) = allocations_in(|| (0..300).for_each(|i| frame(i, &mut out)));
        assert_eq!(count, 0, "{file}: {count} allocations in 300 frames");
    }
}
