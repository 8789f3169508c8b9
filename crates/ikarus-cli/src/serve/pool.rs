//! The bounded pool that runs the heavy requests (solve, animate, track, workspace, reach,
//! render) off the async runtime's threads, each under a time budget.
//!
//! - At most `--workers` computations run at once, each on a thread of tokio's blocking pool;
//!   at most `--max-queued` more wait for a worker. A request beyond that is answered 503
//!   ("server busy") at once, so tokio's blocking pool never fills and the runtime's own
//!   threads stay free for `/api/health` and the page.
//! - Every request has a time budget (`--request-budget-ms`) covering its wait in the queue and
//!   its work. At the deadline its [`Interrupt`] is set, the computation stops at its next check
//!   (every solve iteration, every workspace sample), and the answer is 503 naming the budget.
//! - A computation still running after [`LONG_AFTER`] is *long*: at most `--long-workers` long
//!   ones run at once (by default half the workers), so the other workers stay free for the
//!   page's quick requests. One that would exceed that is stopped and answered 503 ("server
//!   busy") at once, rather than holding a worker until its budget runs out.
//! - When the handler's future is dropped (hyper drops it when the client closes the
//!   connection) a drop guard sets the interrupt too, so nobody's work runs on for nobody.
//! - When the server stops (Ctrl-C), every request's interrupt is set and it answers 503.

use std::sync::Arc;
use std::time::Duration;

use ikarus::Interrupt;
use tokio::sync::{OwnedSemaphorePermit, Semaphore, watch};
use tokio::time::Instant;

use super::errors::ApiError;

/// How long a computation runs before it counts as long.
pub const LONG_AFTER: Duration = Duration::from_millis(500);

/// How many computations run and wait, and for how long.
#[derive(Debug, Clone, Copy)]
pub struct PoolConfig {
    pub workers: usize,
    /// Computations that may run longer than [`LONG_AFTER`] at once.
    pub long_workers: usize,
    pub max_queued: usize,
    pub budget: Duration,
}

/// The pool; cheap to clone (the clones share the permits).
#[derive(Debug, Clone)]
pub struct Pool {
    config: PoolConfig,
    /// One permit per running computation.
    workers: Arc<Semaphore>,
    /// One permit per admitted request, running or waiting: `workers + max_queued`.
    admitted: Arc<Semaphore>,
    /// One permit per long computation.
    long: Arc<Semaphore>,
    /// Becomes `true` when the server stops.
    stopping: watch::Receiver<bool>,
}

/// Sets the interrupt when dropped: the handler's future was dropped (client gone) or ended.
struct InterruptOnDrop(Interrupt);

impl Drop for InterruptOnDrop {
    fn drop(&mut self) {
        self.0.interrupt();
    }
}

impl Pool {
    pub fn new(config: PoolConfig, stopping: watch::Receiver<bool>) -> Self {
        let admitted = config.workers.saturating_add(config.max_queued).min(Semaphore::MAX_PERMITS);
        Self {
            config,
            workers: Arc::new(Semaphore::new(config.workers.min(Semaphore::MAX_PERMITS))),
            admitted: Arc::new(Semaphore::new(admitted)),
            long: Arc::new(Semaphore::new(config.long_workers.clamp(1, Semaphore::MAX_PERMITS))),
            stopping,
        }
    }

    /// Runs `work` on a worker under the request's budget; `work` gets the request's interrupt
    /// to pass to the library (solve options, workspace options). A panic in `work` becomes a
    /// 500 and the server keeps serving.
    pub async fn run<T: Send + 'static>(
        &self,
        work: impl FnOnce(&Interrupt) -> Result<T, ApiError> + Send + 'static,
    ) -> Result<T, ApiError> {
        let deadline = Instant::now() + self.config.budget;
        let token = Interrupt::new();
        let _guard = InterruptOnDrop(token.clone());
        let mut stopping = self.stopping.clone();
        if *stopping.borrow() {
            return Err(stopping_error());
        }
        let Ok(_admitted) = Arc::clone(&self.admitted).try_acquire_owned() else {
            return Err(ApiError {
                status: crate::api::status::SERVICE_UNAVAILABLE,
                message: format!(
                    "server busy: {} computations running and {} waiting (--workers, --max-queued); try again later",
                    self.config.workers, self.config.max_queued
                ),
            });
        };
        let permit = tokio::select! {
            permit = Arc::clone(&self.workers).acquire_owned() => {
                permit.map_err(|_| stopping_error())?
            }
            () = tokio::time::sleep_until(deadline) => return Err(self.over_budget()),
            _ = stopping.wait_for(|&s| s) => return Err(stopping_error()),
        };
        let worker_token = token.clone();
        // The long permit, once taken, is held here and by the computation: it is given back
        // when both are done.
        let long: Arc<std::sync::Mutex<Option<OwnedSemaphorePermit>>> = Arc::default();
        let long_held = Arc::clone(&long);
        // The worker keeps its permits until the computation really ends, even when the answer
        // (503) has already gone: the interrupt makes that soon.
        let mut handle = tokio::task::spawn_blocking(move || {
            let _permits = (permit, long_held);
            work(&worker_token)
        });
        let long_from = (Instant::now() + LONG_AFTER).min(deadline);
        let mut is_long = false;
        let result = loop {
            tokio::select! {
                joined = &mut handle => break joined,
                () = tokio::time::sleep_until(deadline) => {
                    token.interrupt();
                    return Err(self.over_budget());
                }
                () = tokio::time::sleep_until(long_from), if !is_long => {
                    match Arc::clone(&self.long).try_acquire_owned() {
                        Ok(permit) => {
                            is_long = true;
                            *long.lock().unwrap_or_else(std::sync::PoisonError::into_inner) = Some(permit);
                        }
                        Err(_) => {
                            token.interrupt();
                            return Err(self.too_many_long());
                        }
                    }
                }
                _ = stopping.wait_for(|&s| s) => {
                    token.interrupt();
                    return Err(stopping_error());
                }
            }
        };
        if token.is_interrupted() {
            // The deadline passed as the work ended: its result may be cut short.
            return Err(if *stopping.borrow() { stopping_error() } else { self.over_budget() });
        }
        match result {
            Ok(result) => result,
            Err(e) if e.is_panic() => {
                let payload = e.into_panic();
                let what = payload
                    .downcast_ref::<&str>()
                    .map(|s| (*s).to_owned())
                    .or_else(|| payload.downcast_ref::<String>().cloned())
                    .unwrap_or_else(|| "a request handler panicked".to_owned());
                Err(ApiError::internal(what))
            }
            Err(e) => Err(ApiError::internal(e.to_string())),
        }
    }

    fn too_many_long(&self) -> ApiError {
        ApiError {
            status: crate::api::status::SERVICE_UNAVAILABLE,
            message: format!(
                "server busy: {} long computations already running (--long-workers); this one was stopped after {} ms, try again later or ask for less work",
                self.config.long_workers,
                LONG_AFTER.as_millis()
            ),
        }
    }

    fn over_budget(&self) -> ApiError {
        ApiError {
            status: crate::api::status::SERVICE_UNAVAILABLE,
            message: format!(
                "request stopped: it took longer than the budget of {} ms (--request-budget-ms); ask for less work (fewer iterations, restarts, samples, frames)",
                self.config.budget.as_millis()
            ),
        }
    }
}

fn stopping_error() -> ApiError {
    ApiError { status: crate::api::status::SERVICE_UNAVAILABLE, message: "server stopping".to_owned() }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pool(workers: usize, max_queued: usize, budget_ms: u64) -> (Pool, watch::Sender<bool>) {
        let (tx, rx) = watch::channel(false);
        let config = PoolConfig { workers, long_workers: 1, max_queued, budget: Duration::from_millis(budget_ms) };
        (Pool::new(config, rx), tx)
    }

    /// Waits (a bounded number of times) until `token` is set.
    fn wait_interrupted(token: &Interrupt) {
        for _ in 0..6000 {
            if token.is_interrupted() {
                return;
            }
            std::thread::sleep(Duration::from_millis(5));
        }
        panic!("never interrupted");
    }

    #[tokio::test]
    async fn a_panic_in_a_handler_becomes_a_500_with_a_generic_body() {
        let (pool, _tx) = pool(2, 2, 10_000);
        let e = pool.run::<()>(|_| panic!("boom at /home/someone/src/x.rs:1")).await.unwrap_err();
        assert_eq!(e.status, crate::api::status::INTERNAL_SERVER_ERROR);
        assert!(!e.message.contains("boom") && !e.message.contains("/home"), "{}", e.message);
        // The pool still works afterwards.
        assert_eq!(pool.run(|_| Ok(7)).await.unwrap(), 7);
    }

    #[tokio::test]
    async fn the_deadline_interrupts_the_work_and_answers_503() {
        let (pool, _tx) = pool(1, 0, 50);
        let e = pool
            .run::<()>(|token| {
                wait_interrupted(token);
                Ok(())
            })
            .await
            .unwrap_err();
        assert_eq!(e.status, crate::api::status::SERVICE_UNAVAILABLE);
        assert!(e.message.contains("budget of 50 ms (--request-budget-ms)"), "{}", e.message);
    }

    #[tokio::test]
    async fn beyond_the_queue_the_answer_is_busy_at_once() {
        let (pool, tx) = pool(1, 0, 60_000);
        let busy = pool.clone();
        let running = tokio::spawn(async move {
            busy.run::<()>(|token| {
                wait_interrupted(token);
                Ok(())
            })
            .await
        });
        // Until the first request holds the only slot.
        while pool.admitted.available_permits() > 0 {
            tokio::time::sleep(Duration::from_millis(5)).await;
        }
        let e = pool.run(|_| Ok(())).await.unwrap_err();
        assert_eq!(e.status, crate::api::status::SERVICE_UNAVAILABLE);
        assert!(e.message.starts_with("server busy"), "{}", e.message);
        // Stopping the server interrupts the running one.
        tx.send(true).unwrap();
        let e = running.await.unwrap().unwrap_err();
        assert_eq!(e.message, "server stopping");
    }

    #[tokio::test]
    async fn a_second_long_computation_is_stopped_busy() {
        let (pool, _tx) = pool(2, 0, 60_000);
        let first = pool.clone();
        let long = tokio::spawn(async move {
            first
                .run::<()>(|token| {
                    wait_interrupted(token);
                    Ok(())
                })
                .await
        });
        while pool.long.available_permits() > 0 {
            tokio::time::sleep(Duration::from_millis(5)).await;
        }
        let e = pool
            .run::<()>(|token| {
                wait_interrupted(token);
                Ok(())
            })
            .await
            .unwrap_err();
        assert_eq!(e.status, crate::api::status::SERVICE_UNAVAILABLE);
        assert!(e.message.contains("--long-workers"), "{}", e.message);
        // Quick work still runs beside the long one.
        assert_eq!(pool.run(|_| Ok(5)).await.unwrap(), 5);
        long.abort();
    }

    #[tokio::test]
    async fn dropping_the_request_interrupts_its_work() {
        let (pool, _tx) = pool(1, 0, 60_000);
        let (seen_tx, seen_rx) = std::sync::mpsc::channel();
        let request = pool.run::<()>(move |token| {
            wait_interrupted(token);
            seen_tx.send(()).unwrap();
            Ok(())
        });
        // Poll the request until its work runs, then drop it (as hyper does when the client
        // goes away).
        let _ = tokio::time::timeout(Duration::from_millis(100), request).await;
        tokio::task::spawn_blocking(move || seen_rx.recv_timeout(Duration::from_secs(30)))
            .await
            .unwrap()
            .expect("the work saw the interrupt");
        // And the worker is free again.
        assert_eq!(pool.run(|_| Ok(3)).await.unwrap(), 3);
    }
}
