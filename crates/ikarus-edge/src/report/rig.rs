//! A rig file as JSON (`GET /api/rigs`, `POST /api/rig/parse`, the requests' `rig`).

use crate::error::Error;
use crate::rig::{BoneCap, Rig, RigFile};

/// A rig file's fields as JSON (the requests' `rig`): `name`, `base`, `bones` (each with
/// `parent`, null for a root, and `limits_deg`, `stiffness`, `rest_deg` and the joint keys
/// `offset`, `joint`, `slide`, `extension`, `limits` when it has them)
/// and, when the file has one, `solver`.
#[derive(Debug, serde::Serialize)]
pub struct RigJson {
    /// The file's `name`; `rig` when it has none.
    pub name: String,
    /// Where every root bone starts; the origin when the file has no `base`.
    pub base: [f64; 2],
    /// The bones, in the file's order.
    pub bones: Vec<BoneJson>,
    /// The file's `[solver]` table as written; only when it has one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub solver: Option<serde_json::Value>,
}

/// One `[[bones]]` entry as JSON, angles in degrees.
#[derive(Debug, serde::Serialize)]
pub struct BoneJson {
    /// The bone's name, unique in the rig.
    pub name: String,
    /// Its parent's name; `null` for a bone that starts at the base.
    pub parent: Option<String>,
    /// Its length.
    pub length: f64,
    /// Its start angle, degrees, from its parent's direction (a root bone's from +x).
    pub angle_deg: f64,
    /// Its `[min, max]` joint angle range, degrees; only when it has one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub limits_deg: Option<[f64; 2]>,
    /// How much it resists turning away from its rest angle; only when the file gives it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stiffness: Option<f64>,
    /// The angle it is pulled back to, degrees; only when the file gives it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rest_deg: Option<f64>,
    /// The joint's origin in its parent's frame. This and the joint keys below appear only when
    /// the file has them (so a rig without them reads as before).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub offset: Option<[f64; 2]>,
    /// The joint's kind, `revolute` or `prismatic`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub joint: Option<crate::rig::JointFile>,
    /// A prismatic joint's direction in its parent's frame.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub slide: Option<[f64; 2]>,
    /// A prismatic joint's start displacement.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub extension: Option<f64>,
    /// A prismatic joint's `[min, max]` displacement, length units.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub limits: Option<[f64; 2]>,
}

impl RigJson {
    /// The rig of rig-file `text` as JSON, after the CLI's checks (whose one-line message it
    /// returns for a bad file, starting with `label`), under the command line's cap on bones.
    /// The `[solver]` table is carried as written.
    pub fn parse(text: &str, label: &str) -> Result<Self, Error> {
        Self::parse_within(text, label, BoneCap::cli())
    }

    /// [`RigJson::parse`] of a rig of at most `cap` bones (counted before anything else).
    pub fn parse_within(text: &str, label: &str, cap: BoneCap) -> Result<Self, Error> {
        let file = RigFile::read(text, label, cap).map_err(|e| Error::input(e.to_string()))?;
        Rig::from_file(file.clone(), label, cap).map_err(|e| Error::input(e.to_string()))?;
        let table: toml::Table = toml::from_str(text).map_err(|e| Error::input(format!("{label}: {e}")))?;
        let solver = match table.get("solver") {
            Some(t) => Some(serde_json::to_value(t).map_err(|e| Error::input(format!("{label}: [solver]: {e}")))?),
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
mod rig_tests {
    use super::*;
    use crate::report::ByName;

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
