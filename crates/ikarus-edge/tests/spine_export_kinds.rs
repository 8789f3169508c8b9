//! The Spine export of characters with transform, path and physics constraints, played back
//! ([`export_play`]): in the bake (and in the editable form under ikarus's solver) every
//! constraint is keyed to mix 0 at time 0, since the keys already hold what it did; under the
//! runtime's rules the editable form keeps them on.

mod export_play;

use export_play::{moved, played, text};
use ikarus::EaseKind;
use ikarus_edge::character::export::Form;
use ikarus_edge::character::load;
use ikarus_edge::character::motion::{Course, Motion, Physics};
use ikarus_edge::pose::IkChoice;
use serde_json::Value;

/// Every key of every constraint of `kind` in `animation` (for `path` and `physics`, its `mix`
/// timeline), by constraint.
fn keys<'a>(animation: &'a Value, kind: &str) -> Vec<(&'a String, &'a Value)> {
    let timelines = animation[kind].as_object().into_iter().flatten();
    timelines.map(|(name, t)| (name, if kind == "transform" || kind == "ik" { t } else { &t["mix"] })).collect()
}

/// Both forms of moving `targets` (bone, by) over 0.6 s played back within 1e-2 at every
/// frame under `ik`; returns the bake's animation and the editable's.
fn check(file: &str, targets: &[(&str, [f64; 2])], ik: &IkChoice) -> [Value; 2] {
    let loaded = load(&text(file), file).unwrap();
    let targets = targets.iter().map(|(b, by)| moved(&loaded, b, *by)).collect();
    let course = Course::Eased { targets, ease: EaseKind::Sine.ease(None, None).unwrap(), duration: 0.6 };
    let mut motion = Motion::new(&loaded, course, 30.0).unwrap();
    motion.ik = ik.clone();
    let mut out = Vec::new();
    for form in [Form::Bake, Form::Editable] {
        let p = played(file, &motion, form);
        println!(
            "{file} {form:?} {}: {} keys at {} times, error at frames {:.3e}, between {:.3e}, at the last key {:.3e}",
            if *ik == IkChoice::Runtime { "spine" } else { "ikarus" },
            p.keys,
            p.times,
            p.frames,
            p.worst,
            p.last
        );
        assert!(p.frames < 1e-2, "{file} {form:?}: {} at a frame", p.frames);
        assert!(p.last < 1e-2, "{file} {form:?}: {} at the last key", p.last);
        out.push(p.animation);
    }
    [out.remove(0), out.remove(0)]
}

fn ikarus() -> IkChoice {
    IkChoice::Ikarus(Box::default())
}

#[test]
fn stretchyman_s_paths_are_switched_off_in_the_bake_and_on_in_the_editable_form() {
    let file = "spine-stretchyman-pro.json";
    let targets = [("back-arm-ik-target", [30.0, -40.0]), ("front-leg-ik-target", [40.0, 20.0])];
    let [bake, editable] = check(file, &targets, &IkChoice::Runtime);
    let paths = keys(&bake, "path");
    assert_eq!(paths.len(), 4, "{paths:?}");
    for (name, mix) in paths.iter().chain(&keys(&bake, "transform")) {
        let key = &mix[0];
        assert_eq!(key["time"], 0.0, "{name}");
        for field in ["mixRotate", "mixX", "mixY"] {
            assert_eq!(key[field], 0.0, "{name}.{field}");
        }
    }
    assert!(editable.get("path").is_none() && editable.get("transform").is_none());
    // Under ikarus's solver the editable form keys every bone the motion moves, the path
    // bones too, and switches every constraint off.
    let [_, editable] = check(file, &targets, &ikarus());
    assert_eq!(keys(&editable, "path").len(), 4);
    assert_eq!(keys(&editable, "transform").len(), 2);
}

#[test]
fn spineboy_s_transforms_are_switched_off_under_ikarus_s_solver() {
    // The foot-board and shoulder transform constraints read the legs' targets and bones that
    // ikarus solves.
    let file = "spine-spineboy-pro.json";
    let targets = [("front-leg-target", [60.0, 80.0]), ("rear-leg-target", [-40.0, 50.0])];
    let [bake, editable] = check(file, &targets, &ikarus());
    for animation in [&bake, &editable] {
        let transforms = keys(animation, "transform");
        assert_eq!(transforms.len(), 8);
        for (name, k) in transforms {
            let k = &k[0];
            for field in ["mixRotate", "mixX", "mixY", "mixScaleX", "mixScaleY", "mixShearY"] {
                assert_eq!(k[field], 0.0, "{name}.{field}");
            }
        }
    }
}

#[test]
fn celestial_circus_s_physics_are_switched_off_in_the_bake_and_read_back() {
    // No IK: a transform constraint's target moved (the face control), its physics keyed to
    // mix 0 (`{"mix": [{"time": 0, "value": 0}]}`), which our reader reads back.
    let file = "spine-celestial-circus-pro.json";
    let [bake, _] = check(file, &[("face-control", [6.0, -4.0])], &IkChoice::Runtime);
    let physics = keys(&bake, "physics");
    assert_eq!(physics.len(), 30);
    for (name, mix) in physics {
        assert_eq!(mix[0]["value"], 0.0, "{name}");
    }
}

#[test]
fn celestial_circus_s_editable_export_keeps_its_physics_on_unless_the_motion_has_it_off() {
    // On: the export plays its physics on top of the keys in a game, as the motion does
    // (checked within 1e-2 at every frame, both played at the motion's clock); off: keyed to
    // mix 0, as the motion leaves it out.
    let file = "spine-celestial-circus-pro.json";
    let loaded = load(&text(file), file).unwrap();
    let targets = vec![moved(&loaded, "face-control", [6.0, -4.0])];
    let course = Course::Eased { targets, ease: EaseKind::Sine.ease(None, None).unwrap(), duration: 0.6 };
    let mut motion = Motion::new(&loaded, course, 30.0).unwrap();
    let on = played(file, &motion, Form::Editable);
    assert!(on.frames < 1e-2, "{}", on.frames);
    assert!(on.animation.get("physics").is_none());
    motion.physics = Physics::Off;
    let off = played(file, &motion, Form::Editable);
    assert!(off.frames < 1e-2 && off.last < 1e-2, "{} {}", off.frames, off.last);
    let physics = keys(&off.animation, "physics");
    assert_eq!(physics.len(), 30);
    assert!(physics.iter().all(|(_, mix)| mix[0]["value"] == 0.0 && mix[0]["time"] == 0.0));
}
