//! `ikarus render`: the figures of `POST /api/render` from the command line: `arm`, `motion`,
//! `workspace`, `ease` and `rig`, with the flags of the other commands and the same drawings
//! ([`crate::picture`] builds each figure for both).

use std::path::PathBuf;

use clap::{Args, Subcommand};
use ikarus::{EaseKind, RigTask};

use crate::animate::MotionArgs;
use crate::arm::Arm;
use crate::ease_args::EaseArgs;
use crate::error::Error;
use crate::goal_args::{GoalArg, RigTaskArgs, Target, parse_bone_angle, parse_goal};
use crate::options::{parse_finite, parse_point};
use crate::picture::{
    Drawing, PictureArgs, PictureFormat, PictureOut, arm_drawing, draw, draw_for_command, rig_figure, workspace_drawing,
};
use crate::rig::Rig;
use crate::workspace::AreaArgs;

#[derive(Debug, Subcommand)]
pub enum RenderCommand {
    /// Draw the arm in a pose (its start pose by default), with a goal and its reachable area
    #[command(allow_negative_numbers = true)]
    Arm(RenderArmArgs),
    /// Draw a motion as `ikarus animate` computes it: every frame as a ghost (.svg, .png), or
    /// animated (.gif)
    #[command(allow_negative_numbers = true)]
    Motion(Box<RenderMotionArgs>),
    /// Draw the arm over the region its tip can reach, as `ikarus workspace --out` does
    Workspace(RenderWorkspaceArgs),
    /// Plot an ease curve: position and velocity against time (the seed's Figure 10)
    Ease(RenderEaseArgs),
    /// Draw a rig in a pose (its start pose by default), with goals, pins and limit wedges
    #[command(allow_negative_numbers = true)]
    Rig(RenderRigArgs),
}

#[derive(Debug, Args)]
pub struct RenderArmArgs {
    /// Arm file (TOML) [default: the built-in seed arm]
    #[arg(long, value_name = "FILE")]
    pub arm: Option<PathBuf>,
    /// The pose drawn, one angle per joint, degrees [default: the arm's start angles]
    #[arg(long, value_name = "A,B,…", value_delimiter = ',', allow_hyphen_values = true, value_parser = parse_finite)]
    pub pose_deg: Option<Vec<f64>>,
    /// A goal to mark
    #[arg(long, value_name = "X,Y", allow_hyphen_values = true, value_parser = parse_point)]
    pub goal: Option<[f64; 2]>,
    /// Also shade the reachable area: the exact region, or the grid the flags below sample
    #[arg(long)]
    pub workspace: bool,
    #[command(flatten)]
    pub area: AreaArgs,
    #[command(flatten)]
    pub picture: PictureArgs,
}

#[derive(Debug, Args)]
pub struct RenderRigArgs {
    /// Rig file (TOML)
    #[arg(long, value_name = "FILE")]
    pub rig: PathBuf,
    /// The angle of bone NAME, degrees, relative to its parent (repeatable); the other bones
    /// keep their start angles
    #[arg(long, value_name = "NAME=DEG", allow_hyphen_values = true, value_parser = parse_bone_angle)]
    pub pose_deg: Vec<(String, f64)>,
    /// A goal to mark: the tip of bone NAME at X,Y, pointing DEG degrees from +x (repeatable)
    #[arg(long, value_name = "NAME=X,Y[,DEG]", allow_hyphen_values = true, value_parser = parse_goal)]
    pub goal: Vec<GoalArg>,
    /// A pinned tip to mark (repeatable)
    #[arg(long, value_name = "NAME")]
    pub pin: Vec<String>,
    /// Draw each limited bone's range as a wedge at its joint
    #[arg(long)]
    pub limits: bool,
    /// Write each bone's name beside it
    #[arg(long)]
    pub labels: bool,
    #[command(flatten)]
    pub picture: PictureArgs,
}

#[derive(Debug, Args)]
pub struct RenderMotionArgs {
    #[command(flatten)]
    pub motion: MotionArgs,
    #[command(flatten)]
    pub picture: PictureArgs,
}

#[derive(Debug, Args)]
pub struct RenderWorkspaceArgs {
    /// Arm file (TOML) [default: the built-in seed arm]
    #[arg(long, value_name = "FILE")]
    pub arm: Option<PathBuf>,
    #[command(flatten)]
    pub area: AreaArgs,
    #[command(flatten)]
    pub picture: PictureArgs,
}

#[derive(Debug, Args)]
pub struct RenderEaseArgs {
    #[command(flatten)]
    pub ease: EaseArgs,
    #[command(flatten)]
    pub picture: PictureArgs,
}

pub fn run(command: &RenderCommand) -> Result<(), Error> {
    let still = [PictureFormat::Svg, PictureFormat::Png];
    match command {
        RenderCommand::Arm(args) => {
            let out = required_out(&args.picture, &still)?;
            let arm = Arm::load(args.arm.as_deref())?;
            let pose = pose(&arm, args.pose_deg.as_deref())?;
            let workspace = if args.workspace { Some(args.area.area(&arm)?) } else { None };
            let goal = args.goal.map(|[x, y]| ikarus::Point2::new(x, y));
            let drawing = arm_drawing(&arm, &pose, goal, workspace.as_ref());
            still_picture(&drawing, out, &args.picture)
        }
        RenderCommand::Motion(args) => {
            let out = required_out(&args.picture, &[PictureFormat::Svg, PictureFormat::Png, PictureFormat::Gif])?;
            let run = crate::animate::motion(&args.motion)?;
            let bytes = draw_for_command(&run.drawing(), out.format, &args.picture, run.frames())?;
            out.commit(&bytes)
        }
        RenderCommand::Workspace(args) => {
            let out = required_out(&args.picture, &still)?;
            let arm = Arm::load(args.arm.as_deref())?;
            let area = args.area.area(&arm)?;
            still_picture(&workspace_drawing(&arm, &area), out, &args.picture)
        }
        RenderCommand::Ease(args) => {
            let out = required_out(&args.picture, &still)?;
            let ease = args.ease.resolve(EaseKind::Parent)?;
            still_picture(&Drawing::Ease(ease), out, &args.picture)
        }
        RenderCommand::Rig(args) => {
            let out = required_out(&args.picture, &still)?;
            let rig = crate::body::load_rig(&args.rig)?;
            let pose = rig_pose(&rig, &args.pose_deg)?;
            let targets = args.goal.iter().map(|g| Target::of(g, &rig)).collect::<Result<Vec<_>, _>>()?;
            let task = if targets.is_empty() && args.pin.is_empty() {
                RigTask::default()
            } else {
                RigTaskArgs { pin: args.pin.clone(), ..RigTaskArgs::default() }.task(&rig.skeleton, &targets)?
            };
            let figure = ikarus_render::SkeletonFigure {
                labels: args.labels,
                ..rig_figure(&rig, &pose, &task, args.limits, None)
            };
            still_picture(&Drawing::Skeleton(figure), out, &args.picture)
        }
    }
}

/// `--out`, which every figure needs, checked against the formats it can be drawn in.
fn required_out(picture: &PictureArgs, allowed: &[PictureFormat]) -> Result<PictureOut, Error> {
    let names: Vec<&str> = allowed.iter().map(|f| f.extension()).collect();
    picture
        .prepare(allowed)?
        .ok_or_else(|| Error::input(format!("--out: required: the file to draw to ({})", names.join(", "))))
}

fn still_picture(drawing: &Drawing<'_>, out: PictureOut, picture: &PictureArgs) -> Result<(), Error> {
    let bytes = draw(drawing, out.format, picture.size.width, picture.size.height, &|_, _| {})?;
    out.commit(&bytes)
}

/// The rig's start pose with the angles of `--pose-deg NAME=DEG` (normalised as a rig file's
/// start angles), in radians.
fn rig_pose(rig: &Rig, angles: &[(String, f64)]) -> Result<Vec<f64>, Error> {
    let s = &rig.skeleton;
    let mut pose = s.start_angles().to_vec();
    let mut given = vec![false; s.len()];
    for (name, deg) in angles {
        let flag = format!("--pose-deg {name}={deg}");
        let i = crate::goal::index(s, name).map_err(|m| Error::input(format!("{flag}: {m}")))?;
        if std::mem::replace(&mut given[i], true) {
            return Err(Error::input(format!("{flag}: bone {name:?} given twice")));
        }
        match s.joints()[i] {
            ikarus::Joint::Revolute => {}
            ikarus::Joint::Prismatic { .. } => {
                return Err(Error::input(format!(
                    "{flag}: bone {name:?} is prismatic (its value is a length, not an angle); set its extension in the rig file"
                )));
            }
        }
        let limits = s.limits()[i].map(|l| [l.min().to_degrees(), l.max().to_degrees()]);
        pose[i] = crate::arm::start_angle(*deg, limits).to_radians();
    }
    Ok(pose)
}

/// The pose of `--pose-deg` in radians (one angle per joint, within any ranges the arm has),
/// or the arm's start pose.
fn pose(arm: &Arm, pose_deg: Option<&[f64]>) -> Result<Vec<f64>, Error> {
    let Some(deg) = pose_deg else { return Ok(arm.chain.start_pose().angles().to_vec()) };
    let n = arm.chain.len();
    if deg.len() != n {
        return Err(Error::input(format!("--pose-deg: expected {n} angles (one per joint), got {}", deg.len())));
    }
    Ok(deg.iter().map(|a| a.to_radians()).collect())
}
