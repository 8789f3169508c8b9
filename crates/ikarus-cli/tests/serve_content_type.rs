//! Cross-site requests: a web page on another site may send a POST to `127.0.0.1:7878` without
//! asking (a CORS "simple request") only with a body of type `text/plain`,
//! `application/x-www-form-urlencoded` or `multipart/form-data`. The server refuses every body
//! that is not its endpoint's type (`application/json`, or `application/toml` for the arm and
//! rig files' text, `application/octet-stream` too for a character file's bytes) with 415 before
//! reading it, a missing type included, and answers no CORS preflight, so such a page can make
//! it do no work.

mod common;

use std::io::{Read, Write};
use std::net::TcpStream;
use std::time::Duration;

use common::server::{Answer, Server, start};

/// The endpoints that take a JSON body.
const JSON: [&str; 8] = [
    "/api/solve",
    "/api/solve_batch",
    "/api/animate",
    "/api/track",
    "/api/workspace",
    "/api/reach",
    "/api/render",
    "/api/arm/toml",
];

/// The endpoints that take a file's text.
const TOML: [&str; 2] = ["/api/arm/parse", "/api/rig/parse"];

/// What `/api/rig/parse` takes: a file's text or its bytes (a `.skel`).
const RIG_FILE: &str = "application/toml or application/octet-stream";

/// The types a page may send without a preflight, in the spellings browsers use, and no type.
const SIMPLE: [Option<&str>; 6] = [
    Some("text/plain"),
    Some("text/plain;charset=UTF-8"),
    Some("application/x-www-form-urlencoded"),
    Some("multipart/form-data; boundary=----x"),
    Some("TEXT/PLAIN"),
    None,
];

/// A request written byte for byte (so that no client library adds a header): the answer
/// whole, headers and body, as text.
fn raw(s: &Server, request: &str) -> String {
    let mut c = TcpStream::connect(&s.addr).expect("connect");
    c.set_read_timeout(Some(Duration::from_secs(30))).unwrap();
    c.write_all(request.as_bytes()).unwrap();
    let mut out = Vec::new();
    let _ = c.read_to_end(&mut out);
    String::from_utf8_lossy(&out).into_owned()
}

/// `POST path` with `content_type` (no header at all for `None`) and `body`, as an [`Answer`].
fn post(s: &Server, path: &str, content_type: Option<&str>, body: &str) -> Answer {
    let header = content_type.map_or(String::new(), |t| format!("Content-Type: {t}\r\n"));
    let reply = raw(
        s,
        &format!(
            "POST {path} HTTP/1.1\r\nHost: localhost\r\n{header}Content-Length: {}\r\nConnection: close\r\n\r\n{body}",
            body.len()
        ),
    );
    let (head, body) = reply.split_once("\r\n\r\n").unwrap_or_else(|| panic!("no answer: {reply:?}"));
    let status = head.split(' ').nth(1).and_then(|c| c.parse().ok()).unwrap_or_else(|| panic!("{head}"));
    let content_type = head
        .lines()
        .find_map(|l| l.to_ascii_lowercase().strip_prefix("content-type: ").map(str::to_owned))
        .unwrap_or_default();
    Answer { status, content_type, body: body.as_bytes().to_vec() }
}

#[test]
fn every_post_with_another_content_type_is_415_naming_the_header() {
    let s = start(&[]);
    let solve = r#"{"goal":{"x":2,"y":3}}"#;
    let rig = "[[bones]]\nname = \"a\"\nlength = 1\n";
    for (paths, body, want) in [(&JSON[..], solve, "application/json"), (&TOML[..], rig, "application/toml")] {
        for path in paths {
            for content_type in SIMPLE {
                let e = post(&s, path, content_type, body).error(415);
                let named =
                    content_type.map_or("Content-Type: missing".to_owned(), |t| format!("Content-Type = {t:?}"));
                let want = if *path == "/api/rig/parse" { RIG_FILE } else { want };
                assert_eq!(e, format!("{named}: expected {want}"), "{path} with {content_type:?}");
            }
        }
    }
    // Each kind of body is refused by the other kind of endpoint.
    assert_eq!(
        post(&s, "/api/solve", Some("application/toml"), solve).error(415),
        "Content-Type = \"application/toml\": expected application/json"
    );
    assert_eq!(
        post(&s, "/api/rig/parse", Some("application/json"), rig).error(415),
        format!("Content-Type = \"application/json\": expected {RIG_FILE}")
    );
    assert_eq!(
        post(&s, "/api/arm/parse", Some("application/octet-stream"), rig).error(415),
        "Content-Type = \"application/octet-stream\": expected application/toml"
    );
    s.assert_healthy();
}

#[test]
fn the_endpoints_own_types_are_taken_with_parameters_in_any_case() {
    let s = start(&[]);
    for t in ["application/json", "application/json; charset=utf-8", "Application/JSON", "application/vnd.api+json"] {
        let a = post(&s, "/api/solve", Some(t), r#"{"goal":{"x":2,"y":3}}"#);
        assert_eq!(a.status, 200, "{t}: {}", a.text());
    }
    for t in ["application/toml", "application/toml; charset=utf-8"] {
        let a = post(&s, "/api/rig/parse", Some(t), "[[bones]]\nname = \"a\"\nlength = 1\n");
        assert_eq!(a.status, 200, "{t}: {}", a.text());
        assert!(a.json()["rig"].is_object(), "{}", a.text());
        let a = post(&s, "/api/arm/parse", Some(t), "[[links]]\nlength = 1\n");
        assert_eq!(a.status, 200, "{t}: {}", a.text());
        assert!(a.json()["arm"].is_object(), "{}", a.text());
    }
}

#[test]
fn no_cors_preflight_is_answered() {
    let s = start(&[]);
    for path in JSON.iter().chain(&TOML) {
        let reply = raw(
            &s,
            &format!(
                "OPTIONS {path} HTTP/1.1\r\nHost: localhost\r\nOrigin: https://example.com\r\n\
                 Access-Control-Request-Method: POST\r\nAccess-Control-Request-Headers: content-type\r\n\
                 Connection: close\r\n\r\n"
            ),
        );
        let head = reply.split("\r\n\r\n").next().unwrap().to_ascii_lowercase();
        assert!(!head.starts_with("http/1.1 2"), "{path}: a preflight answered {head}");
        assert!(!head.contains("access-control-allow"), "{path}: {head}");
    }
    // Nor does an answer to a request from another origin allow it to be read.
    let reply = raw(
        &s,
        "GET /api/rigs HTTP/1.1\r\nHost: localhost\r\nOrigin: https://example.com\r\nConnection: close\r\n\r\n",
    );
    assert!(!reply.split("\r\n\r\n").next().unwrap().to_ascii_lowercase().contains("access-control-allow"), "{reply}");
}
