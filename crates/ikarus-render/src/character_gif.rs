//! A character's motion in pictures: its frames overlaid (the earlier ones as faded ghosts,
//! the last solid) and as a looping GIF, one GIF frame per motion frame. Both keep one view
//! fitting every frame's bones and targets, so the picture does not jump; each frame is drawn
//! as [`character_svg`](crate::character_svg) draws a pose, and the GIF is encoded as the
//! skeleton's ([`crate::skeleton_gif`]).

use ikarus::Point2;

use crate::RenderError;
use crate::animation::{MAX_FPS, check_interrupt, encode_gif, gif_delay, learn_palette_of};
use crate::arm::MAX_ANIMATION_GHOSTS;
use crate::character::{CharacterFigure, character_svg_in};
use crate::raster::{check_size, svg_to_pixmap};
use crate::view::View;

/// A character's motion: its frames, each posed at its time (seconds), and a caption.
#[derive(Debug, Clone, Default)]
pub struct CharacterMotionFigure<'a> {
    /// Every frame's pose (the figure's own caption is not drawn).
    pub frames: Vec<CharacterFigure<'a>>,
    /// Every frame's time, as many as `frames`.
    pub times: Vec<f64>,
    /// A line of text under the plot.
    pub caption: Option<String>,
}

impl CharacterMotionFigure<'_> {
    fn check(&self, width: u32, height: u32) -> Result<View, RenderError> {
        check_size(width, height)?;
        if self.frames.is_empty() {
            return Err(RenderError::NoFrames);
        }
        for f in &self.frames {
            f.check()?;
        }
        let mut boxes = self.frames.iter().map(CharacterFigure::extent);
        let first = boxes.next().unwrap_or((Point2::origin(), Point2::origin()));
        let (min, max) = boxes.fold(first, |(min, max), (a, b)| (min.inf(&a), max.sup(&b)));
        Ok(View::fitting(min, max, width, height))
    }

    /// The last frame with the motion's caption, and every k-th earlier frame (at most
    /// [`MAX_ANIMATION_GHOSTS`], the first always among them) to draw faded under it; the
    /// motion has frames (checked by the caller).
    pub(crate) fn last_with_ghosts(&self) -> (CharacterFigure<'_>, Vec<&CharacterFigure<'_>>) {
        let n = self.frames.len();
        let every = (n - 1).div_ceil(MAX_ANIMATION_GHOSTS).max(1);
        let ghosts = self.frames[..n - 1].iter().step_by(every).collect();
        (CharacterFigure { caption: self.caption.clone(), ..self.frames[n - 1].clone() }, ghosts)
    }

    /// Frame `i` with its caption: the motion's, then the frame's time (`t = 0.50`).
    pub(crate) fn frame(&self, i: usize) -> CharacterFigure<'_> {
        let clock = format!("t = {:.2}", self.times.get(i).copied().unwrap_or_default());
        let caption = match &self.caption {
            Some(c) => format!("{c} · {clock}"),
            None => clock,
        };
        CharacterFigure { caption: Some(caption), ..self.frames[i].clone() }
    }
}

/// The motion in one picture of `width` × `height` pixels: the last frame solid with its
/// targets and the motion's caption, every k-th earlier frame (at most
/// [`MAX_ANIMATION_GHOSTS`], the first always among them) faded under it.
///
/// # Errors
/// [`RenderError::Size`] for a side outside 16..=4096, [`RenderError::NoFrames`],
/// [`RenderError::NonFinite`] for a point that is not finite.
pub fn character_motion_svg(motion: &CharacterMotionFigure, width: u32, height: u32) -> Result<String, RenderError> {
    let view = motion.check(width, height)?;
    let (last, ghosts) = motion.last_with_ghosts();
    Ok(character_svg_in(&last, &ghosts, view, width, height))
}

/// The motion as a looping GIF of `width` × `height` pixels at `fps` frames per second, one
/// GIF frame per motion frame, each captioned with its time. `progress(done, total)` is called
/// after each frame.
///
/// # Errors
/// As [`character_motion_svg`], [`RenderError::Fps`] for a rate outside (0, 100], and
/// [`RenderError::Encode`] if encoding fails (or the thread's
/// [`with_interrupt`](crate::with_interrupt) token is set).
pub fn character_gif(
    motion: &CharacterMotionFigure,
    width: u32,
    height: u32,
    fps: f64,
    progress: &dyn Fn(usize, usize),
) -> Result<Vec<u8>, RenderError> {
    let view = motion.check(width, height)?;
    if !(fps > 0.0 && fps <= MAX_FPS) {
        return Err(RenderError::Fps { value: fps });
    }
    let total = motion.frames.len();
    let rgba = |i: usize| -> Result<Vec<u8>, RenderError> {
        check_interrupt()?;
        Ok(svg_to_pixmap(&character_svg_in(&motion.frame(i), &[], view, width, height))?.take())
    };
    let palette = learn_palette_of(total, width, &mut |i| rgba(i))?;
    encode_gif(width, height, total, palette, gif_delay(fps), &mut |i| rgba(i), progress)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::PosedBone;

    /// A leg whose foot swings from x = 0 to x = `n - 1` × 20 over `n` frames.
    fn swing<'a>(n: usize) -> CharacterMotionFigure<'a> {
        let frame = |k: usize| {
            let x = k as f64 * 20.0;
            CharacterFigure {
                bones: vec![
                    PosedBone { name: "thigh", origin: Point2::new(0.0, 100.0), tip: Point2::new(x / 2.0, 50.0) },
                    PosedBone { name: "shin", origin: Point2::new(x / 2.0, 50.0), tip: Point2::new(x, 0.0) },
                ],
                targets: vec![Point2::new(x, 0.0)],
                caption: None,
            }
        };
        CharacterMotionFigure {
            frames: (0..n).map(frame).collect(),
            times: (0..n).map(|k| k as f64 / 10.0).collect(),
            caption: Some("leg".into()),
        }
    }

    #[test]
    fn the_picture_has_the_last_frame_solid_and_the_earlier_ones_as_ghosts() {
        let svg = character_motion_svg(&swing(5), 300, 300).unwrap();
        assert_eq!(svg.matches("<g class=\"bone\">").count(), 2);
        assert_eq!(svg.matches("fill-opacity=\"0.12\"").count(), 4 * 2);
        assert!(svg.contains("leg"), "{svg}");
        let many = character_motion_svg(&swing(200), 300, 300).unwrap();
        assert!(many.matches("fill-opacity=\"0.12\"").count() <= MAX_ANIMATION_GHOSTS * 2);
    }

    #[test]
    fn a_gif_has_one_frame_per_motion_frame_in_one_view() {
        let gif = character_gif(&swing(6), 120, 100, 25.0, &|_, _| {}).unwrap();
        let mut decoder = gif::DecodeOptions::new().read_info(gif.as_slice()).unwrap();
        assert_eq!((decoder.width(), decoder.height()), (120, 100));
        let mut frames = 0;
        while let Some(frame) = decoder.read_next_frame().unwrap() {
            frames += 1;
            assert_eq!(frame.delay, 4);
        }
        assert_eq!(frames, 6);
    }

    #[test]
    fn no_frames_bad_sizes_rates_and_points_are_errors() {
        let empty = CharacterMotionFigure::default();
        assert!(matches!(character_gif(&empty, 100, 100, 25.0, &|_, _| {}), Err(RenderError::NoFrames)));
        assert!(matches!(character_motion_svg(&swing(2), 8, 100), Err(RenderError::Size { .. })));
        assert!(matches!(character_gif(&swing(2), 100, 100, 0.0, &|_, _| {}), Err(RenderError::Fps { .. })));
        let mut bad = swing(3);
        bad.frames[1].bones[0].tip.x = f64::NAN;
        let e = character_motion_svg(&bad, 100, 100).unwrap_err();
        assert!(e.to_string().contains("bones[0].tip.x"), "{e}");
    }
}
