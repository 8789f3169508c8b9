//! Path constraints posed as Spine's runtime poses them: stretchyman's four paths (weighted,
//! open, percent spacing, chain scale) against spine-core 4.2.119's output
//! (`/work/shared/characters/reference/full/spine-stretchyman-pro-full.json`, copied to
//! `tests/reference/`).

use ikarus::character::{Affine, Chain, PathScratch, PoseRequest, Posed, solve_path};
use serde_json::Value;

fn num(v: &Value) -> f64 {
    v.as_f64().unwrap()
}

#[test]
fn stretchyman_paths_are_posed_as_the_runtime_does() {
    let file = "spine-stretchyman-pro.json";
    let text =
        std::fs::read_to_string(format!("{}/../../examples/characters/{file}", env!("CARGO_MANIFEST_DIR"))).unwrap();
    let c = ikarus_edge::character::load(&text, file).unwrap().character;
    let paths = ikarus_edge::character::spine_paths(&text).unwrap();
    let r: Value = serde_json::from_str(
        &std::fs::read_to_string(format!(
            "{}/tests/reference/spine-stretchyman-pro-full.json",
            env!("CARGO_MANIFEST_DIR")
        ))
        .unwrap(),
    )
    .unwrap();
    let mut order: Vec<usize> = (0..paths.len()).collect();
    order.sort_by_key(|&k| paths[k].order);
    let mut posed = Posed::default();
    let mut scratch = PathScratch::default();
    let mut overall = (0.0f64, 0.0f64);
    for case in r["cases"].as_array().unwrap() {
        let clip = case["case"]["animation"].as_str().map(|n| (c.clip_index(n).unwrap(), num(&case["case"]["time"])));
        c.pose(&PoseRequest { clip, ..PoseRequest::default() }, &mut posed).unwrap();
        let mut world: Vec<Affine> = (0..c.bones().len()).map(|i| posed.world(i)).collect();
        let deforms = match case["case"]["animation"].as_str() {
            Some(n) => ikarus_edge::character::spine_path_deforms(&text, n).unwrap(),
            None => vec![],
        };
        for &k in &order {
            let p = &paths[k];
            let mut chain: Vec<Affine> = p.bones.iter().map(|&b| world[b]).collect();
            let length: Vec<f64> = p.bones.iter().map(|&b| c.bones()[b].length).collect();
            let w = world.clone();
            let mut offsets = Vec::new();
            let deformed = clip.is_some_and(|(_, t)| deforms.iter().any(|d| d.slot == p.slot && d.at(t, &mut offsets)));
            solve_path(
                p,
                &p.setup,
                &|i| w[i],
                deformed.then_some(&offsets[..]),
                Chain { world: &mut chain, length: &length },
                &mut scratch,
            );
            let mut worst = (0.0f64, 0.0f64);
            for (&b, m) in p.bones.iter().zip(&chain) {
                world[b] = *m;
                let rb = &case["bones"][&c.bones()[b].name];
                let d = (m.x - num(&rb["x"])).hypot(m.y - num(&rb["y"]));
                let t = (m.rotation().to_degrees() - num(&rb["rotation_deg"])).rem_euclid(360.0);
                let t = t.min(360.0 - t);
                worst = (worst.0.max(d), worst.1.max(t));
            }
            println!("{} {}: position {:.3e}, rotation {:.3e}°", case["case"], p.name, worst.0, worst.1);
            assert!(worst.0 < 1e-3 && worst.1 < 1e-3, "{} {}: {worst:?}", case["case"], p.name);
            overall = (overall.0.max(worst.0), overall.1.max(worst.1));
        }
    }
    println!("largest: position {:.3e}, rotation {:.3e}°", overall.0, overall.1);
}
