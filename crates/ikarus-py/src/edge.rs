//! The shared facade of the edges, in one place: arm files, settings, requests, messages and the
//! API's JSON answers, and the character files' reader and pose job (`ikarus pose`'s). Every
//! other module names it as `crate::edge`.

pub(crate) use ikarus_edge::api::parse_json;
pub(crate) use ikarus_edge::api::pose::IkReq;
pub(crate) use ikarus_edge::character::{Loaded, load as load_character, text_of as character_text};
pub(crate) use ikarus_edge::edge::*;
pub(crate) use ikarus_edge::pose::{PhysicsAsk, PoseAsk, PosedBoneJson, pose_watched};
pub(crate) use ikarus_edge::settings::DEFAULT_ITERATION_CAP;
