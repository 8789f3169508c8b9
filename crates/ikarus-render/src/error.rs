//! The one error type of the crate.

use ikarus::Point2;
use ikarus::number::Num;
use thiserror::Error;

/// Why a picture could not be made. Every message is one line and names the field and the
/// offending value.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum RenderError {
    /// A picture side is outside [`MIN_SIDE`](crate::MIN_SIDE)`..=`[`MAX_SIDE`](crate::MAX_SIDE)
    /// pixels.
    #[error("{field}: must be between 16 and 4096 pixels, got {value}")]
    Size {
        /// `"width"` or `"height"`.
        field: &'static str,
        /// The offending size.
        value: u64,
    },
    /// The frame rate is not a number in (0, 100].
    #[error("fps: must be a number in (0, 100], got {}", Num(*.value))]
    Fps {
        /// The offending frame rate.
        value: f64,
    },
    /// A coordinate or an angle is NaN or infinite.
    #[error("{field}: must be a finite number, got {}", Num(*.value))]
    NonFinite {
        /// Which number, e.g. `goal.x`, `pose[2]`, `animation.frames[4].angles[1]`.
        field: String,
        /// The offending value.
        value: f64,
    },
    /// A pose has a different number of angles (or a frame a different number of joint
    /// positions) than the chain needs.
    #[error("{field}: expected {expected} values for this arm or skeleton, got {got}")]
    Length {
        /// Which list, e.g. `pose`, `ghosts[3]`, `animation.frames[0].joints`.
        field: String,
        /// How many the arm or skeleton needs.
        expected: usize,
        /// How many were given.
        got: usize,
    },
    /// A goal or pin names a bone the skeleton does not have.
    #[error("{field}: no bone {index} in a skeleton of {bones} bones")]
    UnknownBone {
        /// Which entry, e.g. `goals[1].bone`, `pins[0]`.
        field: String,
        /// The offending bone index.
        index: usize,
        /// How many bones the skeleton has.
        bones: usize,
    },
    /// An animation without frames.
    #[error("animation.frames: an animation needs at least one frame, got none")]
    NoFrames,
    /// A character's art cannot be drawn as given (a page of the wrong size, a piece naming a
    /// page or a vertex that does not exist).
    #[error("{field}: {problem}")]
    Art {
        /// Which field, e.g. `pieces[3].triangles[7]`.
        field: String,
        /// What is wrong with it, with the offending value.
        problem: String,
    },
    /// An image file (an atlas page) cannot be decoded.
    #[error("{file}: {message}")]
    Image {
        /// The file's name as the caller gave it.
        file: String,
        /// What is wrong, e.g. `not a PNG image: …`.
        message: String,
    },
    /// The SVG text could not be parsed.
    #[error("svg: cannot be parsed: {0}")]
    Svg(String),
    /// PNG or GIF encoding failed.
    #[error("{format}: encoding failed: {message}")]
    Encode {
        /// `"png"` or `"gif"`.
        format: &'static str,
        /// What the encoder said.
        message: String,
    },
}

/// `Ok` if every value is finite, else the first that is not, named `field[i]`.
pub(crate) fn check_finite(values: impl Iterator<Item = f64>, field: &str) -> Result<(), RenderError> {
    for (i, v) in values.enumerate() {
        if !v.is_finite() {
            return Err(RenderError::NonFinite { field: format!("{field}[{i}]"), value: v });
        }
    }
    Ok(())
}

/// `Ok` if the point (when given) is finite, else the bad coordinate, named `field.x` or `field.y`.
pub(crate) fn check_point(p: Option<Point2<f64>>, field: &str) -> Result<(), RenderError> {
    if let Some(p) = p {
        for (axis, v) in [("x", p.x), ("y", p.y)] {
            if !v.is_finite() {
                return Err(RenderError::NonFinite { field: format!("{field}.{axis}"), value: v });
            }
        }
    }
    Ok(())
}
