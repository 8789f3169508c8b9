//! The JSON objects that `ikarus solve`, `ikarus animate` and `ikarus workspace` print, and
//! the work behind the last two, shared by the command line and `ikarus serve` so that both
//! answer with the same shapes (degrees at the edge, names matching the arm files).

use ikarus::motion::{Animation, Timing};
use ikarus::reach::Workspace;
use ikarus::{Chain, Ease, Goal, Outcome, SolveOptions, Solver};
use serde::Serialize;

use crate::arm::Arm;
use crate::error::CliError;

#[derive(Serialize)]
pub struct GoalJson {
    pub x: f64,
    pub y: f64,
    pub angle_deg: Option<f64>,
}

#[derive(Serialize)]
pub struct TipJson {
    pub x: f64,
    pub y: f64,
    pub angle_deg: f64,
}

#[derive(Serialize)]
pub struct FrameJson {
    pub iteration: u32,
    pub angles_deg: Vec<f64>,
    pub joints: Vec<[f64; 2]>,
}

/// One solve: `ikarus solve --format json` and `POST /api/solve`.
#[derive(Serialize)]
pub struct SolveJson<'a> {
    pub arm: &'a str,
    pub method: &'static str,
    pub limits: bool,
    /// `ignore` when limits are off.
    pub limit_mode: &'static str,
    pub goal: GoalJson,
    pub status: &'static str,
    pub iterations: u32,
    /// Restarts used (0 when the first attempt ended the solve).
    pub restarts: u32,
    pub error: f64,
    pub angle_error_deg: f64,
    pub tolerance: f64,
    pub solve_us: f64,
    pub end_effector: TipJson,
    pub angles_deg: Vec<f64>,
    pub joints: Vec<[f64; 2]>,
    pub frames: Vec<FrameJson>,
}

pub fn degrees(angles: &[f64]) -> Vec<f64> {
    angles.iter().map(|a| a.to_degrees()).collect()
}

pub fn points(joints: &[ikarus::Point2<f64>]) -> Vec<[f64; 2]> {
    joints.iter().map(|p| [p.x, p.y]).collect()
}

/// A finished single solve and what it needs to be described.
pub struct SolveReport<'a> {
    pub arm: &'a Arm,
    pub options: &'a SolveOptions,
    pub goal: &'a Goal,
    pub outcome: &'a Outcome,
    pub micros: f64,
}

impl<'a> SolveReport<'a> {
    /// The JSON object of one solve.
    pub fn json(&self) -> SolveJson<'a> {
        let o = self.outcome;
        let target = self.goal.target();
        let joints = points(&ikarus::kinematics::joint_positions(&self.arm.chain, o.pose.angles()));
        SolveJson {
            arm: &self.arm.name,
            method: self.options.method.name(),
            limits: self.options.limits != ikarus::LimitMode::Ignore,
            limit_mode: self.options.limits.name(),
            goal: GoalJson { x: target.x, y: target.y, angle_deg: self.goal.orientation().map(f64::to_degrees) },
            status: o.status.as_str(),
            iterations: o.iterations,
            restarts: o.restarts,
            error: o.error,
            angle_error_deg: o.angle_error.to_degrees(),
            tolerance: self.options.tolerance,
            solve_us: self.micros,
            end_effector: TipJson {
                x: o.end_effector.position.x,
                y: o.end_effector.position.y,
                angle_deg: o.end_effector.orientation.to_degrees(),
            },
            angles_deg: degrees(o.pose.angles()),
            joints,
            frames: o
                .frames
                .iter()
                .map(|f| FrameJson { iteration: f.iteration, angles_deg: degrees(f.angles), joints: points(f.joints) })
                .collect(),
        }
    }
}

/// Builds the solver, checking what depends on the chain (one rate per joint).
pub fn solver_for(chain: &Chain, options: SolveOptions) -> Result<Solver, CliError> {
    if !options.rates.is_empty() && options.rates.len() != chain.len() {
        return Err(CliError::input(format!(
            "--rates: expected {} values (one per joint), got {}",
            chain.len(),
            options.rates.len()
        )));
    }
    Solver::new(options).map_err(|e| CliError::input(e.to_string()))
}

/// One goal of a motion: where it was, and how its solve ended.
#[derive(Serialize)]
pub struct MotionSolveJson {
    pub goal: [f64; 2],
    pub status: &'static str,
    pub iterations: u32,
    pub error: f64,
}

#[derive(Serialize)]
pub struct MotionFrameJson {
    pub time: f64,
    pub angles_deg: Vec<f64>,
    pub joints: Vec<[f64; 2]>,
}

/// A motion: `ikarus animate` (JSON) and `POST /api/animate`.
#[derive(Serialize)]
pub struct AnimateJson<'a> {
    pub arm: &'a str,
    pub ease: &'static str,
    pub duration: f64,
    pub solves: Vec<MotionSolveJson>,
    pub frames: Vec<MotionFrameJson>,
}

/// What a motion request asks for once its values are checked.
pub struct MotionRequest<'a> {
    pub arm: &'a Arm,
    /// The pose the motion starts from, radians.
    pub start: Vec<f64>,
    /// Via points, then the final goal.
    pub goals: Vec<Goal>,
    pub options: SolveOptions,
    pub timing: Timing,
    pub ease: Ease,
    /// Follow the solver's recorded path instead of moving straight between solved poses.
    pub from_solve: bool,
}

/// A computed motion.
pub struct Motion {
    pub solver: Solver,
    pub animation: Animation,
    pub solves: Vec<MotionSolveJson>,
}

impl MotionRequest<'_> {
    /// Solves for each via point, then the goal, each from the previous pose, and eases the
    /// poses into a motion.
    pub fn run(self) -> Result<Motion, CliError> {
        let arm = self.arm;
        let mut solver = solver_for(&arm.chain, self.options)?;
        let mut keyframes = vec![self.start];
        let mut path: Vec<Vec<f64>> = vec![keyframes[0].clone()];
        let mut solves = Vec::with_capacity(self.goals.len());
        for goal in &self.goals {
            let start = keyframes.last().expect("the start pose is a keyframe").clone();
            let mut outcome = Outcome::default();
            solver.solve_into(&arm.chain, &start, goal, &mut outcome).map_err(|e| CliError::input(e.to_string()))?;
            let target = goal.target();
            // The solver's recorded path, without repeating the pose it started from.
            path.extend(outcome.frames.iter().skip(1).map(|f| f.angles.to_vec()));
            keyframes.push(outcome.pose.angles().to_vec());
            solves.push(MotionSolveJson {
                goal: [target.x, target.y],
                status: outcome.status.as_str(),
                iterations: outcome.iterations,
                error: outcome.error,
            });
        }
        let poses = if self.from_solve { &path } else { &keyframes };
        // The motion obeys the same limits as the solve: without limits every joint is free.
        let motion_chain = match solver.options().limits {
            ikarus::LimitMode::Ignore => arm.chain.without_limits(),
            _ => arm.chain.clone(),
        };
        let animation = ikarus::motion::animate(&motion_chain, poses, None, self.timing, self.ease)
            .map_err(|e| CliError::input(e.to_string()))?;
        Ok(Motion { solver, animation, solves })
    }
}

impl Motion {
    /// The JSON object of the motion.
    pub fn json<'a>(&'a self, arm: &'a Arm) -> AnimateJson<'a> {
        AnimateJson {
            arm: &arm.name,
            ease: self.animation.ease.name(),
            duration: self.animation.duration,
            solves: self
                .solves
                .iter()
                .map(|s| MotionSolveJson { goal: s.goal, status: s.status, iterations: s.iterations, error: s.error })
                .collect(),
            frames: self
                .animation
                .frames
                .iter()
                .map(|f| MotionFrameJson { time: f.time, angles_deg: degrees(&f.angles), joints: points(&f.joints) })
                .collect(),
        }
    }

    /// The one-line caption of the motion's pictures.
    pub fn caption(&self) -> String {
        let last = self.solves.last().expect("at least the goal was solved");
        let iterations: u32 = self.solves.iter().map(|s| s.iterations).sum();
        format!(
            "{} · {} · {} iterations · error {:.1e} · {} frames, {} ease",
            self.solver.options().method.name(),
            last.status,
            iterations,
            last.error,
            self.animation.frames.len(),
            self.animation.ease.name()
        )
    }
}

/// The reachable region: `ikarus workspace --format json` and `POST /api/workspace`.
#[derive(Serialize)]
pub struct WorkspaceJson<'a> {
    pub arm: &'a str,
    pub limits: bool,
    pub inner_radius: f64,
    pub outer_radius: f64,
    pub annulus_area: f64,
    pub area: f64,
    pub resolution: u32,
    pub cell_size: f64,
    pub origin: [f64; 2],
    /// One string per row of cells, bottom row first, `1` for reachable and `0` for not.
    pub grid: Vec<String>,
}

/// The JSON object of a sampled workspace.
pub fn workspace_json<'a>(arm: &'a Arm, limits: bool, workspace: &Workspace) -> WorkspaceJson<'a> {
    let annulus = workspace.annulus();
    let origin = workspace.origin();
    WorkspaceJson {
        arm: &arm.name,
        limits,
        inner_radius: annulus.inner,
        outer_radius: annulus.outer,
        annulus_area: annulus.area(),
        area: workspace.area(),
        resolution: workspace.resolution(),
        cell_size: workspace.cell_size(),
        origin: [origin.x, origin.y],
        grid: grid_rows(workspace),
    }
}

fn grid_rows(ws: &Workspace) -> Vec<String> {
    (0..ws.resolution())
        .map(|iy| (0..ws.resolution()).map(|ix| if ws.is_occupied(ix, iy) { '1' } else { '0' }).collect())
        .collect()
}

/// The one-line caption of a workspace picture.
pub fn workspace_caption(arm: &Arm, ws: &Workspace) -> String {
    let limits = if ws.limits() && arm.chain.has_limits() { "with limits" } else { "no limits" };
    format!("{} · {limits} · reachable area {:.2} of {:.2}", arm.name, ws.area(), ws.annulus().area())
}
