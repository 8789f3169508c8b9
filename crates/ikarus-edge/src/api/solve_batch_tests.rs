use serde_json::{Value, json};

use super::*;
use crate::api::{Endpoint, call, status};

fn post(endpoint: Endpoint, body: &Value, limits: &Limits) -> Result<Value, Problem> {
    let reply = call(endpoint, body.to_string().as_bytes(), limits, &Interrupt::new())?;
    Ok(serde_json::from_slice(&reply.body).unwrap())
}

fn bits(v: &Value) -> Vec<u64> {
    v.as_array().unwrap().iter().map(|a| a.as_f64().unwrap().to_bits()).collect()
}

#[test]
fn each_goal_gets_what_api_solve_gives_it_bit_for_bit() {
    let limits = Limits::default();
    let goals = [json!([2, 3]), json!([-3, -1]), json!([1.5, 2.5, 90]), json!([9, 9]), json!([4.5, 0.3])];
    for options in [json!({}), json!({"limits": true, "restarts": 4}), json!({"method": "dls"})] {
        let body = json!({"goals": goals, "options": options, "start_deg": [10, 20, 30]});
        let batch = post(Endpoint::SolveBatch, &body, &limits).unwrap();
        assert_eq!(batch["angles_deg"].as_array().unwrap().len(), goals.len());
        for (i, g) in goals.iter().enumerate() {
            let g = g.as_array().unwrap();
            let goal = json!({"x": g[0], "y": g[1], "angle_deg": g.get(2)});
            let one = json!({"goal": goal, "options": options, "start_deg": [10, 20, 30]});
            let one = post(Endpoint::Solve, &one, &limits).unwrap();
            assert_eq!(bits(&batch["angles_deg"][i]), bits(&one["angles_deg"]), "{options} {goal}");
            assert_eq!(batch["status"][i], one["status"], "{options} {goal}");
            assert_eq!(batch["iterations"][i], one["iterations"], "{options} {goal}");
            assert_eq!(batch["error"][i].as_f64().map(f64::to_bits), one["error"].as_f64().map(f64::to_bits));
            for k in ["arm", "method", "limits", "limit_mode", "tolerance"] {
                assert_eq!(batch[k], one[k], "{k}");
            }
        }
    }
    let empty = post(Endpoint::SolveBatch, &json!({"goals": []}), &limits).unwrap();
    assert_eq!(empty["status"], json!([]));
}

#[test]
fn caps_and_bad_goals_are_one_line_naming_the_field() {
    let limits = Limits { max_goals: 3, ..Limits::default() };
    let refused = |body: Value| post(Endpoint::SolveBatch, &body, &limits).unwrap_err();
    let e = refused(json!({"goals": [[1, 1], [1, 2], [1, 3], [1, 4]]}));
    assert_eq!(
        (e.status, e.message.as_str()),
        (status::UNPROCESSABLE_ENTITY, "goals: 4 goals, more than the cap of 3")
    );
    let e = refused(json!({"goals": [[1, 1], [1, 2, 3, 4]]}));
    assert_eq!(e.message, "goals[1]: expected [x, y] or [x, y, angle_deg], got 4 numbers");
    assert!(refused(json!({"goals": [[1, 1], [1]]})).message.starts_with("goals[1]: expected"));
    assert!(refused(json!({"goals": [[1, "a"]]})).message.contains("goals[0][1]"));
    assert!(refused(json!({})).message.contains("missing field `goals`"));
    assert!(refused(json!({"goals": [[1, 1]], "goal": {"x": 1, "y": 1}})).message.contains("unknown field `goal`"));
    assert!(refused(json!({"goals": [[1, 1]], "start_deg": [1]})).message.starts_with("start_deg: "));
    assert!(refused(json!({"goals": [[1, 1]], "options": {"tolerance": 0}})).message.starts_with("options."));
}

#[test]
fn an_interrupted_batch_is_503() {
    let interrupt = Interrupt::new();
    interrupt.interrupt();
    let body = json!({"goals": [[2, 3], [1, 1]]}).to_string();
    let e = call(Endpoint::SolveBatch, body.as_bytes(), &Limits::default(), &interrupt).unwrap_err();
    assert_eq!(e.status, status::SERVICE_UNAVAILABLE);
}
