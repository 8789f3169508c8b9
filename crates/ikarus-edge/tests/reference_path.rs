//! Path constraints posed as Spine's runtime poses them: stretchyman's four paths (weighted,
//! open, percent spacing, chain scale, two of them deformed by `sneak`) against spine-core
//! 4.2.119's output (`tests/reference/spine-stretchyman-pro-full.json`, a copy of
//! `characters/reference/full/`): every case, every bone a path constraint moves and every bone
//! outside the two transform constraints' reach (those, `back-foot1`, `front-foot1` and the
//! bones below them, are left inactive until transform constraints are read), world x, y within
//! 1e-3 and rotation within 1e-3°.

use ikarus::character::{Character, Constraint, PoseRequest, Posed};
use serde_json::Value;

fn num(v: &Value) -> f64 {
    v.as_f64().unwrap()
}

fn load(file: &str) -> Character {
    let text =
        std::fs::read_to_string(format!("{}/../../examples/characters/{file}", env!("CARGO_MANIFEST_DIR"))).unwrap();
    ikarus_edge::character::load(&text, file).unwrap().character
}

/// Which bones are one of `tops` or below one.
fn below(c: &Character, tops: &[&str]) -> Vec<bool> {
    let mut out = vec![false; c.bones().len()];
    for (i, b) in c.bones().iter().enumerate() {
        out[i] = tops.contains(&b.name.as_str()) || b.parent.is_some_and(|p| out[p]);
    }
    out
}

#[test]
fn stretchyman_paths_are_posed_as_the_runtime_does() {
    let c = load("spine-stretchyman-pro.json");
    let r: Value = serde_json::from_str(
        &std::fs::read_to_string(format!(
            "{}/tests/reference/spine-stretchyman-pro-full.json",
            env!("CARGO_MANIFEST_DIR")
        ))
        .unwrap(),
    )
    .unwrap();
    let paths: Vec<_> = c
        .constraints()
        .iter()
        .filter_map(|k| match k {
            Constraint::Path(p) => Some(p),
            _ => None,
        })
        .collect();
    assert_eq!(paths.len(), 4);
    assert!(c.unsupported().iter().all(|u| u.kind != "path"));
    let skipped = below(&c, &["back-foot1", "front-foot1"]);
    let moved: Vec<bool> = (0..c.bones().len()).map(|i| paths.iter().any(|p| p.bones.contains(&i))).collect();
    let mut posed = Posed::default();
    let mut overall = (0.0f64, 0.0f64, String::new());
    for case in r["cases"].as_array().unwrap() {
        let clip = case["case"]["animation"].as_str().map(|n| (c.clip_index(n).unwrap(), num(&case["case"]["time"])));
        c.pose(&PoseRequest { clip, ..PoseRequest::default() }, &mut posed).unwrap();
        let mut worst = (0.0f64, 0.0f64, String::new(), 0usize);
        for (i, b) in c.bones().iter().enumerate().filter(|(i, _)| !skipped[*i]) {
            let rb = &case["bones"][&b.name];
            let [x, y] = posed.origin(i);
            let d = (x - num(&rb["x"])).hypot(y - num(&rb["y"]));
            let t = (posed.rotation(i).to_degrees() - num(&rb["rotation_deg"])).rem_euclid(360.0);
            let t = t.min(360.0 - t);
            if d.max(t) > worst.0.max(worst.1) {
                worst.2 = b.name.clone();
            }
            worst = (worst.0.max(d), worst.1.max(t), worst.2, worst.3 + usize::from(moved[i]));
        }
        println!(
            "{}: position {:.3e}, rotation {:.3e}° (worst bone {}; {} path-moved bones compared)",
            case["case"], worst.0, worst.1, worst.2, worst.3
        );
        assert_eq!(worst.3, 24);
        assert!(worst.0 < 1e-3 && worst.1 < 1e-3, "{}: {worst:?}", case["case"]);
        if worst.0.max(worst.1) > overall.0.max(overall.1) {
            overall.2 = format!("{} {}", case["case"], worst.2);
        }
        overall = (overall.0.max(worst.0), overall.1.max(worst.1), overall.2);
    }
    println!("largest: position {:.3e}, rotation {:.3e}° ({})", overall.0, overall.1, overall.2);
}
