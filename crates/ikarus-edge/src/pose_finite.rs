//! A pose that went non-finite, refused in one line: finite inputs can still overflow on the
//! way (a key of 1e300 is infinite as the 32-bit float Spine keeps it, a scale of 1e200 under a
//! parent's 1e200 is 1e400, an origin of 1e308 plus a length of 1e308 is past the largest
//! double, a softness of 1e308 makes the IK's arithmetic NaN). Every pose is checked once it is
//! made ([`check`], O(bones)); only a pose that fails is looked at again to tell the cause: the
//! first bone (parents come first) whose world transform or tip is not finite, and what made
//! it so where it can be told — the IK constraint that turned it, the clip that keyed it, the
//! target put on it, or the bone's own field that overflowed under its parent.

use ikarus::character::{Character, IkBones, Posed};

use crate::character::{Format, Loaded};
use crate::error::Error;
use crate::names::Quoted;

/// What a pose was asked for, as far as a refusal tells its cause: the pose's targets, and the
/// clip and time it sampled (a [`crate::pose::PoseAsk`]'s, borrowed).
#[derive(Debug, Clone, Copy)]
pub struct Asked<'a> {
    /// `(bone, [x, y])`: where each target bone was put.
    pub targets: &'a [(String, [f64; 2])],
    /// The clip sampled, by name.
    pub animation: Option<&'a str>,
    /// Seconds into the clip.
    pub time: Option<f64>,
}

/// `Ok` if every bone of `posed` has a finite world transform and tip; else the one-line
/// refusal naming the first bone that has not, and the input that made it so where it can be
/// told.
pub fn check(loaded: &Loaded, ask: &Asked<'_>, posed: &Posed) -> Result<(), Error> {
    match (0..posed.len()).find(|&i| what_is_not_finite(posed, i).is_some()) {
        None => Ok(()),
        Some(i) => Err(Error::input(cause(loaded, ask, posed, i))),
    }
}

/// What of bone `i` is not finite (`origin`, `rotation and scale`, `tip`), if any.
fn what_is_not_finite(posed: &Posed, i: usize) -> Option<&'static str> {
    let w = posed.world(i);
    let tip = posed.tip(i);
    if !(w.x.is_finite() && w.y.is_finite()) {
        Some("origin")
    } else if ![w.a, w.b, w.c, w.d].iter().all(|v| v.is_finite()) {
        Some("rotation and scale")
    } else if !(tip[0].is_finite() && tip[1].is_finite()) {
        Some("tip")
    } else {
        None
    }
}

/// How a bone's field is named in the file: `bones[3] ("hip").scaleX` (Spine),
/// `bone[3] ("hip").transform.scX` (DragonBones).
fn field(loaded: &Loaded, i: usize, spine: &str) -> String {
    let name = Quoted(&loaded.character.bones()[i].name);
    match loaded.format {
        Format::Spine => format!("bones[{i}] ({name}).{spine}"),
        Format::DragonBones => {
            let db = match spine {
                "x" => "transform.x",
                "y" => "transform.y",
                "scaleX" => "transform.scX",
                "scaleY" => "transform.scY",
                other => other,
            };
            format!("bone[{i}] ({name}).{db}")
        }
    }
}

/// The constraint that turns bone `i`, if one does (the last in the order of the file's list).
fn constraint_on(c: &Character, i: usize) -> Option<usize> {
    c.ik_constraints()
        .filter(|(_, k)| match k.bones {
            IkBones::One(b) => b == i,
            IkBones::Two { parent, child } => parent == i || child == i,
        })
        .last()
        .map(|(k, _)| k)
}

/// A world transform's scale: the longer of its axes.
fn scale_of(w: &ikarus::character::Affine) -> f64 {
    w.a.hypot(w.c).max(w.b.hypot(w.d))
}

/// The refusal of a pose whose bone `i` is the first not finite.
fn cause(loaded: &Loaded, ask: &Asked<'_>, posed: &Posed, i: usize) -> String {
    let c = &loaded.character;
    let bone = &c.bones()[i];
    let what = what_is_not_finite(posed, i).unwrap_or("pose");
    let verb = if what == "rotation and scale" { "are" } else { "is" };
    let at = format!("bone {}'s {what} {verb} not finite", Quoted(&bone.name));
    let local = posed.local(i);
    let locals = [
        ("x", local.x),
        ("y", local.y),
        ("rotation", local.rotation),
        ("scaleX", local.scale_x),
        ("scaleY", local.scale_y),
        ("shearX", local.shear_x),
        ("shearY", local.shear_y),
    ];
    // Not finite in the bone's own frame: a constraint turned it, a clip keyed it, or a target
    // put it there.
    if let Some((name, value)) = locals.iter().find(|(_, v)| !v.is_finite()) {
        if let Some((k, settings)) = constraint_on(c, i).and_then(|k| Some((k, posed.ik_settings(k)?))) {
            let constraint = &c.constraints()[k];
            let label = format!("ik[{k}] ({})", Quoted(constraint.name()));
            return if settings.softness.abs() > 1e100 {
                let softness = crate::names::count_text(settings.softness);
                format!("{label}.softness = {softness}: the pose overflows ({at})")
            } else {
                format!("{label}: the pose overflows ({at}: its {name} came out {value})")
            };
        }
        if let Some((target, p)) = ask.targets.iter().find(|(t, _)| *t == bone.name) {
            return format!("target {} = ({}, {}): the pose overflows ({at})", Quoted(target), p[0], p[1]);
        }
        if let Some(animation) = ask.animation {
            let time = ask.time.unwrap_or(0.0);
            return format!(
                "animation {} at {time} s: bone {}'s {name} is keyed to {value} (a key beyond a 32-bit \
                 float, as the runtime keeps it, or a sum of keys past the largest number): the pose overflows",
                Quoted(animation),
                Quoted(&bone.name)
            );
        }
        return format!("{}: the pose overflows ({at})", field(loaded, i, name));
    }
    // Finite in its own frame but not in the world: the bone's largest field overflowed under
    // its parent's world transform (or the skeleton's placement).
    let parent_scale = match bone.parent {
        Some(p) => scale_of(&posed.world(p)),
        None => {
            let s = c.placement().scale;
            s[0].abs().max(s[1].abs())
        }
    };
    let under = match bone.parent {
        Some(p) => format!("bone {}'s", Quoted(&c.bones()[p].name)),
        None => "the skeleton's".to_owned(),
    };
    let num = crate::names::count_text;
    if what == "tip" {
        let w = posed.world(i);
        let length = bone.length;
        return format!(
            "{} = {}: the pose overflows ({at}: origin ({}, {}) plus length {} along a world scale of {})",
            field(loaded, i, "length"),
            num(length),
            num(w.x),
            num(w.y),
            num(length),
            num(scale_of(&w))
        );
    }
    let candidates = if what == "origin" {
        [("x", local.x), ("y", local.y)]
    } else {
        [("scaleX", local.scale_x), ("scaleY", local.scale_y)]
    };
    let (name, value) = if candidates[1].1.abs() > candidates[0].1.abs() { candidates[1] } else { candidates[0] };
    let moved = ask.targets.iter().find(|(t, _)| *t == bone.name);
    if let (Some((target, p)), "x" | "y") = (moved, name) {
        return format!("target {} = ({}, {}): the pose overflows ({at})", Quoted(target), p[0], p[1]);
    }
    let keyed = c.bones()[i].setup != local;
    let clip = match (ask.animation, keyed) {
        (Some(a), true) => format!(", as animation {} keys it at {} s", Quoted(a), ask.time.unwrap_or(0.0)),
        _ => String::new(),
    };
    format!(
        "{} = {}{clip}: the pose overflows ({at}: {name} {} under {under} world scale {})",
        field(loaded, i, name),
        num(value),
        num(value),
        num(parent_scale)
    )
}
