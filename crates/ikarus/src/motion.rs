//! Keyframe motion in joint space, re-timed by an ease curve.
//!
//! [`animate`] turns keyframe poses into frames evenly spaced in time; [`animate_solve`] does the
//! same with the frames a solver recorded; [`through_goals`] solves for goals in order and
//! animates the poses it found. Interpolation happens in joint space, as in the seed
//! program, so the links sweep natural arcs (interpolating joint *positions* instead would cut
//! corners and stretch the links). By default every angle follows a monotone cubic spline
//! through the keyframes ([`Interpolation::Spline`]: velocity continuous at every keyframe, never
//! past a keyframe value, so never past a limit); [`Interpolation::Linear`] moves every angle
//! linearly between keyframes, along the polyline described below. Both share the unwrapping,
//! the knots `C_k` and the timing; the options travel together in [`MotionOptions`].
//!
//! # The path
//!
//! Keyframes `q₀ … q_{K−1}` are poses, one angle per joint. First they are **unwrapped**: an
//! angle of a joint without limits is moved by a whole number of turns so that it continues the
//! previous (unwrapped) keyframe the short way round,
//!
//! ```text
//! q_k,i ← q_k,i − 2π·m,   m = ⌈(q_k,i − q_{k−1},i − π) / 2π⌉,   so   q_k,i − q_{k−1},i ∈ (−π, π]
//! ```
//!
//! (an exact half turn goes counter-clockwise; an angle that needs no turn keeps its bits; all of
//! this up to rounding, which swamps a turn only for angles beyond about 10¹⁵ rad).
//! A joint with limits is used as given: its range is an interval, and a straight line between
//! two angles inside it never leaves it, so it takes the long way round when the short way would
//! cross a limit, and never wraps.
//!
//! The path is the polyline through the unwrapped keyframes, with segment lengths, cumulative
//! lengths and total length
//!
//! ```text
//! l_k = ‖q_{k+1} − q_k‖₂,   C₀ = 0,   C_{k+1} = C_k + l_k,   L = C_{K−1}   (radians).
//! ```
//!
//! # Timing
//!
//! [`Timing`] gives the frame count `n` and frame times `t_i` over a duration `T`; the normalised
//! time of frame `i` is `u_i = t_i / T` and the ease maps it to progress `e(u_i) ∈ [0, 1]`.
//!
//! * **Arc length** (no explicit times): the frame is the point of the path at arc length
//!   `s_i = e(u_i)·L`: with `C_k ≤ s_i < C_{k+1}` and `w = (s_i − C_k) / l_k`, the pose is
//!   `q_k + w·(q_{k+1} − q_k)`. Zero-length segments are skipped, and a path of length 0 gives a
//!   still animation. The pose moves along the path at joint-space speed
//!   `ds/dt = L·e′(u)/T`, which is as continuous as the ease's velocity *at every keyframe too*,
//!   because the ease is applied once to the whole path. (The seed program applied it per
//!   segment, with times that ignored each segment's length, so the speed dropped or jumped at
//!   every keyframe: its "spastic" four-keyframe motion.)
//! * **Explicit times** `τ₀ = 0 < τ₁ < … < τ_{K−1} = T`: the eased time `τ = e(u_i)·T` is
//!   interpolated piecewise linearly, keyframe `k` being reached at `τ = τ_k`. The speed on
//!   segment `k` is `l_k / (τ_{k+1} − τ_k)` times the ease's velocity, so it jumps at a keyframe
//!   unless the times are proportional to the segment lengths: continuity is the caller's
//!   business.
//!
//! # Guarantees
//!
//! * Exactly `n` frames; the first at time 0, the last at exactly `T`.
//! * The first frame's angles are `keyframes[0]`, bit for bit. The last frame's angles are the
//!   last unwrapped keyframe: exactly the last keyframe for joints with limits and for joints that
//!   needed no unwrapping, otherwise a whole number of turns away from it — the same pose, with
//!   the same joint positions up to rounding.
//! * Every angle of every frame lies between the two keyframe angles it interpolates, so a joint
//!   with limits stays inside them. Between two keyframes a joint without limits moves steadily
//!   one way by at most π, so frames never jump by a turn (unless they are so sparse that one
//!   frame step passes several keyframes).
//! * With [`Interpolation::Spline`] the same holds for every frame (see its docs for why); the
//!   spline is at keyframe `k` at the moment the polyline is, and it has no corners.
//! * The polyline has corners at the keyframes. A frame step across a corner where the path turns by
//!   an angle θ is a chord, shorter than the path it stands for: at least `cos(θ/2)` times its
//!   length when it spans a single corner. The ease controls the speed along the path.
//!
//! # Files
//!
//! This file holds the animation types, the errors and the entry points that check their
//! input and lay frames along the path; `timing.rs` holds [`Timing`] (frame counts and times),
//! `options.rs` [`Interpolation`] and [`MotionOptions`], `path.rs` the polyline (unwrapping,
//! lengths, the pose at a point of it), `spline.rs` the spline through the same keyframes, and
//! `through.rs` [`through_goals`].

use crate::number::Num;
use nalgebra::Point2;
use thiserror::Error;

#[cfg(test)]
use crate::chain::Chain; // the tests below name it through `super::*`
use crate::ease::Ease;
use crate::solve::Frames;

mod body;
mod keys;
mod options;
mod path;
mod skeleton;
mod spline;
mod through;
mod timing;

pub use body::Body;
pub use keys::{KeyTrack, KeyTrackError};
pub use options::{Interpolation, MotionOptions};
use path::Path;
pub use skeleton::{RigMotion, RigSolveOutcome, through_rig_tasks};
use spline::Spline;
pub use through::{GoalMotion, GoalMotionError, GoalOutcome, Route, through_goals};
pub use timing::{MAX_FRAMES, Timing};

/// One frame of an [`Animation`].
#[derive(Debug, Clone, PartialEq)]
pub struct AnimationFrame {
    /// When the frame is shown: normalised time in [0, 1] for [`Timing::Frames`], seconds for
    /// [`Timing::Duration`].
    pub time: f64,
    /// Joint angles, radians, base to tip (a skeleton's: one per bone, in its order).
    pub angles: Vec<f64>,
    /// Points by forward kinematics of `angles`, `N + 1` of them ([`Body::frame_points`]): a
    /// chain's joint positions, base first, tip last; a skeleton's base, then every bone's tip
    /// in the skeleton's order.
    pub joints: Vec<Point2<f64>>,
}

/// Timed frames of a motion, from [`animate`] or [`animate_solve`].
#[derive(Debug, Clone, PartialEq)]
pub struct Animation {
    /// The frames in time order; the first at time 0, the last at `duration`.
    pub frames: Vec<AnimationFrame>,
    /// The time of the last frame: 1 for [`Timing::Frames`], the seconds for
    /// [`Timing::Duration`].
    pub duration: f64,
    /// The ease the frames were timed with.
    pub ease: Ease,
}

/// Why an animation could not be made. Every variant names the field and the offending value.
///
/// `field` is `"keyframes"` for [`animate`] and `"frames"` (the recorded frames) for
/// [`animate_solve`].
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum MotionError {
    /// No keyframe was given.
    #[error("keyframes: need at least one keyframe, got none")]
    NoKeyframes,
    /// The solve recorded no frames.
    #[error("frames: the solve recorded no frames (record_every was not set)")]
    NoRecordedFrames,
    /// A pose has a different number of angles than the chain has joints.
    #[error("{field}[{index}]: expected {expected} angles (one per joint), got {got}")]
    AngleCount {
        /// `"keyframes"` or `"frames"`.
        field: &'static str,
        /// Index of the pose, from 0.
        index: usize,
        /// Joints in the chain.
        expected: usize,
        /// Angles given.
        got: usize,
    },
    /// An angle is NaN or infinite.
    #[error("{field}[{index}][{joint}]: must be a finite number, got {}", Num(*.value))]
    NonFiniteAngle {
        /// `"keyframes"` or `"frames"`.
        field: &'static str,
        /// Index of the pose, from 0.
        index: usize,
        /// Index of the joint, from 0.
        joint: usize,
        /// The offending value.
        value: f64,
    },
    /// A keyframe angle lies outside its joint's limits.
    #[error("keyframes[{index}][{joint}]: {} rad lies outside the limits [{}, {}] rad", Num(*.value), Num(*.min), Num(*.max))]
    OutsideLimits {
        /// Index of the keyframe, from 0.
        index: usize,
        /// Index of the joint, from 0.
        joint: usize,
        /// The offending angle, radians.
        value: f64,
        /// Lower limit, radians.
        min: f64,
        /// Upper limit, radians.
        max: f64,
    },
    /// The joint-space path up to this pose is too long to represent (angles near `f64::MAX`).
    #[error("{field}[{index}]: the joint-space path up to this pose is too long to represent, got {} rad", Num(*.length))]
    PathTooLong {
        /// `"keyframes"` or `"frames"`.
        field: &'static str,
        /// Index of the pose, from 0.
        index: usize,
        /// The path length up to it.
        length: f64,
    },
    /// There is not one time per keyframe.
    #[error("times: expected {expected} values (one per keyframe), got {got}")]
    TimesLength {
        /// Keyframes given.
        expected: usize,
        /// Times given.
        got: usize,
    },
    /// A time is NaN or infinite.
    #[error("times[{index}]: must be a finite number, got {}", Num(*.value))]
    NonFiniteTime {
        /// Index of the time, from 0.
        index: usize,
        /// The offending value.
        value: f64,
    },
    /// The first time is not 0.
    #[error("times[0]: must be 0, got {}", Num(*.value))]
    FirstTime {
        /// The offending value.
        value: f64,
    },
    /// A time is not greater than the one before it.
    #[error("times[{index}]: must be greater than times[{}] = {}, got {}", index - 1, Num(*.previous), Num(*.value))]
    TimesNotIncreasing {
        /// Index of the time, from 1.
        index: usize,
        /// The offending value.
        value: f64,
        /// The time before it.
        previous: f64,
    },
    /// The last time is not the animation's duration.
    #[error("times[{index}]: the last time must equal the duration, {}, got {}", Num(*.duration), Num(*.value))]
    LastTime {
        /// Index of the last time.
        index: usize,
        /// The offending value.
        value: f64,
        /// The duration ([`Timing::duration`]).
        duration: f64,
    },
    /// [`Timing::Frames`] with fewer than 2 frames.
    #[error("frames: must be at least 2, got {value}")]
    FrameCount {
        /// The offending value.
        value: usize,
    },
    /// [`Timing::Duration`] with seconds not finite and > 0.
    #[error("seconds: must be a finite number greater than 0, got {}", Num(*.value))]
    Seconds {
        /// The offending value.
        value: f64,
    },
    /// [`Timing::Duration`] with fps not finite and > 0.
    #[error("fps: must be a finite number greater than 0, got {}", Num(*.value))]
    Fps {
        /// The offending value.
        value: f64,
    },
    /// [`Timing::Duration`] so short that it gives a single frame (`seconds·fps < 0.5`).
    #[error("seconds: {} s at {} fps gives a single frame; seconds × fps must be at least 0.5", Num(*.seconds), Num(*.fps))]
    TooFewFrames {
        /// The seconds given.
        seconds: f64,
        /// The fps given.
        fps: f64,
    },
    /// More than [`MAX_FRAMES`] frames.
    #[error("{field}: gives {} frames, more than the maximum of {MAX_FRAMES}", Num(*.frames))]
    TooManyFrames {
        /// `"frames"` or `"seconds × fps"`.
        field: &'static str,
        /// The number of frames asked for (as a float: it may be infinite).
        frames: f64,
    },
}

/// Interpolates `keyframes` in joint space into the frames of `timing`, eased by `ease`.
///
/// See the [module docs](self) for the path, the unwrapping of joints without limits, the two
/// timings and the guarantees. Without `times`, time is shared out by joint-space arc length and
/// the speed is continuous at every keyframe. With `times` (one per keyframe, in the unit of
/// [`Timing::duration`]: normalised for [`Timing::Frames`], seconds for [`Timing::Duration`]),
/// keyframe `k` is reached at eased time `times[k]`; they must be finite, start at 0, increase
/// strictly and end at exactly the duration.
///
/// One keyframe gives a still animation. Checks, in order: the timing; at least one keyframe;
/// for each keyframe one finite angle per joint, within that joint's limits; the path length;
/// the times.
///
/// ```
/// use ikarus::motion::{Timing, animate};
/// use ikarus::{Chain, Ease, Link};
///
/// let chain = Chain::new([0.0, 0.0], &[Link::new(3.0, 0.0), Link::new(2.0, 0.0), Link::new(1.0, 0.0)])?;
/// let keyframes = vec![vec![0.0, 0.0, 0.0], vec![0.8, 0.6, -0.4], vec![1.2, 1.6, 0.2]];
/// let timing = Timing::Duration { seconds: 2.0, fps: 30.0 };
/// let animation = animate(&chain, &keyframes, None, timing, Ease::Sine)?;
///
/// assert_eq!(animation.frames.len(), 61);
/// let last = &animation.frames[60];
/// assert_eq!((last.time, last.angles.as_slice()), (2.0, &keyframes[2][..]));
/// assert_eq!(last.joints.len(), 4); // base, two elbows, tip
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn animate<B: Body + ?Sized>(
    body: &B,
    keyframes: &[Vec<f64>],
    times: Option<&[f64]>,
    timing: Timing,
    ease: Ease,
) -> Result<Animation, MotionError> {
    animate_with(body, keyframes, times, MotionOptions::new(timing, ease))
}

/// [`animate`] with every option: the timing, the ease and the [`Interpolation`].
///
/// [`Interpolation::Linear`] gives the polyline of the [module docs](self), bit for bit as
/// before the spline existed; [`Interpolation::Spline`] (what [`animate`] uses) the monotone
/// cubic spline through the same unwrapped keyframes, timed the same way.
///
/// ```
/// use ikarus::motion::{Interpolation, MotionOptions, Timing, animate_with};
/// use ikarus::{Chain, Ease, Link};
///
/// let chain = Chain::new([0.0, 0.0], &[Link::new(3.0, 0.0), Link::new(2.0, 0.0), Link::new(1.0, 0.0)])?;
/// let keyframes = vec![vec![0.0, 0.0, 0.0], vec![0.8, 0.6, -0.4], vec![1.2, 1.6, 0.2]];
/// let options = MotionOptions::new(Timing::Frames(30), Ease::Sine);
/// let spline = animate_with(&chain, &keyframes, None, options)?;
/// let linear = animate_with(&chain, &keyframes, None, options.with_interpolation(Interpolation::Linear))?;
/// assert_eq!(spline.frames[29].angles, linear.frames[29].angles); // both end on the last keyframe
/// assert_ne!(spline.frames[10].angles, linear.frames[10].angles); // but round the corner differently
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn animate_with<B: Body + ?Sized>(
    body: &B,
    keyframes: &[Vec<f64>],
    times: Option<&[f64]>,
    options: MotionOptions,
) -> Result<Animation, MotionError> {
    let n = options.timing.frame_count()?;
    if keyframes.is_empty() {
        return Err(MotionError::NoKeyframes);
    }
    for (index, key) in keyframes.iter().enumerate() {
        check_pose(body, "keyframes", index, key)?;
        for (joint, (&value, limits)) in key.iter().zip(body.angle_limits()).enumerate() {
            if let Some(lim) = limits.filter(|lim| !lim.contains(value)) {
                return Err(MotionError::OutsideLimits { index, joint, value, min: lim.min(), max: lim.max() });
            }
        }
    }
    let path = Path::new(body.angle_limits(), keyframes.iter().map(Vec::as_slice), "keyframes")?;
    if let Some(times) = times {
        check_times(times, keyframes.len(), options.timing.duration())?;
    }
    Ok(build(body, &path, times, options, n))
}

/// Re-times the frames a solve recorded into the frames of `timing`, eased by `ease`.
///
/// The recorded poses are the keyframes of [`animate`], timed by arc length: a solve that took
/// 2000 small steps becomes, say, 60 frames spread evenly along the path it took (the many
/// near-identical poses of its final approach take almost no time). The first frame is the
/// first recorded pose, the last the last recorded pose (up to whole turns of joints without
/// limits, see the [module docs](self)).
///
/// The recorded angles are not checked against the joint limits: with
/// [`LimitMode::Clamp`](crate::LimitMode::Clamp) they lie inside them and so does every frame;
/// a solve that ignored the limits is animated as it went. Joints with limits still never wrap.
///
/// Errors if nothing was recorded ([`SolveOptions::record_every`](crate::SolveOptions) was
/// `None`), if the frames were recorded for a chain with a different number of joints, or if an
/// angle is not finite.
pub fn animate_solve<B: Body + ?Sized>(
    body: &B,
    frames: &Frames,
    timing: Timing,
    ease: Ease,
) -> Result<Animation, MotionError> {
    animate_solve_with(body, frames, MotionOptions::new(timing, ease))
}

/// [`animate_solve`] with every option: the timing, the ease and the [`Interpolation`] of the
/// path through the recorded poses.
pub fn animate_solve_with<B: Body + ?Sized>(
    body: &B,
    frames: &Frames,
    options: MotionOptions,
) -> Result<Animation, MotionError> {
    let n = options.timing.frame_count()?;
    if frames.is_empty() {
        return Err(MotionError::NoRecordedFrames);
    }
    for (index, frame) in frames.iter().enumerate() {
        check_pose(body, "frames", index, frame.angles)?;
    }
    let path = Path::new(body.angle_limits(), frames.iter().map(|f| f.angles), "frames")?;
    Ok(build(body, &path, None, options, n))
}

/// One finite angle per joint.
fn check_pose<B: Body + ?Sized>(
    body: &B,
    field: &'static str,
    index: usize,
    angles: &[f64],
) -> Result<(), MotionError> {
    if angles.len() != body.angle_count() {
        return Err(MotionError::AngleCount { field, index, expected: body.angle_count(), got: angles.len() });
    }
    match angles.iter().position(|a| !a.is_finite()) {
        Some(joint) => Err(MotionError::NonFiniteAngle { field, index, joint, value: angles[joint] }),
        None => Ok(()),
    }
}

/// Finite, `times[0] = 0`, strictly increasing, last `= duration`.
fn check_times(times: &[f64], keyframes: usize, duration: f64) -> Result<(), MotionError> {
    if times.len() != keyframes {
        return Err(MotionError::TimesLength { expected: keyframes, got: times.len() });
    }
    for (index, &value) in times.iter().enumerate() {
        if !value.is_finite() {
            return Err(MotionError::NonFiniteTime { index, value });
        }
        if index == 0 && value != 0.0 {
            return Err(MotionError::FirstTime { value });
        }
        if index > 0 && value <= times[index - 1] {
            return Err(MotionError::TimesNotIncreasing { index, value, previous: times[index - 1] });
        }
    }
    let index = times.len() - 1;
    if times[index] != duration {
        return Err(MotionError::LastTime { index, value: times[index], duration });
    }
    Ok(())
}

/// The frames of a validated path: arc-length timing without `times`, eased time with them;
/// along the spline unless the options ask for the polyline or the spline would be its single
/// straight segment (then the frames are the polyline's, bit for bit).
fn build<B: Body + ?Sized>(
    body: &B,
    path: &Path,
    times: Option<&[f64]>,
    options: MotionOptions,
    n: usize,
) -> Animation {
    let MotionOptions { timing, ease, interpolation } = options;
    let spline = match (interpolation, times) {
        (Interpolation::Linear, _) => None,
        (Interpolation::Spline, None) => Spline::by_length(path),
        (Interpolation::Spline, Some(times)) => Spline::by_times(path, times),
    };
    let duration = timing.duration();
    let mut frames = Vec::with_capacity(n);
    let mut angles = Vec::with_capacity(body.angle_count());
    for i in 0..n {
        let time = timing.time(i, n);
        if i == 0 {
            angles.clear();
            angles.extend_from_slice(path.key(0));
        } else if i + 1 == n {
            angles.clear();
            angles.extend_from_slice(path.last());
        } else {
            let progress = ease.position(time / duration);
            // The polyline's arc length without times (the spline's knots are the same `C_k`),
            // the eased time with them.
            let (marks, x) = match times {
                None => (path.cumulative(), progress * path.length()),
                Some(times) => (times, progress * duration),
            };
            match &spline {
                None => path.at(marks, x, &mut angles),
                Some(spline) => spline.at(x, &mut angles),
            }
        }
        let joints = body.frame_points(&angles);
        frames.push(AnimationFrame { time, angles: angles.clone(), joints });
    }
    Animation { frames, duration, ease }
}

#[cfg(test)]
mod tests;
