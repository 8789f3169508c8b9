//! Spine 4.2's physics constraints (`physics` in a skeleton's JSON) and a clip's physics
//! timelines (`animations.NAME.physics.CONSTRAINT`, `""` for every constraint): fields and
//! defaults as the JSON export format gives them. A bad value is refused with its field path
//! (`physics[2] ("hair").fps = 0: must be positive`).

use std::collections::HashMap;

use ikarus::character::{
    ChannelKey, ConstraintKeys, ConstraintTimeline, Interpolation, MAX_CHANNELS, PhysicsConstraint, PhysicsGlobal,
    PhysicsKey, PhysicsProperty, PhysicsReset, PhysicsSettings, PhysicsShares, PhysicsTimeline,
};
use serde::Deserialize;
use serde_json::Value;

use crate::error::Error;
use crate::names::Quoted;

/// One entry of the file's `physics` list.
#[derive(Deserialize)]
#[serde(rename_all = "camelCase")]
struct PhysicsJson {
    name: String,
    #[serde(default)]
    order: u32,
    #[serde(default)]
    skin: bool,
    bone: String,
    #[serde(default)]
    x: f64,
    #[serde(default)]
    y: f64,
    #[serde(default)]
    rotate: f64,
    #[serde(default)]
    scale_x: f64,
    #[serde(default)]
    shear_x: f64,
    #[serde(default = "limit")]
    limit: f64,
    #[serde(default = "fps")]
    fps: f64,
    #[serde(default = "one")]
    inertia: f64,
    #[serde(default = "strength")]
    strength: f64,
    #[serde(default = "one")]
    damping: f64,
    #[serde(default = "one")]
    mass: f64,
    #[serde(default)]
    wind: f64,
    #[serde(default)]
    gravity: f64,
    #[serde(default = "one")]
    mix: f64,
    #[serde(default)]
    inertia_global: bool,
    #[serde(default)]
    strength_global: bool,
    #[serde(default)]
    damping_global: bool,
    #[serde(default)]
    mass_global: bool,
    #[serde(default)]
    wind_global: bool,
    #[serde(default)]
    gravity_global: bool,
    #[serde(default)]
    mix_global: bool,
}

fn limit() -> f64 {
    5000.0
}
fn fps() -> f64 {
    60.0
}
fn one() -> f64 {
    1.0
}
fn strength() -> f64 {
    100.0
}

/// The physics constraints of a Spine skeleton (the JSON value of the whole file), their bones
/// found by name in `bones` (name → index).
pub fn read(file: &Value, bones: &HashMap<String, usize>) -> Result<Vec<PhysicsConstraint>, Error> {
    let Some(list) = file.get("physics") else { return Ok(Vec::new()) };
    let Some(list) = list.as_array() else { return Err(Error::input("physics: must be a list")) };
    list.iter()
        .enumerate()
        .map(|(i, v)| {
            let name = v.get("name").and_then(Value::as_str).unwrap_or("");
            let at = format!("physics[{i}] ({:?})", Quoted(name));
            let p: PhysicsJson = serde_json::from_value(v.clone()).map_err(|e| Error::input(format!("{at}: {e}")))?;
            constraint(&p, bones, &at)
        })
        .collect()
}

fn constraint(p: &PhysicsJson, bones: &HashMap<String, usize>, at: &str) -> Result<PhysicsConstraint, Error> {
    let bone =
        *bones.get(&p.bone).ok_or_else(|| Error::input(format!("{at}.bone = {:?}: no such bone", Quoted(&p.bone))))?;
    let positive = [("fps", p.fps), ("mass", p.mass)];
    if let Some((field, value)) = positive.iter().find(|(_, v)| !(v.is_finite() && *v > 0.0)) {
        return Err(Error::input(format!("{at}.{field} = {value}: must be positive")));
    }
    let not_negative = [("limit", p.limit), ("strength", p.strength)];
    if let Some((field, value)) = not_negative.iter().find(|(_, v)| !(v.is_finite() && *v >= 0.0)) {
        return Err(Error::input(format!("{at}.{field} = {value}: must not be negative")));
    }
    let finite = [
        ("x", p.x),
        ("y", p.y),
        ("rotate", p.rotate),
        ("scaleX", p.scale_x),
        ("shearX", p.shear_x),
        ("inertia", p.inertia),
        ("damping", p.damping),
        ("wind", p.wind),
        ("gravity", p.gravity),
        ("mix", p.mix),
    ];
    if let Some((field, value)) = finite.iter().find(|(_, v)| !v.is_finite()) {
        return Err(Error::input(format!("{at}.{field} = {value}: must be finite")));
    }
    Ok(PhysicsConstraint {
        name: p.name.clone(),
        order: p.order,
        skin: p.skin,
        bone,
        shares: PhysicsShares { x: p.x, y: p.y, rotate: p.rotate, scale_x: p.scale_x, shear_x: p.shear_x },
        limit: p.limit,
        fps: p.fps,
        setup: PhysicsSettings {
            inertia: p.inertia,
            strength: p.strength,
            damping: p.damping,
            mass_inverse: 1.0 / p.mass,
            wind: p.wind,
            gravity: p.gravity,
            mix: p.mix,
        },
        global: PhysicsGlobal {
            inertia: p.inertia_global,
            strength: p.strength_global,
            damping: p.damping_global,
            mass: p.mass_global,
            wind: p.wind_global,
            gravity: p.gravity_global,
            mix: p.mix_global,
        },
    })
}

/// A clip's physics timelines and reset timelines (`animation` is the clip's JSON value, `at`
/// its field path, e.g. `animations."wind-idle"`), the constraints found by name in
/// `constraints`.
pub fn read_timelines(
    animation: &Value,
    constraints: &[PhysicsConstraint],
    at: &str,
) -> Result<(Vec<PhysicsTimeline>, Vec<PhysicsReset>), Error> {
    let (mut timelines, mut resets) = (Vec::new(), Vec::new());
    let Some(physics) = animation.get("physics") else { return Ok((timelines, resets)) };
    let Some(physics) = physics.as_object() else {
        return Err(Error::input(format!("{at}.physics: must be an object")));
    };
    for (name, props) in physics {
        let at = format!("{at}.physics.{:?}", Quoted(name));
        let constraint = if name.is_empty() {
            None
        } else {
            let k = constraints.iter().position(|c| c.name == *name);
            Some(k.ok_or_else(|| Error::input(format!("{at}: no physics constraint {:?}", Quoted(name))))?)
        };
        let Some(props) = props.as_object() else { return Err(Error::input(format!("{at}: must be an object"))) };
        for (prop, keys) in props {
            let at = format!("{at}.{prop}");
            let Some(keys) = keys.as_array().filter(|k| !k.is_empty()) else {
                return Err(Error::input(format!("{at}: must be a list of keys")));
            };
            let property = match prop.as_str() {
                "reset" => {
                    let times = keys.iter().enumerate().map(|(i, k)| number(k, "time", 0.0, &format!("{at}[{i}]")));
                    resets.push(PhysicsReset { constraint, times: increasing(times.collect::<Result<_, _>>()?, &at)? });
                    continue;
                }
                "inertia" => PhysicsProperty::Inertia,
                "strength" => PhysicsProperty::Strength,
                "damping" => PhysicsProperty::Damping,
                "mass" => PhysicsProperty::Mass,
                "wind" => PhysicsProperty::Wind,
                "gravity" => PhysicsProperty::Gravity,
                "mix" => PhysicsProperty::Mix,
                other => return Err(Error::input(format!("{at}: no physics timeline {:?}", Quoted(other)))),
            };
            let keys =
                keys.iter().enumerate().map(|(i, k)| key(k, &format!("{at}[{i}]"))).collect::<Result<Vec<_>, _>>()?;
            increasing(keys.iter().map(|k| k.time).collect(), &at)?;
            if property == PhysicsProperty::Mass {
                if let Some((i, k)) = keys.iter().enumerate().find(|(_, k)| k.value <= 0.0) {
                    return Err(Error::input(format!("{at}[{i}].value = {}: a mass must be positive", k.value)));
                }
            }
            timelines.push(PhysicsTimeline { constraint, property, keys });
        }
    }
    Ok((timelines, resets))
}

/// A clip's physics timelines as the character's constraint timelines: constraint `k` of
/// `physics` is constraint `first + k` of the character; a timeline for every constraint (`""`)
/// becomes one per constraint whose global flag for its setting is set (a `reset` one, one per
/// constraint).
pub fn clip_timelines(
    animation: &Value,
    physics: &[PhysicsConstraint],
    first: usize,
    at: &str,
) -> Result<Vec<ConstraintTimeline>, Error> {
    let (timelines, resets) = read_timelines(animation, physics, at)?;
    let mut out = Vec::new();
    for t in timelines {
        let keys: Vec<ChannelKey> = t
            .keys
            .iter()
            .map(|k| ChannelKey {
                time: k.time,
                values: [k.value, 0.0, 0.0, 0.0, 0.0, 0.0],
                curves: [k.curve; MAX_CHANNELS],
            })
            .collect();
        for k in (0..physics.len()).filter(|&k| t.keys_constraint(k, &physics[k])) {
            out.push(ConstraintTimeline {
                constraint: first + k,
                keys: ConstraintKeys::Physics { property: t.property, keys: keys.clone() },
            });
        }
    }
    for r in resets {
        let keys: Vec<ChannelKey> = r
            .times
            .iter()
            .map(|&time| ChannelKey {
                time,
                values: [0.0; MAX_CHANNELS],
                curves: [Interpolation::Stepped; MAX_CHANNELS],
            })
            .collect();
        for k in (0..physics.len()).filter(|&k| r.constraint.is_none_or(|j| j == k)) {
            out.push(ConstraintTimeline { constraint: first + k, keys: ConstraintKeys::PhysicsReset(keys.clone()) });
        }
    }
    Ok(out)
}

/// A finite number field of a key (`default` when absent).
fn number(k: &Value, field: &str, default: f64, at: &str) -> Result<f64, Error> {
    match k.get(field) {
        None => Ok(default),
        Some(v) => v
            .as_f64()
            .filter(|v| v.is_finite())
            .ok_or_else(|| Error::input(format!("{at}.{field} = {v}: must be a number"))),
    }
}

/// One key: `time` (0), `value` (0) and `curve` (absent: linear; `"stepped"`; or `[cx1, cy1,
/// cx2, cy2]`).
fn key(k: &Value, at: &str) -> Result<PhysicsKey, Error> {
    let time = number(k, "time", 0.0, at)?;
    let value = number(k, "value", 0.0, at)?;
    let curve = match k.get("curve") {
        None => Interpolation::Linear,
        Some(Value::String(s)) if s == "stepped" => Interpolation::Stepped,
        Some(Value::Array(c)) if c.len() == 4 && c.iter().all(|v| v.as_f64().is_some_and(f64::is_finite)) => {
            let c: Vec<f64> = c.iter().filter_map(Value::as_f64).collect();
            Interpolation::Bezier { c1: [c[0], c[1]], c2: [c[2], c[3]] }
        }
        Some(other) => {
            return Err(Error::input(format!("{at}.curve = {other}: expected \"stepped\" or [cx1, cy1, cx2, cy2]")));
        }
    };
    Ok(PhysicsKey { time, value, curve })
}

/// `times` when they do not decrease.
fn increasing(times: Vec<f64>, at: &str) -> Result<Vec<f64>, Error> {
    if let Some(i) = (1..times.len()).find(|&i| times[i] < times[i - 1]) {
        return Err(Error::input(format!(
            "{at}[{i}].time = {}: before the key before it ({})",
            times[i],
            times[i - 1]
        )));
    }
    Ok(times)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bones() -> HashMap<String, usize> {
        [("root".to_owned(), 0), ("hair".to_owned(), 1)].into_iter().collect()
    }

    #[test]
    fn defaults_are_the_format_s() {
        let file =
            serde_json::json!({"physics": [{"name": "h", "bone": "hair", "rotate": 1, "mass": 2, "windGlobal": true}]});
        let p = &read(&file, &bones()).unwrap()[0];
        assert_eq!(p.bone, 1);
        assert_eq!((p.limit, p.fps, p.order), (5000.0, 60.0, 0));
        assert_eq!(p.shares, PhysicsShares { rotate: 1.0, ..PhysicsShares::default() });
        assert_eq!(p.setup, PhysicsSettings { mass_inverse: 0.5, ..PhysicsSettings::default() });
        assert_eq!(p.global, PhysicsGlobal { wind: true, ..PhysicsGlobal::default() });
    }

    #[test]
    fn timelines_for_one_constraint_and_for_all() {
        let file = serde_json::json!({"physics": [{"name": "h", "bone": "hair"}]});
        let cs = read(&file, &bones()).unwrap();
        let clip = serde_json::json!({"physics": {
            "h": {"mass": [{"value": 2}, {"time": 1, "value": 4, "curve": "stepped"}], "reset": [{"time": 0.5}]},
            "": {"wind": [{"value": 1, "curve": [0.3, 1, 0.6, 2]}, {"time": 1, "value": 2}]}
        }});
        let (timelines, resets) = read_timelines(&clip, &cs, "animations.\"a\"").unwrap();
        assert_eq!(timelines.len(), 2);
        let mass = timelines.iter().find(|t| t.property == PhysicsProperty::Mass).unwrap();
        assert_eq!(mass.constraint, Some(0));
        assert_eq!(mass.keys[1].curve, Interpolation::Stepped);
        let wind = timelines.iter().find(|t| t.property == PhysicsProperty::Wind).unwrap();
        assert_eq!(wind.constraint, None);
        assert_eq!(wind.keys[0].curve, Interpolation::Bezier { c1: [0.3, 1.0], c2: [0.6, 2.0] });
        assert_eq!(resets, vec![PhysicsReset { constraint: Some(0), times: vec![0.5] }]);
        for (clip, message) in [
            (
                serde_json::json!({"physics": {"nope": {"wind": [{}]}}}),
                r#"animations."a".physics."nope": no physics constraint "nope""#,
            ),
            (
                serde_json::json!({"physics": {"h": {"mass": [{"value": 0}]}}}),
                r#"animations."a".physics."h".mass[0].value = 0: a mass must be positive"#,
            ),
            (
                serde_json::json!({"physics": {"h": {"wind": [{"time": 1}, {"time": 0.5}]}}}),
                r#"animations."a".physics."h".wind[1].time = 0.5: before the key before it (1)"#,
            ),
        ] {
            assert_eq!(read_timelines(&clip, &cs, "animations.\"a\"").unwrap_err(), message);
        }
    }

    #[test]
    fn bad_values_name_their_field() {
        for (entry, message) in [
            (serde_json::json!({"name": "h", "bone": "nose"}), r#"physics[0] ("h").bone = "nose": no such bone"#),
            (
                serde_json::json!({"name": "h", "bone": "hair", "fps": 0}),
                r#"physics[0] ("h").fps = 0: must be positive"#,
            ),
            (
                serde_json::json!({"name": "h", "bone": "hair", "mass": -1}),
                r#"physics[0] ("h").mass = -1: must be positive"#,
            ),
            (
                serde_json::json!({"name": "h", "bone": "hair", "limit": -5}),
                r#"physics[0] ("h").limit = -5: must not be negative"#,
            ),
        ] {
            let file = serde_json::json!({ "physics": [entry] });
            assert_eq!(read(&file, &bones()).unwrap_err(), message);
        }
    }
}
