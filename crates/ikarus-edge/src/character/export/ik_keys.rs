//! The JSON both forms of the export write for IK constraints and for the new animation's
//! body: a key of a constraint's settings, every constraint switched off (keyed to mix 0 at
//! time 0, for a motion whose bones are keyed as ikarus solved them), and the animation's object.

use ikarus::character::{Character, IkSettings};
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

/// Every IK constraint of `c` keyed to mix 0 at time 0 (its other settings as its setup's): at
/// mix 0 a constraint leaves the bones where the keys put them.
pub(super) fn switched_off(c: &Character) -> Map<String, Value> {
    let mut ik = Map::new();
    for (_, k) in c.ik_constraints() {
        let mut key = settings(&k.setup);
        key["time"] = json!(0.0);
        key["mix"] = json!(0.0);
        ik.insert(k.name.clone(), json!([key]));
    }
    ik
}

/// The animation's object: its `bones` timelines and, when there are any, its `ik` ones.
pub(super) fn animation(bones: Map<String, Value>, ik: Map<String, Value>) -> Value {
    let mut out = Map::new();
    out.insert("bones".to_owned(), Value::Object(bones));
    if !ik.is_empty() {
        out.insert("ik".to_owned(), Value::Object(ik));
    }
    Value::Object(out)
}
