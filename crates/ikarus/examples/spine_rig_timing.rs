//! Issue 41: how long [`SpineRig::solve`] takes per frame on spineboy's walk with a 3-bone goal
//! on `front-fist` moving on a circle and a pin on `rear-foot`, 600 frames. Prints the median
//! and p99 µs; asserts nothing (`cargo run --release -p ikarus --example spine_rig_timing`).

use ikarus::Goal;
use ikarus::character::{Placement, PoseRequest, Posed, SpineBone, SpineFrame, SpineRig, TipGoal, spine_bone_numbers};
use ikarus::solve::{Method, RigGoal, SolveOptions, Solver};
use std::time::Instant;

fn main() {
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
    let mut micros = Vec::with_capacity(600);
    for frame in 0..600 {
        let time = frame as f64 / 60.0 % c.clips()[walk].duration;
        let request = PoseRequest { clip: Some((walk, time)), targets: &[], bends: &[], turns: &[], skin: None };
        c.pose(&request, &mut posed).unwrap();
        numbers.clear();
        for i in 0..posed.len() {
            let (w, l) = (posed.world(i), posed.local(i));
            numbers.extend(spine_bone_numbers(&w, &l));
        }
        // The goal on a circle of radius 100 around the shoulder, once round in the 600 frames
        // (as the allocation test has it, tests/spine_rig_alloc.rs).
        let s = posed.origin(upper);
        let turn = frame as f64 / 600.0 * std::f64::consts::TAU;
        let (x, y) = (s[0] + 100.0 * libm::cos(turn), s[1] + 100.0 * libm::sin(turn));
        let goals = [TipGoal { goal: RigGoal::new(fist, Goal::position(x, y).unwrap()), bones: 3 }];
        let pins = [foot];
        let f = SpineFrame { numbers: &numbers, placement: Placement::default(), goals: &goals, pins: &pins };
        let start = Instant::now();
        rig.solve(&f, &mut solver, &mut rotations).unwrap();
        micros.push(start.elapsed().as_secs_f64() * 1e6);
    }
    micros.sort_by(f64::total_cmp);
    println!("solve: median {:.1} µs, p99 {:.1} µs over 600 frames", micros[300], micros[594]);
}
