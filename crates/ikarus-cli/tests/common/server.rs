//! A running `ikarus serve` for the API tests (`serve.rs`, `serve_limits.rs`, `serve_props.rs`
//! through `common`, the rig tests with `#[path = "common/server.rs"] mod server;`): started
//! on an ephemeral port, its address read from its first line, killed on drop; and its answers.
#![allow(dead_code)]

use std::io::{BufRead, BufReader};
use std::process::{Child, Command, Stdio};
use std::time::Duration;

use serde_json::Value;

/// The budget of a test server that does not test the budget: an hour.
pub const UNTIMED_BUDGET_MS: &str = "3600000";

/// A running `ikarus serve`, killed on drop.
pub struct Server {
    pub child: Child,
    /// `http://127.0.0.1:PORT`
    pub base: String,
    /// `127.0.0.1:PORT`
    pub addr: String,
    /// An agent that returns 4xx and 5xx answers instead of failing on them.
    pub agent: ureq::Agent,
}

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

impl Server {
    /// `ikarus serve --port 0 ARGS…`; `timeout` bounds each request of the agent (where a hang
    /// is the bug).
    ///
    /// Unless ARGS set `--request-budget-ms`, the server's budget is an hour
    /// ([`UNTIMED_BUDGET_MS`]): a test checks what the server answers, never how fast this
    /// machine is (the test-profile binary on a busy 2-core machine once took 8 s for a GIF
    /// that the default 10 s budget then refused). Tests of the budget itself set a small one
    /// and ask for work that cannot finish inside it on any machine.
    pub fn start(args: &[&str], timeout: Option<Duration>) -> Self {
        let budget: &[&str] =
            if args.contains(&"--request-budget-ms") { &[] } else { &["--request-budget-ms", UNTIMED_BUDGET_MS] };
        let mut child = Command::new(env!("CARGO_BIN_EXE_ikarus"))
            .args(["serve", "--port", "0"])
            .args(budget)
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
        let addr = base.strip_prefix("http://").expect("http address").to_owned();
        let config = ureq::Agent::config_builder().http_status_as_error(false).timeout_global(timeout).build();
        Self { child, base, addr, agent: config.into() }
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

/// `ikarus serve --port 0 ARGS…` on loopback, without a request timeout.
pub fn start(args: &[&str]) -> Server {
    let server = Server::start(args, None);
    assert!(server.base.starts_with("http://127.0.0.1:"), "{}", server.base);
    server
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

    pub fn assert_healthy(&self) {
        let a = self.get("/api/health");
        assert_eq!(a.status, 200);
        assert_eq!(a.json()["status"], "ok");
    }
}
