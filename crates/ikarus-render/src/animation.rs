//! Animations as looping GIFs.
//!
//! The static layers (page, grid, workspace, reach circles) are drawn once; each frame draws the
//! moving layers (the joints' paths so far, the arm, the goal, the caption and a clock) on a
//! copy of them. Every frame gets its own 256-colour palette: the palette's solid colours
//! ([`style::key_colours`]) exactly, and the rest learnt from the frame by NeuQuant for the
//! anti-aliased edges. Without the exact entries, the few pixels of the red goal are merged
//! into a dull maroon.

use gif::{Encoder, Frame, Repeat};
use ikarus::kinematics::joint_positions;
use ikarus::motion::Animation;
use ikarus::reach::Workspace;
use ikarus::{Chain, Point2};

use crate::RenderError;
use crate::arm::{check_point, check_pose};
use crate::raster::{check_size, new_pixmap, parse, render_onto};
use crate::scene::Scene;
use crate::style;
use crate::svg::Svg;
use crate::view::View;

/// The highest frame rate accepted, frames per second.
pub const MAX_FPS: f64 = 100.0;

/// NeuQuant's sampling factor: 1 is best and slowest, 30 fastest; 10 is the gif crate's
/// suggestion for a good balance.
const QUANTISER_SPEED: i32 = 10;

/// What an animation is drawn with besides the arm.
#[derive(Debug, Clone, Default)]
pub struct Overlay<'a> {
    /// The goal, drawn as a red target.
    pub goal: Option<Point2<f64>>,
    /// Reachable cells to shade, if any.
    pub workspace: Option<&'a Workspace>,
    /// Whether to draw the reach circles.
    pub show_reach: bool,
    /// A line of text under the plot.
    pub caption: Option<String>,
    /// Whether to draw the path every joint has travelled so far.
    pub trail: bool,
}

/// `animation` as a looping GIF of `width` × `height` pixels at `fps` frames per second, one
/// GIF frame per animation frame. `progress(done, total)` is called after each frame.
///
/// GIF delays are whole hundredths of a second, so the frame delay is `round(100 / fps)`
/// hundredths, at least 2 (browsers slow shorter delays down to 10).
///
/// # Errors
/// [`RenderError::Size`] for a side outside 16..=4096, [`RenderError::Fps`] for a rate outside
/// (0, 100], [`RenderError::NoFrames`], [`RenderError::Length`] or [`RenderError::NonFinite`]
/// for frames that do not fit the chain, [`RenderError::Encode`] if encoding fails.
pub fn animation_gif(
    chain: &Chain,
    animation: &Animation,
    overlay: &Overlay,
    width: u32,
    height: u32,
    fps: f64,
    progress: &dyn Fn(usize, usize),
) -> Result<Vec<u8>, RenderError> {
    check_size(width, height)?;
    if !(fps > 0.0 && fps <= MAX_FPS) {
        return Err(RenderError::Fps { value: fps });
    }
    if animation.frames.is_empty() {
        return Err(RenderError::NoFrames);
    }
    for (i, f) in animation.frames.iter().enumerate() {
        check_pose(chain, &f.angles, &format!("animation.frames[{i}].angles"))?;
    }
    check_point(overlay.goal, "goal")?;

    let scene = Scene {
        chain,
        view: View::new(chain, overlay.goal, width, height),
        goal: overlay.goal,
        workspace: overlay.workspace,
        show_reach: overlay.show_reach,
    };
    let mut background_svg = Svg::new(width, height);
    scene.background(&mut background_svg);
    let mut background = new_pixmap(width, height)?;
    render_onto(&parse(&background_svg.finish())?, &mut background);

    let joints: Vec<Vec<Point2<f64>>> = animation.frames.iter().map(|f| joint_positions(chain, &f.angles)).collect();
    let delay = (100.0 / fps).round().max(2.0) as u16;
    let keys = style::key_colours();
    let total = animation.frames.len();
    let mut bytes = Vec::new();
    {
        let encode = |e: gif::EncodingError| RenderError::Encode { format: "gif", message: e.to_string() };
        // check_size keeps both sides ≤ 4096, so they fit a GIF's 16-bit sizes.
        let (w16, h16) = (width as u16, height as u16);
        let mut encoder = Encoder::new(&mut bytes, w16, h16, &[]).map_err(encode)?;
        encoder.set_repeat(Repeat::Infinite).map_err(encode)?;
        for (i, frame) in animation.frames.iter().enumerate() {
            let mut svg = Svg::new(width, height);
            if overlay.trail {
                let path: Vec<&[Point2<f64>]> = joints[..=i].iter().map(Vec::as_slice).collect();
                scene.traces(&mut svg, &path);
            }
            scene.arm(&mut svg, &joints[i]);
            scene.goal(&mut svg);
            let clock = format!("t = {:.2}", frame.time);
            scene.caption(&mut svg, overlay.caption.as_deref(), Some(&clock));
            let mut pixmap = background.clone();
            render_onto(&parse(&svg.finish())?, &mut pixmap);
            // The background is opaque, so the premultiplied pixels are plain RGBA.
            let rgba = pixmap.take();
            let (palette, indices) = quantise(&rgba, &keys);
            let mut gif_frame = Frame::from_palette_pixels(w16, h16, indices, palette, None);
            gif_frame.delay = delay;
            encoder.write_frame(&gif_frame).map_err(encode)?;
            progress(i + 1, total);
        }
    }
    Ok(bytes)
}

/// A 256-colour palette for `rgba` (opaque pixels) and each pixel's index in it: the `keys`
/// exactly, then colours NeuQuant learns from the frame.
fn quantise(rgba: &[u8], keys: &[[u8; 3]]) -> (Vec<u8>, Vec<u8>) {
    let learnt = 256 - keys.len();
    let nq = color_quant::NeuQuant::new(QUANTISER_SPEED, learnt, rgba);
    let mut palette: Vec<u8> = nq.color_map_rgb();
    palette.resize(3 * learnt, 0);
    let exact: std::collections::HashMap<[u8; 3], u8> =
        keys.iter().enumerate().map(|(i, &k)| (k, (learnt + i) as u8)).collect();
    palette.extend(keys.iter().flatten());
    let indices = rgba
        .chunks_exact(4)
        .map(|p| {
            let colour = [p[0], p[1], p[2]];
            exact.get(&colour).copied().unwrap_or_else(|| nq.index_of(p) as u8)
        })
        .collect();
    (palette, indices)
}
