use super::*;

/// A missing field is reported where serde reports it: at the body's last character.
#[test]
fn a_missing_field_is_placed_as_serde_places_it() {
    for body in ["{}", " {\n \"x\": 1 }\n\n", "{\"start_deg\": [1, 2, 3]}"] {
        #[derive(Debug, Deserialize)]
        #[allow(dead_code)]
        struct Needs {
            goal: u32,
            #[serde(default)]
            x: u32,
            #[serde(default)]
            start_deg: Vec<u32>,
        }
        let serde = parse_json::<Needs>(body.as_bytes()).unwrap_err().message;
        let ours = fields_of(BodyKind::Arm, &[], &[], ("goal", false), body.as_bytes()).unwrap_err().message;
        assert_eq!(ours, serde, "{body:?}");
    }
}

/// A field of the other body is refused as serde refuses an unknown field, naming it and
/// whose it is; a body's own fields are taken.
#[test]
fn a_field_of_the_other_body_is_refused_by_name() {
    let limits = Limits::default();
    let interrupt = ikarus::Interrupt::new();
    let call = |endpoint, body: serde_json::Value| {
        super::super::call(endpoint, body.to_string().as_bytes(), &limits, &interrupt).map(|_| ())
    };
    let rig = serde_json::json!({"bones": [{"name": "a", "length": 1}, {"name": "b", "parent": "a", "length": 1}]});
    let goal = serde_json::json!({"x": 1, "y": 1});
    let goals = serde_json::json!([{"bone": "b", "x": 1, "y": 1}]);
    use super::super::Endpoint::{Animate, Solve, Track};
    let refused = [
        (
            Solve,
            serde_json::json!({"goal": goal, "pins": ["a"]}),
            "request body: pins: unknown field `pins`, only with rig",
        ),
        (Solve, serde_json::json!({"goal": goal, "mix": 0.5}), "request body: mix: unknown field `mix`, only with rig"),
        (
            Animate,
            serde_json::json!({"goal": goal, "pins": []}),
            "request body: pins: unknown field `pins`, only with rig",
        ),
        (
            Track,
            serde_json::json!({"line": [1, 1, 2, 2], "effector": "b"}),
            "request body: effector: unknown field `effector`, only with rig",
        ),
        (Solve, serde_json::json!({}), "request body: missing field `goal` at line 1 column 2"),
        (Solve, serde_json::json!({"rig": rig, "goal": goal}), "goal: a rig takes goals"),
        (Solve, serde_json::json!({"goals": goals}), "goals: only with rig"),
        (Solve, serde_json::json!({"arm": {"links": [{"length": 1}]}, "rig": rig}), "arm, rig: give one or the other"),
    ];
    for (endpoint, body, want) in refused {
        let e = call(endpoint, body.clone()).unwrap_err();
        assert_eq!(e.status, 422, "{body}");
        assert!(e.message.starts_with(want), "{body}: {}", e.message);
    }
    // The same fields with the body they belong to are answered.
    call(Solve, serde_json::json!({"rig": rig, "goals": goals, "pins": ["a"], "mix": 0.5})).unwrap();
    call(Animate, serde_json::json!({"rig": rig, "goals": goals, "via": [goals], "frames": 3})).unwrap();
    call(Animate, serde_json::json!({"goal": goal, "via": [[1, 2]], "frames": 3})).unwrap();
    call(Track, serde_json::json!({"rig": rig, "effector": "b", "line": [1, 1, 1.2, 1], "samples": 3})).unwrap();
}

#[cfg(feature = "render")]
#[test]
fn a_figures_fields_for_the_other_body_are_refused_by_name() {
    let limits = Limits::default();
    let interrupt = ikarus::Interrupt::new();
    let call = |body: serde_json::Value| {
        super::super::call(super::super::Endpoint::Render, body.to_string().as_bytes(), &limits, &interrupt)
    };
    let rig = serde_json::json!({"bones": [{"name": "a", "length": 1}]});
    let cases = [
        (
            serde_json::json!({"figure": "rig", "rig": rig, "workspace": true}),
            "request body: workspace: unknown field `workspace`, not with rig",
        ),
        (
            serde_json::json!({"figure": "arm", "rig": rig, "goal": {"x": 1, "y": 0}}),
            "request body: goal: unknown field `goal`, not with rig",
        ),
        (
            serde_json::json!({"figure": "arm", "labels": true}),
            "request body: labels: unknown field `labels`, only with rig",
        ),
        (serde_json::json!({"figure": "rig"}), "request body: missing field `rig` at line 1 column 16"),
    ];
    for (body, want) in cases {
        let e = call(body.clone()).unwrap_err();
        assert_eq!((e.status, e.message.as_str()), (422, want), "{body}");
    }
    let svg = serde_json::json!({"figure": "rig", "format": "svg", "rig": rig, "labels": true, "limits": true});
    assert_eq!(call(svg).unwrap().content_type, "image/svg+xml");
}
