//! The accept loop: HTTP/1.1 connections served by hyper, with the limits `axum::serve` lacks.
//!
//! - At most `--max-connections` open connections; one beyond that gets a short 503 and is
//!   closed at once (so idle sockets cannot use up the process's file descriptors).
//! - A connection must send a request's headers within `--header-timeout-ms` of being ready for
//!   them: this bounds half-sent headers and idle keep-alive connections alike (hyper starts
//!   the timer whenever it waits for a request head).
//! - Request bodies must arrive within `--body-timeout-ms` ([`super::errors::JsonBody`]).
//! - On stop, the listener closes, every connection is asked to finish its answer and close,
//!   and whatever is still open after [`DRAIN`] is dropped.

use std::sync::Arc;
use std::time::Duration;

use axum::Router;
use hyper::server::conn::http1;
use hyper_util::rt::{TokioIo, TokioTimer};
use hyper_util::service::TowerToHyperService;
use tokio::net::TcpListener;
use tokio::sync::{Semaphore, watch};
use tokio::task::JoinSet;

/// How long connections may take to finish after the server is told to stop.
const DRAIN: Duration = Duration::from_millis(600);

/// The answer to a connection over the cap.
const TOO_MANY: &[u8] = b"HTTP/1.1 503 Service Unavailable\r\ncontent-type: application/json\r\ncontent-length: 71\r\nconnection: close\r\n\r\n{\"error\": \"server busy: too many open connections (--max-connections)\"}";

/// The connection limits.
#[derive(Debug, Clone, Copy)]
pub struct ConnConfig {
    pub max_connections: usize,
    pub header_timeout: Duration,
}

/// Serves `router` on `listener` until `stop` becomes `true`.
pub async fn serve(listener: TcpListener, router: Router, config: ConnConfig, mut stop: watch::Receiver<bool>) {
    let slots = Arc::new(Semaphore::new(config.max_connections.min(Semaphore::MAX_PERMITS)));
    let mut connections = JoinSet::new();
    loop {
        let accepted = tokio::select! {
            accepted = listener.accept() => accepted,
            _ = stop.wait_for(|&s| s) => break,
        };
        while connections.try_join_next().is_some() {}
        let stream = match accepted {
            Ok((stream, _)) => stream,
            Err(e) => {
                // Out of file descriptors and the like: wait a little rather than spin.
                eprintln!("ikarus serve: cannot accept a connection: {e}");
                tokio::time::sleep(Duration::from_millis(50)).await;
                continue;
            }
        };
        let Ok(slot) = Arc::clone(&slots).try_acquire_owned() else {
            // One non-blocking write into the socket's empty send buffer, then close.
            let _ = stream.try_write(TOO_MANY);
            continue;
        };
        let _ = stream.set_nodelay(true);
        let service = TowerToHyperService::new(router.clone());
        let mut stop = stop.clone();
        let header_timeout = config.header_timeout;
        connections.spawn(async move {
            let _slot = slot;
            let mut builder = http1::Builder::new();
            builder.timer(TokioTimer::new()).header_read_timeout(header_timeout).keep_alive(true);
            let connection = builder.serve_connection(TokioIo::new(stream), service);
            tokio::pin!(connection);
            tokio::select! {
                _ = connection.as_mut() => {}
                () = async { let _ = stop.wait_for(|&s| s).await; } => {
                    connection.as_mut().graceful_shutdown();
                    let _ = connection.await;
                }
            }
        });
    }
    drop(listener);
    let drained = tokio::time::timeout(DRAIN, async { while connections.join_next().await.is_some() {} }).await;
    if drained.is_err() {
        connections.abort_all();
    }
}
