//! The JSON both forms of the export write for IK constraints and for the new animation's
//! body: a key of a constraint's settings, every constraint of every kind switched off (keyed to
//! mix 0 at time 0, for a motion whose bones are keyed as posing left them), and the animation's
//! object.

use ikarus::character::{Character, Constraint, IkSettings};
use serde_json::{Map, Value, json};

/// An IK key of `s`'s settings (without its time): `mix` and `bendPositive` always, `softness`,
/// `compress` and `stretch` where they differ from Spine's defaults.
pub(super) fn settings(s: &IkSettings) -> Value {
    let mut key = json!({"mix": s.mix, "bendPositive": s.bend_positive});
    if s.softness != 0.0 {
        key["softness"] = json!(s.softness);
    }
    if s.compress {
        key["compress"] = json!(true);
    }
    if s.stretch {
        key["stretch"] = json!(true);
    }
    key
}

/// Every constraint of `c` keyed to mix 0 at time 0, grouped by the animation's field for its
/// kind (`ik`, `transform`, `path`, `physics`): at mix 0 a constraint leaves the bones where the
/// keys put them. An IK key keeps its setup's other settings; a transform key zeroes the six
/// mixes (3.8: `rotateMix`, `translateMix`, `scaleMix`, `shearMix`), a path `mix` key the three
/// (3.8: `rotateMix`, `translateMix`), a physics `mix` key its `value` (Spine 4.2; 3.8 has no
/// physics).
pub(super) fn switched_off(c: &Character, legacy: bool) -> Map<String, Value> {
    let mut out = Map::new();
    for constraint in c.constraints() {
        let key = match constraint {
            Constraint::Ik(k) => {
                let mut key = settings(&k.setup);
                key["time"] = json!(0.0);
                key["mix"] = json!(0.0);
                json!([key])
            }
            Constraint::Transform(_) => {
                let names: &[&str] = if legacy {
                    &["rotateMix", "translateMix", "scaleMix", "shearMix"]
                } else {
                    &["mixRotate", "mixX", "mixY", "mixScaleX", "mixScaleY", "mixShearY"]
                };
                json!([zeroed(names)])
            }
            Constraint::Path(_) => {
                let names: &[&str] =
                    if legacy { &["rotateMix", "translateMix"] } else { &["mixRotate", "mixX", "mixY"] };
                json!({"mix": [zeroed(names)]})
            }
            Constraint::Physics(_) => json!({"mix": [{"time": 0.0, "value": 0.0}]}),
        };
        let kind = out.entry(constraint.kind()).or_insert_with(|| json!({}));
        kind[constraint.name()] = key;
    }
    out
}

/// A key at time 0 with every field of `names` at 0.
fn zeroed(names: &[&str]) -> Value {
    let mut key = json!({"time": 0.0});
    for name in names {
        key[*name] = json!(0.0);
    }
    key
}

/// The animation's object: its `bones` timelines and, for each kind that has any, the
/// constraints' timelines of `off` (`ik`, `transform`, `path`, `physics`).
pub(super) fn animation(bones: Map<String, Value>, off: Map<String, Value>) -> Value {
    let mut out = Map::new();
    out.insert("bones".to_owned(), Value::Object(bones));
    out.extend(off);
    Value::Object(out)
}
