//! The API's rigs: `POST /api/solve` with `rig`, `GET /api/rigs` (the shipped rig files,
//! embedded in the binary), `POST /api/rig/parse` (rig-file text → `{"rig": …}` or
//! `{"problem": "…"}`, as `/api/arm/parse`) and the figure `rig` of `POST /api/render`. The work
//! and the answers are the command line's (`crate::goal`, `crate::report`,
//! `crate::picture`), under the server's caps and time budget.

use ikarus::{Bend, Interrupt, Outcome, Priority, RigTask};
use serde::Serialize;
use web_time::Instant;

#[cfg(feature = "render")]
use super::jobs::picture;
use super::jobs::{
    MAX_SOLVE_RECORDED_VALUES, json_response, options_for, pose_from_degrees, recorded_values_cap, stopped,
};
#[cfg(feature = "render")]
use super::rig_requests::RigFigureReq;
use super::rig_requests::{BendReq, PriorityReq, RigGoalReq, RigSolveReq};
use super::{Limits, Problem, Reply};
use crate::goal::{self, Field, NamedGoal};
#[cfg(feature = "render")]
use crate::picture::{Drawing, PictureFormat, draw, rig_figure};
use crate::report::{RigJson, RigSolveReport};
use crate::rig::{BoneCap, Rig, RigFile};
use crate::settings::solver;

/// Most effectors (goals and pins together) of a request.
pub const MAX_EFFECTORS: usize = 64;

/// The shipped rigs (`examples/rigs/`), by name, as rig-file text.
pub const SHIPPED: &[(&str, &str)] = &[
    ("puppet", include_str!("../../../../examples/rigs/puppet.toml")),
    ("hand", include_str!("../../../../examples/rigs/hand.toml")),
];

/// The request's rig, checked as a rig file is (errors start with `rig:`); at most
/// `--max-bones` bones (counted first).
pub fn load_rig(file: RigFile, limits: &Limits) -> Result<Rig, Problem> {
    Ok(Rig::from_file(file, "rig", BoneCap::flag(limits.max_bones))?)
}

/// The task of a request's `goals`, `pins` and `mix` on `rig`; problems name the field
/// (`goals[1].bone`, `pins[0]`); at most [`MAX_EFFECTORS`] goals and pins together. `need_one`:
/// a solve needs a goal or a pin, a picture does not.
pub fn task(
    rig: &Rig,
    goals: &[RigGoalReq],
    pins: &[String],
    mix: Option<f64>,
    need_one: bool,
) -> Result<RigTask, Problem> {
    let effectors = goals.len() + pins.len();
    if effectors > MAX_EFFECTORS {
        return Err(Problem::invalid(format!(
            "goals, pins: {effectors} effectors (goals and pins together), more than the cap of {MAX_EFFECTORS}"
        )));
    }
    if !need_one && effectors == 0 {
        return Ok(RigTask::default());
    }
    let goals: Vec<NamedGoal> = goals
        .iter()
        .map(|g| NamedGoal {
            weight: g.weight.unwrap_or(1.0),
            priority: match g.priority {
                None | Some(PriorityReq::Primary) => Priority::Primary,
                Some(PriorityReq::Secondary) => Priority::Secondary,
            },
            bend: g.bend.map(|b| match b {
                BendReq::Ccw => Bend::Positive,
                BendReq::Cw => Bend::Negative,
            }),
            softness: g.softness.unwrap_or(0.0),
            ..NamedGoal::new(g.bone.clone(), g.x, g.y, g.angle_deg)
        })
        .collect();
    let field = |f: Field| match f {
        Field::Goal(i) => format!("goals[{i}]"),
        Field::Weight(i) => format!("goals[{i}].weight"),
        Field::Softness(i) => format!("goals[{i}].softness"),
        Field::Bend(i) => format!("goals[{i}].bend"),
        Field::Pin(i) => format!("pins[{i}]"),
    };
    goal::build(&rig.skeleton, &goals, pins, mix.unwrap_or(1.0), &field).map_err(Problem::invalid)
}

/// `POST /api/solve` with `rig`: the JSON of `ikarus solve --rig --format json`.
pub fn solve(req: RigSolveReq, limits: &Limits, interrupt: &Interrupt) -> Result<Reply, Problem> {
    {
        let rig = load_rig(req.rig, limits)?;
        let task = task(&rig, &req.goals, &req.pins, req.mix, true)?;
        let n = rig.skeleton.len();
        // No frames unless `options.record_every` (or the rig's table) asks.
        let options = options_for(&rig.solver, n, req.options.as_ref(), None, limits, interrupt)?;
        // Each frame: n angles and n + 1 points.
        recorded_values_cap(n, 3 * n as u64 + 2, &options, 1, MAX_SOLVE_RECORDED_VALUES)?;
        let start = pose_from_degrees(
            rig.skeleton.start_angles(),
            rig.skeleton.limits(),
            req.start_deg.as_deref(),
            "start_deg",
        )?;
        let mut solver = solver(options)?;
        let mut outcome = Outcome::default();
        let started = Instant::now();
        solver
            .solve_rig_into(&rig.skeleton, &start, &task, &mut outcome)
            .map_err(|e| Problem::invalid(e.to_string()))?;
        stopped(interrupt)?;
        let micros = started.elapsed().as_secs_f64() * 1e6;
        json_response(&RigSolveReport { rig: &rig, options: solver.options(), outcome: &outcome, micros }.json())
    }
}

/// One shipped rig.
#[derive(Serialize)]
pub struct Shipped {
    name: &'static str,
    rig: RigJson,
}

#[derive(Serialize)]
struct Rigs {
    rigs: Vec<Shipped>,
}

/// `GET /api/rigs`: `{"rigs": [{"name", "rig"}, …]}`.
pub fn list() -> Result<Reply, Problem> {
    let rigs = SHIPPED
        .iter()
        .map(|(name, text)| {
            let rig = RigJson::parse(text, &format!("examples/rigs/{name}.toml")).map_err(Problem::internal)?;
            Ok(Shipped { name, rig })
        })
        .collect::<Result<Vec<_>, Problem>>()?;
    json_response(&Rigs { rigs })
}

/// The answer of `POST /api/rig/parse`: the rig, or why the text is not a rig file (a 200
/// either way, as `/api/arm/parse`).
#[derive(Debug, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Parsed {
    Rig(RigJson),
    Problem(String),
}

/// `POST /api/rig/parse`: the body is the file's text, of at most `--max-bones` bones (a
/// bigger one is a problem, found before any bone is checked).
pub fn parsed(text: &str, limits: &Limits) -> Parsed {
    match RigJson::parse_within(text, "rig file", BoneCap::flag(limits.max_bones)) {
        Ok(rig) => Parsed::Rig(rig),
        Err(problem) => Parsed::Problem(problem),
    }
}

#[cfg(feature = "render")]
/// The figure `rig`: the rig at `pose_deg` (its start pose by default) with goals and pins.
pub fn figure(
    r: RigFigureReq,
    format: PictureFormat,
    width: u32,
    height: u32,
    limits: &Limits,
    interrupt: &Interrupt,
) -> Result<Vec<u8>, Problem> {
    let rig = load_rig(r.rig, limits)?;
    let task = task(&rig, &r.goals, &r.pins, None, false)?;
    // Degrees say nothing about a slide: a rig with prismatic joints is drawn in the pose its
    // bones' `angle_deg` and `extension` give.
    if r.pose_deg.is_some() {
        for (j, joint) in rig.skeleton.joints().iter().enumerate() {
            match joint {
                ikarus::Joint::Revolute => {}
                ikarus::Joint::Prismatic { .. } => {
                    return Err(Problem::invalid(format!(
                        "pose_deg: bone {:?} is prismatic (its value is a length, not an angle); give the pose as the bones' angle_deg and extension",
                        rig.skeleton.name(j)
                    )));
                }
            }
        }
    }
    let pose =
        pose_from_degrees(rig.skeleton.start_angles(), rig.skeleton.limits(), r.pose_deg.as_deref(), "pose_deg")?;
    let figure = ikarus_render::SkeletonFigure { labels: r.labels, ..rig_figure(&rig, &pose, &task, r.limits, None) };
    picture(draw(&Drawing::Skeleton(figure), format, width, height, &|_, _| {}), interrupt)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What WebAssembly and Python call: the edges' cap on bones (the server's default for
    /// WebAssembly), counted before a bone is checked, for a file's text and a request's rig.
    #[test]
    fn the_edges_count_a_rigs_bones_first() {
        let chain = |n: usize| -> String {
            (0..n)
                .map(|i| format!("[[bones]]\nname = \"b{i}\"\nparent = \"b{}\"\nlength = 1\n", i.max(1) - 1))
                .collect()
        };
        // Bone 0 names itself its parent: a cycle, had the bones been checked.
        let limits = Limits::default();
        let interrupt = Interrupt::new();
        let reply = super::super::call(super::super::Endpoint::RigParse, chain(257).as_bytes(), &limits, &interrupt);
        let answer: serde_json::Value = serde_json::from_slice(&reply.unwrap().body).unwrap();
        assert_eq!(
            answer,
            serde_json::json!({"problem": "rig file: bones: 257 bones exceed the cap of 256 (--max-bones)"})
        );
        let reply = super::super::call(super::super::Endpoint::RigParse, chain(256).as_bytes(), &limits, &interrupt);
        let answer: serde_json::Value = serde_json::from_slice(&reply.unwrap().body).unwrap();
        assert!(answer["problem"].as_str().unwrap().contains("a cycle (b0 → b0)"), "{answer}");
        let file: RigFile = toml::from_str(&chain(300)).unwrap();
        let e = load_rig(file, &Limits { max_bones: 299, ..Limits::default() }).unwrap_err();
        assert_eq!((e.status, e.message.as_str()), (422, "rig: bones: 300 bones exceed the cap of 299 (--max-bones)"));
    }

    /// Every rig file in `examples/rigs/` is shipped, and reads.
    #[test]
    fn every_example_rig_is_shipped() {
        let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/rigs");
        let mut files: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| p.extension().is_some_and(|x| x == "toml"))
            .map(|p| p.file_stem().unwrap().to_str().unwrap().to_owned())
            .collect();
        files.sort();
        let mut shipped: Vec<String> = SHIPPED.iter().map(|(n, _)| (*n).to_owned()).collect();
        shipped.sort();
        assert_eq!(files, shipped);
        for (name, text) in SHIPPED {
            let rig = RigJson::parse(text, name).unwrap();
            assert_eq!(rig.name, *name);
        }
    }
}
