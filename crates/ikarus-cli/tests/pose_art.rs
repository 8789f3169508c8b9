//! `ikarus pose --atlas`: a Spine character drawn with its art, under its bones or alone
//! (`--art-only`), and the refusals, each one line. The pixels are compared with Spine's own
//! renderer in `ikarus-edge`'s `tests/art_reference.rs` (the same edge and renderer path).

mod common;

use common::{fails, ikarus, stderr};

const CHARACTERS: &str = "../../examples/characters";

fn file(name: &str) -> String {
    format!("{CHARACTERS}/{name}")
}

/// A fresh output path in a folder of this test process's own.
fn out(name: &str) -> String {
    let dir = std::env::temp_dir().join(format!("ikarus-test-pose-art-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name).to_str().unwrap().to_owned()
}

/// Runs `ikarus pose ARGS`, which must succeed and print nothing on stdout.
fn pose(args: &[&str]) {
    let mut all = vec!["pose"];
    all.extend_from_slice(args);
    let o = ikarus(&all);
    assert!(o.status.success(), "{all:?}: {}", stderr(&o));
    assert!(o.stdout.is_empty());
}

/// A PNG's width, height and straight RGBA bytes.
fn decode(path: &str) -> (usize, usize, Vec<u8>) {
    let mut reader = png::Decoder::new(std::io::Cursor::new(std::fs::read(path).unwrap())).read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!((info.color_type, info.bit_depth), (png::ColorType::Rgba, png::BitDepth::Eight));
    buf.truncate(info.buffer_size());
    (info.width as usize, info.height as usize, buf)
}

#[test]
fn the_art_alone_is_fitted_as_spines_pictures_are() {
    let png = out("raptor-walk.png");
    pose(&[
        "--rig",
        &file("spine-raptor-pro.json"),
        "--atlas",
        &file("raptor.atlas"),
        "--animation",
        "walk",
        "--time",
        "0.4",
        "--physics",
        "off",
        "--art-only",
        "--width",
        "600",
        "--height",
        "400",
        "--out",
        &png,
    ]);
    let (w, h, rgba) = decode(&png);
    assert_eq!((w, h), (600, 400));
    // The corners are transparent: no background, no grid, no bones.
    for (x, y) in [(0, 0), (w - 1, 0), (0, h - 1), (w - 1, h - 1)] {
        assert_eq!(rgba[(y * w + x) * 4 + 3], 0, "({x}, {y})");
    }
    // The raptor is wider than tall (1169 × 1132 units): its box is 90 % of the height, 360 px
    // of 400, and centred. Its opaque pixels lie inside by at most the images' transparent
    // edges (a few pixels).
    let (mut lo, mut hi) = ([usize::MAX; 2], [0usize; 2]);
    for (k, px) in rgba.chunks_exact(4).enumerate() {
        if px[3] > 0 {
            let p = [k % w, k / w];
            lo = [lo[0].min(p[0]), lo[1].min(p[1])];
            hi = [hi[0].max(p[0]), hi[1].max(p[1])];
        }
    }
    let (top, bottom) = (lo[1] as f64, hi[1] as f64 + 1.0);
    assert!((20.0..=27.0).contains(&top) && (373.0..=380.0).contains(&bottom), "rows {top}..{bottom}");
    let centre = 0.5 * (lo[0] as f64 + hi[0] as f64 + 1.0);
    assert!((centre - 300.0).abs() < 3.0, "columns centred on {centre}");
}

#[test]
fn the_art_goes_under_the_bones() {
    let png = out("spineboy.png");
    let args = ["--rig", &file("spine-spineboy-pro.skel"), "--atlas", &file("spineboy.atlas")];
    pose(&[&args[..], &["--out", &png]].concat());
    let (w, h, rgba) = decode(&png);
    assert_eq!((w, h), (800, 800));
    assert!(rgba.chunks_exact(4).all(|p| p[3] == 255), "the picture has its background");
    let svg = out("spineboy.svg");
    pose(&[&args[..], &["--out", &svg, "--width", "300", "--height", "200"]].concat());
    let text = std::fs::read_to_string(&svg).unwrap();
    let image = text.find("<image x=\"0\" y=\"0\" width=\"300\" height=\"200\" href=\"data:image/png;base64,").unwrap();
    assert_eq!(text.matches("<image").count(), 1);
    assert!(text.find("<!-- grid -->").unwrap() < image && image < text.find("<g class=\"bone\">").unwrap());
    let alone = out("alone.svg");
    pose(&[&args[..], &["--out", &alone, "--art-only"]].concat());
    let text = std::fs::read_to_string(&alone).unwrap();
    assert!(text.contains("<image") && !text.contains("class=\"bone\"") && !text.contains("<!-- grid -->"));
}

#[test]
fn refusals_are_one_line() {
    let raptor = file("spine-raptor-pro.json");
    let png = out("refused.png");
    let err = fails(&["pose", "--rig", &raptor, "--art-only", "--out", &png], 2);
    assert!(err.contains("--art-only") && err.contains("--atlas"), "{err}");
    let mecha = file("dragonbones-mecha_1406_ske.json");
    let err = fails(&["pose", "--rig", &mecha, "--atlas", &file("raptor.atlas"), "--out", &png], 2);
    assert!(err.contains("DragonBones") && err.contains("bones only"), "{err}");
    let err = fails(&["pose", "--rig", &raptor, "--atlas", &file("no-such.atlas"), "--out", &png], 2);
    assert!(err.contains("no-such.atlas: cannot read"), "{err}");
    let err = fails(&["pose", "--rig", &raptor, "--atlas", &file("raptor.atlas"), "--format", "json"], 2);
    assert!(err.contains("--out FILE.png"), "{err}");
    // An atlas without its page beside it: the page and the folder searched are named.
    let dir = std::env::temp_dir().join(format!("ikarus-test-pose-art-lone-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let lone = dir.join("raptor.atlas");
    std::fs::copy(file("raptor.atlas"), &lone).unwrap();
    let err = fails(&["pose", "--rig", &raptor, "--atlas", lone.to_str().unwrap(), "--out", &png], 2);
    assert!(err.contains("page 0 \"raptor.png\": no such image in") && err.contains(dir.to_str().unwrap()), "{err}");
    // A region the pose draws that the atlas lacks: refused, naming it and its slot.
    let atlas = std::fs::read_to_string(file("raptor.atlas")).unwrap();
    assert!(atlas.contains("\nraptor-jaw\n"));
    std::fs::write(&lone, atlas.replace("\nraptor-jaw\n", "\nraptor-jaw-renamed\n")).unwrap();
    std::fs::copy(file("raptor.png"), dir.join("raptor.png")).unwrap();
    let err = fails(&["pose", "--rig", &raptor, "--atlas", lone.to_str().unwrap(), "--out", &png], 2);
    // The first slot drawing it (the draw order) is the inside of the jaw, whose mesh has its
    // image.
    assert!(err.contains("no region \"raptor-jaw\" (slot \"raptor-jaw-inside\"'s attachment)"), "{err}");
    assert!(!std::path::Path::new(&png).exists(), "nothing is written when refused");
}
