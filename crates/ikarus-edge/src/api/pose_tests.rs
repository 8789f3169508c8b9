use super::super::{Endpoint, Limits, call, status};
use ikarus::Interrupt;

/// A character's pose, motion and track with their interrupt set end 503 (the server's
/// deadline), not 200 nor a refusal of the request; unset, the same requests answer.
#[test]
fn character_jobs_stop_at_their_interrupt() {
    let rig = include_str!("../../../../examples/characters/spine-spineboy-pro.json");
    let bodies = [
        (Endpoint::Pose, serde_json::json!({"rig": rig, "animation": "walk", "time": 0.2, "ik": "ikarus"})),
        (Endpoint::Pose, serde_json::json!({"rig": rig, "animation": "walk", "time": 0.2})),
        (
            Endpoint::Animate,
            serde_json::json!({"rig": rig, "targets": [{"bone": "front-leg-target", "x": 30, "y": 0}], "fps": 10}),
        ),
        (
            Endpoint::Track,
            serde_json::json!({"rig": rig, "effector": "front-leg-target", "line": [0, 0, 30, 0], "samples": 5}),
        ),
    ];
    for (endpoint, body) in bodies {
        let body = body.to_string();
        let answered = call(endpoint, body.as_bytes(), &Limits::default(), &Interrupt::new());
        assert!(answered.is_ok(), "{endpoint:?}: {:?}", answered.err());
        let token = Interrupt::new();
        token.interrupt();
        let e = call(endpoint, body.as_bytes(), &Limits::default(), &token).unwrap_err();
        assert_eq!(e.status, status::SERVICE_UNAVAILABLE, "{endpoint:?}: {}", e.message);
    }
}
