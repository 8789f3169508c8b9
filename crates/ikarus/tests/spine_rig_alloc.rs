//! [`SpineRig::solve`] allocates nothing once a frame's goals, pins and bones have been seen:
//! a counting global allocator around 600 frames of spineboy's walk (its own test binary, so
//! that no other test's allocations are counted).
#![allow(unsafe_code)]

use ikarus::Goal;
use ikarus::character::{Placement, PoseRequest, Posed, SpineBone, SpineFrame, SpineRig, TipGoal, spine_bone_numbers};
use ikarus::solve::{Method, RigGoal, SolveOptions, Solver};
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::sync::atomic::{AtomicUsize, Ordering};

/// The system allocator, counting the allocations of a thread while its `COUNTING` is on.
struct Counting;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

thread_local! {
    static COUNTING: Cell<bool> = const { Cell::new(false) };
}

fn note() {
    if COUNTING.with(Cell::get) {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
    }
}

// SAFETY: every call is passed to `System` unchanged; the count is a side effect.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        note();
        // SAFETY: the caller's contract, passed on.
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: the caller's contract, passed on.
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        note();
        // SAFETY: the caller's contract, passed on.
        unsafe { System.alloc_zeroed(layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        note();
        // SAFETY: the caller's contract, passed on.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn six_hundred_frames_of_a_fist_on_a_circle_and_a_pinned_foot_allocate_nothing_after_the_first() {
    let file = "spine-spineboy-pro.json";
    let path = format!("{}/../../examples/characters/{file}", env!("CARGO_MANIFEST_DIR"));
    let c = ikarus_edge::character::load(&std::fs::read_to_string(path).unwrap(), file).unwrap().character;
    let bone = |n: &str| c.bones().iter().position(|b| b.name == n).unwrap();
    let (fist, foot, upper) = (bone("front-fist"), bone("rear-foot"), bone("front-upper-arm"));
    let bones = c
        .bones()
        .iter()
        .map(|b| SpineBone { parent: b.parent, length: b.length, inherit: b.inherit, limits_deg: None })
        .collect();
    let mut rig = SpineRig::new(bones).unwrap();
    let mut solver =
        Solver::new(SolveOptions { method: Method::LevenbergMarquardt, ..SolveOptions::default() }).unwrap();
    let walk = c.clip_index("walk").unwrap();
    let mut posed = Posed::default();
    let (mut numbers, mut rotations) = (Vec::new(), vec![0.0; c.bones().len()]);
    let mut per_frame = Vec::with_capacity(600);
    for frame in 0..600 {
        let time = frame as f64 / 60.0 % c.clips()[walk].duration;
        let request = PoseRequest { clip: Some((walk, time)), targets: &[], bends: &[], turns: &[], skin: None };
        c.pose(&request, &mut posed).unwrap();
        numbers.clear();
        for i in 0..posed.len() {
            let (w, l) = (posed.world(i), posed.local(i));
            numbers.extend(spine_bone_numbers(&w, &l));
        }
        let s = posed.origin(upper);
        let turn = frame as f64 / 600.0 * std::f64::consts::TAU;
        let (x, y) = (s[0] + 100.0 * libm::cos(turn), s[1] + 100.0 * libm::sin(turn));
        let goals = [TipGoal { goal: RigGoal::new(fist, Goal::position(x, y).unwrap()), bones: 3 }];
        let pins = [foot];
        let f = SpineFrame { numbers: &numbers, placement: Placement::default(), goals: &goals, pins: &pins };
        ALLOCATIONS.store(0, Ordering::Relaxed);
        COUNTING.with(|c| c.set(true));
        let solved = rig.solve(&f, &mut solver, &mut rotations).map(|_| ());
        COUNTING.with(|c| c.set(false));
        solved.unwrap();
        per_frame.push(ALLOCATIONS.load(Ordering::Relaxed));
        assert!(rig.errors()[0] < 1e-3, "frame {frame}: the fist misses by {}", rig.errors()[0]);
    }
    let allocating: Vec<(usize, usize)> =
        per_frame.iter().copied().enumerate().skip(1).filter(|&(_, n)| n > 0).take(10).collect();
    assert!(allocating.is_empty(), "frames allocating (frame, count), the first 10: {allocating:?}");
}
