//! A running `ikarus serve` for the API tests (`serve.rs`, `serve_limits.rs`, `serve_props.rs`):
//! started on an ephemeral port, its address read from its first line, killed on drop.

use std::io::{BufRead, BufReader};
use std::process::{Child, Command, Stdio};
use std::time::Duration;

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
    pub fn start(args: &[&str], timeout: Option<Duration>) -> Self {
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
        let addr = base.strip_prefix("http://").expect("http address").to_owned();
        let config = ureq::Agent::config_builder().http_status_as_error(false).timeout_global(timeout).build();
        Self { child, base, addr, agent: config.into() }
    }
}
