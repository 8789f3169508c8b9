//! The JSON requests of the API's jobs, in the names of the command line and the arm and rig
//! files (degrees at the edge). Every field is optional unless said otherwise; unknown fields
//! are refused.
//!
//! `POST /api/solve`, `/api/animate` and `/api/track` each take one request that carries the
//! body, `arm` (the built-in arm without one) or `rig`, and the fields of both: an arm takes
//! one `goal`, a rig `goals` on named bones, `pins` and `mix`. Which fields a body takes is
//! checked in one place, [`super::bodies`].
//!
//! The groups of fields that several requests share (the body, a rig's goals, a motion's
//! timing, a picture's size, a reachable area) are declared once, in `request!`, which declares
//! a request struct from its own fields and these groups. They are written into each struct as
//! plain fields rather than as `serde(flatten)`ed structs: a flattened struct would lose
//! `deny_unknown_fields` and the field paths of `serde_path_to_error`, and the refusals name
//! the field and its place (the refusal of an unknown field lists the fields in their order,
//! so a group stands where its fields stood).

use ikarus::EaseKind;
use serde::Deserialize;

use crate::arm::ArmFile;
use crate::settings::SolverSettings;

/// Declares a request struct: its attributes and name (with at most one type parameter), then
/// a list of fields, each either a field as in a struct (`pub name: Type,` with its attributes)
/// or a group, `..name,`, that stands for the group's fields in its place. Every field is
/// optional: absent, it takes its type's default (`#[serde(default)]` is added to each).
///
/// - `..body`: `arm` and `rig`, the request's body.
/// - `..rig_goals`: a rig's `goals` and `pins`.
/// - `..aim`: `..body`, `start_deg`, an arm's `goal`, `..rig_goals` and a rig's `mix`
///   (what a solve is aimed at).
/// - `..motion`: `options` and the motion's timing (`ease`, `frames`, `duration`, `fps`,
///   `interpolation`, `from_solve`), after its `via`.
/// - `..picture`: `figure` (read by the render request's first pass), `format`, `width`,
///   `height`.
/// - `..area`: `limits`, `grid`, `resolution`, `samples`, `seed` (the exact region, or the
///   sampled grid).
/// - `..character_ik`: a character's `ik` (`"runtime"` or `"ikarus"`) and `ik_file` (TOML).
/// - `..ik_goals`: `..character_ik`, then goals on bones' tips and pins (with `"ikarus"`).
/// - `..pose`: a character's pose (`/api/pose`'s fields): `rig` or `character`, the clip and its
///   time, targets, bends, rotations, physics, skin, atlas, then `..ik_goals`.
/// - `..export`: a character's motion's `format`, `..character_ik`, `animation_name`, `bake`.
///
/// A field written `required name: Type,` has no default: absent, it is refused.
macro_rules! request {
    ($(#[$meta:meta])* pub struct $name:ident $(<$param:ident>)? { $($fields:tt)* }) => {
        $crate::api::requests::request!(@fields [$(#[$meta])* pub struct $name $(<$param>)?] [] $($fields)*);
    };
    (@fields [$($head:tt)*] [$($done:tt)*]) => {
        $($head)* { $($done)* }
    };
    (@fields $head:tt $done:tt ..body, $($rest:tt)*) => {
        $crate::api::requests::request!(@fields $head $done
            /// An arm file, in its TOML fields as JSON [default: the built-in arm].
            pub arm: Option<$crate::arm::ArmFile>,
            /// A rig file, in its TOML fields as JSON, in place of `arm`.
            pub rig: Option<$crate::rig::RigFile>,
            $($rest)*
        );
    };
    (@fields $head:tt $done:tt ..rig_goals, $($rest:tt)*) => {
        $crate::api::requests::request!(@fields $head $done
            /// A rig's goals.
            pub goals: Option<Vec<$crate::api::requests::RigGoalReq>>,
            /// A rig's pinned bones (held where they are).
            pub pins: Option<Vec<String>>,
            $($rest)*
        );
    };
    (@fields $head:tt $done:tt ..aim, $($rest:tt)*) => {
        $crate::api::requests::request!(@fields $head $done
            ..body,
            /// One angle per joint (a rig's bones in its order) [default: the body's start pose].
            pub start_deg: Option<Vec<f64>>,
            /// An arm's goal.
            pub goal: Option<$crate::api::requests::GoalReq>,
            ..rig_goals,
            /// A rig's mix, from 0 to 1 [default: 1].
            pub mix: Option<f64>,
            $($rest)*
        );
    };
    (@fields $head:tt $done:tt ..motion, $($rest:tt)*) => {
        $crate::api::requests::request!(@fields $head $done
            /// The solver's settings, as `ikarus solve`'s flags name them.
            pub options: Option<$crate::settings::SolverSettings>,
            /// The ease of the motion between its stops.
            pub ease: Option<$crate::api::requests::EaseReq>,
            /// How many frames the motion has; or `duration` and `fps`.
            pub frames: Option<u32>,
            /// The motion's length, seconds (with `fps`, in place of `frames`).
            pub duration: Option<f64>,
            /// Frames per second (with `duration`).
            pub fps: Option<f64>,
            /// The path through the poses: `spline` (the default) or `polyline`.
            pub interpolation: Option<ikarus::motion::Interpolation>,
            /// Follow the solver's recorded path instead of moving straight between solved poses.
            pub from_solve: bool,
            $($rest)*
        );
    };
    (@fields $head:tt $done:tt ..picture, $($rest:tt)*) => {
        $crate::api::requests::request!(@fields $head $done
            /// Read by the first pass.
            #[serde(rename = "figure")]
            pub _figure: serde::de::IgnoredAny,
            /// `png` (the default), `svg`, or `gif` (a motion's figure, animated).
            pub format: Option<$crate::picture::PictureFormat>,
            /// The picture's width, pixels [default: 800].
            pub width: Option<u32>,
            /// The picture's height, pixels [default: 800].
            pub height: Option<u32>,
            $($rest)*
        );
    };
    (@fields $head:tt $done:tt ..area, $($rest:tt)*) => {
        $crate::api::requests::request!(@fields $head $done
            /// The area within the limits (a rig figure's: its limit wedges).
            pub limits: Option<bool>,
            /// The sampled grid instead of the exact region.
            pub grid: Option<bool>,
            /// The grid's cells per side.
            pub resolution: Option<u32>,
            /// The random poses sampled for the grid.
            pub samples: Option<u32>,
            /// The seed of the sampled poses (the same seed gives the same grid).
            pub seed: Option<u64>,
            $($rest)*
        );
    };
    (@fields $head:tt $done:tt ..character_ik, $($rest:tt)*) => {
        $crate::api::requests::request!(@fields $head $done
            /// `"runtime"` (the default) or `"ikarus"`.
            pub ik: Option<String>,
            /// With `"ik": "ikarus"`: an IK file's text (TOML; see `ikarus pose --ik-file`).
            pub ik_file: Option<String>,
            $($rest)*
        );
    };
    (@fields $head:tt $done:tt ..pose, $($rest:tt)*) => {
        $crate::api::requests::request!(@fields $head $done
            /// The character file's text; or `character`.
            pub rig: Option<String>,
            /// The id `/api/rig/parse` answered for the character ([`crate::character::store`]).
            pub character: Option<String>,
            /// The clip the pose is taken from [default: the setup pose].
            pub animation: Option<String>,
            /// Seconds into the clip [default: 0].
            pub time: Option<f64>,
            /// Bones' world origins put at points after the clip and before the constraints, in order.
            pub targets: Vec<$crate::api::requests::TargetReq>,
            /// Which way a two-bone IK constraint bends (`cw` or `ccw`), by the name of its lower bone.
            pub bends: std::collections::BTreeMap<String, $crate::keys::BendName>,
            /// Bones' local rotations, degrees, in place of the clip's, by the bone's name.
            pub rotations: std::collections::BTreeMap<String, f64>,
            /// Whether the clip is played from 0 with the physics constraints stepping [default: true].
            pub physics: Option<bool>,
            /// Frames a second of the play with physics [default: 60].
            pub fps: Option<f64>,
            /// The skin whose bones and constraints take part, by name [default: `default`, if any].
            pub skin: Option<String>,
            /// The id `/api/atlas/parse` answered for the character's atlas.
            pub atlas: Option<String>,
            ..ik_goals,
            $($rest)*
        );
    };
    (@fields $head:tt $done:tt ..ik_goals, $($rest:tt)*) => {
        $crate::api::requests::request!(@fields $head $done
            ..character_ik,
            /// With `"ik": "ikarus"`: goals on bones' tips, solved with the constraints (a rig's
            /// goals, and `bones`: how many bones each turns).
            pub goals: Vec<$crate::api::requests::RigGoalReq>,
            /// With `"ik": "ikarus"`: bones whose tips stay where they start.
            pub pins: Vec<String>,
            $($rest)*
        );
    };
    (@fields $head:tt $done:tt ..export, $($rest:tt)*) => {
        $crate::api::requests::request!(@fields $head $done
            /// `json` (the frames, the default) or `spine` (the file with the motion added).
            pub format: $crate::api::requests::MotionFormat,
            ..character_ik,
            /// With `spine`: the added animation's name.
            pub animation_name: Option<String>,
            /// With `spine`: every bone keyed at every frame (`true`) instead of the keys an
            /// animator edits.
            pub bake: bool,
            $($rest)*
        );
    };
    (@fields $head:tt [$($done:tt)*] $(#[$attr:meta])* required $field:ident : $ty:ty, $($rest:tt)*) => {
        $crate::api::requests::request!(@fields $head [$($done)* $(#[$attr])* pub $field: $ty,] $($rest)*);
    };
    (@fields $head:tt [$($done:tt)*] $(#[$attr:meta])* pub $field:ident : $ty:ty, $($rest:tt)*) => {
        $crate::api::requests::request!(@fields $head [$($done)* $(#[$attr])* #[serde(default)] pub $field: $ty,] $($rest)*);
    };
}

pub(super) use request;

/// A goal: position, and optionally the orientation of the last link.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GoalReq {
    /// The goal's x.
    pub x: f64,
    /// The goal's y.
    pub y: f64,
    /// The last link's absolute direction wanted, degrees from +x; position only when absent.
    #[serde(default)]
    pub angle_deg: Option<f64>,
}

/// A goal's priority: `primary` (the default) or `secondary`.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum PriorityReq {
    /// Solved first, together with the pins.
    Primary,
    /// Solved in what the primary goals and pins leave free, never pulling them away.
    Secondary,
}

/// Which way a limb bends: `ccw` or `cw`.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum BendReq {
    /// Counterclockwise.
    Ccw,
    /// Clockwise.
    Cw,
}

/// A rig's goal on the tip of the bone `bone`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RigGoalReq {
    /// The bone whose tip should reach the goal, by name.
    pub bone: String,
    /// The goal's x.
    pub x: f64,
    /// The goal's y.
    pub y: f64,
    /// The bone's absolute direction wanted, degrees from +x; position only when absent.
    #[serde(default)]
    pub angle_deg: Option<f64>,
    /// Its weight when goals conflict, > 0: the heavier is met more closely [default: 1].
    #[serde(default)]
    pub weight: Option<f64>,
    /// [default: primary].
    #[serde(default)]
    pub priority: Option<PriorityReq>,
    /// Which way the joint between the bone and its parent bends [default: either].
    #[serde(default)]
    pub bend: Option<BendReq>,
    /// How far short of full stretch, in length units, the goal starts to be drawn in smoothly,
    /// ≥ 0 [default: 0, none].
    #[serde(default)]
    pub softness: Option<f64>,
    /// A character's goal (`/api/pose`): how many bones it turns, counted up from its bone.
    #[serde(default)]
    pub bones: Option<usize>,
}

request! {
    /// `POST /api/solve`: an arm's tip to `goal` (required with an arm), or a rig's `goals` and
    /// `pins` solved together.
    #[derive(Debug, Deserialize)]
    #[serde(deny_unknown_fields)]
    pub struct SolveReq {
        ..aim,
        /// The solver's settings, as `ikarus solve`'s flags name them.
        pub options: Option<SolverSettings>,
    }
}

/// An ease curve: `kind` (default sine for a motion, parent for the ease figure), `k1`, `k2`.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EaseReq {
    /// The curve, as `GET /api/meta` lists the eases.
    #[serde(default)]
    pub kind: Option<EaseKind>,
    /// The parent curve's end of acceleration, a fraction of the time.
    #[serde(default)]
    pub k1: Option<f64>,
    /// The parent curve's start of deceleration, a fraction of the time.
    #[serde(default)]
    pub k2: Option<f64>,
}

request! {
    /// `POST /api/animate`: the solves of [`SolveReq`] in turn, through `via`, eased into frames.
    /// `V` is what one `via` entry is for the body: an arm's point `[x, y]`, a rig's goal set
    /// (a list of goals, the pins held in each); the body is told apart before the request is
    /// read. `goal` (an arm's) or `goals` (a rig's) is the final goal; a rig's `pins` hold in
    /// every goal set.
    #[derive(Debug, Deserialize)]
    #[serde(deny_unknown_fields)]
    pub struct AnimateReq<V> {
        ..aim,
        /// What to pass through first, in order.
                pub via: Vec<V>,
        ..motion,
        /// A rig's keyframes per effector ([`crate::keys`]): instead of `goals`, `via`, `pins`
        /// and the motion's timing.
        pub keys: Option<crate::keys::KeysFile>,
    }
}

request! {
    /// `POST /api/track`: exactly one of `path`, `line`, `circle`, `figure8`, followed by an
    /// arm's tip, or by the tip of a rig's `effector` while its `goals` hold and its `pins` stay.
    #[derive(Debug, Deserialize)]
    #[serde(deny_unknown_fields)]
    pub struct TrackReq {
        ..body,
        /// One angle per joint, degrees (a rig's bones in its order) [default: the body's start
        /// pose].
        pub start_deg: Option<Vec<f64>>,
        /// A rig's bone whose tip follows the path (required with a rig).
        pub effector: Option<String>,
        ..rig_goals,
        /// A rig's mix, from 0 to 1 [default: 1].
        pub mix: Option<f64>,
        /// The samples, `[[x, y], …]`, used as given.
        pub path: Option<Vec<[f64; 2]>>,
        /// `[x0, y0, x1, y1]`.
        pub line: Option<[f64; 4]>,
        /// `[cx, cy, r]`.
        pub circle: Option<[f64; 3]>,
        /// `[cx, cy, a]`.
        pub figure8: Option<[f64; 3]>,
        /// Samples of a shape [default: 100].
        pub samples: Option<usize>,
        /// `follow` or `plan` [default: plan for an arm; follow, the only mode, for a rig].
        pub mode: Option<ikarus::TrackMode>,
        /// The bound on a joint's change between samples, degrees [default: 10].
        pub max_step_deg: Option<f64>,
        /// With `mode: "follow"`: bound the first sample's step from `start_deg` too, as every
        /// later one (a pointer followed one request at a time) [default: false, the first sample
        /// is placed on the path].
        pub bound_first: bool,
        /// The solver's settings, as `ikarus solve`'s flags name them.
        pub options: Option<SolverSettings>,
    }
}

request! {
    /// `POST /api/workspace`: the exact region, or with `grid: true` (or any of `resolution`,
    /// `samples`, `seed`) the sampled grid; with `rig` in place of `arm`, the region of `bone`'s
    /// tip (sampled unless the rig is a chain).
    #[derive(Debug, Default, Deserialize)]
    #[serde(deny_unknown_fields)]
    pub struct WorkspaceReq {
        ..body,
        /// The rig's bone [default: the last].
        pub bone: Option<String>,
        ..area,
    }
}

impl WorkspaceReq {
    /// The area a picture shades (figures `arm`, `motion`, `workspace`): the arm is the
    /// picture's, so none here.
    pub fn area(
        limits: Option<bool>,
        grid: Option<bool>,
        resolution: Option<u32>,
        samples: Option<u32>,
        seed: Option<u64>,
    ) -> Self {
        Self { arm: None, rig: None, bone: None, limits, grid, resolution, samples, seed }
    }
}

request! {
    /// `POST /api/reach`: exactly one of `point` and `points`.
    #[derive(Debug, Deserialize)]
    #[serde(deny_unknown_fields)]
    pub struct ReachReq {
        /// The arm [default: the built-in arm].
        pub arm: Option<ArmFile>,
        /// Whether the joint limits bound the reach [default: the arm file's `[solver] limits`,
        /// else off].
        pub limits: Option<bool>,
        /// Distance that still counts as reachable [default: the arm's `solver.tolerance`, else
        /// 1e-6].
        pub tolerance: Option<f64>,
        /// One point: the answer is one object.
        pub point: Option<[f64; 2]>,
        /// Many points: the answer is an array of objects, in order.
        pub points: Option<Vec<[f64; 2]>>,
    }
}

/// What a character's motion is answered as.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum MotionFormat {
    /// Its frames.
    #[default]
    Json,
    /// The Spine document with the motion added.
    Spine,
    /// Its frames as CSV, one row per bone per frame ([`crate::character::motion_files`]).
    Csv,
}

/// A bone's world origin put at (x, y).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TargetReq {
    /// The bone, by name.
    pub bone: String,
    /// Where its origin goes, x in world units.
    pub x: f64,
    /// Where its origin goes, y in world units.
    pub y: f64,
}
