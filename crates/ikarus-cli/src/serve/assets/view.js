// Pure geometry of the playground: forward kinematics in degrees, the world <-> canvas transform,
// grid steps, the drag threshold, keyboard nudges, playback (the pose between two frames, the
// default duration, the ease's progress between the backend's samples), ghost timing, and the smooth edge of the reachable area. No DOM and no state of its own: every function takes what it reads and
// returns a new value, so node can test it (e2e/view.test.mjs).
//
// World: x to the right, y up, in arm units. Canvas: CSS pixels, x to the right, y down.

import { DEG, bodyForward, chainBody } from "./body.js";

export { DEG };

/**
 * A solve's time (`solve_us`) for the chip: milliseconds to three places. In the static build
 * the time is read from the browser's clock, which Chromium coarsens to 0.1 ms on a page that is
 * not cross-origin isolated: a quicker solve reads 0, shown as "< 0.1 ms" rather than "0.000 ms".
 */
export function solveTime(us) {
  const coarse = globalThis.document?.body?.dataset.backend === "wasm";
  return coarse && us < 100 ? "< 0.1 ms" : `${(us / 1000).toFixed(3)} ms`;
}

/** A pointer press becomes a drag once it has moved this many CSS pixels. */
export const DRAG_PIXELS = 4;

/** The view spans the arm's reach times this margin in its shorter direction. */
export const VIEW_MARGIN = 1.12;

/**
 * Joint positions [[x, y], …], base first, of `pose` (degrees, relative; a missing angle is the
 * link's own): the base and each link's tip, from the one forward kinematics (body.js).
 */
export function forward(arm, pose) {
  const [bx, by] = arm.base || [0, 0];
  return [[bx, by], ...bodyForward(chainBody(arm), pose).tips];
}

/** The sum of the link lengths (a negative or unreadable length counts as 0). */
export function maxReach(arm) {
  return arm.links.reduce((s, l) => s + Math.max(0, Number(l.length) || 0), 0);
}

/**
 * The transform that centres the arm's base in a `w` × `h` canvas and fits its reach (with a
 * margin) into the shorter side: canvas = (cx + x·scale, cy − y·scale).
 */
export function fitView(arm, w, h) {
  const [bx, by] = arm.base || [0, 0];
  const half = Math.max(maxReach(arm), 1e-3) * VIEW_MARGIN;
  const scale = Math.min(w, h) / (2 * half);
  return { cx: w / 2 - bx * scale, cy: h / 2 + by * scale, scale, w, h };
}

/**
 * The transform that fits the world box {x0, x1, y0, y1} with `room` world units around it into
 * a `w` × `h` canvas, centred: canvas = (cx + x·scale, cy − y·scale).
 */
export function fitBox({ x0, x1, y0, y1 }, room, w, h) {
  const halfW = (x1 - x0) / 2 + room;
  const halfH = (y1 - y0) / 2 + room;
  const scale = Math.min(w / (2 * halfW), h / (2 * halfH));
  const [mx, my] = [(x0 + x1) / 2, (y0 + y1) / 2];
  return { cx: w / 2 - mx * scale, cy: h / 2 + my * scale, scale, w, h };
}

/** Canvas pixels of the world point (x, y). */
export const toCanvas = (view, x, y) => [view.cx + x * view.scale, view.cy - y * view.scale];

/** The world point under the canvas pixel (px, py); the inverse of `toCanvas`. */
export const toWorld = (view, px, py) => [(px - view.cx) / view.scale, (view.cy - py) / view.scale];

/** A grid step of 1, 2 or 5 times a power of ten giving about eight lines over `span`. */
export function niceStep(span) {
  const raw = span / 8;
  const p = 10 ** Math.floor(Math.log10(raw));
  const m = raw / p;
  return (m < 1.5 ? 1 : m < 3.5 ? 2 : m < 7.5 ? 5 : 10) * p;
}

/** The multiples of `step` from `lo` to `hi` (accumulated by addition, as the grid is drawn). */
export function gridValues(lo, hi, step) {
  const values = [];
  for (let v = Math.ceil(lo / step) * step; v <= hi; v += step) values.push(v);
  return values;
}

/** Decimals needed to print multiples of `step` (0 for steps of 1 and more). */
export function decimalsFor(step) {
  return Math.max(0, -Math.floor(Math.log10(step) + 1e-9));
}

/** Whether two boxes {x, y, w, h} (canvas pixels) overlap, each grown by `pad` pixels. */
export function boxesOverlap(a, b, pad = 0) {
  return a.x - pad < b.x + b.w && b.x - pad < a.x + a.w && a.y - pad < b.y + b.h && b.y - pad < a.y + a.h;
}

/** Whether box `b` lies inside the `w` × `h` canvas and clear of every box of `keepOut`. */
export function inClear(b, keepOut, w, h) {
  return b.x >= 0 && b.y >= 0 && b.x + b.w <= w && b.y + b.h <= h && !keepOut.some((k) => boxesOverlap(b, k));
}

/** The room kept between two labels, pixels. */
export const LABEL_GAP = 2;

/**
 * Places the axis labels: each candidate ({text, places}: boxes {x, y, w, h} where it may go,
 * the preferred first) goes in the first of its places that lies inside the `w` × `h` canvas and
 * clear of `keepOut` (boxes the page lays over the canvas: the status chip, the hint) and of
 * the labels placed before it (earlier candidates win: the axis names first), else is left
 * out. Returns the labels placed, [{text, x, y, w, h}].
 */
export function placeLabels(candidates, keepOut, w, h) {
  const placed = [];
  const free = (b) => inClear(b, keepOut, w, h) && !placed.some((p) => boxesOverlap(b, p, LABEL_GAP));
  for (const c of candidates) {
    const box = c.places.find(free);
    if (box) placed.push({ text: c.text, ...box });
  }
  return placed;
}

/** Whether the pointer at (x, y) has moved far enough from the press to be a drag. */
export function isDrag(press, x, y) {
  return Math.hypot(x - press.x, y - press.y) > DRAG_PIXELS;
}

const NUDGES = { ArrowLeft: [-1, 0], ArrowRight: [1, 0], ArrowUp: [0, 1], ArrowDown: [0, -1] };

/** The goal moved by one keyboard step (a 40th of the reach) for an arrow key, else null. */
export function nudge(arm, goal, key) {
  const d = NUDGES[key];
  if (!d) return null;
  const step = maxReach(arm) / 40;
  return { x: goal.x + d[0] * step, y: goal.y + d[1] * step };
}

/** The index of the frame shown at motion time `t`: the last one whose time is not after `t`, from `from` on. */
export function frameIndexAt(frames, t, from = 0) {
  let i = from;
  while (i < frames.length - 1 && frames[i + 1].time <= t) i++;
  return i;
}

/**
 * `b − a` (degrees) moved by whole turns into (−180, 180]: the short way from a to b, an exact
 * half turn counter-clockwise (as the library unwraps free joints).
 */
export function shortDelta(a, b) {
  const d = b - a;
  return d - 360 * Math.ceil((d - 180) / 360);
}

/**
 * The angle a fraction `w` of the way from `a` to `b` (degrees): along the straight line for a
 * joint with limits (its range is an interval, the line stays inside it), the short way round
 * for a free one.
 */
export function lerpAngle(a, b, w, free) {
  return a + w * (free ? shortDelta(a, b) : b - a);
}

/**
 * The angle nearest `angle` (degrees) that `limits` ([min, max] degrees, or null for none)
 * allows, on the circle: `angle` itself if it lies inside, else its 360°-equivalent inside
 * nearest it (370° in [0°, 45°] is 10°), else the bound it is the shorter way round from (73.6°
 * in [−45°, 45°] is 45°; 170° is 45°, 125° away, not −45°, 145° away the other way).
 */
export function intoRange(angle, limits) {
  if (!limits || !Number.isFinite(angle)) return angle;
  const [lo, hi] = limits;
  if (lo <= angle && angle <= hi) return angle;
  // The equivalent just above lo (every equivalent inside lies from there on).
  const first = lo + (((angle - lo) % 360) + 360) % 360;
  if (first <= hi) return first;
  return Math.abs(shortDelta(angle, lo)) <= Math.abs(shortDelta(angle, hi)) ? lo : hi;
}

/**
 * `pose` (degrees, one per link) brought inside the links' limits (intoRange per joint):
 * {pose, moved}, `moved` listing each joint that had to move, {joint (from 1), from, to}, where
 * `from` is the angle as it stood. A joint whose 360°-equivalent lies inside is not moved (the
 * arm stands the same) but takes that equivalent, as the server would.
 */
export function poseIntoLimits(arm, pose) {
  const moved = [];
  const inside = arm.links.map((link, i) => {
    const a = pose[i] ?? link.angle_deg;
    const b = intoRange(a, link.limits_deg);
    if (Math.abs(shortDelta(a, b)) > 1e-9) moved.push({ joint: i + 1, from: a, to: b });
    return b;
  });
  return { pose: inside, moved };
}

/**
 * A short motion from pose `a` to pose `b` (degrees) as frames the timeline plays, one per sample
 * of `curve` (an /api/ease answer, {t, s}: the backend's ease at evenly spaced times): frame k at
 * time t[k], each joint turned the short way from its angle in `a` to its angle in `b` by the
 * progress s[k], with the joints' positions; the last frame is `b` exactly.
 */
export function glideFrames(arm, a, b, curve) {
  const n = curve.s.length;
  return curve.s.map((s, k) => {
    const angles = b.map((to, i) => (k === n - 1 ? to : to - (1 - s) * shortDelta(a[i], to)));
    return { time: curve.t[k], angles_deg: angles, joints: forward(arm, angles) };
  });
}

/**
 * Which joints of a motion's request are free (no limits to respect): every one when the
 * request ignores the limits, else those without `limits_deg`.
 */
export function freeJoints(arm, limits) {
  return arm.links.map((l) => !limits || !l.limits_deg);
}

/**
 * The pose at normalised playback time `u` in [0, 1] of `frames` (a /api/animate answer's): the
 * frames around motion time u·T (T the last frame's time) interpolated linearly, joint by joint
 * (`free[i]` the short way round). Returns {angles, index, w}: the frame before the playhead and
 * how far past it; at w = 0 the angles are that frame's own. `from` is a frame index to search
 * from (a hint; the search goes back when the playhead did).
 */
export function poseAt(frames, u, free = [], from = 0) {
  const last = frames.length - 1;
  const T = frames[last].time;
  const t = Math.min(Math.max(u, 0), 1) * T;
  let index = frameIndexAt(frames, t, Math.min(from, last));
  while (index > 0 && frames[index].time > t) index--;
  const f = frames[index];
  if (index === last || t <= f.time) return { angles: f.angles_deg.slice(), index, w: 0 };
  const g = frames[index + 1];
  const span = g.time - f.time;
  const w = span > 0 ? (t - f.time) / span : 0;
  const angles = f.angles_deg.map((a, i) => lerpAngle(a, g.angles_deg[i], w, !!free[i]));
  return { angles, index, w };
}

/** The joint-space distance travelled through `frames`, in radians: Σ ‖q_{k+1} − q_k‖₂. */
export function jointDistance(frames) {
  let sum = 0;
  for (let k = 1; k < frames.length; k++) {
    const a = frames[k - 1].angles_deg;
    const b = frames[k].angles_deg;
    sum += Math.hypot(...b.map((v, i) => (v - a[i]) * DEG));
  }
  return sum;
}

/**
 * The default playback duration in seconds: 0.6 s plus 0.4 s per radian of joint-space distance,
 * from 0.6 s to 4 s. A small correction takes just over half a second, a 90° swing of the seed
 * arm's three joints (2.7 rad) about 1.7 s, and a long path through via points at most 4 s.
 */
export const DURATION = { base: 0.6, perRadian: 0.4, min: 0.6, max: 4 };

export function autoDuration(distance) {
  const d = DURATION.base + DURATION.perRadian * (Number.isFinite(distance) ? Math.max(0, distance) : 0);
  return Math.min(Math.max(d, DURATION.min), DURATION.max);
}

/**
 * The progress at normalised time `u` of `curve` (an /api/ease answer, {t, s}, its times evenly
 * spaced from 0 to 1): the backend's value on a sample, linear between two, clamped to [0, 1].
 * The page draws and plays the library's ease this way and has no copy of its formulas.
 */
export function easeAt(curve, u) {
  const n = curve.s.length - 1;
  if (!(u > 0)) return curve.s[0];
  if (u >= 1) return curve.s[n];
  const x = u * n;
  const k = Math.min(Math.floor(x), n - 1);
  const w = x - k;
  return w === 0 ? curve.s[k] : curve.s[k] + w * (curve.s[k + 1] - curve.s[k]);
}

/**
 * The ghost poses drawn behind the arm when frames 0..=`last` of `total` have played: about
 * twelve over the whole motion, older ones fainter. Returns [{index, alpha}].
 */
export function ghostFrames(total, last) {
  const ghosts = [];
  const every = Math.max(1, Math.round(total / 12));
  const shown = last + 1;
  for (let i = 0; i < shown - 1; i += every) {
    const age = (shown - 1 - i) / Math.max(1, total - 1);
    ghosts.push({ index: i, alpha: 0.06 + 0.16 * (1 - age) });
  }
  return ghosts;
}

// ---- The edge of the reachable area -------------------------------------------------------

/**
 * Marching squares: the edges a square crosses, per case (corners inside: bl 1, br 2, tr 4,
 * tl 8), each walked with the inside on its left so that the pieces join into loops.
 */
const CROSSINGS = [
  [],
  [["b", "l"]],
  [["r", "b"]],
  [["r", "l"]],
  [["t", "r"]],
  [["b", "l"], ["t", "r"]],
  [["t", "b"]],
  [["t", "l"]],
  [["l", "t"]],
  [["b", "t"]],
  [["r", "b"], ["l", "t"]],
  [["r", "t"]],
  [["l", "r"]],
  [["b", "r"]],
  [["l", "b"]],
  [],
];

/** Rounds of corner cutting (Chaikin) that turn the chamfered cell edges into a smooth curve. */
export const OUTLINE_SMOOTHING = 2;

/** Rounds of neighbour averaging before the corner cutting: they iron out the cells' ripple. */
export const OUTLINE_AVERAGING = 3;

/** One round of averaging each point of a closed loop with its two neighbours (¼, ½, ¼). */
function average(loop) {
  const m = loop.length;
  return loop.map(([x, y], k) => {
    const [ax, ay] = loop[(k + m - 1) % m];
    const [bx, by] = loop[(k + 1) % m];
    return [0.25 * ax + 0.5 * x + 0.25 * bx, 0.25 * ay + 0.5 * y + 0.25 * by];
  });
}

/** One round of Chaikin's corner cutting on a closed loop. */
function chaikin(loop) {
  const out = [];
  for (let k = 0; k < loop.length; k++) {
    const [x0, y0] = loop[k];
    const [x1, y1] = loop[(k + 1) % loop.length];
    out.push([0.75 * x0 + 0.25 * x1, 0.75 * y0 + 0.25 * y1], [0.25 * x0 + 0.75 * x1, 0.25 * y0 + 0.75 * y1]);
  }
  return out;
}

/**
 * The edge of the sampled reachable area of a /api/workspace answer with a grid (a server that
 * sends no exact `boundary`, or a `grid: true` request; region.js draws the exact region) as
 * closed loops of world points ([[[x, y], …], …]; holes are loops too, so fill them with the
 * even-odd rule): marching squares over the cell centres, crossing each edge half-way, then
 * smoothed (neighbour averaging, then `smoothing` rounds of corner cutting; 0: the raw
 * marching-squares edge) instead of the cells' staircase.
 */
export function areaOutline(ws, smoothing = OUTLINE_SMOOTHING) {
  const n = ws.resolution;
  const inside = (i, j) => i >= 0 && j >= 0 && i < n && j < n && ws.grid[j].charCodeAt(i) === 49;
  // Squares between the centres of cells (i, j) .. (i + 1, j + 1), one ring beyond the grid.
  const next = new Map();
  const key = (edge, i, j) => {
    switch (edge) {
      case "b":
        return `h${i},${j}`;
      case "t":
        return `h${i},${j + 1}`;
      case "l":
        return `v${i},${j}`;
      default:
        return `v${i + 1},${j}`;
    }
  };
  for (let j = -1; j < n; j++) {
    for (let i = -1; i < n; i++) {
      const c = (inside(i, j) ? 1 : 0) | (inside(i + 1, j) ? 2 : 0) | (inside(i + 1, j + 1) ? 4 : 0) | (inside(i, j + 1) ? 8 : 0);
      for (const [a, b] of CROSSINGS[c]) next.set(key(a, i, j), key(b, i, j));
    }
  }
  const point = (k) => {
    const [i, j] = k.slice(1).split(",").map(Number);
    // h(i, j): between the centres of cells (i, j) and (i + 1, j); v(i, j): (i, j) and (i, j + 1).
    const cx = k[0] === "h" ? i + 1 : i + 0.5;
    const cy = k[0] === "h" ? j + 0.5 : j + 1;
    return [ws.origin[0] + cx * ws.cell_size, ws.origin[1] + cy * ws.cell_size];
  };
  const loops = [];
  const seen = new Set();
  for (const start of next.keys()) {
    if (seen.has(start)) continue;
    let loop = [];
    for (let k = start; k !== undefined && !seen.has(k); k = next.get(k)) {
      seen.add(k);
      loop.push(point(k));
    }
    if (smoothing > 0) for (let r = 0; r < OUTLINE_AVERAGING && loop.length > 2; r++) loop = average(loop);
    for (let r = 0; r < smoothing && loop.length > 2; r++) loop = chaikin(loop);
    if (loop.length > 2) loops.push(loop);
  }
  return loops;
}
