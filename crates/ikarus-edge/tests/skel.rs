//! Spine's binary exports (`examples/characters/*.skel`) decoded into the tree of Spine's JSON
//! export, compared with the JSON export of the same skeleton, field by field.
//!
//! The JSON export rounds its numbers (2 decimals for most, 4 for scales and mixes, 5 for
//! UVs) while the binary keeps the 32-bit floats, so a JSON number `j` printed with `d`
//! decimals is matched by a decoded `s` with |j − s| ≤ min(½·10⁻ᵈ, 0.005) (plus f32's relative
//! step). Where the JSON omits a field at its default, the decoded value must be that default
//! within 0.005. What the two exports say differently on purpose is named where it is allowed:
//! a deform key's `offset` and `vertices` (JSON trims the zeros that round to 0: compared as
//! the full offsets), a stepped curve between equal keys (the binary writes it linear: the
//! same motion), the bend of a one-bone IK constraint (it bends nothing: the binary stores 0),
//! and nonessential editor fields the JSON does not carry (`visible`, default colours).

use serde_json::{Map, Value};

fn file(name: &str) -> Vec<u8> {
    std::fs::read(format!("{}/../../examples/characters/{name}", env!("CARGO_MANIFEST_DIR"))).unwrap()
}

fn pair(character: &str) -> (Value, Value) {
    let json: Value = serde_json::from_slice(&file(&format!("spine-{character}-pro.json"))).unwrap();
    let skel = ikarus_edge::character::skel::to_json(&file(&format!("spine-{character}-pro.skel"))).unwrap();
    (json, skel)
}

/// How far a decoded number may be from the JSON's rounded one.
fn tolerance(j: f64) -> f64 {
    let text = format!("{j}");
    let decimals = text.split_once('.').map_or(0, |(_, d)| d.len());
    let printed = 0.5 * 10f64.powi(-i32::try_from(decimals).unwrap());
    printed.min(0.005) * 1.0001 + j.abs() * f64::from(f32::EPSILON)
}

fn close(j: f64, s: f64) -> bool {
    (j - s).abs() <= tolerance(j)
}

/// The default JSON leaves out for `key` of an object at `path` (`j` the JSON's object, `s` the
/// decoded one); `None` for a field the comparison leaves aside (named in the module's doc).
fn default(path: &str, key: &str, j: &Map<String, Value>, s: &Map<String, Value>) -> Option<Value> {
    let animations = path.contains(".animations");
    let physics = path.starts_with(".physics[") || path.contains(".physics.");
    let transform = path.starts_with(".transform[");
    let attachment = path.starts_with(".skins[");
    let v = match key {
        "visible" | "vertexCount" | "icon" => return None,
        "color" if !animations && !path.starts_with(".slots[") => return None,
        "bendPositive" if path.starts_with(".ik[") && s["bones"].as_array().is_some_and(|b| b.len() == 1) => {
            return None;
        }
        "color" => Value::from("ffffffff"),
        "mixY" => j.get("mixX").cloned().unwrap_or(Value::from(1.0)),
        "mixScaleY" => j.get("mixScaleX").cloned().unwrap_or(Value::from(1.0)),
        "rotation" | "x" | "y" | "scaleX" | "scaleY" | "shearY" if transform => Value::from(0.0),
        "x" | "y" | "rotate" | "scaleX" | "shearX" | "wind" | "gravity" if physics => Value::from(0.0),
        "limit" => Value::from(5000.0),
        "fps" if physics => Value::from(60.0),
        "fps" => Value::from(30.0),
        "inertia" | "damping" | "mass" => Value::from(1.0),
        "strength" => Value::from(100.0),
        "referenceScale" => Value::from(100.0),
        "x" | "y" | "value" if animations && path.contains(".scale") => Value::from(1.0),
        "scaleX" | "scaleY" | "mix" | "mixRotate" | "mixX" | "mixScaleX" | "mixShearY" => Value::from(1.0),
        "name" if attachment => Value::from(path.rsplit('.').next().unwrap_or_default()),
        "name" if animations => Value::Null,
        "path" if attachment => s["name"].clone(),
        "type" => Value::from("region"),
        "inherit" | "blend" => Value::from("normal"),
        "bendPositive" | "timelines" | "constantSpeed" => Value::from(true),
        "skin" | "compress" | "stretch" | "uniform" | "local" | "relative" | "closed" => Value::from(false),
        k if k.ends_with("Global") => Value::from(false),
        "positionMode" => Value::from("percent"),
        "spacingMode" => Value::from("length"),
        "rotateMode" => Value::from("tangent"),
        "string" => Value::from(""),
        _ => Value::from(0.0),
    };
    Some(v)
}

/// Every difference between the JSON export `j` and the decoded tree `s` under `path`.
fn compare(j: &Value, s: &Value, path: &str, out: &mut Vec<String>) {
    match (j, s) {
        (Value::Object(jo), Value::Object(so)) => {
            for (k, jv) in jo {
                let p = format!("{path}.{k}");
                match so.get(k) {
                    Some(sv) => compare(jv, sv, &p, out),
                    None => out.push(format!("{p}: not decoded (JSON {jv})")),
                }
            }
            for (k, sv) in so.iter().filter(|(k, _)| !jo.contains_key(*k)) {
                let Some(d) = default(path, k, jo, so) else { continue };
                let same = match (&d, sv) {
                    (Value::Number(d), Value::Number(v)) => (d.as_f64().unwrap() - v.as_f64().unwrap()).abs() <= 0.005,
                    (Value::Array(_) | Value::Object(_), _) => true,
                    (d, v) => d == v,
                };
                let empty = sv.as_array().is_some_and(Vec::is_empty) || sv.as_object().is_some_and(Map::is_empty);
                if !same && !empty {
                    out.push(format!("{path}.{k}: decoded {sv}, JSON leaves out {d}"));
                }
            }
        }
        (Value::Array(ja), Value::Array(sa)) if path.ends_with(".deform") => {
            if ja.len() != sa.len() {
                out.push(format!("{path}: {} keys, decoded {}", ja.len(), sa.len()));
            }
            for (i, (jk, sk)) in ja.iter().zip(sa).enumerate() {
                let (jv, sv) = (offsets(jk), offsets(sk));
                let n = jv.len().max(sv.len());
                for v in 0..n {
                    let (a, b) = (jv.get(v).copied().unwrap_or(0.0), sv.get(v).copied().unwrap_or(0.0));
                    if !close(a, b) {
                        out.push(format!("{path}[{i}].vertices[{v}]: JSON {a}, decoded {b}"));
                    }
                }
                let (mut jk, mut sk) = (jk.clone(), sk.clone());
                for k in [&mut jk, &mut sk] {
                    if let Value::Object(o) = k {
                        o.remove("offset");
                        o.remove("vertices");
                    }
                }
                compare(&jk, &sk, &format!("{path}[{i}]"), out);
            }
        }
        (Value::Array(ja), Value::Array(sa)) => {
            if ja.len() != sa.len() {
                out.push(format!("{path}: {} items, decoded {}", ja.len(), sa.len()));
                return;
            }
            for (i, (jv, sv)) in ja.iter().zip(sa).enumerate() {
                let p = match jv.get("name").and_then(Value::as_str).filter(|_| jv.get("time").is_none()) {
                    Some(n) => format!("{path}[{n:?}]"),
                    None => format!("{path}[{i}]"),
                };
                if jv.get("curve").and_then(Value::as_str) == Some("stepped") && sv.get("curve").is_none() {
                    // Stepped between equal keys: the binary writes it linear.
                    let mut stripped = jv.clone();
                    stripped.as_object_mut().unwrap().remove("curve");
                    let next_same = ja.get(i + 1).is_some_and(|n| values_equal(jv, n));
                    if !next_same {
                        out.push(format!("{p}.curve: JSON stepped, decoded linear"));
                    }
                    compare(&stripped, sv, &p, out);
                    continue;
                }
                compare(jv, sv, &p, out);
            }
        }
        (Value::Number(a), Value::Number(b)) => {
            if !close(a.as_f64().unwrap(), b.as_f64().unwrap()) {
                out.push(format!("{path}: JSON {a}, decoded {b}"));
            }
        }
        (a, b) => {
            if a != b {
                out.push(format!("{path}: JSON {a}, decoded {b}"));
            }
        }
    }
}

/// A deform key's full offsets (zeros before `offset`).
fn offsets(key: &Value) -> Vec<f64> {
    let start = key.get("offset").and_then(Value::as_u64).unwrap_or(0) as usize;
    let mut v = vec![0.0; start];
    v.extend(key.get("vertices").and_then(Value::as_array).into_iter().flatten().map(|x| x.as_f64().unwrap()));
    v
}

/// Whether two keys hold the same values (every field but time and curve).
fn values_equal(a: &Value, b: &Value) -> bool {
    let strip = |v: &Value| {
        let mut o = v.as_object().cloned().unwrap_or_default();
        o.remove("time");
        o.remove("curve");
        o
    };
    strip(a) == strip(b)
}

fn check(character: &str) -> usize {
    let (json, skel) = pair(character);
    let mut out = Vec::new();
    compare(&json, &skel, "", &mut out);
    assert!(out.is_empty(), "{character}: {} differences, the first: {:#?}", out.len(), &out[..out.len().min(60)]);
    // What was compared, for the report.
    let keys: usize = json["animations"].as_object().unwrap().values().map(count_keys).sum();
    println!("{character}: the decoded tree matches the JSON export ({keys} animation keys)");
    keys
}

fn count_keys(v: &Value) -> usize {
    match v {
        Value::Array(a) if a.iter().all(|k| k.get("time").is_some() || k.is_object()) => a.len(),
        Value::Object(o) => o.values().map(count_keys).sum(),
        _ => 0,
    }
}

#[test]
fn spineboy_skel_decodes_to_its_json_export() {
    assert!(check("spineboy") > 1000);
}

#[test]
fn raptor_skel_decodes_to_its_json_export() {
    assert!(check("raptor") > 500);
}

#[test]
fn stretchyman_skel_decodes_to_its_json_export() {
    assert!(check("stretchyman") > 50);
}

#[test]
fn celestial_circus_skel_decodes_to_its_json_export() {
    assert!(check("celestial-circus") > 100);
}

#[test]
fn the_decoded_trees_text_reads_back_to_the_same_bits() {
    for character in ["spineboy", "raptor", "stretchyman", "celestial-circus"] {
        let (_, skel) = pair(character);
        let back: Value = serde_json::from_str(&serde_json::to_string(&skel).unwrap()).unwrap();
        assert_eq!(back, skel, "{character}");
        // And every number is a 32-bit float widened (or an integer).
        let mut numbers = vec![&skel];
        let mut checked = 0;
        while let Some(v) = numbers.pop() {
            match v {
                Value::Array(a) => numbers.extend(a),
                Value::Object(o) => numbers.extend(o.values()),
                Value::Number(n) => {
                    let f = n.as_f64().unwrap();
                    assert_eq!(f64::from(f as f32).to_bits(), f.to_bits(), "{character}: {f}");
                    checked += 1;
                }
                _ => {}
            }
        }
        assert!(checked > 5_000, "{character}: {checked}");
    }
}
