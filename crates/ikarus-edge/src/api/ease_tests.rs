use super::*;
use crate::api::{Endpoint, Limits, call};
use ikarus::{Ease, Interrupt};

fn answer(body: &str) -> Result<serde_json::Value, Problem> {
    let reply = call(Endpoint::Ease, body.as_bytes(), &Limits::default(), &Interrupt::new())?;
    Ok(serde_json::from_slice(&reply.body).unwrap())
}

/// Every kind, Parent's with its parameters, is the library's `Ease::position`, bit for bit,
/// at `i / (samples − 1)`; the ends are 0 and 1.
#[test]
fn the_curve_is_the_librarys() {
    let cases = [
        (r#"{"samples": 11}"#, EaseKind::Sine.ease(None, None).unwrap()),
        (r#"{"ease": {"kind": "linear"}, "samples": 2}"#, EaseKind::Linear.ease(None, None).unwrap()),
        (r#"{"ease": {"kind": "smoothstep"}, "samples": 49}"#, EaseKind::Smoothstep.ease(None, None).unwrap()),
        (r#"{"ease": {"kind": "parent"}, "samples": 24}"#, EaseKind::Parent.ease(None, None).unwrap()),
        (r#"{"ease": {"kind": "parent", "k1": 0.3, "k2": 0.75}, "samples": 101}"#, Ease::parent(0.3, 0.75).unwrap()),
    ];
    for (body, want) in cases {
        let v = answer(body).unwrap();
        let (t, s) = (v["t"].as_array().unwrap(), v["s"].as_array().unwrap());
        assert_eq!(t.len(), s.len());
        let n = t.len() - 1;
        for (i, (t, s)) in t.iter().zip(s).enumerate() {
            let t = t.as_f64().unwrap();
            assert_eq!(t.to_bits(), (i as f64 / n as f64).to_bits(), "{body}");
            assert_eq!(s.as_f64().unwrap().to_bits(), want.position(t).to_bits(), "{body} at {t}");
        }
        assert_eq!((s[0].as_f64(), s[n].as_f64()), (Some(0.0), Some(1.0)), "{body}");
    }
    // ease.rs's reference values for Parent's ease with k1 = 0.3, k2 = 0.75 (ERRATA.md).
    let v = answer(r#"{"ease": {"kind": "parent", "k1": 0.3, "k2": 0.75}, "samples": 21}"#).unwrap();
    for (i, want) in [(5, 0.176913), (10, 0.488646), (18, 0.962012)] {
        assert!((v["s"][i].as_f64().unwrap() - want).abs() < 5e-7, "{i}");
    }
}

#[test]
fn bad_requests_name_the_field_and_value() {
    let e = |body: &str| answer(body).unwrap_err().message;
    assert_eq!(e(r#"{"samples": 1}"#), "samples: 1, must be from 2 to 10001");
    assert_eq!(e(r#"{"samples": 10002}"#), "samples: 10002, must be from 2 to 10001");
    assert!(e(r#"{"ease": {"kind": "linear", "k1": 0.2}, "samples": 5}"#).starts_with("ease.k1"));
    assert!(e(r#"{"ease": {"kind": "parent", "k1": 0.9, "k2": 0.1}, "samples": 5}"#).starts_with("ease."));
    assert!(e(r#"{}"#).contains("samples"));
}
