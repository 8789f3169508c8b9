//! `POST /api/rig/parse` of a Spine binary export (issue 39, point 6): the `.skel`'s bytes, sent
//! as `application/octet-stream`, are decoded into the JSON text the command line reads and kept
//! under the answer's id, so that every later request by id works as for the JSON; `?text=1`
//! echoes that text. Bytes that are not a character are a 422 with the decoder's one line.

mod common;

use common::server::start;
use common::{ikarus, stderr, stdout};
use serde_json::{Value, json};

const SKEL: &str = "../../examples/characters/spine-spineboy-pro.skel";
const JSON: &str = "../../examples/characters/spine-spineboy-pro.json";
const OCTETS: &str = "application/octet-stream";

/// Writes `bytes` to `NAME` in a directory of this test process's own and gives its path.
fn temp_bytes(name: &str, bytes: &[u8]) -> String {
    let dir = std::env::temp_dir().join(format!("ikarus-test-serve-skel-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path.to_str().unwrap().to_owned()
}

#[test]
fn a_skel_is_read_as_its_json_and_posed_by_id_as_the_cli_poses_it() {
    let s = start(&[]);
    let bytes = std::fs::read(SKEL).unwrap();
    let from_skel = s.post_raw("/api/rig/parse?text=1", OCTETS, &bytes);
    assert_eq!(from_skel.status, 200, "{}", from_skel.text());
    let from_skel = from_skel.json();
    let json_text = std::fs::read_to_string(JSON).unwrap();
    let from_json = s.post_raw("/api/rig/parse", "application/toml", json_text.as_bytes()).json();
    assert_eq!(from_json.get("text"), None, "no text unless asked");
    let (a, b) = (&from_skel["character"], &from_json["character"]);
    assert_eq!(a["bones"].as_array().unwrap().len(), 67);
    let names = |c: &Value| c["bones"].as_array().unwrap().iter().map(|b| b["name"].clone()).collect::<Vec<_>>();
    assert_eq!(names(a), names(b));
    assert_eq!(a["format"], b["format"]);
    // The constraints and clips: the same, but for the JSON's rounding of durations and a
    // one-bone IK's `bend_positive` (without effect on one bone: the binary stores false where
    // the JSON omits it, true by default).
    let (ik_a, ik_b) = (a["ik"].as_array().unwrap(), b["ik"].as_array().unwrap());
    assert_eq!(ik_a.len(), 7);
    for (x, y) in ik_a.iter().zip(ik_b) {
        for field in ["name", "bones", "target", "order", "mix", "rule"] {
            assert_eq!(x[field], y[field], "{field}");
        }
    }
    let (clips_a, clips_b) = (a["clips"].as_array().unwrap(), b["clips"].as_array().unwrap());
    assert_eq!(clips_a.len(), clips_b.len());
    for (x, y) in clips_a.iter().zip(clips_b) {
        assert_eq!(x["name"], y["name"]);
        assert!((x["duration"].as_f64().unwrap() - y["duration"].as_f64().unwrap()).abs() < 1e-4, "{x} {y}");
    }
    for (x, y) in a["bones"].as_array().unwrap().iter().zip(b["bones"].as_array().unwrap()) {
        assert_eq!(x["parent"], y["parent"]);
        for field in ["x", "y", "rotation_deg", "length"] {
            let d = (x[field].as_f64().unwrap() - y[field].as_f64().unwrap()).abs();
            assert!(d < 0.15, "{} {field}: {x} vs {y}", x["name"]);
        }
    }
    // The echoed text is the decoded JSON: read again as text, the same character.
    let text = from_skel["text"].as_str().unwrap();
    let again = s.post_raw("/api/rig/parse", "application/toml", text.as_bytes()).json();
    assert_eq!(again["character"]["bones"], a["bones"]);

    // Posed by id, the bytes `ikarus pose --rig X.skel --format json` prints.
    let id = a["id"].as_str().unwrap();
    let args = ["--animation", "walk", "--time", "0.25", "--target", "front-leg-target=60,20"];
    let o = ikarus(&[&["pose", "--rig", SKEL, "--format", "json"][..], &args[..]].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    let body = json!({"character": id, "animation": "walk", "time": 0.25,
        "targets": [{"bone": "front-leg-target", "x": 60, "y": 20}]});
    let posed = s.post("/api/pose", &body);
    assert_eq!(posed.status, 200, "{}", posed.text());
    assert_eq!(posed.text().trim_end(), stdout(&o).trim_end());
    // And by id it plays: an animation of the kept character.
    let motion = s.post(
        "/api/animate",
        &json!({"character": id, "targets": [{"bone": "front-leg-target", "x": 300, "y": 20}], "fps": 10}),
    );
    assert_eq!(motion.status, 200, "{}", motion.text());
    s.assert_healthy();
}

#[test]
fn bytes_that_are_not_a_character_are_422_with_one_line() {
    let s = start(&[]);
    let bytes = std::fs::read(SKEL).unwrap();
    let cut = &bytes[..bytes.len() / 3];
    let e = s.post_raw("/api/rig/parse", OCTETS, cut).error(422);
    assert!(e.starts_with("rig file: skel: byte "), "{e}");
    let o = ikarus(&["pose", "--rig", &temp_bytes("cut.skel", cut), "--format", "json"]);
    assert!(stderr(&o).contains(e.trim_start_matches("rig file: ")), "the CLI's message: {}", stderr(&o));
    // A picture is neither UTF-8 nor a 4.2 export.
    let png = [0x89, b'P', b'N', b'G', b'\r', b'\n', 0x1a, b'\n', 0, 0, 0, 13, b'I', b'H', b'D', b'R', 0xff, 0xfe];
    let e = s.post_raw("/api/rig/parse", OCTETS, &png).error(422);
    assert!(e.starts_with("rig file: "), "{e}");
    // Any other type is refused, the two accepted named.
    let e = s.post_raw("/api/rig/parse", "image/png", &png).error(415);
    assert!(e.contains("application/toml or application/octet-stream"), "{e}");
    let e = s.post_raw("/api/rig/parse?text=yes", OCTETS, &bytes).error(422);
    assert_eq!(e, "query: text = \"yes\": expected 1 or 0");
    s.assert_healthy();
}

#[test]
fn the_file_cap_applies_to_the_bytes() {
    let bytes = std::fs::read(SKEL).unwrap();
    let s = start(&["--max-file-bytes", "60000"]);
    let e = s.post_raw("/api/rig/parse", OCTETS, &bytes).error(413);
    assert!(e.contains("60000") && e.contains("--max-file-bytes"), "{e}");
    let s = start(&["--max-file-bytes", "70000"]);
    assert_eq!(s.post_raw("/api/rig/parse", OCTETS, &bytes).status, 200);
}
