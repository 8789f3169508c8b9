//! Rigs for the tests of `--rig` and the API's `rig`: the shipped files, as JSON, and forward
//! kinematics written out here (independent of the library) to make targets a rig can reach.
//! Use it with `#[path = "common/rigs.rs"] mod rigs;`.
#![allow(dead_code)]

use std::path::{Path, PathBuf};

use serde_json::Value;

/// The path of `examples/rigs/NAME.toml`.
pub fn path(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/rigs").join(format!("{name}.toml"))
}

/// The path of the shipped puppet, as a command line's argument.
pub fn puppet() -> String {
    path("puppet").to_str().unwrap().to_owned()
}

/// The puppet's tip of bone `name` at its start pose.
pub fn puppet_start_tip(name: &str) -> [f64; 2] {
    let rig = json("puppet");
    let i = names(&rig).iter().position(|n| n == name).unwrap();
    tips(&rig, &start_deg(&rig))[i].0
}

/// `examples/rigs/NAME.toml` as the JSON a request carries.
pub fn json(name: &str) -> Value {
    toml::from_str(&std::fs::read_to_string(path(name)).unwrap()).unwrap()
}

/// The names of a rig's bones, in file order.
pub fn names(rig: &Value) -> Vec<String> {
    rig["bones"].as_array().unwrap().iter().map(|b| b["name"].as_str().unwrap().to_owned()).collect()
}

/// The start angles, degrees, in file order.
pub fn start_deg(rig: &Value) -> Vec<f64> {
    rig["bones"].as_array().unwrap().iter().map(|b| b["angle_deg"].as_f64().unwrap_or(0.0)).collect()
}

/// Every bone's tip and absolute direction (degrees) at `angles_deg` (file order), from the
/// base (the origin unless `base` says otherwise).
pub fn tips(rig: &Value, angles_deg: &[f64]) -> Vec<([f64; 2], f64)> {
    let bones = rig["bones"].as_array().unwrap();
    let names = names(rig);
    let base = rig
        .get("base")
        .and_then(|b| b.as_array())
        .map_or([0.0, 0.0], |b| [b[0].as_f64().unwrap(), b[1].as_f64().unwrap()]);
    fn at(i: usize, bones: &[Value], names: &[String], angles: &[f64], base: [f64; 2]) -> ([f64; 2], f64) {
        let (start, phi) = match bones[i].get("parent").and_then(Value::as_str) {
            Some(p) => at(names.iter().position(|n| n == p).unwrap(), bones, names, angles, base),
            None => (base, 0.0),
        };
        let phi = phi + angles[i];
        let l = bones[i]["length"].as_f64().unwrap();
        ([start[0] + l * phi.to_radians().cos(), start[1] + l * phi.to_radians().sin()], phi)
    }
    (0..bones.len()).map(|i| at(i, bones, &names, angles_deg, base)).collect()
}

/// A pose of the puppet inside its limits, reaching forward with both hands, legs as they start.
pub fn puppet_reaching_deg() -> Vec<f64> {
    let rig = json("puppet");
    let mut angles = start_deg(&rig);
    for (bone, deg) in [
        ("spine", -10.0),
        ("left_upper_arm", -100.0),
        ("left_forearm", 40.0),
        ("right_upper_arm", -60.0),
        ("right_forearm", 30.0),
        ("right_hand", 10.0),
    ] {
        angles[names(&rig).iter().position(|n| n == bone).unwrap()] = deg;
    }
    angles
}

/// Where the puppet's hands are in [`puppet_reaching_deg`]: `(name, [x, y])`.
pub fn puppet_hand_targets() -> Vec<(&'static str, [f64; 2])> {
    let rig = json("puppet");
    let tips = tips(&rig, &puppet_reaching_deg());
    let names = names(&rig);
    ["right_hand", "left_hand"].into_iter().map(|h| (h, tips[names.iter().position(|n| n == h).unwrap()].0)).collect()
}
