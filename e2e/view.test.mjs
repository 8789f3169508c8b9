// Unit tests of the playground's pure modules (no browser, no server): the geometry of view.js,
// and the small pure helpers of controls.js and files.js. Run by e2e/run and .ci/run:
//   node --test e2e/view.test.mjs
import { test } from "node:test";
import assert from "node:assert/strict";
import {
  AREA_RGBA,
  DRAG_PIXELS,
  areaPixels,
  areaRect,
  decimalsFor,
  fitView,
  forward,
  frameIndexAt,
  ghostFrames,
  gridValues,
  isDrag,
  maxReach,
  niceStep,
  nudge,
  toCanvas,
  toWorld,
} from "../crates/ikarus-cli/src/serve/assets/view.js";
import { armForRequest, withLimit } from "../crates/ikarus-cli/src/serve/assets/controls.js";
import { framesCsv } from "../crates/ikarus-cli/src/serve/assets/files.js";

const near = (a, b, tol = 1e-12) => assert.ok(Math.abs(a - b) <= tol, `${a} vs ${b} (tolerance ${tol})`);
const nearAll = (a, b, tol = 1e-12) => {
  assert.equal(a.length, b.length);
  a.forEach((v, i) => near(v, b[i], tol));
};

// The server's seed arm (GET /api/arm/default).
const SEED = {
  name: "seed",
  base: [0, 0],
  links: [
    { length: 3, angle_deg: 5, limits_deg: [-45, 45] },
    { length: 2, angle_deg: 5, limits_deg: [-90, 90] },
    { length: 1, angle_deg: 5, limits_deg: [-170, 170] },
  ],
};

test("forward kinematics: relative angles in degrees, base first", () => {
  const j = forward(SEED, [0, 90, -90]);
  assert.equal(j.length, 4);
  nearAll(j[0], [0, 0]);
  nearAll(j[1], [3, 0]);
  nearAll(j[2], [3, 2]);
  nearAll(j[3], [4, 2]);
  // A missing angle is the link's own; a base offsets every joint.
  const moved = forward({ ...SEED, base: [1, -1] }, []);
  const own = forward(SEED, [5, 5, 5]);
  moved.forEach((p, i) => nearAll(p, [own[i][0] + 1, own[i][1] - 1]));
});

test("reach sums the lengths, ignoring negative and unreadable ones", () => {
  assert.equal(maxReach(SEED), 6);
  assert.equal(maxReach({ links: [{ length: 2 }, { length: -1 }, { length: "x" }, { length: "0.5" }] }), 2.5);
});

test("the view centres the base and fits the reach with a margin into the shorter side", () => {
  const v = fitView(SEED, 1000, 800);
  near(v.scale, 800 / (2 * 6 * 1.12));
  nearAll(toCanvas(v, 0, 0), [500, 400]);
  // The reach circle touches neither edge of the shorter side.
  const [, top] = toCanvas(v, 0, 6);
  assert.ok(top > 0 && top < 400, `top of the reach at ${top}`);
  // y points up in the world, down on the canvas.
  assert.ok(toCanvas(v, 0, 1)[1] < toCanvas(v, 0, 0)[1]);
  const off = fitView({ ...SEED, base: [2, 3] }, 600, 600);
  nearAll(toCanvas(off, 2, 3), [300, 300]);
  // A degenerate arm still gives a finite view.
  assert.ok(Number.isFinite(fitView({ links: [{ length: 0 }] }, 100, 100).scale));
});

test("toWorld inverts toCanvas", () => {
  const v = fitView({ ...SEED, base: [0.5, -2] }, 913, 517);
  for (const [x, y] of [[0, 0], [2, 3], [-5.5, 1.25], [1e3, -1e-3]]) {
    nearAll(toWorld(v, ...toCanvas(v, x, y)), [x, y], 1e-9);
  }
  for (const [px, py] of [[0, 0], [913, 517], [17.5, 400]]) {
    nearAll(toCanvas(v, ...toWorld(v, px, py)), [px, py], 1e-9);
  }
});

test("grid steps are 1, 2 or 5 times a power of ten, six to fourteen per span", () => {
  for (const [span, step] of [[8, 1], [10, 1], [16, 2], [40, 5], [80, 10], [0.8, 0.1], [13.4, 2], [3000, 500]]) {
    near(niceStep(span), step, 1e-12 * step);
  }
  for (let span = 0.01; span < 1e4; span *= 1.37) {
    const n = span / niceStep(span);
    // 8·m/k for a mantissa m in [1, 10) and the k in {1, 2, 5, 10} it picks: 5.6 to 14 steps.
    assert.ok(n >= 5.6 - 1e-9 && n < 14 + 1e-9, `span ${span}: ${n} steps`);
  }
  assert.deepEqual(gridValues(-1.5, 2.2, 1), [-1, 0, 1, 2]);
  assert.deepEqual(gridValues(0.1, 0.9, 1), []);
  assert.equal(decimalsFor(1), 0);
  assert.equal(decimalsFor(5), 0);
  assert.equal(decimalsFor(0.5), 1);
  assert.equal(decimalsFor(0.1), 1);
  assert.equal(decimalsFor(0.02), 2);
});

test("a press becomes a drag past the threshold", () => {
  const press = { x: 100, y: 50 };
  assert.equal(isDrag(press, 100 + DRAG_PIXELS, 50), false);
  assert.equal(isDrag(press, 103, 53), true);
  assert.equal(isDrag(press, 100, 50), false);
});

test("arrow keys nudge the goal by a 40th of the reach; other keys do not", () => {
  const g = { x: 1, y: 2 };
  const step = 6 / 40;
  assert.deepEqual(nudge(SEED, g, "ArrowLeft"), { x: 1 - step, y: 2 });
  assert.deepEqual(nudge(SEED, g, "ArrowRight"), { x: 1 + step, y: 2 });
  assert.deepEqual(nudge(SEED, g, "ArrowUp"), { x: 1, y: 2 + step });
  assert.deepEqual(nudge(SEED, g, "ArrowDown"), { x: 1, y: 2 - step });
  assert.equal(nudge(SEED, g, "Enter"), null);
  assert.equal(nudge(SEED, g, "a"), null);
});

test("playback shows the last frame not after the time, never going back", () => {
  const frames = [0, 0.1, 0.25, 0.5, 1].map((time) => ({ time }));
  assert.equal(frameIndexAt(frames, 0), 0);
  assert.equal(frameIndexAt(frames, 0.1), 1);
  assert.equal(frameIndexAt(frames, 0.3), 2);
  assert.equal(frameIndexAt(frames, 5), 4);
  assert.equal(frameIndexAt(frames, 0, 3), 3);
  assert.equal(frameIndexAt([{ time: 0 }], 1), 0);
});

test("ghosts: about twelve over the motion, older ones fainter, none at the current frame", () => {
  const all = ghostFrames(61, 60);
  assert.deepEqual(all.map((g) => g.index), [0, 5, 10, 15, 20, 25, 30, 35, 40, 45, 50, 55]);
  for (let i = 1; i < all.length; i++) assert.ok(all[i].alpha > all[i - 1].alpha);
  near(all[0].alpha, 0.06);
  assert.ok(all.every((g) => g.alpha > 0 && g.alpha <= 0.22));
  assert.deepEqual(ghostFrames(61, 12).map((g) => g.index), [0, 5, 10]);
  assert.deepEqual(ghostFrames(61, 0), []);
  assert.deepEqual(ghostFrames(3, 2).map((g) => g.index), [0, 1]);
});

test("the reachable area: one pixel per cell, the lowest row at the bottom", () => {
  const ws = { resolution: 3, cell_size: 2, origin: [-3, -3], grid: ["100", "000", "011"] };
  const px = areaPixels(ws);
  assert.equal(px.length, 3 * 3 * 4);
  const at = (ix, py) => Array.from(px.slice((py * 3 + ix) * 4, (py * 3 + ix) * 4 + 4));
  assert.deepEqual(at(0, 2), AREA_RGBA); // grid[0][0]: bottom-left
  assert.deepEqual(at(1, 0), AREA_RGBA); // grid[2][1]: top row
  assert.deepEqual(at(2, 0), AREA_RGBA);
  assert.deepEqual(at(0, 0), [0, 0, 0, 0]);
  assert.deepEqual(at(1, 1), [0, 0, 0, 0]);
  assert.equal(px.filter((_, i) => i % 4 === 3 && px[i] > 0).length, 3);
  // Its picture covers [origin, origin + side] in world units, top-left corner first.
  const v = fitView(SEED, 800, 800);
  const [x, y, size] = areaRect(v, ws);
  nearAll([x, y], toCanvas(v, -3, 3));
  near(size, 6 * v.scale);
});

test("links: an empty limit field removes the limits; requests carry the arm file's fields only", () => {
  assert.equal(withLimit([-45, 45], 0, ""), null);
  assert.deepEqual(withLimit([-45, 45], 1, "30"), [-45, 30]);
  assert.deepEqual(withLimit(null, 0, "-10"), [-10, 180]);
  const lim = [-1, 1];
  withLimit(lim, 0, "5");
  assert.deepEqual(lim, [-1, 1], "the old limits are not changed in place");
  const arm = { name: "a", base: [0, 0], links: [{ length: 1, angle_deg: 2, limits_deg: null, rate: 3 }, { length: 2, angle_deg: 0, limits_deg: [-5, 5] }] };
  assert.deepEqual(armForRequest(arm), {
    name: "a",
    base: [0, 0],
    links: [{ length: 1, angle_deg: 2 }, { length: 2, angle_deg: 0, limits_deg: [-5, 5] }],
  });
});

test("frames as CSV: time, angles, then every joint's x and y", () => {
  const anim = {
    frames: [
      { time: 0, angles_deg: [0, 90], joints: [[0, 0], [1, 0], [1, 1]] },
      { time: 0.5, angles_deg: [10, 80], joints: [[0, 0], [0.98, 0.17], [0.5, 1.1]] },
    ],
  };
  assert.equal(
    framesCsv(anim),
    "time,angle1_deg,angle2_deg,x0,y0,x1,y1,x2,y2\n0,0,90,0,0,1,0,1,1\n0.5,10,80,0,0,0.98,0.17,0.5,1.1\n",
  );
  assert.equal(framesCsv({ frames: [] }), "time,x0,y0\n");
});
