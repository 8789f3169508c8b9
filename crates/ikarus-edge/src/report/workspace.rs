//! The answers about an arm's reach: its reachable area (`ikarus workspace --format json`,
//! `POST /api/workspace`) and the verdicts on points (`ikarus reach`, `POST /api/reach`).

use ikarus::reach::{Annulus, BoundarySegment, Verdict, Workspace};
use serde::Serialize;

use crate::area::ReachableArea;
use crate::arm::Arm;
use crate::rig::Rig;

/// The reachable region: `ikarus workspace --format json` and `POST /api/workspace`. The exact
/// region gives `boundary` (and `curves`, for a region without area); the grid (`--grid`)
/// gives `resolution`, `cell_size`, `origin` and `grid` instead.
#[derive(Serialize)]
pub struct WorkspaceJson<'a> {
    /// The arm's (or rig's) name.
    pub arm: &'a str,
    /// A rig's (or an arm with slides') effector bone, whose tip's region is sampled.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub bone: Option<&'a str>,
    /// Whether the joint limits bound the region.
    pub limits: bool,
    /// Whether `area` and the boundary are the exact region's (not a sampled grid's).
    pub exact: bool,
    /// The inner radius of the ring the tip reaches with every joint free.
    pub inner_radius: f64,
    /// The outer radius of that ring.
    pub outer_radius: f64,
    /// The area of that ring.
    pub annulus_area: f64,
    /// The region's area: the exact region's, or the sampled grid's reachable cells'.
    pub area: f64,
    /// Closed loops of segments, outer boundaries counter-clockwise, holes clockwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub boundary: Option<Vec<Vec<SegmentJson>>>,
    /// The curves a region without area is made of (empty for a region with area).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub curves: Option<Vec<SegmentJson>>,
    /// The grid's cells along each side.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub resolution: Option<u32>,
    /// The side of a cell.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cell_size: Option<f64>,
    /// The lower-left corner of the bottom-left cell.
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
    /// A straight segment `[[x0, y0], [x1, y1]]`.
    Line([[f64; 2]; 2]),
    /// An arc of a circle.
    Arc(ArcJson),
}

/// An arc: its circle and the angles it runs between, degrees.
#[derive(Serialize)]
pub struct ArcJson {
    /// The circle's centre.
    pub center: [f64; 2],
    /// The circle's radius.
    pub radius: f64,
    /// The angle it starts at, degrees from +x.
    pub from_deg: f64,
    /// The angle it ends at, degrees from +x.
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
