// The static page's solver thread, kept answering: the module worker (ikarus-worker.js) that runs
// the WebAssembly module, one job at a time, each with a budget, as `ikarus serve` gives each
// request one (its --request-budget-ms, 10 s by default). The page's api.js starts it when the
// page is the static build (`bash web/build DIR` copies this file beside ikarus-worker.js).
//
// WebAssembly cannot be stopped from outside while it runs (a long solve holds the worker's only
// thread, and nothing in it can look at a clock or a flag), so a job that outlives its budget is
// stopped by terminating the worker: the job is answered 503 naming the budget, a new worker is
// started, and the jobs queued behind it go to the new one. A job that trapped (out of memory, a
// panic: the worker says `restart: true`) is answered with the worker's 500 and the worker is
// replaced too, so that no state of the stopped module (its handles, the character and chain
// the worker keeps) outlives it.
//
// The budget: `?budget_ms=N` in the page's address, else DEFAULT_BUDGET_MS.

/** The budget of one job when the page's address names none: `ikarus serve`'s default. */
export const DEFAULT_BUDGET_MS = 10000;

/** The budget in ms that the page's query string `search` names (`budget_ms=N`, N > 0), else the default. */
export function budgetOf(search) {
  const v = Number(new URLSearchParams(search).get("budget_ms"));
  return Number.isFinite(v) && v > 0 ? v : DEFAULT_BUDGET_MS;
}

/** A worker started from `url` once its module says it is ready (rejects with why it is not). */
function spawn(url) {
  return new Promise((resolve, reject) => {
    let worker;
    try {
      worker = new Worker(url, { type: "module" });
    } catch (e) {
      reject(e);
      return;
    }
    worker.onerror = (e) => reject(e.message || e);
    worker.onmessage = ({ data }) => {
      if (!("ready" in data)) return;
      worker.onerror = null;
      if (data.ready) resolve(worker);
      else {
        worker.terminate();
        reject(data.error);
      }
    };
  });
}

/** A job's answer as the worker gives it: `{status, text}` with the server's `{"error": …}`. */
const refusal = (status, error) => ({ status, text: JSON.stringify({ error }) });

/**
 * Starts the solver thread at `url` with a budget of `budgetMs` per job. Resolves with
 * `{ask(message): Promise<reply>, restarts(): number}` once the first worker is ready (rejects
 * if it never is); `onRestart()` is called each time a worker is replaced (the state the page
 * sent the old one is gone).
 */
export async function solverThread(url, budgetMs, onRestart = () => {}) {
  let worker = await spawn(url);
  let restarts = 0;
  let broken = null; // why a new worker did not start: every later job is answered with it
  const queue = [];
  let current = null; // the job the worker is running: {message, done, timer, id}
  let next = 0;

  const listen = (w) => {
    w.onmessage = ({ data }) => {
      if (w !== worker || !current || data.id !== current.id) return;
      const { done, timer } = current;
      clearTimeout(timer);
      current = null;
      if (data.restart) replace();
      done(data);
      pump();
    };
  };

  function replace() {
    worker.terminate();
    worker = null;
    restarts++;
    onRestart();
    spawn(url).then(
      (w) => {
        worker = w;
        listen(w);
        pump();
      },
      (why) => {
        broken = `the WebAssembly solver did not restart: ${why && why.message ? why.message : why}`;
        pump();
      },
    );
  }

  function pump() {
    if (broken) {
      while (queue.length) queue.shift().done(refusal(503, broken));
      return;
    }
    if (current || !worker || !queue.length) return;
    current = queue.shift();
    current.id = next++;
    current.timer = setTimeout(() => {
      const { done } = current;
      current = null;
      replace();
      done(
        refusal(
          503,
          `request stopped: it took longer than the budget of ${budgetMs} ms (budget_ms in the page's address); ` +
            "the WebAssembly solver was restarted; ask for less work (fewer iterations, restarts, samples, frames)",
        ),
      );
    }, budgetMs);
    worker.postMessage({ ...current.message, id: current.id });
  }

  listen(worker);
  return {
    ask: (message) =>
      new Promise((done) => {
        queue.push({ message, done });
        pump();
      }),
    restarts: () => restarts,
  };
}
