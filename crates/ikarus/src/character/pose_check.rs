//! What a pose request must hold before posing starts: a skin, clip, bones and constraints the
//! character has, a finite time, finite points and rotations (see [`PoseError`]).

use super::Character;
use super::pose::{PoseError, PoseRequest};

impl Character {
    /// Refuses a request naming what the character does not have, or a value not finite.
    pub(super) fn check(&self, request: &PoseRequest) -> Result<(), PoseError> {
        if let Some(s) = request.skin.filter(|&s| s >= self.skins.len()) {
            return Err(PoseError::UnknownSkin(s));
        }
        if let Some((c, time)) = request.clip {
            if c >= self.clips.len() {
                return Err(PoseError::UnknownClip(c));
            }
            if !time.is_finite() {
                return Err(PoseError::Time(time));
            }
        }
        for &(bone, [x, y]) in request.targets {
            if bone >= self.bones.len() {
                return Err(PoseError::UnknownBone(bone));
            }
            if !(x.is_finite() && y.is_finite()) {
                return Err(PoseError::TargetPoint { bone, x, y });
            }
        }
        for &(bone, rotation) in request.turns {
            if bone >= self.bones.len() {
                return Err(PoseError::UnknownTurn(bone));
            }
            if !rotation.is_finite() {
                return Err(PoseError::TurnRotation { bone, rotation });
            }
        }
        if let Some(&(k, _)) = request.bends.iter().find(|(k, _)| self.ik(*k).is_none()) {
            return Err(PoseError::UnknownConstraint(k));
        }
        Ok(())
    }
}
