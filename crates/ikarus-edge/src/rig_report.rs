//! The JSON objects of rigs, shared by `ikarus solve --rig --format json` and `ikarus serve`
//! (`POST /api/solve` with `rig`, `GET /api/rigs`, `POST /api/rig/parse`), so that both answer
//! with the same shapes: degrees at the edge, bones by name, objects keyed by bone name in the
//! rig's (file) order. Shapes only: the work is done elsewhere.

use ikarus::{Outcome, Point2, SolveOptions};
use serde::ser::{Serialize, SerializeMap, Serializer};

use crate::report::{FrameJson, degrees, points};
use crate::rig::{BoneCap, Rig, RigFile};

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
    /// Bone name → its angle (relative to its parent), degrees.
    pub angles_deg: ByName<'a, f64>,
    /// Bone name → its tip.
    pub joints: ByName<'a, [f64; 2]>,
    /// Recorded frames (empty unless recording is asked): angles in bone order, and the base
    /// then every bone's tip.
    pub frames: Vec<FrameJson>,
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
            angles_deg: ByName { names, values: degrees(o.pose.angles()) },
            joints: ByName { names, values: points(&tips(self.rig, o.pose.angles())) },
            frames: o
                .frames
                .iter()
                .map(|f| FrameJson { iteration: f.iteration, angles_deg: degrees(f.angles), joints: points(f.joints) })
                .collect(),
        }
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
/// `parent`, null for a root, and `limits_deg`, `stiffness` and `rest_deg` when it has them)
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
                })
                .collect(),
            solver,
        })
    }
}

#[cfg(test)]
mod tests {
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
