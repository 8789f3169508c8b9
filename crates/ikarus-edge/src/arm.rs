//! Arm files (TOML): a chain in degrees, plus optional solver defaults.
//!
//! ```toml
//! name = "seed"
//! base = [0.0, 0.0]          # optional
//! [[links]]
//! length = 3.0
//! angle_deg = 5.0
//! limits_deg = [-45.0, 45.0] # optional
//! [solver]                   # optional; flags override it
//! method = "dls"
//! ```
//!
//! A link may also take a rig file's joint keys (`offset`, `joint = "revolute" | "prismatic"`,
//! `slide`, `extension`, `limits`; see [`crate::rig`]): such an arm is a one-branch rig whose
//! bones are named `link0`, `link1`, … ([`crate::body::Body::from_arm_file`]); `joint =
//! "revolute"` alone changes nothing (the same chain as without it).
//!
//! Every problem becomes one line naming the file, the field and the value.

use std::path::Path;

use ikarus::number::Num;
use ikarus::{Chain, ChainError, JointLimits, Link};
use serde::Deserialize;

use crate::error::Error;
use crate::settings::SolverSettings;

/// The built-in default arm: the seed program's, shipped as `examples/arms/seed.toml`.
pub const DEFAULT_ARM: &str = include_str!("../../../examples/arms/seed.toml");

/// An arm as written in a file: names and units of the edge (degrees).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ArmFile {
    /// A name for the arm, shown in outputs.
    #[serde(default)]
    pub name: Option<String>,
    /// Base position; the origin when absent.
    #[serde(default)]
    pub base: Option<[f64; 2]>,
    /// Links, base to tip.
    #[serde(default)]
    pub links: Vec<LinkFile>,
    /// Solver defaults: the `[solver]` table, which flags override. Field names match the flags.
    #[serde(default)]
    pub solver: SolverSettings,
}

/// Declares a `[[links]]` or a `[[bones]]` entry: the fields of the `{ … }` before, then the
/// joint's fields both take (`length`, `angle_deg`, `limits_deg`), then the fields of the `{ … }`
/// after, then the joint keys (`offset`, `joint`, `slide`, `extension`, `limits`), in that
/// order (the order serde's "expected one of" lists them). Written once for both, so that an
/// arm's link takes every joint key a rig's bone takes, under the same name.
macro_rules! part_file {
    ($(#[$attr:meta])* pub struct $name:ident { $($head:tt)* } { $($tail:tt)* }) => {
        $(#[$attr])*
        pub struct $name {
            $($head)*
            /// Length.
            pub length: f64,
            /// Start angle of the joint, degrees, relative to the parent's direction (a link's
            /// parent is the previous link; the first link's and a root bone's is +x).
            #[serde(default)]
            pub angle_deg: f64,
            /// Optional `[min, max]` range of the joint angle, degrees.
            #[serde(default)]
            pub limits_deg: Option<[f64; 2]>,
            $($tail)*
            /// The origin in the parent's frame (the first link's and a root bone's from the
            /// base); absent: the parent's tip.
            #[serde(default)]
            pub offset: Option<[f64; 2]>,
            /// The joint's kind; absent: revolute.
            #[serde(default)]
            pub joint: Option<$crate::arm::JointFile>,
            /// A prismatic joint's direction in the parent's frame; absent: along the link or
            /// bone.
            #[serde(default)]
            pub slide: Option<[f64; 2]>,
            /// A prismatic joint's start displacement; absent: 0.
            #[serde(default)]
            pub extension: Option<f64>,
            /// A prismatic joint's `[min, max]` displacement, length units.
            #[serde(default)]
            pub limits: Option<[f64; 2]>,
        }
    };
}
pub(crate) use part_file;

part_file! {
    /// One `[[links]]` entry.
    #[derive(Debug, Clone, Default, Deserialize)]
    #[serde(deny_unknown_fields)]
    pub struct LinkFile {} {}
}

impl LinkFile {
    /// The first joint key of this link that a chain's link cannot hold (`offset`,
    /// `joint = "prismatic"`, `slide`, `extension`, `limits`), as `links[i].KEY` names it;
    /// `joint = "revolute"` alone changes nothing.
    #[must_use]
    pub fn joint_key(&self) -> Option<&'static str> {
        [
            ("offset", self.offset.is_some()),
            ("joint", self.joint == Some(JointFile::Prismatic)),
            ("slide", self.slide.is_some()),
            ("extension", self.extension.is_some()),
            ("limits", self.limits.is_some()),
        ]
        .into_iter()
        .find_map(|(key, given)| given.then_some(key))
    }
}

/// A link's or a bone's `joint` key.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum JointFile {
    /// A revolute joint: the link turns about it (the default).
    Revolute,
    /// A prismatic joint: the link slides along `slide` (a rig's joint, not a chain's).
    Prismatic,
}

/// A loaded arm: the validated chain, its name, and the file's solver defaults.
#[derive(Debug, Clone)]
pub struct Arm {
    /// The arm's name, shown in outputs (the file's `name`, else `arm`).
    pub name: String,
    /// Where the arm came from, as error messages start (`arm file a.toml`, `built-in arm`).
    pub label: String,
    /// The links, base to tip, start angles in radians.
    pub chain: Chain,
    /// The file's `[solver]` table, under any flag or request field.
    pub solver: SolverSettings,
}

impl Arm {
    /// The options of a command: `flags` over this arm file's `[solver]` table over the
    /// defaults, for the arm's chain; problems name the flag, or the arm file's `[solver]`
    /// field a setting came from.
    pub fn options(&self, flags: &SolverSettings, record_every: Option<u32>) -> Result<ikarus::SolveOptions, Error> {
        crate::settings::command_options(flags, &self.solver, &self.label, self.chain.len(), record_every)
    }

    /// Whether the arm's joint ranges are respected: `asked` (a flag, a request's `limits`) over
    /// the arm file's `[solver] limits`, off when neither says.
    pub fn limits(&self, asked: Option<bool>) -> bool {
        asked.or(self.solver.limits).unwrap_or(false)
    }

    /// Loads `path`, or the built-in seed arm when `None`.
    pub fn load(path: Option<&Path>) -> Result<Self, Error> {
        match path {
            None => Self::parse(DEFAULT_ARM, "built-in arm"),
            Some(p) => {
                let label = format!("arm file {}", p.display());
                let text = crate::input::read_text(p, &label)?;
                Self::parse(&text, &label)
            }
        }
    }

    /// Parses and validates arm-file text; `label` starts every error message.
    pub fn parse(text: &str, label: &str) -> Result<Self, Error> {
        Self::from_file(ArmFile::read(text, label)?, label)
    }

    /// Validates an arm already read (from a file or a JSON request); `label` starts every
    /// error message.
    ///
    /// A link with joint keys is refused here, naming the first: such an arm is read as a body
    /// ([`crate::body::Body::from_arm_file`]) by the commands that take one.
    pub fn from_file(file: ArmFile, label: &str) -> Result<Self, Error> {
        if let Some((i, key)) = file.joint_key() {
            return Err(Error::input(format!(
                "{label}: links[{i}].{key}: an arm with offsets or slides is a one-branch rig, which this \
                 command does not take (solve, animate, track and workspace do; in the API solve, track \
                 and workspace)"
            )));
        }
        let chain = file.to_chain().map_err(|msg| Error::input(format!("{label}: {msg}")))?;
        file.solver.check().map_err(|msg| Error::input(format!("{label}: [solver].{msg}")))?;
        let name = file.name.clone().unwrap_or_else(|| "arm".to_owned());
        Ok(Self { name, label: label.to_owned(), chain, solver: file.solver })
    }
}

impl ArmFile {
    /// Reads arm-file text (TOML), unchecked otherwise; `label` starts every error message.
    pub fn read(text: &str, label: &str) -> Result<Self, Error> {
        toml::from_str(text).map_err(|e| Error::input(toml_error(label, text, &e)))
    }

    /// The first link that gives a joint key a chain cannot hold, and the key.
    #[must_use]
    pub fn joint_key(&self) -> Option<(usize, &'static str)> {
        self.links.iter().enumerate().find_map(|(i, l)| l.joint_key().map(|k| (i, k)))
    }

    /// Builds the chain, describing any problem in the file's own names and numbers.
    pub fn to_chain(&self) -> Result<Chain, Error> {
        let mut links = Vec::with_capacity(self.links.len());
        for (i, l) in self.links.iter().enumerate() {
            let mut link = Link::new(l.length, start_angle(l.angle_deg, l.limits_deg).to_radians());
            if let Some([lo, hi]) = l.limits_deg {
                let limits = JointLimits::new(lo.to_radians(), hi.to_radians()).map_err(|_| {
                    Error::input(format!(
                        "links[{i}].limits_deg = [{}, {}]: {}",
                        Num(lo),
                        Num(hi),
                        limits_problem(lo, hi)
                    ))
                })?;
                link = link.with_limits(limits);
            }
            links.push(link);
        }
        Chain::new(self.base.unwrap_or([0.0, 0.0]), &links).map_err(|e| Error::input(self.describe(&e)))
    }

    fn describe(&self, e: &ChainError) -> String {
        match *e {
            ChainError::Empty => "links: an arm needs at least one [[links]] entry, got none".to_owned(),
            ChainError::NonFiniteBase { x, y } => {
                format!("base = [{}, {}]: coordinates must be finite", Num(x), Num(y))
            }
            ChainError::NonPositiveLength { index, value } => {
                format!("links[{index}].length = {}: must be greater than 0", Num(value))
            }
            ChainError::NonFinite { index, field: ikarus::LinkField::Length, value } => {
                format!("links[{index}].length = {}: must be a finite number", Num(value))
            }
            ChainError::NonFinite { index, .. } => {
                format!("links[{index}].angle_deg = {}: must be a finite number", Num(self.links[index].angle_deg))
            }
            ChainError::AngleOutsideLimits { index, .. } => {
                let l = &self.links[index];
                let [lo, hi] = l.limits_deg.unwrap_or([f64::NAN; 2]);
                format!(
                    "links[{index}].angle_deg = {}: outside limits_deg [{}, {}]",
                    Num(l.angle_deg),
                    Num(lo),
                    Num(hi)
                )
            }
            _ => e.to_string(),
        }
    }
}

/// A start angle in degrees as the chain takes it: with limits, the angle itself if it lies
/// inside them, else its 360°-equivalent inside them nearest it (so `angle_deg = 370` with
/// `limits_deg = [0, 45]` starts at 10°; none inside is reported as outside the limits);
/// without limits, wrapped into (−180°, 180°] exactly (`angle_deg = 1e300` is a direction, not
/// a number no step could change). See [`ikarus::angle::degrees_within`].
pub fn start_angle(angle_deg: f64, limits_deg: Option<[f64; 2]>) -> f64 {
    if !angle_deg.is_finite() {
        return angle_deg;
    }
    match limits_deg {
        Some([lo, hi]) => ikarus::angle::degrees_within(angle_deg, lo, hi).unwrap_or(angle_deg),
        None => ikarus::angle::wrap_degrees(angle_deg),
    }
}

pub(crate) fn limits_problem(lo: f64, hi: f64) -> &'static str {
    if !lo.is_finite() || !hi.is_finite() { "both ends must be finite numbers" } else { "min must not exceed max" }
}

/// One line for a TOML error: position and message, without the source excerpt.
pub(crate) fn toml_error(label: &str, text: &str, e: &toml::de::Error) -> String {
    let msg = e.message().trim().replace('\n', " ");
    match e.span() {
        Some(span) => {
            let before = &text[..span.start.min(text.len())];
            let line = before.matches('\n').count() + 1;
            let col = before.len() - before.rfind('\n').map_or(0, |i| i + 1) + 1;
            format!("{label}: line {line}, column {col}: {msg}")
        }
        None => format!("{label}: {msg}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn err(text: &str) -> String {
        match Arm::parse(text, "arm file a.toml") {
            Ok(_) => panic!("accepted: {text}"),
            Err(e) => e.to_string(),
        }
    }

    #[test]
    fn the_default_arm_is_the_seed() {
        let arm = Arm::load(None).unwrap();
        assert_eq!(arm.name, "seed");
        assert_eq!(arm.chain.lengths(), &[3.0, 2.0, 1.0]);
        for a in arm.chain.start_pose().angles() {
            assert!((a - 5f64.to_radians()).abs() < 1e-15);
        }
        let lim = arm.chain.limits()[1].unwrap();
        assert!((lim.min() + 90f64.to_radians()).abs() < 1e-15 && (lim.max() - 90f64.to_radians()).abs() < 1e-15);
        assert_eq!(arm.solver.limits, None);
    }

    #[test]
    fn shipped_examples_load() {
        for (file, n) in [("seed.toml", 3), ("seven.toml", 7), ("tentacle.toml", 20)] {
            let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/arms").join(file);
            let arm = Arm::load(Some(&path)).unwrap_or_else(|e| panic!("{file}: {e}"));
            assert_eq!(arm.chain.len(), n, "{file}");
        }
    }

    #[test]
    fn each_problem_is_one_line_naming_field_and_value() {
        let cases = [
            ("[[links]]\nlenght = 1.0\n", "arm file a.toml: line 2, column 1: unknown field `lenght`"),
            ("[[links]]\nlength = -1.0\n", "arm file a.toml: links[0].length = -1: must be greater than 0"),
            ("[[links]]\nlength = nan\n", "arm file a.toml: links[0].length = NaN: must be a finite number"),
            ("[[links]]\nlength = 1\nangle_deg = inf\n", "arm file a.toml: links[0].angle_deg = inf: must be a finite"),
            (
                "[[links]]\nlength = 1\nangle_deg = 50\nlimits_deg = [-45, 45]\n",
                "arm file a.toml: links[0].angle_deg = 50: outside limits_deg [-45, 45]",
            ),
            (
                "[[links]]\nlength = 1\nlimits_deg = [45, -45]\n",
                "arm file a.toml: links[0].limits_deg = [45, -45]: min must not exceed max",
            ),
            ("name = \"x\"\n", "arm file a.toml: links: an arm needs at least one [[links]] entry"),
            (
                "base = [nan, 0]\n[[links]]\nlength = 1\n",
                "arm file a.toml: base = [NaN, 0]: coordinates must be finite",
            ),
            ("[[links]]\nlength = 1\n[solver]\nlambda = -1\n", "arm file a.toml: [solver].lambda = -1: must be"),
            (
                "[[links]]\nlength = 1\n[solver]\nmethod = \"newton\"\n",
                "arm file a.toml: line 4, column 10: unknown variant",
            ),
            ("[[links]]\nlength = \"1\"\n", "arm file a.toml: line 2, column 10: invalid type"),
            ("[[links]\n", "arm file a.toml: line 1"),
        ];
        for (text, want) in cases {
            let got = err(text);
            assert!(got.starts_with(want), "for {text:?}\n got {got:?}\nwant {want:?}");
            assert!(!got.contains('\n'), "multi-line: {got:?}");
        }
    }

    /// Issue 11: `angle_deg = 1e300` was taken as 1.7e298 rad, which no step can change (the
    /// solve stalled after 0 iterations). Start angles are normalised: wrapped without limits,
    /// moved onto the equivalent inside the limits with them.
    #[test]
    fn start_angles_are_normalised() {
        let angles = |text: &str| -> Vec<f64> {
            let arm = Arm::parse(text, "a").unwrap();
            arm.chain.start_pose().angles().iter().map(|a| a.to_degrees()).collect()
        };
        let got = angles(
            "[[links]]\nlength = 1\nangle_deg = 1e20\n\
             [[links]]\nlength = 1\nangle_deg = 370\nlimits_deg = [0, 45]\n\
             [[links]]\nlength = 1\nangle_deg = 400\nlimits_deg = [-720, 720]\n\
             [[links]]\nlength = 1\nangle_deg = -190\n",
        );
        let want = [-80.0, 10.0, 400.0, 170.0];
        for (g, w) in got.iter().zip(want) {
            assert!((g - w).abs() < 1e-12, "{got:?}");
        }
        let big = angles("[[links]]\nlength = 1\nangle_deg = 1e300\n")[0];
        assert!(big.abs() <= 180.0, "{big}");
    }

    /// Issue 11: numbers in error lines were written with every digit (1e300: 301 of them).
    #[test]
    fn numbers_in_errors_are_short() {
        let cases = [
            ("[[links]]\nlength = -1e300\n", "arm file a.toml: links[0].length = -1e300: must be greater than 0"),
            (
                "[[links]]\nlength = 1\nangle_deg = 5e-324\nlimits_deg = [1, 2]\n",
                "arm file a.toml: links[0].angle_deg = 5e-324: outside limits_deg [1, 2]",
            ),
            (
                "[[links]]\nlength = 1\nlimits_deg = [1e300, 5e-324]\n",
                "arm file a.toml: links[0].limits_deg = [1e300, 5e-324]: min must not exceed max",
            ),
            ("[[links]]\nlength = 1\n[solver]\ngain = -1e300\n", "arm file a.toml: [solver].gain = -1e300: must be"),
        ];
        for (text, want) in cases {
            let got = err(text);
            assert!(got.starts_with(want), "got {got:?}, want {want:?}");
        }
    }

    #[test]
    fn a_missing_file_is_reported_plainly() {
        let e = Arm::load(Some(Path::new("/nonexistent/arm.toml"))).unwrap_err().to_string();
        assert_eq!(e, "arm file /nonexistent/arm.toml: cannot read: No such file or directory");
    }
}
