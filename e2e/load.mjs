// Load check of `ikarus serve` on loopback, run by hand (about 15 seconds; not part of .ci/run):
//   cargo build --release && node e2e/load.mjs
// Environment: LOAD_SECONDS (default 10), LOAD_MIX (`issue11`, the default, or `issue24`),
// LOAD_HEAVY (how many of the mix's heavy kinds, default all), LOAD_LIGHT (0 leaves out the light
// clients), LOAD_SERVER_ARGS (extra `ikarus serve` flags, e.g. "--workers 4"), IKARUS_BIN.
//
// For SECONDS seconds a mixed load runs against one server:
//   - 100 clients solving random goals (the old check: 200 of them and nothing else);
//   - 10 clients animating, 5 sampling workspaces, 5 rendering (PNG arms, small GIF motions);
//   - the heavy clients of the mix, in a loop. LOAD_MIX=issue11: 4 clients sending the
//     expensive requests of issue 11: a solve that runs for hours, a 64-link animate with 100
//     via points, 64 restarts and gain 1e-9, a workspace at resolution 1024 with 10⁶ samples, a
//     2000-frame GIF of a 64-link arm, expected to end 503 at the server's time budget (or be
//     refused 503 "busy" when their queue is full). LOAD_MIX=issue24: 8 clients, two each of
//     requests of issue 24's kinds that take 0.5 to 3.5 s alone: solve_batch of 100,000 goals
//     out of reach, animate of 64 links through 100 via points out of reach with 64 restarts, a
//     planned track of 4000 samples on 24 links, the exact workspace of 64 limited links (200, or
//     503 at the budget or busy);
//   - one prober asking GET /api/health every 10 ms, and one posting a small /api/solve every
//     100 ms, each on its own thread, timing each answer.
// It reports, per kind, the answers by status; the latency (p50, p99, max) of health and of the
// small solves; and the server's resident memory at the start, midway and at the end. It exits 1
// if a health check fails or its p99 reaches 50 ms, if a small solve is not 200 or takes 2 s, if
// any answer is neither 200 nor an expected 503, or if the server's memory ends above MAX_RSS_KB
// (bounded memory; it varies with the heavy requests' timing, so no growth ratio is checked).
import { spawn } from "node:child_process";
import { readFileSync } from "node:fs";
import { dirname, join } from "node:path";
import { fileURLToPath } from "node:url";
import { Worker } from "node:worker_threads";

const here = dirname(fileURLToPath(import.meta.url));
const binary = process.env.IKARUS_BIN ?? join(here, "..", "target", "release", "ikarus");
const SECONDS = Number(process.env.LOAD_SECONDS ?? 10);
const HEALTH_P99_GOAL_MS = 50;
const SMALL_SOLVE_MAX_MS = 2000;
const MAX_RSS_KB = 512 * 1024;
const MIX = process.env.LOAD_MIX ?? "issue11";
const LIGHT_CLIENTS = process.env.LOAD_LIGHT !== "0";
const serverArgs = (process.env.LOAD_SERVER_ARGS ?? "").split(" ").filter(Boolean);

const server = spawn(binary, ["serve", "--port", "0", ...serverArgs], { stdio: ["ignore", "pipe", "inherit"] });
const url = await new Promise((resolve, reject) => {
  let out = "";
  server.on("error", reject);
  server.stdout.on("data", (c) => {
    out += c;
    const m = out.match(/listening on (http:\/\/\S+)/);
    if (m) resolve(m[1]);
  });
});
const rss = () => Number(readFileSync(`/proc/${server.pid}/status`, "utf8").match(/VmRSS:\s+(\d+)/)[1]);

const deadline = Date.now() + SECONDS * 1000;
/** answers[kind][status] = count; "network" for a failed fetch. */
const answers = {};
/** The first 503 message of each kind. */
const busy = {};
const unexpected = [];
const count = (kind, status) => {
  answers[kind] ??= {};
  answers[kind][status] = (answers[kind][status] ?? 0) + 1;
};

async function post(kind, path, body, expected) {
  try {
    const res = await fetch(`${url}${path}`, {
      method: "POST",
      headers: { "content-type": "application/json" },
      body: JSON.stringify(body),
    });
    const bytes = await res.arrayBuffer();
    count(kind, res.status);
    if (res.status === 503) busy[kind] ??= new TextDecoder().decode(bytes).slice(0, 160);
    if (!expected.includes(res.status)) {
      unexpected.push(`${kind}: ${res.status} ${new TextDecoder().decode(bytes).slice(0, 200)}`);
    }
  } catch (e) {
    count(kind, "network");
    unexpected.push(`${kind}: ${e.message}`);
  }
}

function rng(seed) {
  let s = seed;
  return () => (s = (s * 1103515245 + 12345) % 2147483648) / 2147483648;
}

const goal = (random) => {
  const r = 5.5 * Math.sqrt(random());
  const a = 2 * Math.PI * random();
  return { x: r * Math.cos(a), y: r * Math.sin(a) };
};

// Light requests: 200 normally; 503 only if the server is saturated by the heavy ones.
const LIGHT = [200, 503];
async function loop(kind, seed, request) {
  const random = rng(seed);
  while (Date.now() < deadline) {
    const [path, body, expected] = request(random);
    await post(kind, path, body, expected);
  }
}

const links64 = Array.from({ length: 64 }, () => ({ length: 0.1, angle_deg: 5 }));
const via100 = Array.from({ length: 100 }, (_, i) => [(i % 7) * 0.5, 1]);
const ISSUE11 = [
  // Hours: a 64-link arm held within ±1° of straight, asked for a goal it cannot reach so.
  () => [
    "/api/solve",
    {
      arm: { links: Array.from({ length: 64 }, () => ({ length: 0.1, angle_deg: 0, limits_deg: [-1, 1] })) },
      goal: { x: -3, y: -1 },
      options: {
        limits: true, restarts: 64, backtrack: 0, max_iterations: 100000, stall_window: 4294967295,
        tolerance: 5e-324, gain: 1e-9,
      },
    },
    // 65 × 10⁵ iterations of 64 links take about 10 s: it may finish just inside the budget.
    [200, 503],
  ],
  () => [
    "/api/animate",
    { arm: { links: links64 }, goal: { x: 3, y: 3 }, via: via100, options: { restarts: 64, max_iterations: 100000, gain: 1e-9 } },
    [503],
  ],
  () => [
    "/api/workspace",
    {
      arm: { links: [{ length: 1, angle_deg: 0, limits_deg: [-90, 90] }, { length: 100, angle_deg: 0 }, { length: 100, angle_deg: 0 }] },
      limits: true, resolution: 1024, samples: 1000000,
    },
    [503],
  ],
  () => [
    "/api/render",
    { figure: "motion", arm: { links: links64 }, goal: { x: 3, y: 3 }, frames: 2000, format: "gif", width: 223, height: 223 },
    [200, 503],
  ],
];

// Each of these takes about 0.5 to 3.5 s alone (release build, 2 cores).
const farGoals = Array.from({ length: 100000 }, (_, i) => [10 + (i % 5), 1 + (i % 3)]);
const farVia = Array.from({ length: 100 }, (_, i) => [20 + (i % 7) * 0.5, 1]);
const links24 = links64.slice(0, 24);
const limited64 = Array.from({ length: 64 }, () => ({ length: 0.1, angle_deg: 5, limits_deg: [-30, 30] }));
const ISSUE24_KINDS = [
  () => ["/api/solve_batch", { goals: farGoals }, [200, 503]],
  () => ["/api/animate", { arm: { links: links64 }, goal: { x: 30, y: 3 }, via: farVia, options: { restarts: 64 } }, [200, 503]],
  () => ["/api/track", { arm: { links: links24 }, circle: [0, 0, 1], samples: 4000, mode: "plan" }, [200, 503]],
  () => ["/api/workspace", { arm: { links: limited64 }, limits: true }, [200, 503]],
];
const MIXES = { issue11: ISSUE11, issue24: [...ISSUE24_KINDS, ...ISSUE24_KINDS] };
if (!MIXES[MIX]) throw new Error(`LOAD_MIX=${MIX}: expected issue11 or issue24`);
/** How many of the mix's heavy kinds run (from the first): LOAD_HEAVY=1 runs only the first. */
const HEAVY_KINDS = Number(process.env.LOAD_HEAVY ?? MIXES[MIX].length);
const HEAVY = MIXES[MIX];

// The probers run on their own threads (their own event loops), so that their timings are the
// server's answers and not the wait behind the other clients' callbacks in this one.
const PROBER = `
const { parentPort, workerData } = require("node:worker_threads");
(async () => {
  const latencies = [];
  let failures = 0;
  let firstFailure = null;
  const { url, deadline, path, body, every } = workerData;
  const init = body ? { method: "POST", headers: { "content-type": "application/json" }, body } : undefined;
  while (Date.now() < deadline) {
    const began = performance.now();
    try {
      const res = await fetch(url + path, init);
      const text = await res.text();
      if (res.status !== 200) {
        failures += 1;
        firstFailure ??= res.status + " " + text.slice(0, 160);
      }
    } catch (e) {
      failures += 1;
      firstFailure ??= e.message;
    }
    latencies.push(performance.now() - began);
    await new Promise((r) => setTimeout(r, every));
  }
  parentPort.postMessage({ latencies, failures, firstFailure });
})();
`;
/** Times `path` (a POST of `body`, if given) every `every` ms until the deadline, on its own thread. */
function prober(path, body, every) {
  return new Promise((resolve, reject) => {
    const worker = new Worker(PROBER, { eval: true, workerData: { url, deadline, path, body, every } });
    worker.on("message", (m) => resolve({ ...m, latencies: m.latencies.sort((a, b) => a - b) }));
    worker.on("error", reject);
  });
}

const before = rss();
let middle = 0;
const sampler = setTimeout(() => (middle = rss()), (SECONDS * 1000) / 2);
const health = prober("/api/health", null, 10);
const small = prober("/api/solve", JSON.stringify({ goal: { x: 2, y: 3 } }), 100);
const clients = [health, small];
if (LIGHT_CLIENTS) {
  for (let i = 0; i < 100; i++) {
    clients.push(loop("solve", i + 1, (r) => ["/api/solve", { goal: goal(r), options: { record_every: 50 } }, LIGHT]));
  }
  for (let i = 0; i < 10; i++) {
    clients.push(loop("animate", 1000 + i, (r) => ["/api/animate", { goal: goal(r), frames: 60 }, LIGHT]));
  }
  for (let i = 0; i < 5; i++) {
    clients.push(loop("workspace", 2000 + i, () => ["/api/workspace", { resolution: 256 }, LIGHT]));
  }
  for (let i = 0; i < 5; i++) {
    clients.push(
      loop("render", 3000 + i, (r) =>
        i % 2 === 0
          ? ["/api/render", { figure: "arm", goal: goal(r), width: 400, height: 400 }, LIGHT]
          : ["/api/render", { figure: "motion", goal: goal(r), frames: 30, format: "gif", width: 200, height: 200 }, LIGHT],
      ),
    );
  }
}
HEAVY.slice(0, HEAVY_KINDS).forEach((request, i) => clients.push(loop(`heavy ${request()[0]}`, 4000 + i, request)));
await Promise.all(clients);
clearTimeout(sampler);
const after = rss();
server.kill("SIGINT");

const pct = (sorted, p) => sorted[Math.min(sorted.length - 1, Math.floor((p / 100) * sorted.length))];
const summary = (name, { latencies, failures, firstFailure }, goal) =>
  `  ${name}: ${latencies.length} answers, ${failures} failed${firstFailure ? ` (first: ${firstFailure})` : ""}; ` +
  `latency p50 ${pct(latencies, 50).toFixed(1)} ms, p99 ${pct(latencies, 99).toFixed(1)} ms, ` +
  `max ${latencies[latencies.length - 1].toFixed(1)} ms (goal: ${goal})`;
const [h, sm] = [await health, await small];
const light = LIGHT_CLIENTS ? "with" : "without";
console.log(`load: ${SECONDS} s of the ${MIX} mix (${HEAVY_KINDS} heavy clients, ${light} the light ones) on ${url} ${serverArgs.join(" ")}`);
for (const [kind, by] of Object.entries(answers)) {
  const parts = Object.entries(by).map(([status, n]) => `${n}× ${status}`);
  console.log(`  ${kind}: ${parts.join(", ")}${busy[kind] ? ` (first 503: ${busy[kind]})` : ""}`);
}
console.log(summary("GET /api/health", h, `p99 < ${HEALTH_P99_GOAL_MS} ms`));
console.log(summary("small POST /api/solve", sm, `all 200, max < ${SMALL_SOLVE_MAX_MS} ms`));
console.log(`  server RSS ${before} kB at start, ${middle} kB midway, ${after} kB at the end`);
if (unexpected.length > 0) console.log(`  ${unexpected.length} unexpected answers; first: ${unexpected[0]}`);
const failed =
  h.failures > 0 ||
  pct(h.latencies, 99) >= HEALTH_P99_GOAL_MS ||
  sm.failures > 0 ||
  sm.latencies[sm.latencies.length - 1] >= SMALL_SOLVE_MAX_MS ||
  unexpected.length > 0 ||
  Math.max(middle, after) > MAX_RSS_KB;
process.exit(failed ? 1 : 0);
