//! The pictures decode as what they claim to be, at the requested size and frame count, and
//! show what they should where they should: the goal is red at the goal's pixel, the arm's
//! links are drawn, the caption's text is there.

use ikarus::motion::{Timing, animate};
use ikarus::reach::{WorkspaceOptions, sample};
use ikarus::{Chain, Ease, JointLimits, Link, Point2};
use ikarus_render::{ArmFigure, Overlay, RenderError, View, animation_gif, arm_png, arm_svg, ease_png, svg_to_png};

fn seed_arm() -> Chain {
    let d = f64::to_radians;
    let lim = |a: f64, b: f64| JointLimits::new(d(a), d(b)).unwrap();
    Chain::new(
        [0.0, 0.0],
        &[
            Link::new(3.0, d(5.0)).with_limits(lim(-45.0, 45.0)),
            Link::new(2.0, d(5.0)).with_limits(lim(-90.0, 90.0)),
            Link::new(1.0, d(5.0)).with_limits(lim(-170.0, 170.0)),
        ],
    )
    .unwrap()
}

/// Decoded RGBA pixels and size of a PNG.
fn decode_png(bytes: &[u8]) -> (u32, u32, Vec<u8>) {
    let mut decoder = png::Decoder::new(std::io::Cursor::new(bytes));
    decoder.set_transformations(png::Transformations::EXPAND);
    let mut reader = decoder.read_info().expect("a PNG header");
    let mut buf = vec![0; reader.output_buffer_size().expect("a size")];
    let info = reader.next_frame(&mut buf).expect("PNG pixels");
    assert_eq!(info.color_type, png::ColorType::Rgba, "RGBA output");
    buf.truncate(info.buffer_size());
    (info.width, info.height, buf)
}

fn pixel(rgba: &[u8], width: u32, (x, y): (f64, f64)) -> [u8; 3] {
    let i = 4 * (y.round() as usize * width as usize + x.round() as usize);
    [rgba[i], rgba[i + 1], rgba[i + 2]]
}

fn is_red([r, g, b]: [u8; 3]) -> bool {
    r > 180 && g < 90 && b < 90
}

/// How many pixels along the segment a→b (in pixels) differ clearly from `background`.
fn inked_along(rgba: &[u8], width: u32, a: (f64, f64), b: (f64, f64), background: [u8; 3]) -> usize {
    (1..20)
        .map(|k| {
            let t = f64::from(k) / 20.0;
            (a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1))
        })
        .filter(|&p| {
            let c = pixel(rgba, width, p);
            c.iter().zip(background).map(|(x, y)| (i32::from(*x) - i32::from(y)).abs()).sum::<i32>() > 60
        })
        .count()
}

#[test]
fn arm_png_has_the_size_the_goal_in_red_and_the_links_drawn() {
    let chain = seed_arm();
    let pose = [0.3, 1.1, 0.9];
    let goal = Point2::new(-2.0, 3.5);
    let figure =
        ArmFigure { goal: Some(goal), caption: Some("dls · reached".into()), ..ArmFigure::new(&chain, &pose) };
    let (w, h) = (640, 480);
    let (width, height, rgba) = decode_png(&arm_png(&figure, w, h).unwrap());
    assert_eq!((width, height), (w, h));

    let view = figure.view(w, h);
    assert!(
        is_red(pixel(&rgba, w, view.world_to_pixel(goal))),
        "goal pixel {:?}",
        pixel(&rgba, w, view.world_to_pixel(goal))
    );
    // Elsewhere, far from the goal, it is not red.
    let away = view.world_to_pixel(Point2::new(4.0, -4.0));
    assert!(!is_red(pixel(&rgba, w, away)));

    // Every link is inked along its length (a blank or misplaced arm fails this).
    let joints = ikarus::kinematics::joint_positions(&chain, &pose);
    let background = pixel(&rgba, w, view.world_to_pixel(Point2::new(-4.5, -4.5)));
    for pair in joints.windows(2) {
        let (a, b) = (view.world_to_pixel(pair[0]), view.world_to_pixel(pair[1]));
        assert!(inked_along(&rgba, w, a, b, background) >= 17, "link {pair:?} is not drawn");
    }
}

#[test]
fn a_blank_figure_fails_the_ink_check() {
    // The same check as above on a picture with nothing drawn: it must find no link.
    let chain = seed_arm();
    let pose = [0.3, 1.1, 0.9];
    let view = View::new(&chain, None, 640, 480);
    let blank = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"640\" height=\"480\">\
                 <rect width=\"640\" height=\"480\" fill=\"#ffffff\"/></svg>";
    let (_, _, rgba) = decode_png(&svg_to_png(blank).unwrap());
    let joints = ikarus::kinematics::joint_positions(&chain, &pose);
    let (a, b) = (view.world_to_pixel(joints[0]), view.world_to_pixel(joints[1]));
    assert_eq!(inked_along(&rgba, 640, a, b, [255, 255, 255]), 0);
}

#[test]
fn the_caption_is_set_in_the_embedded_font() {
    // No system font is ever loaded (see raster.rs); dark pixels below the plot prove the text
    // was drawn with the embedded DejaVu Sans.
    let chain = seed_arm();
    let pose = [0.0, 0.0, 0.0];
    let with = ArmFigure { caption: Some("ikarus caption text".into()), ..ArmFigure::new(&chain, &pose) };
    let without = ArmFigure::new(&chain, &pose);
    let dark = |fig: &ArmFigure| {
        let (w, h, rgba) = decode_png(&arm_png(fig, 400, 400).unwrap());
        let plot = fig.view(w, h).plot_area();
        let top = plot.bottom.ceil() as usize + 2;
        (top..h as usize)
            .flat_map(|y| (0..w as usize).map(move |x| (x, y)))
            .filter(|&(x, y)| pixel(&rgba, w, (x as f64, y as f64)).iter().all(|&c| c < 140))
            .count()
    };
    let (with, without) = (dark(&with), dark(&without));
    assert!(with > 100 && without < with / 4, "caption pixels: {with} with text, {without} without");
}

#[test]
fn svg_parses_with_the_requested_size() {
    let chain = seed_arm();
    let ws = sample(&chain, &WorkspaceOptions { resolution: 64, ..WorkspaceOptions::default() }).unwrap();
    let pose = [0.1, 0.2, 0.3];
    let figure = ArmFigure {
        workspace: Some((&ws).into()),
        traces: true,
        ghosts: vec![&[0.0, 0.0, 0.0]],
        ..ArmFigure::new(&chain, &pose)
    };
    let svg = arm_svg(&figure, 500, 300).unwrap();
    let tree = resvg::usvg::Tree::from_str(&svg, &resvg::usvg::Options::default()).unwrap();
    assert_eq!((tree.size().width(), tree.size().height()), (500.0, 300.0));
    // The shaded workspace is there: its cells are drawn.
    assert!(svg.contains("workspace"), "no workspace group");
}

#[test]
fn gif_has_one_frame_per_animation_frame() {
    let chain = seed_arm();
    let animation =
        animate(&chain, &[vec![0.1, 0.1, 0.1], vec![0.5, 1.0, 0.5]], None, Timing::Frames(7), Ease::Sine).unwrap();
    let overlay = Overlay { goal: Some(Point2::new(2.0, 3.0)), show_reach: true, trail: true, ..Overlay::default() };
    let calls = std::cell::Cell::new(0);
    let bytes = animation_gif(&chain, &animation, &overlay, 420, 420, 25.0, &|done, total| {
        assert_eq!(total, 7);
        calls.set(done);
    })
    .unwrap();
    assert_eq!(calls.get(), 7, "progress reaches the end");

    let mut options = gif::DecodeOptions::new();
    options.set_color_output(gif::ColorOutput::RGBA);
    let mut decoder = options.read_info(std::io::Cursor::new(&bytes)).unwrap();
    assert_eq!((decoder.width(), decoder.height()), (420, 420));
    let view = View::new(&chain, overlay.goal, 420, 420);
    let goal_px = view.world_to_pixel(overlay.goal.unwrap());
    // Frames after the first hold only what changed and are drawn over the previous picture, as
    // a viewer does: paste each frame's opaque pixels onto a canvas and look at the canvas.
    let mut canvas = vec![0u8; 420 * 420 * 4];
    let mut frames = 0;
    let mut partial = 0;
    while let Some(frame) = decoder.read_next_frame().unwrap() {
        assert_eq!(frame.delay, 4, "25 fps is 4 hundredths per frame");
        let (left, top, w) = (usize::from(frame.left), usize::from(frame.top), usize::from(frame.width));
        if frames == 0 {
            assert_eq!((frame.width, frame.height), (420, 420), "the first frame is whole");
        } else if usize::from(frame.width) * usize::from(frame.height) < 420 * 420 / 2 {
            partial += 1;
        }
        for (k, p) in frame.buffer.chunks_exact(4).enumerate() {
            if p[3] != 0 {
                let i = 4 * ((top + k / w) * 420 + left + k % w);
                canvas[i..i + 4].copy_from_slice(p);
            }
        }
        // Quantising must not lose the goal's red: the palette keeps the style's colours exact.
        let goal = pixel(&canvas, 420, goal_px);
        assert!(is_red(goal), "frame {frames}: goal pixel {goal:?}");
        // The arm is where this frame puts it.
        let background = pixel(&canvas, 420, view.world_to_pixel(Point2::new(-4.5, -4.5)));
        for pair in animation.frames[frames].joints.windows(2) {
            let (a, b) = (view.world_to_pixel(pair[0]), view.world_to_pixel(pair[1]));
            assert!(inked_along(&canvas, 420, a, b, background) >= 17, "frame {frames}: link {pair:?} is not drawn");
        }
        frames += 1;
    }
    assert_eq!(frames, 7);
    assert!(partial >= 3, "only {partial} frames store less than half the picture");
}

#[test]
fn ease_plot_decodes() {
    let (w, h, rgba) = decode_png(&ease_png(&Ease::parent(0.3, 0.75).unwrap(), 420, 300).unwrap());
    assert_eq!((w, h), (420, 300));
    let distinct: std::collections::HashSet<[u8; 3]> = rgba.chunks(4).map(|p| [p[0], p[1], p[2]]).collect();
    assert!(distinct.len() > 20, "a plot, not a blank page: {} colours", distinct.len());
}

#[test]
fn bad_input_is_an_error_naming_the_field() {
    let chain = seed_arm();
    let pose = [0.0, 0.0];
    let e = arm_svg(&ArmFigure::new(&chain, &pose), 100, 100).unwrap_err();
    assert_eq!(e.to_string(), "pose: expected 3 values for this arm or skeleton, got 2");
    let pose = [0.0, 0.0, 0.0];
    assert!(matches!(arm_svg(&ArmFigure::new(&chain, &pose), 8, 100), Err(RenderError::Size { field: "width", .. })));
    let nan_goal = ArmFigure { goal: Some(Point2::new(f64::NAN, 0.0)), ..ArmFigure::new(&chain, &pose) };
    assert_eq!(arm_svg(&nan_goal, 100, 100).unwrap_err().to_string(), "goal.x: must be a finite number, got NaN");
    let animation = animate(&chain, &[vec![0.0; 3]], None, Timing::Frames(2), Ease::Linear).unwrap();
    let e = animation_gif(&chain, &animation, &Overlay::default(), 100, 100, 0.0, &|_, _| {}).unwrap_err();
    assert_eq!(e.to_string(), "fps: must be a number in (0, 100], got 0");
    // Numbers are written short (issue 11: 1e300 was 301 digits).
    let e = animation_gif(&chain, &animation, &Overlay::default(), 100, 100, 1e300, &|_, _| {}).unwrap_err();
    assert_eq!(e.to_string(), "fps: must be a number in (0, 100], got 1e300");
}
