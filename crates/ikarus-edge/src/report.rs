//! The JSON objects that `ikarus solve`, `ikarus animate`, `ikarus workspace` and `ikarus reach`
//! print, shared by the command line and `ikarus serve` so that both answer with the same
//! shapes (degrees at the edge, names matching the arm files). Shapes only: the work is done elsewhere.
//!
//! A rig's objects (`ikarus solve --rig --format json`, `POST /api/solve` with `rig`,
//! `GET /api/rigs`, `POST /api/rig/parse`) are the same shapes with bones by name: objects keyed
//! by bone name in the rig's (file) order.

use ikarus::motion::GoalMotion;
use ikarus::reach::{Annulus, BoundarySegment, Verdict, Workspace};
use ikarus::{Goal, Outcome, Point2, SolveOptions};
use serde::Serialize;
use serde::ser::{SerializeMap, Serializer};

use crate::area::ReachableArea;
use crate::arm::Arm;
use crate::rig::{BoneCap, Rig, RigFile};

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
pub struct FrameJson<'a> {
    pub iteration: u32,
    pub angles_deg: Vec<f64>,
    /// A rig's prismatic bones' displacements at this frame; only when it has any.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub extensions: Option<Extensions<'a>>,
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
    pub frames: Vec<FrameJson<'a>>,
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
                .map(|f| FrameJson {
                    iteration: f.iteration,
                    angles_deg: degrees(f.angles),
                    extensions: None,
                    joints: points(f.joints),
                })
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
    /// A rig's (or an arm with slides') effector bone, whose tip's region is sampled.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub bone: Option<&'a str>,
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
    area_json(&arm.name, Annulus::of(&arm.chain), area)
}

/// The JSON object of the sampled region of the tip of bone `bone` of `rig`
/// ([`ikarus::reach::sample_skeleton`]): `"exact": false`, the radii of the disk no tip leaves
/// (inner radius 0), and the grid.
pub fn rig_workspace_json(rig: &Rig, bone: usize, workspace: Workspace) -> WorkspaceJson<'_> {
    let disk = workspace.annulus();
    let json = area_json(&rig.name, disk, &ReachableArea::Grid(workspace));
    WorkspaceJson { bone: Some(rig.skeleton.name(bone)), ..json }
}

/// The JSON object of a reachable area of the body named `name`, `annulus` the region with
/// every joint free.
fn area_json<'a>(name: &'a str, annulus: Annulus, area: &ReachableArea) -> WorkspaceJson<'a> {
    let base = WorkspaceJson {
        arm: name,
        bone: None,
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

/// Values keyed by bone name, written as a JSON object in the rig's order (a map type would
/// sort the names).
pub struct ByName<'a, T> {
    pub names: &'a [String],
    pub values: Vec<T>,
}

impl<T: Serialize> Serialize for ByName<'_, T> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(Some(self.values.len()))?;
        for (name, value) in self.names.iter().zip(&self.values) {
            map.serialize_entry(name, value)?;
        }
        map.end()
    }
}

/// One effector of a rig solve: a goal, or a pin (held where it started).
#[derive(serde::Serialize)]
pub struct EffectorJson<'a> {
    pub name: &'a str,
    pub pinned: bool,
    pub status: &'static str,
    pub error: f64,
    pub angle_error_deg: f64,
    pub tip: [f64; 2],
    pub target: [f64; 2],
}

impl<'a> EffectorJson<'a> {
    /// The JSON of effector `e` of a solve on `skeleton`.
    pub fn of(skeleton: &'a ikarus::Skeleton, e: &ikarus::EffectorOutcome) -> Self {
        EffectorJson {
            name: skeleton.name(e.bone),
            pinned: e.pinned,
            status: e.status.as_str(),
            error: e.error,
            angle_error_deg: e.angle_error.to_degrees(),
            tip: [e.tip.x, e.tip.y],
            target: [e.target.x, e.target.y],
        }
    }
}

/// One rig solve: `ikarus solve --rig … --format json` and `POST /api/solve` with `rig`.
#[derive(serde::Serialize)]
pub struct RigSolveJson<'a> {
    pub rig: &'a str,
    pub method: &'static str,
    pub limits: bool,
    /// `ignore` when limits are off.
    pub limit_mode: &'static str,
    /// `reached` only if every effector is.
    pub status: &'static str,
    pub iterations: u32,
    pub restarts: u32,
    /// The largest effector error.
    pub error: f64,
    /// The largest effector orientation error, degrees.
    pub angle_error_deg: f64,
    pub tolerance: f64,
    pub solve_us: f64,
    /// Goals in the task's order, then pins.
    pub effectors: Vec<EffectorJson<'a>>,
    /// Bone name → its angle (relative to its parent), degrees (a prismatic bone's fixed one).
    pub angles_deg: ByName<'a, f64>,
    /// Prismatic bone name → its displacement; only when the rig has prismatic joints.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub extensions: Option<Extensions<'a>>,
    /// Bone name → its tip.
    pub joints: ByName<'a, [f64; 2]>,
    /// Recorded frames (empty unless recording is asked): angles in bone order, and the base
    /// then every bone's tip.
    pub frames: Vec<FrameJson<'a>>,
}

/// A finished rig solve and what it needs to be described.
pub struct RigSolveReport<'a> {
    pub rig: &'a Rig,
    pub options: &'a SolveOptions,
    pub outcome: &'a Outcome,
    pub micros: f64,
}

impl<'a> RigSolveReport<'a> {
    /// The JSON object of one rig solve.
    pub fn json(&self) -> RigSolveJson<'a> {
        let o = self.outcome;
        let s = &self.rig.skeleton;
        let names = s.names();
        RigSolveJson {
            rig: &self.rig.name,
            method: self.options.method.name(),
            limits: self.options.limits != ikarus::LimitMode::Ignore,
            limit_mode: self.options.limits.name(),
            status: o.status.as_str(),
            iterations: o.iterations,
            restarts: o.restarts,
            error: o.error,
            angle_error_deg: o.angle_error.to_degrees(),
            tolerance: self.options.tolerance,
            solve_us: self.micros,
            effectors: o.effectors.iter().map(|e| EffectorJson::of(s, e)).collect(),
            angles_deg: ByName { names, values: relative_degrees(s, o.pose.angles()) },
            extensions: Extensions::of(s, o.pose.angles()),
            joints: ByName { names, values: points(&tips(self.rig, o.pose.angles())) },
            frames: o
                .frames
                .iter()
                .map(|f| FrameJson {
                    iteration: f.iteration,
                    angles_deg: relative_degrees(s, f.angles),
                    extensions: Extensions::of(s, f.angles),
                    joints: points(f.joints),
                })
                .collect(),
        }
    }
}

/// Every bone's angle from its parent's direction at joint values `q`, degrees: the joint
/// value of a revolute bone, the fixed angle of a prismatic one (the same bits as
/// `degrees` for a rig without prismatic joints).
pub fn relative_degrees(s: &ikarus::Skeleton, q: &[f64]) -> Vec<f64> {
    q.iter().enumerate().map(|(j, &v)| s.relative_angle(j, v).to_degrees()).collect()
}

/// The displacements of a rig's prismatic bones, keyed by name in the rig's order.
pub struct Extensions<'a> {
    pub skeleton: &'a ikarus::Skeleton,
    /// Every bone's joint value.
    pub values: Vec<f64>,
}

impl<'a> Extensions<'a> {
    /// The displacements at joint values `q`: `None` for a skeleton without prismatic joints,
    /// so that its answers carry no `extensions` (and stay what they were before joint kinds).
    pub fn of(skeleton: &'a ikarus::Skeleton, q: &[f64]) -> Option<Self> {
        skeleton.has_prismatic().then(|| Self { skeleton, values: q.to_vec() })
    }
}

/// The CSV columns of a rig's pose: `NAME_deg` for every bone (its angle from its parent's
/// direction), then `NAME_ext` for every prismatic bone (its displacement), in the rig's order.
pub fn pose_columns(s: &ikarus::Skeleton) -> Vec<String> {
    let angles = s.names().iter().map(|n| format!("{n}_deg"));
    let prismatic = |(j, n): (usize, &String)| match s.joint(j) {
        ikarus::Joint::Revolute => None,
        ikarus::Joint::Prismatic { .. } => Some(format!("{n}_ext")),
    };
    angles.chain(s.names().iter().enumerate().filter_map(prismatic)).collect()
}

/// The values under [`pose_columns`] at joint values `q`.
pub fn pose_values(s: &ikarus::Skeleton, q: &[f64]) -> Vec<f64> {
    let prismatic = |(j, &v): (usize, &f64)| match s.joint(j) {
        ikarus::Joint::Revolute => None,
        ikarus::Joint::Prismatic { .. } => Some(v),
    };
    relative_degrees(s, q).into_iter().chain(q.iter().enumerate().filter_map(prismatic)).collect()
}

impl Serialize for Extensions<'_> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(None)?;
        for (j, joint) in self.skeleton.joints().iter().enumerate() {
            match joint {
                ikarus::Joint::Revolute => {}
                ikarus::Joint::Prismatic { .. } => map.serialize_entry(self.skeleton.name(j), &self.values[j])?,
            }
        }
        map.end()
    }
}

/// Every bone's tip at `angles`, in the rig's order.
pub fn tips(rig: &Rig, angles: &[f64]) -> Vec<Point2<f64>> {
    let s = &rig.skeleton;
    let mut points = vec![Point2::origin(); s.len() + 1];
    let mut directions = vec![0.0; s.len()];
    s.points_into(angles, &mut points, &mut directions);
    points.remove(0);
    points
}

/// A rig file's fields as JSON (the requests' `rig`): `name`, `base`, `bones` (each with
/// `parent`, null for a root, and `limits_deg`, `stiffness`, `rest_deg` and the joint keys
/// `offset`, `joint`, `slide`, `extension`, `limits` when it has them)
/// and, when the file has one, `solver`.
#[derive(Debug, serde::Serialize)]
pub struct RigJson {
    pub name: String,
    pub base: [f64; 2],
    pub bones: Vec<BoneJson>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub solver: Option<serde_json::Value>,
}

#[derive(Debug, serde::Serialize)]
pub struct BoneJson {
    pub name: String,
    pub parent: Option<String>,
    pub length: f64,
    pub angle_deg: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub limits_deg: Option<[f64; 2]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stiffness: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rest_deg: Option<f64>,
    /// The file's joint keys, each only when it has it (so a rig without them reads as before).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub offset: Option<[f64; 2]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub joint: Option<crate::rig::JointFile>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub slide: Option<[f64; 2]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub extension: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub limits: Option<[f64; 2]>,
}

impl RigJson {
    /// The rig of rig-file `text` as JSON, after the CLI's checks (whose one-line message it
    /// returns for a bad file, starting with `label`), under the command line's cap on bones.
    /// The `[solver]` table is carried as written.
    pub fn parse(text: &str, label: &str) -> Result<Self, String> {
        Self::parse_within(text, label, BoneCap::cli())
    }

    /// [`RigJson::parse`] of a rig of at most `cap` bones (counted before anything else).
    pub fn parse_within(text: &str, label: &str, cap: BoneCap) -> Result<Self, String> {
        let file = RigFile::read(text, label, cap).map_err(|e| e.to_string())?;
        Rig::from_file(file.clone(), label, cap).map_err(|e| e.to_string())?;
        let table: toml::Table = toml::from_str(text).map_err(|e| format!("{label}: {e}"))?;
        let solver = match table.get("solver") {
            Some(t) => Some(serde_json::to_value(t).map_err(|e| format!("{label}: [solver]: {e}"))?),
            None => None,
        };
        Ok(Self {
            name: file.name.clone().unwrap_or_else(|| "rig".to_owned()),
            base: file.base.unwrap_or([0.0, 0.0]),
            bones: file
                .bones
                .into_iter()
                .map(|b| BoneJson {
                    name: b.name,
                    parent: b.parent,
                    length: b.length,
                    angle_deg: b.angle_deg,
                    limits_deg: b.limits_deg,
                    stiffness: b.stiffness,
                    rest_deg: b.rest_deg,
                    offset: b.offset,
                    joint: b.joint,
                    slide: b.slide,
                    extension: b.extension,
                    limits: b.limits,
                })
                .collect(),
            solver,
        })
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

#[cfg(test)]
mod rig_tests {
    use super::*;

    #[test]
    fn a_rig_file_as_json_reads_back_as_the_same_rig() {
        let text = "name = \"fork\"\n[[bones]]\nname = \"a.b\"\nlength = 1\nangle_deg = 90\n\
                    [[bones]]\nname = \"c\"\nparent = \"a.b\"\nlength = 0.5\nlimits_deg = [-10, 20]\n\
                    [solver]\nmethod = \"dls\"\nrates = [1, 0.5]\n";
        let json = serde_json::to_value(RigJson::parse(text, "r").unwrap()).unwrap();
        assert_eq!(
            json,
            serde_json::json!({"name": "fork", "base": [0.0, 0.0], "bones": [
                {"name": "a.b", "parent": null, "length": 1.0, "angle_deg": 90.0},
                {"name": "c", "parent": "a.b", "length": 0.5, "angle_deg": 0.0, "limits_deg": [-10.0, 20.0]}],
                "solver": {"method": "dls", "rates": [1, 0.5]}})
        );
        let file: RigFile = serde_json::from_value(json).unwrap();
        let rig = Rig::from_file(file, "r", BoneCap::cli()).unwrap();
        assert_eq!(rig.skeleton.names(), &["a.b", "c"]);
        assert_eq!(rig.solver.rates, Some(vec![1.0, 0.5]));
        let e = RigJson::parse("[[bones]]\nname = \"a\"\nparent = \"b\"\nlength = 1\n", "rig file").unwrap_err();
        assert_eq!(e, "rig file: bones[0] (\"a\").parent = \"b\": no bone of that name");
    }

    #[test]
    fn objects_by_name_keep_the_rigs_order() {
        let names = ["z".to_owned(), "a".to_owned(), "m".to_owned()];
        let text = serde_json::to_string(&ByName { names: &names, values: vec![1, 2, 3] }).unwrap();
        assert_eq!(text, r#"{"z":1,"a":2,"m":3}"#);
    }
}
