//! The API's rig requests under random bodies, valid and invalid: random rigs (any bone order,
//! names with dots, parents that may be missing or form cycles, lengths and angles of mixed
//! magnitudes, now and then bad), goals and pins on bones that may not exist, controls in and
//! out of range, `start_deg` of any length, cheap solver options (any method, ccd and fabrik
//! included). Every answer must be deliberate: 200, or 422 (400 for a number where a name
//! belongs, as serde_json has it), never a 500; a 200 solve is JSON
//! without a `null` (serde writes NaN and infinities as `null`), a 200 picture is an SVG; an
//! error is one line. The server still answers `/api/health` at the end.

#[path = "common/server.rs"]
mod server;

use proptest::prelude::*;
use proptest::test_runner::{Config, FileFailurePersistence, TestCaseError, TestRunner};
use serde_json::{Value, json};

/// A bone's name: unique by its index, some with dots.
fn bone_name(i: usize) -> String {
    if i % 3 == 1 { format!("arm.{i}") } else { format!("b{i}") }
}

fn number() -> BoxedStrategy<Value> {
    prop_oneof![
        24 => (-3.0..3.0f64).prop_map(|v| json!(v)),
        1 => prop_oneof![Just(1e300), Just(-1e300), Just(5e-324), Just(0.0), Just(1e-9), Just(1e9)].prop_map(|v| json!(v)),
        1 => prop_oneof![Just(json!("x")), Just(json!(null)), Just(json!([]))],
    ]
    .boxed()
}

/// A name among the rig's `n` bones, now and then one it does not have.
fn name(n: usize) -> BoxedStrategy<Value> {
    prop_oneof![20 => (0..n).prop_map(|i| json!(bone_name(i))), 1 => Just(json!("no.such"))].boxed()
}

/// What is wrong with a rig, if anything.
#[derive(Debug, Clone, Copy)]
enum Fault {
    None,
    DuplicateName,
    MissingParent,
    Cycle,
    Length,
}

/// A rig of `n` bones: each bone's parent an earlier bone or none, now and then a fault.
fn rig(n: usize) -> impl Strategy<Value = Value> {
    let bone = (
        any::<proptest::sample::Index>(),
        any::<bool>(),
        prop_oneof![60 => (0.1..2.0f64).prop_map(|v| json!(v)), 1 => number()],
        (-180.0..180.0f64),
        proptest::option::weighted(0.3, (-90.0..0.0f64, 0.0..90.0f64)),
    );
    let fault = prop_oneof![
        12 => Just(Fault::None),
        1 => Just(Fault::DuplicateName),
        1 => Just(Fault::MissingParent),
        1 => Just(Fault::Cycle),
        1 => Just(Fault::Length),
    ];
    (proptest::collection::vec(bone, n), fault).prop_map(move |(bones, fault)| {
        let mut list: Vec<Value> = bones
            .into_iter()
            .enumerate()
            .map(|(i, (parent, root, length, angle, limits))| {
                let mut b = json!({"name": bone_name(i), "length": length, "angle_deg": angle});
                if i > 0 && !root {
                    b["parent"] = json!(bone_name(parent.index(i)));
                }
                if let Some((lo, hi)) = limits {
                    b["limits_deg"] = json!([lo, hi]);
                    b["angle_deg"] = json!(0.0);
                }
                b
            })
            .collect();
        let last = n - 1;
        match fault {
            Fault::None => {}
            Fault::DuplicateName => list[last]["name"] = json!(bone_name(0)),
            Fault::MissingParent => list[last]["parent"] = json!("nobody"),
            Fault::Cycle => list[0]["parent"] = json!(bone_name(last)),
            Fault::Length => list[last]["length"] = json!(-1.0),
        }
        json!({"name": "r", "bones": list})
    })
}

fn goal(n: usize) -> impl Strategy<Value = Value> {
    (
        name(n),
        number(),
        number(),
        proptest::option::weighted(0.2, number()),
        proptest::option::weighted(0.2, number()),
        proptest::option::weighted(
            0.2,
            prop_oneof![Just(json!("primary")), Just(json!("secondary")), Just(json!("x"))],
        ),
        proptest::option::weighted(0.2, prop_oneof![Just(json!("ccw")), Just(json!("cw")), Just(json!(1))]),
        proptest::option::weighted(0.2, number()),
    )
        .prop_map(|(bone, x, y, angle, weight, priority, bend, softness)| {
            let mut g = json!({"bone": bone, "x": x, "y": y});
            for (k, v) in [
                ("angle_deg", angle),
                ("weight", weight),
                ("priority", priority),
                ("bend", bend),
                ("softness", softness),
            ] {
                if let Some(v) = v {
                    g[k] = v;
                }
            }
            g
        })
}

fn options() -> impl Strategy<Value = Value> {
    (
        prop_oneof![
            12 => proptest::sample::select(&["lm", "dls", "sdls", "pinv", "transpose"][..]),
            1 => proptest::sample::select(&["ccd", "fabrik", "analytic"][..]),
        ],
        any::<bool>(),
        1u32..60,
        0u32..3,
        proptest::option::of(1u32..20),
    )
        .prop_map(|(method, limits, iterations, restarts, every)| {
            let mut o = json!({"method": method, "limits": limits, "max_iterations": iterations, "restarts": restarts});
            if let Some(k) = every {
                o["record_every"] = json!(k);
            }
            o
        })
}

fn request() -> impl Strategy<Value = (&'static str, Value)> {
    (1usize..10).prop_flat_map(|n| {
        (
            rig(n),
            proptest::collection::vec(goal(n), 0..3),
            proptest::collection::vec(name(n), 0..2),
            proptest::option::weighted(0.2, number()),
            proptest::option::weighted(0.2, proptest::collection::vec(number(), n - 1..n + 1)),
            options(),
            any::<bool>(),
        )
            .prop_map(|(rig, goals, pins, mix, angles, options, render)| {
                if render {
                    let mut body = json!({"figure": "rig", "format": "svg", "width": 64, "height": 64, "rig": rig,
                                          "goals": goals, "pins": pins, "limits": true, "labels": true});
                    if let Some(a) = angles {
                        body["pose_deg"] = json!(a);
                    }
                    ("/api/render", body)
                } else {
                    let mut body = json!({"rig": rig, "goals": goals, "pins": pins, "options": options});
                    if let Some(m) = mix {
                        body["mix"] = m;
                    }
                    if let Some(a) = angles {
                        body["start_deg"] = json!(a);
                    }
                    ("/api/solve", body)
                }
            })
    })
}

fn check(s: &server::Server, path: &str, body: &Value, ok: &std::cell::Cell<u32>) -> Result<(), TestCaseError> {
    let a = s.post(path, body);
    match a.status {
        200 if path == "/api/render" => {
            prop_assert_eq!(a.content_type.as_str(), "image/svg+xml");
            prop_assert!(a.text().starts_with("<svg"));
        }
        200 => {
            let text = a.text();
            prop_assert!(!text.contains("null"), "a null in {text}");
            let v = a.json();
            prop_assert!(v["effectors"].is_array() && v["angles_deg"].is_object(), "{text}");
        }
        // 400 too: serde_json calls a number where an enum's name belongs malformed JSON.
        status @ (400 | 422) => {
            let e = a.error(status);
            prop_assert!(!e.is_empty());
        }
        other => prop_assert!(false, "{path} {body}: status {other}: {}", a.text()),
    }
    if a.status == 200 {
        ok.set(ok.get() + 1);
    }
    Ok(())
}

#[test]
fn random_rig_requests_get_deliberate_answers() {
    let s = server::start(&[]);
    let cases = std::env::var("PROPTEST_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(96);
    let config =
        Config { cases, failure_persistence: Some(Box::new(FileFailurePersistence::Off)), ..Config::default() };
    let ok = std::cell::Cell::new(0);
    TestRunner::new(config)
        .run(&request(), |(path, body)| check(&s, path, &body, &ok))
        .unwrap_or_else(|e| panic!("{e}"));
    eprintln!("{} of {cases} answered 200", ok.get());
    // The cases reach the work, not only the validation.
    assert!(ok.get() >= cases / 10, "only {} of {cases} answered 200", ok.get());
    assert_eq!(s.get("/api/health").status, 200);
}
