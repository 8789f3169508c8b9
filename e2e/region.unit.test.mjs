// Unit tests of region.js, the page's exact reachable region (no browser, no server): the
// winding number with arcs, the nearest point, the area and the path drawn, on shapes whose
// answers are known (an annulus, a quarter disk, a three-quarter disk, a hole), and against
// the Rust library's own answers for the seed arm with its limits (e2e/fixtures/seed-reach.json:
// its Region's boundary, area and verdicts for 200 points; see that file's `made_by`). Run by e2e/run and .ci/run:
//   node --test e2e/region.unit.test.mjs
import { test } from "node:test";
import assert from "node:assert/strict";
import { existsSync, readFileSync } from "node:fs";
import { dirname, join } from "node:path";
import { fileURLToPath } from "node:url";
import {
  formatDistance,
  nearestOnBoundary,
  regionArea,
  regionOf,
  traceCurves,
  traceRegion,
  unreachableText,
  verdict,
  winding,
} from "../crates/ikarus-cli/src/serve/assets/region.js";
import { svgContext } from "../crates/ikarus-cli/src/serve/assets/export.js";
import { fitView } from "../crates/ikarus-cli/src/serve/assets/view.js";

const near = (a, b, tol = 1e-12) => assert.ok(Math.abs(a - b) <= tol, `${a} vs ${b} (tolerance ${tol})`);
const nearPoint = (p, q, tol = 1e-12) => assert.ok(Math.hypot(p[0] - q[0], p[1] - q[1]) <= tol, `[${p}] vs [${q}] (tolerance ${tol})`);

const arc = (center, radius, from_deg, to_deg) => ({ arc: { center, radius, from_deg, to_deg } });
const line = (a, b) => ({ line: [a, b] });

// The region of two free links 4 and 2: the annulus 2 ≤ r ≤ 6 (outer counter-clockwise, hole clockwise).
const ANNULUS = [[arc([0, 0], 6, 0, 360)], [arc([0, 0], 2, 90, -270)]];
// The quarter disk of radius 2 in the first quadrant.
const QUARTER = [[line([0, 0], [2, 0]), arc([0, 0], 2, 0, 90), line([0, 2], [0, 0])]];
// Three quarters of the unit disk: the "mouth" is the fourth quadrant (an arc of 270°).
const PACMAN = [[line([0, 0], [1, 0]), arc([0, 0], 1, 0, 270), line([0, -1], [0, 0])]];

test("the annulus: inside the ring, not in the hole or beyond; its area; the nearest points", () => {
  const r = regionOf(ANNULUS);
  assert.equal(winding(r, [4, 0]), 1);
  assert.equal(winding(r, [0, -3]), 1);
  assert.equal(winding(r, [0, 0]), 0, "the hole");
  assert.equal(winding(r, [1.5, 0.5]), 0, "the hole");
  assert.equal(winding(r, [7, 0]), 0);
  assert.equal(winding(r, [-4.5, -4.5]), 0);
  near(regionArea(r), Math.PI * (36 - 4), 1e-12);
  assert.deepEqual(r.bbox, { x0: -6, y0: -6, x1: 6, y1: 6 });

  const hole = verdict(r, [0.5, 0]);
  assert.equal(hole.reachable, false);
  near(hole.distance, 1.5);
  nearPoint(hole.nearest, [2, 0]);
  const beyond = verdict(r, [0, -10]);
  near(beyond.distance, 4);
  nearPoint(beyond.nearest, [0, -6]);
  assert.deepEqual(verdict(r, [3, 3]), { reachable: true, distance: 0, nearest: [3, 3] });
  // Within the tolerance of the boundary counts as reachable, with the distance still told.
  const edge = verdict(r, [6 + 1e-7, 0], 1e-6);
  assert.equal(edge.reachable, true);
  near(edge.distance, 1e-7, 1e-12);
});

test("the quarter disk: the arc's circular segment counts, the corners are nearest from outside", () => {
  const r = regionOf(QUARTER);
  near(regionArea(r), Math.PI, 1e-12);
  assert.equal(winding(r, [0.5, 0.5]), 1);
  // Beyond the chord x + y = 2 but inside the circle: only the arc's segment holds it.
  assert.equal(winding(r, [1.3, 1.3]), 1);
  assert.equal(winding(r, [1.5, 1.5]), 0, "outside the circle");
  assert.equal(winding(r, [-0.1, 0.5]), 0);
  assert.equal(winding(r, [0.5, -0.1]), 0);
  const cases = [
    // point, nearest, distance
    [[-1, -1], [0, 0], Math.SQRT2],
    [[2, 2], [Math.SQRT2, Math.SQRT2], 2 * Math.SQRT2 - 2],
    [[3, -1], [2, 0], Math.SQRT2],
    [[1, -1], [1, 0], 1],
    [[-0.5, 1], [0, 1], 0.5],
    [[0, 5], [0, 2], 3],
  ];
  for (const [p, nearest, distance] of cases) {
    const v = verdict(r, p);
    assert.equal(v.reachable, false, `${p}`);
    nearPoint(v.nearest, nearest, 1e-12);
    near(v.distance, distance, 1e-12);
  }
  assert.deepEqual(r.bbox, { x0: 0, y0: 0, x1: 2, y1: 2 });
});

test("an arc of more than a half turn, and a loop walked clockwise (a hole) winds −1", () => {
  const r = regionOf(PACMAN);
  near(regionArea(r), (3 * Math.PI) / 4, 1e-12);
  for (const p of [[-0.5, 0.5], [-0.5, -0.5], [0.5, 0.5], [-0.9, 0], [0, 0.9]]) assert.equal(winding(r, p), 1, `${p}`);
  for (const p of [[0.5, -0.5], [0.1, -0.1], [1.1, 0], [0, -1.1]]) assert.equal(winding(r, p), 0, `${p}`);
  const mouth = verdict(r, [0.5, -0.3]);
  near(mouth.distance, 0.3);
  nearPoint(mouth.nearest, [0.5, 0]);

  // The quarter disk walked backwards: the same loop, clockwise.
  const reversed = regionOf([
    [line([0, 0], [0, 2]), arc([0, 0], 2, 90, 0), line([2, 0], [0, 0])],
  ]);
  assert.equal(winding(reversed, [0.5, 0.5]), -1);
  assert.equal(winding(reversed, [1.3, 1.3]), -1);
  near(regionArea(reversed), -Math.PI, 1e-12);
});

test("membership agrees with the shape's own test at random points", () => {
  let s = 12345;
  const random = () => (s = (s * 1103515245 + 12345) % 2147483648) / 2147483648;
  const quarter = regionOf(QUARTER);
  const annulus = regionOf(ANNULUS);
  const pacman = regionOf(PACMAN);
  for (let k = 0; k < 20000; k++) {
    const p = [8 * random() - 4, 8 * random() - 4];
    const q = [16 * random() - 8, 16 * random() - 8];
    const [x, y] = p;
    const rp = Math.hypot(x, y);
    const rq = Math.hypot(...q);
    // Far enough from the boundary for rounding not to matter.
    if (Math.min(Math.abs(x), Math.abs(y), Math.abs(rp - 2), Math.abs(rp - 1)) > 1e-9) {
      assert.equal(winding(quarter, p) !== 0, x > 0 && y > 0 && rp < 2, `quarter ${p}`);
      assert.equal(winding(pacman, p) !== 0, rp < 1 && !(x > 0 && y < 0), `pacman ${p}`);
    }
    if (Math.min(Math.abs(rq - 2), Math.abs(rq - 6)) > 1e-9) assert.equal(winding(annulus, q) !== 0, rq > 2 && rq < 6, `annulus ${q}`);
    // The nearest boundary point of the annulus is along the ray from the centre.
    const n = nearestOnBoundary(annulus, q);
    near(n.distance, Math.min(Math.abs(rq - 2), Math.abs(rq - 6)), 1e-12);
  }
});

test("the path: one subpath per loop, arcs as arc() with the canvas's angles, drawn as SVG arcs", () => {
  const calls = [];
  const pen = new Proxy({}, { get: (_, name) => (...args) => calls.push([name, ...args]) });
  const view = { cx: 100, cy: 100, scale: 10, w: 200, h: 200 };
  traceRegion(pen, view, regionOf(QUARTER));
  assert.deepEqual(calls[0], ["moveTo", 100, 100]);
  assert.deepEqual(calls[1], ["lineTo", 120, 100]);
  // World angles 0 → 90° counter-clockwise: canvas angles 0 → −π/2, anticlockwise.
  assert.equal(calls[2][0], "arc");
  assert.deepEqual(calls[2].slice(1, 4), [100, 100, 20]);
  near(calls[2][4], 0);
  near(calls[2][5], -Math.PI / 2);
  assert.equal(calls[2][6], true);
  assert.deepEqual(calls[3], ["lineTo", 100, 100]);
  assert.deepEqual(calls[4], ["closePath"]);

  calls.length = 0;
  traceRegion(pen, view, regionOf(ANNULUS));
  assert.deepEqual(calls.map((c) => c[0]), ["moveTo", "arc", "closePath", "moveTo", "arc", "closePath"]);
  assert.equal(calls[4][6], false, "the hole runs clockwise");

  // As SVG (export.js's recording context): elliptical arcs, the hole a full circle of two halves.
  const ctx = svgContext(200, 200);
  ctx.beginPath();
  traceRegion(ctx, fitView({ links: [{ length: 4 }, { length: 2 }] }, 200, 200), regionOf(ANNULUS));
  ctx.fill("nonzero");
  const d = /<path d="([^"]+)" fill="#000" fill-rule="nonzero"/.exec(ctx.svg())[1];
  assert.equal((d.match(/A/g) || []).length, 4, d);
  assert.equal((d.match(/Z/g) || []).length, 2, d);
  assert.ok(!d.includes("NaN"), d);
});

test("a region without area (one link with limits): only its curve is reachable, stroked as arcs", () => {
  // One link of length 2 turning from −45° to 90°: the arc it traces.
  const r = regionOf([], [arc([0, 0], 2, -45, 90)]);
  near(regionArea(r), 0);
  assert.equal(winding(r, [1, 0]), 0);
  const on = verdict(r, [0, 2], 1e-9);
  assert.equal(on.reachable, true);
  near(on.distance, 0, 1e-12);
  const off = verdict(r, [1, 0]);
  assert.equal(off.reachable, false);
  near(off.distance, 1);
  nearPoint(off.nearest, [2, 0]);
  // Past the arc's end: its end point.
  const past = verdict(r, [-3, 0]);
  nearPoint(past.nearest, [0, 2], 1e-12);
  near(past.distance, Math.hypot(3, 2));
  // Its box: from the top end (0, 2) and the start (√2, −√2) to the rightmost point (2, 0).
  near(r.bbox.x0, 0, 1e-12);
  near(r.bbox.y0, -Math.SQRT2, 1e-12);
  near(r.bbox.x1, 2, 1e-12);
  near(r.bbox.y1, 2, 1e-12);
  const calls = [];
  const pen = new Proxy({}, { get: (_, name) => (...args) => calls.push(name) });
  traceCurves(pen, { cx: 0, cy: 0, scale: 1 }, r);
  traceRegion(pen, { cx: 0, cy: 0, scale: 1 }, r);
  assert.deepEqual(calls, ["moveTo", "arc"]);
});

test("the chip's words for a goal out of reach", () => {
  assert.equal(unreachableText(0.8312), "unreachable · 0.83 from the reachable region");
  assert.equal(formatDistance(12.5), "12.50");
  assert.equal(formatDistance(0.0042), "0.0042");
  assert.equal(formatDistance(0), "0.00");
});

test("no boundary (an older server's answer): no region; no loops: nothing is reachable", () => {
  assert.equal(regionOf(undefined), null);
  const empty = regionOf([]);
  assert.equal(winding(empty, [0, 0]), 0);
  assert.deepEqual(verdict(empty, [0, 0]), { reachable: false, distance: Infinity, nearest: null });
});

// The Rust library's region of the seed arm with its limits and its verdicts for 200 points
// (reach::Region::of, boundary, area and verdict with tolerance 1e-6), written once by a
// throwaway program; `ikarus reach --batch` answers the same.
const here = dirname(fileURLToPath(import.meta.url));
const FIXTURE = join(here, "fixtures", "seed-reach.json");

test("the seed arm's region: the page's verdicts are the Rust library's", { skip: !existsSync(FIXTURE) && "no fixture" }, () => {
  const fx = JSON.parse(readFileSync(FIXTURE, "utf8"));
  const r = regionOf(fx.boundary);
  near(regionArea(r), fx.area, 1e-9 * fx.area);
  let outside = 0;
  for (const p of fx.points) {
    const v = verdict(r, [p.x, p.y], fx.tolerance);
    assert.equal(v.reachable, p.reachable, `(${p.x}, ${p.y})`);
    near(v.distance, p.distance, 1e-9);
    // The same nearest point, but where there are many (the centre of a boundary arc): there
    // both are at the distance.
    const centre = r.loops.flat().some((s) => s.arc && Math.hypot(s.arc.c[0] - p.x, s.arc.c[1] - p.y) < 1e-9);
    if (centre) near(Math.hypot(v.nearest[0] - p.x, v.nearest[1] - p.y), p.distance, 1e-9);
    else nearPoint(v.nearest, [p.nearest_x, p.nearest_y], 1e-9);
    if (!p.reachable) outside++;
  }
  assert.ok(outside >= 10 && fx.points.length - outside >= 10, `${outside} of ${fx.points.length} outside`);
});
