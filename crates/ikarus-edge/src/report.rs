//! The JSON objects that `ikarus solve`, `ikarus animate`, `ikarus workspace` and `ikarus reach`
//! print, shared by the command line and `ikarus serve` so that both answer with the same
//! shapes (degrees at the edge, names matching the arm files). Shapes only: the work is done elsewhere.

use ikarus::motion::GoalMotion;
use ikarus::reach::{Annulus, BoundarySegment, Verdict, Workspace};
use ikarus::{Goal, Outcome, SolveOptions};
use serde::Serialize;

use crate::area::ReachableArea;
use crate::arm::Arm;

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
    /// With limits on: the distance from the goal to the exact reachable region (0 inside);
    /// `null` when no verdict was made.
    pub reach_distance: Option<f64>,
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
            reach_distance: o.reach_distance,
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

impl<'a> AnimateJson<'a> {
    /// The JSON object of a motion of `arm`.
    pub fn new(arm: &'a Arm, motion: &GoalMotion) -> Self {
        AnimateJson {
            arm: &arm.name,
            ease: motion.animation.ease.name(),
            duration: motion.animation.duration,
            solves: motion
                .solves
                .iter()
                .map(|s| {
                    let target = s.goal.target();
                    MotionSolveJson {
                        goal: [target.x, target.y],
                        status: s.status.as_str(),
                        iterations: s.iterations,
                        error: s.error,
                    }
                })
                .collect(),
            frames: motion
                .animation
                .frames
                .iter()
                .map(|f| MotionFrameJson { time: f.time, angles_deg: degrees(&f.angles), joints: points(&f.joints) })
                .collect(),
        }
    }
}

/// The reachable region: `ikarus workspace --format json` and `POST /api/workspace`. The exact
/// region gives `boundary` (and `curves`, for a region without area); the grid (`--grid`)
/// gives `resolution`, `cell_size`, `origin` and `grid` instead.
#[derive(Serialize)]
pub struct WorkspaceJson<'a> {
    pub arm: &'a str,
    pub limits: bool,
    /// Whether `area` and the boundary are the exact region's (not a sampled grid's).
    pub exact: bool,
    pub inner_radius: f64,
    pub outer_radius: f64,
    pub annulus_area: f64,
    pub area: f64,
    /// Closed loops of segments, outer boundaries counter-clockwise, holes clockwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub boundary: Option<Vec<Vec<SegmentJson>>>,
    /// The curves a region without area is made of (empty for a region with area).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub curves: Option<Vec<SegmentJson>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub resolution: Option<u32>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cell_size: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub origin: Option<[f64; 2]>,
    /// One string per row of cells, bottom row first, `1` for reachable and `0` for not.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub grid: Option<Vec<String>>,
}

/// One boundary segment: `{"line": [[x0, y0], [x1, y1]]}` or `{"arc": {"center": [cx, cy],
/// "radius": r, "from_deg": a0, "to_deg": a1}}` (counter-clockwise when `to_deg > from_deg`).
#[derive(Serialize)]
#[serde(rename_all = "lowercase")]
pub enum SegmentJson {
    Line([[f64; 2]; 2]),
    Arc(ArcJson),
}

#[derive(Serialize)]
pub struct ArcJson {
    pub center: [f64; 2],
    pub radius: f64,
    pub from_deg: f64,
    pub to_deg: f64,
}

impl SegmentJson {
    /// The segment with its angles in degrees.
    pub fn of(s: &BoundarySegment) -> Self {
        match *s {
            BoundarySegment::Line { from, to } => SegmentJson::Line([[from.x, from.y], [to.x, to.y]]),
            BoundarySegment::Arc { center, radius, from_angle, to_angle } => SegmentJson::Arc(ArcJson {
                center: [center.x, center.y],
                radius,
                from_deg: from_angle.to_degrees(),
                to_deg: to_angle.to_degrees(),
            }),
        }
    }
}

/// The JSON object of a reachable area of `arm`, exact or sampled.
pub fn workspace_json<'a>(arm: &'a Arm, area: &ReachableArea) -> WorkspaceJson<'a> {
    let annulus = Annulus::of(&arm.chain);
    let base = WorkspaceJson {
        arm: &arm.name,
        limits: area.limits(),
        exact: matches!(area, ReachableArea::Exact(_)),
        inner_radius: annulus.inner,
        outer_radius: annulus.outer,
        annulus_area: annulus.area(),
        area: area.area(),
        boundary: None,
        curves: None,
        resolution: None,
        cell_size: None,
        origin: None,
        grid: None,
    };
    match area {
        ReachableArea::Exact(region) => WorkspaceJson {
            boundary: Some(region.boundary().iter().map(|l| l.iter().map(SegmentJson::of).collect()).collect()),
            curves: Some(region.curves().iter().map(SegmentJson::of).collect()),
            ..base
        },
        ReachableArea::Grid(ws) => {
            let origin = ws.origin();
            WorkspaceJson {
                resolution: Some(ws.resolution()),
                cell_size: Some(ws.cell_size()),
                origin: Some([origin.x, origin.y]),
                grid: Some(grid_rows(ws)),
                ..base
            }
        }
    }
}

fn grid_rows(ws: &Workspace) -> Vec<String> {
    (0..ws.resolution())
        .map(|iy| (0..ws.resolution()).map(|ix| if ws.is_occupied(ix, iy) { '1' } else { '0' }).collect())
        .collect()
}

/// One point's verdict: `ikarus reach --format json` and `POST /api/reach`.
#[derive(Serialize)]
pub struct VerdictJson {
    /// Inside the region, or within the tolerance of it.
    pub reachable: bool,
    /// Distance to the region, 0 inside.
    pub distance: f64,
    /// The nearest reachable point: the point itself inside.
    pub nearest: [f64; 2],
}

impl VerdictJson {
    /// The JSON object of a verdict.
    pub fn of(v: &Verdict) -> Self {
        VerdictJson { reachable: v.reachable, distance: v.distance, nearest: [v.nearest.x, v.nearest.y] }
    }
}

/// An angle in radians as degrees for people: normalised into (−180°, 180°], with `decimals`
/// decimals and the `°` sign, and never `-0.000°` (a value that rounds to zero, or to −180°,
/// prints as 0 or 180).
pub fn deg_text(radians: f64, decimals: usize) -> String {
    let deg = ikarus::angle::wrap_angle(radians).to_degrees();
    let deg = if deg <= -180.0 { deg + 360.0 } else { deg };
    let text = format!("{deg:.decimals$}");
    match text.strip_prefix('-') {
        Some(abs) if abs.parse::<f64>().is_ok_and(|v| v == 0.0 || v == 180.0) => format!("{abs}°"),
        _ => format!("{text}°"),
    }
}

#[cfg(test)]
mod tests {
    use super::deg_text;

    #[test]
    fn angles_for_people_are_in_the_half_open_circle_without_negative_zero() {
        let cases = [
            (0.0, "0.000°"),
            (-0.0, "0.000°"),
            (-1e-9, "0.000°"),
            (-214.371, "145.629°"),
            (180.0, "180.000°"),
            (-180.0, "180.000°"),
            (-179.99999, "180.000°"),
            (540.0, "180.000°"),
            (-90.0, "-90.000°"),
            (359.9996, "0.000°"),
            (1e20, "-" /* any value, but one in range */),
        ];
        for (deg, want) in cases {
            let got = deg_text(f64::to_radians(deg), 3);
            if want == "-" {
                let v: f64 = got.trim_end_matches('°').parse().unwrap();
                assert!(v > -180.0 && v <= 180.0, "{deg} -> {got}");
            } else {
                assert_eq!(got, want, "{deg}");
            }
        }
    }
}
