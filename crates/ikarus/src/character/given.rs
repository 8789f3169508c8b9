//! Posing from local transforms the caller gives: what a runtime's `updateWorldTransform` does
//! with the bones' locals and the constraints' settings an animation (or a game) left, without
//! the clip. [`Character::sample`] is the other half: the clip's locals and settings at a time,
//! what a runtime's `AnimationState.apply` writes. A sample given back to
//! [`Character::pose_given`] poses bit for bit as [`Character::pose`] does.

use super::{Frame, PoseError, PoseRequest, Posed};
use crate::character::{Character, LocalTransform, PhysicsMode, Placement, Settings};

/// What [`Character::pose_given`] poses: every bone's local transform and every constraint's
/// settings (as [`Posed::local`] and [`Posed::settings`] give them), the skeleton's placement,
/// the skin, and what the physics constraints do.
#[derive(Debug, Clone, Copy)]
pub struct GivenPose<'a> {
    /// One per bone, in the character's order.
    pub local: &'a [LocalTransform],
    /// One per constraint, in the character's order, each of its constraint's kind.
    pub settings: &'a [Settings],
    /// The skeleton's own position and scale (Spine's `skeleton.x`, `y`, `scaleX`, `scaleY`),
    /// in place of the character's.
    pub placement: Placement,
    /// The skin (an index in [`Character::skins`]) whose skin-required bones and constraints
    /// take part, as in [`PoseRequest::skin`].
    pub skin: Option<usize>,
    /// `None`: the physics constraints leave the bones as given (Spine's `Physics.none`);
    /// `Reset`: their simulations restart here; `Update`: they step to `clock`. Their states
    /// live in the [`Posed`], from call to call.
    pub physics: PhysicsMode,
    /// The skeleton's clock, seconds (read by `Reset` and `Update`).
    pub clock: f64,
}

impl Character {
    /// The setup pose, then `request`'s clip at its time, turns and bends, into `out`'s local
    /// transforms and settings (read them with [`Posed::local`] and [`Posed::settings`]): what
    /// the clip sets, before any target or constraint. `out`'s world transforms are those of
    /// these locals with no constraint applied. The targets are checked but not applied.
    pub fn sample(&self, request: &PoseRequest, out: &mut Posed) -> Result<(), PoseError> {
        self.sample_frame(request, out, Frame::Still)?;
        out.parts(self, self.placement).0.update_all();
        Ok(())
    }

    /// Poses the character from `given`'s local transforms and settings: the world transforms,
    /// then the constraints in their order as [`Character::pose`] applies them, the skeleton
    /// placed at `given.placement`. The path constraints follow their paths as the last
    /// [`Character::sample`] into `out` deformed them (a runtime keeps a deform on its slot until
    /// the next `apply`): sample into the `Posed` you pose into. Allocates nothing once `out` has
    /// grown to the character.
    pub fn pose_given(&self, given: &GivenPose, out: &mut Posed) -> Result<(), PoseError> {
        let (bones, constraints) = (self.bones.len(), self.constraints.len());
        if given.local.len() != bones {
            return Err(PoseError::GivenLocals { got: given.local.len(), want: bones });
        }
        if given.settings.len() != constraints {
            return Err(PoseError::GivenSettings { got: given.settings.len(), want: constraints });
        }
        if let Some(k) = (0..constraints)
            .find(|&k| std::mem::discriminant(&given.settings[k]) != std::mem::discriminant(&self.setup[k]))
        {
            return Err(PoseError::GivenKind(k));
        }
        if let Some(s) = given.skin.filter(|&s| s >= self.skins.len()) {
            return Err(PoseError::UnknownSkin(s));
        }
        let frame = match given.physics {
            PhysicsMode::None => Frame::Still,
            mode => {
                if !given.clock.is_finite() {
                    return Err(PoseError::Time(given.clock));
                }
                Frame::Play { mode, clock: given.clock, from: given.clock, world: self.physics_world() }
            }
        };
        out.local.clear();
        out.local.extend_from_slice(given.local);
        out.settings.clear();
        out.settings.extend_from_slice(given.settings);
        // The paths' deforms are the last sample's (a runtime keeps them on the slots).
        if self.kinds.path && out.path.deformed.len() != constraints {
            out.path.reset(constraints);
        }
        self.begin(out, given.skin);
        let request = PoseRequest { skin: given.skin, ..PoseRequest::default() };
        self.constrain(&request, out, None, frame, given.placement)
    }
}
