//! Bad files: hand-made ones with their exact messages, and the four example files cut short
//! and with bytes flipped (every outcome a value or a one-line message, never a panic).

use super::to_json;
use crate::error::Error;

/// A file built byte by byte.
#[derive(Default)]
struct File(Vec<u8>);

impl File {
    fn bytes(mut self, b: &[u8]) -> Self {
        self.0.extend_from_slice(b);
        self
    }
    fn string(self, s: &str) -> Self {
        let n = u8::try_from(s.len() + 1).unwrap();
        self.bytes(&[n]).bytes(s.as_bytes())
    }
    fn floats(self, values: &[f32]) -> Self {
        values.iter().fold(self, |f, v| f.bytes(&v.to_be_bytes()))
    }
    /// The header of a 4.2 file without nonessential data.
    fn header() -> Self {
        File::default()
            .bytes(&[1, 2, 3, 4, 5, 6, 7, 8])
            .string("4.2.22")
            .floats(&[0.0, 0.0, 10.0, 10.0, 100.0])
            .bytes(&[0])
    }
    /// A bone: name, parent (not for the first), the seven transform values and length,
    /// inherit, skin.
    fn bone(self, name: &str, parent: Option<u8>) -> Self {
        let f = self.string(name);
        let f = match parent {
            Some(p) => f.bytes(&[p]),
            None => f,
        };
        f.floats(&[0.0, 1.0, 2.0, 1.0, 1.0, 0.0, 0.0, 5.0]).bytes(&[0, 0])
    }
}

/// A file with the bones `root` and `arm`, one slot on `arm` with a region attachment, and
/// `tail` appended after the skins (events and animations).
fn small(tail: &[u8]) -> Vec<u8> {
    let f = File::header().bytes(&[1]).string("arm-image");
    let f = f.bytes(&[2]).bone("root", None).bone("arm", Some(0));
    // One slot: name, bone 1, colour, no dark colour, attachment (string 1), blend normal.
    let f = f.bytes(&[1]).string("arm").bytes(&[1, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 1, 0]);
    // No IK, transform, path or physics constraints.
    let f = f.bytes(&[0, 0, 0, 0]);
    // The default skin: one slot (0), one attachment named by string 1: a region (flags 0).
    let f = f.bytes(&[1, 0, 1, 1, 0]).floats(&[0.0, 0.0, 1.0, 1.0, 20.0, 10.0]);
    // No named skins.
    f.bytes(&[0]).bytes(tail).0
}

#[test]
fn a_small_hand_made_file_decodes() {
    let tree = to_json(&small(&[0, 0])).unwrap();
    assert_eq!(tree["bones"][1]["parent"], "root");
    assert_eq!(tree["bones"][1]["x"], 1.0);
    assert_eq!(tree["bones"][1]["length"], 5.0);
    assert_eq!(tree["slots"][0]["attachment"], "arm-image");
    let region = &tree["skins"][0]["attachments"]["arm"]["arm-image"];
    assert_eq!(region["type"], "region");
    assert_eq!((region["width"].as_f64(), region["height"].as_f64()), (Some(20.0), Some(10.0)));
    assert_eq!(tree["skeleton"]["hash"], "AQIDBAUGBwg");
    assert_eq!(tree["animations"], serde_json::json!({}));
}

#[test]
fn bad_files_are_one_line_naming_the_byte_and_the_field() {
    let cases: Vec<(Vec<u8>, &str)> = vec![
        (vec![1, 2, 3, 4, 5], "skel: byte 0: skeleton.hash: the file ends: 8 bytes needed (got 5)"),
        (
            File::default().bytes(&[0; 8]).string("3.8.99").0,
            "skel: byte 8: skeleton.spine: this reader reads Spine 4.2's binary format (got \"3.8.99\")",
        ),
        (
            File::header().bytes(&[0xff; 5]).0,
            "skel: byte 36: strings.count: a varint has at most 5 bytes (got a 5th of 0xff)",
        ),
        (
            File::header().bytes(&[0xc0, 0x84, 0x3d]).0,
            "skel: byte 36: strings.count: a count beyond the 0 bytes left (got 1000000)",
        ),
        (
            File::header().bytes(&[0, 2]).bone("root", None).bone("arm", Some(9)).0,
            "skel: byte 81: bones[1].parent: bone index 9 out of 1",
        ),
        (small(&[0, 0, 7]), "skel: byte 178: end: bytes after the last animation (got 1)"),
        (
            small(&[0, 1]).into_iter().chain([2, b'w', 0, 9, 0]).collect(),
            "skel: byte 177: animations.count: a count beyond the 5 bytes left (got 1)",
        ),
        (
            small(&[0, 1]).into_iter().chain([2, b'w', 1, 0, 1, 0, 1, 11, 1, 0, 0, 0, 0, 0, 0, 0, 0]).collect(),
            "skel: byte 185: animations[\"w\"].bones[\"root\"].type: an unknown type (got 11)",
        ),
    ];
    for (bytes, message) in cases {
        assert_eq!(to_json(&bytes).err().map(|e| e.to_string()).as_deref(), Some(message));
    }
    // An unknown attachment type (7) in the default skin.
    let mut bad = small(&[0, 0]);
    // The attachment's type byte: before its six floats, the named skins' count and the tail.
    let at = bad.len() - 2 - 1 - 24 - 1;
    bad[at] = 7;
    assert_eq!(
        to_json(&bad).err().map(|e| e.to_string()),
        Some(format!(
            "skel: byte {at}: skins[\"default\"].attachments[\"arm\"][\"arm-image\"].type: an unknown type (got 7)"
        ))
    );
}

fn examples() -> Vec<Vec<u8>> {
    ["spineboy", "raptor", "stretchyman", "celestial-circus"]
        .iter()
        .map(|c| {
            std::fs::read(format!("{}/../../examples/characters/spine-{c}-pro.skel", env!("CARGO_MANIFEST_DIR")))
                .unwrap()
        })
        .collect()
}

/// Ok, or one line of the form `skel: byte N: …`.
fn outcome(bytes: &[u8]) -> Result<(), Error> {
    match to_json(bytes) {
        Ok(_) => Ok(()),
        Err(e) if e.to_string().starts_with("skel: byte ") && !e.to_string().contains('\n') => Ok(()),
        Err(e) => Err(e),
    }
}

#[test]
fn every_example_cut_short_is_refused_in_one_line() {
    for file in examples() {
        assert!(to_json(&file).is_ok());
        let step = (file.len() / 250).max(1);
        for len in (0..file.len()).step_by(step).chain(0..64) {
            let e = to_json(&file[..len]).expect_err("a file cut short is refused");
            assert!(e.to_string().starts_with("skel: byte ") && !e.to_string().contains('\n'), "cut at {len}: {e}");
        }
    }
}

#[test]
fn every_example_with_bytes_flipped_decodes_or_is_refused_in_one_line() {
    // A fixed sequence (a linear congruential generator): the same bytes on every run.
    let mut seed: u64 = 0x2545_f491_4f6c_dd1d;
    let mut next = move || {
        seed = seed.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
        seed >> 33
    };
    for file in examples() {
        for _ in 0..250 {
            let mut bytes = file.clone();
            for _ in 0..=next() % 3 {
                let at = usize::try_from(next()).unwrap() % bytes.len();
                bytes[at] ^= u8::try_from(next() % 255 + 1).unwrap();
            }
            if let Err(e) = outcome(&bytes) {
                panic!("flipped: {e}");
            }
        }
    }
}

#[test]
fn a_string_referred_to_over_and_over_is_refused_past_the_cap() {
    // One long string and a slot timeline keying it a million times: every reference would
    // copy it.
    let long = "x".repeat(250);
    let mut f = File::header().bytes(&[1, 0xfb, 0x01]).bytes(long.as_bytes());
    f = f
        .bytes(&[1])
        .bone("root", None)
        .bytes(&[1])
        .string("s")
        .bytes(&[0, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0, 0]);
    f = f.bytes(&[0, 0, 0, 0, 0, 0, 0, 1]).string("a").bytes(&[1, 1, 0, 1, 0]);
    let keys = 10_000;
    f = f.bytes(&[0x90, 0x4e]); // 10000 frames
    for _ in 0..keys {
        f = f.floats(&[0.0]).bytes(&[1]);
    }
    let bytes = f.bytes(&[0; 8]).0;
    let e = to_json(&bytes).err().map(|e| e.to_string()).unwrap_or_default();
    let cap = bytes.len() * 16 + (1 << 20);
    assert!(e.to_string().contains(&format!("the strings referred to exceed {cap} bytes in all")), "{e}");
}

/// The kinds the four example files do not hold, read as the format page describes them: a
/// region with a sequence, a point, a named skin with its bones and constraints and a linked
/// mesh naming it, a physics constraint, an event with audio, and alpha, inherit, physics
/// reset, sequence and event keys.
#[test]
fn the_kinds_the_examples_lack_decode_to_their_json_names() {
    let mut f = File::header().bytes(&[3]).string("img").string("pt").string("lm");
    f = f.bytes(&[1]).bone("root", None);
    f = f.bytes(&[1]).string("s").bytes(&[0, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0, 0]);
    // No IK, transform or path constraints; a physics constraint `p` on root.
    f = f.bytes(&[0, 0, 0, 1]).string("p").bytes(&[0, 0, 0, 60]).floats(&[0.5, 100.0, 0.9, 0.0, 0.0]).bytes(&[0]);
    // The default skin: a region `img` with a sequence (flags 64), a point `pt` (type 5).
    f = f.bytes(&[1, 0, 2, 1, 64, 3, 1, 2, 0]).floats(&[1.0, 2.0, 1.0, 1.0, 8.0, 4.0]);
    f = f.bytes(&[2, 5]).floats(&[45.0, 3.0, 4.0]);
    // A named skin `B` with root and `p`, and a linked mesh `lm` (type 3, inheriting timelines)
    // of skin 1 (itself), parent `img`.
    f = f.bytes(&[1]).string("B").bytes(&[1, 0, 0, 0, 0, 1, 0]);
    f = f.bytes(&[1, 0, 1, 3, 3 | 128, 1, 1]);
    // An event `e`: int -2, float 0.5, no string, audio `a.ogg` (volume 1, balance 0).
    f = f.bytes(&[1]).string("e").bytes(&[3]).floats(&[0.5]).bytes(&[0]).string("a.ogg").floats(&[1.0, 0.0]);
    // An animation `w`.
    f = f.bytes(&[1]).string("w").bytes(&[6]);
    // Slots: an alpha timeline, 2 keys (255 then 0), the first stepped.
    f = f.bytes(&[1, 0, 1, 5, 2, 0]).floats(&[0.0]).bytes(&[255]).floats(&[1.0]).bytes(&[0, 1]);
    // Bones: an inherit key at 0.5 s: noRotationOrReflection.
    f = f.bytes(&[1, 0, 1, 10, 1]).floats(&[0.5]).bytes(&[2]);
    // No IK, transform, path timelines; physics: every constraint (0), a reset at 0.25 s.
    f = f.bytes(&[0, 0, 0, 1, 0, 1, 8, 1]).floats(&[0.25]);
    // Attachments: skin 0, slot 0, `img`: a sequence key (loop, index 5, delay 0.1).
    f = f.bytes(&[1, 0, 1, 0, 1, 1, 1, 1]).floats(&[0.0]).bytes(&[0, 0, 0, 0x52]).floats(&[0.1]);
    // No draw order; an event key at 0.3 s: `e`, int 7, float 1.5, string "hi".
    f = f.bytes(&[0, 1]).floats(&[0.3]).bytes(&[0, 14]).floats(&[1.5]).bytes(&[1]).string("hi").floats(&[1.0, 0.0]);
    let t = to_json(&f.0).unwrap();
    let region = &t["skins"][0]["attachments"]["s"]["img"];
    assert_eq!(region["sequence"], serde_json::json!({"count": 3, "start": 1, "digits": 2, "setup": 0}));
    let point = &t["skins"][0]["attachments"]["s"]["pt"];
    assert_eq!(
        (point["type"].as_str(), point["rotation"].as_f64(), point["y"].as_f64()),
        (Some("point"), Some(45.0), Some(4.0))
    );
    let b = &t["skins"][1];
    assert_eq!(
        (b["name"].as_str(), &b["bones"], &b["physics"]),
        (Some("B"), &serde_json::json!(["root"]), &serde_json::json!(["p"]))
    );
    let linked = &b["attachments"]["s"]["lm"];
    assert_eq!(
        (linked["type"].as_str(), linked["skin"].as_str(), linked["parent"].as_str()),
        (Some("linkedmesh"), Some("B"), Some("img"))
    );
    assert_eq!(linked["timelines"], true);
    assert_eq!(t["physics"][0]["fps"], 60);
    assert_eq!(
        t["events"]["e"],
        serde_json::json!({"int": -2, "float": 0.5, "audio": "a.ogg", "volume": 1.0, "balance": 0.0})
    );
    let w = &t["animations"]["w"];
    assert_eq!(
        w["slots"]["s"]["alpha"],
        serde_json::json!([{"time": 0.0, "value": 1.0, "curve": "stepped"}, {"time": 1.0, "value": 0.0}])
    );
    assert_eq!(w["bones"]["root"]["inherit"], serde_json::json!([{"time": 0.5, "inherit": "noRotationOrReflection"}]));
    assert_eq!(w["physics"][""]["reset"], serde_json::json!([{"time": 0.25}]));
    let key = &w["attachments"]["default"]["s"]["img"]["sequence"][0];
    assert_eq!((key["mode"].as_str(), key["index"].as_i64()), (Some("loop"), Some(5)));
    let event = &w["events"][0];
    assert_eq!(
        (event["name"].as_str(), event["int"].as_i64(), event["string"].as_str()),
        (Some("e"), Some(7), Some("hi"))
    );
}
