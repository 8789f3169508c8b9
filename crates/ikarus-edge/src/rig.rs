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

use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};

use ikarus::number::Num;
use ikarus::{Bone, BoneField, JointLimits, Skeleton, SkeletonError};
use serde::Deserialize;

pub use crate::arm::JointFile;
use crate::arm::{ArmFile, limits_problem, start_angle, toml_error};
use crate::error::CliError;
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

/// One `[[bones]]` entry.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BoneFile {
    /// Name, unique in the rig.
    pub name: String,
    /// The parent's name; absent for a bone that starts at the base.
    #[serde(default)]
    pub parent: Option<String>,
    /// Bone length.
    pub length: f64,
    /// Start angle, degrees, relative to the parent's direction (a root's to +x).
    #[serde(default)]
    pub angle_deg: f64,
    /// Optional `[min, max]` range of the angle, degrees.
    #[serde(default)]
    pub limits_deg: Option<[f64; 2]>,
    /// How much the bone resists turning away from its rest angle, ≥ 0 (absent: 0, no
    /// preference); see `ikarus::Bone::stiffness`.
    #[serde(default)]
    pub stiffness: Option<f64>,
    /// The angle the bone is pulled back to, degrees (absent: `angle_deg`).
    #[serde(default)]
    pub rest_deg: Option<f64>,
    /// The bone's origin in its parent's frame (a root's from the base); absent: the
    /// parent's tip.
    #[serde(default)]
    pub offset: Option<[f64; 2]>,
    /// The joint's kind; absent: revolute.
    #[serde(default)]
    pub joint: Option<JointFile>,
    /// A prismatic joint's direction in the parent's frame; absent: along the bone.
    #[serde(default)]
    pub slide: Option<[f64; 2]>,
    /// A prismatic joint's start displacement; absent: 0.
    #[serde(default)]
    pub extension: Option<f64>,
    /// A prismatic joint's `[min, max]` displacement, length units.
    #[serde(default)]
    pub limits: Option<[f64; 2]>,
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
    pub fn check(self, count: usize) -> Result<(), String> {
        if count > self.max {
            return Err(format!("bones: {count} bones exceed the cap of {} ({})", self.max, self.raise));
        }
        Ok(())
    }
}

/// A loaded rig: the validated skeleton, its name, and the file's solver defaults.
#[derive(Debug, Clone)]
pub struct Rig {
    pub name: String,
    /// Where the rig came from, as error messages start (`rig file puppet.toml`).
    pub label: String,
    pub skeleton: Skeleton,
    pub solver: SolverSettings,
    /// The bone a goal without a bone's name is on (`--goal X,Y`, a request's `goal`): an arm
    /// file's last link; `None` for a rig file, whose goals name their bones.
    pub tip: Option<usize>,
}

impl Rig {
    /// The options of a command: `flags` over this rig file's `[solver]` table over the
    /// defaults, `rates` one per bone; problems name the flag, or the file's `[solver]` field a
    /// setting came from (as [`crate::arm::Arm::options`]).
    pub fn options(&self, flags: &SolverSettings, record_every: Option<u32>) -> Result<ikarus::SolveOptions, CliError> {
        crate::settings::command_options(flags, &self.solver, &self.label, self.skeleton.len(), record_every)
    }

    /// Loads the rig file `path` (a regular file within the input cap, as every input file)
    /// under the command line's cap on bones.
    pub fn load(path: &Path) -> Result<Self, CliError> {
        let label = format!("rig file {}", path.display());
        let text = crate::input::read_text(path, &label)?;
        Self::parse(&text, &label)
    }

    /// Parses and validates rig-file text under the command line's cap on bones
    /// ([`BoneCap::cli`]); `label` starts every error message.
    pub fn parse(text: &str, label: &str) -> Result<Self, CliError> {
        Self::parse_within(text, label, BoneCap::cli())
    }

    /// Parses and validates rig-file text of at most `cap` bones; `label` starts every error
    /// message.
    pub fn parse_within(text: &str, label: &str, cap: BoneCap) -> Result<Self, CliError> {
        Self::from_file(RigFile::read(text, label, cap)?, label, cap)
    }

    /// Validates a rig already read (from a file or a JSON request) of at most `cap` bones (the
    /// first check, before any bone is looked at); `label` starts every error message.
    pub fn from_file(file: RigFile, label: &str, cap: BoneCap) -> Result<Self, CliError> {
        cap.check(file.bones.len()).map_err(|msg| CliError::input(format!("{label}: {msg}")))?;
        let skeleton = file.to_skeleton().map_err(|msg| CliError::input(format!("{label}: {msg}")))?;
        file.solver.check().map_err(|msg| CliError::input(format!("{label}: [solver].{msg}")))?;
        let name = file.name.clone().unwrap_or_else(|| "rig".to_owned());
        Ok(Self { name, label: label.to_owned(), skeleton, solver: file.solver, tip: None })
    }

    /// The one-branch rig of an arm file: link `i` is bone `link{i}` (as
    /// [`Skeleton::from_chain`] names them) on bone `link{i-1}`, with the link's joint keys; its
    /// name is the arm's (`arm` without one), a goal without a bone's name is on the last link,
    /// and every problem is named as in an arm file (`arm file a.toml: links[2].limits_deg = …`).
    pub fn from_arm(file: &ArmFile, label: &str) -> Result<Self, CliError> {
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
    pub fn read(text: &str, label: &str, cap: BoneCap) -> Result<Self, CliError> {
        let over = |count: usize| cap.check(count).map_err(|msg| CliError::input(format!("{label}: {msg}")));
        // Bones written as `[[bones]]` tables are counted on the text first, so that a file far
        // over the cap is refused before the TOML parser holds it (some 40 times its size in
        // memory, seconds for a few MB); bones in an inline array are counted once parsed. (A
        // `[[bones]]` line inside a multi-line string would be counted too: no rig has one.)
        over(text.lines().filter(|l| is_bones_header(l)).count())?;
        let file: RigFile = toml::from_str(text).map_err(|e| CliError::input(toml_error(label, text, &e)))?;
        over(file.bones.len())?;
        Ok(file)
    }

    /// Builds the skeleton, describing any problem in the file's own names and numbers.
    pub fn to_skeleton(&self) -> Result<Skeleton, String> {
        let mut bones = Vec::with_capacity(self.bones.len());
        for (i, b) in self.bones.iter().enumerate() {
            if let Some(c) = b.name.chars().find(|&c| !name_char(c)) {
                return Err(format!(
                    "{}.name = {:?}: must not contain {c:?} (no spaces, control characters, commas, '=' or quotes: \
                     names are written in --goal NAME=X,Y and in CSV headers NAME.x)",
                    self.bone(i),
                    b.name
                ));
            }
            let mut bone = Bone::new(b.name.clone(), b.length, start_angle(b.angle_deg, b.limits_deg).to_radians());
            bone.parent.clone_from(&b.parent);
            bone.offset = b.offset;
            bone = self.joint(i, bone)?;
            if let Some([lo, hi]) = b.limits_deg {
                let limits = JointLimits::new(lo.to_radians(), hi.to_radians()).map_err(|_| {
                    format!("{}.limits_deg = [{}, {}]: {}", self.bone(i), Num(lo), Num(hi), limits_problem(lo, hi))
                })?;
                bone = bone.with_limits(limits);
            }
            bone.stiffness = b.stiffness.unwrap_or(0.0);
            bone.rest = b.rest_deg.map(f64::to_radians);
            bones.push(bone);
        }
        Skeleton::new(self.base.unwrap_or([0.0, 0.0]), &bones).map_err(|e| self.describe(&e))
    }

    /// Bone `i`'s joint from its `joint`, `slide`, `extension` and `limits` keys: a revolute
    /// joint takes none of the last three, a prismatic one no `limits_deg` or `rest_deg`.
    fn joint(&self, i: usize, bone: Bone) -> Result<Bone, String> {
        let b = &self.bones[i];
        let refuse = |key: &str, kind: &str| Err(format!("{}.{key}: not for a {kind}", self.bone(i)));
        match b.joint.unwrap_or(JointFile::Revolute) {
            JointFile::Revolute => {
                for (key, given) in
                    [("slide", b.slide.is_some()), ("extension", b.extension.is_some()), ("limits", b.limits.is_some())]
                {
                    if given {
                        return refuse(
                            key,
                            "revolute joint (say joint = \"prismatic\"; a revolute joint has limits_deg)",
                        );
                    }
                }
                Ok(bone)
            }
            JointFile::Prismatic => {
                if b.limits_deg.is_some() {
                    return refuse("limits_deg", "prismatic joint (its limits = [lo, hi] are in length units)");
                }
                if b.rest_deg.is_some() {
                    return refuse("rest_deg", "prismatic joint");
                }
                let mut bone = bone.prismatic(b.extension.unwrap_or(0.0));
                if let Some(slide) = b.slide {
                    bone = bone.with_slide(slide);
                }
                if let Some([lo, hi]) = b.limits {
                    let limits = JointLimits::new(lo, hi).map_err(|_| {
                        format!("{}.limits = [{}, {}]: {}", self.bone(i), Num(lo), Num(hi), limits_problem(lo, hi))
                    })?;
                    bone = bone.with_limits(limits);
                }
                Ok(bone)
            }
        }
    }

    /// `bones[i] ("name")`, as every message about a bone starts (`links[i]` for an arm's).
    fn bone(&self, i: usize) -> String {
        if self.links { format!("links[{i}]") } else { format!("bones[{i}] ({:?})", self.bones[i].name) }
    }

    /// `message` with an arm's bones named as its links: `bones[2] ("link2")` → `links[2]`.
    fn linked(&self, message: String) -> String {
        if !self.links {
            return message;
        }
        (0..self.bones.len()).rev().fold(message, |m, i| m.replace(&format!("bones[{i}] (\"link{i}\")"), &self.bone(i)))
    }

    fn describe(&self, e: &SkeletonError) -> String {
        match e {
            SkeletonError::Empty => "bones: a rig needs at least one [[bones]] entry, got none".to_owned(),
            SkeletonError::NonFiniteBase { x, y } => {
                format!("base = [{}, {}]: coordinates must be finite", Num(*x), Num(*y))
            }
            SkeletonError::EmptyName { index } => format!("bones[{index}].name = \"\": must not be empty"),
            SkeletonError::DuplicateName { index, name, first } => {
                format!(
                    "{}.name = {name:?}: the name of bones[{first}] already; names must be unique",
                    self.bone(*index)
                )
            }
            SkeletonError::NonPositiveLength { index, value, .. } => {
                format!("{}.length = {}: must be greater than 0", self.bone(*index), Num(*value))
            }
            SkeletonError::NonFinite { index, field: BoneField::Length, value, .. } => {
                format!("{}.length = {}: must be a finite number", self.bone(*index), Num(*value))
            }
            SkeletonError::NonFinite { index, field: BoneField::Stiffness, value, .. } => {
                format!("{}.stiffness = {}: must be a finite number", self.bone(*index), Num(*value))
            }
            SkeletonError::NegativeStiffness { index, value, .. } => {
                format!("{}.stiffness = {}: must be 0 or more", self.bone(*index), Num(*value))
            }
            SkeletonError::NonFinite { index, field: BoneField::Rest, .. } => {
                let value = self.bones[*index].rest_deg.unwrap_or(f64::NAN);
                format!("{}.rest_deg = {}: must be a finite number", self.bone(*index), Num(value))
            }
            SkeletonError::RestOutsideLimits { index, .. } => {
                let b = &self.bones[*index];
                let [lo, hi] = b.limits_deg.unwrap_or([f64::NAN; 2]);
                let value = b.rest_deg.unwrap_or(f64::NAN);
                format!(
                    "{}.rest_deg = {}: outside limits_deg [{}, {}]",
                    self.bone(*index),
                    Num(value),
                    Num(lo),
                    Num(hi)
                )
            }
            SkeletonError::NonFinite { index, field: BoneField::Extension, value, .. } => {
                format!("{}.extension = {}: must be a finite number", self.bone(*index), Num(*value))
            }
            SkeletonError::NonFinite { index, .. } => {
                format!(
                    "{}.angle_deg = {}: must be a finite number",
                    self.bone(*index),
                    Num(self.bones[*index].angle_deg)
                )
            }
            SkeletonError::AngleOutsideLimits { index, .. } => {
                let b = &self.bones[*index];
                let [lo, hi] = b.limits_deg.unwrap_or([f64::NAN; 2]);
                format!(
                    "{}.angle_deg = {}: outside limits_deg [{}, {}]",
                    self.bone(*index),
                    Num(b.angle_deg),
                    Num(lo),
                    Num(hi)
                )
            }
            // Already in the file's terms: `bones[i] ("name").parent = "p": …`, the reach (an
            // arm's bone named as its link).
            _ => self.linked(e.to_string()),
        }
    }
}

/// Whether `line` is a `[[bones]]` header (spaces and a comment aside).
fn is_bones_header(line: &str) -> bool {
    let line = line.split('#').next().unwrap_or_default().trim();
    line.strip_prefix("[[").and_then(|l| l.strip_suffix("]]")).is_some_and(|key| key.trim() == "bones")
}

/// Whether `c` may appear in a bone's name: a name goes into `--goal NAME=X,Y`, into CSV
/// headers `NAME.x` (split at the last `.`) and into JSON keys, so it holds no whitespace or
/// control characters, commas, `=` or quotes.
fn name_char(c: char) -> bool {
    !(c.is_whitespace() || c.is_control() || matches!(c, ',' | '=' | '"' | '\''))
}

#[cfg(test)]
mod tests {
    use super::*;
    use ikarus::Point2;

    fn err(text: &str) -> String {
        match Rig::parse(text, "rig file r.toml") {
            Ok(_) => panic!("accepted: {text}"),
            Err(e) => e.to_string(),
        }
    }

    fn shipped(file: &str) -> Rig {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/rigs").join(file);
        Rig::load(&path).unwrap_or_else(|e| panic!("{file}: {e}"))
    }

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

    /// `stiffness` and `rest_deg` (degrees, by default the start angle) reach the skeleton;
    /// the shipped puppet holds its torso stiffer than its limbs.
    #[test]
    fn the_rest_pose_preference_reads() {
        let rig = Rig::parse(
            "[[bones]]\nname = \"a\"\nlength = 1\nangle_deg = 30\nstiffness = 2.5\n\
             [[bones]]\nname = \"b\"\nparent = \"a\"\nlength = 1\nangle_deg = 10\nrest_deg = -20\n",
            "r",
        )
        .unwrap();
        let s = &rig.skeleton;
        assert_eq!(s.stiffness(), &[2.5, 0.0]);
        assert_eq!(s.rest_angles(), &[30f64.to_radians(), (-20f64).to_radians()]);
        assert!(s.has_rest_pose());
        let puppet = shipped("puppet.toml").skeleton;
        let of = |n: &str| puppet.stiffness()[puppet.index_of(n).unwrap()];
        for (stiff, supple) in [("spine", "right_upper_arm"), ("neck", "left_forearm"), ("pelvis", "left_thigh")] {
            assert!(of(stiff) > of(supple), "{stiff} {supple}");
        }
        assert_eq!(puppet.rest_angles(), puppet.start_angles());
        assert!(shipped("hand.toml").skeleton.has_rest_pose());
    }

    #[test]
    fn each_problem_is_one_line_naming_the_bone_field_and_value() {
        let a = "[[bones]]\nname = \"a\"\nlength = 1\n";
        let cases = [
            // Duplicate names.
            (
                format!(
                    "{a}[[bones]]\nname = \"neck\"\nparent = \"a\"\nlength = 1\n[[bones]]\nname = \"neck\"\nlength = 1\n"
                ),
                "rig file r.toml: bones[2] (\"neck\").name = \"neck\": the name of bones[1] already; names must be unique",
            ),
            (
                format!("{a}[[bones]]\nname = \"\"\nlength = 1\n"),
                "rig file r.toml: bones[1].name = \"\": must not be empty",
            ),
            // Names that --goal NAME=X,Y or a CSV header could not carry.
            (
                format!("{a}[[bones]]\nname = \"left hand\"\nlength = 1\n"),
                "rig file r.toml: bones[1] (\"left hand\").name = \"left hand\": must not contain ' ' (no spaces",
            ),
            (
                format!("{a}[[bones]]\nname = \"a=b\"\nlength = 1\n"),
                "rig file r.toml: bones[1] (\"a=b\").name = \"a=b\": must not contain '='",
            ),
            (
                format!("{a}[[bones]]\nname = \"x,y\"\nlength = 1\n"),
                "rig file r.toml: bones[1] (\"x,y\").name = \"x,y\": must not contain ','",
            ),
            // A missing parent.
            (
                format!("{a}[[bones]]\nname = \"spine\"\nparent = \"pelvs\"\nlength = 1\n"),
                "rig file r.toml: bones[1] (\"spine\").parent = \"pelvs\": no bone of that name",
            ),
            // A cycle, and a bone its own parent.
            (
                format!(
                    "{a}[[bones]]\nname = \"b\"\nparent = \"c\"\nlength = 1\n[[bones]]\nname = \"c\"\nparent = \"b\"\nlength = 1\n"
                ),
                "rig file r.toml: bones[1] (\"b\").parent = \"c\": a cycle (b → c → b); a bone cannot be its own ancestor",
            ),
            (
                "[[bones]]\nname = \"a\"\nparent = \"a\"\nlength = 1\n".to_owned(),
                "rig file r.toml: bones[0] (\"a\").parent = \"a\": a cycle (a → a)",
            ),
            // Bad lengths.
            (
                format!("{a}[[bones]]\nname = \"b\"\nlength = -1\n"),
                "rig file r.toml: bones[1] (\"b\").length = -1: must be greater than 0",
            ),
            (
                "[[bones]]\nname = \"a\"\nlength = nan\n".to_owned(),
                "rig file r.toml: bones[0] (\"a\").length = NaN: must be a finite",
            ),
            ("[[bones]]\nname = \"a\"\n".to_owned(), "rig file r.toml: line 1, column 1: missing field `length`"),
            ("[[bones]]\nlength = 1\n".to_owned(), "rig file r.toml: line 1, column 1: missing field `name`"),
            // Angles outside their limits, malformed limits, a non-finite angle.
            (
                format!(
                    "{a}[[bones]]\nname = \"neck\"\nparent = \"a\"\nlength = 1\nangle_deg = 50\nlimits_deg = [-45, 45]\n"
                ),
                "rig file r.toml: bones[1] (\"neck\").angle_deg = 50: outside limits_deg [-45, 45]",
            ),
            (
                format!("{a}[[bones]]\nname = \"neck\"\nparent = \"a\"\nlength = 1\nlimits_deg = [45, -45]\n"),
                "rig file r.toml: bones[1] (\"neck\").limits_deg = [45, -45]: min must not exceed max",
            ),
            (
                "[[bones]]\nname = \"a\"\nlength = 1\nangle_deg = inf\n".to_owned(),
                "rig file r.toml: bones[0] (\"a\").angle_deg = inf: must be a finite number",
            ),
            // A bad rest-pose preference.
            (
                "[[bones]]\nname = \"a\"\nlength = 1\nstiffness = -2\n".to_owned(),
                "rig file r.toml: bones[0] (\"a\").stiffness = -2: must be 0 or more",
            ),
            (
                "[[bones]]\nname = \"a\"\nlength = 1\nstiffness = nan\n".to_owned(),
                "rig file r.toml: bones[0] (\"a\").stiffness = NaN: must be a finite number",
            ),
            (
                "[[bones]]\nname = \"a\"\nlength = 1\nrest_deg = 60\nlimits_deg = [-45, 45]\n".to_owned(),
                "rig file r.toml: bones[0] (\"a\").rest_deg = 60: outside limits_deg [-45, 45]",
            ),
            (
                "[[bones]]\nname = \"a\"\nlength = 1\nrest_deg = -inf\n".to_owned(),
                "rig file r.toml: bones[0] (\"a\").rest_deg = -inf: must be a finite number",
            ),
            // Unknown keys, at the top, in a bone, in the solver table.
            (
                "[[bones]]\nname = \"a\"\nlenght = 1\n".to_owned(),
                "rig file r.toml: line 3, column 1: unknown field `lenght`",
            ),
            (format!("{a}links = []\n"), "rig file r.toml: line 4, column 1: unknown field `links`"),
            (format!("{a}[solver]\nspeed = 1\n"), "rig file r.toml: line 5, column 1: unknown field `speed`"),
            (format!("{a}[solver]\nlambda = -1\n"), "rig file r.toml: [solver].lambda = -1: must be"),
            // The rest of a rig.
            ("name = \"x\"\n".to_owned(), "rig file r.toml: bones: a rig needs at least one [[bones]] entry, got none"),
            (format!("base = [inf, 0]\n{a}"), "rig file r.toml: base = [inf, 0]: coordinates must be finite"),
            (
                "[[bones]]\nname = \"a\"\nlength = 1e300\n".to_owned(),
                "rig file r.toml: bones: the longest path of lengths reaches 1e300 from the origin, beyond 1e152",
            ),
            ("[[bones]\n".to_owned(), "rig file r.toml: line 1"),
        ];
        for (text, want) in cases {
            let got = err(&text);
            assert!(got.starts_with(want), "for {text:?}\n got {got:?}\nwant {want:?}");
            assert!(!got.contains('\n'), "multi-line: {got:?}");
        }
    }

    /// The bones are counted before the file is parsed, as `[[bones]]` headers, and after, in
    /// an inline array; one line either way.
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

    /// Names may hold any other character: letters of any script, digits, `.`, `-`, `_`.
    #[test]
    fn names_beyond_ascii_and_with_dots_are_fine() {
        let rig = Rig::parse("[[bones]]\nname = \"Hüfte.links-1_a\"\nlength = 1\n", "r").unwrap();
        assert_eq!(rig.skeleton.names(), &["Hüfte.links-1_a"]);
    }

    /// Start angles are normalised as in arm files: onto the turn inside the limits, or
    /// wrapped without limits.
    #[test]
    fn start_angles_are_normalised() {
        let rig = Rig::parse(
            "[[bones]]\nname = \"a\"\nlength = 1\nangle_deg = 1e20\n\
             [[bones]]\nname = \"b\"\nparent = \"a\"\nlength = 1\nangle_deg = 370\nlimits_deg = [0, 45]\n",
            "r",
        )
        .unwrap();
        let got: Vec<f64> = rig.skeleton.start_angles().iter().map(|a| a.to_degrees()).collect();
        assert!((got[0] + 80.0).abs() < 1e-12 && (got[1] - 10.0).abs() < 1e-12, "{got:?}");
    }

    #[test]
    fn a_missing_or_special_file_is_reported_plainly() {
        let e = Rig::load(Path::new("/nonexistent/rig.toml")).unwrap_err().to_string();
        assert_eq!(e, "rig file /nonexistent/rig.toml: cannot read: No such file or directory");
        let e = Rig::load(Path::new("/dev/zero")).unwrap_err().to_string();
        assert!(e.starts_with("rig file /dev/zero: cannot read: not a regular file"), "{e}");
    }

    #[test]
    fn the_shipped_rigs_load() {
        let puppet = shipped("puppet.toml");
        assert_eq!(puppet.name, "puppet");
        assert!(puppet.skeleton.len() >= 16, "{}", puppet.skeleton.len());
        for name in [
            "pelvis",
            "spine",
            "neck",
            "head",
            "left_upper_arm",
            "left_forearm",
            "left_hand",
            "right_upper_arm",
            "right_forearm",
            "right_hand",
            "left_thigh",
            "left_shin",
            "left_foot",
            "right_thigh",
            "right_shin",
            "right_foot",
        ] {
            let i = puppet.skeleton.index_of(name).unwrap_or_else(|| panic!("no {name}"));
            assert!(puppet.skeleton.limits()[i].is_some(), "{name} has no limits");
        }
        let hand = shipped("hand.toml");
        let s = &hand.skeleton;
        assert_eq!(s.len(), 17);
        let (wrist, palm) = (s.index_of("wrist").unwrap(), s.index_of("palm").unwrap());
        assert_eq!((s.parent(wrist), s.parent(palm)), (None, Some(wrist)));
        // Five fingers of three bones each: five tips, each three bones below the palm or the
        // wrist (the thumb).
        let tips: Vec<usize> = (0..s.len()).filter(|&i| s.children(i).len() == 0).collect();
        assert_eq!(tips.len(), 5, "{:?}", tips.iter().map(|&i| s.name(i)).collect::<Vec<_>>());
        for &t in &tips {
            let path = s.path(t);
            let finger: Vec<usize> = path.iter().copied().filter(|&b| b != palm && b != wrist).collect();
            assert_eq!(finger.len(), 3, "{}", s.name(t));
            // Flexion mostly one way: every finger joint bends further one way than the other.
            for &b in &finger[1..] {
                let lim = s.limits()[b].unwrap_or_else(|| panic!("{} has no limits", s.name(b)));
                assert!(lim.min().abs() > 2.0 * lim.max().abs(), "{}: {lim:?}", s.name(b));
            }
        }
    }

    #[test]
    fn the_puppet_stands_upright() {
        let rig = shipped("puppet.toml");
        let s = &rig.skeleton;
        let n = s.len();
        let (mut starts, mut tips, mut dirs) = (vec![Point2::origin(); n], vec![Point2::origin(); n], vec![0.0; n]);
        s.forward_into(s.start_angles(), &mut starts, &mut tips, &mut dirs);
        let at = |name: &str| tips[s.index_of(name).unwrap()];
        let (pelvis, head) = (at("pelvis"), at("head"));
        assert!(head.y > pelvis.y + 0.5, "head {head:?}, pelvis {pelvis:?}");
        for foot in ["left_foot", "right_foot"] {
            assert!(at(foot).y < s.base().y - 0.7, "{foot} at {:?}", at(foot));
        }
        for hand in ["left_hand", "right_hand"] {
            assert!(at(hand).y < pelvis.y && at(hand).y > at("left_foot").y, "{hand} at {:?}", at(hand));
        }
        // About 1.8 tall, from the soles to the top of the head.
        let height = head.y - at("left_foot").y.min(at("right_foot").y);
        assert!((1.7..=1.9).contains(&height), "height {height}");
    }
}
