//! Animations as looping GIFs.
//!
//! The static layers (page, grid, workspace, reach circles) are drawn once; each frame draws the
//! moving layers (the joints' paths so far, the arm, the goal, the caption and a clock) on a
//! copy of them. The GIF has one global 256-colour palette ([`Palette`]): the style's solid
//! colours ([`style::key_colours`]) exactly — without them the few pixels of the red goal merge
//! into a dull maroon — and the rest learnt by NeuQuant from the first, middle and last frames.
//! After the first frame, each frame stores only the rectangle that changed, with unchanged
//! pixels transparent, drawn over the previous frame: a still background costs nothing per
//! frame and cannot flicker between palettes.

use gif::{DisposalMethod, Encoder, Frame, Repeat};
use ikarus::kinematics::joint_positions;
use ikarus::motion::Animation;
use ikarus::reach::Workspace;
use ikarus::{Chain, Point2};
use resvg::tiny_skia::Pixmap;

use crate::RenderError;
use crate::arm::check_pose;
use crate::error::check_point;
use crate::palette::{Palette, UNCHANGED};
use crate::path::PathLayer;
use crate::raster::{check_size, new_pixmap, parse, render_onto};
use crate::scene::Scene;
use crate::style;
use crate::svg::Svg;
use crate::view::View;

/// The highest frame rate accepted, frames per second.
pub const MAX_FPS: f64 = 100.0;

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
    /// A tracked path: frame `i` shows its trace up to point `i`.
    pub path: Option<&'a PathLayer>,
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
    if let Some(layer) = overlay.path {
        layer.check("path")?;
    }

    let painter = Painter::new(chain, animation, overlay, width, height)?;
    let palette = painter.learn_palette()?;
    let delay = (100.0 / fps).round().max(2.0) as u16;
    encode_gif(&painter, palette, delay, progress)
}

/// Paints the frames of an animation: the static layers once, the moving ones per frame.
struct Painter<'a> {
    scene: Scene<'a>,
    animation: &'a Animation,
    overlay: &'a Overlay<'a>,
    width: u32,
    height: u32,
    /// The static layers, painted.
    background: Pixmap,
    /// The joints of every frame.
    joints: Vec<Vec<Point2<f64>>>,
}

impl<'a> Painter<'a> {
    fn new(
        chain: &'a Chain,
        animation: &'a Animation,
        overlay: &'a Overlay<'a>,
        width: u32,
        height: u32,
    ) -> Result<Self, RenderError> {
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
        let joints = animation.frames.iter().map(|f| joint_positions(chain, &f.angles)).collect();
        Ok(Self { scene, animation, overlay, width, height, background, joints })
    }

    /// The number of frames.
    fn len(&self) -> usize {
        self.animation.frames.len()
    }

    /// The moving layers of frame `i` over a copy of the background, as RGBA (the background
    /// is opaque, so the premultiplied pixels are plain RGBA).
    fn rgba(&self, i: usize) -> Result<Vec<u8>, RenderError> {
        let scene = &self.scene;
        let mut svg = Svg::new(self.width, self.height);
        if self.overlay.trail {
            let path: Vec<&[Point2<f64>]> = self.joints[..=i].iter().map(Vec::as_slice).collect();
            scene.traces(&mut svg, &path);
        }
        if let Some(layer) = self.overlay.path {
            layer.draw(scene, &mut svg, Some(i));
        }
        scene.arm(&mut svg, &self.joints[i]);
        scene.goal(&mut svg);
        let clock = format!("t = {:.2}", self.animation.frames[i].time);
        scene.caption(&mut svg, self.overlay.caption.as_deref(), Some(&clock));
        let mut pixmap = self.background.clone();
        render_onto(&parse(&svg.finish())?, &mut pixmap);
        Ok(pixmap.take())
    }

    /// One palette for the whole GIF, learnt from the first, middle and last frames (the last
    /// holds the whole trail), each thinned to at most [`SAMPLE_PIXELS`] pixels.
    fn learn_palette(&self) -> Result<Palette, RenderError> {
        let total = self.len();
        let mut sample: Vec<u8> = Vec::new();
        let mut sampled: Vec<usize> = vec![0, total / 2, total - 1];
        sampled.dedup();
        for &i in &sampled {
            thin_into(&self.rgba(i)?, self.width, &mut sample);
        }
        Ok(Palette::learn(&sample, &style::key_colours()))
    }
}

/// The GIF of every frame `painter` paints, `delay` hundredths of a second each, looping:
/// the first frame whole, each later one as its changes. `progress(done, total)` is called
/// after each frame.
fn encode_gif(
    painter: &Painter,
    mut palette: Palette,
    delay: u16,
    progress: &dyn Fn(usize, usize),
) -> Result<Vec<u8>, RenderError> {
    let total = painter.len();
    let mut bytes = Vec::new();
    {
        let encode = |e: gif::EncodingError| RenderError::Encode { format: "gif", message: e.to_string() };
        // check_size keeps both sides ≤ 4096, so they fit a GIF's 16-bit sizes.
        let (w16, h16) = (painter.width as u16, painter.height as u16);
        let mut encoder = Encoder::new(&mut bytes, w16, h16, &palette.rgb_table()).map_err(encode)?;
        encoder.set_repeat(Repeat::Infinite).map_err(encode)?;
        let (mut previous, mut current) = (Vec::new(), Vec::new());
        for i in 0..total {
            let rgba = painter.rgba(i)?;
            palette.map_into(&rgba, &mut current);
            let mut frame = if i == 0 {
                Frame::from_indexed_pixels(w16, h16, current.clone(), None)
            } else {
                changes(&previous, &current, w16)
            };
            frame.delay = delay;
            frame.dispose = DisposalMethod::Keep;
            encoder.write_frame(&frame).map_err(encode)?;
            std::mem::swap(&mut previous, &mut current);
            progress(i + 1, total);
        }
    }
    Ok(bytes)
}

/// At most this many pixels of each sampled frame teach the palette.
const SAMPLE_PIXELS: usize = 1 << 19;

/// Appends every k-th pixel of `rgba` (a picture `width` wide) to `out`, k the smallest step
/// that keeps at most [`SAMPLE_PIXELS`], made odd and not a divisor of `width` so that the
/// picked pixels do not line up in columns.
fn thin_into(rgba: &[u8], width: u32, out: &mut Vec<u8>) {
    let pixels = rgba.len() / 4;
    let mut step = pixels.div_ceil(SAMPLE_PIXELS).max(1);
    if step > 1 {
        step |= 1;
        while (width as usize) % step == 0 {
            step += 2;
        }
    }
    out.extend(rgba.chunks_exact(4).step_by(step).flatten());
}

/// The part of `current` that differs from `previous` (palette indices of pictures `width`
/// wide) as a frame to draw over it: the smallest rectangle holding every changed pixel,
/// with the unchanged ones inside it transparent. If nothing changed, one transparent pixel
/// (the frame still has to be there, to take its time).
fn changes(previous: &[u8], current: &[u8], width: u16) -> Frame<'static> {
    let w = usize::from(width);
    let (mut left, mut right, mut top, mut bottom) = (usize::MAX, 0, usize::MAX, 0);
    for (y, (old, new)) in previous.chunks_exact(w).zip(current.chunks_exact(w)).enumerate() {
        let Some(first) = old.iter().zip(new).position(|(a, b)| a != b) else { continue };
        let last = w - 1 - old.iter().rev().zip(new.iter().rev()).position(|(a, b)| a != b).unwrap_or(0);
        left = left.min(first);
        right = right.max(last);
        top = top.min(y);
        bottom = y;
    }
    if top == usize::MAX {
        return Frame::from_indexed_pixels(1, 1, vec![UNCHANGED], Some(UNCHANGED));
    }
    let mut pixels = Vec::with_capacity((right - left + 1) * (bottom - top + 1));
    for y in top..=bottom {
        let row = y * w;
        pixels.extend(
            previous[row + left..=row + right]
                .iter()
                .zip(&current[row + left..=row + right])
                .map(|(a, b)| if a == b { UNCHANGED } else { *b }),
        );
    }
    // Within the picture, so within u16.
    let mut frame =
        Frame::from_indexed_pixels((right - left + 1) as u16, (bottom - top + 1) as u16, pixels, Some(UNCHANGED));
    frame.left = left as u16;
    frame.top = top as u16;
    frame
}
