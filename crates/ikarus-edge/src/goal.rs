//! Goals at the edges, from flags or a request: an arm's tip ([`make_goal`], degrees), and a
//! rig's task from names ([`build`]): goals and pins on bones named as in the rig file, checked
//! before any solve with messages in each edge's own field names (`--goal left_hand=…` on the
//! command line, `goals[0].bone` in a request).

use ikarus::character::Character;
use ikarus::{Bend, Goal, Pin, Priority, RigGoal, RigTask, Skeleton};

use crate::error::Error;
use crate::error::FieldPath;

/// A goal at `(x, y)`, with the last link's orientation when `angle_deg` is given (wrapped
/// into (−180°, 180°] exactly before it becomes radians: 1e20° is the direction it names).
pub fn make_goal(x: f64, y: f64, angle_deg: Option<f64>) -> Result<Goal, Error> {
    match angle_deg {
        None => Goal::position(x, y),
        Some(a) if !a.is_finite() => Goal::with_orientation(x, y, a),
        Some(a) => Goal::with_orientation(x, y, ikarus::angle::radians_from_degrees(a)),
    }
    .map_err(|e| Error::input(e.to_string()))
}

/// Most bone names listed in a message about an unknown bone.
const LISTED_NAMES: usize = 24;

/// A goal on the tip of a bone named in the rig, in the edge's units (degrees).
#[derive(Debug, Clone, PartialEq)]
pub struct NamedGoal {
    /// The bone whose tip should reach the goal, by name.
    pub bone: String,
    /// The goal's x.
    pub x: f64,
    /// The goal's y.
    pub y: f64,
    /// The bone's absolute direction wanted, degrees from +x.
    pub angle_deg: Option<f64>,
    /// Its weight when goals conflict, > 0: the heavier is met more closely.
    pub weight: f64,
    /// Primary (solved first, with the pins) or secondary (in what they leave free).
    pub priority: Priority,
    /// Which way the joint between the bone and its parent bends (`None`: either).
    pub bend: Option<Bend>,
    /// How far short of full stretch, in length units, the goal starts to be drawn in smoothly (0: none).
    pub softness: f64,
}

impl NamedGoal {
    /// A primary goal of weight 1 at `(x, y)` for the tip of `bone`, without bend or softness.
    pub fn new(bone: impl Into<String>, x: f64, y: f64, angle_deg: Option<f64>) -> Self {
        Self { bone: bone.into(), x, y, angle_deg, weight: 1.0, priority: Priority::Primary, bend: None, softness: 0.0 }
    }
}

/// What a message is about; the edge turns it into its own field name.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Field {
    /// Goal `i`: its bone and target.
    Goal(usize),
    /// Goal `i`'s weight.
    Weight(usize),
    /// Goal `i`'s softness.
    Softness(usize),
    /// Goal `i`'s bend.
    Bend(usize),
    /// Pin `i`.
    Pin(usize),
    /// How many bones goal `i` turns (a character's goal).
    Bones(usize),
}

impl Field {
    /// This field's path in a request whose goals are the list at `goals` (`goals`, or `via[1]`
    /// for a set of via goals) and whose pins are `pins`: `goals[1].weight`, `via[1][0]`,
    /// `pins[0]`.
    #[must_use]
    pub fn path_in(self, goals: FieldPath) -> FieldPath {
        match self {
            Field::Goal(i) => goals.index(i),
            Field::Weight(i) => goals.index(i).field("weight"),
            Field::Softness(i) => goals.index(i).field("softness"),
            Field::Bend(i) => goals.index(i).field("bend"),
            Field::Bones(i) => goals.index(i).field("bones"),
            Field::Pin(i) => FieldPath::new().field("pins").index(i),
        }
    }
}

/// Bones known by name: a rig's skeleton, or a character's bones.
pub trait BoneNames {
    /// The index of the bone `name`, or a message listing the bones there are.
    fn index(&self, name: &str) -> Result<usize, Error>;
    /// How many bones there are.
    fn count(&self) -> usize;
    /// The name of bone `i`.
    fn name_of(&self, i: usize) -> &str;
    /// Whether bone `i` has a parent.
    fn has_parent(&self, i: usize) -> bool;
}

impl BoneNames for Skeleton {
    fn index(&self, name: &str) -> Result<usize, Error> {
        index_among(self.index_of(name), self.names().iter().map(String::as_str), name)
    }
    fn count(&self) -> usize {
        self.len()
    }
    fn name_of(&self, i: usize) -> &str {
        self.name(i)
    }
    fn has_parent(&self, i: usize) -> bool {
        self.parent(i).is_some()
    }
}

impl BoneNames for Character {
    fn index(&self, name: &str) -> Result<usize, Error> {
        index_among(self.bone_index(name), self.bones().iter().map(|b| b.name.as_str()), name)
    }
    fn count(&self) -> usize {
        self.bones().len()
    }
    fn name_of(&self, i: usize) -> &str {
        &self.bones()[i].name
    }
    fn has_parent(&self, i: usize) -> bool {
        self.bones()[i].parent.is_some()
    }
}

/// The task of `goals` and `pins` (bone names) with `mix` on `skeleton`, or the first problem
/// in one line, each field named by `field`: an unknown bone, a bad target, a weight or
/// softness out of range, two goals or pins on one bone, a bend on a root bone.
pub fn build(
    skeleton: &Skeleton,
    goals: &[NamedGoal],
    pins: &[String],
    mix: f64,
    field: &dyn Fn(Field) -> String,
) -> Result<RigTask, Error> {
    let (goals, pins) = goals_and_pins(skeleton, goals, pins, field)?;
    let task = RigTask { goals, pins: pins.into_iter().map(Pin::new).collect(), mix, bends: Vec::new() };
    // The library's own check last: what is left (no goal and no pin, a mix out of range).
    task.validate(skeleton).map_err(|e| Error::input(e.to_string()))?;
    Ok(task)
}

/// The goals (on bone indices of `bones`) and the pinned bones of `goals` and `pins`, checked
/// as [`build`] says.
pub fn goals_and_pins(
    bones: &dyn BoneNames,
    goals: &[NamedGoal],
    pins: &[String],
    field: &dyn Fn(Field) -> String,
) -> Result<(Vec<RigGoal>, Vec<usize>), Error> {
    // Which goal or pin took each bone first.
    let mut taken: Vec<Option<Field>> = vec![None; bones.count()];
    let mut claim = |bone: usize, by: Field| match taken[bone] {
        Some(first) => Err(Error::input(format!(
            "{}: bone {:?} already has a {} ({}); one goal or pin per bone",
            field(by),
            crate::names::Quoted(bones.name_of(bone)),
            if matches!(first, Field::Pin(_)) { "pin" } else { "goal" },
            field(first)
        ))),
        None => {
            taken[bone] = Some(by);
            Ok(())
        }
    };
    let mut solved = Vec::with_capacity(goals.len());
    for (i, g) in goals.iter().enumerate() {
        let bone = bones.index(&g.bone).map_err(|m| Error::input(format!("{}: {m}", field(Field::Goal(i)))))?;
        claim(bone, Field::Goal(i))?;
        let goal =
            make_goal(g.x, g.y, g.angle_deg).map_err(|m| Error::input(format!("{}: {m}", field(Field::Goal(i)))))?;
        if !(g.weight.is_finite() && g.weight > 0.0) {
            let value = ikarus::number::Num(g.weight);
            return Err(Error::input(format!("{}: {value}: must be a finite number > 0", field(Field::Weight(i)))));
        }
        if !(g.softness.is_finite() && g.softness >= 0.0) {
            let value = ikarus::number::Num(g.softness);
            return Err(Error::input(format!("{}: {value}: must be a finite number ≥ 0", field(Field::Softness(i)))));
        }
        if g.bend.is_some() && !bones.has_parent(bone) {
            return Err(Error::input(format!(
                "{}: bone {:?} has no parent, so no joint to bend (bend applies to the second bone of a limb)",
                field(Field::Bend(i)),
                crate::names::Quoted(&g.bone)
            )));
        }
        let mut goal =
            RigGoal::new(bone, goal).with_weight(g.weight).with_priority(g.priority).with_softness(g.softness);
        goal.bend = g.bend;
        solved.push(goal);
    }
    let mut pinned = Vec::with_capacity(pins.len());
    for (i, name) in pins.iter().enumerate() {
        let bone = bones.index(name).map_err(|m| Error::input(format!("{}: {m}", field(Field::Pin(i)))))?;
        claim(bone, Field::Pin(i))?;
        pinned.push(bone);
    }
    Ok((solved, pinned))
}

/// The index of the bone `name`, or a message listing the rig's bones.
pub fn index(skeleton: &Skeleton, name: &str) -> Result<usize, Error> {
    skeleton.index(name)
}

/// `found`, or a message listing `names`.
fn index_among<'a>(
    found: Option<usize>,
    names: impl ExactSizeIterator<Item = &'a str>,
    name: &str,
) -> Result<usize, Error> {
    found.ok_or_else(|| {
        Error::input({
            let n = names.len();
            let mut listed = names.take(LISTED_NAMES).map(crate::names::cell).collect::<Vec<_>>().join(", ");
            if n > LISTED_NAMES {
                listed.push_str(&format!(", … ({n} in all)"));
            }
            format!("no bone named {} in the rig (its bones: {listed})", crate::names::Quoted(name))
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use ikarus::Bone;

    fn fork() -> Skeleton {
        Skeleton::new(
            [0.0, 0.0],
            &[
                Bone::new("trunk", 1.0, 1.5),
                Bone::new("arm.l", 0.8, 0.9).with_parent("trunk"),
                Bone::new("arm.r", 0.8, -0.9).with_parent("trunk"),
            ],
        )
        .unwrap()
    }

    fn name(f: Field) -> String {
        format!("{f:?}")
    }

    #[test]
    fn goals_and_pins_become_bone_indices() {
        let s = fork();
        let mut g = NamedGoal::new("arm.r", 1.0, 2.0, Some(90.0));
        g.weight = 2.0;
        g.bend = Some(Bend::Negative);
        let task = build(&s, &[g], &["arm.l".to_owned()], 0.5, &name).unwrap();
        assert_eq!(task.goals[0].bone, 2);
        assert_eq!(task.goals[0].weight, 2.0);
        assert_eq!(task.goals[0].bend, Some(Bend::Negative));
        assert_eq!(task.goals[0].goal.orientation(), Some(std::f64::consts::FRAC_PI_2));
        assert_eq!(task.pins, vec![Pin::new(1)]);
        assert_eq!(task.mix, 0.5);
    }

    #[test]
    fn each_problem_names_its_field() {
        let s = fork();
        let goal = |bone: &str| NamedGoal::new(bone, 1.0, 1.0, None);
        let pins = |names: &[&str]| names.iter().map(|n| (*n).to_owned()).collect::<Vec<_>>();
        let cases: Vec<(Vec<NamedGoal>, Vec<String>, &str)> = vec![
            (vec![goal("arm")], vec![], "Goal(0): no bone named \"arm\" in the rig (its bones: trunk, arm.l, arm.r)"),
            (vec![], pins(&["leg"]), "Pin(0): no bone named \"leg\""),
            (
                vec![goal("arm.l"), goal("arm.l")],
                vec![],
                "Goal(1): bone \"arm.l\" already has a goal (Goal(0)); one goal or pin per bone",
            ),
            (vec![goal("arm.l")], pins(&["arm.l"]), "Pin(0): bone \"arm.l\" already has a goal (Goal(0))"),
            (vec![], pins(&["trunk", "trunk"]), "Pin(1): bone \"trunk\" already has a pin (Pin(0))"),
            (vec![NamedGoal { weight: 0.0, ..goal("trunk") }], vec![], "Weight(0): 0: must be a finite number > 0"),
            (vec![NamedGoal { softness: f64::NAN, ..goal("trunk") }], vec![], "Softness(0): NaN: must be"),
            (
                vec![NamedGoal { bend: Some(Bend::Positive), ..goal("trunk") }],
                vec![],
                "Bend(0): bone \"trunk\" has no parent",
            ),
            (vec![NamedGoal::new("trunk", f64::INFINITY, 0.0, None)], vec![], "Goal(0): goal.x: must be"),
            (vec![], vec![], "goals: a rig solve needs at least one goal or pin, got none"),
        ];
        for (goals, pins, want) in cases {
            let got = build(&s, &goals, &pins, 1.0, &name).unwrap_err();
            assert!(got.to_string().starts_with(want), "got {got:?}, want {want:?}");
        }
        let e = build(&s, &[goal("trunk")], &[], 1.5, &name).unwrap_err();
        assert_eq!(e, "mix: must be from 0 to 1, got 1.5");
    }
}
