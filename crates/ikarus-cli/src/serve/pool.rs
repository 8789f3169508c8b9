//! The bounded pool that runs the computations (solve, animate, track, workspace, reach,
//! render) off the async runtime's threads, each under a time budget, in two lanes so that
//! quick requests never wait behind long ones.
//!
//! - Every computation is *quick* or *long* by the worst case its request allows
//!   ([`super::cost`]), before it runs. Long ones run on at most `--long-workers` workers (by
//!   default half the workers, at least 1) and wait in their own queue; the other workers are
//!   kept for quick ones (at least one, even with `--workers 1`), which may also take a long
//!   worker left free. So a quick request finds a worker no matter how many long ones run or
//!   wait, and waits only behind other quick ones.
//! - Each lane admits its workers plus at most `--max-queued` waiting computations; a request
//!   beyond that is answered 503 ("server busy") at once, so tokio's blocking pool never fills
//!   and the runtime's own threads stay free for `/api/health` and the page. Long requests
//!   filling their queue do not make quick ones busy.
//! - Every request has a time budget (`--request-budget-ms`) covering its wait in the queue and
//!   its work. At the deadline its [`Interrupt`] is set, the computation stops at its next check
//!   (every solve iteration, every workspace sample), and the answer is 503 naming the budget.
//! - A quick computation still running after [`LONG_AFTER`] (the estimate was wrong) moves to a
//!   long worker, giving its quick one back; when none is free it is stopped and answered 503
//!   ("server busy") at once, rather than holding a quick worker.
//! - When the handler's future is dropped (hyper drops it when the client closes the
//!   connection) a drop guard sets the interrupt too, so nobody's work runs on for nobody.
//! - When the server stops (Ctrl-C), every request's interrupt is set and it answers 503.

use std::sync::Arc;
use std::time::Duration;

use ikarus::Interrupt;
use tokio::sync::{OwnedSemaphorePermit, Semaphore, watch};
use tokio::time::Instant;

use super::errors::ApiError;

/// How long a quick computation may run before it must move to a long worker.
pub const LONG_AFTER: Duration = Duration::from_millis(500);

/// The lane of a computation, chosen by [`super::cost::lane`] before it runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Lane {
    /// Quick at worst: runs on a quick worker, or a long one left free.
    Quick,
    /// Possibly long: runs only on a long worker.
    Long,
}

/// How many computations run and wait, and for how long.
#[derive(Debug, Clone, Copy)]
pub struct PoolConfig {
    pub workers: usize,
    /// Workers that run long computations (the others are kept for quick ones).
    pub long_workers: usize,
    pub max_queued: usize,
    pub budget: Duration,
}

/// The workers and admissions of the two lanes.
#[derive(Debug, Clone)]
struct Lanes {
    /// Workers kept for quick computations.
    quick: Arc<Semaphore>,
    /// Workers for long computations (and quick ones, when free).
    long: Arc<Semaphore>,
    /// Quick computations admitted, running or waiting.
    quick_admitted: Arc<Semaphore>,
    /// Long computations admitted, running or waiting.
    long_admitted: Arc<Semaphore>,
}

/// The pool; cheap to clone (the clones share the permits).
#[derive(Debug, Clone)]
pub struct Pool {
    config: PoolConfig,
    lanes: Lanes,
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

/// The worker a computation holds, shared by the handler (which may swap a quick worker for a
/// long one) and the computation (which gives it back when it really ends).
type Held = Arc<std::sync::Mutex<Option<OwnedSemaphorePermit>>>;

fn semaphore(permits: usize) -> Arc<Semaphore> {
    Arc::new(Semaphore::new(permits.min(Semaphore::MAX_PERMITS)))
}

impl Pool {
    pub fn new(config: PoolConfig, stopping: watch::Receiver<bool>) -> Self {
        let long = config.long_workers.max(1);
        let quick = config.workers.saturating_sub(long).max(1);
        let lanes = Lanes {
            quick: semaphore(quick),
            long: semaphore(long),
            // A quick computation may run on any worker.
            quick_admitted: semaphore(quick.saturating_add(long).saturating_add(config.max_queued)),
            long_admitted: semaphore(long.saturating_add(config.max_queued)),
        };
        Self { config, lanes, stopping }
    }

    /// Runs `work` on a worker of its `lane` under the request's budget; `work` gets the
    /// request's interrupt to pass to the library (solve options, workspace options). A panic
    /// in `work` becomes a 500 and the server keeps serving.
    pub async fn run<T: Send + 'static>(
        &self,
        lane: Lane,
        work: impl FnOnce(&Interrupt) -> Result<T, ApiError> + Send + 'static,
    ) -> Result<T, ApiError> {
        self.run_by(self.deadline(), lane, work).await
    }

    /// The deadline of a request that starts now: its budget from now.
    pub fn deadline(&self) -> Instant {
        Instant::now() + self.config.budget
    }

    /// [`Pool::run`] under a budget that ends at `deadline`: the second step of a request
    /// (its work moved to the long lane once read) keeps the first step's deadline.
    pub async fn run_by<T: Send + 'static>(
        &self,
        deadline: Instant,
        lane: Lane,
        work: impl FnOnce(&Interrupt) -> Result<T, ApiError> + Send + 'static,
    ) -> Result<T, ApiError> {
        let token = Interrupt::new();
        let _guard = InterruptOnDrop(token.clone());
        let mut stopping = self.stopping.clone();
        if *stopping.borrow() {
            return Err(stopping_error());
        }
        let admitted = match lane {
            Lane::Quick => &self.lanes.quick_admitted,
            Lane::Long => &self.lanes.long_admitted,
        };
        let Ok(_admitted) = Arc::clone(admitted).try_acquire_owned() else {
            return Err(self.busy(lane));
        };
        let (permit, mut on_long) = tokio::select! {
            permit = self.worker(lane) => permit.map_err(|_| stopping_error())?,
            () = tokio::time::sleep_until(deadline) => return Err(self.over_budget()),
            _ = stopping.wait_for(|&s| s) => return Err(stopping_error()),
        };
        let held: Held = Arc::new(std::sync::Mutex::new(Some(permit)));
        let worker_held = Arc::clone(&held);
        let worker_token = token.clone();
        // The worker is held until the computation really ends, even when the answer (503)
        // has already gone: the interrupt makes that soon.
        let mut handle = tokio::task::spawn_blocking(move || {
            let _worker = worker_held;
            work(&worker_token)
        });
        let long_from = (Instant::now() + LONG_AFTER).min(deadline);
        let result = loop {
            tokio::select! {
                joined = &mut handle => break joined,
                () = tokio::time::sleep_until(deadline) => {
                    token.interrupt();
                    return Err(self.over_budget());
                }
                () = tokio::time::sleep_until(long_from), if !on_long => {
                    // A quick computation that runs long: onto a long worker, or stopped.
                    let Ok(permit) = Arc::clone(&self.lanes.long).try_acquire_owned() else {
                        token.interrupt();
                        return Err(self.too_many_long());
                    };
                    on_long = true;
                    // The quick worker is given back here.
                    *held.lock().unwrap_or_else(std::sync::PoisonError::into_inner) = Some(permit);
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

    /// A worker of `lane`, and whether it is a long one: a quick computation takes whichever
    /// is free first.
    async fn worker(&self, lane: Lane) -> Result<(OwnedSemaphorePermit, bool), tokio::sync::AcquireError> {
        let long = Arc::clone(&self.lanes.long).acquire_owned();
        match lane {
            Lane::Long => Ok((long.await?, true)),
            // The quick worker first, keeping the long ones for long work.
            Lane::Quick => tokio::select! {
                biased;
                permit = Arc::clone(&self.lanes.quick).acquire_owned() => Ok((permit?, false)),
                permit = long => Ok((permit?, true)),
            },
        }
    }

    fn busy(&self, lane: Lane) -> ApiError {
        let (what, running, flag) = match lane {
            Lane::Quick => ("computations", self.config.workers, "--workers"),
            Lane::Long => ("long computations", self.config.long_workers, "--long-workers"),
        };
        ApiError::new(
            crate::api::status::SERVICE_UNAVAILABLE,
            format!(
                "server busy: {running} {what} running and {} waiting ({flag}, --max-queued); try again later",
                self.config.max_queued
            ),
        )
    }

    fn too_many_long(&self) -> ApiError {
        ApiError::new(
            crate::api::status::SERVICE_UNAVAILABLE,
            format!(
                "server busy: {} long computations already running (--long-workers); this one was stopped after {} ms, try again later or ask for less work",
                self.config.long_workers,
                LONG_AFTER.as_millis()
            ),
        )
    }

    fn over_budget(&self) -> ApiError {
        ApiError::new(
            crate::api::status::SERVICE_UNAVAILABLE,
            format!(
                "request stopped: it took longer than the budget of {} ms (--request-budget-ms); ask for less work (fewer iterations, restarts, samples, frames)",
                self.config.budget.as_millis()
            ),
        )
    }
}

fn stopping_error() -> ApiError {
    ApiError::new(crate::api::status::SERVICE_UNAVAILABLE, "server stopping".to_owned())
}

#[cfg(test)]
mod tests {
    use super::*;
    use Lane::{Long, Quick};

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

    /// Runs, in the background, a computation of `lane` that ends only when interrupted.
    fn endless(pool: &Pool, lane: Lane) -> tokio::task::JoinHandle<Result<(), ApiError>> {
        let pool = pool.clone();
        tokio::spawn(async move {
            pool.run(lane, |token| {
                wait_interrupted(token);
                Ok(())
            })
            .await
        })
    }

    /// Waits until `semaphore` has no permit left.
    async fn until_taken(semaphore: &Semaphore) {
        while semaphore.available_permits() > 0 {
            tokio::time::sleep(Duration::from_millis(5)).await;
        }
    }

    #[tokio::test]
    async fn a_panic_in_a_handler_becomes_a_500_with_a_generic_body() {
        let (pool, _tx) = pool(2, 2, 10_000);
        for lane in [Quick, Long] {
            let e = pool.run::<()>(lane, |_| panic!("boom at /home/someone/src/x.rs:1")).await.unwrap_err();
            assert_eq!(e.status, crate::api::status::INTERNAL_SERVER_ERROR);
            assert!(!e.message.contains("boom") && !e.message.contains("/home"), "{}", e.message);
            // The pool still works afterwards.
            assert_eq!(pool.run(lane, |_| Ok(7)).await.unwrap(), 7);
        }
    }

    #[tokio::test]
    async fn the_deadline_interrupts_the_work_and_answers_503() {
        let (pool, _tx) = pool(1, 0, 50);
        let e = pool
            .run::<()>(Long, |token| {
                wait_interrupted(token);
                Ok(())
            })
            .await
            .unwrap_err();
        assert_eq!(e.status, crate::api::status::SERVICE_UNAVAILABLE);
        assert!(e.message.contains("budget of 50 ms (--request-budget-ms)"), "{}", e.message);
    }

    /// Fills `lane`'s admissions with two computations that end only when interrupted, and
    /// checks that one more is answered busy, naming `flag`.
    async fn two_fill_the_lane(
        pool: &Pool,
        lane: Lane,
        flag: &str,
    ) -> [tokio::task::JoinHandle<Result<(), ApiError>>; 2] {
        let requests = [endless(pool, lane), endless(pool, lane)];
        until_taken(match lane {
            Quick => &pool.lanes.quick_admitted,
            Long => &pool.lanes.long_admitted,
        })
        .await;
        let e = pool.run(lane, |_| Ok(())).await.unwrap_err();
        assert_eq!(e.status, crate::api::status::SERVICE_UNAVAILABLE);
        assert!(e.message.starts_with("server busy") && e.message.contains(flag), "{}", e.message);
        requests
    }

    #[tokio::test]
    async fn beyond_the_long_queue_long_ones_are_busy_and_quick_ones_still_run() {
        // One long worker and one waiting.
        let (pool, tx) = pool(1, 1, 60_000);
        let requests = two_fill_the_lane(&pool, Long, "--long-workers").await;
        // The quick lane has a worker of its own, even with --workers 1.
        assert_eq!(pool.run(Quick, |_| Ok(5)).await.unwrap(), 5);
        // Stopping the server interrupts the running one and the waiting one.
        tx.send(true).unwrap();
        for request in requests {
            assert_eq!(request.await.unwrap().unwrap_err().message, "server stopping");
        }
    }

    #[tokio::test]
    async fn beyond_the_quick_queue_quick_ones_are_busy() {
        // One quick worker, one long one (free, so a quick computation takes it too), no queue.
        let (pool, _tx) = pool(2, 0, 60_000);
        for request in two_fill_the_lane(&pool, Quick, "--workers").await {
            request.abort();
        }
    }

    #[tokio::test]
    async fn a_quick_one_that_runs_long_moves_to_a_long_worker_or_is_stopped() {
        let (pool, _tx) = pool(2, 4, 60_000);
        // The first takes the quick worker and, after LONG_AFTER, moves to the long one.
        let first = endless(&pool, Quick);
        until_taken(&pool.lanes.long).await;
        assert_eq!(pool.lanes.quick.available_permits(), 1, "the quick worker was given back");
        // The second has no long worker to move to: stopped once it runs long.
        let e = pool
            .run::<()>(Quick, |token| {
                wait_interrupted(token);
                Ok(())
            })
            .await
            .unwrap_err();
        assert_eq!(e.status, crate::api::status::SERVICE_UNAVAILABLE);
        assert!(e.message.contains("--long-workers"), "{}", e.message);
        // Quick work still runs beside the long one.
        assert_eq!(pool.run(Quick, |_| Ok(5)).await.unwrap(), 5);
        first.abort();
    }

    #[tokio::test]
    async fn dropping_the_request_interrupts_its_work() {
        let (pool, _tx) = pool(1, 0, 60_000);
        let (seen_tx, seen_rx) = std::sync::mpsc::channel();
        let request = pool.run::<()>(Long, move |token| {
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
        assert_eq!(pool.run(Long, |_| Ok(3)).await.unwrap(), 3);
    }
}
