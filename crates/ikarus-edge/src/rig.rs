//! Rig files (TOML): a skeleton in degrees, plus optional solver defaults.
//!
//! ```toml
//! name = "puppet"
//! base = [0.0, 0.0]              # optional
//! [[bones]]
//! name = "pelvis"
//! length = 0.4
//! angle_deg = 90.0
//! [[bones]]
//! name = "spine"
//! parent = "pelvis"              # absent: starts at the base
//! length = 1.0
//! angle_deg = 0.0                # relative to the parent's direction (a root's to +x)
//! limits_deg = [-30.0, 30.0]     # optional
//! offset = [0.5, 0.1]            # optional: the origin in the parent's frame (default its tip)
//! [[bones]]
//! name = "ram"
//! parent = "spine"
//! length = 0.5
//! joint = "prismatic"            # optional: "revolute" (the default) or "prismatic"
//! slide = [1.0, 0.0]             # prismatic: the direction in the parent's frame (default along the bone)
//! extension = 0.1                # prismatic: the start displacement (default 0)
//! limits = [0.0, 0.4]            # prismatic: the displacement's range, length units
//! [solver]                       # optional, as in arm files; flags override it
//! method = "dls"
//! ```
//!
//! A bone's name is unique and holds no whitespace, control characters, commas, `=` or quotes
//! (it is written in `--goal NAME=X,Y` and in CSV headers `NAME.x`). Bones are kept in the
//! order written: a bone's index (in messages, in angles) is its place in
//! the file, and a parent may come after its children. Every problem becomes one line naming
//! the file, the bone (index and name), the field and the value, as arm files do.
//!
//! A rig has at most a capped number of bones ([`BoneCap`]: the command line's
//! [`DEFAULT_MAX_BONES`] unless `ikarus --max-bones N` says otherwise, the server's
//! `--max-bones`), counted in the file as read, before any bone is checked or built.
//!
//! This file reads a rig file (the reader, the caps, the loaded [`Rig`]); `skeleton` checks
//! its bones and converts them into the library's skeleton.

mod skeleton;

use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};

use ikarus::Skeleton;
use serde::Deserialize;

pub use crate::arm::JointFile;
use crate::arm::{ArmFile, part_file, toml_error};
use crate::error::Error;
use crate::settings::SolverSettings;

/// A rig as written in a file: names and units of the edge (degrees).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RigFile {
    /// A name for the rig, shown in outputs.
    #[serde(default)]
    pub name: Option<String>,
    /// Base position, where every root bone starts; the origin when absent.
    #[serde(default)]
    pub base: Option<[f64; 2]>,
    /// Bones, in any order that names existing parents.
    #[serde(default)]
    pub bones: Vec<BoneFile>,
    /// Solver defaults: the `[solver]` table, which flags override (as in arm files).
    #[serde(default)]
    pub solver: SolverSettings,
    /// Made from an arm file's links ([`RigFile::from_arm`]): messages name a bone as the arm
    /// file does, `links[i]`, not `bones[i] ("link{i}")`. Never read from a file or a request.
    #[serde(skip)]
    links: bool,
}

part_file! {
    /// One `[[bones]]` entry.
    #[derive(Debug, Clone, Deserialize)]
    #[serde(deny_unknown_fields)]
    pub struct BoneFile {
        /// Name, unique in the rig.
        pub name: String,
        /// The parent's name; absent for a bone that starts at the base.
        #[serde(default)]
        pub parent: Option<String>,
    } {
        /// How much the bone resists turning away from its rest angle, ≥ 0 (absent: 0, no
        /// preference); see `ikarus::Bone::stiffness`.
        #[serde(default)]
        pub stiffness: Option<f64>,
        /// The angle the bone is pulled back to, degrees (absent: `angle_deg`).
        #[serde(default)]
        pub rest_deg: Option<f64>,
    }
}

/// The most bones of a rig the command line (and Python) reads unless `ikarus --max-bones N`
/// raises it: far beyond any character (the puppet has 16), and a rig this size is read and
/// solved in well under a second.
pub const DEFAULT_MAX_BONES: usize = 10_000;

static MAX_BONES: AtomicUsize = AtomicUsize::new(DEFAULT_MAX_BONES);

/// Sets the command line's cap (from `--max-bones`).
pub fn set_max_bones(bones: usize) {
    MAX_BONES.store(bones, Ordering::Relaxed);
}

/// The most bones a rig may have, and how to raise the cap (said in the message).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BoneCap {
    /// The most bones.
    pub max: usize,
    /// How the cap is raised, in the message's parentheses (`--max-bones`).
    pub raise: &'static str,
}

impl BoneCap {
    /// The command line's: [`DEFAULT_MAX_BONES`], or `ikarus --max-bones N`.
    #[must_use]
    pub fn cli() -> Self {
        Self { max: MAX_BONES.load(Ordering::Relaxed), raise: "raise it with --max-bones N" }
    }

    /// A server's (or an edge's), set by its `--max-bones` flag.
    #[must_use]
    pub fn flag(max: usize) -> Self {
        Self { max, raise: "--max-bones" }
    }

    /// `bones: N bones exceed the cap of MAX (…)` when `count` is over the cap.
    pub fn check(self, count: usize) -> Result<(), Error> {
        if count > self.max {
            return Err(Error::input(format!("bones: {count} bones exceed the cap of {} ({})", self.max, self.raise)));
        }
        Ok(())
    }
}

/// A loaded rig: the validated skeleton, its name, and the file's solver defaults.
#[derive(Debug, Clone)]
pub struct Rig {
    /// The rig's name, shown in outputs.
    pub name: String,
    /// Where the rig came from, as error messages start (`rig file puppet.toml`).
    pub label: String,
    /// The validated skeleton, start angles in radians.
    pub skeleton: Skeleton,
    /// The file's `[solver]` table, under any flag or request field.
    pub solver: SolverSettings,
    /// The bone a goal without a bone's name is on (`--goal X,Y`, a request's `goal`): an arm
    /// file's last link; `None` for a rig file, whose goals name their bones.
    pub tip: Option<usize>,
}

impl Rig {
    /// The options of a command: `flags` over this rig file's `[solver]` table over the
    /// defaults, `rates` one per bone; problems name the flag, or the file's `[solver]` field a
    /// setting came from (as [`crate::arm::Arm::options`]).
    pub fn options(&self, flags: &SolverSettings, record_every: Option<u32>) -> Result<ikarus::SolveOptions, Error> {
        crate::settings::command_options(flags, &self.solver, &self.label, self.skeleton.len(), record_every)
    }

    /// Loads the rig file `path` (a regular file within the input cap, as every input file)
    /// under the command line's cap on bones.
    pub fn load(path: &Path) -> Result<Self, Error> {
        let label = format!("rig file {}", path.display());
        let text = crate::input::read_text(path, &label)?;
        Self::parse(&text, &label)
    }

    /// Parses and validates rig-file text under the command line's cap on bones
    /// ([`BoneCap::cli`]); `label` starts every error message.
    pub fn parse(text: &str, label: &str) -> Result<Self, Error> {
        Self::parse_within(text, label, BoneCap::cli())
    }

    /// Parses and validates rig-file text of at most `cap` bones; `label` starts every error
    /// message.
    pub fn parse_within(text: &str, label: &str, cap: BoneCap) -> Result<Self, Error> {
        Self::from_file(RigFile::read(text, label, cap)?, label, cap)
    }

    /// Validates a rig already read (from a file or a JSON request) of at most `cap` bones (the
    /// first check, before any bone is looked at); `label` starts every error message.
    pub fn from_file(file: RigFile, label: &str, cap: BoneCap) -> Result<Self, Error> {
        cap.check(file.bones.len()).map_err(|msg| Error::input(format!("{label}: {msg}")))?;
        let skeleton = file.to_skeleton().map_err(|msg| Error::input(format!("{label}: {msg}")))?;
        file.solver.check().map_err(|msg| Error::input(format!("{label}: [solver].{msg}")))?;
        let name = file.name.clone().unwrap_or_else(|| "rig".to_owned());
        Ok(Self { name, label: label.to_owned(), skeleton, solver: file.solver, tip: None })
    }

    /// The one-branch rig of an arm file: link `i` is bone `link{i}` (as
    /// [`ikarus::Chain::new`] names them) on bone `link{i-1}`, with the link's joint keys; its
    /// name is the arm's (`arm` without one), a goal without a bone's name is on the last link,
    /// and every problem is named as in an arm file (`arm file a.toml: links[2].limits_deg = …`).
    pub fn from_arm(file: &ArmFile, label: &str) -> Result<Self, Error> {
        let mut rig = Self::from_file(RigFile::from_arm(file), label, BoneCap::cli())?;
        rig.tip = rig.skeleton.len().checked_sub(1);
        Ok(rig)
    }
}

impl RigFile {
    /// An arm file's links as the bones of a one-branch rig: `link{i}` on `link{i-1}`, each
    /// with the link's length, angle, limits and joint keys; the same base, name and `[solver]`.
    #[must_use]
    pub fn from_arm(arm: &ArmFile) -> Self {
        let bones = arm
            .links
            .iter()
            .enumerate()
            .map(|(i, l)| BoneFile {
                name: format!("link{i}"),
                parent: i.checked_sub(1).map(|p| format!("link{p}")),
                length: l.length,
                angle_deg: l.angle_deg,
                limits_deg: l.limits_deg,
                stiffness: None,
                rest_deg: None,
                offset: l.offset,
                joint: l.joint,
                slide: l.slide,
                extension: l.extension,
                limits: l.limits,
            })
            .collect();
        let name = Some(arm.name.clone().unwrap_or_else(|| "arm".to_owned()));
        Self { name, base: arm.base, bones, solver: arm.solver.clone(), links: true }
    }

    /// Reads rig-file text (TOML) of at most `cap` bones, unchecked otherwise; `label` starts
    /// every error message.
    pub fn read(text: &str, label: &str, cap: BoneCap) -> Result<Self, Error> {
        let over = |count: usize| cap.check(count).map_err(|msg| Error::input(format!("{label}: {msg}")));
        // Bones written as `[[bones]]` tables are counted on the text first, so that a file far
        // over the cap is refused before the TOML parser holds it (some 40 times its size in
        // memory, seconds for a few MB); bones in an inline array are counted once parsed. (A
        // `[[bones]]` line inside a multi-line string would be counted too: no rig has one.)
        over(text.lines().filter(|l| is_bones_header(l)).count())?;
        if crate::character::atlas::is_atlas(text) {
            return Err(Error::input(format!("{label}: {}", crate::character::atlas::ATLAS)));
        }
        let file: RigFile = toml::from_str(text).map_err(|e| Error::input(toml_error(label, text, &e)))?;
        over(file.bones.len())?;
        Ok(file)
    }
}

/// Whether `line` is a `[[bones]]` header (spaces and a comment aside).
fn is_bones_header(line: &str) -> bool {
    let line = line.split('#').next().unwrap_or_default().trim();
    line.strip_prefix("[[").and_then(|l| l.strip_suffix("]]")).is_some_and(|key| key.trim() == "bones")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_issues_example_reads() {
        let rig = Rig::parse(
            "name = \"puppet\"\nbase = [0.0, 0.0]\n\
             [[bones]]\nname = \"pelvis\"\nlength = 0.4\nangle_deg = 90.0\n\
             [[bones]]\nname = \"spine\"\nparent = \"pelvis\"\nlength = 1.0\nangle_deg = 0.0\nlimits_deg = [-30.0, 30.0]\n\
             [solver]\nmethod = \"dls\"\n",
            "r",
        )
        .unwrap();
        assert_eq!(rig.name, "puppet");
        let s = &rig.skeleton;
        assert_eq!(s.names(), &["pelvis", "spine"]);
        assert_eq!(s.parents(), &[None, Some(0)]);
        assert!((s.start_angles()[0] - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
        let lim = s.limits()[1].unwrap();
        assert!((lim.min() + 30f64.to_radians()).abs() < 1e-15 && (lim.max() - 30f64.to_radians()).abs() < 1e-15);
        assert_eq!(rig.solver.method, Some(ikarus::Method::DampedLeastSquares));
    }

    #[test]
    fn a_rig_over_the_cap_is_refused_however_its_bones_are_written() {
        let cap = BoneCap { max: 2, raise: "--max-bones" };
        let tables = "[[bones]]\nname = \"a\"\nlength = 1\n[[ bones ]] # b\nname = \"b\"\nparent = \"a\"\nlength = 1\n";
        assert_eq!(Rig::parse_within(tables, "r", cap).unwrap().skeleton.len(), 2);
        let three = format!("{tables}[[bones]]\nname = \"c\"\nlength = 1\n");
        let want = "r: bones: 3 bones exceed the cap of 2 (--max-bones)";
        assert_eq!(Rig::parse_within(&three, "r", cap).unwrap_err().to_string(), want);
        // Refused on the count although the rest of the file is not TOML.
        assert_eq!(Rig::parse_within(&format!("{three}[[[ not toml"), "r", cap).unwrap_err().to_string(), want);
        let inline = "bones = [{name = \"a\", length = 1}, {name = \"b\", length = 1}, {name = \"c\", length = 1}]\n";
        assert_eq!(Rig::parse_within(inline, "r", cap).unwrap_err().to_string(), want);
        let e = Rig::parse_within(inline, "rig file x.toml", BoneCap::cli()).map(|r| r.skeleton.len());
        assert_eq!(e.unwrap(), 3);
    }

    /// An arm file's link takes the joint's keys a rig file's bone takes, under the same names
    /// and in the same order: the bone's keys but its own (`name`, `parent`, `stiffness`,
    /// `rest_deg`), as each reader lists them for an unknown key.
    #[test]
    fn a_link_takes_the_joint_keys_of_a_bone() {
        fn expected(message: String) -> Vec<String> {
            let list = message.split("expected one of ").nth(1).unwrap_or_else(|| panic!("{message}"));
            list.split(", ").map(|k| k.trim_matches('`').to_owned()).collect()
        }
        let link = expected(crate::arm::Arm::parse("[[links]]\nlength = 1\nbogus = 1\n", "a").unwrap_err().to_string());
        let bone =
            expected(Rig::parse("[[bones]]\nname = \"a\"\nlength = 1\nbogus = 1\n", "r").unwrap_err().to_string());
        let own = ["name", "parent", "stiffness", "rest_deg"];
        let shared: Vec<String> = bone.iter().filter(|k| !own.contains(&k.as_str())).cloned().collect();
        assert_eq!(link, shared);
        assert_eq!(
            link,
            ["length", "angle_deg", "limits_deg", "offset", "joint", "slide", "extension", "limits"].map(String::from)
        );
    }

    #[test]
    fn names_beyond_ascii_and_with_dots_are_fine() {
        let rig = Rig::parse("[[bones]]\nname = \"Hüfte.links-1_a\"\nlength = 1\n", "r").unwrap();
        assert_eq!(rig.skeleton.names(), &["Hüfte.links-1_a"]);
    }

    #[test]
    fn a_missing_or_special_file_is_reported_plainly() {
        let e = Rig::load(Path::new("/nonexistent/rig.toml")).unwrap_err().to_string();
        assert_eq!(e, "rig file /nonexistent/rig.toml: cannot read: No such file or directory");
        let e = Rig::load(Path::new("/dev/zero")).unwrap_err().to_string();
        assert!(e.starts_with("rig file /dev/zero: cannot read: not a regular file"), "{e}");
    }
}
