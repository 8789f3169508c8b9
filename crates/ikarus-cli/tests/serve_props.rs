//! The API's handlers under random requests, valid and invalid: one `ikarus serve` (started
//! like `serve.rs` does, on an ephemeral port, killed when done) gets random JSON bodies for
//! every endpoint, built from the fields each request takes with values of every kind (valid
//! ones of mixed magnitudes, out of range, huge, of the wrong type, unknown fields). Each
//! answer must be a deliberate one: never a 500; JSON answers parse and hold no `null` where a
//! number belongs (serde writes NaN and infinities as `null`); pictures are what their content
//! type says. The server still answers `/api/health` at the end. Valid values are kept cheap
//! (small arms, iteration caps, grids and pictures), so that the cases run in seconds.

mod common;

use common::server::Server;

use proptest::prelude::*;
use proptest::test_runner::{Config, FileFailurePersistence, TestCaseError, TestRunner};
use serde_json::{Map, Value, json};

fn start() -> Server {
    Server::start(&[], None)
}

/// Status, content type and body of an answer.
fn post(s: &Server, path: &str, body: &str) -> (u16, String, Vec<u8>) {
    let request = s.agent.post(format!("{}{path}", s.base)).header("Content-Type", "application/json");
    let mut response = request.send(body.as_bytes()).expect("POST");
    let content_type =
        response.headers().get("content-type").map(|v| v.to_str().unwrap().to_owned()).unwrap_or_default();
    let body = response.body_mut().with_config().limit(64 << 20).read_to_vec().expect("read the body");
    (response.status().as_u16(), content_type, body)
}

/// Values that no field takes, or that are out of every range.
fn bad() -> impl Strategy<Value = Value> {
    prop_oneof![
        Just(json!(-3)),
        Just(json!(0)),
        Just(json!(1e300)),
        Just(json!(-1e300)),
        Just(json!(5e-324)),
        Just(json!(4_294_967_296u64)),
        Just(json!("x")),
        Just(json!(null)),
        Just(json!(true)),
        Just(json!([])),
        Just(json!({})),
    ]
}

/// `good`, or now and then (1 in 41) a bad value.
fn or_bad(good: impl Strategy<Value = Value> + 'static) -> BoxedStrategy<Value> {
    prop_oneof![40 => good, 1 => bad()].boxed()
}

fn magnitude() -> impl Strategy<Value = f64> {
    (-9.0f64..9.0, any::<bool>()).prop_map(|(e, neg)| if neg { -(10f64.powf(e)) } else { 10f64.powf(e) })
}

fn number(lo: f64, hi: f64) -> BoxedStrategy<Value> {
    or_bad((lo..hi).prop_map(|v| json!(v)))
}

fn whole(lo: u64, hi: u64) -> BoxedStrategy<Value> {
    or_bad((lo..=hi).prop_map(|v| json!(v)))
}

/// A JSON object of the fields that are present (a `None` leaves the field out).
fn object(fields: Vec<(&'static str, Option<Value>)>, extra: Option<Value>) -> Value {
    let mut m = Map::new();
    for (k, v) in fields {
        if let Some(v) = v {
            m.insert(k.to_owned(), v);
        }
    }
    if let Some(v) = extra {
        m.insert("unknown_field".to_owned(), v);
    }
    Value::Object(m)
}

fn link() -> impl Strategy<Value = Value> {
    let length = or_bad(prop_oneof![(0.01f64..10.0).prop_map(|v| json!(v)), magnitude().prop_map(|v| json!(v.abs()))]);
    let angle = prop::option::of(or_bad(prop_oneof![(-200.0f64..200.0).prop_map(|v| json!(v)), Just(json!(1e300))]));
    let limits = prop::option::of(or_bad((-180.0f64..180.0, 0.0f64..300.0).prop_map(|(lo, w)| json!([lo, lo + w]))));
    (length, angle, limits).prop_map(|(length, angle_deg, limits_deg)| {
        object(vec![("length", Some(length)), ("angle_deg", angle_deg), ("limits_deg", limits_deg)], None)
    })
}

fn arm() -> impl Strategy<Value = Option<Value>> {
    prop::option::of(
        (
            prop::collection::vec(link(), 1..=6),
            prop::option::of(or_bad((-5.0f64..5.0, -5.0f64..5.0).prop_map(|(x, y)| json!([x, y])))),
        )
            .prop_map(|(links, base)| object(vec![("links", Some(json!(links))), ("base", base)], None)),
    )
}

fn goal() -> impl Strategy<Value = Option<Value>> {
    let coordinate = or_bad(prop_oneof![(-8.0f64..8.0).prop_map(|v| json!(v)), magnitude().prop_map(|v| json!(v))]);
    prop::option::weighted(
        0.97,
        or_bad(
            (coordinate.clone(), coordinate, prop::option::of(number(-1e6, 1e6)))
                .prop_map(|(x, y, a)| object(vec![("x", Some(x)), ("y", Some(y)), ("angle_deg", a)], None)),
        ),
    )
}

fn name(names: &'static [&'static str]) -> BoxedStrategy<Value> {
    or_bad(prop::sample::select(names).prop_map(|n| json!(n)))
}

fn options() -> impl Strategy<Value = Option<Value>> {
    let methods: &'static [&'static str] = &["transpose", "pinv", "dls", "sdls", "lm", "ccd", "fabrik", "analytic"];
    let modes: &'static [&'static str] = &["ignore", "clamp", "lock", "nullspace", "weighted"];
    prop::option::of(
        (
            (
                prop::option::of(name(methods)),
                prop::option::of(or_bad(any::<bool>().prop_map(|b| json!(b)))),
                prop::option::weighted(0.2, name(modes)),
                prop::option::of(number(0.0, 2.0)),
                prop::option::of(or_bad((-12.0f64..0.0).prop_map(|e| json!(10f64.powf(e))))),
                prop::option::of(whole(0, 200)),
            ),
            (
                prop::option::of(whole(0, 64)),
                prop::option::of(whole(1, 5000)),
                prop::option::of(whole(0, 2)),
                prop::option::of(number(0.001, 3.0)),
                prop::option::of(number(0.0, 90.0)),
                prop::option::of(number(0.1, 1000.0)),
            ),
        )
            .prop_map(
                |(
                    (method, limits, limit_mode, lambda, tolerance, max_iterations),
                    (backtrack, stall_window, restarts, gain, max_step_deg, time_budget_ms),
                )| {
                    object(
                        vec![
                            ("method", method),
                            ("limits", limits),
                            ("limit_mode", limit_mode),
                            ("lambda", lambda),
                            ("tolerance", tolerance),
                            ("max_iterations", max_iterations),
                            ("backtrack", backtrack),
                            ("stall_window", stall_window),
                            ("restarts", restarts),
                            ("gain", gain),
                            ("max_step_deg", max_step_deg),
                            ("time_budget_ms", time_budget_ms),
                        ],
                        None,
                    )
                },
            ),
    )
}

fn start_deg() -> impl Strategy<Value = Option<Value>> {
    prop::option::weighted(
        0.2,
        or_bad(prop::collection::vec(prop_oneof![-400.0f64..400.0, Just(1e20)], 1..=6).prop_map(|v| json!(v))),
    )
}

fn extra() -> impl Strategy<Value = Option<Value>> {
    prop::option::weighted(0.05, Just(json!(1)))
}

/// An endpoint and a body for it.
fn request() -> impl Strategy<Value = (&'static str, Value)> {
    let solve = (arm(), start_deg(), goal(), options(), extra()).prop_map(|(arm, start, goal, options, extra)| {
        ("/api/solve", object(vec![("arm", arm), ("start_deg", start), ("goal", goal), ("options", options)], extra))
    });
    let motion = || {
        (
            (arm(), start_deg(), goal(), options()),
            (
                prop::option::of(or_bad(
                    prop::collection::vec((-5.0f64..5.0, -5.0f64..5.0).prop_map(|(x, y)| json!([x, y])), 0..=2)
                        .prop_map(|v| json!(v)),
                )),
                prop::option::of(whole(2, 30)),
                prop::option::of(or_bad(any::<bool>().prop_map(|b| json!(b)))),
                prop::option::of(name(&["joint", "cartesian", "spline"])),
                extra(),
            ),
        )
    };
    let animate =
        motion().prop_map(|((arm, start, goal, options), (via, frames, from_solve, interpolation, extra))| {
            let fields = vec![
                ("arm", arm),
                ("start_deg", start),
                ("goal", goal),
                ("options", options),
                ("via", via),
                ("frames", frames),
                ("from_solve", from_solve),
                ("interpolation", interpolation),
            ];
            ("/api/animate", object(fields, extra))
        });
    let track = (
        arm(),
        start_deg(),
        prop::option::of(or_bad((-5.0f64..5.0, -5.0f64..5.0, 0.0f64..5.0).prop_map(|(x, y, r)| json!([x, y, r])))),
        prop::option::of(whole(2, 20)),
        prop::option::of(name(&["follow", "plan"])),
        options(),
        extra(),
    )
        .prop_map(|(arm, start, circle, samples, mode, options, extra)| {
            let fields = vec![
                ("arm", arm),
                ("start_deg", start),
                ("circle", circle),
                ("samples", samples),
                ("mode", mode),
                ("options", options),
            ];
            ("/api/track", object(fields, extra))
        });
    let workspace = (
        arm(),
        prop::option::of(or_bad(any::<bool>().prop_map(|b| json!(b)))),
        prop::option::of(whole(8, 48)),
        prop::option::of(whole(1, 64)),
        extra(),
    )
        .prop_map(|(arm, limits, resolution, samples, extra)| {
            (
                "/api/workspace",
                object(vec![("arm", arm), ("limits", limits), ("resolution", resolution), ("samples", samples)], extra),
            )
        });
    let point = || or_bad((-8.0f64..8.0, -8.0f64..8.0).prop_map(|(x, y)| json!([x, y])));
    let reach = (
        arm(),
        prop::option::of(or_bad(any::<bool>().prop_map(|b| json!(b)))),
        prop::option::of(or_bad(magnitude().prop_map(|v| json!(v.abs())))),
        prop::option::of(point()),
        prop::option::of(or_bad(prop::collection::vec(point(), 0..20).prop_map(|p| json!(p)))),
        extra(),
    )
        .prop_map(|(arm, limits, tolerance, point, points, extra)| {
            let fields =
                vec![("arm", arm), ("limits", limits), ("tolerance", tolerance), ("point", point), ("points", points)];
            ("/api/reach", object(fields, extra))
        });
    let picture = (
        prop::option::of(name(&["png", "svg", "gif"])),
        prop::option::of(whole(16, 128)),
        prop::option::of(whole(16, 128)),
    );
    let render_arm = (arm(), goal(), start_deg(), picture.clone(), extra()).prop_map(
        |(arm, goal, pose, (format, width, height), extra)| {
            let fields = vec![
                ("figure", Some(json!("arm"))),
                ("arm", arm),
                ("goal", goal),
                ("pose_deg", pose),
                ("format", format),
                ("width", width),
                ("height", height),
            ];
            ("/api/render", object(fields, extra))
        },
    );
    let render_motion = (motion(), picture.clone()).prop_map(
        |(((arm, start, goal, options), (via, frames, _, _, extra)), (format, width, height))| {
            let fields = vec![
                ("figure", Some(json!("motion"))),
                ("arm", arm),
                ("start_deg", start),
                ("goal", goal),
                ("options", options),
                ("via", via),
                ("frames", frames),
                ("format", format),
                ("width", width),
                ("height", height),
            ];
            ("/api/render", object(fields, extra))
        },
    );
    let render_workspace =
        (arm(), prop::option::of(whole(8, 48)), picture).prop_map(|(arm, resolution, (format, width, height))| {
            let fields = vec![
                ("figure", Some(json!("workspace"))),
                ("arm", arm),
                ("resolution", resolution),
                ("format", format),
                ("width", width),
                ("height", height),
            ];
            ("/api/render", object(fields, None))
        });
    prop_oneof![3 => solve, 2 => animate, 1 => track, 1 => workspace, 1 => reach, 1 => render_arm, 1 => render_motion, 1 => render_workspace]
}

/// Where a `null` may stand: an absent orientation, and the region's distance of a solve made
/// without limits (no verdict).
const NULLABLE: &[&str] = &["angle_deg", "reach_distance"];

/// The path of a `null` that stands where a number belongs, if any.
fn misplaced_null(v: &Value, key: &str, path: &str) -> Option<String> {
    match v {
        Value::Null if !NULLABLE.contains(&key) => Some(path.to_owned()),
        Value::Array(items) => {
            items.iter().enumerate().find_map(|(i, x)| misplaced_null(x, key, &format!("{path}[{i}]")))
        }
        Value::Object(m) => m.iter().find_map(|(k, x)| misplaced_null(x, k, &format!("{path}.{k}"))),
        _ => None,
    }
}

fn check(s: &Server, path: &str, body: &Value, answered: &std::cell::Cell<[u32; 2]>) -> Result<(), TestCaseError> {
    let (status, content_type, bytes) = post(s, path, &body.to_string());
    let [ok, all] = answered.get();
    answered.set([ok + u32::from(status == 200), all + 1]);
    prop_assert!(
        status != 500 && (status < 500 || status == 503),
        "{} {}: {}",
        path,
        status,
        String::from_utf8_lossy(&bytes)
    );
    match content_type.as_str() {
        "image/png" => prop_assert!(bytes.starts_with(b"\x89PNG")),
        "image/gif" => prop_assert!(bytes.starts_with(b"GIF89a")),
        t if t.starts_with("image/svg+xml") => prop_assert!(String::from_utf8_lossy(&bytes).contains("<svg")),
        t => {
            prop_assert!(t.starts_with("application/json"), "{} {}: content type {:?}", path, status, t);
            let v: Value = serde_json::from_slice(&bytes).map_err(|e| TestCaseError::fail(format!("not JSON: {e}")))?;
            prop_assert_eq!(status == 200, !v.get("error").is_some_and(Value::is_string), "{} {}", status, v);
            if let Some(at) = misplaced_null(&v, "", "") {
                return Err(TestCaseError::fail(format!("{path} {status}: null at {at} for {body}")));
            }
        }
    }
    Ok(())
}

/// 96 requests (about ten seconds in a debug build) unless `PROPTEST_CASES` says otherwise.
#[test]
fn random_requests_get_deliberate_answers() {
    // The nested strategies are deep for a debug build's default test-thread stack.
    let run = std::thread::Builder::new().stack_size(256 << 20).spawn(random_requests).expect("a thread");
    if let Err(panic) = run.join() {
        std::panic::resume_unwind(panic);
    }
}

fn random_requests() {
    let server = start();
    let cases = std::env::var("PROPTEST_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(96);
    let config =
        Config { cases, failure_persistence: Some(Box::new(FileFailurePersistence::Off)), ..Config::default() };
    let mut runner = TestRunner::new(config);
    let answered = std::cell::Cell::new([0, 0]);
    let outcome = runner.run(&request(), |(path, body)| check(&server, path, &body, &answered));
    if let Err(e) = outcome {
        panic!("{e}");
    }
    // The cases reach the work, not only the validation: a good share is answered 200.
    let [ok, all] = answered.get();
    println!("{ok} of {all} requests answered 200");
    assert!(ok * 4 >= all, "{ok} of {all}");
    let (status, _, body) = {
        let mut r = server.agent.get(format!("{}/api/health", server.base)).call().expect("GET");
        (r.status().as_u16(), (), r.body_mut().read_to_string().expect("body"))
    };
    assert_eq!(status, 200, "{body}");
}
