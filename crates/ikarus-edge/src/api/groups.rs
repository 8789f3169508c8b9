//! The groups of fields that several requests share (the body, a rig's goals, a motion's
//! timing, a picture's size, a reachable area), each declared once, and [`request!`] that
//! declares a request struct from its own fields and these groups.
//!
//! The groups are written into each struct as plain fields rather than as `serde(flatten)`ed
//! structs: a flattened struct would lose `deny_unknown_fields` and the field paths of
//! `serde_path_to_error`, and the refusals name the field and its place (`unknown field
//! \`x\`, expected one of …` lists the fields in their order, so a group stands where its
//! fields stood).

/// Declares a request struct: its attributes and name (with at most one type parameter), then
/// a list of fields, each either a field as in a struct (`pub name: Type,` with its attributes)
/// or a group, `..name,`, that stands for the group's fields in its place. Every field is
/// optional: absent, it takes its type's default (`#[serde(default)]` is added to each).
///
/// - `..body`: `arm` and `rig`, the request's body.
/// - `..rig_goals`: a rig's `goals` and `pins`.
/// - `..aim`: `..body`, `start_deg`, an arm's `goal`, `..rig_goals` and a rig's `mix`
///   (what a solve is aimed at).
/// - `..motion`: `options` and the motion's timing (`ease`, `frames`, `duration`, `fps`,
///   `interpolation`, `from_solve`), after its `via`.
/// - `..picture`: `figure` (read by the render request's first pass), `format`, `width`,
///   `height`.
/// - `..area`: `limits`, `grid`, `resolution`, `samples`, `seed` (the exact region, or the
///   sampled grid).
macro_rules! request {
    ($(#[$meta:meta])* pub struct $name:ident $(<$param:ident>)? { $($fields:tt)* }) => {
        $crate::api::groups::request!(@fields [$(#[$meta])* pub struct $name $(<$param>)?] [] $($fields)*);
    };
    (@fields [$($head:tt)*] [$($done:tt)*]) => {
        $($head)* { $($done)* }
    };
    (@fields $head:tt $done:tt ..body, $($rest:tt)*) => {
        $crate::api::groups::request!(@fields $head $done
            pub arm: Option<$crate::arm::ArmFile>,
            pub rig: Option<$crate::rig::RigFile>,
            $($rest)*
        );
    };
    (@fields $head:tt $done:tt ..rig_goals, $($rest:tt)*) => {
        $crate::api::groups::request!(@fields $head $done
            /// A rig's goals.
            pub goals: Option<Vec<$crate::api::requests::RigGoalReq>>,
            /// A rig's pinned bones (held where they are).
            pub pins: Option<Vec<String>>,
            $($rest)*
        );
    };
    (@fields $head:tt $done:tt ..aim, $($rest:tt)*) => {
        $crate::api::groups::request!(@fields $head $done
            ..body,
            /// One angle per joint (a rig's bones in its order) [default: the body's start pose].
            pub start_deg: Option<Vec<f64>>,
            /// An arm's goal.
            pub goal: Option<$crate::api::requests::GoalReq>,
            ..rig_goals,
            /// A rig's mix, from 0 to 1 [default: 1].
            pub mix: Option<f64>,
            $($rest)*
        );
    };
    (@fields $head:tt $done:tt ..motion, $($rest:tt)*) => {
        $crate::api::groups::request!(@fields $head $done
            pub options: Option<$crate::settings::SolverSettings>,
            pub ease: Option<$crate::api::requests::EaseReq>,
            pub frames: Option<u32>,
            pub duration: Option<f64>,
            pub fps: Option<f64>,
            pub interpolation: Option<ikarus::motion::Interpolation>,
            pub from_solve: bool,
            $($rest)*
        );
    };
    (@fields $head:tt $done:tt ..picture, $($rest:tt)*) => {
        $crate::api::groups::request!(@fields $head $done
            /// Read by the first pass.
            #[serde(rename = "figure")]
            pub _figure: serde::de::IgnoredAny,
            pub format: Option<$crate::picture::PictureFormat>,
            pub width: Option<u32>,
            pub height: Option<u32>,
            $($rest)*
        );
    };
    (@fields $head:tt $done:tt ..area, $($rest:tt)*) => {
        $crate::api::groups::request!(@fields $head $done
            /// The area within the limits (a rig figure's: its limit wedges).
            pub limits: Option<bool>,
            pub grid: Option<bool>,
            pub resolution: Option<u32>,
            pub samples: Option<u32>,
            pub seed: Option<u64>,
            $($rest)*
        );
    };
    (@fields $head:tt [$($done:tt)*] $(#[$attr:meta])* pub $field:ident : $ty:ty, $($rest:tt)*) => {
        $crate::api::groups::request!(@fields $head [$($done)* $(#[$attr])* #[serde(default)] pub $field: $ty,] $($rest)*);
    };
}

pub(crate) use request;

#[cfg(test)]
mod tests {
    use serde::de::DeserializeOwned;

    use super::super::figures::{BodyFigureReq, EaseFigureReq, MotionFigureReq, WorkspaceFigureReq};
    use super::super::requests::{AnimateReq, ReachReq, SolveReq, TrackReq, WorkspaceReq};

    /// The fields `T` takes, in order, as its refusal of an unknown field lists them.
    fn fields<T: DeserializeOwned + std::fmt::Debug>() -> String {
        let message = serde_json::from_str::<T>(r#"{"unknown": 0}"#).unwrap_err().to_string();
        let list = message.split("expected one of ").nth(1).expect(&message);
        list.split(" at line").next().unwrap().replace('`', "")
    }

    /// Each request takes the fields it took when every field was written out, in the same
    /// order (the refusals list them), a group standing where its fields stood.
    #[test]
    fn groups_stand_where_their_fields_stood() {
        let aim = "arm, rig, start_deg, goal, goals, pins, mix";
        let motion = "options, ease, frames, duration, fps, interpolation, from_solve";
        let picture = "figure, format, width, height";
        let area = "limits, grid, resolution, samples, seed";
        assert_eq!(fields::<SolveReq>(), format!("{aim}, options"));
        assert_eq!(fields::<AnimateReq<[f64; 2]>>(), format!("{aim}, via, {motion}"));
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
            format!("{picture}, arm, start_deg, goal, via, {motion}, workspace, {area}, traces, ghosts")
        );
        assert_eq!(fields::<WorkspaceFigureReq>(), format!("{picture}, arm, {area}"));
        assert_eq!(fields::<EaseFigureReq>(), format!("{picture}, ease"));
    }

    /// Every field of a request may be left out.
    #[test]
    fn every_field_is_optional() {
        let solve: SolveReq = serde_json::from_str("{}").unwrap();
        assert!(solve.arm.is_none() && solve.goal.is_none() && solve.options.is_none());
        let animate: AnimateReq<[f64; 2]> = serde_json::from_str("{}").unwrap();
        assert!(animate.via.is_empty() && !animate.from_solve);
        let figure: MotionFigureReq = serde_json::from_str("{}").unwrap();
        assert!(figure.via.is_empty() && !figure.workspace && !figure.ghosts && figure.format.is_none());
    }
}
