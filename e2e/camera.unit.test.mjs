// Unit tests of the playground's camera (camera.js: zoom and pan over the fitted view) and of
// the onion skins' frame selection (onion.js); no browser, no server. Run by .ci/run:
//   node --test e2e/camera.unit.test.mjs
import { test } from "node:test";
import assert from "node:assert/strict";
import { ZOOM, clampZoom, fittedCamera, isFitted, panBy, pinch, viewThrough, wheelFactor, zoomAbout, zoomText } from "../crates/ikarus-cli/src/serve/assets/camera.js";
import { ONION, drawOnion, newOnion, onionAlpha, onionFrames, onionMotion, skinLines } from "../crates/ikarus-cli/src/serve/assets/onion.js";
import { fitView, forward, toCanvas, toWorld } from "../crates/ikarus-cli/src/serve/assets/view.js";
import { fitBox } from "../crates/ikarus-cli/src/serve/assets/view.js";
import { bodyForward } from "../crates/ikarus-cli/src/serve/assets/body.js";

const arm = { name: "a", base: [0.5, -0.25], links: [{ length: 1, angle_deg: 30 }, { length: 0.8, angle_deg: 20 }, { length: 0.5, angle_deg: -10 }] };
const fit = fitView(arm, 900, 640);

/** |a − b| within `rel` of the larger magnitude (or of 1). */
const near = (a, b, rel = 1e-12) => Math.abs(a - b) <= rel * Math.max(1, Math.abs(a), Math.abs(b));
const nearPoint = (p, q, rel, what) => assert.ok(near(p[0], q[0], rel) && near(p[1], q[1], rel), `${what}: ${p} is not ${q}`);

test("the fitted camera shows the fit itself, bit for bit", () => {
  const cam = fittedCamera();
  assert.ok(isFitted(cam));
  const v = viewThrough(fit, cam);
  assert.deepEqual([v.cx, v.cy, v.scale, v.w, v.h, v.zoom], [fit.cx, fit.cy, fit.scale, fit.w, fit.h, 1]);
  assert.equal(v.fit, fit);
});

test("zooming about a point keeps the world point under it, at every zoom", () => {
  let view = viewThrough(fit, fittedCamera());
  const px = 613.25;
  const py = 141.5;
  const p = toWorld(view, px, py);
  // In to the top of the range and out to the bottom, in steps.
  for (const factor of [1.5, 3, 7, 11, 0.5, 0.01, 0.2, 1e-6, 1e6]) {
    view = viewThrough(fit, zoomAbout(view, factor, px, py));
    nearPoint(toWorld(view, px, py), p, 1e-12, `after ×${factor} (zoom ${view.zoom})`);
    nearPoint(toCanvas(view, ...p), [px, py], 1e-12, `the point's pixel after ×${factor}`);
  }
  // The last steps ran into the limits: clamped, the point still fixed.
  assert.equal(view.zoom, ZOOM.max);
  view = viewThrough(fit, zoomAbout(view, 1e-9, px, py));
  assert.equal(view.zoom, ZOOM.min);
  nearPoint(toWorld(view, px, py), p, 1e-12, "at the lowest zoom");
  assert.equal(view.scale, fit.scale * ZOOM.min);
});

test("the zoom is clamped to its range", () => {
  assert.equal(clampZoom(1e9), ZOOM.max);
  assert.equal(clampZoom(0), ZOOM.min);
  assert.equal(clampZoom(3), 3);
  assert.deepEqual([ZOOM.min, ZOOM.max], [0.05, 200]);
});

test("panning moves the world with the pointer by exactly the pixels dragged", () => {
  for (const zoom of [0.05, 1, 200]) {
    const view = viewThrough(fit, { zoom, x: 0.3, y: -0.2 });
    const q = toWorld(view, 100, 200);
    const moved = viewThrough(fit, panBy(view, 37.5, -12.25));
    nearPoint(toCanvas(moved, ...q), [137.5, 187.75], 1e-9, `zoom ${zoom}`);
    assert.equal(moved.zoom, zoom);
  }
});

test("a pinch zooms by the fingers' spread and carries the point under their midpoint", () => {
  const view = viewThrough(fit, { zoom: 2, x: 0.1, y: 0.1 });
  const from = [300, 250];
  const to = [340, 230];
  const q = toWorld(view, ...from);
  const after = viewThrough(fit, pinch(view, 1.75, from, to));
  assert.ok(near(after.zoom, 3.5));
  nearPoint(toCanvas(after, ...q), to, 1e-12, "the midpoint's world point");
});

test("toWorld ∘ toCanvas is the identity at 0.05×, 1× and 200×, anywhere", () => {
  for (const zoom of [0.05, 1, 200]) {
    for (const cam of [{ zoom, x: 0, y: 0 }, { zoom, x: -123.4, y: 56.7 }, { zoom, x: 1e-7, y: -3e-5 }]) {
      const view = viewThrough(fit, cam);
      for (const p of [[0, 0], [0.5, -0.25], [-1234.5, 987.25], [1e-6, -2e-7]]) {
        nearPoint(toWorld(view, ...toCanvas(view, ...p)), p, 1e-12, `zoom ${zoom}, camera ${JSON.stringify(cam)}`);
      }
      for (const px of [[0, 0], [450, 320], [899.5, 1.25]]) {
        nearPoint(toCanvas(view, ...toWorld(view, ...px)), px, 1e-12, `pixel ${px} at zoom ${zoom}`);
      }
    }
  }
});

test("the camera stays relative to the fit: a resized canvas keeps the same world at the centre", () => {
  const box = { x0: -1, x1: 2, y0: 0, y1: 3 };
  const a = fitBox(box, 0.3, 800, 600);
  const b = fitBox(box, 0.3, 1200, 500);
  const cam = { zoom: 4, x: 0.25, y: -0.5 };
  const va = viewThrough(a, cam);
  const vb = viewThrough(b, cam);
  nearPoint(toWorld(va, 400, 300), toWorld(vb, 600, 250), 1e-12, "the centre's world point");
  assert.ok(near(va.scale / a.scale, 4) && near(vb.scale / b.scale, 4));
});

test("the wheel's factor: up zooms in, a notch about 1.22×, lines and pages counted in pixels, one event at most e^0.5", () => {
  assert.ok(wheelFactor(-100) > 1 && wheelFactor(100) < 1);
  assert.ok(near(wheelFactor(-100), Math.exp(0.2)));
  assert.ok(near(wheelFactor(-3, 1), Math.exp(48 / 500)));
  assert.ok(near(wheelFactor(1, 2, false, 800), Math.exp(-0.5)));
  assert.ok(near(wheelFactor(-10, 0, true), Math.exp(0.1)));
  assert.ok(near(wheelFactor(-1000, 0, true), Math.exp(0.5)));
  assert.ok(near(wheelFactor(-100) * wheelFactor(100), 1));
});

test("the zoom readout", () => {
  assert.equal(zoomText(1), "100%");
  assert.equal(zoomText(200), "20,000%");
  assert.equal(zoomText(0.05), "5%");
  assert.equal(zoomText(0.004), "0.4%");
  assert.equal(zoomText(1.2345), "123%");
});

// ---- Onion skins ---------------------------------------------------------------------------

const frames = Array.from({ length: 10 }, (_, i) => ({ time: i / 10 }));

test("onion frames: count each side of the playhead, farthest first, fading with distance", () => {
  // On frame 5: frames 2..4 before, 6..8 after; frame 5 itself is the live pose.
  const on = onionFrames(frames, 0.5, 3);
  assert.deepEqual(on.map((s) => `${s.side[0]}${s.index}`), ["b2", "a8", "b3", "a7", "b4", "a6"]);
  assert.deepEqual(on.map((s) => s.alpha), [onionAlpha(3, 3), onionAlpha(3, 3), onionAlpha(2, 3), onionAlpha(2, 3), onionAlpha(1, 3), onionAlpha(1, 3)]);
  assert.ok(onionAlpha(1, 3) > onionAlpha(2, 3) && onionAlpha(2, 3) > onionAlpha(3, 3));
  // Between frames 5 and 6: frame 5 is the nearest before, 6 the nearest after.
  assert.deepEqual(onionFrames(frames, 0.55, 2).map((s) => `${s.side[0]}${s.index}`), ["b4", "a7", "b5", "a6"]);
  // A playhead within a rounding error of a frame is on it.
  assert.deepEqual(onionFrames(frames, 0.5 + 1e-13, 1).map((s) => `${s.side[0]}${s.index}`), ["b4", "a6"]);
  // At the ends: only one side, as many as there are.
  assert.deepEqual(onionFrames(frames, 0, 3).map((s) => `${s.side[0]}${s.index}`), ["a3", "a2", "a1"]);
  assert.deepEqual(onionFrames(frames, 0.9, 2).map((s) => `${s.side[0]}${s.index}`), ["b7", "b8"]);
  assert.deepEqual(onionFrames(frames, 0.5, 10).length, 9);
  // One skin each side: the nearest, fully faded in.
  assert.deepEqual(onionFrames(frames, 0.3, 1), [
    { index: 2, side: "before", alpha: onionAlpha(1, 1) },
    { index: 4, side: "after", alpha: onionAlpha(1, 1) },
  ]);
  assert.deepEqual(onionFrames([], 0, 3), []);
  assert.deepEqual(newOnion(), { show: false, count: ONION.count });
});

test("the motion skinned: the arm's animation at the playhead, a rig's or a character's keyed motion", () => {
  const anim = { frames: [{ time: 0, joints: forward(arm, [0, 0, 0]) }, { time: 2, joints: forward(arm, [10, 0, 0]) }] };
  const armState = { animation: anim, playback: { u: 0.25, posed: true } };
  assert.deepEqual(onionMotion(armState), { frames: anim.frames, kind: "arm", t: 0.5 });
  // The arm moved off the playhead (following the pointer): no skins.
  assert.equal(onionMotion({ ...armState, playback: { u: 0.25, posed: false } }), null);
  assert.equal(onionMotion({ animation: null, playback: { u: 0 } }), null);
  const rig = { name: "r", bones: [{ name: "a", length: 1, angle_deg: 0 }, { name: "b", parent: "a", length: 1, angle_deg: 0 }] };
  const motion = { frames: [{ time: 0, pose: [0, 0] }, { time: 1, pose: [90, -90] }] };
  const rigState = { rig: { rig }, motion, playback: { u: 1 } };
  assert.deepEqual(onionMotion(rigState), { frames: motion.frames, kind: "rig", t: 1 });
  assert.equal(onionMotion({ rig: { rig }, motion: null, playback: { u: 0 } }), null);
  const { starts, tips } = bodyForward(rig, [90, -90]);
  assert.deepEqual(skinLines(motion.frames[1], "rig", rig), [[starts[0], tips[0]], [starts[1], tips[1]]]);
  assert.deepEqual(skinLines(anim.frames[1], "arm"), [anim.frames[1].joints]);
  assert.deepEqual(skinLines({ bones: [{ x: 1, y: 2, tip: [3, 4] }] }, "character"), [[[1, 2], [3, 4]]]);
  assert.equal(onionMotion({ character: {}, motion: null, playback: { u: 0 } }), null);
});

test("drawOnion strokes count skins each side, and none when off", () => {
  const lines = [];
  const ctx = { beginPath() {}, moveTo() {}, lineTo() {}, stroke() { lines.push([this.strokeStyle, this.globalAlpha]); } };
  const anim = { frames: frames.map((f, i) => ({ time: f.time, joints: forward(arm, [i, 0, 0]) })) };
  const state = { animation: anim, playback: { u: 4 / 9, posed: true }, onion: { show: true, count: 2 } };
  const view = { ...fit };
  drawOnion(ctx, view, state);
  assert.deepEqual(view.onion, [2, 2]);
  assert.equal(lines.length, 4);
  assert.equal(ctx.globalAlpha, 1);
  state.onion.show = false;
  drawOnion(ctx, view, state);
  assert.deepEqual(view.onion, [0, 0]);
  assert.equal(lines.length, 4);
});
