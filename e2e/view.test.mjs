// Unit tests of the playground's pure modules (no browser, no server): the geometry of view.js,
// the paths of paths.js (stroke resampling, default shapes, a track as frames), and the small
// pure helpers of controls.js and files.js. Run by e2e/run and .ci/run:
//   node --test e2e/view.test.mjs
import { test } from "node:test";
import assert from "node:assert/strict";
import {
  DRAG_PIXELS,
  DURATION,
  areaOutline,
  autoDuration,
  boxesOverlap,
  decimalsFor,
  easeAt,
  fitView,
  forward,
  frameIndexAt,
  freeJoints,
  ghostFrames,
  glideFrames,
  gridValues,
  intoRange,
  isDrag,
  jointDistance,
  lerpAngle,
  maxReach,
  niceStep,
  nudge,
  placeLabels,
  poseAt,
  poseIntoLimits,
  shortDelta,
  toCanvas,
  toWorld,
  solveTime,
} from "../crates/ikarus-cli/src/serve/assets/view.js";
import { CHOSEN_DURATION, armForRequest, clampInto, methodApplies, numberProblem, withLimit } from "../crates/ikarus-cli/src/serve/assets/controls.js";
import { GIF_FPS, GIF_MAX_PIXELS, framesCsv, gifRequest, playedMotion, playedTrack, timesInSeconds } from "../crates/ikarus-cli/src/serve/assets/files.js";
import { forPeople } from "../crates/ikarus-cli/src/serve/assets/api.js";
import { svgContext } from "../crates/ikarus-cli/src/serve/assets/export.js";
import {
  STROKE_MAX_SAMPLES,
  flipTips,
  offPathRuns,
  polylineLength,
  resampleStroke,
  shapeDefaults,
  trackMotion,
  trackSeconds,
  trackStatus,
  trackSummaryText,
} from "../crates/ikarus-cli/src/serve/assets/paths.js";

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

/** A grid of `n` × `n` unit cells centred on the origin, reachable where `inside(x, y)` holds at the cell's centre. */
function gridOf(n, inside) {
  const grid = [];
  for (let j = 0; j < n; j++) {
    let row = "";
    for (let i = 0; i < n; i++) row += inside(i + 0.5 - n / 2, j + 0.5 - n / 2) ? "1" : "0";
    grid.push(row);
  }
  return { resolution: n, cell_size: 1, origin: [-n / 2, -n / 2], grid };
}

/** The area of a closed loop (shoelace), positive counter-clockwise. */
const loopArea = (loop) => loop.reduce((s, [x0, y0], k) => {
  const [x1, y1] = loop[(k + 1) % loop.length];
  return s + (x0 * y1 - x1 * y0) / 2;
}, 0);

/** The largest turn between two consecutive segments of a closed loop, degrees. */
function sharpestTurn(loop) {
  let worst = 0;
  for (let k = 0; k < loop.length; k++) {
    const [a, b, c] = [loop[k], loop[(k + 1) % loop.length], loop[(k + 2) % loop.length]];
    const t = Math.abs(Math.atan2((b[0] - a[0]) * (c[1] - b[1]) - (b[1] - a[1]) * (c[0] - b[0]), (b[0] - a[0]) * (c[0] - b[0]) + (b[1] - a[1]) * (c[1] - b[1])));
    worst = Math.max(worst, (t * 180) / Math.PI);
  }
  return worst;
}

test("the reachable area's edge: closed loops around it and its holes, smooth, where the cells end", () => {
  // A ring of radii 5 and 15 on a 40 × 40 grid: two loops, the outer one counter-clockwise
  // (the inside on its left) and the hole clockwise.
  const ws = gridOf(40, (x, y) => Math.hypot(x, y) < 15 && Math.hypot(x, y) > 5);
  const cells = ws.grid.join("").split("").filter((c) => c === "1").length;
  const loops = areaOutline(ws);
  assert.equal(loops.length, 2);
  const [outer, hole] = loops[0].length > loops[1].length ? loops : [loops[1], loops[0]];
  assert.ok(loopArea(outer) > 0 && loopArea(hole) < 0);
  for (const [x, y] of outer) assert.ok(Math.abs(Math.hypot(x, y) - 15) < 0.5, `outer edge at r = ${Math.hypot(x, y)}`);
  for (const [x, y] of hole) assert.ok(Math.abs(Math.hypot(x, y) - 5) < 0.5, `hole's edge at r = ${Math.hypot(x, y)}`);
  // Filled even-odd, the loops cover the cells' area (within the half cell the edge may move).
  const area = loopArea(outer) + loopArea(hole);
  assert.ok(Math.abs(area - cells) / cells < 0.03, `area ${area} of ${cells} cells`);
  // No staircase: the raw marching-squares edge turns by 45° at every cell corner; the drawn one
  // by far less.
  assert.ok(sharpestTurn(areaOutline(ws, 0)[0]) >= 45);
  assert.ok(sharpestTurn(outer) < 25, `a turn of ${sharpestTurn(outer)}°`);
  // Cells on the grid's border still close their loop; an empty grid has no edge.
  const full = areaOutline(gridOf(4, () => true));
  assert.equal(full.length, 1);
  for (const [x, y] of full[0]) assert.ok(Math.abs(x) <= 2 && Math.abs(y) <= 2);
  assert.deepEqual(areaOutline(gridOf(4, () => false)), []);
  // Rows go up: a cell of the lowest row gives an edge near the bottom.
  const low = areaOutline({ resolution: 3, cell_size: 2, origin: [-3, -3], grid: ["010", "000", "000"] }, 0)[0];
  for (const [x, y] of low) assert.ok(y <= -1 + 1e-9 && y >= -3 && Math.abs(x) <= 1, `${x}, ${y}`);
});

test("the reachable area's edge: the very points of the library's Workspace::outline (reach/outline.rs)", () => {
  // The same grid and the same numbers as outline.rs's test the_same_points_as_the_playground.
  const ws = { resolution: 3, cell_size: 0.5, origin: [1, -1], grid: ["010", "111", "010"] };
  const raw = areaOutline(ws, 0);
  assert.equal(raw.length, 1);
  assert.deepEqual(raw[0], [
    [1.5, -0.75], [1.75, -1], [2, -0.75], [2.25, -0.5], [2.5, -0.25], [2.25, 0],
    [2, 0.25], [1.75, 0.5], [1.5, 0.25], [1.25, 0], [1, -0.25], [1.25, -0.5],
  ]);
  const smooth = areaOutline(ws, 2);
  assert.equal(smooth[0].length, 48);
  assert.deepEqual(smooth[0].slice(0, 3), [[1.5986328125, -0.716796875], [1.6591796875, -0.736328125], [1.7197265625, -0.74609375]]);
});

test("links: an empty limit field opens that side and keeps the other; requests carry the arm file's fields only", () => {
  assert.deepEqual(withLimit([-45, 45], 0, ""), [-180, 45]);
  assert.deepEqual(withLimit([-45, 45], 1, ""), [-45, 180]);
  assert.equal(withLimit([-180, 45], 1, ""), null, "both sides open: no limits");
  assert.deepEqual(withLimit([-45, 45], 1, "30"), [-45, 30]);
  assert.deepEqual(withLimit(null, 0, "-10"), [-10, 180]);
  // A pose moves into a new range.
  assert.equal(clampInto(5, [10, 45]), 10);
  assert.equal(clampInto(50, [10, 45]), 45);
  assert.equal(clampInto(20, [10, 45]), 20);
  assert.equal(clampInto(200, null), 200);
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
    "time,theta1_deg,theta2_deg,x0,y0,x1,y1,x2,y2\n0,0,90,0,0,1,0,1,1\n0.5,10,80,0,0,0.98,0.17,0.5,1.1\n",
  );
  assert.equal(framesCsv({ frames: [] }), "time,x0,y0\n");
});

test("angles: the short way round for free joints, the straight line for limited ones", () => {
  assert.equal(shortDelta(170, -170), 20);
  assert.equal(shortDelta(-170, 170), -20);
  assert.equal(shortDelta(0, 180), 180, "an exact half turn goes counter-clockwise");
  assert.equal(shortDelta(0, -180), 180);
  assert.equal(shortDelta(10, 730), 0);
  assert.equal(shortDelta(359, 1), 2);
  near(lerpAngle(170, -170, 0.5, true), 180);
  near(lerpAngle(170, -170, 0.25, true), 175);
  near(lerpAngle(170, -170, 0.5, false), 0, 1e-12);
  near(lerpAngle(-40, 40, 0.75, false), 20);
  assert.equal(lerpAngle(12.5, 99, 0, true), 12.5);
  assert.deepEqual(freeJoints(SEED, true), [false, false, false]);
  assert.deepEqual(freeJoints(SEED, false), [true, true, true]);
  assert.deepEqual(freeJoints({ links: [{ limits_deg: [-1, 1] }, {}] }, true), [false, true]);
});

test("the pose between two frames: linear in time, exact on the frames", () => {
  // Five frames at 0, .25, .5, .75, 1 (as /api/animate with frames 5 answers).
  const frames = [0, 10, 40, 70, 80].map((a, k) => ({ time: k / 4, angles_deg: [a, -a, 170 + a / 8] }));
  const at = (u, free, from) => poseAt(frames, u, free, from);
  assert.deepEqual(at(0), { angles: [0, -0, 170], index: 0, w: 0 });
  assert.deepEqual(at(1), { angles: frames[4].angles_deg, index: 4, w: 0 });
  assert.deepEqual(at(0.5).angles, frames[2].angles_deg);
  const mid = at(0.125);
  assert.equal(mid.index, 0);
  near(mid.w, 0.5);
  nearAll(mid.angles, [5, -5, 170.625]);
  // Five frames play as a continuum, not as four steps: every u gives a new pose.
  const seen = new Set();
  for (let i = 0; i <= 40; i++) seen.add(at(i / 40).angles[0].toFixed(9));
  assert.equal(seen.size, 41);
  // Clamped outside [0, 1]; a hint past the playhead is walked back.
  assert.deepEqual(at(-1).angles, frames[0].angles_deg);
  assert.deepEqual(at(2).angles, frames[4].angles_deg);
  nearAll(at(0.375, [], 4).angles, [25, -25, 173.125]);
  assert.equal(at(0.375, [], 4).index, 1);
  // Frames in seconds (Timing::Duration) are scaled the same way.
  const secs = frames.map((f) => ({ ...f, time: f.time * 3 }));
  nearAll(poseAt(secs, 0.125).angles, [5, -5, 170.625]);
  // A free joint crossing ±180 between two frames takes the short way.
  const wrap = [{ time: 0, angles_deg: [170] }, { time: 1, angles_deg: [-170] }];
  near(poseAt(wrap, 0.5, [true]).angles[0], 180);
  near(poseAt(wrap, 0.5, [false]).angles[0], 0, 1e-12);
  // One frame: a still motion.
  assert.deepEqual(poseAt([{ time: 0, angles_deg: [3] }], 0.7).angles, [3]);
});

test("the default duration: 0.6 s plus 0.4 s per radian travelled, from 0.6 s to 4 s", () => {
  assert.deepEqual(DURATION, { base: 0.6, perRadian: 0.4, min: 0.6, max: 4 });
  assert.equal(autoDuration(0), 0.6);
  near(autoDuration(1), 1.0);
  near(autoDuration(2.5), 1.6);
  assert.equal(autoDuration(100), 4);
  assert.equal(autoDuration(-1), 0.6);
  assert.equal(autoDuration(NaN), 0.6);
  // The distance is the joint-space path length, in radians, frame to frame.
  const frames = [[0, 0, 0], [30, 0, 0], [30, 40, 0], [60, 80, 0]].map((a, k) => ({ time: k / 3, angles_deg: a }));
  near(jointDistance(frames), (30 + 40 + 50) * (Math.PI / 180), 1e-12);
  assert.equal(jointDistance(frames.slice(0, 1)), 0);
  // A 90° swing of all three seed joints: √3·π/2 rad, about 1.69 s.
  const swing = [{ time: 0, angles_deg: [0, 0, 0] }, { time: 1, angles_deg: [90, 90, 90] }];
  near(autoDuration(jointDistance(swing)), 0.6 + 0.4 * Math.sqrt(3) * (Math.PI / 2), 1e-12);
});

test("the ease's progress between the backend's samples: exact on them, linear between, clamped", () => {
  // An /api/ease answer's shape: {t, s} at evenly spaced times (here smoothstep's, 5 samples).
  const t = [0, 0.25, 0.5, 0.75, 1];
  const curve = { t, s: t.map((x) => x * x * (3 - 2 * x)) };
  t.forEach((x, i) => assert.equal(easeAt(curve, x), curve.s[i]));
  near(easeAt(curve, 0.125), curve.s[1] / 2, 1e-15);
  near(easeAt(curve, 0.6), curve.s[2] + 0.4 * (curve.s[3] - curve.s[2]), 1e-15);
  assert.equal(easeAt(curve, -2), 0);
  assert.equal(easeAt(curve, 3), 1);
  assert.equal(easeAt(curve, NaN), 0);
  // Two samples: a straight line.
  near(easeAt({ t: [0, 1], s: [0, 1] }, 0.3), 0.3, 1e-15);
});

test("a stroke is resampled at even arc lengths, ends kept, at most 200 samples", () => {
  // An L: 3 along x, then 1 up, drawn with uneven pointer spacing and a repeated point.
  const stroke = [[0, 0], [0.1, 0], [0.1, 0], [2.5, 0], [3, 0], [3, 0.2], [3, 1]];
  const path = resampleStroke(stroke, 0.5);
  assert.equal(path.length, 9, "4 / 0.5 + 1 samples");
  assert.deepEqual(path[0], [0, 0]);
  assert.deepEqual(path.at(-1), [3, 1]);
  for (let k = 1; k < path.length; k++) {
    near(Math.hypot(path[k][0] - path[k - 1][0], path[k][1] - path[k - 1][1]), 0.5, 1e-12);
  }
  nearAll(path[6], [3, 0]);
  nearAll(path[7], [3, 0.5]);
  // A long stroke is capped, evenly still; the input is not changed.
  const long = Array.from({ length: 1000 }, (_, i) => [i / 100, Math.sin(i / 100)]);
  const capped = resampleStroke(long, 0.001);
  assert.equal(capped.length, STROKE_MAX_SAMPLES);
  const spacing = polylineLength(long) / (STROKE_MAX_SAMPLES - 1);
  for (let k = 1; k < capped.length; k++) {
    const d = Math.hypot(capped[k][0] - capped[k - 1][0], capped[k][1] - capped[k - 1][1]);
    assert.ok(d <= spacing + 1e-12 && d > 0.97 * spacing, `step ${k}: ${d} vs ${spacing}`);
  }
  assert.equal(resampleStroke(long, 0.001, 10).length, 10);
  assert.deepEqual(long[0], [0, 0]);
  // A click, a stroke shorter than the spacing, and non-finite points are not paths.
  assert.equal(resampleStroke([[1, 1]], 0.1), null);
  assert.equal(resampleStroke([[1, 1], [1.05, 1]], 0.1), null);
  assert.equal(resampleStroke([[1, 1], [2, 1]], 0), null);
  assert.equal(resampleStroke([[1, 1], [NaN, 0], [2, 1]], 0.5).length, 3);
});

test("the default shapes sit in front of the arm, inside its reach", () => {
  const seed = { base: [0, 0], links: [{ length: 3, limits_deg: [-45, 45] }, { length: 2 }, { length: 1 }] };
  const d = shapeDefaults(seed);
  nearAll(d.figure8, [4.08, 0, 1.2]);
  nearAll(d.circle, [4.08, 0, 0.96]);
  nearAll(d.line, [4.08, -1.5, 4.08, 1.5]);
  // Every point of every shape is inside the reach, outside the base's neighbourhood.
  const reach = maxReach(seed);
  const [cx, cy, a] = d.figure8;
  for (let i = 0; i < 64; i++) {
    const t = (2 * Math.PI * i) / 64;
    const r = Math.hypot(cx + a * Math.cos(t), cy + a * Math.sin(t) * Math.cos(t));
    assert.ok(r < 0.9 * reach && r > 0.4 * reach, `figure-8 at ${r}`);
  }
  // The middle of the first joint's range sets the direction; without limits, along x.
  const up = { base: [1, 2], links: [{ length: 2, limits_deg: [60, 120] }, { length: 2 }] };
  nearAll(shapeDefaults(up).circle, [1, 2 + 0.68 * 4, 0.64]);
  nearAll(shapeDefaults(up, false).circle, [1 + 0.68 * 4, 2, 0.64]);
  const [x0, y0, x1, y1] = shapeDefaults(up).line;
  near(y0, y1);
  near(Math.hypot(x1 - x0, y1 - y0), 2);
});

test("a /api/track answer becomes frames, flips, a status and a summary", () => {
  const sample = (status, a, tip) => ({ goal: tip, status, error: 0, angles_deg: [a, 0], joints: [[0, 0], [1, 0], tip], step_deg: 0 });
  const answer = {
    arm: "two",
    mode: "plan",
    samples: [sample("reached", 0, [2, 0]), sample("reached", 30, [1.7, 1]), sample("unreachable", 180, [-2, 0])],
    summary: { samples: 3, reached: 2, limited: 0, flips: 1, flip_samples: [2], max_step_deg: 150, max_error: 0.5 },
  };
  const m = trackMotion(answer);
  assert.deepEqual(m.frames.map((f) => f.time), [0, 0.5, 1]);
  assert.deepEqual(m.frames[1].angles_deg, [30, 0]);
  assert.deepEqual(m.frames[2].joints.at(-1), [-2, 0]);
  assert.deepEqual(flipTips(answer), [[-2, 0]]);
  assert.equal(trackStatus(answer), "unreachable");
  assert.equal(trackStatus({ samples: answer.samples.slice(0, 2) }), "reached");
  assert.equal(trackSummaryText(answer), "plan · 2 of 3 reached · 1 flip · largest step 150.0° · error 5.00e-1");
  near(trackSeconds(answer), 1);
  near(trackSeconds({ samples: new Array(120) }), 4.8);
  assert.deepEqual(trackMotion({ ...answer, samples: answer.samples.slice(0, 1) }).frames.map((f) => f.time), [0]);
});

test("fields: a bad value is named with its rule; server messages number links from 1", () => {
  const restarts = { whole: true, min: 0, max: 64 };
  assert.equal(numberProblem("-3", restarts), "must be a whole number from 0 to 64");
  assert.equal(numberProblem("2.5", restarts), "must be a whole number from 0 to 64");
  assert.equal(numberProblem("", restarts), "must be a whole number from 0 to 64");
  assert.equal(numberProblem("abc", { above: 0 }), "must be a number > 0");
  assert.equal(numberProblem("0", { above: 0 }), "must be a number > 0");
  assert.equal(numberProblem("16", restarts), null);
  assert.equal(numberProblem("1e-6", { above: 0 }), null);
  assert.equal(
    forPeople("arm: links[0].angle_deg = 5: outside limits_deg [10, 45]"),
    "arm: link 1 angle_deg = 5: outside limits_deg [10, 45]",
  );
  assert.equal(forPeople("start_deg[2]: not a number"), "joint 3 angle: not a number");
  assert.equal(
    forPeople("start_deg: joint 1 at 73.6° lies outside its limits [-45°, 45°]"),
    "start pose: joint 1 at 73.6° lies outside its limits [-45°, 45°]",
  );
  assert.equal(forPeople("options.rates[1] = -1: must be > 0"), "options.joint 2 rate = -1: must be > 0");
});

test("methods: the closed form only for two links, or three with a goal angle", () => {
  const analytic = { name: "analytic", shapes: [[2, false], [3, true]] };
  const lm = { name: "lm" };
  assert.ok(methodApplies(analytic, 2, false));
  assert.ok(methodApplies(analytic, 3, true));
  assert.ok(!methodApplies(analytic, 3, false));
  assert.ok(!methodApplies(analytic, 2, true));
  assert.ok(!methodApplies(analytic, 7, false));
  assert.ok(methodApplies(lm, 7, true));
});

test("the GIF asks for the page's playback duration (less the last frame's delay) at 4 hundredths a frame", () => {
  assert.equal(100 / GIF_FPS, 4, "a whole number of hundredths per frame");
  const look = { width: 900, height: 620, workspace: true, grid: null, traces: true, ghosts: false };
  const req = gifRequest({ arm: {}, goal: { x: 1, y: 2 }, frames: 60, ease: { kind: "sine" } }, 1.35, look);
  assert.equal(req.frames, undefined);
  // The last frame is shown for a delay too: the motion takes one delay less than the playback.
  assert.deepEqual([req.figure, req.format, req.duration, req.fps], ["motion", "gif", 1.35 - 0.04, GIF_FPS]);
});

test("the GIF asks for the screen's picture: the canvas's size, scaled to the pixel cap, and its layers", () => {
  const motion = { arm: {}, goal: { x: 1, y: 2 }, options: { limits: true } };
  const look = { width: 900, height: 620, workspace: true, grid: null, traces: true, ghosts: false };
  const req = gifRequest(motion, 1.25, look);
  assert.deepEqual([req.width, req.height, req.workspace, req.traces, req.ghosts], [900, 620, true, true, false]);
  assert.equal(req.grid, undefined, "the exact region: no grid fields");
  // The sampled grid the screen shows, at its resolution.
  const grid = gifRequest(motion, 1.25, { ...look, grid: 160 });
  assert.deepEqual([grid.grid, grid.resolution], [true, 160]);
  // A long motion: scaled down to the server's cap, the aspect kept.
  const long = gifRequest(motion, 400, look);
  const frames = Math.round(long.duration * GIF_FPS) + 1;
  assert.ok(frames * long.width * long.height <= GIF_MAX_PIXELS, `${frames} × ${long.width} × ${long.height}`);
  near(long.width / long.height, 900 / 620, 0.02); // within a pixel of rounding
  // Never outside the server's sides.
  const huge = gifRequest(motion, 1, { ...look, width: 9000, height: 100 });
  assert.ok(huge.width <= 4096 && huge.height >= 16, `${huge.width} × ${huge.height}`);
});

test("a plan's off-path poses: runs from the sample before to the sample after, in the summary, not the status", () => {
  const pose = (status, tip) => ({ goal: [0, 0], status, error: 0, angles_deg: [0, 0], joints: [[0, 0], [1, 0], tip], step_deg: 0 });
  const answer = {
    arm: "two",
    mode: "plan",
    samples: [pose("reached", [2, 0]), pose("off_path", [1, 1]), pose("off_path", [0, 2]), pose("reached", [-2, 0]), pose("unreachable", [-1, -1])],
    summary: { samples: 3, reached: 2, limited: 0, off_path: 2, flips: 0, flip_samples: [], max_step_deg: 10, max_error: 0.5 },
  };
  assert.deepEqual(offPathRuns(answer), [[[2, 0], [1, 1], [0, 2], [-2, 0]]]);
  assert.deepEqual(offPathRuns({ samples: answer.samples.slice(0, 1) }), []);
  assert.equal(trackStatus(answer), "unreachable");
  assert.equal(trackStatus({ samples: answer.samples.slice(0, 4) }), "reached");
  assert.equal(trackSummaryText(answer), "plan · 2 of 3 reached · 2 off path · 0 flips · largest step 10.0° · error 5.00e-1");
});

test("the SVG download records the canvas calls: paths, arcs, text, alpha and dashes", () => {
  const ctx = svgContext(100, 50);
  ctx.fillStyle = "#ffffff";
  ctx.fillRect(0, 0, 100, 50);
  ctx.beginPath();
  ctx.moveTo(10, 10);
  ctx.lineTo(20, 30);
  ctx.setLineDash([6, 5]);
  ctx.strokeStyle = "#5f9e77";
  ctx.lineWidth = 1.5;
  ctx.stroke();
  ctx.setLineDash([]);
  ctx.beginPath();
  ctx.arc(50, 25, 10, 0, 2 * Math.PI);
  ctx.globalAlpha = 0.5;
  ctx.fillStyle = "#d62728";
  ctx.fill("evenodd");
  ctx.globalAlpha = 1;
  ctx.beginPath();
  ctx.arc(0, 0, 10, 0, Math.PI / 2);
  ctx.stroke();
  ctx.textAlign = "center";
  ctx.fillText("a<b", 5, 5);
  const svg = ctx.svg();
  assert.match(svg, /^<svg xmlns="http:\/\/www.w3.org\/2000\/svg" width="100" height="50"/);
  assert.match(svg, /<rect x="0" y="0" width="100" height="50" fill="#ffffff"\/>/);
  assert.match(svg, /<path d="M10 10L20 30" fill="none" stroke="#5f9e77" stroke-width="1.5"[^>]*stroke-dasharray="6 5"\/>/);
  assert.match(svg, /<path d="M60 25A10 10 0 1 1 40 25A10 10 0 1 1 60 25" fill="#d62728" fill-rule="evenodd" opacity="0.5"\/>/);
  assert.match(svg, /<path d="M10 0A10 10 0 0 1 0 10" fill="none"/);
  assert.match(svg, /text-anchor="middle"[^>]*>a&lt;b<\/text>/);
});

test("a solve's time: three places of ms; under the static build's coarse clock a zero reads < 0.1 ms", () => {
  assert.equal(solveTime(12), "0.012 ms");
  assert.equal(solveTime(0), "0.000 ms");
  const before = globalThis.document;
  globalThis.document = { body: { dataset: { backend: "wasm" } } };
  try {
    assert.equal(solveTime(0), "< 0.1 ms");
    assert.equal(solveTime(200), "0.200 ms");
  } finally {
    if (before === undefined) delete globalThis.document;
    else globalThis.document = before;
  }
});

test("limits turned on: each joint to the nearest angle its range allows, on the circle", () => {
  assert.equal(intoRange(73.6, [-45, 45]), 45);
  assert.equal(intoRange(-50, [-45, 45]), -45);
  assert.equal(intoRange(30, [-45, 45]), 30);
  assert.equal(intoRange(30, null), 30);
  // A 360°-equivalent inside is the same place: 370° in [0°, 45°] is 10°.
  assert.equal(intoRange(370, [0, 45]), 10);
  assert.equal(intoRange(-350, [0, 45]), 10);
  // The bound the shorter way round: 170° is 125° from 45° and 145° from −45°.
  assert.equal(intoRange(170, [-45, 45]), 45);
  assert.equal(intoRange(-170, [-45, 45]), -45);
  assert.equal(intoRange(-100, [10, 45]), 10);
  // The seed arm after a click on (−2, 3) without limits: joints 1 and 2 move, joint 3 does not.
  const { pose, moved } = poseIntoLimits(SEED, [73.6, 97.4, 23.8]);
  assert.deepEqual(pose, [45, 90, 23.8]);
  assert.deepEqual(moved, [
    { joint: 1, from: 73.6, to: 45 },
    { joint: 2, from: 97.4, to: 90 },
  ]);
  assert.deepEqual(poseIntoLimits(SEED, [5, 5, 365]), { pose: [5, 5, 5], moved: [] });
});

test("the glide into range: eased frames from the pose to the pose in range, the joints' positions with them", () => {
  // The sine ease at five times, as /api/ease sends it.
  const sine = { t: [0, 0.25, 0.5, 0.75, 1], s: [0, 0.14644660940672624, 0.5, 0.8535533905932737, 1] };
  const frames = glideFrames(SEED, [73.6, 97.4, 23.8], [45, 90, 23.8], sine);
  assert.equal(frames.length, 5);
  nearAll(frames.map((f) => f.time), [0, 0.25, 0.5, 0.75, 1]);
  nearAll(frames[0].angles_deg, [73.6, 97.4, 23.8], 1e-12);
  assert.deepEqual(frames[4].angles_deg, [45, 90, 23.8]);
  near(frames[2].angles_deg[0], (73.6 + 45) / 2, 1e-12);
  // Sine: slow at the ends.
  assert.ok(frames[1].angles_deg[0] > 73.6 - (73.6 - 45) / 4);
  assert.deepEqual(frames[4].joints, forward(SEED, [45, 90, 23.8]));
  // The short way round for a free joint: 170° to −170° through 180°.
  const free = { links: [{ length: 1, angle_deg: 0 }] };
  near(glideFrames(free, [170], [-170], { t: [0, 0.5, 1], s: [0, 0.5, 1] })[1].angles_deg[0], -180, 1e-12);
});

test("downloads carry the seconds played: times scaled to the playback's duration", () => {
  const frames = [0, 0.5, 1].map((time, k) => ({ time, angles_deg: [k], joints: [[0, 0], [1, k]] }));
  nearAll(timesInSeconds(frames, 1.25), [0, 0.625, 1.25]);
  assert.deepEqual(timesInSeconds([{ time: 0 }], 2), [0]);
  const anim = { arm: "seed", duration: 1, frames };
  const played = playedMotion(anim, 1.25);
  assert.equal(played.duration, 1.25);
  assert.equal(played.frames.at(-1).time, 1.25);
  assert.equal(anim.frames.at(-1).time, 1, "the motion itself is left as it is");
  assert.equal(framesCsv(played).trim().split("\n").at(-1).split(",")[0], "1.25");
  // A traced path of 200 samples at 25 a second: 8 s, each sample's time first.
  const samples = Array.from({ length: 200 }, (_, k) => ({ goal: [k, 0], status: "reached" }));
  const track = playedTrack({ mode: "plan", samples }, samples.map((_, k) => ({ time: k / 199 })), 8);
  assert.equal(track.duration, 8);
  assert.deepEqual(Object.keys(track.samples[0]), ["time", "goal", "status"]);
  assert.equal(track.samples.at(-1).time, 8);
  near(track.samples[1].time, 8 / 199);
});

test("the duration field: a tenth of a second to a minute", () => {
  const rule = { min: CHOSEN_DURATION.min, max: CHOSEN_DURATION.max };
  assert.equal(numberProblem("-2", rule), "must be a number from 0.1 to 60");
  assert.equal(numberProblem("1000", rule), "must be a number from 0.1 to 60");
  assert.equal(numberProblem("0", rule), "must be a number from 0.1 to 60");
  assert.equal(numberProblem("2.5", rule), null);
  assert.equal(numberProblem("60", rule), null);
});

test("axis labels: the first place clear of the page's boxes and of the labels before, or none", () => {
  assert.ok(boxesOverlap({ x: 0, y: 0, w: 10, h: 10 }, { x: 9, y: 9, w: 5, h: 5 }));
  assert.ok(!boxesOverlap({ x: 0, y: 0, w: 10, h: 10 }, { x: 10, y: 0, w: 5, h: 5 }));
  assert.ok(boxesOverlap({ x: 0, y: 0, w: 10, h: 10 }, { x: 11, y: 0, w: 5, h: 5 }, 2));
  const chip = { x: 8, y: 8, w: 300, h: 40 };
  const placed = placeLabels(
    [
      { text: "x", places: [{ x: 590, y: 280, w: 7, h: 12 }] },
      // Under the x name: left out.
      { text: "8", places: [{ x: 588, y: 284, w: 7, h: 12 }] },
      // Under the chip: its next place.
      { text: "6", places: [{ x: 290, y: 20, w: 7, h: 12 }, { x: 300, y: 20, w: 7, h: 12 }, { x: 310, y: 20, w: 7, h: 12 }] },
      // Off the canvas: left out.
      { text: "-8", places: [{ x: -3, y: 300, w: 11, h: 12 }] },
      { text: "2", places: [{ x: 400, y: 300, w: 7, h: 12 }] },
    ],
    [chip],
    600,
    600,
  );
  assert.deepEqual(
    placed.map((l) => [l.text, l.x]),
    [
      ["x", 590],
      ["6", 310],
      ["2", 400],
    ],
  );
});
