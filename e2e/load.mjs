// Load check: 200 concurrent clients solving random goals against `ikarus serve` on loopback for
// 10 seconds. Reports requests, errors and the server's resident memory (from /proc) at the
// start, the middle and the end; exits 1 on any error or if memory grew by more than half.
//   node e2e/load.mjs            (builds nothing: run `cargo build --release` first)
import { spawn } from "node:child_process";
import { readFileSync } from "node:fs";
import { dirname, join } from "node:path";
import { fileURLToPath } from "node:url";

const here = dirname(fileURLToPath(import.meta.url));
const binary = process.env.IKARUS_BIN ?? join(here, "..", "target", "release", "ikarus");
const CLIENTS = 200;
const SECONDS = 10;

const server = spawn(binary, ["serve", "--port", "0"], { stdio: ["ignore", "pipe", "inherit"] });
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

let requests = 0;
let errors = 0;
let firstError = null;
const deadline = Date.now() + SECONDS * 1000;
async function client(seed) {
  let s = seed;
  const random = () => ((s = (s * 1103515245 + 12345) % 2147483648) / 2147483648);
  while (Date.now() < deadline) {
    const r = 5.5 * Math.sqrt(random());
    const a = 2 * Math.PI * random();
    try {
      const res = await fetch(`${url}/api/solve`, {
        method: "POST",
        headers: { "content-type": "application/json" },
        body: JSON.stringify({ goal: { x: r * Math.cos(a), y: r * Math.sin(a) }, options: { record_every: 50 } }),
      });
      const body = await res.json();
      if (res.status !== 200 || !body.status) throw new Error(`${res.status} ${JSON.stringify(body)}`);
      requests += 1;
    } catch (e) {
      errors += 1;
      firstError ??= e.message;
    }
  }
}

const before = rss();
let middle = 0;
const sampler = setTimeout(() => (middle = rss()), (SECONDS * 1000) / 2);
await Promise.all(Array.from({ length: CLIENTS }, (_, i) => client(i + 1)));
clearTimeout(sampler);
const after = rss();
server.kill("SIGINT");

console.log(
  `load: ${CLIENTS} clients, ${SECONDS} s: ${requests} solves (${Math.round(requests / SECONDS)}/s), ${errors} errors; ` +
    `server RSS ${before} kB at start, ${middle} kB midway, ${after} kB at the end`,
);
if (errors > 0) console.log(`first error: ${firstError}`);
process.exit(errors > 0 || after > 1.5 * Math.max(middle, before) ? 1 : 0);
