//! `ikarus reach`: whether the tip can reach a point, how far the point is from the exact
//! reachable region, and the nearest reachable point; for one point (`--point`) or every row of
//! a CSV file (`--batch`). The region is built once per run ([`ReachRequest::region`], shared
//! with `POST /api/reach`), and each answer is [`crate::report::VerdictJson`] in JSON.

use std::io::{IsTerminal, Write};
use std::path::PathBuf;

use clap::{Args, ValueEnum};
use ikarus::reach::Verdict;
pub use ikarus_edge::reach::*;

use crate::arm::Arm;
use crate::error::Error;
use crate::options::{parse_point, parse_positive};
use crate::output::{self, PendingFile};
use crate::report::VerdictJson;
use crate::settings::LimitsArgs;

/// Output format of `ikarus reach`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum ReachFormat {
    /// `reachable`, `distance` and `nearest`, one a line (a single point only)
    Text,
    /// An object `{"reachable", "distance", "nearest"}`; with --batch, an array of them
    Json,
    /// A header `x,y,reachable,distance,nearest_x,nearest_y` and one row per point
    Csv,
}

/// Whether the arm's tip can reach a point: `reachable`, the `distance` to the reachable
/// region (0 inside) and the `nearest` reachable point.
#[derive(Debug, Args)]
pub struct ReachArgs {
    /// The point asked about
    #[arg(long, value_name = "X,Y", allow_hyphen_values = true, value_parser = parse_point,
          required_unless_present = "batch", conflicts_with = "batch")]
    pub point: Option<[f64; 2]>,
    /// Every point of a CSV file (header `x,y`), in order: one CSV row per point on stdout
    #[arg(long, value_name = "POINTS.csv")]
    pub batch: Option<PathBuf>,
    /// Arm file (TOML) [default: the built-in seed arm]
    #[arg(long, value_name = "FILE")]
    pub arm: Option<PathBuf>,
    #[command(flatten)]
    pub limits: LimitsArgs,
    /// Distance from the region that still counts as reachable, > 0 [default: the arm file's
    /// [solver] tolerance, else the solver's, 1e-6]
    #[arg(long, value_parser = parse_positive)]
    pub tolerance: Option<f64>,
    /// Output format [default: text on a terminal, json otherwise; csv with --batch]
    #[arg(long, value_enum)]
    pub format: Option<ReachFormat>,
    /// Write the output to FILE instead of stdout (whole or not at all)
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
}

pub fn run(args: &ReachArgs) -> Result<(), Error> {
    let arm = Arm::load(args.arm.as_deref())?;
    let (points, single) = match (&args.batch, args.point) {
        (Some(path), _) => (crate::goals::read_points(path, &format!("batch file {}", path.display()))?, false),
        (None, Some(p)) => (vec![p], true),
        (None, None) => return Err(Error::input("--point X,Y or --batch POINTS.csv: give one")),
    };
    let format = match args.format {
        Some(ReachFormat::Text) if !single => {
            return Err(Error::input("--format text: only for a single --point (use csv or json with --batch)"));
        }
        Some(f) => f,
        None if !single => ReachFormat::Csv,
        None if args.out.is_none() && std::io::stdout().is_terminal() => ReachFormat::Text,
        None => ReachFormat::Json,
    };
    let file = args.out.as_deref().map(|p| PendingFile::create(p, "--out")).transpose()?;
    let request = ReachRequest { limits: args.limits.asked(), tolerance: args.tolerance };
    let region = request.region(&arm, None)?;
    let tolerance = request.tolerance(&arm);
    let verdicts: Vec<Verdict> = points.iter().map(|&p| verdict(&region, p, tolerance)).collect();
    let write = |w: &mut dyn Write| write(w, format, single, &points, &verdicts);
    match file {
        Some(file) => {
            let mut bytes = Vec::new();
            write(&mut bytes).map_err(|e| Error::runtime(format!("cannot format the output: {e}")))?;
            file.commit(&bytes)
        }
        None => output::stdout(write),
    }
}

fn write(
    w: &mut dyn Write,
    format: ReachFormat,
    single: bool,
    points: &[[f64; 2]],
    verdicts: &[Verdict],
) -> std::io::Result<()> {
    match format {
        ReachFormat::Json if single => serde_json::to_writer(&mut *w, &VerdictJson::of(&verdicts[0]))?,
        ReachFormat::Json => {
            serde_json::to_writer(&mut *w, &verdicts.iter().map(VerdictJson::of).collect::<Vec<_>>())?;
        }
        ReachFormat::Text => {
            let v = &verdicts[0];
            writeln!(w, "reachable  {}", v.reachable)?;
            writeln!(w, "distance   {}", v.distance)?;
            return writeln!(w, "nearest    [{}, {}]", v.nearest.x, v.nearest.y);
        }
        // Floats as `{:?}`, as `solve --batch` writes them: the shortest text that reads back
        // to the same number.
        ReachFormat::Csv => {
            writeln!(w, "x,y,reachable,distance,nearest_x,nearest_y")?;
            for (p, v) in points.iter().zip(verdicts) {
                writeln!(
                    w,
                    "{:?},{:?},{},{:?},{:?},{:?}",
                    p[0], p[1], v.reachable, v.distance, v.nearest.x, v.nearest.y
                )?;
            }
            return Ok(());
        }
    }
    writeln!(w)
}
