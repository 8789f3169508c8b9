//! Arm files for the page: `POST /api/arm/parse` reads arm-file text (TOML, the format of
//! `--arm` and `examples/arms/`) into the arm the page edits, or says why it is not an arm file
//! with the CLI's one-line error. That answer is a 200 either way (`{"arm": …}` or
//! `{"problem": "…"}`): a bad file is the reader's to fix, not a failed request, and a browser
//! logs every 4xx answer as a console error;
//! `POST /api/arm/toml` writes the page's arm back as arm-file text; `GET /api/arm/default` is
//! the built-in arm. The page's per-joint rates
//! are the file's `[solver].rates`; the file's other `[solver]` settings are the page's controls'
//! business and are not carried.

use serde::{Deserialize, Serialize};

use super::wire::{Problem, Reply};
use crate::arm::{Arm, ArmFile, DEFAULT_ARM, LinkFile};
use crate::error::Error;
use crate::settings::SolverSettings;

/// The arm as the page holds it: the arm file's fields, and each joint's rate.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PageArm {
    /// The arm's name, shown in outputs.
    pub name: String,
    /// The base's position, `[x, y]`.
    pub base: [f64; 2],
    /// The links, base to tip.
    pub links: Vec<PageLink>,
}

/// One link of a [`PageArm`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PageLink {
    /// The link's length.
    pub length: f64,
    /// The joint's start angle, degrees, relative to the link before; 0 when absent.
    #[serde(default)]
    pub angle_deg: f64,
    /// The joint's limits, `[min, max]` degrees; none when absent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub limits_deg: Option<[f64; 2]>,
    /// The joint's step multiplier (`[solver].rates`); 1 when absent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rate: Option<f64>,
}

/// `POST /api/arm/toml`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TomlReq {
    /// The arm to write as arm-file text.
    pub arm: PageArm,
}

/// The label that starts every error of a parsed file.
const LABEL: &str = "arm file";

/// Arm-file text → the page's arm; a bad file is the CLI's one-line error.
pub fn parse(text: &str) -> Result<PageArm, Error> {
    // The CLI's reading and checks first, so that the messages are the CLI's.
    Arm::parse(text, LABEL).map_err(|e| Error::input(e.to_string()))?;
    let file: ArmFile = toml::from_str(text).map_err(|e| Error::input(format!("{LABEL}: {e}")))?;
    let rates = file.solver.rates.clone();
    Ok(PageArm {
        name: file.name.clone().unwrap_or_else(|| "arm".to_owned()),
        base: file.base.unwrap_or([0.0, 0.0]),
        links: file
            .links
            .iter()
            .enumerate()
            .map(|(i, l)| PageLink {
                length: l.length,
                angle_deg: l.angle_deg,
                limits_deg: l.limits_deg,
                rate: rates.as_ref().and_then(|r| r.get(i).copied()),
            })
            .collect(),
    })
}

/// The page's arm → arm-file text (checked as the CLI would read it).
pub fn to_toml(arm: &PageArm) -> Result<String, Error> {
    let rates: Vec<f64> = arm.links.iter().map(|l| l.rate.unwrap_or(1.0)).collect();
    let file = ArmFile {
        name: Some(arm.name.clone()),
        base: Some(arm.base),
        links: arm
            .links
            .iter()
            .map(|l| LinkFile {
                length: l.length,
                angle_deg: l.angle_deg,
                limits_deg: l.limits_deg,
                ..LinkFile::default()
            })
            .collect(),
        solver: SolverSettings { rates: rates.iter().any(|&r| r != 1.0).then_some(rates), ..SolverSettings::default() },
    };
    Arm::from_file(file, "arm").map_err(|e| Error::input(e.to_string()))?;
    let text =
        toml::to_string(&FileOut::of(arm)).map_err(|e| Error::input(format!("arm: cannot write it as TOML: {e}")))?;
    Ok(format!("# An arm saved by the ikarus playground; load it with `ikarus solve --arm FILE`.\n{text}"))
}

/// What [`to_toml`] writes: the arm file's fields in the file's order.
#[derive(Serialize)]
struct FileOut<'a> {
    name: &'a str,
    base: [f64; 2],
    links: Vec<LinkOut>,
    #[serde(skip_serializing_if = "Option::is_none")]
    solver: Option<SolverOut>,
}

#[derive(Serialize)]
struct LinkOut {
    length: f64,
    angle_deg: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    limits_deg: Option<[f64; 2]>,
}

#[derive(Serialize)]
struct SolverOut {
    rates: Vec<f64>,
}

impl<'a> FileOut<'a> {
    fn of(arm: &'a PageArm) -> Self {
        let rates: Vec<f64> = arm.links.iter().map(|l| l.rate.unwrap_or(1.0)).collect();
        Self {
            name: &arm.name,
            base: arm.base,
            links: arm
                .links
                .iter()
                .map(|l| LinkOut { length: l.length, angle_deg: l.angle_deg, limits_deg: l.limits_deg })
                .collect(),
            solver: rates.iter().any(|&r| r != 1.0).then_some(SolverOut { rates }),
        }
    }
}

/// The answer of `POST /api/arm/parse`: the arm, or why the text is not an arm file.
#[derive(Debug, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Parsed {
    /// `{"arm": …}`: the file's arm, as the page edits it.
    Arm(PageArm),
    /// `{"problem": "…"}`: the one-line error that says why the text is not an arm file.
    Problem(String),
}

/// `POST /api/arm/parse`: the body is the file's text.
pub fn parsed(text: &str) -> Parsed {
    match parse(text) {
        Ok(arm) => Parsed::Arm(arm),
        Err(problem) => Parsed::Problem(problem.to_string()),
    }
}

/// `POST /api/arm/toml`: `{"arm": …}` → the file's text.
pub fn toml(req: &TomlReq) -> Result<Reply, Problem> {
    let text = to_toml(&req.arm).map_err(Problem::from)?;
    Ok(Reply { content_type: "application/toml; charset=utf-8", body: text.into_bytes() })
}

#[derive(serde::Serialize)]
struct LinkJson {
    length: f64,
    angle_deg: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    limits_deg: Option<[f64; 2]>,
}

#[derive(serde::Serialize)]
struct ArmJson {
    name: String,
    base: [f64; 2],
    links: Vec<LinkJson>,
}

/// `GET /api/arm/default`: the built-in arm.
pub fn default_arm() -> Result<Reply, Problem> {
    let file: ArmFile = toml::from_str(DEFAULT_ARM).map_err(|e| Problem::internal(format!("the built-in arm: {e}")))?;
    Reply::json(&ArmJson {
        name: file.name.clone().unwrap_or_else(|| "arm".to_owned()),
        base: file.base.unwrap_or([0.0, 0.0]),
        links: file
            .links
            .iter()
            .map(|l| LinkJson { length: l.length, angle_deg: l.angle_deg, limits_deg: l.limits_deg })
            .collect(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn examples() -> Vec<(String, String)> {
        let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/arms");
        let mut files: Vec<_> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| p.extension().is_some_and(|x| x == "toml"))
            .map(|p| (p.display().to_string(), std::fs::read_to_string(&p).unwrap()))
            .collect();
        files.sort();
        files
    }

    #[test]
    fn every_example_arm_reads_and_writes_back_the_same_arm() {
        let files = examples();
        assert!(files.len() >= 3, "{files:?}");
        for (path, text) in files {
            // An arm with a slide (`rrp.toml`) is a one-branch rig, not the page's arm: refused
            // in the CLI's one line naming the first joint key.
            if let Some((i, key)) = ArmFile::read(&text, "x").unwrap().joint_key() {
                let e = parse(&text).unwrap_err();
                assert!(
                    e.to_string().starts_with(&format!("arm file: links[{i}].{key}: an arm with offsets")),
                    "{path}: {e}"
                );
                continue;
            }
            let arm = parse(&text).unwrap_or_else(|e| panic!("{path}: {e}"));
            let cli = Arm::parse(&text, "x").unwrap();
            assert_eq!(arm.links.len(), cli.chain.len(), "{path}");
            let again = parse(&to_toml(&arm).unwrap()).unwrap();
            assert_eq!(again, arm, "{path}");
        }
    }

    #[test]
    fn rates_are_the_solver_tables_rates() {
        let text = "[[links]]\nlength = 1.0\n[[links]]\nlength = 2.0\nangle_deg = 5.0\nlimits_deg = [-10.0, 10.0]\n[solver]\nrates = [1.0, 0.5]\n";
        let arm = parse(text).unwrap();
        assert_eq!(arm.links[1].rate, Some(0.5));
        assert_eq!(arm.links[1].limits_deg, Some([-10.0, 10.0]));
        let out = to_toml(&arm).unwrap();
        assert!(out.contains("rates = [1.0, 0.5]"), "{out}");
    }

    #[test]
    fn a_bad_file_is_the_clis_one_line_error() {
        let e = parse("[[links]]\nlength = -1.0\n").unwrap_err();
        assert!(e.to_string().starts_with("arm file: "), "{e}");
        assert!(!e.to_string().contains('\n'), "{e}");
        assert!(e.to_string().contains("length"), "{e}");
        let e = to_toml(&PageArm {
            name: "x".into(),
            base: [0.0, 0.0],
            links: vec![PageLink { length: 1.0, angle_deg: 50.0, limits_deg: Some([10.0, 45.0]), rate: None }],
        })
        .unwrap_err();
        assert!(e.to_string().contains("limits"), "{e}");
    }
}
