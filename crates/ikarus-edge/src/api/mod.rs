//! The JSON API without HTTP: every endpoint of `ikarus serve` as a function from a request's
//! bytes to an answer's bytes ([`call`]). The server's handlers call it on a worker of their
//! pool; Python and WebAssembly call it directly (through [`crate::edge`]), so the four edges
//! answer the same request with the same bytes, the same status and the same message.
//!
//! Requests ([`requests`], [`figures`]: one type per job, for an arm or a rig, told apart by
//! [`bodies`]) use the names of the command line and the arm and rig files (degrees at the
//! edge); answers are the objects the commands print (`crate::report`), made by the same
//! workflows ([`jobs`]: `crate::settings`, `crate::motion`, `crate::track`; [`regions`]:
//! `crate::area`, `crate::reach`; `render`: `crate::picture`), the request's fields checked by
//! [`fields`].

pub mod arm_files;
pub mod atlases;
pub mod bodies;
pub mod character_motion;
pub mod ease;
pub mod fields;
pub mod figures;
pub mod jobs;
pub mod keyed;
pub mod meta;
pub mod pose;
#[cfg(feature = "render")]
pub mod pose_figure;
pub mod regions;
#[cfg(feature = "render")]
pub mod render;
pub mod requests;
pub mod rigs;
pub mod solve_batch;
pub mod wire;

use bodies::AnimateBody;
use ikarus::Interrupt;
use requests::{SolveReq, TrackReq};
use wire::text;
pub use wire::{Limits, Problem, Reply, parse_json, status};

/// The endpoints of the API (`/api/<path>`), without HTTP.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Endpoint {
    /// `GET /api/meta`: the methods, limit modes, eases and defaults the page offers.
    Meta,
    /// `GET /api/arm/default`: the built-in arm.
    ArmDefault,
    /// `POST /api/arm/parse`: an arm file's text → `{arm}` or `{problem}`.
    ArmParse,
    /// `POST /api/arm/toml`: `{"arm": …}` → the file's text.
    ArmToml,
    /// `GET /api/rigs`: the shipped rigs.
    Rigs,
    /// `POST /api/rig/parse`: a rig file's text → `{rig}` or `{problem}`.
    RigParse,
    /// `POST /api/atlas/parse`: a texture atlas (and its page images) → its id and pages.
    AtlasParse,
    /// `POST /api/solve`: an arm's or a rig's solve.
    Solve,
    /// `POST /api/solve_batch`: many goals for one arm, through the library's batch path.
    SolveBatch,
    /// `POST /api/animate`: a motion.
    Animate,
    /// `POST /api/track`: a path followed or planned.
    Track,
    /// `POST /api/workspace`: the reachable region.
    Workspace,
    /// `POST /api/reach`: the verdict on points.
    Reach,
    /// `POST /api/pose`: a character file posed as its runtime does.
    Pose,
    /// `POST /api/render`: a picture (PNG, SVG or GIF).
    #[cfg(feature = "render")]
    Render,
    /// `POST /api/ease`: an ease curve's progress at evenly spaced times.
    Ease,
}

impl Endpoint {
    /// Every endpoint.
    pub const ALL: &[Endpoint] = &[
        Endpoint::Meta,
        Endpoint::ArmDefault,
        Endpoint::ArmParse,
        Endpoint::ArmToml,
        Endpoint::Rigs,
        Endpoint::RigParse,
        Endpoint::AtlasParse,
        Endpoint::Solve,
        Endpoint::SolveBatch,
        Endpoint::Animate,
        Endpoint::Track,
        Endpoint::Workspace,
        Endpoint::Reach,
        Endpoint::Pose,
        #[cfg(feature = "render")]
        Endpoint::Render,
        Endpoint::Ease,
    ];

    /// Its path, `/api/solve`.
    #[must_use]
    pub fn path(self) -> &'static str {
        match self {
            Endpoint::Meta => "/api/meta",
            Endpoint::ArmDefault => "/api/arm/default",
            Endpoint::ArmParse => "/api/arm/parse",
            Endpoint::ArmToml => "/api/arm/toml",
            Endpoint::Rigs => "/api/rigs",
            Endpoint::RigParse => "/api/rig/parse",
            Endpoint::AtlasParse => "/api/atlas/parse",
            Endpoint::Solve => "/api/solve",
            Endpoint::SolveBatch => "/api/solve_batch",
            Endpoint::Animate => "/api/animate",
            Endpoint::Track => "/api/track",
            Endpoint::Workspace => "/api/workspace",
            Endpoint::Reach => "/api/reach",
            Endpoint::Pose => "/api/pose",
            #[cfg(feature = "render")]
            Endpoint::Render => "/api/render",
            Endpoint::Ease => "/api/ease",
        }
    }

    /// The endpoint at `path`: `/api/solve`, `api/solve` or `solve`.
    #[must_use]
    pub fn from_path(path: &str) -> Option<Endpoint> {
        let path = path.trim_start_matches('/');
        let path = path.strip_prefix("api/").unwrap_or(path);
        Self::ALL.iter().copied().find(|e| &e.path()["/api/".len()..] == path)
    }

    /// Whether the endpoint reads a body (`POST`); the others ignore it (`GET`).
    #[must_use]
    pub fn takes_body(self) -> bool {
        !matches!(self, Endpoint::Meta | Endpoint::ArmDefault | Endpoint::Rigs)
    }
}

/// Exactly what `ikarus serve` answers for `endpoint` with this body (the `GET` endpoints
/// ignore it): the same bytes, or the same status and message. Computations check `interrupt`
/// and stop with 503 when it is set.
pub fn call(endpoint: Endpoint, body: &[u8], limits: &Limits, interrupt: &Interrupt) -> Result<Reply, Problem> {
    match endpoint {
        Endpoint::Meta => Reply::json(&meta::meta()),
        Endpoint::ArmDefault => arm_files::default_arm(),
        Endpoint::ArmParse => Reply::json(&arm_files::parsed(text(body)?)),
        Endpoint::ArmToml => arm_files::toml(body),
        Endpoint::Rigs => rigs::list(),
        Endpoint::RigParse => rigs::parse_file(body, rigs::FileBody::Text, rigs::Echo::Without, limits),
        Endpoint::AtlasParse => atlases::parse(body),
        Endpoint::Solve => jobs::solve(SolveReq::parse(body)?.1, limits, interrupt),
        Endpoint::SolveBatch => solve_batch::solve_batch(body, limits, interrupt),
        Endpoint::Animate if character_motion::is_character(body) => character_motion::animate(body, limits, interrupt),
        Endpoint::Track if character_motion::is_character(body) => character_motion::track(body, limits, interrupt),
        Endpoint::Animate => jobs::animate(AnimateBody::parse(body)?, limits, interrupt),
        Endpoint::Track => jobs::track(TrackReq::parse(body)?.1, limits, interrupt),
        Endpoint::Workspace => regions::workspace(body, limits, interrupt),
        Endpoint::Reach => regions::reach(body, limits, interrupt),
        Endpoint::Pose => pose::pose(body, limits, interrupt),
        #[cfg(feature = "render")]
        Endpoint::Render => render::render(body, limits, interrupt),
        Endpoint::Ease => ease::curve(body),
    }
}
