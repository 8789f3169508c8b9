//! What the `pose` job answers ([`super::pose`]): every bone's world origin, rotation and tip,
//! what the file has that is not posed, and with ikarus's solver what the solve did; as JSON,
//! as text, and as the renderer's figure.

use ikarus::Point2;
use ikarus::character::{Character, GoalEnd, LimbEnd, Posed, TogetherReport};
use ikarus_render::{CharacterFigure, PosedBone};
use serde::Serialize;

use crate::names::{Quoted, cell};
use crate::report::character::UnsupportedJson;

/// One bone posed: world origin, the world direction of its x axis in degrees, and its tip
/// (origin plus length along that axis), in the file's units, y up.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PosedBoneJson {
    /// The bone's name.
    pub name: String,
    /// Its world origin's x.
    pub x: f64,
    /// Its world origin's y.
    pub y: f64,
    /// The world direction of its x axis, degrees.
    pub rotation_deg: f64,
    /// Its tip: the origin plus its length along that axis.
    pub tip: [f64; 2],
    /// `false` for a bone the skin does not turn on (not posed, at zeros); absent when active.
    #[serde(skip_serializing_if = "is_true")]
    pub active: bool,
}

fn is_true(b: &bool) -> bool {
    *b
}

/// `{"bones": [{"name", "x", "y", "rotation_deg", "tip"}, …], "unsupported": […]}`.
#[derive(Debug, Serialize)]
pub struct PoseReport {
    /// Every bone, in the file's order.
    pub bones: Vec<PosedBoneJson>,
    /// What the file has that is not posed.
    pub unsupported: Vec<UnsupportedJson>,
    /// With `--ik ikarus`: what the solve did (absent under the runtime's rules).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ik: Option<IkJson>,
    /// The IK constraints' target bones' origins and the goals' points, for the picture (not in
    /// the JSON).
    #[serde(skip)]
    pub(crate) targets: Vec<[f64; 2]>,
}

/// What `--ik ikarus` did: `{"solver": "ikarus", "status", "rounds", "constraints": [{"name",
/// "active", "error"}]}`, each constraint's error its last bone's tip's distance from its target.
#[derive(Debug, Serialize)]
pub struct IkJson {
    /// `ikarus`.
    pub solver: &'static str,
    /// The solve's status (`converged`, …), if it ran.
    pub status: Option<String>,
    /// How many times the skeleton was solved.
    pub rounds: usize,
    /// Each IK constraint's end.
    pub constraints: Vec<LimbJson>,
    /// The goals on bones' tips ([`crate::pose::add_goals`]), when there are any.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub goals: Vec<GoalJson>,
}

/// One goal's end: its bone's tip's distance from it, and with an angle, the bone's direction's
/// difference from it, degrees.
#[derive(Debug, Serialize)]
pub struct GoalJson {
    /// The goal's bone.
    pub bone: String,
    /// Its tip's distance from the goal.
    pub error: f64,
    /// With an angle: the bone's direction's difference from it, degrees.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub angle_error_deg: Option<f64>,
}

/// One constraint's end under `--ik ikarus`.
#[derive(Debug, Serialize)]
pub struct LimbJson {
    /// The constraint's name.
    pub name: String,
    /// Whether it took part (mix > 0, turned on by the skin).
    pub active: bool,
    /// Its last bone's tip's distance from its target.
    pub error: f64,
}

impl LimbJson {
    fn of(c: &Character, l: &LimbEnd) -> Self {
        LimbJson { name: c.constraints()[l.constraint].name().to_owned(), active: l.active, error: l.error }
    }
}

impl GoalJson {
    fn of(c: &Character, g: &GoalEnd) -> Self {
        let bone = c.bones()[g.bone].name.clone();
        GoalJson { bone, error: g.error, angle_error_deg: g.angle_error.map(f64::to_degrees) }
    }
}

impl IkJson {
    pub(crate) fn of(c: &Character, t: &TogetherReport) -> Self {
        IkJson {
            solver: "ikarus",
            status: t.outcome.as_ref().map(|o| o.status.to_string()),
            rounds: t.rounds,
            constraints: t.limbs.iter().map(|l| LimbJson::of(c, l)).collect(),
            goals: t.goals.iter().map(|g| GoalJson::of(c, g)).collect(),
        }
    }
}

impl PoseReport {
    /// The report of a pose of `c`.
    #[must_use]
    pub fn of(c: &Character, posed: &Posed) -> Self {
        let bones = c
            .bones()
            .iter()
            .enumerate()
            .map(|(i, b)| {
                let [x, y] = posed.origin(i);
                PosedBoneJson {
                    name: b.name.clone(),
                    x,
                    y,
                    rotation_deg: posed.rotation(i).to_degrees(),
                    tip: posed.tip(i),
                    active: posed.is_active(i),
                }
            })
            .collect();
        let unsupported =
            c.unsupported().iter().map(|u| UnsupportedJson { kind: u.kind.clone(), name: u.name.clone() }).collect();
        // A target the skin leaves inactive is not posed: not drawn.
        let targets = c
            .ik_constraints()
            .filter(|(_, k)| posed.is_active(k.target))
            .map(|(_, k)| posed.origin(k.target))
            .collect();
        PoseReport { bones, unsupported, ik: None, targets }
    }

    /// One line per bone: `name  x  y  rotation_deg  tip_x  tip_y`, under a header, then one line
    /// per unsupported constraint, one per bone the skin leaves inactive, then one per goal on a
    /// bone's tip (its miss).
    #[must_use]
    pub fn text(&self) -> String {
        use std::fmt::Write;
        let width = self.bones.iter().map(|b| cell(&b.name).chars().count()).max().unwrap_or(4).max(4);
        let mut out = format!(
            "{:width$}  {:>12}  {:>12}  {:>12}  {:>12}  {:>12}\n",
            "bone", "x", "y", "rotation_deg", "tip_x", "tip_y"
        );
        for b in &self.bones {
            let _ = writeln!(
                out,
                "{:width$}  {:>12.4}  {:>12.4}  {:>12.4}  {:>12.4}  {:>12.4}",
                cell(&b.name),
                b.x,
                b.y,
                b.rotation_deg,
                b.tip[0],
                b.tip[1]
            );
        }
        for u in &self.unsupported {
            let _ = writeln!(out, "unsupported {} {:?}: left out", u.kind, Quoted(&u.name));
        }
        for b in self.bones.iter().filter(|b| !b.active) {
            let _ = writeln!(out, "inactive bone {:?}: the skin does not turn it on (not posed)", Quoted(&b.name));
        }
        for g in self.ik.iter().flat_map(|k| &k.goals) {
            let _ = write!(out, "goal on {:?}: tip {:.6} from its point", Quoted(&g.bone), g.error);
            if let Some(a) = g.angle_error_deg {
                let _ = write!(out, ", direction {a:.6}° from its angle");
            }
            out.push('\n');
        }
        out
    }

    /// The picture of the pose: every active bone (an inactive one is not posed, so not drawn),
    /// and the IK targets as goals.
    #[must_use]
    pub fn figure(&self, caption: Option<String>) -> CharacterFigure<'_> {
        let point = |p: [f64; 2]| Point2::new(p[0], p[1]);
        CharacterFigure {
            bones: self
                .bones
                .iter()
                .filter(|b| b.active)
                .map(|b| PosedBone { name: &b.name, origin: Point2::new(b.x, b.y), tip: point(b.tip) })
                .collect(),
            targets: self.targets.iter().copied().map(point).collect(),
            caption,
        }
    }
}
