// The ikarus-spine demo (web/build writes it as DIR/spine-demo.html): spineboy walks (the stand-in
// skeleton of web/spine/standin, posed by ikarus in WebAssembly where a game would have Spine's
// runtime), and every frame the add-on puts the front fist's tip on the pointer (3 bones) and
// keeps the rear foot's tip where the walk put it. Bones are drawn as lines on a 2D canvas (no
// art); the moved bones in colour. The readout: apply()'s µs over the last 300 frames (see
// `speed`) and the goal's error.
//
// `?still` holds the clock (frames advance only through window.spineDemo.step), for tests.

import initCore, * as core from "../ikarus_core.js";
import { loadStandIn, Physics } from "./standin/index.js";
import { attach } from "./ikarus-spine/index.js";

const canvas = document.getElementById("view");
const readout = document.getElementById("readout");
const still = new URLSearchParams(location.search).has("still");

await initCore({ module_or_path: new URL("../ikarus_core_bg.wasm", import.meta.url) });
const text = await (await fetch(new URL("./spineboy.json", import.meta.url))).text();
const { skeleton, state } = await loadStandIn(text, { core });
state.setAnimation(0, "walk", true);
const ik = await attach(skeleton, { limits: { "front-bracer": [0, 150] }, physics: Physics.pose });
const fist = skeleton.findBone("front-fist");
const shoulder = skeleton.findBone("front-upper-arm");
const moving = new Set(["front-upper-arm", "front-bracer", "front-fist", "rear-thigh", "rear-shin", "rear-foot"]);

// The view: world y up, spineboy's walk fitted with room for the arm's reach.
const view = { scale: 1, x: 0, y: 0 };
function fit() {
  const r = devicePixelRatio || 1;
  canvas.width = Math.round(canvas.clientWidth * r);
  canvas.height = Math.round(canvas.clientHeight * r);
  const [w, h] = [700, 760]; // world units shown: x -350..350, y -60..700
  view.scale = Math.min(canvas.width / w, canvas.height / h);
  view.x = canvas.width / 2;
  view.y = canvas.height - 60 * view.scale;
}
const toCanvas = (x, y) => [view.x + x * view.scale, view.y - y * view.scale];
const fromCanvas = (cx, cy) => [(cx - view.x) / view.scale, (view.y - cy) / view.scale];

/** The pointer in world coordinates, or null. */
let pointer = null;
canvas.addEventListener("pointermove", (e) => {
  const r = devicePixelRatio || 1;
  const rect = canvas.getBoundingClientRect();
  pointer = fromCanvas((e.clientX - rect.left) * r, (e.clientY - rect.top) * r);
});
canvas.addEventListener("pointerleave", () => (pointer = null));

const rearFoot = skeleton.findBone("rear-foot");
/** The rear foot's tip as the walk put it this frame, before the add-on. */
const pinnedAt = [0, 0];
/** Every bone's world numbers (a b c d worldX worldY) as the runtime left them this frame. */
const before = new Float64Array(6 * skeleton.bones.length);
const times = new Float64Array(300);
let frames = 0;
let report = null;

/** One frame of a game: the runtime's own update, then the add-on. */
function step(dt) {
  state.update(dt);
  state.apply(skeleton);
  skeleton.update(dt);
  skeleton.updateWorldTransform(Physics.update);
  ik.clear();
  if (pointer) ik.goal(fist, pointer[0], pointer[1], { bones: 3 });
  ik.pin(rearFoot);
  [pinnedAt[0], pinnedAt[1]] = tip(rearFoot);
  for (let i = 0; i < skeleton.bones.length; i++) {
    const b = skeleton.bones[i];
    before.set([b.a, b.b, b.c, b.d, b.worldX, b.worldY], 6 * i);
  }
  const t = performance.now();
  report = ik.apply();
  times[frames % times.length] = (performance.now() - t) * 1000;
  frames++;
}

/** The tip of `bone` in world coordinates. */
const tip = (b) => [b.worldX + b.a * b.data.length, b.worldY + b.c * b.data.length];

function draw() {
  const g = canvas.getContext("2d");
  g.setTransform(1, 0, 0, 1, 0, 0);
  g.clearRect(0, 0, canvas.width, canvas.height);
  g.lineCap = "round";
  // The ground.
  g.strokeStyle = "#c9c4b6";
  g.lineWidth = 2;
  g.beginPath();
  g.moveTo(0, toCanvas(0, 0)[1]);
  g.lineTo(canvas.width, toCanvas(0, 0)[1]);
  g.stroke();
  for (const b of skeleton.bones) {
    if (!b.active) continue;
    const [x0, y0] = toCanvas(b.worldX, b.worldY);
    const [x1, y1] = toCanvas(...tip(b));
    const moved = moving.has(b.data.name);
    g.strokeStyle = moved ? (b.data.name.startsWith("rear") ? "#2b7bb9" : "#d9480f") : "#555";
    g.lineWidth = (moved ? 5 : 2.5) * (devicePixelRatio || 1);
    g.beginPath();
    g.moveTo(x0, y0);
    g.lineTo(x1, y1);
    g.stroke();
    g.fillStyle = g.strokeStyle;
    g.beginPath();
    g.arc(x0, y0, (moved ? 4 : 2.5) * (devicePixelRatio || 1), 0, 2 * Math.PI);
    g.fill();
  }
  if (pointer) {
    const [px, py] = toCanvas(...pointer);
    g.strokeStyle = "#d9480f";
    g.lineWidth = 1.5 * (devicePixelRatio || 1);
    g.beginPath();
    g.arc(px, py, 9 * (devicePixelRatio || 1), 0, 2 * Math.PI);
    g.stroke();
  }
  const n = Math.min(frames, times.length);
  const error = report && report.goals.length ? report.goals[0].error : null;
  readout.textContent = `${speed(n)}${error === null ? " · move the pointer over the canvas" : ` · fist error ${error.toExponential(1)}`}`;
}

/**
 * apply()'s cost over the last `n` frames. A page that is not cross-origin isolated reads a
 * clock coarsened to 100 µs steps (with jitter), so a frame's own figure means nothing there: the
 * mean over the frames is shown; median and p99 only when the clock is fine (isolated: 5 µs).
 */
function speed(n) {
  if (!n) return "apply(): no frame yet";
  let sum = 0;
  for (let i = 0; i < n; i++) sum += times[i];
  const mean = `apply(): mean ${(sum / n).toFixed(1)} µs over the last ${n} frames`;
  if (!globalThis.crossOriginIsolated) return `${mean} (the page's clock is coarse: no median)`;
  const sorted = Array.from(times.subarray(0, n)).sort((a, b) => a - b);
  const at = (q) => sorted[Math.min(n - 1, Math.floor(q * n))];
  return `${mean}, median ${at(0.5).toFixed(1)} µs, p99 ${at(0.99).toFixed(1)} µs`;
}

let last = null;
function frame(now) {
  if (!still) {
    const dt = last === null ? 0 : Math.min(0.05, (now - last) / 1000);
    last = now;
    step(dt);
  }
  draw();
  requestAnimationFrame(frame);
}

fit();
addEventListener("resize", fit);
step(0);
requestAnimationFrame(frame);

/** What the browser test reads and drives. */
window.spineDemo = {
  skeleton,
  ik,
  fist,
  shoulder,
  step,
  draw,
  tip,
  toCanvas,
  fromCanvas,
  get pointer() {
    return pointer;
  },
  get report() {
    return report;
  },
  get frames() {
    return frames;
  },
  times,
  pinnedAt,
  before,
  ready: true,
};
