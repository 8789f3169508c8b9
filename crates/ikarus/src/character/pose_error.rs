//! Why a pose request is refused.

use thiserror::Error;

/// A pose request the character cannot take.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum PoseError {
    /// The clip index is not one of the character's clips.
    #[error("clip: no clip {0}")]
    UnknownClip(usize),
    /// The time is NaN or infinite.
    #[error("time: must be finite, got {0}")]
    Time(f64),
    /// A play's frame rate is not a positive number.
    #[error("fps: must be a positive number, got {0}")]
    Fps(f64),
    /// A play would take more than [`MAX_FRAMES`](crate::character::MAX_FRAMES) frames.
    #[error("time: {time} s at {fps} frames a second is more frames than a play takes")]
    TooLong {
        /// The time asked, seconds.
        time: f64,
        /// The frames a second.
        fps: f64,
    },
    /// A target names a bone that does not exist.
    #[error("target: no bone {0}")]
    UnknownBone(usize),
    /// A target's point is not finite.
    #[error("target: bone {bone}'s point must be finite, got ({x}, {y})")]
    TargetPoint {
        /// The bone's index.
        bone: usize,
        /// The point's x.
        x: f64,
        /// The point's y.
        y: f64,
    },
    /// A turn names a bone that does not exist.
    #[error("turn: no bone {0}")]
    UnknownTurn(usize),
    /// A turn's rotation is not finite.
    #[error("turn: bone {bone}'s rotation must be finite, got {rotation}")]
    TurnRotation {
        /// The bone's index.
        bone: usize,
        /// The rotation, radians.
        rotation: f64,
    },
    /// The skin index is not one of the character's skins.
    #[error("skin: no skin {0}")]
    UnknownSkin(usize),
    /// A target names a bone the skin leaves inactive (not posed, so not movable).
    #[error("target: bone {0} is inactive: the skin does not turn it on")]
    InactiveTarget(usize),
    /// A bend names a constraint that does not exist or is not an IK constraint.
    #[error("bend: no IK constraint {0}")]
    UnknownConstraint(usize),
    /// A target's bone has a parent whose world matrix is singular (scaled to nothing), so no
    /// local position puts it anywhere else.
    #[error("target: bone {0}'s parent is scaled to nothing, its origin cannot be placed")]
    SingularParent(usize),
    /// [`GivenPose::local`](crate::character::GivenPose::local) has not one transform per bone.
    #[error("local: {got} transforms for the character's {want} bones")]
    GivenLocals {
        /// How many were given.
        got: usize,
        /// How many bones.
        want: usize,
    },
    /// [`GivenPose::settings`](crate::character::GivenPose::settings) has not one per constraint.
    #[error("settings: {got} for the character's {want} constraints")]
    GivenSettings {
        /// How many were given.
        got: usize,
        /// How many constraints.
        want: usize,
    },
    /// A given constraint's settings are not of its kind.
    #[error("settings[{0}]: not the settings of constraint {0}'s kind")]
    GivenKind(usize),
    /// The pose's [`Interrupt`](crate::Interrupt) was set
    /// ([`Character::pose_watched`](crate::character::Character::pose_watched)): `out` holds a
    /// pose half done, to be thrown away.
    #[error("interrupted")]
    Interrupted,
}
