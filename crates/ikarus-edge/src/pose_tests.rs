//! Tests of [`super`]: posing a character by the runtime's rules and by ikarus's.

use super::*;

fn spineboy() -> Loaded {
    let text = include_str!("../../../examples/characters/spine-spineboy-pro.json");
    crate::character::load(text, "spineboy").unwrap()
}

#[test]
fn names_that_do_not_exist_are_refused_in_one_line() {
    let boy = spineboy();
    let ask = |animation: Option<&str>, time, targets: Vec<(String, [f64; 2])>| PoseAsk {
        animation: animation.map(str::to_owned),
        time,
        targets,
        ik: IkChoice::Runtime,
        bends: Vec::new(),
        turns: Vec::new(),
        physics: PhysicsAsk::default(),
        skin: None,
    };
    let e = pose(&boy, &ask(Some("wlk"), None, vec![])).unwrap_err();
    let villain = PoseAsk { skin: Some("villain".into()), ..PoseAsk::default() };
    assert_eq!(pose(&boy, &villain).unwrap_err(), "skin \"villain\": no such skin (the file has: default)");
    assert!(
        e.to_string().starts_with("animation \"wlk\": no such animation (the file has: ")
            && e.to_string().contains("walk"),
        "{e}"
    );
    let e = pose(&boy, &ask(None, Some(1.0), vec![])).unwrap_err();
    assert_eq!(e, "time: only with an animation");
    let e = pose(&boy, &ask(Some("walk"), Some(f64::NAN), vec![])).unwrap_err();
    assert_eq!(e, "time: must be a finite number of seconds, got NaN");
    let e = pose(&boy, &ask(None, None, vec![("toe".into(), [0.0, 0.0])])).unwrap_err();
    assert_eq!(e, "target \"toe\": no bone of that name");
    let e = pose(&boy, &ask(None, None, vec![("hip".into(), [f64::INFINITY, 0.0])])).unwrap_err();
    assert_eq!(e, "target \"hip\": the point must be finite, got (inf, 0)");
    assert!(e.to_string().lines().count() == 1);
}

#[test]
fn a_target_moves_its_bone_and_the_report_lists_every_bone() {
    let boy = spineboy();
    let setup = pose(&boy, &PoseAsk::default()).unwrap();
    assert_eq!(setup.bones.len(), boy.character.bones().len());
    let moved = PoseAsk { targets: vec![("front-leg-target".into(), [120.0, 40.0])], ..PoseAsk::default() };
    let report = pose(&boy, &moved).unwrap();
    let target = report.bones.iter().find(|b| b.name == "front-leg-target").unwrap();
    assert!((target.x - 120.0).abs() < 1e-9 && (target.y - 40.0).abs() < 1e-9, "{target:?}");
    // The tip is the origin plus the length along the bone's direction.
    for (b, bone) in report.bones.iter().zip(boy.character.bones()) {
        let r = b.rotation_deg.to_radians();
        let (s, c) = r.sin_cos();
        let scale = ((b.tip[0] - b.x).powi(2) + (b.tip[1] - b.y).powi(2)).sqrt();
        if bone.length > 0.0 {
            assert!(((b.tip[0] - b.x) - scale * c).abs() < 1e-6 && ((b.tip[1] - b.y) - scale * s).abs() < 1e-6);
        }
    }
    let text = report.text();
    let rows = text.lines().filter(|l| !l.starts_with("unsupported ")).count();
    assert!(text.starts_with("bone") && rows == report.bones.len() + 1, "{text}");
    assert_eq!(text.lines().count(), rows + report.unsupported.len());
    let svg = ikarus_render::character_svg(&report.figure(None), 300, 300).unwrap();
    assert_eq!(svg.matches("<g class=\"bone\">").count(), report.bones.len());
}

/// Each constraint's miss under the runtime's rules, from the report: a two-bone one's tip
/// from its target.
fn two_bone_misses(c: &Character, report: &PoseReport) -> Vec<f64> {
    let at = |i: usize| &report.bones[i];
    c.ik_constraints()
        .filter_map(|(_, k)| match k.bones {
            ikarus::character::IkBones::Two { child, .. } => {
                let (tip, t) = (at(child).tip, at(k.target));
                Some(((tip[0] - t.x).powi(2) + (tip[1] - t.y).powi(2)).sqrt())
            }
            ikarus::character::IkBones::One(_) => None,
        })
        .collect()
}

#[test]
fn ikarus_rules_meet_every_two_bone_limb_the_runtime_meets_on_the_shipped_walks() {
    let raptor =
        crate::character::load(include_str!("../../../examples/characters/spine-raptor-pro.json"), "raptor").unwrap();
    for loaded in [spineboy(), raptor] {
        let c = &loaded.character;
        for step in 0..=10 {
            let time = Some(f64::from(step) * 0.1);
            let runtime =
                pose(&loaded, &PoseAsk { animation: Some("walk".into()), time, ..PoseAsk::default() }).unwrap();
            let ask = PoseAsk {
                animation: Some("walk".into()),
                time,
                ik: IkChoice::Ikarus(Box::default()),
                ..PoseAsk::default()
            };
            let together = pose(&loaded, &ask).unwrap();
            let ik = together.ik.as_ref().unwrap();
            assert_eq!(ik.constraints.len(), c.ik_constraints().count());
            let (was, now) = (two_bone_misses(c, &runtime), two_bone_misses(c, &together));
            for (w, n) in was.iter().zip(&now) {
                assert!(n <= &(w + 1e-6), "{time:?}: ikarus misses {n}, the runtime {w}");
            }
            // The report's errors are the pose's own.
            let two: Vec<f64> = c
                .ik_constraints()
                .map(|(_, k)| k)
                .zip(&ik.constraints)
                .filter(|(k, _)| matches!(k.bones, ikarus::character::IkBones::Two { .. }))
                .map(|(_, l)| l.error)
                .collect();
            for (a, b) in two.iter().zip(&now) {
                assert!((a - b).abs() < 1e-9);
            }
        }
    }
}

#[test]
fn the_ik_choice_is_read_or_refused_in_one_line() {
    let boy = spineboy();
    let c = &boy.character;
    assert_eq!(ik_choice(None, None, "ik_file", c).unwrap(), IkChoice::Runtime);
    assert_eq!(ik_choice(Some("ikarus"), None, "ik_file", c).unwrap(), IkChoice::Ikarus(Box::default()));
    let e = ik_choice(Some("spine"), None, "ik_file", c).unwrap_err().to_string();
    assert_eq!(e, "ik = \"spine\": expected \"runtime\" or \"ikarus\"");
    let e = ik_choice(None, Some("pins = []"), "ik_file", c).unwrap_err().to_string();
    assert_eq!(e, "ik_file: an IK file is read only with ik = \"ikarus\"");
}
