//! Which bones take part in a pose with the default skin: the reference files of Spine's runtime
//! (spine-core 4.2.119, the default skin set) say it per bone (`active`), for every case of the
//! four characters.

use ikarus::character::{PoseRequest, Posed};
use serde_json::Value;

#[test]
fn the_default_skin_turns_on_the_bones_the_runtime_turns_on() {
    for (file, reference) in [
        ("spine-spineboy-pro.json", "spine-spineboy-pro-full.json"),
        ("spine-raptor-pro.json", "spine-raptor-pro-full.json"),
        ("spine-stretchyman-pro.json", "spine-stretchyman-pro-full.json"),
        ("spine-celestial-circus-pro.json", "spine-celestial-circus-pro-full.json"),
    ] {
        let dir = env!("CARGO_MANIFEST_DIR");
        let text = std::fs::read_to_string(format!("{dir}/../../examples/characters/{file}")).unwrap();
        let c = ikarus_edge::character::load(&text, file).unwrap().character;
        let r: Value =
            serde_json::from_str(&std::fs::read_to_string(format!("{dir}/tests/reference/{reference}")).unwrap())
                .unwrap();
        let skin = ikarus_edge::pose::skin_index(&c, None).unwrap();
        assert_eq!(skin.map(|s| c.skins()[s].name.as_str()), Some("default"), "{file}");
        let mut posed = Posed::default();
        let (mut bones, mut cases) = (0, 0);
        for case in r["cases"].as_array().unwrap() {
            let what = &case["case"];
            let clip = what
                .get("animation")
                .map(|a| (c.clip_index(a.as_str().unwrap()).unwrap(), what["time"].as_f64().unwrap()));
            c.pose(&PoseRequest { clip, skin, ..PoseRequest::default() }, &mut posed).unwrap();
            for (i, b) in c.bones().iter().enumerate() {
                let want = case["bones"][&b.name]["active"].as_bool().unwrap();
                assert_eq!(posed.is_active(i), want, "{file} {what}: {}", b.name);
                bones += 1;
            }
            cases += 1;
        }
        println!("{file}: {cases} cases, {bones} bones' active flags as the runtime's");
    }
}
