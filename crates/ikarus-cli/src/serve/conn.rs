//! The accept loop: HTTP/1.1 connections served by hyper, with the limits `axum::serve` lacks.
//!
//! - At most `--max-connections` open connections. When all are taken, the one that has waited
//!   longest for a request (nothing sent yet, headers half-sent, or idle between keep-alive
//!   requests) is closed to make room, so idle sockets cannot lock `/api/health` and the page
//!   out; only when every connection is inside a request (from its head to its answer) does a
//!   new one get a short 503 and is closed (so sockets cannot use up the process's file
//!   descriptors).
//! - A connection must send a request's headers within `--header-timeout-ms` of being ready for
//!   them: this bounds half-sent headers and idle keep-alive connections alike (hyper starts
//!   the timer whenever it waits for a request head).
//! - Request bodies must arrive within `--body-timeout-ms` ([`super::errors::JsonBody`]).
//! - On stop, the listener closes, every connection is asked to finish its answer and close
//!   (the computations answer 503 at once), and whatever is still open after [`DRAIN`] (a client
//!   still sending its body) is dropped.

use std::collections::BTreeMap;
use std::future::Future;
use std::pin::Pin;
use std::sync::{Arc, Mutex, PoisonError};
use std::time::Duration;

use axum::Router;
use axum::extract::Request;
use hyper::body::Incoming;
use hyper::server::conn::http1;
use hyper_util::rt::{TokioIo, TokioTimer};
use hyper_util::service::TowerToHyperService;
use tokio::net::TcpListener;
use tokio::sync::{Notify, OwnedSemaphorePermit, Semaphore, watch};
use tokio::task::JoinSet;

/// How long connections may take to finish after the server is told to stop.
const DRAIN: Duration = Duration::from_millis(250);

/// How long the accept loop waits for a closed idle connection's slot.
const ROOM_TIME: Duration = Duration::from_secs(1);

/// The answer to a connection over the cap.
const TOO_MANY: &[u8] = b"HTTP/1.1 503 Service Unavailable\r\ncontent-type: application/json\r\ncontent-length: 71\r\nconnection: close\r\n\r\n{\"error\": \"server busy: too many open connections (--max-connections)\"}";

/// The connection limits.
#[derive(Debug, Clone, Copy)]
pub struct ConnConfig {
    pub max_connections: usize,
    pub header_timeout: Duration,
}

/// The connections waiting for a request, by the order they began to wait, each with what
/// closes it.
#[derive(Debug, Default)]
struct Waiting {
    next: u64,
    queue: BTreeMap<u64, Arc<Notify>>,
}

/// [`Waiting`], shared by the accept loop and the connections.
#[derive(Debug, Clone, Default)]
struct Registry(Arc<Mutex<Waiting>>);

impl Registry {
    fn lock(&self) -> std::sync::MutexGuard<'_, Waiting> {
        self.0.lock().unwrap_or_else(PoisonError::into_inner)
    }

    /// Closes the connection that has waited longest for a request; `false` if none waits.
    fn close_oldest(&self) -> bool {
        let Some((_, close)) = self.lock().queue.pop_first() else { return false };
        close.notify_one();
        true
    }
}

/// One connection's place: waiting for a request (with its key in the registry), or inside one.
#[derive(Debug)]
struct Tracker {
    registry: Registry,
    close: Arc<Notify>,
    key: Mutex<Option<u64>>,
}

impl Tracker {
    /// A new connection, waiting for its first request.
    fn new(registry: Registry) -> Arc<Self> {
        let tracker = Arc::new(Self { registry, close: Arc::default(), key: Mutex::new(None) });
        tracker.waiting();
        tracker
    }

    /// The connection waits for a request, last in line to be closed.
    fn waiting(&self) {
        let key = {
            let mut waiting = self.registry.lock();
            waiting.next += 1;
            let key = waiting.next;
            waiting.queue.insert(key, Arc::clone(&self.close));
            key
        };
        if let Some(old) = self.key.lock().unwrap_or_else(PoisonError::into_inner).replace(key) {
            self.registry.lock().queue.remove(&old);
        }
    }

    /// The connection is inside a request: not to be closed for room.
    fn busy(&self) {
        if let Some(key) = self.key.lock().unwrap_or_else(PoisonError::into_inner).take() {
            self.registry.lock().queue.remove(&key);
        }
    }
}

impl Drop for Tracker {
    fn drop(&mut self) {
        self.busy();
    }
}

/// The router as hyper's service, marking its connection busy from a request's head (all of
/// it received) to its answer.
#[derive(Debug, Clone)]
struct Tracked {
    inner: TowerToHyperService<Router>,
    tracker: Arc<Tracker>,
}

type Inner = TowerToHyperService<Router>;
type Answer = Result<
    <Inner as hyper::service::Service<Request<Incoming>>>::Response,
    <Inner as hyper::service::Service<Request<Incoming>>>::Error,
>;

impl hyper::service::Service<Request<Incoming>> for Tracked {
    type Response = <Inner as hyper::service::Service<Request<Incoming>>>::Response;
    type Error = <Inner as hyper::service::Service<Request<Incoming>>>::Error;
    type Future = Pin<Box<dyn Future<Output = Answer> + Send>>;

    fn call(&self, req: Request<Incoming>) -> Self::Future {
        self.tracker.busy();
        let answer = self.inner.call(req);
        let tracker = Arc::clone(&self.tracker);
        Box::pin(async move {
            let answer = answer.await;
            tracker.waiting();
            answer
        })
    }
}

/// A slot for a new connection when all are taken: the one waiting longest for a request is
/// closed and its slot taken; `None` if every connection is inside a request.
async fn make_room(registry: &Registry, slots: &Arc<Semaphore>) -> Option<OwnedSemaphorePermit> {
    if !registry.close_oldest() {
        return None;
    }
    tokio::time::timeout(ROOM_TIME, Arc::clone(slots).acquire_owned()).await.ok()?.ok()
}

/// Serves `router` on `listener` until `stop` becomes `true`.
pub async fn serve(listener: TcpListener, router: Router, config: ConnConfig, mut stop: watch::Receiver<bool>) {
    let slots = Arc::new(Semaphore::new(config.max_connections.min(Semaphore::MAX_PERMITS)));
    let registry = Registry::default();
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
        let slot = match Arc::clone(&slots).try_acquire_owned() {
            Ok(slot) => slot,
            Err(_) => match make_room(&registry, &slots).await {
                Some(slot) => slot,
                None => {
                    // One non-blocking write into the socket's empty send buffer, then close.
                    let _ = stream.try_write(TOO_MANY);
                    continue;
                }
            },
        };
        let _ = stream.set_nodelay(true);
        let tracker = Tracker::new(registry.clone());
        let close = Arc::clone(&tracker.close);
        let service = Tracked { inner: TowerToHyperService::new(router.clone()), tracker };
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
                // Closed to make room: dropped at once.
                () = close.notified() => {}
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_connection_waiting_longest_is_closed_first_and_busy_ones_never() {
        let registry = Registry::default();
        let [a, b, c] = [(); 3].map(|()| Tracker::new(registry.clone()));
        // b was first to wait, but is inside a request now; a waits again after a request.
        b.busy();
        a.busy();
        a.waiting();
        assert!(registry.close_oldest());
        // c had waited longest: its close was signalled (a stored permit), a's was not.
        assert!(notified_now(&c.close));
        assert!(!notified_now(&a.close));
        assert!(registry.close_oldest());
        assert!(notified_now(&a.close));
        // Only b is left, inside its request.
        assert!(!registry.close_oldest());
        drop(b);
        assert!(registry.lock().queue.is_empty());
    }

    /// Whether `notify` holds a stored notification (taking it).
    fn notified_now(notify: &Notify) -> bool {
        let notified = notify.notified();
        tokio::pin!(notified);
        notified.as_mut().enable()
    }
}
