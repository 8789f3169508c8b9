use super::*;

/// What WebAssembly and Python call: the edges' cap on bones (the server's default for
/// WebAssembly), counted before a bone is checked, for a file's text and a request's rig.
#[test]
fn the_edges_count_a_rigs_bones_first() {
    let chain = |n: usize| -> String {
        (0..n).map(|i| format!("[[bones]]\nname = \"b{i}\"\nparent = \"b{}\"\nlength = 1\n", i.max(1) - 1)).collect()
    };
    // Bone 0 names itself its parent: a cycle, had the bones been checked.
    let limits = Limits::default();
    let interrupt = ikarus::Interrupt::new();
    let reply = super::super::call(super::super::Endpoint::RigParse, chain(257).as_bytes(), &limits, &interrupt);
    let answer: serde_json::Value = serde_json::from_slice(&reply.unwrap().body).unwrap();
    assert_eq!(
        answer,
        serde_json::json!({"problem": "rig file: bones: 257 bones exceed the cap of 256 (--max-bones)"})
    );
    let reply = super::super::call(super::super::Endpoint::RigParse, chain(256).as_bytes(), &limits, &interrupt);
    let answer: serde_json::Value = serde_json::from_slice(&reply.unwrap().body).unwrap();
    assert!(answer["problem"].as_str().unwrap().contains("a cycle (b0 → b0)"), "{answer}");
    let file: crate::rig::RigFile = toml::from_str(&chain(300)).unwrap();
    let e = super::super::bodies::load_rig(file, &Limits { max_bones: 299, ..Limits::default() }).unwrap_err();
    assert_eq!((e.status, e.message.as_str()), (422, "rig: bones: 300 bones exceed the cap of 299 (--max-bones)"));
}

/// A Spine or DragonBones file answers with the character; a bad one with its one line.
#[test]
fn a_character_file_answers_with_its_bones_constraints_and_clips() {
    let spineboy = include_str!("../../../../examples/characters/spine-spineboy-pro.json");
    let reply = super::super::call(
        super::super::Endpoint::RigParse,
        spineboy.as_bytes(),
        &Limits::default(),
        &ikarus::Interrupt::new(),
    );
    let answer: serde_json::Value = serde_json::from_slice(&reply.unwrap().body).unwrap();
    let c = &answer["character"];
    assert_eq!((c["format"].as_str(), c["version"].as_str()), (Some("spine"), Some("4.2.22")));
    assert_eq!((c["bones"].as_array().unwrap().len(), c["ik"].as_array().unwrap().len()), (67, 7));
    assert_eq!(
        c["bones"][1],
        serde_json::json!({"name": "hip", "parent": "root", "length": 0.0, "x": 0.0, "y": 247.27, "rotation_deg": 0.0,
            "scale_x": 1.0, "scale_y": 1.0, "shear_x_deg": 0.0, "shear_y_deg": 0.0, "inherit": "normal"})
    );
    assert_eq!(c["ik"][4]["bones"], serde_json::json!(["front-thigh", "front-shin"]));
    assert_eq!(c["clips"][10], serde_json::json!({"name": "walk", "duration": 1.0}));
    // Spineboy's bounding box, not drawn (its transform constraints are applied, its
    // clipping attachment clips the art).
    assert_eq!(
        c["unsupported"],
        serde_json::json!([{"kind": "bounding box attachment", "name": "head (skin default, slot head-bb)"}])
    );
    let parsed = parsed("{\"skeleton\": {\"spine\": \"4.2\"}, \"bones\": [{\"name\": 1}]}", &Limits::default());
    let Parsed::Problem(p) = parsed else { panic!("{parsed:?}") };
    assert!(p.starts_with("rig file: bones[0].name: invalid type: integer `1`, expected a string"), "{p}");
}

/// A `.skel`'s bytes answer as its JSON export's text does, the decoded text echoed when
/// asked; bytes that are not a character are a 422 with the decoder's one line.
#[test]
fn a_skel_answers_as_its_json_and_bad_bytes_are_422() {
    let skel = include_bytes!("../../../../examples/characters/spine-spineboy-pro.skel");
    let limits = Limits::default();
    let answer = |body: &[u8], given, echo| -> serde_json::Value {
        serde_json::from_slice(&parse_file(body, given, echo, &limits).unwrap().body).unwrap()
    };
    let from_skel = answer(skel, FileBody::Bytes, Echo::Text);
    let text = from_skel["text"].as_str().unwrap();
    assert!(text.starts_with('{'), "{text:.40}");
    let from_text = answer(text.as_bytes(), FileBody::Text, Echo::Without);
    assert_eq!(from_text.get("text"), None);
    assert_eq!(from_skel["character"]["bones"], from_text["character"]["bones"]);
    assert_eq!(from_skel["character"]["bones"].as_array().unwrap().len(), 67);
    let json = include_str!("../../../../examples/characters/spine-spineboy-pro.json");
    let from_json = answer(json.as_bytes(), FileBody::Bytes, Echo::Text);
    assert_eq!(from_json["text"].as_str(), Some(json));
    let e = parse_file(&skel[..skel.len() / 2], FileBody::Bytes, Echo::Text, &limits).unwrap_err();
    assert_eq!(e.status, 422);
    assert!(e.message.starts_with("rig file: skel: byte "), "{}", e.message);
    assert!(!e.message.contains('\n'), "{}", e.message);
    let e = parse_file(&[0x89, b'P', b'N', b'G', 0, 0, 0xff], FileBody::Bytes, Echo::Without, &limits).unwrap_err();
    assert_eq!(e.status, 422);
    assert!(e.message.starts_with("rig file: "), "{}", e.message);
    // The text route keeps answering a bad file with its problem, and refuses bytes that are not text.
    assert!(answer(b"{\"bones\": 1}", FileBody::Text, Echo::Text)["problem"].is_string());
    assert_eq!(parse_file(&skel[..], FileBody::Text, Echo::Without, &limits).unwrap_err().status, 400);
}

/// Every rig file in `examples/rigs/` is shipped, and reads.
#[test]
fn every_example_rig_is_shipped() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/rigs");
    let mut files: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .map(|p| p.file_stem().unwrap().to_str().unwrap().to_owned())
        .collect();
    files.sort();
    let mut shipped: Vec<String> = SHIPPED.iter().map(|(n, _)| (*n).to_owned()).collect();
    shipped.sort();
    assert_eq!(files, shipped);
    for (name, text) in SHIPPED {
        let rig = RigJson::parse(text, name).unwrap();
        assert_eq!(rig.name, *name);
    }
}
