//! A character's motion as frames CSV and as pictures: spineboy's front foot keyed over its
//! `walk` (the keys of `keys.rs`'s spineboy test). The CSV has a row per bone per frame whose
//! numbers are the JSON frames' bit for bit, and the same bytes through `ikarus animate` and
//! `POST /api/animate`; the GIF is the same bytes through the command line and `POST
//! /api/render`, one 800 × 800 frame per motion frame; the SVG and PNG are written; a format
//! that does not apply and a GIF over the cap are refused in one line naming them.

mod common;

use common::{SPINEBOY, ikarus, spineboy_keys, stderr, stdout};
use serde_json::{Value, json};

/// The stdout bytes of a command that succeeds (spineboy's constraints ikarus leaves inactive
/// are named on stderr).
fn bytes_of(args: &[&str]) -> Vec<u8> {
    let o = ikarus(args);
    assert!(o.status.success(), "{args:?}: {}", stderr(&o));
    o.stdout
}

/// The last line of stderr of a command that fails with status 2, after checking stdout is
/// empty.
fn refusal(args: &[&str]) -> String {
    let o = ikarus(args);
    assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
    assert!(stdout(&o).is_empty(), "{args:?} printed data");
    let err = stderr(&o);
    assert!(!err.contains("panicked"), "{err}");
    err.lines().last().unwrap().to_owned()
}

/// A directory of the test's own, and the keys written into it.
fn setup(name: &str) -> (tempfile::TempDir, String) {
    let dir = tempfile::Builder::new().prefix(&format!("ikarus-char-exports-{name}")).tempdir().unwrap();
    let keys = dir.path().join("keys.json");
    std::fs::write(&keys, spineboy_keys().to_string()).unwrap();
    let keys = keys.to_str().unwrap().to_owned();
    (dir, keys)
}

/// Splits one CSV line into fields, honouring RFC 4180 quotes.
fn fields(line: &str) -> Vec<String> {
    let (mut out, mut field, mut quoted, mut chars) = (Vec::new(), String::new(), false, line.chars().peekable());
    while let Some(c) = chars.next() {
        match (c, quoted) {
            ('"', true) if chars.peek() == Some(&'"') => {
                field.push('"');
                chars.next();
            }
            ('"', _) => quoted = !quoted,
            (',', false) => out.push(std::mem::take(&mut field)),
            _ => field.push(c),
        }
    }
    out.push(field);
    out
}

#[test]
fn the_csv_is_the_json_frames_row_by_row_and_the_same_bytes_through_the_api() {
    let (_dir, keys) = setup("csv");
    let base = ["animate", "--rig", SPINEBOY, "--keys", &keys, "--animation", "walk", "--format"];
    let csv = String::from_utf8(bytes_of(&[&base[..], &["csv"]].concat())).unwrap();
    let frames: Value = serde_json::from_slice(&bytes_of(&[&base[..], &["json"]].concat())).unwrap();
    let frames = frames["frames"].as_array().unwrap();
    let bones = frames[0]["bones"].as_array().unwrap().len();
    assert_eq!(frames.len(), 28);
    let mut lines = csv.lines();
    assert_eq!(lines.next(), Some("frame,time,bone,x,y,rotation_deg,tip_x,tip_y"));
    let rows: Vec<Vec<String>> = lines.map(fields).collect();
    assert_eq!(rows.len(), frames.len() * bones, "a row per bone per frame");
    for (i, row) in rows.iter().enumerate() {
        let (k, b) = (i / bones, i % bones);
        let (frame, bone) = (&frames[k], &frames[k]["bones"][b]);
        assert_eq!(row.len(), 8, "row {i}: {row:?}");
        assert_eq!(row[0], k.to_string());
        assert_eq!(row[2], bone["name"].as_str().unwrap());
        let want = [&frame["time"], &bone["x"], &bone["y"], &bone["rotation_deg"], &bone["tip"][0], &bone["tip"][1]];
        let got = [&row[1], &row[3], &row[4], &row[5], &row[6], &row[7]];
        for (g, w) in got.iter().zip(want) {
            let g: f64 = g.parse().unwrap_or_else(|e| panic!("row {i}: {g:?} is not a number: {e}"));
            assert_eq!(g.to_bits(), w.as_f64().unwrap().to_bits(), "row {i}: {g} vs {w}");
        }
    }
    let s = common::server::start(&[]);
    let text = std::fs::read_to_string(SPINEBOY).unwrap();
    let a =
        s.post("/api/animate", &json!({"rig": text, "keys": spineboy_keys(), "animation": "walk", "format": "csv"}));
    assert_eq!(a.status, 200, "{}", a.text());
    assert_eq!(a.content_type, "text/csv; charset=utf-8");
    assert!(a.body == csv.as_bytes(), "the API's CSV differs from the command line's");
    // `ikarus track` writes the same CSV of its motion.
    let track = String::from_utf8(bytes_of(&[
        "track",
        "--rig",
        SPINEBOY,
        "--effector",
        "front-leg-target",
        "--line",
        "0,0,40,20",
        "--samples",
        "5",
        "--format",
        "csv",
    ]))
    .unwrap();
    assert_eq!(track.lines().count(), 1 + 5 * bones);
}

#[test]
fn the_gif_is_the_same_bytes_through_the_api_one_800_square_frame_per_motion_frame() {
    let (dir, keys) = setup("gif");
    let gif = dir.path().join("walk.gif");
    let args = ["animate", "--rig", SPINEBOY, "--keys", &keys, "--animation", "walk", "--out", gif.to_str().unwrap()];
    assert!(bytes_of(&args).is_empty(), "the picture is the result: stdout stays quiet");
    let cli = std::fs::read(&gif).unwrap();
    let mut decoder = gif::DecodeOptions::new().read_info(cli.as_slice()).unwrap();
    assert_eq!((decoder.width(), decoder.height()), (800, 800));
    let mut frames = 0;
    while let Some(frame) = decoder.read_next_frame().unwrap() {
        assert!(frame.left + frame.width <= 800 && frame.top + frame.height <= 800);
        frames += 1;
    }
    assert_eq!(frames, 28, "one GIF frame per motion frame");

    let s = common::server::start(&[]);
    let text = std::fs::read_to_string(SPINEBOY).unwrap();
    let body = json!({"figure": "motion", "format": "gif", "rig": text, "keys": spineboy_keys(), "animation": "walk"});
    let a = s.post("/api/render", &body);
    assert_eq!(a.status, 200, "{}", a.text());
    assert_eq!(a.content_type, "image/gif");
    assert!(a.body == cli, "the API's GIF differs from the command line's");

    // A GIF over the cap is refused naming frames, width and height: the server's, and the
    // command line's --max-gif-pixels.
    let mut big = body.clone();
    big["width"] = json!(4096);
    big["height"] = json!(4096);
    let e = s.post("/api/render", &big).error(422);
    assert!(e.starts_with("frames, width, height: 28 frames of 4096×4096"), "{e}");
    let e = refusal(&[&args[..], &["--max-gif-pixels", "1000"]].concat());
    assert!(e.starts_with("ikarus: --out: a GIF of 28 frames of 800×800"), "{e}");
    // The picture's own fields only: a field of another course is refused, naming it.
    let mut odd = body.clone();
    odd["goal"] = json!({"x": 1, "y": 2});
    let e = s.post("/api/render", &odd).error(422);
    assert!(e.contains("goal"), "{e}");
}

#[test]
fn the_svg_and_png_are_written_and_formats_that_do_not_apply_are_refused() {
    let (dir, keys) = setup("still");
    for ext in ["svg", "png"] {
        let out = dir.path().join(format!("walk.{ext}"));
        bytes_of(&[
            "animate",
            "--rig",
            SPINEBOY,
            "--keys",
            &keys,
            "--animation",
            "walk",
            "--out",
            out.to_str().unwrap(),
        ]);
        let bytes = std::fs::read(&out).unwrap();
        match ext {
            "svg" => {
                let svg = String::from_utf8(bytes).unwrap();
                assert!(svg.starts_with("<svg"), "{}", &svg[..40]);
                assert!(svg.contains("<!-- ghosts -->"), "earlier frames faded under the last");
                assert!(svg.contains("spine character · keys over &quot;walk&quot; · 28 frames at 30 fps"));
            }
            _ => assert!(bytes.starts_with(b"\x89PNG")),
        }
    }
    let e = refusal(&["animate", "--rig", SPINEBOY, "--keys", &keys, "--format", "text"]);
    assert_eq!(e, "ikarus: --format text: a character's motion is written as json (its frames), csv or spine");
    let e = refusal(&["animate", "--rig", SPINEBOY, "--keys", &keys, "--format", "csv", "--animation-name", "x"]);
    assert_eq!(e, "ikarus: --animation-name: only with --format spine");
}
