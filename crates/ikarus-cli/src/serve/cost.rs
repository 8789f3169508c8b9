//! What a computation will cost at most, read from its request before it runs, so that the pool
//! can give quick requests their own lane ([`super::pool::Lane`]).
//!
//! The estimate counts *link steps*: one link handled once in an iteration, tens of nanoseconds
//! (an iteration of an 8-link solve took 36 ns a link, a halving of its step less, in a release
//! build on the README's machine). It is the worst case the request's own fields allow, not a
//! guess at the usual case:
//!
//! - a solve: `links × max_iterations × (1 + restarts) × (1 + backtrack)` (every iteration may
//!   halve its step `backtrack` times, every restart may run to the cap); a rig's solve also
//!   times its goals and pins;
//! - `solve_batch`: a solve per goal; `animate`: a solve per via point and the goal, plus a pose
//!   per frame (with `keys`, one solve of its tracks and pins per frame); `track`: a solve per sample (12 in `plan`: candidates, seeds, polish);
//! - `workspace`: the grid's cells and samples × links, or for the exact region links² × 100
//!   (10 times more with limits); `reach`: that region's cost once, plus a solve per point;
//! - `render`: its pixels (times the frames of a GIF) plus the cost of what it draws;
//! - a character's job (`rig` a character file's text): reading the file, plus its poses (one
//!   for `pose`, a frame's for `animate` and `render`, a sample's for `track`), each costed from
//!   the file's bones and constraints ([`character`]); `rig/parse` and `arm/parse`: their bytes
//!   (a `.skel`'s bytes as the JSON text they may decode into at most: [`character::SKEL_TEXT_BYTES`]);
//!   `atlas/parse`: [`ATLAS_BYTE_COST`] a byte of its body (its page images are decoded: an
//!   atlas alone is quick, one with its images is long).
//!
//! The body is read leniently: unknown fields are skipped, and a field of the wrong type counts
//! as absent (the request is then refused when it runs, at once). A body that is not a JSON
//! object costs nothing to refuse and is quick. A request the estimate gets wrong is still
//! caught: a quick one running past [`super::pool::LONG_AFTER`] must move to the long lane.

use std::fmt;

use serde::Deserialize;
use serde::de::{self, Deserializer, IgnoredAny, MapAccess, SeqAccess, Visitor};

use super::pool::Lane;
use crate::api::Endpoint;
use crate::api::rigs::FileBody;
pub use character::{file_estimate, file_lane};

mod character;
mod keys;

use character::Rules;

/// The largest estimate (link steps) of a quick request: about a tenth of a second of work in its
/// worst case.
pub const QUICK_COST: f64 = 2.5e6;

/// Link steps a byte of `/api/atlas/parse`'s body counts for: a compressed PNG byte decodes
/// into several pixels (a megabyte of images is far past [`QUICK_COST`]).
pub const ATLAS_BYTE_COST: f64 = 10.0;

/// What a solve runs at most when neither the request nor its file says: the library's
/// defaults (`ikarus::SolveOptions::default()`), as link-step factors.
struct SolverDefaults {
    iterations: f64,
    restarts: f64,
    backtrack: f64,
}

impl SolverDefaults {
    fn get() -> Self {
        let d = ikarus::SolveOptions::default();
        SolverDefaults {
            iterations: f64::from(d.max_iterations),
            restarts: f64::from(d.restarts.map_or(0, |r| r.attempts)),
            backtrack: f64::from(d.backtrack),
        }
    }
}

/// Links of the built-in arm (the seed's), when a request has no `arm`.
fn seed_links() -> f64 {
    static LINKS: std::sync::LazyLock<f64> =
        std::sync::LazyLock::new(|| ikarus_edge::edge::default_arm().chain().len() as f64);
    *LINKS
}
/// Samples of a track's shape, frames of a motion, pixels of a picture side when not given.
const TRACK_SAMPLES: f64 = 100.0;
const FRAMES: f64 = 60.0;
const PICTURE_SIDE: f64 = 800.0;
/// Solves per sample of a planned track: 8 candidates, 2 seeds, 2 polish passes.
const PLAN_SOLVES: f64 = 12.0;

/// The lane of a computation of `endpoint` asked for by `body`.
pub fn lane(endpoint: Endpoint, body: &[u8]) -> Lane {
    if estimate(endpoint, body) <= QUICK_COST { Lane::Quick } else { Lane::Long }
}

/// The request's worst-case work in link steps (see the module docs); 0 for a body that is not
/// a JSON object.
pub fn estimate(endpoint: Endpoint, body: &[u8]) -> f64 {
    let shape = |cost: fn(&Shape) -> f64| serde_json::from_slice::<Shape>(body).map_or(0.0, |r| cost(&r));
    match endpoint {
        // Answered at once, never on the pool: nothing in them a request can lengthen.
        Endpoint::Meta | Endpoint::ArmDefault | Endpoint::Rigs | Endpoint::ArmToml | Endpoint::Ease => 0.0,
        Endpoint::ArmParse | Endpoint::RigParse => file_estimate(FileBody::Text, body),
        Endpoint::AtlasParse => body.len() as f64 * ATLAS_BYTE_COST,
        Endpoint::Solve => shape(Shape::solve),
        Endpoint::SolveBatch => shape(|r| r.goals.0.max(1.0) * r.solve()),
        Endpoint::Animate => shape(Shape::animate),
        Endpoint::Track => shape(Shape::track),
        Endpoint::Workspace => shape(Shape::workspace),
        Endpoint::Reach => shape(|r| r.region() + r.points.0.max(1.0) * r.solve()),
        Endpoint::Pose => shape(|r| r.character().map_or(0.0, |c| c.parse() + c.pose(r.rules()))),
        #[cfg(feature = "render")]
        Endpoint::Render => shape(Shape::render),
    }
}

/// The fields of any computation's request that its cost depends on.
#[derive(Debug, Default, Deserialize)]
#[serde(default)]
struct Shape {
    arm: Nested<Body>,
    rig: character::RigField,
    /// A kept character's id (`"character": ID`).
    character: Option<String>,
    ik: Json,
    options: Nested<Solver>,
    goals: Count,
    pins: Count,
    via: Count,
    path: Count,
    points: Count,
    samples: Num,
    frames: Num,
    duration: Num,
    fps: Num,
    resolution: Num,
    width: Num,
    height: Num,
    grid: Json,
    limits: Json,
    workspace: Json,
    figure: Json,
    format: Json,
    mode: Json,
    keys: Nested<keys::Keys>,
}

/// An arm's or a rig's file: how many links or bones, and its `[solver]` table.
#[derive(Debug, Default, Deserialize)]
#[serde(default)]
struct Body {
    links: Count,
    bones: Count,
    solver: Nested<Solver>,
}

/// The solver options that bound a solve's work.
#[derive(Debug, Default, Deserialize)]
#[serde(default)]
struct Solver {
    max_iterations: Num,
    restarts: Num,
    backtrack: Num,
}

impl Shape {
    /// The request's character: `rig` as a character's JSON text, or the kept one `character`
    /// names.
    fn character(&self) -> Option<character::Character> {
        self.rig.character.or_else(|| self.character.as_deref().and_then(character::Character::kept))
    }

    /// Whose rules the request's character poses follow.
    fn rules(&self) -> Rules {
        if self.ik.is_text("ikarus") {
            Rules::Ikarus { goals: self.goals.0, pins: self.pins.0 }
        } else {
            Rules::Runtime
        }
    }

    /// Joints of the request's arm or rig.
    fn joints(&self) -> f64 {
        match (&self.arm.0, &self.rig.body) {
            (_, Some(rig)) => rig.bones.0,
            (Some(arm), None) => arm.links.0,
            (None, None) => seed_links(),
        }
        .max(1.0)
    }

    /// A solver option: `options`, else the arm's or rig's `[solver]`, else `default`.
    fn option(&self, field: impl Fn(&Solver) -> Option<f64>, default: f64) -> f64 {
        let file = self.arm.0.as_ref().or(self.rig.body.as_ref()).and_then(|b| b.solver.0.as_ref());
        [self.options.0.as_ref(), file].into_iter().flatten().find_map(field).unwrap_or(default).max(0.0)
    }

    /// One solve, worst case.
    fn solve(&self) -> f64 {
        // A rig's solve places every bone for each goal and pin.
        self.solve_of(if self.rig.body.is_some() { 1.0 + self.goals.0 + self.pins.0 } else { 1.0 })
    }

    /// One solve placing every joint for each of `targets`, worst case.
    fn solve_of(&self, targets: f64) -> f64 {
        let d = SolverDefaults::get();
        let iterations = self.option(|s| s.max_iterations.value(), d.iterations);
        let restarts = self.option(|s| s.restarts.value(), d.restarts);
        let backtrack = self.option(|s| s.backtrack.value(), d.backtrack);
        self.joints() * targets * iterations.max(1.0) * (1.0 + restarts) * (1.0 + backtrack)
    }

    /// Frames of a motion: a keyed one's, else `frames`, else `duration` × `fps`.
    fn frames(&self) -> f64 {
        if let Some(keys) = &self.keys.0 {
            return keys.frames();
        }
        match (self.frames.value(), self.duration.value()) {
            (Some(frames), _) => frames,
            (None, Some(seconds)) => seconds * self.fps.value().unwrap_or(FRAMES),
            (None, None) => FRAMES,
        }
        .max(0.0)
    }

    /// A motion's solves and poses; a keyed one's, one solve of its tracks and pins per frame.
    fn animate(&self) -> f64 {
        if let Some(c) = self.character() {
            return c.parse() + self.frames() * c.pose(self.rules());
        }
        if let Some(keys) = &self.keys.0 {
            return keys.frames() * (self.solve_of(1.0 + keys.effectors()) + self.joints());
        }
        (1.0 + self.via.0) * self.solve() + self.frames() * self.joints()
    }

    fn track(&self) -> f64 {
        let samples = if self.path.0 > 0.0 { self.path.0 } else { self.samples.value().unwrap_or(TRACK_SAMPLES) };
        if let Some(c) = self.character() {
            return c.parse() + samples.max(1.0) * c.pose(self.rules());
        }
        let solves = if self.mode.is_text("follow") { 1.0 } else { PLAN_SOLVES };
        samples.max(0.0) * solves * self.solve()
    }

    fn is_grid(&self) -> bool {
        self.grid.is_true() || self.resolution.value().is_some() || self.samples.value().is_some()
    }

    /// The exact region of the arm: links² × 100, 10 times more with limits.
    fn region(&self) -> f64 {
        let n = self.joints();
        let limits = if self.limits.is_true() { 10.0 } else { 1.0 };
        n * n * 100.0 * limits
    }

    fn workspace(&self) -> f64 {
        if !self.is_grid() {
            return self.region();
        }
        let resolution = self.resolution.value().unwrap_or(256.0);
        // The library samples 4096 · 4^k poses by default, k = min(joints − 1, 3).
        let n = self.joints();
        let samples = self.samples.value().unwrap_or(4096.0 * 4f64.powf((n - 1.0).clamp(0.0, 3.0)));
        resolution * resolution + samples * n
    }

    fn render(&self) -> f64 {
        let pixels = self.width.value().unwrap_or(PICTURE_SIDE) * self.height.value().unwrap_or(PICTURE_SIDE);
        let drawn = if self.figure.is_text("motion") {
            let frames = if self.format.is_text("gif") { self.frames() } else { 1.0 };
            self.animate() + frames * pixels
        } else if self.figure.is_text("workspace") || self.workspace.is_true() {
            self.workspace()
        } else {
            0.0
        };
        pixels + drawn
    }
}

/// One JSON value of any type, kept as much as the estimate needs: a number, `true`, a short
/// text, an array's length.
#[derive(Debug, Default, Clone, PartialEq)]
enum Json {
    #[default]
    Other,
    Number(f64),
    True,
    Text(String),
    Array(f64),
}

impl Json {
    fn is_true(&self) -> bool {
        *self == Json::True
    }

    fn is_text(&self, text: &str) -> bool {
        matches!(self, Json::Text(t) if t == text)
    }
}

/// A number, or absent (any other value).
#[derive(Debug, Default)]
struct Num(Json);

impl Num {
    fn value(&self) -> Option<f64> {
        match self.0 {
            Json::Number(x) if x.is_finite() => Some(x),
            _ => None,
        }
    }
}

/// An array's length, or 0 (any other value).
#[derive(Debug, Default)]
struct Count(f64);

/// An object read as `T`, or absent (any other value).
#[derive(Debug)]
struct Nested<T>(Option<T>);

impl<T> Default for Nested<T> {
    fn default() -> Self {
        Self(None)
    }
}

impl<'de> Deserialize<'de> for Json {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(AnyValue)
    }
}

impl<'de> Deserialize<'de> for Num {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        Json::deserialize(d).map(Num)
    }
}

impl<'de> Deserialize<'de> for Count {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        Ok(Count(match Json::deserialize(d)? {
            Json::Array(n) => n,
            _ => 0.0,
        }))
    }
}

impl<'de, T: Deserialize<'de>> Deserialize<'de> for Nested<T> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(NestedValue(std::marker::PhantomData))
    }
}

/// Reads any value into a [`Json`], skipping what it does not keep.
struct AnyValue;

impl<'de> Visitor<'de> for AnyValue {
    type Value = Json;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("any JSON value")
    }

    fn visit_bool<E>(self, v: bool) -> Result<Json, E> {
        Ok(if v { Json::True } else { Json::Other })
    }

    fn visit_i64<E>(self, v: i64) -> Result<Json, E> {
        Ok(Json::Number(v as f64))
    }

    fn visit_u64<E>(self, v: u64) -> Result<Json, E> {
        Ok(Json::Number(v as f64))
    }

    fn visit_f64<E>(self, v: f64) -> Result<Json, E> {
        Ok(Json::Number(v))
    }

    fn visit_str<E>(self, v: &str) -> Result<Json, E> {
        // The texts the estimate compares are short names (`gif`, `follow`, `motion`).
        Ok(if v.len() <= 16 { Json::Text(v.to_owned()) } else { Json::Other })
    }

    fn visit_unit<E>(self) -> Result<Json, E> {
        Ok(Json::Other)
    }

    fn visit_none<E>(self) -> Result<Json, E> {
        Ok(Json::Other)
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Json, A::Error> {
        let mut n = 0.0;
        while seq.next_element::<IgnoredAny>()?.is_some() {
            n += 1.0;
        }
        Ok(Json::Array(n))
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Json, A::Error> {
        while map.next_entry::<IgnoredAny, IgnoredAny>()?.is_some() {}
        Ok(Json::Other)
    }
}

/// Reads an object as a `T`, and any other value as absent.
struct NestedValue<T>(std::marker::PhantomData<T>);

impl<'de, T: Deserialize<'de>> Visitor<'de> for NestedValue<T> {
    type Value = Nested<T>;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("any JSON value")
    }

    fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<Nested<T>, A::Error> {
        T::deserialize(de::value::MapAccessDeserializer::new(map)).map(|t| Nested(Some(t)))
    }

    fn visit_bool<E>(self, _: bool) -> Result<Nested<T>, E> {
        Ok(Nested(None))
    }

    fn visit_i64<E>(self, _: i64) -> Result<Nested<T>, E> {
        Ok(Nested(None))
    }

    fn visit_u64<E>(self, _: u64) -> Result<Nested<T>, E> {
        Ok(Nested(None))
    }

    fn visit_f64<E>(self, _: f64) -> Result<Nested<T>, E> {
        Ok(Nested(None))
    }

    fn visit_str<E>(self, _: &str) -> Result<Nested<T>, E> {
        Ok(Nested(None))
    }

    fn visit_unit<E>(self) -> Result<Nested<T>, E> {
        Ok(Nested(None))
    }

    fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<Nested<T>, A::Error> {
        AnyValue.visit_seq(seq).map(|_| Nested(None))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    fn lane_of(endpoint: Endpoint, body: &serde_json::Value) -> Lane {
        lane(endpoint, body.to_string().as_bytes())
    }

    #[test]
    fn the_pages_requests_are_quick() {
        let goal = json!({ "x": 2.0, "y": 3.0 });
        for (endpoint, body) in [
            (Endpoint::Solve, json!({ "goal": goal })),
            (Endpoint::Solve, json!({ "goal": goal, "options": { "limits": true, "record_every": 50 } })),
            (Endpoint::Animate, json!({ "goal": goal, "frames": 60 })),
            (Endpoint::Animate, json!({ "goal": goal, "duration": 1.25, "fps": 60 })),
            (Endpoint::Track, json!({ "circle": [0, 0, 4], "samples": 2, "mode": "follow" })),
            (Endpoint::Workspace, json!({})),
            (Endpoint::Workspace, json!({ "resolution": 256 })),
            (Endpoint::Reach, json!({ "point": [1, 2] })),
            (Endpoint::SolveBatch, json!({ "goals": [[1, 2], [2, 1]] })),
            (Endpoint::Render, json!({ "figure": "arm", "goal": goal, "width": 400, "height": 400 })),
        ] {
            assert_eq!(lane_of(endpoint, &body), Lane::Quick, "{endpoint:?} {body}");
        }
    }

    #[test]
    fn the_issues_heavy_requests_are_long() {
        let links64 = vec![json!({ "length": 0.1, "angle_deg": 5.0 }); 64];
        let goals: Vec<[f64; 2]> = (0..100_000).map(|i| [f64::from(i % 50) * 0.1, 1.0]).collect();
        let via: Vec<[f64; 2]> = (0..100).map(|i| [f64::from(i % 7) * 0.5, 1.0]).collect();
        for (endpoint, body) in [
            (Endpoint::SolveBatch, json!({ "goals": goals })),
            (Endpoint::Animate, json!({ "goal": { "x": 1, "y": 1 }, "via": via })),
            (Endpoint::Track, json!({ "arm": { "links": links64 }, "circle": [0, 0, 4], "samples": 5000 })),
            (Endpoint::Workspace, json!({ "arm": { "links": links64 }, "limits": true })),
            (Endpoint::Workspace, json!({ "resolution": 1024, "samples": 1_000_000 })),
            (
                Endpoint::Solve,
                json!({ "arm": { "links": links64 }, "goal": { "x": 1, "y": 1 }, "options": { "max_iterations": 100_000 } }),
            ),
            (
                Endpoint::Render,
                json!({ "figure": "motion", "goal": { "x": 1, "y": 1 }, "frames": 2000, "format": "gif" }),
            ),
        ] {
            assert_eq!(lane_of(endpoint, &body), Lane::Long, "{endpoint:?}");
        }
    }

    #[test]
    fn the_arms_solver_table_counts_and_options_win() {
        let arm = json!({ "links": [{ "length": 1.0 }], "solver": { "max_iterations": 100_000_000 } });
        assert_eq!(lane_of(Endpoint::Solve, &json!({ "arm": arm, "goal": { "x": 1, "y": 0 } })), Lane::Long);
        let body = json!({ "arm": arm, "goal": { "x": 1, "y": 0 }, "options": { "max_iterations": 10 } });
        assert_eq!(lane_of(Endpoint::Solve, &body), Lane::Quick);
    }

    #[test]
    fn odd_bodies_are_read_leniently() {
        // Fields of the wrong type count as absent; a body that is not an object is quick
        // (it is refused at once when it runs).
        let bodies: [&[u8]; 4] =
            [b"[]", b"nonsense", b"", br#"{"arm": 3, "options": [1], "goals": {"a": 1}, "frames": "x"}"#];
        for body in bodies {
            assert_eq!(lane(Endpoint::Solve, body), Lane::Quick, "{}", String::from_utf8_lossy(body));
        }
        // A rig's bones, goals and pins count.
        let bones: Vec<_> = (0..256).map(|i| json!({ "name": format!("b{i}"), "length": 1.0 })).collect();
        let goals: Vec<_> = (0..64).map(|_| json!({ "bone": "b0", "x": 1, "y": 1 })).collect();
        assert_eq!(lane_of(Endpoint::Solve, &json!({ "rig": { "bones": bones }, "goals": goals })), Lane::Long);
    }
}
