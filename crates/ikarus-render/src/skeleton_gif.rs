//! A skeleton's animation as a looping GIF: the figure of [`skeleton_svg`] at every frame's
//! pose, encoded as the arm's animations are (one palette learnt from the first, middle and
//! last frames; each later frame stored as the rectangle that changed).

use ikarus::motion::Animation;

use crate::RenderError;
use crate::animation::{MAX_FPS, check_interrupt, encode_gif, gif_delay, learn_palette_of};
use crate::raster::{check_size, svg_to_pixmap};
use crate::skeleton::{SkeletonFigure, skeleton_svg};

/// `animation` of `figure`'s skeleton as a looping GIF of `width` × `height` pixels at `fps`
/// frames per second, one GIF frame per animation frame: each is `figure` (its goals, pins,
/// ranges and names) with the frame's angles as the pose, and its caption followed by the
/// frame's time (`t = 0.50`). The view is the same for every frame, so the picture does not
/// jump: fitted to the bones at every frame's pose and the goals ([`SkeletonFigure::extent`]),
/// unless `figure.fit` gives it. `figure.pose` is not drawn. `progress(done, total)` is called
/// after each frame.
///
/// # Errors
/// [`RenderError::Size`] for a side outside 16..=4096, [`RenderError::Fps`] for a rate outside
/// (0, 100], [`RenderError::NoFrames`], the errors of [`skeleton_svg`] for a frame whose
/// angles do not fit the skeleton, [`RenderError::Encode`] if encoding fails (or the thread's
/// [`with_interrupt`](crate::with_interrupt) token is set).
pub fn skeleton_gif(
    figure: &SkeletonFigure,
    animation: &Animation,
    width: u32,
    height: u32,
    fps: f64,
    progress: &dyn Fn(usize, usize),
) -> Result<Vec<u8>, RenderError> {
    check_size(width, height)?;
    if !(fps > 0.0 && fps <= MAX_FPS) {
        return Err(RenderError::Fps { value: fps });
    }
    let total = animation.frames.len();
    if total == 0 {
        return Err(RenderError::NoFrames);
    }
    let fit = figure.fit.or_else(|| Some(figure.extent(animation.frames.iter().map(|f| f.angles.as_slice()))));
    let rgba = |i: usize| -> Result<Vec<u8>, RenderError> {
        check_interrupt()?;
        let frame = &animation.frames[i];
        let clock = format!("t = {:.2}", frame.time);
        let caption = match &figure.caption {
            Some(c) => format!("{c} · {clock}"),
            None => clock,
        };
        let at = SkeletonFigure { pose: &frame.angles, caption: Some(caption), fit, ..figure.clone() };
        Ok(svg_to_pixmap(&skeleton_svg(&at, width, height)?)?.take())
    };
    let palette = learn_palette_of(total, width, &mut |i| rgba(i))?;
    encode_gif(width, height, total, palette, gif_delay(fps), &mut |i| rgba(i), progress)
}

#[cfg(test)]
mod tests {
    use super::*;
    use ikarus::motion::{Timing, animate};
    use ikarus::{Bone, Ease, Interrupt, Point2, Skeleton};

    use crate::BoneGoal;

    fn fork() -> Skeleton {
        Skeleton::new(
            [0.0, 0.0],
            &[
                Bone::new("trunk", 1.0, 1.5),
                Bone::new("left", 0.8, 0.9).with_parent("trunk"),
                Bone::new("right", 0.8, -0.9).with_parent("trunk"),
            ],
        )
        .unwrap()
    }

    #[test]
    fn a_skeleton_gif_has_one_frame_per_pose_and_the_pose_moves() {
        let s = fork();
        let keys = [s.start_angles().to_vec(), vec![1.5, 1.8, -0.2]];
        let animation = animate(&s, &keys, None, Timing::Frames(6), Ease::Sine).unwrap();
        let figure = SkeletonFigure {
            goals: vec![BoneGoal::at(1, Point2::new(-0.9, 1.2))],
            pins: vec![2],
            caption: Some("fork".into()),
            ..SkeletonFigure::new(&s, s.start_angles())
        };
        let gif = skeleton_gif(&figure, &animation, 120, 100, 25.0, &|_, _| {}).unwrap();
        let mut decoder = gif::DecodeOptions::new().read_info(gif.as_slice()).unwrap();
        assert_eq!((decoder.width(), decoder.height()), (120, 100));
        let mut frames = 0;
        let mut changed = 0;
        while let Some(frame) = decoder.read_next_frame().unwrap() {
            frames += 1;
            if frames > 1 && frame.width * frame.height > 1 {
                changed += 1;
            }
            assert_eq!(frame.delay, 4);
        }
        assert_eq!(frames, 6);
        assert!(changed >= 4, "the bones move between frames: {changed} frames changed");
    }

    #[test]
    fn bad_frames_sizes_and_rates_are_errors() {
        let s = fork();
        let figure = SkeletonFigure::new(&s, s.start_angles());
        let keys = [vec![0.1, 0.2]];
        let still = animate(&fork(), &[s.start_angles().to_vec()], None, Timing::Frames(2), Ease::Sine).unwrap();
        assert!(matches!(skeleton_gif(&figure, &still, 8, 100, 25.0, &|_, _| {}), Err(RenderError::Size { .. })));
        assert!(matches!(skeleton_gif(&figure, &still, 100, 100, 0.0, &|_, _| {}), Err(RenderError::Fps { .. })));
        let mut short = still.clone();
        short.frames[1].angles = keys[0].clone();
        let e = skeleton_gif(&figure, &short, 100, 100, 25.0, &|_, _| {}).unwrap_err();
        assert!(matches!(e, RenderError::Length { .. }), "{e:?}");
        short.frames.clear();
        assert!(matches!(skeleton_gif(&figure, &short, 100, 100, 25.0, &|_, _| {}), Err(RenderError::NoFrames)));
        let token = Interrupt::new();
        token.interrupt();
        let e = crate::with_interrupt(&token, || skeleton_gif(&figure, &still, 100, 100, 25.0, &|_, _| {}));
        assert!(matches!(e, Err(RenderError::Encode { .. })));
    }
}
