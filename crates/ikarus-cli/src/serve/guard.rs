//! Checks made on every request before its handler runs, and the shape of axum's own 405.
//!
//! - **Host** (against DNS rebinding: a web page on another site whose name is made to resolve
//!   to 127.0.0.1 would otherwise reach the server from the victim's browser): while the server
//!   listens on a loopback address, only loopback host names are accepted (`localhost`,
//!   `127.x.y.z`, `[::1]`, with or without a port) plus the names given with `--allow-host`;
//!   anything else is answered 403. A request without a Host header (HTTP/1.0) cannot come
//!   from a rebinding page and is accepted. Listening beyond loopback accepts any host.
//! - **Content-Length** over `--max-body-bytes` is answered 413 before the body is used, so a
//!   client sending `Expect: 100-continue` gets no "100 Continue" and sends nothing; a client
//!   that sends at once gets its 413 after its body (up to 1 MiB, 2 s) is read and dropped, not
//!   a reset connection.
//! - **405** answers (a known path with another method) get the API's `{"error": …}` body,
//!   keeping axum's `Allow` header.

use std::net::IpAddr;
use std::sync::Arc;

use axum::body::Body;
use axum::extract::{Request, State};
use axum::http::{HeaderMap, StatusCode, header};
use axum::middleware::Next;
use axum::response::{IntoResponse, Response};

use super::errors::{ApiError, Refusal};

/// The largest oversized body read and dropped before its 413 (see [`check`]).
const DRAIN_BYTES: u64 = 1 << 20;

/// How long reading such a body may take.
const DRAIN_TIME: std::time::Duration = std::time::Duration::from_secs(2);

/// What the checks need to know.
#[derive(Debug, Clone)]
pub struct Guard {
    /// Accept any Host (the server listens beyond loopback).
    pub any_host: bool,
    /// Host names accepted besides the loopback ones (`--allow-host`), lowercase.
    pub allowed_hosts: Vec<String>,
    pub max_body_bytes: usize,
    /// The cap of a file's text (`/api/arm/parse`, `/api/rig/parse`): `--max-file-bytes`.
    pub max_file_bytes: usize,
}

impl Guard {
    /// The body cap of a request to `path` and the flag that sets it.
    pub fn cap_of(&self, path: &str) -> (usize, &'static str) {
        if super::is_file_path(path) {
            (self.max_file_bytes, "--max-file-bytes")
        } else {
            (self.max_body_bytes, "--max-body-bytes")
        }
    }
}

/// The middleware: see the module docs.
pub async fn check(State(guard): State<Arc<Guard>>, req: Request, next: Next) -> Response {
    if let Some(host) = req.headers().get(header::HOST) {
        let host = String::from_utf8_lossy(host.as_bytes()).into_owned();
        if !guard.any_host && !guard.host_allowed(&host) {
            return Refusal(ApiError::new(crate::api::status::FORBIDDEN, format!(
                    "Host: {host:?} is not a loopback name; this server answers only localhost, 127.0.0.1 and [::1] (add names with --allow-host)"
                )))
            .into_response();
        }
    }
    let (cap, flag) = guard.cap_of(req.uri().path());
    if let Some(length) = content_length(req.headers()) {
        if length > cap as u64 {
            // A client that does not wait for "100 Continue" is sending the body already: when
            // it is small, read it and drop it first, so that the 413 reaches the client rather
            // than a reset of a connection closed on its unread bytes (a client that waits gets
            // its 413 at once and sends nothing).
            let expects = req.headers().contains_key(header::EXPECT);
            if !expects && length <= DRAIN_BYTES {
                let drain = axum::body::to_bytes(req.into_body(), DRAIN_BYTES as usize);
                let _ = tokio::time::timeout(DRAIN_TIME, drain).await;
            }
            return Refusal(ApiError::new(
                crate::api::status::PAYLOAD_TOO_LARGE,
                format!("request body: Content-Length {length} is larger than the cap of {cap} bytes ({flag})"),
            ))
            .into_response();
        }
    }
    let (method, path) = (req.method().clone(), req.uri().path().to_owned());
    let response = next.run(req).await;
    if response.status() != StatusCode::METHOD_NOT_ALLOWED {
        return response;
    }
    let (mut parts, _) = response.into_parts();
    // axum adds the `Allow` header outside this layer; the body names the method and path.
    let message = format!("{method} {path}: method not allowed");
    let body = serde_json::json!({ "error": message }).to_string();
    parts.headers.insert(header::CONTENT_TYPE, header::HeaderValue::from_static("application/json"));
    parts.headers.remove(header::CONTENT_LENGTH);
    Response::from_parts(parts, Body::from(body))
}

/// The declared body length, if the header is there and a number.
fn content_length(headers: &HeaderMap) -> Option<u64> {
    headers.get(header::CONTENT_LENGTH)?.to_str().ok()?.trim().parse().ok()
}

impl Guard {
    fn host_allowed(&self, host: &str) -> bool {
        let Some(name) = host_name(host) else { return false };
        is_loopback_name(name) || self.allowed_hosts.iter().any(|a| a.eq_ignore_ascii_case(name))
    }
}

/// The name of a Host header value without its port: `localhost:7878` → `localhost`,
/// `[::1]:7878` → `::1`; `None` if malformed.
fn host_name(host: &str) -> Option<&str> {
    let host = host.trim();
    let port_ok = |p: &str| !p.is_empty() && p.bytes().all(|b| b.is_ascii_digit());
    let name = if let Some(rest) = host.strip_prefix('[') {
        let (inside, tail) = rest.split_once(']')?;
        match tail.strip_prefix(':') {
            None if tail.is_empty() => inside,
            Some(port) if port_ok(port) => inside,
            _ => return None,
        }
    } else {
        match host.split_once(':') {
            None => host,
            Some((name, port)) if port_ok(port) => name,
            Some(_) => return None,
        }
    };
    Some(name.strip_suffix('.').unwrap_or(name))
}

/// `localhost`, or an IP address on the loopback interface (IPv4-mapped ones included).
pub fn is_loopback_name(name: &str) -> bool {
    name.eq_ignore_ascii_case("localhost") || name.parse::<IpAddr>().is_ok_and(|ip| ip.to_canonical().is_loopback())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn loopback_hosts_with_or_without_port_are_accepted() {
        let guard = Guard {
            any_host: false,
            allowed_hosts: vec!["ikarus.test".to_owned()],
            max_body_bytes: 1,
            max_file_bytes: 1,
        };
        for ok in [
            "localhost",
            "LOCALHOST:7878",
            "localhost.",
            "127.0.0.1",
            "127.0.0.1:80",
            "127.8.9.10:1",
            "[::1]",
            "[::1]:7878",
            "[::ffff:127.0.0.1]:9",
            "ikarus.test:7878",
        ] {
            assert!(guard.host_allowed(ok), "{ok}");
        }
        for bad in [
            "evil.example",
            "evil.example:7878",
            "localhost.evil.example",
            "10.0.0.1",
            "[::2]:7878",
            "::1",
            "localhost:",
            "localhost:x",
            "[::1]x",
            "",
        ] {
            assert!(!guard.host_allowed(bad), "{bad}");
        }
    }
}
