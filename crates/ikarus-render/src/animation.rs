//! Animations as looping GIFs.
//!
//! The static layers (page, grid, workspace, reach circles) are drawn once; the joints' paths
//! grow by one step per frame on a copy of them (so a GIF costs time linear in its frames); each
//! frame draws the moving layers (the arm, the goal, the caption and a clock) on a copy of that. The GIF has one global 256-colour palette ([`Palette`]): the style's solid
//! colours ([`style::key_colours`]) exactly — without them the few pixels of the red goal merge
//! into a dull maroon — and the rest learnt by NeuQuant from the first, middle and last frames.
//! After the first frame, each frame stores only the rectangle that changed, with unchanged
//! pixels transparent, drawn over the previous frame: a still background costs nothing per
//! frame and cannot flicker between palettes.

use crate::reachable::Reachable;
use gif::{DisposalMethod, Encoder, Frame, Repeat};
use ikarus::kinematics::joint_positions;
use ikarus::motion::Animation;
use ikarus::{Chain, Interrupt, Point2};
use resvg::tiny_skia::Pixmap;

use crate::RenderError;
use crate::arm::check_pose;
use crate::error::check_point;
use crate::palette::{Palette, UNCHANGED};
use crate::path::PathLayer;
use crate::raster::{check_size, new_pixmap, parse, render_onto};
use crate::scene::{Scene, TrailStyle};
use crate::style;
use crate::svg::Svg;
use crate::view::View;

thread_local! {
    /// The interrupt of [`with_interrupt`] on this thread.
    static INTERRUPT: std::cell::RefCell<Option<Interrupt>> = const { std::cell::RefCell::new(None) };
}

/// Runs `f` with `interrupt` checked before every frame of every GIF this thread encodes
/// meanwhile ([`animation_gif`]): once it is set, the GIF ends with [`RenderError::Encode`]
/// ("interrupted"). A server stops a picture nobody waits for any more this way, without a
/// parameter through every drawing function.
pub fn with_interrupt<T>(interrupt: &Interrupt, f: impl FnOnce() -> T) -> T {
    /// Puts the previous interrupt back, even if `f` panics.
    struct Restore(Option<Interrupt>);
    impl Drop for Restore {
        fn drop(&mut self) {
            let previous = self.0.take();
            INTERRUPT.with(|slot| *slot.borrow_mut() = previous);
        }
    }
    let _restore = Restore(INTERRUPT.with(|slot| slot.replace(Some(interrupt.clone()))));
    f()
}

/// Fails when this thread's [`with_interrupt`] token is set.
pub(crate) fn check_interrupt() -> Result<(), RenderError> {
    if INTERRUPT.with(|slot| slot.borrow().as_ref().is_some_and(Interrupt::is_interrupted)) {
        Err(RenderError::Encode { format: "gif", message: "interrupted".to_owned() })
    } else {
        Ok(())
    }
}

/// The highest frame rate accepted, frames per second.
pub const MAX_FPS: f64 = 100.0;

/// What an animation is drawn with besides the arm.
#[derive(Debug, Clone, Default)]
pub struct Overlay<'a> {
    /// The goal, drawn as a red target.
    pub goal: Option<Point2<f64>>,
    /// The reachable area to shade, if any.
    pub workspace: Option<Reachable<'a>>,
    /// Whether to draw the reach circles.
    pub show_reach: bool,
    /// A line of text under the plot.
    pub caption: Option<String>,
    /// Whether to draw the path every joint has travelled so far.
    pub trail: bool,
    /// How the trail is drawn: with a cross at every frame (the still pictures' style, the
    /// default), or as the playground's screen draws it, lines only.
    pub trail_style: TrailStyle,
    /// Whether to draw earlier poses as ghosts, as the playground's screen does: about a dozen
    /// of the frames before the current one, evenly spread, fading with age ([`ghost_frames`]).
    pub ghosts: bool,
    /// A tracked path: frame `i` shows its trace up to point `i`.
    pub path: Option<&'a PathLayer>,
}

/// The ghosts at frame `current` of `total`, as the playground's screen draws them (view.js's
/// `ghostFrames`): frames `0, e, 2e, …` before `current`, `e = max(1, round(total / 12))`, each
/// with the opacity `0.06 + 0.16 · (1 − age)`, `age = (current − i) / max(1, total − 1)`.
#[must_use]
pub fn ghost_frames(total: usize, current: usize) -> Vec<(usize, f64)> {
    let every = ((total as f64 / 12.0).round() as usize).max(1);
    let span = total.saturating_sub(1).max(1) as f64;
    (0..current).step_by(every).map(|i| (i, 0.06 + 0.16 * (1.0 - (current - i) as f64 / span))).collect()
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
    let delay = gif_delay(fps);
    let mut trail = painter.trail();
    let (width, height) = (painter.width, painter.height);
    encode_gif(width, height, painter.len(), palette, delay, &mut |i| painter.rgba(i, &mut trail), progress)
}

/// The delay of a GIF frame at `fps`, in hundredths of a second: `round(100 / fps)`, at least 2.
pub(crate) fn gif_delay(fps: f64) -> u16 {
    (100.0 / fps).round().max(2.0) as u16
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
        let view = View::new(chain, overlay.goal, width, height);
        let scene = Scene::of_chain(chain, view, overlay.goal, overlay.workspace, overlay.show_reach);
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

    /// A trail before its first step: the background.
    fn trail(&self) -> Trail {
        Trail { pixmap: self.background.clone(), next: 0 }
    }

    /// Draws the trail's steps up to frame `i` (from the start again if it is past `i`).
    fn advance(&self, trail: &mut Trail, i: usize) -> Result<(), RenderError> {
        if !self.overlay.trail {
            return Ok(());
        }
        if trail.next > i + 1 {
            *trail = self.trail();
        }
        while trail.next <= i {
            check_interrupt()?;
            let j = trail.next;
            let mut svg = Svg::new(self.width, self.height);
            let from = j.checked_sub(1).map(|p| self.joints[p].as_slice());
            self.scene.trace_step(&mut svg, from, &self.joints[j], self.overlay.trail_style);
            render_onto(&parse(&svg.finish())?, &mut trail.pixmap);
            trail.next += 1;
        }
        Ok(())
    }

    /// The moving layers of frame `i` over the background and the trail so far, as RGBA (the
    /// background is opaque, so the premultiplied pixels are plain RGBA).
    fn rgba(&self, i: usize, trail: &mut Trail) -> Result<Vec<u8>, RenderError> {
        let scene = &self.scene;
        self.advance(trail, i)?;
        let mut svg = Svg::new(self.width, self.height);
        if self.overlay.ghosts {
            let ghosts: Vec<(&[Point2<f64>], f64)> =
                ghost_frames(self.len(), i).into_iter().map(|(k, o)| (self.joints[k].as_slice(), o)).collect();
            scene.ghosts(&mut svg, &ghosts);
        }
        if let Some(layer) = self.overlay.path {
            layer.draw(scene, &mut svg, Some(i));
        }
        scene.arm(&mut svg, &self.joints[i]);
        scene.goal(&mut svg);
        let clock = format!("t = {:.2}", self.animation.frames[i].time);
        scene.caption(&mut svg, self.overlay.caption.as_deref(), Some(&clock));
        let mut pixmap = trail.pixmap.clone();
        render_onto(&parse(&svg.finish())?, &mut pixmap);
        Ok(pixmap.take())
    }

    /// One palette for the whole GIF, learnt from the first, middle and last frames (the last
    /// holds the whole trail), each thinned to at most [`SAMPLE_PIXELS`] pixels.
    fn learn_palette(&self) -> Result<Palette, RenderError> {
        let mut trail = self.trail();
        learn_palette_of(self.len(), self.width, &mut |i| self.rgba(i, &mut trail))
    }
}

/// One palette for a GIF of `total` frames `width` wide, learnt from the first, middle and
/// last frames as `rgba(i)` paints them, each thinned to at most [`SAMPLE_PIXELS`] pixels.
/// Shared by the skeleton's GIF and the character's.
pub(crate) fn learn_palette_of(
    total: usize,
    width: u32,
    rgba: &mut dyn FnMut(usize) -> Result<Vec<u8>, RenderError>,
) -> Result<Palette, RenderError> {
    let mut sample = Vec::new();
    let mut sampled = vec![0, total / 2, total - 1];
    sampled.dedup();
    for &i in &sampled {
        thin_into(&rgba(i)?, width, &mut sample);
    }
    Ok(Palette::learn(&sample, &style::key_colours()))
}

/// The GIF of `total` frames of `width` × `height` pixels, frame `i` painted as RGBA by
/// `rgba(i)` (in order), `delay` hundredths of a second each, looping: the first frame whole,
/// each later one as its changes. `progress(done, total)` is called after each frame. Shared
/// by the arm's animations and the skeleton's ([`crate::skeleton_gif`]).
pub(crate) fn encode_gif(
    width: u32,
    height: u32,
    total: usize,
    mut palette: Palette,
    delay: u16,
    rgba: &mut dyn FnMut(usize) -> Result<Vec<u8>, RenderError>,
    progress: &dyn Fn(usize, usize),
) -> Result<Vec<u8>, RenderError> {
    let mut bytes = Vec::new();
    {
        let encode = |e: gif::EncodingError| RenderError::Encode { format: "gif", message: e.to_string() };
        // check_size keeps both sides ≤ 4096, so they fit a GIF's 16-bit sizes.
        let (w16, h16) = (width as u16, height as u16);
        let mut encoder = Encoder::new(&mut bytes, w16, h16, &palette.rgb_table()).map_err(encode)?;
        encoder.set_repeat(Repeat::Infinite).map_err(encode)?;
        let (mut previous, mut current) = (Vec::new(), Vec::new());
        for i in 0..total {
            check_interrupt()?;
            let rgba = rgba(i)?;
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

/// The background with the joints' paths drawn up to (not including) frame `next`.
struct Trail {
    pixmap: Pixmap,
    next: usize,
}

/// At most this many pixels of each sampled frame teach the palette.
const SAMPLE_PIXELS: usize = 1 << 19;

/// Appends every k-th pixel of `rgba` (a picture `width` wide) to `out`, k the smallest step
/// that keeps at most [`SAMPLE_PIXELS`], made odd and not a divisor of `width` so that the
/// picked pixels do not line up in columns.
pub(crate) fn thin_into(rgba: &[u8], width: u32, out: &mut Vec<u8>) {
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

#[cfg(test)]
mod tests {
    use super::*;
    use ikarus::motion::{Timing, animate};
    use ikarus::{Ease, Link};

    #[test]
    fn a_gif_stops_when_its_interrupt_is_set() {
        let chain = Chain::new([0.0, 0.0], &[Link::new(3.0, 0.1), Link::new(2.0, 0.1)]).unwrap();
        let keyframes = [vec![0.1, 0.1], vec![0.9, 1.2]];
        let animation = animate(&chain, &keyframes, None, Timing::Frames(5), Ease::Sine).unwrap();
        let overlay = Overlay { trail: true, ..Overlay::default() };
        let token = Interrupt::new();
        let gif = || animation_gif(&chain, &animation, &overlay, 64, 64, 25.0, &|_, _| {});
        assert!(with_interrupt(&token, gif).is_ok(), "an unset token changes nothing");
        token.interrupt();
        let e = with_interrupt(&token, gif).unwrap_err();
        assert_eq!(e.to_string(), "gif: encoding failed: interrupted");
        // Outside `with_interrupt` the token does not apply.
        assert!(gif().is_ok());
    }

    #[test]
    fn ghosts_are_the_screens() {
        // view.js's ghostFrames(25, 24): every 2nd frame before the 24th, the oldest faintest.
        let g = ghost_frames(25, 24);
        assert_eq!(g.iter().map(|&(i, _)| i).collect::<Vec<_>>(), (0..24).step_by(2).collect::<Vec<_>>());
        assert!((g[0].1 - 0.06).abs() < 1e-12 && (g[11].1 - (0.06 + 0.16 * (1.0 - 2.0 / 24.0))).abs() < 1e-12);
        assert!(ghost_frames(25, 0).is_empty() && ghost_frames(1, 0).is_empty());
    }

    /// The trail grown one step per frame looks like the trail drawn at once (as the still
    /// figures draw it, and as every GIF frame drew it before, at a cost quadratic in the
    /// frames): few pixels differ, and by little.
    #[test]
    fn the_incremental_trail_matches_the_whole_trail() {
        let links = [Link::new(3.0, 0.1), Link::new(2.0, 0.1), Link::new(1.0, 0.1)];
        let chain = Chain::new([0.0, 0.0], &links).unwrap();
        let keyframes = [vec![0.1, 0.1, 0.1], vec![0.9, 1.2, -0.6], vec![1.6, 0.4, 0.8]];
        let animation = animate(&chain, &keyframes, None, Timing::Frames(40), Ease::Sine).unwrap();
        let overlay = Overlay { goal: Some(Point2::new(2.0, 3.0)), trail: true, ..Overlay::default() };
        let painter = Painter::new(&chain, &animation, &overlay, 300, 300).unwrap();
        let last = painter.len() - 1;
        let mut trail = painter.trail();
        // Out of order, as the palette asks for frames: the trail starts again when needed.
        painter.rgba(last, &mut trail).unwrap();
        painter.rgba(3, &mut trail).unwrap();
        let incremental = painter.rgba(last, &mut trail).unwrap();

        let mut svg = Svg::new(300, 300);
        let path: Vec<&[Point2<f64>]> = painter.joints.iter().map(Vec::as_slice).collect();
        painter.scene.traces(&mut svg, &path);
        let mut whole = painter.background.clone();
        render_onto(&parse(&svg.finish()).unwrap(), &mut whole);
        let mut svg = Svg::new(300, 300);
        painter.scene.arm(&mut svg, &painter.joints[last]);
        painter.scene.goal(&mut svg);
        let clock = format!("t = {:.2}", animation.frames[last].time);
        painter.scene.caption(&mut svg, None, Some(&clock));
        render_onto(&parse(&svg.finish()).unwrap(), &mut whole);
        let whole = whole.take();

        let background = painter.background.data();
        let differs = |a: &[u8], b: &[u8]| a.iter().zip(b).any(|(x, y)| x.abs_diff(*y) > 24);
        let pixels = |v: &[u8]| v.chunks_exact(4).map(<[u8]>::to_vec).collect::<Vec<_>>();
        let (inc, wh, bg) = (pixels(&incremental), pixels(&whole), pixels(background));
        let drawn = wh.iter().zip(&bg).filter(|(w, b)| differs(w, b)).count();
        let off = inc.iter().zip(&wh).filter(|(i, w)| differs(i, w)).count();
        assert!(drawn > 1000, "the trail and arm are drawn: {drawn} pixels");
        assert!(off * 20 < drawn, "{off} of {drawn} drawn pixels differ");
    }
}
