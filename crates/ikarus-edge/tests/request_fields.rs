//! The requests declared with field groups (`request!`) take the fields they took when every
//! field was written out, in the same order: the refusal of an unknown field lists them, so a
//! group must stand where its fields stood; and every field may be left out.

use ikarus_edge::api::figures::{BodyFigureReq, EaseFigureReq, MotionFigureReq, WorkspaceFigureReq};
use ikarus_edge::api::requests::{AnimateReq, ReachReq, SolveReq, TrackReq, WorkspaceReq};
use serde::de::DeserializeOwned;

/// The fields `T` takes, in order, as its refusal of an unknown field lists them.
fn fields<T: DeserializeOwned + std::fmt::Debug>() -> String {
    let message = serde_json::from_str::<T>(r#"{"unknown": 0}"#).unwrap_err().to_string();
    let list = message.split("expected one of ").nth(1).expect(&message);
    list.split(" at line").next().unwrap().replace('`', "")
}

#[test]
fn groups_stand_where_their_fields_stood() {
    let aim = "arm, rig, start_deg, goal, goals, pins, mix";
    let motion = "options, ease, frames, duration, fps, interpolation, from_solve";
    let picture = "figure, format, width, height";
    let area = "limits, grid, resolution, samples, seed";
    assert_eq!(fields::<SolveReq>(), format!("{aim}, options"));
    assert_eq!(fields::<AnimateReq<[f64; 2]>>(), format!("{aim}, via, {motion}, keys"));
    assert_eq!(
        fields::<TrackReq>(),
        "arm, rig, start_deg, effector, goals, pins, mix, path, line, circle, figure8, samples, mode, \
         max_step_deg, bound_first, options"
    );
    assert_eq!(fields::<WorkspaceReq>(), format!("arm, rig, bone, {area}"));
    assert_eq!(fields::<ReachReq>(), "arm, limits, tolerance, point, points");
    assert_eq!(
        fields::<BodyFigureReq>(),
        format!("{picture}, arm, rig, pose_deg, goal, goals, pins, workspace, {area}, labels")
    );
    assert_eq!(
        fields::<MotionFigureReq>(),
        format!("{picture}, arm, rig, keys, start_deg, goal, via, {motion}, workspace, {area}, traces, ghosts")
    );
    assert_eq!(fields::<WorkspaceFigureReq>(), format!("{picture}, arm, {area}"));
    assert_eq!(fields::<EaseFigureReq>(), format!("{picture}, ease"));
}

#[test]
fn every_field_is_optional() {
    let solve: SolveReq = serde_json::from_str("{}").unwrap();
    assert!(solve.arm.is_none() && solve.goal.is_none() && solve.options.is_none());
    let animate: AnimateReq<[f64; 2]> = serde_json::from_str("{}").unwrap();
    assert!(animate.via.is_empty() && !animate.from_solve && animate.ease.is_none());
    let figure: MotionFigureReq = serde_json::from_str("{}").unwrap();
    assert!(figure.via.is_empty() && !figure.workspace && !figure.ghosts && figure.format.is_none());
}
