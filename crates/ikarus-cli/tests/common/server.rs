//! A running `ikarus serve` for the API tests, on an ephemeral port, killed on drop. Use it
//! with `#[path = "common/server.rs"] mod server;` (it is not part of `common`, so that the
//! tests that do not start a server do not compile it).
#![allow(dead_code)]

use std::io::{BufRead, BufReader};
use std::process::{Child, Command, Stdio};

use serde_json::Value;

/// A running `ikarus serve`, killed on drop.
pub struct Server {
    child: Child,
    pub base: String,
    agent: ureq::Agent,
}

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// An answer: status, content type, body.
pub struct Answer {
    pub status: u16,
    pub content_type: String,
    pub body: Vec<u8>,
}

impl Answer {
    pub fn json(&self) -> Value {
        serde_json::from_slice(&self.body)
            .unwrap_or_else(|e| panic!("not JSON ({e}): {}", String::from_utf8_lossy(&self.body)))
    }

    pub fn text(&self) -> String {
        String::from_utf8_lossy(&self.body).into_owned()
    }

    /// The `error` of a JSON error body, after checking the status: one line, the only key.
    pub fn error(&self, status: u16) -> String {
        assert_eq!(self.status, status, "body: {}", self.text());
        assert_eq!(self.content_type, "application/json");
        let v = self.json();
        let e = v["error"].as_str().unwrap_or_else(|| panic!("no error string: {v}")).to_owned();
        assert!(!e.contains('\n'), "multi-line error: {e:?}");
        assert_eq!(v.as_object().unwrap().len(), 1, "only `error`: {v}");
        e
    }
}

/// Starts `ikarus serve --port 0` with `args` and waits for its address.
pub fn start(args: &[&str]) -> Server {
    let mut child = Command::new(env!("CARGO_BIN_EXE_ikarus"))
        .args(["serve", "--port", "0"])
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("start ikarus serve");
    let mut line = String::new();
    BufReader::new(child.stdout.take().expect("stdout")).read_line(&mut line).expect("read the address line");
    let base = line
        .trim()
        .strip_prefix("ikarus serve: listening on ")
        .unwrap_or_else(|| panic!("unexpected first line: {line:?}"))
        .to_owned();
    let config = ureq::Agent::config_builder().http_status_as_error(false).build();
    Server { child, base, agent: config.into() }
}

impl Server {
    fn answer(mut response: ureq::http::Response<ureq::Body>) -> Answer {
        let content_type =
            response.headers().get("content-type").map(|v| v.to_str().unwrap().to_owned()).unwrap_or_default();
        let body = response.body_mut().with_config().limit(64 << 20).read_to_vec().expect("read the body");
        Answer { status: response.status().as_u16(), content_type, body }
    }

    pub fn get(&self, path: &str) -> Answer {
        Self::answer(self.agent.get(format!("{}{path}", self.base)).call().expect("GET"))
    }

    pub fn post_raw(&self, path: &str, content_type: &str, body: &[u8]) -> Answer {
        let request = self.agent.post(format!("{}{path}", self.base)).header("Content-Type", content_type);
        Self::answer(request.send(body).expect("POST"))
    }

    pub fn post(&self, path: &str, body: &Value) -> Answer {
        self.post_raw(path, "application/json", body.to_string().as_bytes())
    }
}
