//! Every case of the four full reference files (`tests/reference/*-full.json`: Spine's runtime,
//! spine-core 4.2.119, posing spineboy, the raptor, stretchyman and celestial-circus with every
//! constraint active and the default skin) posed through the edge as `ikarus pose` poses them:
//! every active bone's world origin within 1e-3 units and its rotation within 1e-3°, the
//! bones the runtime leaves inactive reported inactive. A case with `"physics": true` is played
//! from 0 at 60 frames a second with physics, as the file's protocol says; the others are posed
//! with physics left out (the runtime's `Physics.none`).

use ikarus_edge::character::{Loaded, load};
use ikarus_edge::pose::{PhysicsAsk, PoseAsk, pose};
use serde_json::Value;

/// The largest differences of one file: units, degrees, and where.
#[derive(Debug, Default)]
struct Worst {
    units: f64,
    degrees: f64,
    at: String,
}

fn character(file: &str) -> Loaded {
    let path = format!("{}/../../examples/characters/{file}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    load(&text, file).unwrap()
}

fn reference(name: &str) -> Value {
    let path = format!("{}/tests/reference/{name}", env!("CARGO_MANIFEST_DIR"));
    serde_json::from_str(&std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"))).unwrap()
}

/// The angle `a − b` in degrees, wrapped into (−180, 180].
fn turn(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(360.0);
    if d > 180.0 { d - 360.0 } else { d }
}

fn compare(file: &str) -> Worst {
    let loaded = character(file);
    let r = reference(&file.replace(".json", "-full.json"));
    let mut worst = Worst::default();
    for case in r["cases"].as_array().unwrap() {
        let spec = &case["case"];
        let animation = spec["animation"].as_str().map(str::to_owned);
        let time = animation.as_ref().map(|_| spec["time"].as_f64().unwrap());
        let played = spec["physics"].as_bool() == Some(true);
        let physics = if played { PhysicsAsk::Play { fps: 60.0 } } else { PhysicsAsk::Off };
        let ask = PoseAsk { animation: animation.clone(), time, physics, ..PoseAsk::default() };
        let report = pose(&loaded, &ask).unwrap_or_else(|e| panic!("{file} {spec}: {e}"));
        let label = format!(
            "{} at {:?}{}",
            animation.as_deref().unwrap_or("setup"),
            time,
            if played { " with physics" } else { "" }
        );
        for (name, want) in case["bones"].as_object().unwrap() {
            let got = report.bones.iter().find(|b| &b.name == name).unwrap_or_else(|| panic!("{file}: no bone {name}"));
            let active = want["active"].as_bool().unwrap_or(true);
            assert_eq!(got.active, active, "{file} {label}: bone {name}'s activity");
            if !active {
                continue;
            }
            let units = (got.x - want["x"].as_f64().unwrap()).abs().max((got.y - want["y"].as_f64().unwrap()).abs());
            let degrees = turn(got.rotation_deg, want["rotation_deg"].as_f64().unwrap()).abs();
            if units > worst.units || degrees > worst.degrees {
                worst.at = format!("{label}, bone {name}");
            }
            worst.units = worst.units.max(units);
            worst.degrees = worst.degrees.max(degrees);
            assert!(
                units <= 1e-3 && degrees <= 1e-3,
                "{file} {label}: bone {name} is {units} units and {degrees}° from the runtime's"
            );
        }
    }
    println!("{file}: largest difference {} units, {}° ({})", worst.units, worst.degrees, worst.at);
    worst
}

#[test]
fn spineboy_every_case_as_the_runtime_poses_it() {
    compare("spine-spineboy-pro.json");
}

#[test]
fn the_raptor_every_case_as_the_runtime_poses_it() {
    compare("spine-raptor-pro.json");
}

#[test]
fn stretchyman_every_case_as_the_runtime_poses_it() {
    compare("spine-stretchyman-pro.json");
}

#[test]
fn celestial_circus_every_case_as_the_runtime_plays_it() {
    compare("spine-celestial-circus-pro.json");
}
