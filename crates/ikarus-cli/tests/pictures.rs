//! End-to-end tests of `ikarus animate`, `ikarus workspace` and `ikarus render`: the frames'
//! contract, the picture files (format and size, read from their headers), and bad input.

mod common;

use std::path::Path;

use common::{floats, ikarus, json};

/// A command that must fail with `code` and one line on stderr containing `want`.
fn fails(args: &[&str], code: i32, want: &str) {
    let err = common::fails(args, code);
    assert!(err.contains(want), "{args:?}: {err:?} lacks {want:?}");
}

/// Width and height from a PNG's IHDR chunk.
fn png_size(bytes: &[u8]) -> (u32, u32) {
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "not a PNG");
    let be = |i: usize| u32::from_be_bytes(bytes[i..i + 4].try_into().unwrap());
    (be(16), be(20))
}

/// Logical screen size of a GIF and the number of image descriptors (frames).
fn gif_size(bytes: &[u8]) -> (u32, u32) {
    assert_eq!(&bytes[..6], b"GIF89a", "not a GIF");
    let le = |i: usize| u32::from(u16::from_le_bytes([bytes[i], bytes[i + 1]]));
    (le(6), le(8))
}

#[test]
fn animate_frames_contract() {
    let v = json(&["animate", "--goal", "2,3"]);
    let frames = v["frames"].as_array().unwrap();
    assert_eq!(frames.len(), 60, "60 frames by default");
    assert_eq!(frames[0]["time"], 0.0);
    assert_eq!(frames[59]["time"], 1.0);
    assert_eq!(floats(&frames[0]["angles_deg"]), vec![5.0, 5.0, 5.0], "starts at the start pose");
    let tip = floats(&frames[59]["joints"][3]);
    assert!((tip[0] - 2.0).hypot(tip[1] - 3.0) <= 1e-6, "ends on the goal: {tip:?}");
    assert_eq!(v["ease"], "sine");
    assert_eq!(v["solves"].as_array().unwrap().len(), 1);
    assert_eq!(v["solves"][0]["status"], "reached");
    // An eased motion starts slowly: the first step is much shorter than a middle one.
    let step = |i: usize| {
        let (a, b) = (floats(&frames[i]["angles_deg"]), floats(&frames[i + 1]["angles_deg"]));
        a.iter().zip(&b).map(|(x, y)| (x - y).powi(2)).sum::<f64>().sqrt()
    };
    assert!(step(0) < 0.1 * step(29), "{} vs {}", step(0), step(29));
}

#[test]
fn animate_timing_via_points_and_csv() {
    let v = json(&["animate", "--goal", "2,3", "--duration", "2", "--fps", "30", "--ease", "parent", "--k1", "0.2"]);
    let frames = v["frames"].as_array().unwrap();
    assert_eq!(frames.len(), 61);
    assert_eq!(frames[60]["time"], 2.0);
    assert_eq!(v["duration"], 2.0);
    assert_eq!(v["ease"], "parent");

    let v = json(&["animate", "--goal", "2,3", "--via", "4,-1", "--via=-1,4", "--frames", "90"]);
    let solves = v["solves"].as_array().unwrap();
    assert_eq!(solves.len(), 3);
    assert_eq!(floats(&solves[0]["goal"]), vec![4.0, -1.0]);
    assert_eq!(floats(&solves[2]["goal"]), vec![2.0, 3.0]);
    assert_eq!(v["frames"].as_array().unwrap().len(), 90);

    // With --limits the motion stays inside the seed's ranges on every frame.
    let v = json(&["animate", "--goal", "2,4", "--via", "4,-1", "--limits", "--frames", "40"]);
    for f in v["frames"].as_array().unwrap() {
        let a = floats(&f["angles_deg"]);
        assert!(a[0].abs() <= 45.0 && a[1].abs() <= 90.0 && a[2].abs() <= 170.0, "{a:?}");
    }

    let v = json(&["animate", "--goal", "-4,1", "--from-solve", "--method", "transpose", "--frames", "30"]);
    assert_eq!(v["frames"].as_array().unwrap().len(), 30);
    assert!(v["solves"][0]["iterations"].as_u64().unwrap() > 30, "a long solve, re-timed into 30 frames");

    let o = ikarus(&["animate", "--goal", "2,3", "--format", "csv", "--frames", "10"]);
    assert!(o.status.success());
    let text = String::from_utf8(o.stdout).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines[0], "time,theta1_deg,theta2_deg,theta3_deg,x0,y0,x1,y1,x2,y2,x3,y3");
    assert_eq!(lines.len(), 11);
}

/// Issue 10's example: at each via point the step of every joint (degrees per frame) changes by
/// at most 1.5× the most it changes between any other neighbouring frames with the spline (the
/// default; measured 1.06×), and by far more with the polyline (measured 10.9×: joint 1 goes
/// from −0.36°/frame to +1.55°/frame within two frames).
#[test]
fn animate_spline_has_no_corner_at_via_points() {
    let ratio = |interpolation: &str| {
        let v = json(&[
            "animate",
            "--goal",
            "-2,3",
            "--via",
            "4,2",
            "--via",
            "1,4",
            "--frames",
            "120",
            "--ease",
            "parent",
            "--k1",
            "0.2",
            "--k2",
            "0.8",
            "--format",
            "json",
            "--interpolation",
            interpolation,
        ]);
        let frames = v["frames"].as_array().unwrap();
        let angles: Vec<Vec<f64>> = frames.iter().map(|f| floats(&f["angles_deg"])).collect();
        // The frame where the tip passes nearest each via point.
        let near: Vec<usize> = [[4.0, 2.0], [1.0, 4.0]]
            .iter()
            .map(|via| {
                let off = |i: usize| {
                    let tip = floats(&frames[i]["joints"][3]);
                    (tip[0] - via[0]).hypot(tip[1] - via[1])
                };
                (0..frames.len()).min_by(|&a, &b| off(a).total_cmp(&off(b))).unwrap()
            })
            .collect();
        let (mut at_via, mut elsewhere) = ([0.0f64; 3], [0.0f64; 3]);
        for i in 1..angles.len() - 1 {
            let slot = if near.iter().any(|&k| i.abs_diff(k) <= 1) { &mut at_via } else { &mut elsewhere };
            for j in 0..3 {
                slot[j] = slot[j].max((angles[i + 1][j] - 2.0 * angles[i][j] + angles[i - 1][j]).abs());
            }
        }
        (0..3).map(|j| at_via[j] / elsewhere[j]).fold(0.0, f64::max)
    };
    let (spline, linear) = (ratio("spline"), ratio("linear"));
    assert!(spline <= 1.5, "spline: {spline}");
    assert!(linear >= 6.0, "linear: {linear}");
}

#[test]
fn animate_draws_gif_png_and_svg() {
    let dir = tempfile::tempdir().unwrap();
    let gif = dir.path().join("m.gif");
    let o = ikarus(
        &["animate", "--goal", "2,3", "--frames", "12", "--width", "320", "--height", "240", "--out"]
            .into_iter()
            .chain([gif.to_str().unwrap()])
            .collect::<Vec<_>>(),
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(gif_size(&std::fs::read(&gif).unwrap()), (320, 240));

    let png = dir.path().join("m.png");
    let o = ikarus(&["animate", "--goal", "2,3", "--out", png.to_str().unwrap(), "--width", "300", "--height", "200"]);
    assert!(o.status.success());
    assert_eq!(png_size(&std::fs::read(&png).unwrap()), (300, 200));

    let svg = dir.path().join("m.svg");
    let o = ikarus(&["animate", "--goal", "2,3", "--out", svg.to_str().unwrap()]);
    assert!(o.status.success());
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.contains("<svg") && text.trim_end().ends_with("</svg>"));
    let names: Vec<_> = std::fs::read_dir(dir.path()).unwrap().map(|e| e.unwrap().file_name()).collect();
    assert_eq!(names.len(), 3, "no temporary files left: {names:?}");
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        let mode = std::fs::metadata(&png).unwrap().permissions().mode() & 0o777;
        assert_eq!(mode, 0o644, "an ordinary file, not the temporary file's 0600");
    }
}

#[test]
fn animate_bad_input() {
    fails(&["animate", "--goal", "2,3", "--k1", "0.8", "--k2", "0.2"], 2, "--k1: must not exceed k2");
    fails(&["animate", "--goal", "2,3", "--k2", "1.5"], 2, "--k2: must be a number in [0, 1], got 1.5");
    fails(&["animate", "--goal", "2,3", "--ease", "sine", "--k1", "0.3"], 2, "--k1: only applies with --ease parent");
    fails(&["animate", "--goal", "2,3", "--frames", "1"], 2, "--frames 1: a motion needs at least 2 frames");
    fails(&["animate", "--goal", "2,3", "--duration", "-1"], 2, "--duration -1: must be greater than 0");
    fails(&["animate", "--goal", "2,3", "--duration", "2", "--fps", "0"], 2, "--fps 0: must be greater than 0");
    fails(&["animate", "--goal", "2,3", "--frames", "5", "--duration", "2"], 2, "cannot be used with");
    fails(&["animate", "--goal", "2,3", "--via", "1,nan"], 2, "'--via <X,Y>': y: must be a finite number");
    fails(&["animate", "--goal", "2,3", "--out", "m.jpg"], 2, "--out m.jpg: unsupported picture format");
    fails(&["animate", "--goal", "2,3", "--interpolation", "cubic"], 2, "invalid value 'cubic' for '--interpolation");
    fails(
        &["animate", "--goal", "2,3", "--out", "/nonexistent/dir/m.gif"],
        1,
        "--out /nonexistent/dir/m.gif: cannot write",
    );
    fails(&["animate", "--goal", "2,3", "--width", "5"], 2, "'--width <WIDTH>'");
}

#[test]
fn workspace_numbers_grid_and_picture() {
    let v = json(&["workspace", "--resolution", "128"]);
    assert_eq!(v["inner_radius"], 0.0);
    assert_eq!(v["outer_radius"], 6.0);
    let annulus = v["annulus_area"].as_f64().unwrap();
    assert!((annulus - 36.0 * std::f64::consts::PI).abs() < 1e-9);
    let free = v["area"].as_f64().unwrap();
    assert!((free - annulus).abs() / annulus < 0.02, "{free} vs {annulus}");
    let grid = v["grid"].as_array().unwrap();
    assert_eq!(grid.len(), 128);
    assert!(grid.iter().all(|row| row.as_str().unwrap().len() == 128));
    assert_eq!(v["limits"], false);

    let v = json(&["workspace", "--resolution", "128", "--limits"]);
    assert_eq!(v["limits"], true);
    let limited = v["area"].as_f64().unwrap();
    assert!(limited < 0.9 * free, "the seed's ranges cut the area: {limited} vs {free}");

    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("w.png");
    let o = ikarus(&["workspace", "--limits", "--resolution", "64", "--out", png.to_str().unwrap(), "--width", "400"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(png_size(&std::fs::read(&png).unwrap()), (400, 800));

    fails(&["workspace", "--resolution", "4"], 2, "'--resolution <RESOLUTION>'");
    fails(&["workspace", "--out", "w.gif"], 2, "--out w.gif: unsupported picture format (use .svg, .png)");
    let arm = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/arms/seven.toml");
    let v = json(&["workspace", "--arm", arm.to_str().unwrap(), "--resolution", "64"]);
    assert_eq!(v["arm"], "seven");
}

#[test]
fn render_ease() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("e.png");
    let o = ikarus(&["render", "ease", "--k1", "0.3", "--k2", "0.75", "--out", png.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(png_size(&std::fs::read(&png).unwrap()), (800, 800));
    let svg = dir.path().join("e.svg");
    let o = ikarus(&["render", "ease", "--ease", "smoothstep", "--out", svg.to_str().unwrap()]);
    assert!(o.status.success());
    assert!(std::fs::read_to_string(&svg).unwrap().contains("<svg"));
    fails(&["render", "ease", "--k1", "0.3"], 2, "--out: required");
    fails(&["render", "ease", "--k1", "0.9", "--k2", "0.3", "--out", "e.png"], 2, "--k1: must not exceed k2");
}

#[test]
fn animate_prints_as_solve_does() {
    // Piped: JSON; --format text: the short report; --format csv: rows.
    let v = json(&["animate", "--goal", "2,3", "--frames", "5"]);
    assert_eq!(v["frames"].as_array().unwrap().len(), 5);
    let text = common::succeeds(&["animate", "--goal", "2,3", "--frames", "5", "--format", "text"]);
    assert!(text.starts_with("arm       seed (3 links, reach 6)\n"), "{text}");
    assert!(text.contains("goal      (2, 3): reached after"), "{text}");
    assert!(text.contains("motion    5 frames over 1 s, sine ease"), "{text}");
    assert!(text.contains("start     5.000°, 5.000°, 5.000°"), "{text}");
    assert!(text.lines().count() < 12, "short: {text}");
    let csv = common::succeeds(&["animate", "--goal", "2,3", "--frames", "5", "--format", "csv"]);
    assert_eq!(csv.lines().count(), 6);

    // With --out, stdout stays empty unless a format is asked for.
    let dir = tempfile::tempdir().unwrap();
    let gif = dir.path().join("m.gif");
    let gif = gif.to_str().unwrap();
    let quiet = common::succeeds(&["animate", "--goal", "2,3", "--frames", "4", "--width", "64", "--out", gif]);
    assert_eq!(quiet, "", "nothing on stdout after writing the GIF");
    let asked = common::succeeds(&[
        "animate", "--goal", "2,3", "--frames", "4", "--width", "64", "--out", gif, "--format", "json",
    ]);
    assert_eq!(serde_json::from_str::<serde_json::Value>(&asked).unwrap()["frames"].as_array().unwrap().len(), 4);
}

#[test]
fn text_angles_are_normalised_without_negative_zero() {
    // The tip of this pose points at -200° = 160°; its first joint is at -88.872°.
    let text = common::succeeds(&["solve", "--goal", "-2,-1", "--goal-angle", "-200", "--format", "text"]);
    assert!(text.contains("goal      (-2, -1) at 160.000°"), "{text}");
    assert!(text.contains("pointing 160.000°"), "{text}");
    let dir = tempfile::tempdir().unwrap();
    let arm = dir.path().join("arm.toml");
    // Start angles whose sum winds past a turn, and one that is a tiny negative number.
    std::fs::write(&arm, "[[links]]\nlength = 1\nangle_deg = -1e-9\n[[links]]\nlength = 1\nangle_deg = -300\n")
        .unwrap();
    let arm = arm.to_str().unwrap();
    for args in [
        &["solve", "--arm", arm, "--goal", "7,0", "--format", "text", "--restarts", "0"][..],
        &["animate", "--arm", arm, "--goal", "0.5,1", "--frames", "3", "--format", "text"],
        &["solve", "--goal", "-5.5,-1", "--format", "text"],
    ] {
        let text = common::succeeds(args);
        assert!(!text.contains("-0.000°"), "{args:?}: {text}");
        // Every angle printed as a number of degrees (not an error in scientific notation).
        let angles: Vec<f64> = text
            .split([' ', ',', '(', ')', '\n'])
            .filter_map(|t| t.strip_suffix('°'))
            .filter(|t| !t.contains('e'))
            .map(|t| t.parse().unwrap_or_else(|_| panic!("{t} in {text}")))
            .collect();
        assert!(angles.len() >= 2, "{args:?}: {text}");
        for v in angles {
            assert!(v > -180.0 && v <= 180.0, "{args:?}: {v} in {text}");
        }
    }
}

#[test]
fn render_draws_the_apis_figures() {
    let dir = tempfile::tempdir().unwrap();
    let path = |name: &str| dir.path().join(name).to_str().unwrap().to_owned();
    let arm = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/arms/seven.toml");
    let arm = arm.to_str().unwrap();

    let png = path("arm.png");
    common::succeeds(&["render", "arm", "--goal", "2,3", "--width", "640", "--height", "480", "--out", &png]);
    assert_eq!(png_size(&std::fs::read(&png).unwrap()), (640, 480));
    let plain = std::fs::read(path("arm.png")).unwrap();
    let shaded = path("shaded.png");
    common::succeeds(&[
        "render",
        "arm",
        "--goal",
        "2,3",
        "--width",
        "640",
        "--height",
        "480",
        "--workspace",
        "--limits",
        "--resolution",
        "32",
        "--out",
        &shaded,
    ]);
    assert_ne!(std::fs::read(&shaded).unwrap(), plain, "the reachable area is shaded");
    let posed = path("posed.svg");
    common::succeeds(&["render", "arm", "--arm", arm, "--pose-deg", "0,10,-20,30,-40,50,-60", "--out", &posed]);
    assert!(std::fs::read_to_string(&posed).unwrap().contains("<svg"));
    fails(
        &["render", "arm", "--pose-deg", "1,2", "--out", &path("x.png")],
        2,
        "--pose-deg: expected 3 angles (one per joint), got 2",
    );
    fails(&["render", "arm", "--out", &path("x.gif")], 2, "unsupported picture format (use .svg, .png)");

    // The motion figure is what animate draws, for the same flags.
    let a = path("a.svg");
    let r = path("r.svg");
    common::succeeds(&["animate", "--goal", "2,3", "--via", "4,1", "--frames", "8", "--out", &a]);
    common::succeeds(&["render", "motion", "--goal", "2,3", "--via", "4,1", "--frames", "8", "--out", &r]);
    assert_eq!(std::fs::read(&a).unwrap(), std::fs::read(&r).unwrap());
    let gif = path("m.gif");
    common::succeeds(&[
        "render", "motion", "--goal", "2,3", "--frames", "6", "--width", "100", "--height", "80", "--out", &gif,
    ]);
    assert_eq!(gif_size(&std::fs::read(&gif).unwrap()), (100, 80));
    fails(&["render", "motion", "--goal", "2,3"], 2, "--out: required: the file to draw to (.svg, .png, .gif)");

    // The workspace figure is what workspace --out draws.
    let w1 = path("w1.svg");
    let w2 = path("w2.svg");
    let quiet = common::succeeds(&["workspace", "--limits", "--resolution", "32", "--out", &w1]);
    assert_eq!(quiet, "", "nothing on stdout with --out unless --format asks");
    let quiet = common::succeeds(&["track", "--circle", "2,2,1", "--samples", "8", "--out", &path("t.svg")]);
    assert_eq!(quiet, "", "nothing on stdout with --out unless --format asks");
    common::succeeds(&["render", "workspace", "--limits", "--resolution", "32", "--out", &w2]);
    assert_eq!(std::fs::read(&w1).unwrap(), std::fs::read(&w2).unwrap());
    fails(&["render", "workspace"], 2, "--out: required");
}

/// On a terminal (a pseudo-terminal from util-linux `script`, where it is installed): text
/// without `--format`, and nothing at all with `--out`.
#[cfg(unix)]
#[test]
fn animate_on_a_terminal_prints_text_or_nothing_with_out() {
    let on_terminal = |args: &str| {
        // stderr (the GIF's progress bar, on a terminal) is left out: stdout is the subject.
        let command = format!("{} {args} 2>/dev/null", env!("CARGO_BIN_EXE_ikarus"));
        std::process::Command::new("script").args(["-q", "-e", "-c", &command, "/dev/null"]).output()
    };
    let Ok(o) = on_terminal("animate --goal 2,3 --frames 5") else {
        eprintln!("skipped: `script` is not installed");
        return;
    };
    let text = String::from_utf8_lossy(&o.stdout).replace('\r', "");
    assert!(o.status.success(), "{text}");
    assert!(text.starts_with("arm       seed (3 links, reach 6)\n"), "{text}");
    assert!(text.contains("motion    5 frames over 1 s, sine ease"), "{text}");
    let dir = tempfile::tempdir().unwrap();
    let gif = dir.path().join("m.gif");
    let o = on_terminal(&format!("animate --goal 2,3 --frames 4 --width 64 --out {}", gif.display())).unwrap();
    assert!(o.status.success());
    assert_eq!(String::from_utf8_lossy(&o.stdout).trim(), "", "nothing but the GIF");
    assert!(gif.exists());
}

/// Every frame of a GIF as it is shown (RGBA, each drawn over the one before: a frame stores only
/// the rectangle that changed, its unchanged pixels transparent), with the GIF's size.
fn gif_frames(bytes: &[u8]) -> ((u32, u32), Vec<Vec<u8>>) {
    let mut options = gif::DecodeOptions::new();
    options.set_color_output(gif::ColorOutput::RGBA);
    let mut decoder = options.read_info(bytes).unwrap();
    let (w, h) = (usize::from(decoder.width()), usize::from(decoder.height()));
    let mut shown = vec![0u8; w * h * 4];
    let mut frames = Vec::new();
    while let Some(frame) = decoder.read_next_frame().unwrap() {
        let (left, top, fw) = (usize::from(frame.left), usize::from(frame.top), usize::from(frame.width));
        for (i, px) in frame.buffer.chunks_exact(4).enumerate() {
            if px[3] != 0 {
                let at = ((top + i / fw) * w + left + i % fw) * 4;
                shown[at..at + 4].copy_from_slice(px);
            }
        }
        frames.push(shown.clone());
    }
    ((w as u32, h as u32), frames)
}

/// How many opaque pixels of `frame` (RGBA) lie within `tolerance` of `rgb` on every channel.
fn pixels_near(frame: &[u8], rgb: [u8; 3], tolerance: u8) -> usize {
    frame.chunks_exact(4).filter(|p| p[3] == 255 && (0..3).all(|c| p[c].abs_diff(rgb[c]) <= tolerance)).count()
}

/// How many opaque pixels of `frame` (RGBA) are `rgb` exactly.
fn pixels_of(frame: &[u8], rgb: [u8; 3]) -> usize {
    pixels_near(frame, rgb, 0)
}

#[test]
fn the_playgrounds_gif_is_the_screens_picture() {
    // What the page sends for its GIF (files.js gifRequest): the motion, the canvas's size, and
    // the layers the screen shows: the area (the exact region with the limits on), the traces,
    // the ghosts.
    // (A debug build rasterises slowly on a busy machine: a generous budget.)
    let s = common::server::start(&["--request-budget-ms", "300000"]);
    let base = serde_json::json!({
        "figure": "motion", "format": "gif", "width": 480, "height": 330,
        "goal": { "x": 2, "y": 3 }, "options": { "limits": true }, "duration": 0.4, "fps": 25,
    });
    let with = |extra: serde_json::Value| {
        let mut body = base.clone();
        body.as_object_mut().unwrap().extend(extra.as_object().unwrap().clone());
        let a = s.post("/api/render", &body);
        assert_eq!((a.status, a.content_type.as_str()), (200, "image/gif"), "{}", a.text());
        gif_frames(&a.body)
    };
    const AREA: [u8; 3] = [0xdc, 0xea, 0xe1];
    const TIP: [u8; 3] = [0xec, 0x7f, 0x2d];
    let (size, screen) = with(serde_json::json!({ "workspace": true, "traces": true, "ghosts": true }));
    assert_eq!(size, (480, 330));
    assert_eq!(screen.len(), 11);
    assert_eq!(screen[0].len(), 480 * 330 * 4, "the first frame is whole");
    let area = pixels_of(&screen[0], AREA);
    assert!(area > 5_000, "the shaded area: {area} pixels of its colour");
    // The tip's trace in the path colour (antialiased thin lines: near it), on the last frame.
    let tip = pixels_near(screen.last().unwrap(), TIP, 40);
    assert!(tip > 60, "the tip's trace in the path colour: {tip} pixels");

    // Hidden on the screen, not in the GIF either.
    let (_, bare) = with(serde_json::json!({ "workspace": false, "traces": false, "ghosts": false }));
    // (A few antialiased edge pixels may round to a key colour: far fewer than the layers paint.)
    let (bare_area, bare_tip) = (pixels_of(&bare[0], AREA), pixels_near(bare.last().unwrap(), TIP, 40));
    assert!(bare_area * 100 < area, "{bare_area} pixels of the area's colour without the area, {area} with it");
    assert!(bare_tip * 4 < tip, "{bare_tip} pixels of the trace's colour without traces, {tip} with them");
    // The ghosts change the frames after the first (which has none yet).
    let (_, no_ghosts) = with(serde_json::json!({ "workspace": true, "traces": true, "ghosts": false }));
    assert_ne!(no_ghosts[1..], screen[1..]);
    // The area follows the options' limits: without them it is the whole disc, more of it.
    let (_, free) = with(serde_json::json!({ "workspace": true, "options": { "limits": false } }));
    assert!(pixels_of(&free[0], AREA) > area, "{} vs {area}", pixels_of(&free[0], AREA));
}

/// Issue 24: `ikarus solve --out puppet.png` printed the whole JSON while `animate`, `track`
/// and `workspace` with `--out` printed nothing. Now all four agree (with an arm or a rig):
/// with `--out` the picture is the result and stdout stays quiet, unless `--format` asks for
/// the report too; nothing goes to stderr either.
#[test]
fn with_out_every_command_prints_nothing_unless_a_format_is_asked() {
    let dir = tempfile::tempdir().unwrap();
    let rig = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/rigs/puppet.toml");
    let rig = rig.to_str().unwrap();
    let commands: [&[&str]; 7] = [
        &["solve", "--goal", "2,3"],
        &["solve", "--rig", rig, "--goal", "right_hand=0.6451,1.0024", "--pin", "left_foot"],
        &["animate", "--goal", "2,3", "--frames", "4"],
        &["animate", "--rig", rig, "--goal", "right_hand=0.6451,1.0024", "--frames", "4"],
        &["track", "--circle", "0,2,1", "--samples", "8"],
        &["track", "--rig", rig, "--effector", "left_hand", "--line", "-0.6,0.6,-0.7,0.9", "--samples", "4"],
        &["workspace"],
    ];
    for (i, args) in commands.into_iter().enumerate() {
        let out = dir.path().join(format!("{i}.svg"));
        let with_out = [args, &["--out", out.to_str().unwrap()]].concat();
        let o = ikarus(&with_out);
        assert!(o.status.success(), "{with_out:?}: {}", String::from_utf8_lossy(&o.stderr));
        assert_eq!(String::from_utf8_lossy(&o.stdout), "", "{with_out:?}: nothing on stdout");
        assert_eq!(String::from_utf8_lossy(&o.stderr), "", "{with_out:?}: nothing on stderr");
        assert!(std::fs::read_to_string(&out).unwrap().starts_with("<svg"), "{with_out:?}");
        // Asked for, the report comes too: the same JSON as without --out.
        let asked = [&with_out[..], &["--format", "json"]].concat();
        let o = ikarus(&asked);
        assert!(o.status.success(), "{asked:?}: {}", String::from_utf8_lossy(&o.stderr));
        let report: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        let plain = json(args);
        let key = ["area", "arm", "rig"].into_iter().find(|k| plain.get(k).is_some()).unwrap();
        assert_eq!(report[key], plain[key], "{asked:?}");
        assert!(report.is_object() && !report[key].is_null(), "{asked:?}: {report}");
    }
}
