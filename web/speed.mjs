// The WebAssembly module's speed in node, per call, interleaved in one run: the seed arm's solve
// through `call("solve", json)` (a JSON request in, a JSON answer out), the same solve through
// the typed `Chain.solve(x, y, out)` (the record copied out of the module's memory), through
// `Chain.solveHere(x, y)` (read in place, no copy) and through wasm-bindgen's glue with the
// Float64Array as argument (what `Chain.solve` was: the glue allocates, copies in and out, frees);
// and a pose of spineboy (`walk` at a time that advances, one target) the same three typed ways;
// then, optionally, the native server's `solve_us` for the same requests (the library at native
// speed, HTTP aside). Each call is timed alone; the kinds run in rounds of 100 calls each, in
// turn, so that a change of the machine's load hits all alike. Prints medians and p99 in µs with
// os.loadavg() before and after; checks nothing.
//
//   node web/speed.mjs DIR [N] [--native]   (DIR from `bash web/build DIR`; N calls of each, 20000)
import { spawn } from "node:child_process";
import { readFileSync } from "node:fs";
import { loadavg } from "node:os";
import { dirname, join, resolve } from "node:path";
import { fileURLToPath, pathToFileURL } from "node:url";

const root = join(dirname(fileURLToPath(import.meta.url)), "..");
const args = process.argv.slice(2).filter((a) => a !== "--native");
const withNative = process.argv.includes("--native");
const dir = resolve(args[0] ?? "");
const n = Number(args[1] ?? 20000);
const ikarus = await import(pathToFileURL(join(dir, "ikarus.js")).href);
await ikarus.init(readFileSync(join(dir, "ikarus_wasm_bg.wasm")));
// The glue ikarus.js wraps (the same module instance), for the copying path.
const glue = await import(pathToFileURL(join(dir, "ikarus_wasm.js")).href);

const goal = (k) => {
  const a = (k * 2.399963) % (2 * Math.PI);
  const r = 1.5 + (k % 7) * 0.55;
  return { x: r * Math.cos(a), y: r * Math.sin(a) };
};
const request = (k) => JSON.stringify({ goal: goal(k), options: { record_every: 1000000 } });
const sorted = (v) => v.slice().sort((a, b) => a - b);
const median = (v) => sorted(v)[v.length >> 1];
const p99 = (v) => sorted(v)[Math.min(v.length - 1, Math.floor(v.length * 0.99))];
const load = () => loadavg().map((l) => l.toFixed(2)).join(" ");

const chain = new ikarus.Chain();
const record = new Float64Array(chain.recordLen);
const glueChain = new glue.Chain("", "");
const spineboyText = readFileSync(join(root, "examples", "characters", "spine-spineboy-pro.json"), "utf8");
const spineboy = new ikarus.Character(spineboyText);
spineboy.setAnimation("walk");
const glueSpineboy = new glue.Character(spineboyText);
glueSpineboy.setAnimation("walk");
const targets = Float64Array.of(spineboy.bones.indexOf("front-leg-target"), 120, 40);
const posed = new Float64Array(spineboy.poseLen);

const kinds = {
  json: { label: 'call("solve", json)', run: (k) => JSON.parse(ikarus.call("solve", request(k))), times: [], inside: [] },
  typed: { label: "Chain.solve (typed)", run: (k) => { const g = goal(k); chain.solve(g.x, g.y, record); }, times: [] },
  here: { label: "Chain.solveHere (in place)", run: (k) => { const g = goal(k); chain.solveHere(g.x, g.y); }, times: [] },
  glue: { label: "glue Chain.solve(x, y, out) (copies)", run: (k) => { const g = goal(k); glueChain.solve(g.x, g.y, record); }, times: [] },
  pose: { label: "Character.pose spineboy walk (typed)", run: (k) => spineboy.pose((k % 100) * 0.0123, targets, posed), times: [] },
  poseHere: { label: "Character.poseHere (in place)", run: (k) => spineboy.poseHere((k % 100) * 0.0123, targets), times: [] },
  poseGlue: { label: "glue Character.pose (copies)", run: (k) => glueSpineboy.pose((k % 100) * 0.0123, targets, posed), times: [] },
};
for (const kind of Object.values(kinds)) for (let k = 0; k < 300; k++) kind.run(k); // warm up

const loadBefore = load();
const round = 100;
for (let start = 0; start < n; start += round) {
  for (const kind of Object.values(kinds)) {
    for (let k = start; k < Math.min(n, start + round); k++) {
      const t0 = performance.now();
      const answer = kind.run(k);
      kind.times.push((performance.now() - t0) * 1000);
      if (kind.inside) kind.inside.push(answer.solve_us);
    }
  }
}
const loadAfter = load();

console.log(`node ${process.version}, ${n} calls of each, interleaved in rounds of ${round}; loadavg ${loadBefore} before, ${loadAfter} after`);
for (const kind of Object.values(kinds)) {
  let line = `  ${kind.label.padEnd(38)} median ${median(kind.times).toFixed(2).padStart(7)} µs   p99 ${p99(kind.times).toFixed(2).padStart(7)} µs`;
  if (kind.inside) line += `   (the solve inside: median ${median(kind.inside).toFixed(2)} µs)`;
  console.log(line);
}

if (withNative) {
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
  for (let k = 0; k < Math.min(n, 5000); k++) {
    const res = await fetch(`${url}/api/solve`, { method: "POST", headers: { "content-type": "application/json" }, body: request(k) });
    native.push((await res.json()).solve_us);
  }
  child.kill();
  console.log(`  native library (the server's solve_us)   median ${median(native).toFixed(2).padStart(7)} µs   p99 ${p99(native).toFixed(2).padStart(7)} µs`);
}
