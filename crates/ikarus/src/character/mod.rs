//! Imported characters (Spine and DragonBones skeletons), held as their runtimes hold them:
//! bones with a full affine local transform (translation, rotation, scale, shear) and an
//! inherit mode, constraints of every kind in one list applied one after another in their
//! order (the `constraint` module), and animation clips whose timelines key the bones' transforms and
//! the constraints' settings.
//!
//! This module is the model only: what a character *is*, validated once by [`Character::new`].
//! Reading the files belongs to the edge (`ikarus-edge`), which names fields and values in its
//! errors; posing a character as its runtime does lives beside this model.
//!
//! Conventions: y points up (a DragonBones file, y down, is flipped when it is read), angles are
//! radians, counter-clockwise positive, and lengths are in the file's own units. A bone's local
//! transform is relative to its parent's frame (the skeleton's frame for a root bone).

mod applied;
mod art;
mod clip;
mod clipping;
mod constraint;
mod draw;
mod error;
mod flat;
mod ik;
mod path;
mod physics;
mod physics_timeline;
mod play;
mod pose;
mod pose_check;
mod skin;
mod slot_clip;
mod slot_pose;
mod timeline;
mod together;
mod transform;
mod world;

pub use art::{
    Art, AtlasRegion, Attachment, BlendMode, ClippingAttachment, MeshAttachment, RegionAttachment, Regions, Rgba,
    SkinArt, Slot, WHITE,
};
pub use clip::{BoneKey, BoneProperty, BoneTimeline, Clip, IkKey, Interpolation};
pub use clipping::MAX_CLIP_VERTICES;
pub use constraint::{ChannelKey, Constraint, ConstraintKeys, ConstraintTimeline, MAX_CHANNELS, Settings};
pub use draw::{DrawItem, DrawList};
pub use error::CharacterError;
pub use path::{
    Chain, DeformKey, Followed, PathConstraint, PathDeform, PathScratch, PathSettings, PathShape, PathVertices,
    PositionMode, RotateMode, SkinPath, SpacingMode, Weight, solve as solve_path,
};
pub use physics::{
    MAX_STEPS, PhysicsConstraint, PhysicsGlobal, PhysicsInput, PhysicsMode, PhysicsSettings, PhysicsShares,
    PhysicsState, PhysicsWorld,
};
pub use physics_timeline::{PhysicsKey, PhysicsProperty, PhysicsReset, PhysicsTimeline, physics_settings_at};
pub use play::{MAX_FRAMES, Play, PlayFrame};
pub use pose::{GivenPose, PoseError, PoseRequest, Posed};
pub use skin::{Skin, SkinRequired};
pub use slot_clip::{
    AttachmentKey, AttachmentTimeline, COLOR_CHANNELS, ColorKey, ColorProperty, ColorTimeline, DrawOrderKey,
    MeshDeform, SlotClip, draw_order_at, draw_order_from_offsets,
};
pub use slot_pose::SlotPose;
pub use together::{
    BoneRule, GoalEnd, LimbEnd, LimbRule, ROUNDS, SPINE_BONE_NUMBERS, SpineBone, SpineFrame, SpineRig, TIP_GOAL_BONES,
    TipGoal, Together, TogetherError, TogetherReport, spine_bone_numbers, spine_local_numbers,
};
pub use transform::{
    MIX_NAMES, TransformConstraint, TransformMode, TransformOffsets, TransformSettings, TransformSpace, local_absolute,
    local_relative, world_absolute, world_relative,
};
pub use world::{Affine, world_transform};

/// A character: bones listed parent first, constraints of every kind, clips, and the
/// skeleton's own placement.
#[derive(Debug, Clone, PartialEq)]
pub struct Character {
    bones: Vec<CharacterBone>,
    constraints: Vec<Constraint>,
    clips: Vec<Clip>,
    placement: Placement,
    unsupported: Vec<Unsupported>,
    /// The skins.
    skins: Vec<Skin>,
    /// What only a skin turns on, as posing reads it.
    activity: skin::Activity,
    /// The constraints' indices in the order they apply (by `order`, ties as listed).
    order: Vec<usize>,
    /// The clips' Bézier segments, sampled once.
    curves: timeline::Curves,
    /// The bones a pose without targets leaves to the constraints' updates ([`world::deferred`]).
    deferred: Vec<bool>,
    /// The bones and constraints as posing reads them.
    flat: flat::Flat,
    /// Every constraint's settings in the setup pose (a pose starts by copying them).
    setup: Vec<Settings>,
    /// Which kinds with per-pose state the character has.
    kinds: Kinds,
    /// The skeleton's reference scale for physics ([`Character::reference_scale`]).
    reference_scale: f64,
    /// The slots and the skins' attachments (what is drawn).
    art: Art,
}

/// Whether a character has path and physics constraints (a pose keeps their buffers only then).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
struct Kinds {
    path: bool,
    physics: bool,
}

/// The skeleton's own position and scale: every world transform is the bones' own transform
/// scaled by `scale` and moved by `position` (Spine's `skeleton.x`, `y`, `scaleX`, `scaleY`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Placement {
    /// Where the skeleton's origin goes in the world.
    pub position: [f64; 2],
    /// The skeleton's scale along x and y (a negative one mirrors it).
    pub scale: [f64; 2],
}

impl Default for Placement {
    fn default() -> Self {
        Placement { position: [0.0, 0.0], scale: [1.0, 1.0] }
    }
}

/// One bone.
#[derive(Debug, Clone, PartialEq)]
pub struct CharacterBone {
    /// Its name in the file.
    pub name: String,
    /// The parent's index, always lower than this bone's; `None` for a root.
    pub parent: Option<usize>,
    /// Length along the bone's local x axis (0 for a bone that is only a frame).
    pub length: f64,
    /// The setup pose's local transform.
    pub setup: LocalTransform,
    /// What it takes from its parent's world transform.
    pub inherit: Inherit,
}

/// A local transform in the parent's frame. The local matrix is
/// `[[cos(r + shx)·sx, cos(r + π/2 + shy)·sy], [sin(r + shx)·sx, sin(r + π/2 + shy)·sy]]`
/// with `r = rotation`, and the origin is `(x, y)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LocalTransform {
    /// Origin x in the parent's frame.
    pub x: f64,
    /// Origin y in the parent's frame.
    pub y: f64,
    /// Radians, counter-clockwise.
    pub rotation: f64,
    /// Scale along the local x axis.
    pub scale_x: f64,
    /// Scale along the local y axis.
    pub scale_y: f64,
    /// Radians.
    pub shear_x: f64,
    /// Radians.
    pub shear_y: f64,
}

impl Default for LocalTransform {
    fn default() -> Self {
        LocalTransform { x: 0.0, y: 0.0, rotation: 0.0, scale_x: 1.0, scale_y: 1.0, shear_x: 0.0, shear_y: 0.0 }
    }
}

crate::listed_enum! {
    /// What a bone takes from its parent's world transform (Spine's `inherit`, called
    /// `transform` in 3.8).
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
    pub enum Inherit {
        /// Translation, rotation, scale, shear and reflection.
        #[default]
        Normal,
        /// The parent's translation only.
        OnlyTranslation,
        /// Translation and scale; not rotation nor reflection.
        NoRotationOrReflection,
        /// Translation, rotation and reflection; not scale.
        NoScale,
        /// Translation and rotation; not scale nor reflection.
        NoScaleOrReflection,
    }
}

impl Inherit {
    /// Spine's name of the mode (`normal`, `onlyTranslation`, …).
    pub fn as_str(self) -> &'static str {
        match self {
            Inherit::Normal => "normal",
            Inherit::OnlyTranslation => "onlyTranslation",
            Inherit::NoRotationOrReflection => "noRotationOrReflection",
            Inherit::NoScale => "noScale",
            Inherit::NoScaleOrReflection => "noScaleOrReflection",
        }
    }
}

/// Whose rules an IK constraint follows when the character is posed as its runtime does.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum IkRule {
    /// Spine's: one bone aims, two bones by the law of cosines in the parent's parent's frame,
    /// with softness, stretch, compress and uniform.
    Spine,
    /// DragonBones': one bone aims, two bones by a circle–circle intersection in world space.
    DragonBones,
}

/// The bones an IK constraint moves: one, or a parent and its child.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum IkBones {
    /// One bone, which aims at the target.
    One(usize),
    /// A parent and its child (the child's tip reaches for the target).
    Two {
        /// The parent bone's index.
        parent: usize,
        /// The child bone's index.
        child: usize,
    },
}

/// An IK constraint's settings that clips can key.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IkSettings {
    /// How much of the solved rotation is applied, 0 to 1.
    pub mix: f64,
    /// The width of the band near full reach over which a two-bone limb straightens smoothly
    /// (Spine; 0 is none). In the file's units, before the skeleton's scale.
    pub softness: f64,
    /// Bend counter-clockwise (`true`, Spine's `bendPositive`) or clockwise.
    pub bend_positive: bool,
    /// One bone: shrink along x to reach a target nearer than its length.
    pub compress: bool,
    /// Stretch along x to reach a target beyond the bone's (the limb's) length.
    pub stretch: bool,
}

impl Default for IkSettings {
    fn default() -> Self {
        IkSettings { mix: 1.0, softness: 0.0, bend_positive: true, compress: false, stretch: false }
    }
}

/// An IK constraint: its bones' last tip is brought to the target bone's origin.
#[derive(Debug, Clone, PartialEq)]
pub struct IkConstraint {
    /// Its name in the file.
    pub name: String,
    /// Constraints are applied in increasing `order` (ties: the order they are listed in).
    pub order: u32,
    /// The bone or bones it moves.
    pub bones: IkBones,
    /// The bone whose world origin is the target.
    pub target: usize,
    /// The settings of the setup pose (clips key them).
    pub setup: IkSettings,
    /// With stretch or compress, scale y as x (Spine's `uniform`).
    pub uniform: bool,
    /// Whose rules posing follows.
    pub rule: IkRule,
}

/// A feature of the character's file that ikarus does not use (a clipping attachment, a
/// sequence, a field of a later format, a DragonBones inherit combination no Spine mode
/// matches), reported to the user so that nothing is dropped silently.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Unsupported {
    /// What it is: `clipping attachment`, `sequence`, `field`, `timeline`, `inherit mode`.
    pub kind: String,
    /// Its name in the file, with where it is when the name alone does not say.
    pub name: String,
}

/// The parts of a character, checked by [`Character::new`].
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CharacterParts {
    /// The bones, parent first.
    pub bones: Vec<CharacterBone>,
    /// The constraints, of every kind.
    pub constraints: Vec<Constraint>,
    /// The clips.
    pub clips: Vec<Clip>,
    /// The skeleton's own position and scale.
    pub placement: Placement,
    /// The constraints left inactive.
    pub unsupported: Vec<Unsupported>,
    /// The skins (what each turns on).
    pub skins: Vec<Skin>,
    /// The bones and constraints only a skin turns on.
    pub skin_required: SkinRequired,
    /// The slots and the skins' attachments (none for a character read without its art).
    pub art: Art,
}

impl Character {
    /// A character from its parts, once they are checked: at least one bone, every parent an
    /// earlier bone, every number finite, lengths not negative, every constraint's bones and
    /// target existing (a two-bone constraint's child the parent's child), mix within [0, 1]
    /// and softness not negative, every timeline's bone or constraint existing and its keys
    /// in increasing finite time with finite values.
    pub fn new(parts: CharacterParts) -> Result<Self, CharacterError> {
        let CharacterParts { bones, constraints, clips, placement, unsupported, skins, skin_required, art } = parts;
        if bones.is_empty() {
            return Err(CharacterError::NoBones);
        }
        for (i, b) in bones.iter().enumerate() {
            if let Some(p) = b.parent {
                if p >= i {
                    return Err(CharacterError::ParentOrder { bone: i, parent: p });
                }
            }
            let t = &b.setup;
            for (field, value) in [
                ("length", b.length),
                ("x", t.x),
                ("y", t.y),
                ("rotation", t.rotation),
                ("scaleX", t.scale_x),
                ("scaleY", t.scale_y),
                ("shearX", t.shear_x),
                ("shearY", t.shear_y),
            ] {
                if !value.is_finite() {
                    return Err(CharacterError::NotFinite { bone: i, field, value });
                }
            }
            if b.length < 0.0 {
                return Err(CharacterError::NegativeLength { bone: i, value: b.length });
            }
        }
        for (k, c) in constraints.iter().enumerate() {
            c.check(k, &bones)?;
        }
        for (ci, clip) in clips.iter().enumerate() {
            for t in &clip.bones {
                if t.bone >= bones.len() {
                    return Err(CharacterError::MissingTarget { clip: ci, what: "bone", index: t.bone });
                }
                check_times(ci, t.keys.iter().map(|k| k.time))?;
                for k in &t.keys {
                    if let Some(&value) = k.values[..t.property.channels()].iter().find(|v| !v.is_finite()) {
                        return Err(CharacterError::KeyValue { clip: ci, value });
                    }
                }
            }
            for t in &clip.constraints {
                if t.constraint >= constraints.len() {
                    return Err(CharacterError::MissingTarget { clip: ci, what: "constraint", index: t.constraint });
                }
                check_times(ci, (0..t.keys.len()).map(|i| t.keys.time(i)))?;
                t.keys.check(t.constraint, &constraints[t.constraint])?;
            }
        }
        let mut order: Vec<usize> = (0..constraints.len()).collect();
        order.sort_by_key(|&k| (constraints[k].order(), k));
        let curves = timeline::Curves::of(&clips);
        let deferred = world::deferred(&bones, &constraints, &order);
        let flat = flat::Flat::of(&bones, constraints.iter().map(Constraint::updates));
        let setup = constraints.iter().map(Constraint::setup).collect();
        let kinds = Kinds {
            path: constraints.iter().any(|c| matches!(c, Constraint::Path(_))),
            physics: constraints.iter().any(|c| matches!(c, Constraint::Physics(_))),
        };
        skin::check(&skins, &skin_required, [bones.len(), constraints.len()])?;
        for (k, c) in constraints.iter().enumerate() {
            if let Some(p) = c.path().and_then(|p| p.skin_paths.iter().find(|p| p.skin >= skins.len())) {
                return Err(CharacterError::PathSkin { constraint: k, skin: p.skin });
            }
        }
        art.check(bones.len(), skins.len(), clips.len())?;
        let activity = skin::Activity::new(bones.len(), constraints.len(), &skin_required);
        Ok(Character {
            bones,
            constraints,
            clips,
            placement,
            unsupported,
            skins,
            activity,
            order,
            curves,
            deferred,
            flat,
            setup,
            kinds,
            reference_scale: PhysicsWorld::default().reference_scale,
            art,
        })
    }

    /// The bones, parent first.
    pub fn bones(&self) -> &[CharacterBone] {
        &self.bones
    }

    /// The constraints of every kind, as listed (they apply by [`Constraint::order`]).
    pub fn constraints(&self) -> &[Constraint] {
        &self.constraints
    }

    /// The constraints' indices in the order they apply: by [`Constraint::order`], ties as
    /// listed.
    pub fn order(&self) -> &[usize] {
        &self.order
    }

    /// The IK constraints with their indices in [`Character::constraints`].
    pub fn ik_constraints(&self) -> impl Iterator<Item = (usize, &IkConstraint)> {
        self.constraints.iter().enumerate().filter_map(|(k, c)| c.ik().map(|c| (k, c)))
    }

    /// Constraint `k` if it is an IK constraint.
    pub fn ik(&self, k: usize) -> Option<&IkConstraint> {
        self.constraints.get(k).and_then(Constraint::ik)
    }

    /// The animation clips.
    pub fn clips(&self) -> &[Clip] {
        &self.clips
    }

    /// The slots (the setup draw order) and the skins' attachments.
    pub fn art(&self) -> &Art {
        &self.art
    }

    /// The skins, as listed in the file.
    pub fn skins(&self) -> &[Skin] {
        &self.skins
    }

    /// The index of the skin called `name`.
    pub fn skin_index(&self, name: &str) -> Option<usize> {
        self.skins.iter().position(|s| s.name == name)
    }

    /// The skin a pose takes unless told otherwise: the one called `default`, if any.
    pub fn default_skin(&self) -> Option<usize> {
        self.skin_index("default")
    }

    /// The skeleton's own position and scale.
    pub fn placement(&self) -> Placement {
        self.placement
    }

    /// The constraints of the file that posing leaves inactive.
    pub fn unsupported(&self) -> &[Unsupported] {
        &self.unsupported
    }

    /// The index of the bone called `name`.
    pub fn bone_index(&self, name: &str) -> Option<usize> {
        self.bones.iter().position(|b| b.name == name)
    }

    /// The index of the clip called `name`.
    pub fn clip_index(&self, name: &str) -> Option<usize> {
        self.clips.iter().position(|c| c.name == name)
    }
}

pub(crate) fn check_settings(constraint: usize, s: &IkSettings) -> Result<(), CharacterError> {
    if !(0.0..=1.0).contains(&s.mix) {
        return Err(CharacterError::Setting { constraint, field: "mix", value: s.mix });
    }
    if !(s.softness.is_finite() && s.softness >= 0.0) {
        return Err(CharacterError::Setting { constraint, field: "softness", value: s.softness });
    }
    Ok(())
}

fn check_times(clip: usize, times: impl Iterator<Item = f64>) -> Result<(), CharacterError> {
    let mut last = f64::NEG_INFINITY;
    for time in times {
        if !(time.is_finite() && time >= 0.0 && time > last) {
            return Err(CharacterError::KeyTime { clip, time });
        }
        last = time;
    }
    Ok(())
}

#[cfg(test)]
#[path = "mod_tests.rs"]
mod tests;
