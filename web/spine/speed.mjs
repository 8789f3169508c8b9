// What ikarus-spine's apply() costs a frame in node, beside the runtime's own work of the frame:
// spineboy walk, 600 frames at 60 Hz, a 3-bone goal on front-fist moving on a circle and rear-foot
// pinned. Prints a table (median and p99 µs) and the JS heap's growth over the measured frames.
// Not a test: nothing here asserts a time.
//   IKARUS_SPINE_DIR=… IKARUS_WEB_DIR=… node --expose-gc web/spine/speed.mjs [frames]
// The runtime's work is the stand-in's (web/spine/standin/: spine-core's API, posed by ikarus's
// own code in WebAssembly), not spine-core's, which the ikarus repository never installs.
import { spinePackage, standIn, gameUpdate } from "./common.mjs";

const frames = Number(process.argv[2] ?? 600);
const { attach } = await spinePackage();
const boy = await standIn("spine-spineboy-pro", "walk");
const { skeleton, state } = boy;
gameUpdate(boy, 0);
const ik = await attach(skeleton);
const shoulder = skeleton.findBone("front-upper-arm");
const reach = ["front-upper-arm", "front-bracer", "front-fist"].reduce((s, n) => s + skeleton.findBone(n).data.length, 0);
const [cx, cy] = [shoulder.worldX, shoulder.worldY];
const three = { bones: 3 };

// The skeleton's updateWorldTransform, timed when apply() calls it (its own part = the whole less this).
const update = skeleton.updateWorldTransform;
let inner = 0;
let timing = false;
skeleton.updateWorldTransform = function (physics) {
  if (!timing) return update.call(this, physics);
  const t0 = performance.now();
  update.call(this, physics);
  inner += performance.now() - t0;
};

const rows = { whole: [], own: [], runtime: [], runtimeApply: [], runtimeUpdate: [] };
function frame(f, record) {
  const t = (2 * Math.PI * f) / 240;
  const t0 = performance.now();
  state.update(1 / 60);
  state.apply(skeleton);
  const t1 = performance.now();
  skeleton.updateWorldTransform(2);
  const t2 = performance.now();
  inner = 0;
  timing = true;
  const a0 = performance.now();
  ik.clear();
  ik.goal("front-fist", cx + 0.55 * reach * Math.cos(t), cy + 0.55 * reach * Math.sin(t), three);
  ik.pin("rear-foot");
  ik.apply();
  const a1 = performance.now();
  timing = false;
  if (!record) return;
  rows.runtimeApply.push((t1 - t0) * 1000);
  rows.runtimeUpdate.push((t2 - t1) * 1000);
  rows.runtime.push((t2 - t0) * 1000);
  rows.whole.push((a1 - a0) * 1000);
  rows.own.push((a1 - a0 - inner) * 1000);
}

for (let f = 0; f < 600; f++) frame(f, false); // warm-up: the JIT's tiers
globalThis.gc?.();
const heap = process.memoryUsage().heapUsed;
for (let f = 0; f < frames; f++) frame(600 + f, true);
const grown = process.memoryUsage().heapUsed - heap;
// The add-on alone: the same calls on a still pose (no stand-in work in between).
globalThis.gc?.();
const heapAlone = process.memoryUsage().heapUsed;
for (let f = 0; f < frames; f++) {
  const t = (2 * Math.PI * f) / 240;
  ik.clear();
  ik.goal("front-fist", cx + 0.55 * reach * Math.cos(t), cy + 0.55 * reach * Math.sin(t), three);
  ik.pin("rear-foot");
  ik.apply();
}
const grownAlone = process.memoryUsage().heapUsed - heapAlone;

const quantile = (xs, q) => {
  const s = [...xs].sort((a, b) => a - b);
  return s[Math.min(s.length - 1, Math.floor(q * s.length))];
};
const table = [
  ["ik.apply(), whole", rows.whole],
  ["ik.apply(), its own part (without updateWorldTransform)", rows.own],
  ["runtime (stand-in): state.update + state.apply", rows.runtimeApply],
  ["runtime (stand-in): skeleton.updateWorldTransform", rows.runtimeUpdate],
  ["runtime (stand-in): the frame's update, all of it", rows.runtime],
];
console.log(`spineboy walk, ${skeleton.bones.length} bones, ${frames} frames at 60 Hz, node ${process.version}; goal front-fist (3 bones) + pin rear-foot`);
console.log("| what | median µs | p99 µs |");
console.log("| --- | ---: | ---: |");
for (const [what, xs] of table) console.log(`| ${what} | ${quantile(xs, 0.5).toFixed(2)} | ${quantile(xs, 0.99).toFixed(2)} |`);
if (globalThis.gc) {
  console.log(`JS heap growth, no gc in between: ${grownAlone} bytes over ${frames} frames of the add-on alone (clear, goal, pin, apply);`);
  console.log(`  ${grown} bytes over ${frames} whole game frames (the stand-in's update included)`);
} else console.log("(node --expose-gc for the heap growth)");
