// Solves per second of the WebAssembly module in node, beside the native library's: the seed
// arm's solves of N goals through ikarus.js's solve (a JSON request in, a JSON answer out), with
// the median time of a call, the median `solve_us` the module measures around the solve alone
// (so the JSON boundary's cost is the difference), and the native server's `solve_us` for the
// same requests (the library at native speed, HTTP aside). Prints; checks nothing.
//
//   node web/speed.mjs DIR [N]      (DIR from `bash web/build DIR`; target/release/ikarus native)
import { spawn } from "node:child_process";
import { readFileSync } from "node:fs";
import { dirname, join, resolve } from "node:path";
import { fileURLToPath, pathToFileURL } from "node:url";

const root = join(dirname(fileURLToPath(import.meta.url)), "..");
const dir = resolve(process.argv[2] ?? "");
const n = Number(process.argv[3] ?? 5000);
const ikarus = await import(pathToFileURL(join(dir, "ikarus.js")).href);
await ikarus.init(readFileSync(join(dir, "ikarus_wasm_bg.wasm")));

const goal = (k) => {
  const a = (k * 2.399963) % (2 * Math.PI);
  const r = 1.5 + (k % 7) * 0.55;
  return { x: r * Math.cos(a), y: r * Math.sin(a) };
};
const request = (k) => JSON.stringify({ goal: goal(k), options: { record_every: 1000000 } });
const median = (v) => v.slice().sort((a, b) => a - b)[v.length >> 1];

for (let k = 0; k < 200; k++) ikarus.call("solve", request(k)); // warm up
const calls = [];
const solves = [];
const t = performance.now();
for (let k = 0; k < n; k++) {
  const t0 = performance.now();
  const text = ikarus.call("solve", request(k));
  calls.push((performance.now() - t0) * 1000);
  solves.push(JSON.parse(text).solve_us);
}
const total = performance.now() - t;

const binary = process.env.IKARUS_BIN ?? join(root, "target", "release", "ikarus");
const child = spawn(binary, ["serve", "--port", "0"], { stdio: ["ignore", "pipe", "inherit"] });
const url = await new Promise((ok) => {
  let out = "";
  child.stdout.on("data", (c) => {
    out += c;
    const m = out.match(/listening on (http:\/\/\S+)/);
    if (m) ok(m[1]);
  });
});
const native = [];
for (let k = 0; k < n; k++) {
  const res = await fetch(`${url}/api/solve`, { method: "POST", headers: { "content-type": "application/json" }, body: request(k) });
  native.push((await res.json()).solve_us);
}
child.kill();

console.log(`${n} solves of the seed arm (LM, up to 16 restarts), node ${process.version}:`);
console.log(`  wasm: ${Math.round((n / total) * 1000)} calls/s; median call ${median(calls).toFixed(1)} µs, of which the solve ${median(solves).toFixed(1)} µs (JSON in and out: ${(median(calls) - median(solves)).toFixed(1)} µs)`);
console.log(`  native library (the server's solve_us): median ${median(native).toFixed(1)} µs a solve`);
