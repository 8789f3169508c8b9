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
pub mod intake;
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
pub use intake::Intake;
use requests::{SolveReq, TrackReq};
use wire::text;
pub use wire::{Limits, Problem, Reply, parse_json, status};

/// Declares the endpoints, each once: its doc, its variant, its path, what it reads
/// ([`Intake`]: how the server takes its body and where it runs it) and its handler, a closure
/// `|body, limits, interrupt|` answering the request's bytes. From it come [`Endpoint`],
/// [`Endpoint::ALL`], [`Endpoint::path`], [`Endpoint::intake`] and [`call`]'s match, and from
/// those the server's routes: an endpoint declared here is routed, served and costed, and one
/// not declared does not exist.
macro_rules! endpoints {
    ($(
        $(#[doc = $doc:literal])*
        $(#[cfg($cfg:meta)])?
        $variant:ident = $path:literal, $intake:ident, |$body:pat_param, $limits:pat_param, $interrupt:pat_param| $handler:expr;
    )*) => {
        /// The endpoints of the API (`/api/<path>`), without HTTP.
        #[derive(Debug, Clone, Copy, PartialEq, Eq)]
        pub enum Endpoint {
            $(
                $(#[doc = $doc])*
                $(#[cfg($cfg)])?
                $variant,
            )*
        }

        impl Endpoint {
            /// Every endpoint, in the order they are declared.
            pub const ALL: &[Endpoint] = &[$($(#[cfg($cfg)])? Endpoint::$variant,)*];

            /// Its path, `/api/solve`.
            #[must_use]
            pub fn path(self) -> &'static str {
                match self {
                    $($(#[cfg($cfg)])? Endpoint::$variant => concat!("/api/", $path),)*
                }
            }

            /// What it reads, and so how the server takes its request and where it runs it.
            #[must_use]
            pub fn intake(self) -> Intake {
                match self {
                    $($(#[cfg($cfg)])? Endpoint::$variant => Intake::$intake,)*
                }
            }
        }

        /// Exactly what `ikarus serve` answers for `endpoint` with this body (the `GET` endpoints
        /// ignore it): the same bytes, or the same status and message. Computations check
        /// `interrupt` and stop with 503 when it is set.
        pub fn call(endpoint: Endpoint, body: &[u8], limits: &Limits, interrupt: &Interrupt) -> Result<Reply, Problem> {
            match endpoint {
                $($(#[cfg($cfg)])? Endpoint::$variant => {
                    let ($body, $limits, $interrupt) = (body, limits, interrupt);
                    $handler
                })*
            }
        }
    };
}

endpoints! {
    /// `GET /api/meta`: the methods, limit modes, eases and defaults the page offers.
    Meta = "meta", Nothing, |_, _, _| Reply::json(&meta::meta());
    /// `GET /api/arm/default`: the built-in arm.
    ArmDefault = "arm/default", Nothing, |_, _, _| arm_files::default_arm();
    /// `POST /api/arm/parse`: an arm file's text → `{arm}` or `{problem}`.
    ArmParse = "arm/parse", FileText, |body, _, _| Reply::json(&arm_files::parsed(text(body)?));
    /// `POST /api/arm/toml`: `{"arm": …}` → the file's text.
    ArmToml = "arm/toml", Json, |body, _, _| arm_files::toml(body);
    /// `GET /api/rigs`: the shipped rigs.
    Rigs = "rigs", Nothing, |_, _, _| rigs::list();
    /// `POST /api/rig/parse`: a rig file's text → `{rig}` or `{problem}` (the server also takes
    /// a `.skel`'s bytes and `?text=1`: [`rigs::parse_file`]).
    RigParse = "rig/parse", FileTextOrBytes, |body, limits, _| {
        rigs::parse_file(body, rigs::FileBody::Text, rigs::Echo::Without, limits)
    };
    /// `POST /api/atlas/parse`: a texture atlas (and its page images) → its id and pages.
    AtlasParse = "atlas/parse", JsonFile, |body, _, _| atlases::parse(body);
    /// `POST /api/solve`: an arm's or a rig's solve.
    Solve = "solve", Computation, |body, limits, interrupt| jobs::solve(SolveReq::parse(body)?.1, limits, interrupt);
    /// `POST /api/solve_batch`: many goals for one arm, through the library's batch path.
    SolveBatch = "solve_batch", Computation, |body, limits, interrupt| solve_batch::solve_batch(body, limits, interrupt);
    /// `POST /api/animate`: a motion.
    Animate = "animate", Computation, |body, limits, interrupt| {
        if character_motion::is_character(body) {
            character_motion::animate(body, limits, interrupt)
        } else {
            jobs::animate(AnimateBody::parse(body)?, limits, interrupt)
        }
    };
    /// `POST /api/track`: a path followed or planned.
    Track = "track", Computation, |body, limits, interrupt| {
        if character_motion::is_character(body) {
            character_motion::track(body, limits, interrupt)
        } else {
            jobs::track(TrackReq::parse(body)?.1, limits, interrupt)
        }
    };
    /// `POST /api/workspace`: the reachable region.
    Workspace = "workspace", Computation, |body, limits, interrupt| regions::workspace(body, limits, interrupt);
    /// `POST /api/reach`: the verdict on points.
    Reach = "reach", Computation, |body, limits, interrupt| regions::reach(body, limits, interrupt);
    /// `POST /api/pose`: a character file posed as its runtime does.
    Pose = "pose", Computation, |body, limits, interrupt| pose::pose(body, limits, interrupt);
    /// `POST /api/render`: a picture (PNG, SVG or GIF).
    #[cfg(feature = "render")]
    Render = "render", Computation, |body, limits, interrupt| render::render(body, limits, interrupt);
    /// `POST /api/ease`: an ease curve's progress at evenly spaced times.
    Ease = "ease", Json, |body, _, _| ease::curve(body);
}

impl Endpoint {
    /// The endpoint at `path`: `/api/solve`, `api/solve` or `solve`.
    #[must_use]
    pub fn from_path(path: &str) -> Option<Endpoint> {
        let path = path.trim_start_matches('/');
        let path = path.strip_prefix("api/").unwrap_or(path);
        Self::ALL.iter().copied().find(|e| &e.path()["/api/".len()..] == path)
    }

    /// The endpoint at exactly `path` (`/api/solve`), as the server routes it.
    #[must_use]
    pub fn at(path: &str) -> Option<Endpoint> {
        Self::ALL.iter().copied().find(|e| e.path() == path)
    }

    /// Whether the endpoint reads a body (`POST`); the others ignore it (`GET`).
    #[must_use]
    pub fn takes_body(self) -> bool {
        self.intake().takes_body()
    }
}
