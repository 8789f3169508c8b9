//! Transform constraints posed as Spine's runtime poses them: every active bone's world
//! position within 1e-3 units and the direction of its x axis within 1e-3° of the runtime's own
//! output with every constraint active (`tests/reference/*-full.json`, spine-core 4.2.119).

use ikarus::character::{Character, PoseRequest, Posed};
use serde_json::Value;

fn load(file: &str) -> Character {
    let path = format!("{}/../../examples/characters/{file}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap();
    ikarus_edge::character::load(&text, file).unwrap().character
}

fn reference(file: &str) -> Value {
    let path = format!("{}/tests/reference/{file}", env!("CARGO_MANIFEST_DIR"));
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// The largest differences over `file`'s cases without physics: (position, bone, case) and
/// (rotation in degrees, bone, case), over the bones the reference marks active.
fn largest(file: &str, reference_file: &str) -> [(f64, String); 2] {
    let c = load(file);
    let r = reference(reference_file);
    let mut posed = Posed::default();
    let mut worst = [(0.0, String::new()), (0.0, String::new())];
    let mut cases = 0;
    for case in r["cases"].as_array().unwrap() {
        let what = &case["case"];
        if what.get("physics").is_some() {
            continue;
        }
        cases += 1;
        let clip =
            what.get("animation").map(|a| (c.clip_index(a.as_str().unwrap()).unwrap(), what["time"].as_f64().unwrap()));
        c.pose(&PoseRequest { clip, targets: &[], bends: &[], turns: &[], skin: None }, &mut posed).unwrap();
        for (i, b) in c.bones().iter().enumerate() {
            let rb = &case["bones"][&b.name];
            if rb["active"] == Value::Bool(false) {
                continue;
            }
            let o = posed.origin(i);
            let position = (o[0] - rb["x"].as_f64().unwrap()).hypot(o[1] - rb["y"].as_f64().unwrap());
            let turn = (posed.rotation(i).to_degrees() - rb["rotation_deg"].as_f64().unwrap()).rem_euclid(360.0);
            for (w, d) in worst.iter_mut().zip([position, turn.min(360.0 - turn)]) {
                if d > w.0 {
                    *w = (d, format!("{} in {what}", b.name));
                }
            }
        }
    }
    println!("{file}: {cases} cases, largest differences: position {:?}, rotation (°) {:?}", worst[0], worst[1]);
    worst
}

#[test]
fn spineboy_with_its_transform_constraints_is_posed_as_the_runtime_does() {
    let [position, rotation] = largest("spine-spineboy-pro.json", "spine-spineboy-pro-full.json");
    assert!(position.0 < 1e-3, "{position:?}");
    assert!(rotation.0 < 1e-3, "{rotation:?}");
}

#[test]
fn celestial_circus_without_physics_is_posed_as_the_runtime_does() {
    let [position, rotation] = largest("spine-celestial-circus-pro.json", "spine-celestial-circus-pro-full.json");
    assert!(position.0 < 1e-3, "{position:?}");
    assert!(rotation.0 < 1e-3, "{rotation:?}");
}

/// Stretchyman's feet follow the ends of legs its path constraints move (which ikarus does not
/// apply yet), so the pose is not compared; its two transform constraints are checked on the
/// runtime's own bones instead: each foot's world transform, put through the constraint with the
/// runtime's target, comes back unchanged (translate and shear mixes 1 put the foot exactly at
/// the target's point and skew, the others are 0), within 1e-3 units and 1e-3°.
#[test]
fn stretchymans_feet_are_where_their_transform_constraints_put_them() {
    use ikarus::character::{Affine, Constraint, world_absolute};
    let c = load("spine-stretchyman-pro.json");
    let r = reference("spine-stretchyman-pro-full.json");
    let world = |bones: &Value, name: &str| {
        let b = &bones[name];
        let n = |k: &str| b[k].as_f64().unwrap();
        Affine { a: n("a"), b: n("b"), c: n("c"), d: n("d"), x: n("x"), y: n("y") }
    };
    let mut worst: (f64, f64) = (0.0, 0.0);
    let mut checked = 0;
    for case in r["cases"].as_array().unwrap() {
        for k in c.constraints() {
            let Constraint::Transform(t) = k else { continue };
            let target = world(&case["bones"], &c.bones()[t.target].name);
            for &b in &t.bones {
                let before = world(&case["bones"], &c.bones()[b].name);
                let after = world_absolute(&before, &target, &t.offsets, &t.setup);
                let skew = |m: &Affine| (m.d.atan2(m.b) - m.c.atan2(m.a)).to_degrees();
                worst.0 = worst.0.max((after.x - before.x).hypot(after.y - before.y));
                worst.1 = worst
                    .1
                    .max((skew(&after) - skew(&before)).abs())
                    .max((after.rotation() - before.rotation()).abs().to_degrees());
                checked += 1;
            }
        }
    }
    println!("stretchyman: {checked} feet, largest differences: position {}, angle (°) {}", worst.0, worst.1);
    assert_eq!(checked, 14);
    assert!(worst.0 < 1e-3 && worst.1 < 1e-3, "{worst:?}");
}
