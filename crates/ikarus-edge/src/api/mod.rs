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
pub mod cost;
pub mod costed;
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

use costed::{AnimateJob, PoseJob, TrackJob};
#[cfg(feature = "render")]
use figures::RenderReq;
use ikarus::Interrupt;
pub use intake::Intake;
use requests::{ReachReq, SolveReq, WorkspaceReq};
use rigs::FileBody;
use solve_batch::SolveBatchReq;
use wire::text;
pub use wire::{Limits, Problem, Reply, parse_json, status};

/// Declares the endpoints, each once: its doc, its variant, its path, what it reads
/// ([`Intake`]: how the server takes its body and where it runs it), and its request: the type
/// it is read into, how it is read from the body (`parse`), what its work costs at most
/// (`cost`, in link steps: [`cost`]) and how it is answered (`run`). From it come [`Endpoint`]
/// with [`Endpoint::ALL`], [`Endpoint::path`], [`Endpoint::intake`] and [`Endpoint::parse`],
/// [`Request`] with [`Request::cost`] and [`Request::run`], and [`call`]; and from those the
/// server's routes and lanes. An endpoint declared here is routed, read, costed and answered;
/// one declared without any of these does not compile.
macro_rules! endpoints {
    ($(
        $(#[doc = $doc:literal])*
        $(#[cfg($cfg:meta)])?
        $variant:ident = $path:literal, $intake:ident, $req:ty,
            parse |$body:pat_param, $plimits:pat_param| $parse:expr,
            cost |$creq:pat_param| $cost:expr,
            run |$rreq:pat_param, $limits:pat_param, $interrupt:pat_param| $run:expr;
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

        /// A request read from its body ([`Endpoint::parse`]), ready to cost and to run: one
        /// variant per endpoint, holding what its job runs.
        pub enum Request {
            $(
                $(#[doc = $doc])*
                $(#[cfg($cfg)])?
                $variant(Box<$req>),
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

            /// Its request read from `body` (the `GET` endpoints ignore it), once: refused as
            /// [`call`] refuses it, with the same status and message.
            pub fn parse(self, body: &[u8], limits: &Limits) -> Result<Request, Problem> {
                match self {
                    $($(#[cfg($cfg)])? Endpoint::$variant => {
                        let ($body, $plimits) = (body, limits);
                        let read: Result<$req, Problem> = $parse;
                        read.map(|r| Request::$variant(Box::new(r)))
                    })*
                }
            }
        }

        impl Request {
            /// The endpoint it was read for.
            #[must_use]
            pub fn endpoint(&self) -> Endpoint {
                match self {
                    $($(#[cfg($cfg)])? Request::$variant(_) => Endpoint::$variant,)*
                }
            }

            /// Its work at most, in link steps ([`cost`]): what a server reads to run it in a
            /// quick or a long lane.
            #[must_use]
            pub fn cost(&self) -> f64 {
                match self {
                    $($(#[cfg($cfg)])? Request::$variant(req) => {
                        let $creq: &$req = req;
                        $cost
                    })*
                }
            }

            /// Its answer: the same bytes, or the same status and message, as [`call`]'s.
            /// Computations check `interrupt` and stop with 503 when it is set.
            pub fn run(self, limits: &Limits, interrupt: &Interrupt) -> Result<Reply, Problem> {
                match self {
                    $($(#[cfg($cfg)])? Request::$variant(req) => {
                        let ($rreq, $limits, $interrupt) = (*req, limits, interrupt);
                        $run
                    })*
                }
            }
        }
    };
}

endpoints! {
    /// `GET /api/meta`: the methods, limit modes, eases and defaults the page offers.
    Meta = "meta", Nothing, (),
        parse |_, _| Ok(()),
        cost |()| 0.0,
        run |(), _, _| Reply::json(&meta::meta());
    /// `GET /api/arm/default`: the built-in arm.
    ArmDefault = "arm/default", Nothing, (),
        parse |_, _| Ok(()),
        cost |()| 0.0,
        run |(), _, _| arm_files::default_arm();
    /// `POST /api/arm/parse`: an arm file's text → `{arm}` or `{problem}`.
    ArmParse = "arm/parse", FileText, String,
        parse |body, _| text(body).map(str::to_owned),
        cost |file| cost::file_bytes(FileBody::Text, file.as_bytes()),
        run |file, _, _| Reply::json(&arm_files::parsed(&file));
    /// `POST /api/arm/toml`: `{"arm": …}` → the file's text.
    ArmToml = "arm/toml", Json, arm_files::TomlReq,
        parse |body, _| parse_json(body),
        cost |_| 0.0,
        run |req, _, _| arm_files::toml(&req);
    /// `GET /api/rigs`: the shipped rigs.
    Rigs = "rigs", Nothing, (),
        parse |_, _| Ok(()),
        cost |()| 0.0,
        run |(), _, _| rigs::list();
    /// `POST /api/rig/parse`: a rig file's text → `{rig}` or `{problem}` (the server also takes
    /// a `.skel`'s bytes and `?text=1`: [`rigs::parse_file`]).
    RigParse = "rig/parse", FileTextOrBytes, Vec<u8>,
        parse |body, _| Ok(body.to_vec()),
        cost |file| cost::file_bytes(FileBody::Text, file),
        run |file, limits, _| rigs::parse_file(&file, FileBody::Text, rigs::Echo::Without, limits);
    /// `POST /api/atlas/parse`: a texture atlas (and its page images) → its id and pages.
    AtlasParse = "atlas/parse", JsonFile, Vec<u8>,
        parse |body, _| Ok(body.to_vec()),
        cost |body| body.len() as f64 * cost::ATLAS_BYTE_COST,
        run |body, _, _| atlases::parse(&body);
    /// `POST /api/solve`: an arm's or a rig's solve.
    Solve = "solve", Computation, SolveReq,
        parse |body, _| SolveReq::parse(body).map(|(_, req)| req),
        cost |req| cost::solve(req),
        run |req, limits, interrupt| jobs::solve(req, limits, interrupt);
    /// `POST /api/solve_batch`: many goals for one arm, through the library's batch path.
    SolveBatch = "solve_batch", Computation, SolveBatchReq,
        parse |body, _| parse_json(body),
        cost |req| cost::solve_batch(req),
        run |req, limits, interrupt| solve_batch::solve_batch(req, limits, interrupt);
    /// `POST /api/animate`: a motion.
    Animate = "animate", Computation, AnimateJob,
        parse |body, limits| AnimateJob::parse(body, limits),
        cost |job| job.cost(),
        run |job, limits, interrupt| job.run(limits, interrupt);
    /// `POST /api/track`: a path followed or planned.
    Track = "track", Computation, TrackJob,
        parse |body, limits| TrackJob::parse(body, limits),
        cost |job| job.cost(),
        run |job, limits, interrupt| job.run(limits, interrupt);
    /// `POST /api/workspace`: the reachable region.
    Workspace = "workspace", Computation, WorkspaceReq,
        parse |body, _| parse_json(body),
        cost |req| cost::workspace(req),
        run |req, limits, interrupt| regions::workspace(req, limits, interrupt);
    /// `POST /api/reach`: the verdict on points.
    Reach = "reach", Computation, ReachReq,
        parse |body, _| parse_json(body),
        cost |req| cost::reach(req),
        run |req, limits, interrupt| regions::reach(req, limits, interrupt);
    /// `POST /api/pose`: a character file posed as its runtime does.
    Pose = "pose", Computation, PoseJob,
        parse |body, limits| PoseJob::parse(body, limits),
        cost |job| job.cost(),
        run |job, _, interrupt| job.run(interrupt);
    /// `POST /api/render`: a picture (PNG, SVG or GIF).
    #[cfg(feature = "render")]
    Render = "render", Computation, RenderReq,
        parse |body, _| RenderReq::parse(body),
        cost |req| cost::render(req),
        run |req, limits, interrupt| render::render(req, limits, interrupt);
    /// `POST /api/ease`: an ease curve's progress at evenly spaced times.
    Ease = "ease", Json, ease::EaseCurveReq,
        parse |body, _| parse_json(body),
        cost |_| 0.0,
        run |req, _, _| ease::curve(&req);
}

/// Exactly what `ikarus serve` answers for `endpoint` with this body (the `GET` endpoints
/// ignore it): the same bytes, or the same status and message. Computations check `interrupt`
/// and stop with 503 when it is set. The request is read once ([`Endpoint::parse`]) and run
/// ([`Request::run`]).
pub fn call(endpoint: Endpoint, body: &[u8], limits: &Limits, interrupt: &Interrupt) -> Result<Reply, Problem> {
    endpoint.parse(body, limits)?.run(limits, interrupt)
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
