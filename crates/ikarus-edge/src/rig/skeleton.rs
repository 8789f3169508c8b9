//! A rig file's bones into the skeleton: every bone's name, length, angles, limits, rest-pose
//! preference and joint keys checked and converted (degrees to radians), each problem one line
//! naming the bone (index and name), the field and the value.

use ikarus::number::Num;
use ikarus::{Bone, BoneField, JointLimits, Skeleton, SkeletonError};

use super::{JointFile, RigFile};
use crate::arm::{limits_problem, start_angle};
use crate::error::Error;

impl RigFile {
    /// Builds the skeleton, describing any problem in the file's own names and numbers.
    pub fn to_skeleton(&self) -> Result<Skeleton, Error> {
        let mut bones = Vec::with_capacity(self.bones.len());
        for (i, b) in self.bones.iter().enumerate() {
            if let Some(c) = b.name.chars().find(|&c| !name_char(c)) {
                return Err(Error::input(format!(
                    "{}.name = {:?}: must not contain {c:?} (no spaces, control characters, commas, '=' or quotes: \
                     names are written in --goal NAME=X,Y and in CSV headers NAME.x)",
                    self.bone(i),
                    b.name
                )));
            }
            let mut bone = Bone::new(b.name.clone(), b.length, start_angle(b.angle_deg, b.limits_deg).to_radians());
            bone.parent.clone_from(&b.parent);
            bone.offset = b.offset;
            bone = self.joint(i, bone)?;
            if let Some([lo, hi]) = b.limits_deg {
                let limits = JointLimits::new(lo.to_radians(), hi.to_radians()).map_err(|_| {
                    Error::input(format!(
                        "{}.limits_deg = [{}, {}]: {}",
                        self.bone(i),
                        Num(lo),
                        Num(hi),
                        limits_problem(lo, hi)
                    ))
                })?;
                bone = bone.with_limits(limits);
            }
            bone.stiffness = b.stiffness.unwrap_or(0.0);
            bone.rest = b.rest_deg.map(f64::to_radians);
            bones.push(bone);
        }
        Skeleton::new(self.base.unwrap_or([0.0, 0.0]), &bones).map_err(|e| Error::input(self.describe(&e)))
    }

    /// Bone `i`'s joint from its `joint`, `slide`, `extension` and `limits` keys: a revolute
    /// joint takes none of the last three, a prismatic one no `limits_deg` or `rest_deg`.
    fn joint(&self, i: usize, bone: Bone) -> Result<Bone, Error> {
        let b = &self.bones[i];
        let refuse = |key: &str, kind: &str| Err(Error::input(format!("{}.{key}: not for a {kind}", self.bone(i))));
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
                        Error::input(format!(
                            "{}.limits = [{}, {}]: {}",
                            self.bone(i),
                            Num(lo),
                            Num(hi),
                            limits_problem(lo, hi)
                        ))
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

/// Whether `c` may appear in a bone's name: a name goes into `--goal NAME=X,Y`, into CSV
/// headers `NAME.x` (split at the last `.`) and into JSON keys, so it holds no whitespace or
/// control characters, commas, `=` or quotes.
fn name_char(c: char) -> bool {
    !(c.is_whitespace() || c.is_control() || matches!(c, ',' | '=' | '"' | '\''))
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::super::Rig;
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
    /// Names may hold any other character: letters of any script, digits, `.`, `-`, `_`.
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
