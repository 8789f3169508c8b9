//! `POST /api/workspace` and `POST /api/reach`: an arm's reachable area and the verdicts on
//! points, as `ikarus workspace` and `ikarus reach` print them (`crate::area`, `crate::reach`,
//! `crate::report`), under the server's caps.

use ikarus::Interrupt;
use ikarus::reach::WorkspaceOptions;

use super::bodies::{load, load_arm};
use super::fields::{json_response, stopped, watched};
use super::requests::{ReachReq, WorkspaceReq};
use super::wire::{Limits, Problem, Reply};
use crate::area::{self, Effector, GridRequest, ReachableArea};
use crate::arm::Arm;
use crate::reach::ReachRequest;
use crate::report::{self, VerdictJson};

/// Most joint-space samples of a workspace.
const MAX_SAMPLES: u32 = 1_000_000;

/// `POST /api/workspace`: the JSON of `ikarus workspace --format json`.
pub fn workspace(req: WorkspaceReq, limits: &Limits, interrupt: &Interrupt) -> Result<Reply, Problem> {
    if req.rig.is_some() || req.bone.is_some() || req.arm.as_ref().is_some_and(|a| a.joint_key().is_some()) {
        return body_workspace(req, limits, interrupt);
    }
    let arm = load_arm(req.arm.clone(), limits)?;
    let area = reachable_area(&arm, &req, limits, interrupt)?;
    stopped(interrupt)?;
    json_response(&report::workspace_json(&arm, &area))
}

/// `POST /api/workspace` with `rig`, `bone` or an arm with slides: the region of the bone's tip
/// ([`Effector::of`]): a chain's as an arm's, else sampled (`"exact": false`).
fn body_workspace(req: WorkspaceReq, limits: &Limits, interrupt: &Interrupt) -> Result<Reply, Problem> {
    if req.arm.is_some() && req.rig.is_some() {
        return Err(Problem::invalid("arm, rig: give one or the other, not both"));
    }
    let body = load(req.arm.clone(), req.rig.clone(), limits)?;
    let (rig, bone) = match Effector::of(body, req.bone.as_deref(), |name| format!("bone = {name:?}"))? {
        Effector::Chain(arm) => {
            let area = reachable_area(&arm, &req, limits, interrupt)?;
            stopped(interrupt)?;
            return json_response(&report::workspace_json(&arm, &area));
        }
        Effector::Bone(rig, bone) => (rig, bone),
    };
    let grid = grid_of(&req, limits)?;
    let on = req.limits.or(rig.solver.limits).unwrap_or(false);
    let run = WorkspaceOptions {
        limits: on,
        parallel: false,
        interrupt: Some(interrupt.clone()),
        ..WorkspaceOptions::default()
    };
    let workspace = area::sampled(&rig, bone, grid, run).map_err(Problem::from)?;
    stopped(interrupt)?;
    json_response(&report::rig_workspace_json(&rig, bone, workspace))
}

/// The grid a request asks for (`None`: the exact region), within the server's caps.
fn grid_of(req: &WorkspaceReq, limits: &Limits) -> Result<Option<GridRequest>, Problem> {
    let grid =
        GridRequest::of(req.grid, req.resolution, req.samples, req.seed, |field, value| format!("{field} = {value}"))
            .map_err(Problem::from)?;
    if let Some(grid) = &grid {
        if grid.resolution > limits.max_resolution {
            return Err(Problem::invalid(format!(
                "resolution = {}: more than the cap of {} (--max-resolution)",
                grid.resolution, limits.max_resolution
            )));
        }
        if let Some(n) = grid.samples.filter(|&n| n == 0 || n > MAX_SAMPLES) {
            return Err(Problem::invalid(format!("samples = {n}: must be between 1 and {MAX_SAMPLES}")));
        }
    }
    Ok(grid)
}

/// `POST /api/reach`: the verdict on `point`, or on each of `points` (at most `--max-samples`),
/// read off the exact region built once, as `ikarus reach --format json` prints them.
pub fn reach(req: ReachReq, limits: &Limits, interrupt: &Interrupt) -> Result<Reply, Problem> {
    {
        let arm = load_arm(req.arm, limits)?;
        if let Some(t) = req.tolerance {
            crate::options::positive(t).map_err(|m| Problem::invalid(format!("tolerance = {m}")))?;
        }
        let request = ReachRequest { limits: req.limits, tolerance: req.tolerance };
        match (req.point, req.points) {
            (Some(p), None) => {
                let region = watched(request.region(&arm, Some(interrupt)), interrupt)?;
                json_response(&VerdictJson::of(&crate::reach::verdict(&region, p, request.tolerance(&arm))))
            }
            (None, Some(points)) => {
                if points.len() > limits.max_samples {
                    return Err(Problem::invalid(format!(
                        "points: {} points, more than the cap of {} (--max-samples)",
                        points.len(),
                        limits.max_samples
                    )));
                }
                let region = watched(request.region(&arm, Some(interrupt)), interrupt)?;
                let tolerance = request.tolerance(&arm);
                let mut answers = Vec::with_capacity(points.len());
                // A verdict walks every boundary piece: about 10⁶ pieces between two checks.
                let chunk = ((1 << 20) / region.pieces().max(1)).clamp(1, 1024);
                for chunk in points.chunks(chunk) {
                    stopped(interrupt)?;
                    answers
                        .extend(chunk.iter().map(|&p| VerdictJson::of(&crate::reach::verdict(&region, p, tolerance))));
                }
                json_response(&answers)
            }
            (Some(_), Some(_)) => Err(Problem::invalid("point, points: give one or the other, not both")),
            (None, None) => Err(Problem::invalid("point or points: required (a point [x, y], or [[x, y], …])")),
        }
    }
}

/// The reachable area a workspace request asks for: the exact region, or the grid
/// ([`GridRequest::of`]) sampled under `--max-resolution` and the samples' cap.
pub(super) fn reachable_area(
    arm: &Arm,
    req: &WorkspaceReq,
    limits: &Limits,
    interrupt: &Interrupt,
) -> Result<ReachableArea, Problem> {
    let on = arm.limits(req.limits);
    let Some(grid) = grid_of(req, limits)? else { return watched(area::exact(arm, on, Some(interrupt)), interrupt) };
    // Sequential on its worker: rayon's global pool is shared by every request, so a small
    // request would wait behind a large one; the server's workers give the parallelism.
    let options = WorkspaceOptions { parallel: false, interrupt: Some(interrupt.clone()), ..grid.options(on) };
    let workspace = ikarus::reach::sample_with_progress(&arm.chain, &options, &|_, _| {})
        .map_err(|e| Problem::invalid(e.to_string()))?;
    Ok(ReachableArea::Grid(workspace))
}
