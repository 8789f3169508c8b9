//! A character's motion within caps: frames counted before any is made (exit 2 / HTTP 422
//! naming the fields, the value and the cap), and long outputs written as they are posed.

mod common;

use std::io::Read;
use std::process::{Command, Stdio};
use std::sync::mpsc;
use std::time::Duration;

use common::fails;
use serde_json::json;

const RAPTOR: &str = "../../examples/characters/spine-raptor-pro.json";

#[test]
fn a_duration_past_the_frame_cap_is_refused_at_once() {
    // Before: 1e17 s at 240 fps panicked (exit 101, "capacity overflow"); 1e12 s aborted on an
    // 8 TB allocation.
    let e = fails(&["animate", "--rig", RAPTOR, "--target", "root=1,1", "--duration", "1e17", "--fps", "240"], 2);
    assert_eq!(e, "ikarus: --duration 1e17, --fps 240: 2.4e19 frames, more than the cap of 100000\n");
    let e = fails(&["animate", "--rig", RAPTOR, "--target", "root=1,1", "--duration", "1e12"], 2);
    assert_eq!(e, "ikarus: --duration 1000000000000, --fps 30: 30000000000001 frames, more than the cap of 100000\n");
    let e = fails(&["animate", "--rig", RAPTOR, "--target", "root=1,1", "--fps", "1e308", "--duration", "1e308"], 2);
    assert!(e.contains("inf frames, more than the cap of 100000"), "{e}");
}

#[test]
fn the_server_refuses_a_duration_past_the_frame_cap() {
    // Before: a 500 (the frame count overflowed).
    let s = common::server::start(&[]);
    let rig = std::fs::read_to_string(RAPTOR).unwrap();
    let body = json!({"rig": rig, "targets": [{"bone": "root", "x": 1, "y": 1}], "duration": 1e308, "fps": 1e308});
    let e = s.post("/api/animate", &body).error(422);
    assert_eq!(e, "duration, fps: 1e308 s at 1e308 fps is inf frames, more than the cap of 100000");
    let body = json!({"rig": rig, "targets": [{"bone": "root", "x": 1, "y": 1}], "duration": 1e6, "fps": 30});
    let e = s.post("/api/animate", &body).error(422);
    assert!(e.contains("30000001 frames, more than the cap of 100000"), "{e}");
    s.assert_healthy();
}

/// The first `n` bytes `ikarus ARGS` writes to stdout, read while it runs (then it is
/// stopped), or `None` if they do not come within a generous bound.
fn first_bytes(args: &[&str], n: usize) -> Option<String> {
    let mut child = Command::new(env!("CARGO_BIN_EXE_ikarus"))
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("the binary runs");
    let mut out = child.stdout.take().unwrap();
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        let mut got = vec![0; n];
        let _ = tx.send(out.read_exact(&mut got).ok().map(|()| String::from_utf8_lossy(&got).into_owned()));
    });
    // Not a speed bound: a run that holds every frame before writing one takes gigabytes and
    // many minutes here; one that streams writes its first frame at once.
    let got = rx.recv_timeout(Duration::from_secs(300)).ok().flatten();
    let _ = child.kill();
    let _ = child.wait();
    got
}

#[test]
fn a_long_track_is_written_as_it_is_posed() {
    // A million samples, the documented cap: every frame collected first took over 25 GB.
    let args = [
        "track",
        "--rig",
        RAPTOR,
        "--effector",
        "root",
        "--line",
        "0,0,100,0",
        "--samples",
        "1000000",
        "--format",
        "csv",
    ];
    let got = first_bytes(&args, 200).expect("the first rows come while the track runs");
    let rows: Vec<&str> = got.lines().collect();
    assert_eq!(rows[0], "frame,time,bone,x,y,rotation_deg,tip_x,tip_y");
    assert_eq!(rows[1], "0,0.0,root,0.0,0.0,0.0,0.0,0.0");
    assert!(rows[2].starts_with("0,0.0,hip,"), "{rows:?}");
    let args = ["track", "--rig", RAPTOR, "--effector", "root", "--line", "0,0,100,0", "--samples", "1000000"];
    let got = first_bytes(&args, 100).expect("the JSON's first frame comes while the track runs");
    assert!(got.starts_with("{\"frames\":[{\"time\":0.0,\"bones\":[{\"name\":\"root\""), "{got}");
}

#[test]
fn a_picture_of_a_long_motion_is_refused_before_any_frame_is_posed() {
    // A picture holds every frame's bones: a million-sample track drawn as an SVG held them all
    // (gigabytes) and drew every frame.
    let svg = common::temp_file("caps", "long.svg", "");
    let e = fails(
        &["track", "--rig", RAPTOR, "--effector", "root", "--line", "0,0,1,1", "--samples", "1000000", "--out", &svg],
        2,
    );
    assert!(e.starts_with("ikarus: --out: a picture of 1000000 frames × "), "{e}");
    assert!(e.ends_with(" bones draws more than the cap of 1000000 bones (fewer --samples)\n"), "{e}");
}
