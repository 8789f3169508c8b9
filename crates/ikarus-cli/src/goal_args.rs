//! The goal flags of every command: an arm's `--goal X,Y`, and a rig's task: `--goal
//! NAME=X,Y[,DEG]`, `--pin NAME`, and the per-goal controls `--weight NAME=W`, `--secondary NAME`,
//! `--bend NAME=ccw|cw`, `--softness NAME=S`, `--mix M`; turned into the task by
//! [`crate::goal::build`] with messages that name the flag and its value.

use clap::Args;
use ikarus::{Bend, Priority, RigTask, Skeleton};

use crate::error::Error;
use crate::goal::{self, Field, NamedGoal};
use crate::options::{parse_finite, parse_non_negative, parse_point, parse_positive};
use crate::rig::Rig;

/// A `--goal`: an arm's tip position `X,Y`, or a rig bone's `NAME=X,Y[,DEG]`.
#[derive(Debug, Clone, PartialEq)]
pub enum GoalArg {
    /// `X,Y`.
    Point([f64; 2]),
    /// `NAME=X,Y[,DEG]`: the tip of bone NAME at (X, Y), pointing DEG degrees from +x.
    Named { bone: String, x: f64, y: f64, angle_deg: Option<f64> },
}

impl GoalArg {
    /// The flag as written, for messages.
    pub fn text(&self) -> String {
        match self {
            GoalArg::Point([x, y]) => format!("--goal {x},{y}"),
            GoalArg::Named { bone, x, y, angle_deg: None } => format!("--goal {bone}={x},{y}"),
            GoalArg::Named { bone, x, y, angle_deg: Some(a) } => format!("--goal {bone}={x},{y},{a}"),
        }
    }
}

/// Parses `X,Y` or `NAME=X,Y[,DEG]`.
pub fn parse_goal(s: &str) -> Result<GoalArg, Error> {
    let Some((bone, rest)) = s.split_once('=') else { return parse_point(s).map(GoalArg::Point) };
    let bone = bone.trim();
    if bone.is_empty() {
        return Err(Error::input("NAME=X,Y[,DEG]: the bone's name is empty"));
    }
    let parts: Vec<&str> = rest.split(',').collect();
    let (x, y, angle) = match parts[..] {
        [x, y] => (x, y, None),
        [x, y, a] => (x, y, Some(a)),
        _ => {
            return Err(Error::input(format!(
                "{bone}=: expected X,Y or X,Y,DEG after the name, got {} part(s)",
                parts.len()
            )));
        }
    };
    let x = parse_finite(x).map_err(|m| Error::input(format!("{bone}: x: {m}")))?;
    let y = parse_finite(y).map_err(|m| Error::input(format!("{bone}: y: {m}")))?;
    let angle_deg = angle.map(parse_finite).transpose().map_err(|m| Error::input(format!("{bone}: angle: {m}")))?;
    Ok(GoalArg::Named { bone: bone.to_owned(), x, y, angle_deg })
}

/// `NAME=VALUE` with VALUE parsed by `value`.
fn named<T>(s: &str, value: impl Fn(&str) -> Result<T, Error>) -> Result<(String, T), Error> {
    let Some((name, v)) = s.split_once('=') else {
        return Err(Error::input(format!("expected NAME=VALUE, got '{s}'")));
    };
    let name = name.trim();
    if name.is_empty() {
        return Err(Error::input("NAME=VALUE: the bone's name is empty"));
    }
    Ok((name.to_owned(), value(v).map_err(|m| Error::input(format!("{name}: {m}")))?))
}

fn parse_weight(s: &str) -> Result<(String, f64), Error> {
    named(s, parse_positive)
}

fn parse_softness(s: &str) -> Result<(String, f64), Error> {
    named(s, parse_non_negative)
}

fn parse_bend(s: &str) -> Result<(String, Bend), Error> {
    named(s, |v| match v.trim() {
        "ccw" => Ok(Bend::Positive),
        "cw" => Ok(Bend::Negative),
        other => Err(Error::input(format!("'{other}': expected ccw (counter-clockwise) or cw (clockwise)"))),
    })
}

/// `NAME=DEG`: a bone's angle, degrees.
pub fn parse_bone_angle(s: &str) -> Result<(String, f64), Error> {
    named(s, parse_finite)
}

fn parse_mix(s: &str) -> Result<f64, Error> {
    let v = parse_finite(s)?;
    if (0.0..=1.0).contains(&v) {
        Ok(v)
    } else {
        Err(Error::input(format!("{}: must be from 0 to 1", ikarus::number::Num(v))))
    }
}

/// The flags of a rig's task besides `--goal` (each only with `--rig`).
#[derive(Debug, Clone, Default, Args)]
pub struct RigTaskArgs {
    /// With --rig: hold the tip of bone NAME where it starts, position and direction (repeatable)
    #[arg(long, value_name = "NAME", requires = "rig")]
    pub pin: Vec<String>,
    /// With --rig: the weight of the goal on bone NAME, > 0, when goals conflict [default: 1]
    #[arg(long, value_name = "NAME=W", requires = "rig", value_parser = parse_weight)]
    pub weight: Vec<(String, f64)>,
    /// With --rig: the goal on bone NAME is secondary: met only in what the pins and the other
    /// goals leave free (repeatable)
    #[arg(long, value_name = "NAME", requires = "rig")]
    pub secondary: Vec<String>,
    /// With --rig: which way the joint of bone NAME (an elbow, a knee) bends: ccw or cw
    #[arg(long, value_name = "NAME=ccw|cw", requires = "rig", value_parser = parse_bend)]
    pub bend: Vec<(String, Bend)>,
    /// With --rig: softness of the goal on bone NAME, ≥ 0, in length units: the limb slows
    /// its approach near full reach instead of snapping straight [default: 0]
    #[arg(long, value_name = "NAME=S", requires = "rig", value_parser = parse_softness)]
    pub softness: Vec<(String, f64)>,
    /// With --rig: how much of the IK result to take, 0 to 1 (0 keeps the start pose) [default: 1]
    #[arg(long, value_name = "M", requires = "rig", value_parser = parse_mix)]
    pub mix: Option<f64>,
}

impl RigTaskArgs {
    /// Each task flag as written and whether it was given.
    #[must_use]
    pub fn given(&self) -> [(&'static str, bool); 6] {
        [
            ("--pin", !self.pin.is_empty()),
            ("--weight", !self.weight.is_empty()),
            ("--secondary", !self.secondary.is_empty()),
            ("--bend", !self.bend.is_empty()),
            ("--softness", !self.softness.is_empty()),
            ("--mix", self.mix.is_some()),
        ]
    }
}

/// A goal from the command line: its target, and the flag it came from (for messages).
#[derive(Debug, Clone, PartialEq)]
pub struct Target {
    pub bone: String,
    pub x: f64,
    pub y: f64,
    pub angle_deg: Option<f64>,
    /// How the goal was given: `--goal hand=1,2`, or a batch file's `hand.x` column.
    pub source: String,
}

impl Target {
    /// The target of a `--goal` on `rig`, which must name its bone unless the rig has a tip
    /// (an arm file's rig: `--goal X,Y` is on its last link).
    pub fn of(goal: &GoalArg, rig: &Rig) -> Result<Self, Error> {
        match goal {
            GoalArg::Named { bone, x, y, angle_deg } => {
                Ok(Self { bone: bone.clone(), x: *x, y: *y, angle_deg: *angle_deg, source: goal.text() })
            }
            GoalArg::Point([x, y]) => match rig.tip {
                Some(tip) => Ok(Self {
                    bone: rig.skeleton.name(tip).to_owned(),
                    x: *x,
                    y: *y,
                    angle_deg: None,
                    source: goal.text(),
                }),
                None => {
                    Err(Error::input(format!("{}: a rig's goal names its bone: --goal NAME=X,Y[,DEG]", goal.text())))
                }
            },
        }
    }
}

impl RigTaskArgs {
    /// Checks that every per-goal flag names a bone that has a goal among `bones` (the goals'
    /// bones, from --goal or a batch header): a weight for a bone without a goal is a mistake.
    pub fn check_against(&self, bones: &[&str]) -> Result<(), Error> {
        let flags = self.weight.iter().map(|(n, w)| (n, "--weight", format!("--weight {n}={w}")));
        let flags = flags.chain(self.secondary.iter().map(|n| (n, "--secondary", format!("--secondary {n}"))));
        let flags = flags.chain(self.bend.iter().map(|(n, b)| (n, "--bend", format!("--bend {n}={}", bend_name(*b)))));
        let flags = flags.chain(self.softness.iter().map(|(n, s)| (n, "--softness", format!("--softness {n}={s}"))));
        let mut seen: Vec<(&String, &str)> = Vec::new();
        for (name, kind, flag) in flags {
            if !bones.contains(&name.as_str()) {
                return Err(Error::input(format!("{flag}: no goal on bone {name:?} (give it a --goal NAME=X,Y)")));
            }
            if seen.contains(&(name, kind)) {
                return Err(Error::input(format!("{flag}: {kind} given twice for bone {name:?}")));
            }
            seen.push((name, kind));
        }
        Ok(())
    }

    /// The task of `targets` and the pins on `skeleton`, with these flags' controls; problems
    /// name the flag and its value.
    pub fn task(&self, skeleton: &Skeleton, targets: &[Target]) -> Result<RigTask, Error> {
        let goals = self.named(targets)?;
        let field = |f: Field| self.field(targets, f);
        goal::build(skeleton, &goals, &self.pin, self.mix.unwrap_or(1.0), &field).map_err(|m| {
            // The library's words for a task of nothing, in the flags' words.
            if m.to_string().starts_with("goals: ") {
                Error::input("--goal: a rig solve needs at least one --goal NAME=X,Y or --pin NAME")
            } else {
                m
            }
        })
    }

    /// The goals of `targets` with these flags' controls, each per-goal flag checked to name a
    /// goal's bone.
    pub fn named(&self, targets: &[Target]) -> Result<Vec<NamedGoal>, Error> {
        let bones: Vec<&str> = targets.iter().map(|t| t.bone.as_str()).collect();
        self.check_against(&bones)?;
        Ok(targets
            .iter()
            .map(|t| NamedGoal {
                weight: self.weight.iter().find(|(n, _)| *n == t.bone).map_or(1.0, |w| w.1),
                priority: if self.secondary.contains(&t.bone) { Priority::Secondary } else { Priority::Primary },
                bend: self.bend.iter().find(|(n, _)| *n == t.bone).map(|b| b.1),
                softness: self.softness.iter().find(|(n, _)| *n == t.bone).map_or(0.0, |s| s.1),
                ..NamedGoal::new(t.bone.clone(), t.x, t.y, t.angle_deg)
            })
            .collect())
    }

    /// The flag a problem with `f` names, for the goals of `targets`.
    pub fn field(&self, targets: &[Target], f: Field) -> String {
        match f {
            Field::Goal(i) => targets[i].source.clone(),
            Field::Weight(i) => format!("--weight {}", targets[i].bone),
            Field::Softness(i) => format!("--softness {}", targets[i].bone),
            Field::Bend(i) => format!("--bend {}", targets[i].bone),
            Field::Bones(i) => format!("--bones {}", targets[i].bone),
            Field::Pin(i) => format!("--pin {}", self.pin[i]),
        }
    }
}

fn bend_name(b: Bend) -> &'static str {
    match b {
        Bend::Positive => "ccw",
        Bend::Negative => "cw",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn goals_parse_with_or_without_a_name() {
        assert_eq!(parse_goal("1,2"), Ok(GoalArg::Point([1.0, 2.0])));
        assert_eq!(
            parse_goal("left.hand=1,-2"),
            Ok(GoalArg::Named { bone: "left.hand".into(), x: 1.0, y: -2.0, angle_deg: None })
        );
        assert_eq!(
            parse_goal("foot=1,2,-90"),
            Ok(GoalArg::Named { bone: "foot".into(), x: 1.0, y: 2.0, angle_deg: Some(-90.0) })
        );
        assert_eq!(
            parse_goal("foot=1"),
            Err(Error::input("foot=: expected X,Y or X,Y,DEG after the name, got 1 part(s)"))
        );
        assert_eq!(parse_goal("foot=1,nan"), Err(Error::input("foot: y: must be a finite number, got nan")));
        assert_eq!(parse_goal("foot=1,2,x"), Err(Error::input("foot: angle: 'x' is not a number")));
        assert_eq!(parse_goal("=1,2"), Err(Error::input("NAME=X,Y[,DEG]: the bone's name is empty")));
    }

    #[test]
    fn controls_parse() {
        assert_eq!(parse_bend("knee=cw"), Ok(("knee".into(), Bend::Negative)));
        assert!(parse_bend("knee=left").unwrap_err().to_string().contains("expected ccw"));
        assert!(parse_weight("hand=0").unwrap_err().to_string().starts_with("hand: 0: must be"));
        assert!(parse_softness("hand=-1").is_err());
        assert_eq!(parse_mix("0.25"), Ok(0.25));
        assert!(parse_mix("1.5").is_err());
    }
}
