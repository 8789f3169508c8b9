//! Keyframe motion in joint space, re-timed by an ease curve.
