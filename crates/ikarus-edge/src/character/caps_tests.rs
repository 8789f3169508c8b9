//! What a hostile character file cannot make the reader do: animations named alike (refused,
//! the reading linear in the file), constraints far past the bones (refused, counted before
//! anything is read), and bones in an armature after the first (counted under the cap).

use super::*;

fn refused_within(text: &str, cap: BoneCap) -> String {
    match load_within(text, "f", cap) {
        Ok(_) => panic!("accepted a file of {} bytes", text.len()),
        Err(e) => {
            let e = e.to_string();
            assert!(!e.contains('\n'), "more than one line: {e}");
            e
        }
    }
}

/// 73,000 animations named `"a"` and one more with 36,500 keys (1,047,500 bytes, under the
/// server's 1 MiB): each one's duration was measured by looking its name up, which found the
/// big one, so reading took 45–115 s. The second `"a"` is refused as soon as it is read.
#[test]
fn animations_named_alike_are_refused_naming_the_name() {
    let mut text = String::from(r#"{"skeleton": {"spine": "4.2"}, "bones": [{"name": "root"}], "animations": {"#);
    for _ in 0..73_000 {
        text.push_str(r#""a": {}, "#);
    }
    text.push_str(r#""a": {"bones": {"root": {"rotate": ["#);
    let keys: Vec<String> = (0..36_500).map(|k| format!(r#"{{"time": {k}}}"#)).collect();
    text.push_str(&keys.join(","));
    text.push_str("]}}}}}");
    assert!(text.len() > 1_000_000, "{} bytes", text.len());
    let e = refused_within(&text, BoneCap::flag(256));
    assert!(e.starts_with("f: animations: \"a\" is listed twice in this object"), "{e}");
    // Names listed once each are read as before.
    let ok = r#"{"skeleton": {"spine": "4.2"}, "bones": [{"name": "root"}], "animations": {"a": {}, "b": {}}}"#;
    let loaded = load_within(ok, "f", BoneCap::flag(256)).unwrap();
    assert_eq!(loaded.character.clips().len(), 2);
}

/// A Spine file of `bones` bones in a chain with `ik` one-bone IK constraints, each on bone
/// `i % bones` aiming at the root.
fn spine_chain(bones: usize, ik: usize) -> String {
    let mut b = vec![r#"{"name": "b0"}"#.to_owned()];
    b.extend((1..bones).map(|i| format!(r#"{{"name": "b{i}", "parent": "b{}", "length": 1}}"#, i - 1)));
    let k: Vec<String> = (0..ik)
        .map(|i| format!(r#"{{"name": "k{i}", "bones": ["b{}"], "target": "b0"}}"#, 1 + i % (bones - 1)))
        .collect();
    format!(r#"{{"skeleton": {{"spine": "4.2"}}, "bones": [{}], "ik": [{}]}}"#, b.join(","), k.join(","))
}

/// 18,893 one-bone IK constraints on a 256-bone chain made one pose with ikarus's solver 750 s
/// of CPU; constraints are now counted against the bones before anything is read.
#[test]
fn constraints_past_four_a_bone_are_refused_before_they_are_read() {
    let e = refused_within(&spine_chain(256, 18_893), BoneCap::flag(256));
    assert_eq!(
        e,
        "f: ik, transform, path, physics: 18893 constraints for 256 bones, more than the cap of 1024 (4 a bone, at least 64)"
    );
    load_within(&spine_chain(256, 1024), "f", BoneCap::flag(256)).unwrap();
    // A small character may still have a few constraints more than bones.
    load_within(&spine_chain(3, 64), "f", BoneCap::flag(256)).unwrap();
    let e = refused_within(&spine_chain(3, 65), BoneCap::flag(256));
    assert!(e.contains("65 constraints for 3 bones, more than the cap of 64"), "{e}");
}

/// A DragonBones file's second armature was parsed whatever its size, under a cap that counted
/// the first one's bones only.
#[test]
fn every_armatures_bones_count_under_the_cap() {
    let bones = |n: usize, prefix: &str| -> String {
        let list: Vec<String> = (0..n).map(|i| format!(r#"{{"name": "{prefix}{i}"}}"#)).collect();
        list.join(",")
    };
    let text = format!(
        r#"{{"version": "5.5", "frameRate": 24, "armature": [{{"name": "a", "bone": [{}]}}, {{"name": "b", "bone": [{}]}}]}}"#,
        bones(1, "a"),
        bones(200, "b")
    );
    let e = refused_within(&text, BoneCap::flag(100));
    assert_eq!(e, "f: bones: 201 bones exceed the cap of 100 (--max-bones)");
    load_within(&text, "f", BoneCap::flag(201)).unwrap();
}
