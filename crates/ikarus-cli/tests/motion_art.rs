//! `ikarus animate|track --rig FILE.json --atlas FILE.atlas`: a character's motion drawn with its
//! art. Spineboy's front foot keyed over its `walk`: the GIF's frames hold the art's colours
//! (the atlas page's, absent from the same GIF drawn as bones only), change as the walk moves,
//! and alone (`--art-only`) share one fit (the box of every frame's art fills 90 % of the
//! picture, centred, while single frames fill less); the PNG and SVG draw the last frame's art
//! under the ghosts; the server's GIF (`POST /api/render` figure `motion` with `"atlas"`) is the
//! command line's, byte for byte; the refusals are one line naming the flag or the file.

mod common;

use std::collections::HashSet;

use common::{SPINEBOY, b64, fails, ikarus, spineboy_keys, stderr};
use serde_json::json;

const CHARACTERS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/characters");
const SIDE: usize = 200;

fn file(name: &str) -> String {
    format!("{CHARACTERS}/{name}")
}

/// A folder of the test's own with spineboy's keys in it, and the keys' path.
fn setup(name: &str) -> (tempfile::TempDir, String) {
    let dir = tempfile::Builder::new().prefix(&format!("ikarus-motion-art-{name}")).tempdir().unwrap();
    let keys = dir.path().join("keys.json");
    std::fs::write(&keys, spineboy_keys().to_string()).unwrap();
    let keys = keys.to_str().unwrap().to_owned();
    (dir, keys)
}

/// Runs `ikarus ARGS`, which must succeed and print nothing on stdout; the bytes of `out`.
fn drawn(args: &[&str], out: &std::path::Path) -> Vec<u8> {
    let o = ikarus(args);
    assert!(o.status.success(), "{args:?}: {}", stderr(&o));
    assert!(o.stdout.is_empty(), "the picture is the result: stdout stays quiet");
    std::fs::read(out).unwrap()
}

/// Spineboy's keyed walk drawn as `out` at 200 × 200, with `more` flags.
fn walk(keys: &str, out: &std::path::Path, more: &[&str]) -> Vec<u8> {
    let side = SIDE.to_string();
    let mut args = vec!["animate", "--rig", SPINEBOY, "--keys", keys, "--animation", "walk"];
    args.extend(["--width", &side, "--height", &side, "--out", out.to_str().unwrap()]);
    args.extend_from_slice(more);
    drawn(&args, out)
}

/// Every frame of a GIF as a viewer shows it (RGBA, whole picture): each frame drawn over the
/// one before, its transparent pixels leaving what is there, the picture cleared after a frame
/// disposed of to the background.
fn frames(gif: &[u8]) -> Vec<Vec<u8>> {
    let mut options = gif::DecodeOptions::new();
    options.set_color_output(gif::ColorOutput::RGBA);
    let mut decoder = options.read_info(gif).unwrap();
    let (w, h) = (usize::from(decoder.width()), usize::from(decoder.height()));
    assert_eq!((w, h), (SIDE, SIDE));
    let mut shown = vec![0u8; w * h * 4];
    let mut out = Vec::new();
    while let Some(frame) = decoder.read_next_frame().unwrap() {
        let (fw, left, top) = (usize::from(frame.width), usize::from(frame.left), usize::from(frame.top));
        for (k, p) in frame.buffer.chunks_exact(4).enumerate() {
            if p[3] > 0 {
                let at = ((top + k / fw) * w + left + k % fw) * 4;
                shown[at..at + 4].copy_from_slice(p);
            }
        }
        out.push(shown.clone());
        if frame.dispose == gif::DisposalMethod::Background {
            shown.fill(0);
        }
    }
    out
}

/// A colour cut to 4 bits a channel.
fn coarse(p: &[u8]) -> [u8; 3] {
    [p[0] >> 4, p[1] >> 4, p[2] >> 4]
}

/// The coarse colours of the opaque texels of spineboy's atlas page.
fn page_colours() -> HashSet<[u8; 3]> {
    let bytes = std::fs::read(file("spineboy.png")).unwrap();
    let mut decoder = png::Decoder::new(std::io::Cursor::new(bytes));
    decoder.set_transformations(png::Transformations::normalize_to_color8());
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!(info.color_type, png::ColorType::Rgba);
    buf[..info.buffer_size()].chunks_exact(4).filter(|p| p[3] == 255).map(coarse).collect()
}

/// The box `(left, top, right, bottom)` of the pixels of `rgba` (SIDE wide) with alpha, if any.
fn opaque_box(rgba: &[u8]) -> Option<(usize, usize, usize, usize)> {
    let mut b: Option<(usize, usize, usize, usize)> = None;
    for (k, p) in rgba.chunks_exact(4).enumerate() {
        if p[3] > 0 {
            let (x, y) = (k % SIDE, k / SIDE);
            b = Some(b.map_or((x, y, x, y), |(l, t, r, bo)| (l.min(x), t.min(y), r.max(x), bo.max(y))));
        }
    }
    b
}

#[test]
fn a_walk_gif_draws_each_frames_art_under_its_bones() {
    let (dir, keys) = setup("gif");
    let atlas = file("spineboy.atlas");
    let with_art = frames(&walk(&keys, &dir.path().join("art.gif"), &["--atlas", &atlas]));
    let bones = frames(&walk(&keys, &dir.path().join("bones.gif"), &[]));
    assert_eq!((with_art.len(), bones.len()), (28, 28), "one GIF frame per motion frame");
    let page = page_colours();
    for k in [0, 14, 27] {
        let plain: HashSet<[u8; 3]> = bones[k].chunks_exact(4).map(coarse).collect();
        // The art's colours: the page's, which the bones' picture does not have.
        let art = with_art[k].chunks_exact(4).map(coarse).filter(|c| page.contains(c) && !plain.contains(c)).count();
        assert!(art > SIDE * SIDE / 50, "frame {k}: {art} pixels of the art's colours");
        assert!(with_art[k].chunks_exact(4).all(|p| p[3] == 255), "frame {k}: the background is opaque");
    }
    // The walk moves: a frame half a walk later differs in many pixels.
    let changed = with_art[0].chunks_exact(4).zip(with_art[14].chunks_exact(4)).filter(|(a, b)| a != b).count();
    assert!(changed > SIDE * SIDE / 50, "{changed} pixels changed");
}

#[test]
fn alone_the_art_keeps_one_fit_for_the_whole_walk() {
    let (dir, keys) = setup("alone");
    let atlas = file("spineboy.atlas");
    let shown = frames(&walk(&keys, &dir.path().join("alone.gif"), &["--atlas", &atlas, "--art-only"]));
    assert_eq!(shown.len(), 28);
    let boxes: Vec<_> = shown.iter().map(|f| opaque_box(f).unwrap()).collect();
    let union =
        boxes.iter().fold(boxes[0], |(l, t, r, b), &(l2, t2, r2, b2)| (l.min(l2), t.min(t2), r.max(r2), b.max(b2)));
    // The box of every frame's art: its larger side 90 % of 200 px, centred (the pixels' box is
    // within a pixel or two of the vertices').
    let (w, h) = (union.2 + 1 - union.0, union.3 + 1 - union.1);
    assert!((178..=181).contains(&w.max(h)), "{union:?}: {w} × {h}");
    let (cx, cy) = (union.0 + union.2 + 1, union.1 + union.3 + 1);
    assert!(cx.abs_diff(SIDE) <= 3 && cy.abs_diff(SIDE) <= 3, "{union:?} is not centred");
    // One fit: a single frame's art fills less than the whole walk's (a fit of its own would
    // fill 90 % of the picture in every frame): spineboy bobs, some frames 5 px shorter or more.
    let side = |b: &(usize, usize, usize, usize)| (b.2 + 1 - b.0).max(b.3 + 1 - b.1);
    let shortest = boxes.iter().map(side).min().unwrap();
    assert!(shortest + 5 <= w.max(h), "{boxes:?}");
    // The background is transparent, the walk moves.
    let clear = shown[0].chunks_exact(4).filter(|p| p[3] == 0).count();
    assert!(clear > SIDE * SIDE / 3, "{clear} transparent pixels");
    let moved = shown[0].chunks_exact(4).zip(shown[14].chunks_exact(4)).filter(|(a, b)| (a[3] == 0) != (b[3] == 0));
    assert!(moved.count() > 200);
}

#[test]
fn the_png_and_svg_draw_the_last_frames_art_under_the_ghosts() {
    let (dir, keys) = setup("still");
    let atlas = file("spineboy.atlas");
    let png = walk(&keys, &dir.path().join("walk.png"), &["--atlas", &atlas]);
    let mut reader = png::Decoder::new(std::io::Cursor::new(png)).read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!((info.width as usize, info.height as usize, info.color_type), (SIDE, SIDE, png::ColorType::Rgba));
    let page = page_colours();
    let bones_png = walk(&keys, &dir.path().join("bones.png"), &[]);
    let mut reader = png::Decoder::new(std::io::Cursor::new(bones_png)).read_info().unwrap();
    let mut plain_buf = vec![0; reader.output_buffer_size().unwrap()];
    reader.next_frame(&mut plain_buf).unwrap();
    let plain: HashSet<[u8; 3]> = plain_buf.chunks_exact(4).map(coarse).collect();
    let art = buf.chunks_exact(4).map(coarse).filter(|c| page.contains(c) && !plain.contains(c)).count();
    assert!(art > SIDE * SIDE / 50, "{art} pixels of the art's colours");
    let svg = String::from_utf8(walk(&keys, &dir.path().join("walk.svg"), &["--atlas", &atlas])).unwrap();
    assert_eq!(svg.matches("<image").count(), 1, "the art as one image");
    assert!(svg.contains("<!-- ghosts -->") && svg.contains("<g class=\"bone\">"), "vector bones over it");
    assert!(svg.find("<image").unwrap() < svg.find("<!-- ghosts -->").unwrap());
}

#[test]
fn track_draws_the_art_too() {
    let dir = tempfile::Builder::new().prefix("ikarus-motion-art-track").tempdir().unwrap();
    let gif = dir.path().join("track.gif");
    let raptor = file("spine-raptor-pro.json");
    let atlas = file("raptor.atlas");
    let side = SIDE.to_string();
    let args = [
        "track",
        "--rig",
        &raptor,
        "--effector",
        "front-leg-target",
        "--line",
        "100,50,250,60",
        "--samples",
        "4",
        "--atlas",
        &atlas,
        "--art-only",
        "--width",
        &side,
        "--height",
        &side,
        "--out",
        gif.to_str().unwrap(),
    ];
    let shown = frames(&drawn(&args, &gif));
    assert_eq!(shown.len(), 4);
    for f in &shown {
        let opaque = f.chunks_exact(4).filter(|p| p[3] > 0).count();
        assert!(opaque > SIDE * SIDE / 20, "{opaque} opaque pixels");
    }
    assert_ne!(shown[0], shown[3], "the leg moves");
}

#[test]
fn refusals_are_one_line() {
    let dir = tempfile::Builder::new().prefix("ikarus-motion-art-refusals").tempdir().unwrap();
    let gif = dir.path().join("x.gif");
    let gif = gif.to_str().unwrap();
    let raptor = file("spine-raptor-pro.json");
    let (raptor_atlas, spineboy_atlas) = (file("raptor.atlas"), file("spineboy.atlas"));
    let animate = |more: &[&str]| {
        let mut args = vec!["animate", "--rig", &raptor, "--target", "front-leg-target=100,50", "--fps", "5"];
        args.extend_from_slice(more);
        fails(&args, 2)
    };
    let e = animate(&["--art-only", "--out", gif]);
    assert!(e.contains("--art-only draws a character's art: give its atlas with --atlas FILE.atlas"), "{e}");
    let e = animate(&["--atlas", &raptor_atlas, "--format", "json"]);
    assert!(e.contains("the art is drawn in a picture: give --out FILE.gif, FILE.png or FILE.svg"), "{e}");
    let e = animate(&["--atlas", &spineboy_atlas, "--out", gif]);
    assert!(e.contains("atlas file") && e.contains("the atlas has no region") && e.contains("slot"), "{e}");
    let e = animate(&["--atlas", &raptor_atlas, "--skin", "gold", "--out", gif]);
    assert!(e.contains("rig file") && e.contains("skin \"gold\": no such skin"), "{e}");
    let e = animate(&["--atlas", &file("nowhere.atlas"), "--out", gif]);
    assert!(e.contains("nowhere.atlas"), "{e}");
    let mecha = file("dragonbones-mecha_1406_ske.json");
    let e = fails(&["animate", "--rig", &mecha, "--target", "root=1,2", "--atlas", &raptor_atlas, "--out", gif], 2);
    assert!(e.contains("DragonBones characters are drawn as bones only"), "{e}");
    let e = fails(&["animate", "--goal", "1,1", "--atlas", &raptor_atlas, "--out", gif], 2);
    assert!(e.contains("--atlas: only with a character file"), "{e}");
    let e = fails(&["track", "--line", "0,0,1,1", "--art-only"], 2);
    assert!(e.contains("--art-only: only with a character file"), "{e}");
    assert!(!std::path::Path::new(gif).exists(), "nothing written");
}

#[test]
fn the_servers_gif_with_the_art_is_the_command_lines() {
    let (dir, keys) = setup("serve");
    let atlas = file("spineboy.atlas");
    let s = common::server::start(&[]);
    let page = std::fs::read(file("spineboy.png")).unwrap();
    let parse = json!({ "atlas": std::fs::read_to_string(&atlas).unwrap(), "pages": { "spineboy.png": b64(&page) } });
    let id = s.post("/api/atlas/parse", &parse).json()["id"].clone();
    let text = std::fs::read_to_string(SPINEBOY).unwrap();
    for (name, more) in [("under.gif", &["--atlas", &atlas][..]), ("alone.gif", &["--atlas", &atlas, "--art-only"])] {
        let cli = walk(&keys, &dir.path().join(name), more);
        let body = json!({
            "figure": "motion", "format": "gif", "rig": text, "keys": spineboy_keys(), "animation": "walk",
            "atlas": id, "art_only": more.len() == 3, "width": SIDE, "height": SIDE,
        });
        let served = s.post("/api/render", &body);
        assert_eq!(served.status, 200, "{}", served.text());
        assert!(served.body == cli, "{name}: the API's GIF differs from the command line's");
    }
}
