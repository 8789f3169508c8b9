//! A character's motion with its art: every frame's art under its bones, or the art alone, as a
//! looping GIF ([`character_art_gif`]) and as one picture ([`character_art_motion_png`],
//! [`character_art_motion_svg`]).
//!
//! Rules:
//! - One view for the whole motion, so that the character does not jump: under the bones, the
//!   bones picture's view ([`View::fitting`]) of every frame's bones, targets and art vertices
//!   together; alone, the box of every frame's art vertices filling [`ART_FILL`] of the
//!   picture, centred, y up (the fit of `ikarus pose --art-only`, over the whole motion).
//! - Under the bones each GIF frame is the grid, the frame's art, then its bones, targets and
//!   caption (with its time), encoded as the bones' GIF is (one palette, each frame its
//!   changes). Alone, the background is transparent: a GIF pixel is either opaque or
//!   transparent, so a pixel is drawn when its alpha is at least half (128) and left
//!   transparent otherwise, its colour straight (not premultiplied); each frame is whole and
//!   cleared before the next (GIF's disposal "restore to background"), since a transparent
//!   pixel cannot cover an opaque one drawn before.
//! - The one picture is the last frame's art under every frame's bones (the earlier as ghosts,
//!   as [`character_motion_svg`](crate::character_motion_svg) draws them), or the last
//!   frame's art alone in the motion's fit. An SVG holds the art as one embedded PNG.

use gif::{DisposalMethod, Encoder, Frame, Repeat};
use ikarus::Point2;
use resvg::tiny_skia::Pixmap;

use crate::RenderError;
use crate::animation::{MAX_FPS, check_interrupt, encode_gif, gif_delay, learn_palette_of, thin_into};
use crate::art::{Art, WorldToPixel};
use crate::art_raster::{art_pixmap, draw_art};
use crate::character::{CharacterFigure, Layers, character_layers};
use crate::character_art::{ART_FILL, png_data_url};
use crate::character_gif::CharacterMotionFigure;
use crate::palette::{Palette, UNCHANGED};
use crate::raster::{check_size, draw_svg_onto, pixmap_png, svg_to_pixmap};
use crate::svg::Svg;
use crate::view::View;

/// Where a motion's art is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ArtPlacement {
    /// Under the bones, over the grid.
    #[default]
    UnderBones,
    /// Alone, on a transparent background.
    Alone,
}

/// A character's motion with its art: the frames' bones and one [`Art`] per frame.
#[derive(Debug, Clone, Default)]
pub struct CharacterArtMotion<'a> {
    /// The frames' bones, times and caption.
    pub motion: CharacterMotionFigure<'a>,
    /// Every frame's art, as many as the motion's frames.
    pub arts: Vec<Art<'a>>,
    /// Under the bones or alone.
    pub placement: ArtPlacement,
}

/// How a motion's art lands on the picture.
enum Fit {
    /// The bones' view (its grid, its world → pixel map).
    Bones(View),
    /// The art's own fit.
    Alone(WorldToPixel),
}

impl CharacterArtMotion<'_> {
    /// Checks the size, the frames and the arts, and fits the whole motion.
    fn fit(&self, width: u32, height: u32) -> Result<Fit, RenderError> {
        check_size(width, height)?;
        let n = self.motion.frames.len();
        if n == 0 {
            return Err(RenderError::NoFrames);
        }
        if self.arts.len() != n {
            return Err(RenderError::Art {
                field: "arts".to_owned(),
                problem: format!("expected one per frame ({n}), got {}", self.arts.len()),
            });
        }
        for f in &self.motion.frames {
            f.check()?;
        }
        for a in &self.arts {
            a.check()?;
        }
        let art = union(self.arts.iter().filter_map(Art::extent));
        Ok(match self.placement {
            ArtPlacement::Alone => {
                let (min, max) = art.unwrap_or((Point2::origin(), Point2::origin()));
                Fit::Alone(WorldToPixel::fitting(min, max, width, height, ART_FILL))
            }
            ArtPlacement::UnderBones => {
                let bones = union(self.motion.frames.iter().map(CharacterFigure::extent));
                let (min, max) = union(bones.into_iter().chain(art)).unwrap_or((Point2::origin(), Point2::origin()));
                Fit::Bones(View::fitting(min, max, width, height))
            }
        })
    }
}

/// The smallest box holding every box of `boxes`, `None` for none.
fn union(boxes: impl Iterator<Item = (Point2<f64>, Point2<f64>)>) -> Option<(Point2<f64>, Point2<f64>)> {
    boxes.reduce(|(min, max), (a, b)| (min.inf(&a), max.sup(&b)))
}

/// The motion as a looping GIF of `width` × `height` pixels at `fps` frames per second, one GIF
/// frame per motion frame: its art under its bones (captioned with its time), or alone on a
/// transparent background. `progress(done, total)` is called after each frame.
///
/// # Errors
/// [`RenderError::Size`] for a side outside 16..=4096, [`RenderError::NoFrames`],
/// [`RenderError::NonFinite`] for a bone not finite, [`Art::check`]'s (and not one art per
/// frame: `arts`), [`RenderError::Fps`] for a rate outside (0, 100], [`RenderError::Encode`] if
/// encoding fails (or the thread's [`with_interrupt`](crate::with_interrupt) token is set).
pub fn character_art_gif(
    m: &CharacterArtMotion,
    width: u32,
    height: u32,
    fps: f64,
    progress: &dyn Fn(usize, usize),
) -> Result<Vec<u8>, RenderError> {
    let fit = m.fit(width, height)?;
    if !(fps > 0.0 && fps <= MAX_FPS) {
        return Err(RenderError::Fps { value: fps });
    }
    let total = m.motion.frames.len();
    match fit {
        Fit::Bones(view) => {
            let grid = svg_to_pixmap(&character_layers(&m.motion.frames[0], &[], view, (width, height), Layers::Grid))?;
            let rgba = |i: usize| -> Result<Vec<u8>, RenderError> {
                check_interrupt()?;
                let mut pixmap = grid.clone();
                draw_art(&m.arts[i], &WorldToPixel::of_view(&view), &mut pixmap)?;
                let bones = character_layers(&m.motion.frame(i), &[], view, (width, height), Layers::Bones);
                draw_svg_onto(&bones, &mut pixmap)?;
                Ok(pixmap.take())
            };
            let palette = learn_palette_of(total, width, &mut |i| rgba(i))?;
            encode_gif(width, height, total, palette, gif_delay(fps), &mut |i| rgba(i), progress)
        }
        Fit::Alone(map) => {
            let rgba = |i: usize| -> Result<Vec<u8>, RenderError> {
                check_interrupt()?;
                Ok(straight(art_pixmap(&m.arts[i], &map, width, height)?))
            };
            encode_transparent_gif((width, height), total, gif_delay(fps), &rgba, progress)
        }
    }
}

/// A pixmap's pixels with straight (not premultiplied) colours.
fn straight(pixmap: Pixmap) -> Vec<u8> {
    let mut rgba = pixmap.take();
    for p in rgba.chunks_exact_mut(4) {
        let a = u32::from(p[3]);
        if a > 0 && a < 255 {
            for c in &mut p[..3] {
                // Rounded; a premultiplied channel is at most its alpha.
                *c = ((u32::from(*c) * 255 + a / 2) / a).min(255) as u8;
            }
        }
    }
    rgba
}

/// Alpha from which a pixel of a transparent GIF is drawn (opaque), below which it is left
/// transparent.
const OPAQUE_FROM: u8 = 128;

/// The looping GIF of `total` whole frames of straight RGBA pixels painted by `rgba(i)`, each
/// pixel opaque from [`OPAQUE_FROM`] alpha on and transparent below, each frame cleared before
/// the next; one palette learnt from the opaque pixels of the first, middle and last frames.
fn encode_transparent_gif(
    (width, height): (u32, u32),
    total: usize,
    delay: u16,
    rgba: &dyn Fn(usize) -> Result<Vec<u8>, RenderError>,
    progress: &dyn Fn(usize, usize),
) -> Result<Vec<u8>, RenderError> {
    let mut sample = Vec::new();
    let mut sampled = vec![0, total / 2, total - 1];
    sampled.dedup();
    for &i in &sampled {
        let opaque: Vec<u8> =
            rgba(i)?.chunks_exact(4).filter(|p| p[3] >= OPAQUE_FROM).flat_map(|p| [p[0], p[1], p[2], 255]).collect();
        thin_into(&opaque, width, &mut sample);
    }
    if sample.is_empty() {
        // No opaque pixel anywhere: the quantiser still needs one to learn from.
        sample.extend([0, 0, 0, 255]);
    }
    let mut palette = Palette::learn(&sample, &[]);
    let mut bytes = Vec::new();
    {
        let encode = |e: gif::EncodingError| RenderError::Encode { format: "gif", message: e.to_string() };
        let (w16, h16) = (width as u16, height as u16);
        let mut encoder = Encoder::new(&mut bytes, w16, h16, &palette.rgb_table()).map_err(encode)?;
        encoder.set_repeat(Repeat::Infinite).map_err(encode)?;
        let mut indices = Vec::new();
        for i in 0..total {
            check_interrupt()?;
            let pixels = rgba(i)?;
            palette.map_into(&pixels, &mut indices);
            for (index, p) in indices.iter_mut().zip(pixels.chunks_exact(4)) {
                if p[3] < OPAQUE_FROM {
                    *index = UNCHANGED;
                }
            }
            let mut frame = Frame::from_indexed_pixels(w16, h16, std::mem::take(&mut indices), Some(UNCHANGED));
            frame.delay = delay;
            frame.dispose = DisposalMethod::Background;
            encoder.write_frame(&frame).map_err(encode)?;
            indices = frame.buffer.into_owned();
            progress(i + 1, total);
        }
    }
    Ok(bytes)
}

/// The motion in one picture's pixels: the last frame's art under every frame's bones (the
/// earlier as ghosts, at most [`MAX_ANIMATION_GHOSTS`](crate::MAX_ANIMATION_GHOSTS)), or the last frame's art alone.
fn still_pixmap(m: &CharacterArtMotion, width: u32, height: u32) -> Result<Pixmap, RenderError> {
    let fit = m.fit(width, height)?;
    let last = &m.arts[m.arts.len() - 1];
    match fit {
        Fit::Alone(map) => art_pixmap(last, &map, width, height),
        Fit::Bones(view) => {
            let (figure, ghosts) = m.motion.last_with_ghosts();
            let mut pixmap = svg_to_pixmap(&character_layers(&figure, &[], view, (width, height), Layers::Grid))?;
            draw_art(last, &WorldToPixel::of_view(&view), &mut pixmap)?;
            draw_svg_onto(&character_layers(&figure, &ghosts, view, (width, height), Layers::Bones), &mut pixmap)?;
            Ok(pixmap)
        }
    }
}

/// The motion in one PNG picture: the last frame's art under every frame's bones (the earlier
/// as ghosts) and the motion's caption, or the last frame's art alone, in the GIF's view.
///
/// # Errors
/// As [`character_art_gif`], without the rate.
pub fn character_art_motion_png(m: &CharacterArtMotion, width: u32, height: u32) -> Result<Vec<u8>, RenderError> {
    pixmap_png(&still_pixmap(m, width, height)?)
}

/// The motion in one SVG picture: as [`character_art_motion_png`], the art as one embedded PNG
/// `<image>`; under the bones, the grid, the ghosts, the bones (each a `<g class="bone">` with its
/// name), targets and caption stay vector.
///
/// # Errors
/// As [`character_art_motion_png`].
pub fn character_art_motion_svg(m: &CharacterArtMotion, width: u32, height: u32) -> Result<String, RenderError> {
    match (m.fit(width, height)?, m.arts.last()) {
        (Fit::Bones(view), Some(last)) => {
            let layer = art_pixmap(last, &WorldToPixel::of_view(&view), width, height)?;
            let href = png_data_url(&pixmap_png(&layer)?);
            let (figure, ghosts) = m.motion.last_with_ghosts();
            Ok(character_layers(&figure, &ghosts, view, (width, height), Layers::WithImage(&href)))
        }
        _ => {
            let href = png_data_url(&character_art_motion_png(m, width, height)?);
            let mut svg = Svg::new(width, height);
            svg.comment("art");
            svg.image(0.0, 0.0, f64::from(width), f64::from(height), &href);
            Ok(svg.finish())
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{ArtPiece, Blend, Page, PosedBone};

    fn red() -> [Page; 1] {
        [Page { width: 1, height: 1, rgba: vec![255, 0, 0, 255], pma: false }]
    }

    /// A 10 × 10 red square with its lower-left corner at `(x, 0)`.
    fn square(pages: &[Page], x: f32) -> Art<'_> {
        let piece = ArtPiece {
            page: 0,
            positions: vec![[x, 0.0], [x + 10.0, 0.0], [x + 10.0, 10.0], [x, 10.0]],
            uvs: vec![[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]],
            triangles: vec![[0, 1, 2], [0, 2, 3]],
            color: [1.0; 4],
            dark: None,
            blend: Blend::Normal,
        };
        Art { pages, pieces: vec![piece] }
    }

    /// Three frames, the square and a bone over it moving right by 10 a frame.
    fn walk(pages: &[Page], placement: ArtPlacement) -> CharacterArtMotion<'_> {
        let frame = |k: usize| {
            let x = k as f64 * 10.0;
            CharacterFigure {
                bones: vec![PosedBone { name: "b", origin: Point2::new(x, 5.0), tip: Point2::new(x + 10.0, 5.0) }],
                targets: vec![],
                caption: None,
            }
        };
        CharacterArtMotion {
            motion: CharacterMotionFigure {
                frames: (0..3).map(frame).collect(),
                times: vec![0.0, 0.1, 0.2],
                caption: Some("walk".into()),
            },
            arts: (0..3).map(|k| square(pages, k as f32 * 10.0)).collect(),
            placement,
        }
    }

    /// Every frame of a GIF composed as a viewer shows it: RGBA, whole.
    fn frames(gif: &[u8]) -> Vec<Vec<u8>> {
        let mut options = gif::DecodeOptions::new();
        options.set_color_output(gif::ColorOutput::RGBA);
        let mut decoder = options.read_info(gif).unwrap();
        let (w, h) = (usize::from(decoder.width()), usize::from(decoder.height()));
        let mut shown = vec![0u8; w * h * 4];
        let mut out = Vec::new();
        while let Some(frame) = decoder.read_next_frame().unwrap() {
            let (fw, fl, ft) = (usize::from(frame.width), usize::from(frame.left), usize::from(frame.top));
            for (k, p) in frame.buffer.chunks_exact(4).enumerate() {
                if p[3] > 0 {
                    let at = ((ft + k / fw) * w + fl + k % fw) * 4;
                    shown[at..at + 4].copy_from_slice(p);
                }
            }
            out.push(shown.clone());
            if frame.dispose == DisposalMethod::Background {
                shown.fill(0);
            }
        }
        out
    }

    fn reds(rgba: &[u8]) -> Vec<usize> {
        rgba.chunks_exact(4)
            .enumerate()
            .filter(|(_, p)| p[0] > 200 && p[1] < 60 && p[2] < 60 && p[3] == 255)
            .map(|(i, _)| i)
            .collect()
    }

    #[test]
    fn alone_the_frames_share_one_fit_on_a_transparent_background() {
        let pages = red();
        let gif = character_art_gif(&walk(&pages, ArtPlacement::Alone), 100, 100, 10.0, &|_, _| {}).unwrap();
        let shown = frames(&gif);
        assert_eq!(shown.len(), 3);
        // The motion's art spans x 0..30, y 0..10: 3 px a unit (90 px across), from x = 5 to 95,
        // y = 35 to 65. Frame k's square is the k-th 30 px of it, the rest transparent.
        for (k, rgba) in shown.iter().enumerate() {
            let red = reds(rgba);
            assert_eq!(red.len(), 30 * 30, "frame {k}");
            let (first, last) = (red[0], red[red.len() - 1]);
            assert_eq!((first % 100, first / 100), (5 + 30 * k, 35), "frame {k}");
            assert_eq!((last % 100, last / 100), (34 + 30 * k, 64), "frame {k}");
            let clear = rgba.chunks_exact(4).filter(|p| p[3] == 0).count();
            assert_eq!(clear, 100 * 100 - 30 * 30, "frame {k}");
        }
    }

    #[test]
    fn under_the_bones_each_frame_draws_its_art_in_one_view() {
        let pages = red();
        let m = walk(&pages, ArtPlacement::UnderBones);
        let gif = character_art_gif(&m, 160, 120, 10.0, &|_, _| {}).unwrap();
        let shown = frames(&gif);
        assert_eq!(shown.len(), 3);
        let view = match m.fit(160, 120).unwrap() {
            Fit::Bones(view) => view,
            Fit::Alone(_) => unreachable!(),
        };
        // Frame k's art covers the middle of its square, not the middle of the others; the
        // background is opaque.
        for (k, rgba) in shown.iter().enumerate() {
            assert!(rgba.chunks_exact(4).all(|p| p[3] == 255), "frame {k}");
            for j in 0..3 {
                let (x, y) = view.world_to_pixel(Point2::new(j as f64 * 10.0 + 5.0, 2.0));
                let p = &rgba[((y as usize) * 160 + x as usize) * 4..][..4];
                let red = p[0] > 200 && p[1] < 60 && p[2] < 60;
                assert_eq!(red, j == k, "frame {k}, square {j}: {p:?}");
            }
        }
    }

    #[test]
    fn the_one_picture_is_the_last_art_under_the_ghosts() {
        let pages = red();
        let svg = character_art_motion_svg(&walk(&pages, ArtPlacement::UnderBones), 160, 120).unwrap();
        assert_eq!(svg.matches("<g class=\"bone\">").count(), 1);
        assert!(svg.contains("<image") && svg.contains("walk"), "{svg}");
        let png = character_art_motion_png(&walk(&pages, ArtPlacement::Alone), 100, 100).unwrap();
        let page = Page::decode_png(&png, "still.png", false).unwrap();
        // The last square, x 20..30 of the motion's 0..30: pixels 65 to 94 across.
        let red = reds(&page.rgba);
        assert_eq!(red.len(), 30 * 30);
        assert_eq!(red[0] % 100, 65);
    }

    #[test]
    fn one_art_per_frame_and_a_rate_are_asked_for() {
        let pages = red();
        let mut m = walk(&pages, ArtPlacement::Alone);
        m.arts.pop();
        let e = character_art_gif(&m, 100, 100, 10.0, &|_, _| {}).unwrap_err();
        assert_eq!(e.to_string(), "arts: expected one per frame (3), got 2");
        let m = walk(&pages, ArtPlacement::Alone);
        assert!(matches!(character_art_gif(&m, 100, 100, 0.0, &|_, _| {}), Err(RenderError::Fps { .. })));
        assert!(matches!(
            character_art_gif(&CharacterArtMotion::default(), 100, 100, 10.0, &|_, _| {}),
            Err(RenderError::NoFrames)
        ));
    }
}
