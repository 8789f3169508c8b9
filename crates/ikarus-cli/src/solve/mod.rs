//! `ikarus solve`: one goal (JSON, CSV or text), or a batch of goals from a CSV file; with
//! `--rig FILE`, goals on the tips of a rig's bones and pins, solved together from the rig's
//! start pose, or a batch of target sets. One command, one reader of the body ([`Body`]).
//!
//! By concern: the flags and the dispatch here; the single solve of either body
//! ([`single`]); its answers for people and for CSV ([`write`]); the batches ([`batch`]) and
//! the goal columns of a rig's batch file ([`columns`]).

use std::path::PathBuf;

use clap::{Args, ValueEnum};

use crate::body::Body;
use crate::body_args::{BodyArgs, BodyHelp};
use crate::error::Error;
use crate::goal_args::{GoalArg, parse_goal};
use crate::options::{parse_angle, parse_at_least_one};
use crate::picture::StillArgs;

mod batch;
mod character;
mod columns;
mod single;
mod write;

pub use write::write_pose;

// Floats in CSV are written with `{:?}`: the shortest text that reads back to the same
// number, in scientific notation where that is shorter (1.2e-7, not 0.00000012).

/// Output format of a single solve.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Format {
    /// One JSON object (the default when stdout is not a terminal).
    Json,
    /// The recorded frames, one row each.
    Csv,
    /// A short report for people (the default on a terminal).
    Text,
}

/// Move the arm's tip to a goal and report the pose, or solve a batch of goals; with `--rig`,
/// the same for goals on the tips of a rig's bones, solved together.
#[derive(Debug, Args)]
pub struct SolveArgs {
    /// Goal position of the tip; with --rig, NAME=X,Y[,DEG]: the tip of bone NAME at X,Y (and
    /// pointing DEG degrees from +x), repeatable
    #[arg(long, value_name = "X,Y", allow_hyphen_values = true, value_parser = parse_goal,
          required_unless_present_any = ["batch", "rig"])]
    pub goal: Vec<GoalArg>,
    /// Goal orientation of the last link, degrees from +x (counter-clockwise)
    #[arg(long, value_name = "DEG", allow_hyphen_values = true, value_parser = parse_angle,
          conflicts_with_all = ["batch", "rig"])]
    pub goal_angle: Option<f64>,
    #[command(flatten)]
    pub body: BodyArgs<SolveBody>,
    /// Record a frame every K iterations, plus the first and the last [default: 20; with
    /// --rig, none]
    #[arg(long, value_name = "K", value_parser = parse_at_least_one)]
    pub record_every: Option<u32>,
    /// Output format on stdout [default: text on a terminal, json otherwise; nothing with --out]
    #[arg(long, value_enum, conflicts_with = "batch")]
    pub format: Option<Format>,
    /// Solve every goal of a CSV file (header `x,y` or `x,y,angle_deg`; with --rig, `NAME.x,NAME.y`
    /// and optionally `NAME.angle_deg` per goal) from the start pose; one CSV row per goal (or
    /// target set) on stdout, a summary on stderr
    #[arg(long, value_name = "GOALS.csv", conflicts_with = "goal")]
    pub batch: Option<PathBuf>,
    /// Threads for --batch [default: all cores]
    #[arg(long, value_name = "N", value_parser = parse_threads)]
    pub threads: Option<usize>,
    /// Also write the batch summary as JSON to PATH
    #[arg(long, value_name = "PATH")]
    pub summary_json: Option<PathBuf>,
    /// With a character file (--rig FILE.json): how many bones the goal on bone NAME turns,
    /// counted up from it [default: 2, the bone and its parent]
    #[arg(long, value_name = "NAME=N", value_parser = parse_bones)]
    pub bones: Vec<(String, usize)>,
    /// With a character file: an IK file (TOML) adding pins, longer limbs, weights, joint limits
    /// and stiffness to its constraints (see ikarus pose --ik-file)
    #[arg(long, value_name = "FILE")]
    pub ik_file: Option<PathBuf>,
    #[command(flatten)]
    pub picture: StillArgs,
}

/// `NAME=N`, N ≥ 1.
fn parse_bones(s: &str) -> Result<(String, usize), Error> {
    let (name, n) = s.rsplit_once('=').ok_or_else(|| Error::input(format!("expected NAME=N, got {s:?}")))?;
    if name.trim().is_empty() {
        return Err(Error::input("NAME=N: the bone's name is empty"));
    }
    let n = parse_at_least_one(n).map_err(|m| Error::input(format!("{name}: {m}")))?;
    Ok((name.trim().to_owned(), n as usize))
}

fn parse_threads(s: &str) -> Result<usize, Error> {
    let n = parse_at_least_one(s)? as usize;
    if n > 1024 { Err(Error::input(format!("{n}: must be at most 1024"))) } else { Ok(n) }
}

/// The help of `ikarus solve`'s `--arm` and `--rig`.
#[derive(Debug)]
pub struct SolveBody;

impl BodyHelp for SolveBody {
    const ARM: &'static str = "Arm file (TOML) [default: the built-in seed arm, lengths 3, 2, 1]";
    const RIG: &'static str = "Rig file (TOML): a tree of named bones; its goals (--goal NAME=X,Y) and pins (--pin NAME) are solved together; or a character file (Spine, DragonBones JSON): the goals solved with its IK constraints by ikarus's solver";
}

pub fn run(args: &SolveArgs) -> Result<(), Error> {
    if let Some(file) = crate::character_motion::character(args.body.rig.as_deref()) {
        return character::run(args, &file?);
    }
    crate::character_motion::refuse_without(&[
        ("--bones", !args.bones.is_empty()),
        ("--ik-file", args.ik_file.is_some()),
    ])?;
    if args.batch.is_none() {
        if let Some(n) = args.threads {
            return Err(Error::input(format!("--threads {n}: only applies with --batch")));
        }
        if let Some(p) = &args.summary_json {
            return Err(Error::input(format!("--summary-json {}: only applies with --batch", p.display())));
        }
    } else if let Some(p) = &args.picture.out {
        return Err(Error::input(format!("--out {}: only applies to a single solve, not --batch", p.display())));
    }
    match (args.body.load()?, &args.batch) {
        (Body::Chain(arm), Some(path)) => batch::run_batch(args, &arm, path),
        (Body::Rig(rig), Some(path)) => batch::run_rig_batch(args, &rig, path),
        (body, None) => single::run(args, &body),
    }
}
