//! [`Timing`]: how many frames an animation has and when they fall (see the [module
//! docs](super)).

use super::MotionError;

/// The largest number of frames an animation may have.
pub const MAX_FRAMES: usize = 100_000;

/// How many frames an animation has and when they fall.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Timing {
    /// `n ≥ 2` frames in normalised time: frame `i` at `t = i / (n − 1)`, duration 1.
    Frames(usize),
    /// `seconds` at `fps` frames per second: `n = round(seconds·fps) + 1` frames, frame `i` at
    /// `t = i / fps` seconds except the last, which is at exactly `seconds` (so the last interval
    /// lies between `0.5 / fps` and `1.5 / fps`). Both must be finite and > 0, and
    /// `seconds·fps ≥ 0.5` so that there are at least two frames.
    Duration {
        /// Length of the animation in seconds.
        seconds: f64,
        /// Frames per second.
        fps: f64,
    },
}

impl Timing {
    /// The number of frames, after checking the parameters (see the variants) and that there are
    /// at most [`MAX_FRAMES`].
    pub fn frame_count(&self) -> Result<usize, MotionError> {
        match *self {
            Timing::Frames(n) => {
                if n < 2 {
                    return Err(MotionError::FrameCount { value: n });
                }
                if n > MAX_FRAMES {
                    // Lossy above 2⁵³ frames, which is only ever a typo.
                    return Err(MotionError::TooManyFrames { field: "frames", frames: n as f64 });
                }
                Ok(n)
            }
            Timing::Duration { seconds, fps } => {
                if !(seconds.is_finite() && seconds > 0.0) {
                    return Err(MotionError::Seconds { value: seconds });
                }
                if !(fps.is_finite() && fps > 0.0) {
                    return Err(MotionError::Fps { value: fps });
                }
                let frames = (seconds * fps).round() + 1.0;
                // Never NaN (both factors are finite and positive); an infinite product is caught here.
                if frames > MAX_FRAMES as f64 {
                    return Err(MotionError::TooManyFrames { field: "seconds × fps", frames });
                }
                if frames < 2.0 {
                    return Err(MotionError::TooFewFrames { seconds, fps });
                }
                // An integer in [2, MAX_FRAMES]: the cast is exact.
                Ok(frames as usize)
            }
        }
    }

    /// The duration `T`: 1 for [`Timing::Frames`] (normalised time), `seconds` for
    /// [`Timing::Duration`]. Not validated; see [`Timing::frame_count`].
    #[must_use]
    pub fn duration(&self) -> f64 {
        match *self {
            Timing::Frames(_) => 1.0,
            Timing::Duration { seconds, .. } => seconds,
        }
    }

    /// Time of frame `i` of `n` (see the variants).
    pub(super) fn time(&self, i: usize, n: usize) -> f64 {
        match *self {
            Timing::Frames(_) => i as f64 / (n - 1) as f64,
            Timing::Duration { seconds, .. } if i + 1 == n => seconds,
            Timing::Duration { fps, .. } => i as f64 / fps,
        }
    }
}
