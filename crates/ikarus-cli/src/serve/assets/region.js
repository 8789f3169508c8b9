// The exact reachable region of a /api/workspace answer (its `boundary`): closed loops of line
// segments and circular arcs, outer loops counter-clockwise and holes clockwise, so that the
// region is the set of points of non-zero winding number. The page's one home for its geometry:
// the path drawn on a canvas (or the SVG recording context of export.js), the membership test
// (a winding number with arcs), the nearest point and the area. Pure: no DOM and no state, so
// node can test it (e2e/region.unit.test.mjs).
//
// A region without area (fewer than two joints move) is a set of curves instead (the answer's
// `curves`, segments in the same form): reachable are only the points on them.
//
// A segment as the server sends it: {"line": [[x0, y0], [x1, y1]]} or {"arc": {"center":
// [cx, cy], "radius": r, "from_deg": a0, "to_deg": a1}} (counter-clockwise when a1 > a0,
// clockwise otherwise, a full circle when they differ by 360).

import { DEG, toCanvas } from "./view.js";

const TAU = 2 * Math.PI;

/**
 * The region of `boundary` (and `curves`, for a region without area) in the form the functions
 * below read: {loops, curves, bbox}, loops of segments and curves a list of them, a segment being
 * {a, b (ends), arc: null | {c, r, t0, dt (radians, signed)}}, and the bounding box
 * {x0, y0, x1, y1}. Null when the boundary is missing (an older server's answer).
 */
export function regionOf(boundary, curves = []) {
  if (!Array.isArray(boundary)) return null;
  const bbox = { x0: Infinity, y0: Infinity, x1: -Infinity, y1: -Infinity };
  const grow = ([x, y]) => {
    bbox.x0 = Math.min(bbox.x0, x);
    bbox.y0 = Math.min(bbox.y0, y);
    bbox.x1 = Math.max(bbox.x1, x);
    bbox.y1 = Math.max(bbox.y1, y);
  };
  const segment = (seg) => {
    let s;
    if (seg.line) {
      s = { a: seg.line[0].slice(), b: seg.line[1].slice(), arc: null };
    } else {
      const { center, radius, from_deg, to_deg } = seg.arc;
      const arc = { c: center.slice(), r: radius, t0: from_deg * DEG, dt: (to_deg - from_deg) * DEG };
      s = { a: onCircle(arc, arc.t0), b: onCircle(arc, arc.t0 + arc.dt), arc };
      // The arc's extreme points: where it crosses the circle's four axis directions.
      for (let k = 0; k < 4; k++) if (onArc(arc, (k * Math.PI) / 2)) grow(onCircle(arc, (k * Math.PI) / 2));
    }
    grow(s.a);
    grow(s.b);
    return s;
  };
  const loops = boundary.map((loop) => loop.map(segment));
  return { loops, curves: (Array.isArray(curves) ? curves : []).map(segment), bbox };
}

const onCircle = (arc, t) => [arc.c[0] + arc.r * Math.cos(t), arc.c[1] + arc.r * Math.sin(t)];

/** How far the direction `t` lies along the arc from its start, in [0, 2π) (radians). */
function along(arc, t) {
  const d = arc.dt >= 0 ? t - arc.t0 : arc.t0 - t;
  return ((d % TAU) + TAU) % TAU;
}

/** Whether the direction `t` (radians) from the centre lies on the arc. */
const onArc = (arc, t) => Math.abs(arc.dt) >= TAU || along(arc, t) <= Math.abs(arc.dt);

const cross = (ax, ay, bx, by) => ax * by - ay * bx;

/**
 * Adds the region's loops to the current path of `pen` (a canvas 2D context, or export.js's
 * svgContext) in the view `view` (view.js's fitView): each loop a subpath, arcs drawn with
 * `arc()` (the canvas's y points down, so world angles are negated and a counter-clockwise arc
 * is drawn anticlockwise), lines with `lineTo`. Fill it with the `nonzero` rule.
 */
export function traceRegion(pen, view, region) {
  for (const loop of region.loops) {
    if (loop.length === 0) continue;
    pen.moveTo(...toCanvas(view, ...loop[0].a));
    for (const s of loop) traceSegment(pen, view, s);
    pen.closePath();
  }
}

/** Adds the curves of a region without area to the path of `pen`, each its own open subpath (stroke them). */
export function traceCurves(pen, view, region) {
  for (const s of region.curves) {
    pen.moveTo(...toCanvas(view, ...s.a));
    traceSegment(pen, view, s);
  }
}

function traceSegment(pen, view, s) {
  if (s.arc) {
    const [cx, cy] = toCanvas(view, ...s.arc.c);
    pen.arc(cx, cy, s.arc.r * view.scale, -s.arc.t0, -(s.arc.t0 + s.arc.dt), s.arc.dt > 0);
  } else {
    pen.lineTo(...toCanvas(view, ...s.b));
  }
}

/**
 * The winding number of the loops around `p`: the crossings of each segment's chord (Sunday's
 * rule: upward crossings with `p` on the left count +1, downward ones with `p` on the right −1),
 * plus, for an arc, ±1 (its turning sense) when `p` lies in the circular segment between the
 * arc and its chord; the loop of chords and the arcs' segments make up the loop. Non-zero:
 * inside. A point on the boundary may count either way.
 */
export function winding(region, [px, py]) {
  let wn = 0;
  for (const loop of region.loops) {
    for (const { a, b, arc } of loop) {
      const side = cross(b[0] - a[0], b[1] - a[1], px - a[0], py - a[1]);
      if (a[1] <= py) {
        if (b[1] > py && side > 0) wn++;
      } else if (b[1] <= py && side < 0) wn--;
      if (arc && Math.hypot(px - arc.c[0], py - arc.c[1]) < arc.r && betweenArcAndChord(arc, a, b, side)) {
        wn += arc.dt > 0 ? 1 : -1;
      }
    }
  }
  return wn;
}

/** Whether a point inside the arc's circle, at `side` (the chord's cross product) of its chord, is on the arc's side. */
function betweenArcAndChord(arc, a, b, side) {
  if (Math.abs(arc.dt) >= TAU) return true;
  const m = onCircle(arc, arc.t0 + arc.dt / 2);
  return cross(b[0] - a[0], b[1] - a[1], m[0] - a[0], m[1] - a[1]) * side > 0;
}

/** The point of segment `s` nearest `p`. */
export function nearestOnSegment(s, [px, py]) {
  if (s.arc) {
    const { c, r } = s.arc;
    const dx = px - c[0];
    const dy = py - c[1];
    if (dx === 0 && dy === 0) return s.a.slice();
    const t = Math.atan2(dy, dx);
    if (onArc(s.arc, t)) return onCircle(s.arc, t);
    const da = Math.hypot(px - s.a[0], py - s.a[1]);
    const db = Math.hypot(px - s.b[0], py - s.b[1]);
    return (da <= db ? s.a : s.b).slice();
  }
  const [ax, ay] = s.a;
  const ux = s.b[0] - ax;
  const uy = s.b[1] - ay;
  const len2 = ux * ux + uy * uy;
  const w = len2 > 0 ? Math.min(Math.max(((px - ax) * ux + (py - ay) * uy) / len2, 0), 1) : 0;
  return [ax + w * ux, ay + w * uy];
}

/** The point nearest `p` on the boundary (or the curves) and its distance: {point, distance}. */
export function nearestOnBoundary(region, p) {
  let best = { point: null, distance: Infinity };
  for (const s of [...region.loops.flat(), ...region.curves]) {
    const q = nearestOnSegment(s, p);
    const d = Math.hypot(q[0] - p[0], q[1] - p[1]);
    if (d < best.distance) best = { point: q, distance: d };
  }
  return best;
}

/**
 * The verdict for the point `p`, as `POST /api/reach` answers it: {reachable (inside, or within
 * `tolerance` of the region), distance (0 inside, else to the nearest boundary point), nearest
 * (the nearest reachable point: `p` itself inside)}. A region without area reaches its curves
 * only; one with neither reaches nothing (distance Infinity, nearest null).
 */
export function verdict(region, p, tolerance = 0) {
  if (winding(region, p) !== 0) return { reachable: true, distance: 0, nearest: [p[0], p[1]] };
  const { point, distance } = nearestOnBoundary(region, p);
  if (!point) return { reachable: false, distance: Infinity, nearest: null };
  return { reachable: distance <= tolerance, distance, nearest: point };
}

/**
 * The area, ½∮(x dy − y dx) over the loops: x0·y1 − x1·y0 for a line, and for the arc
 * (cx + r cos t, cy + r sin t), t from t0 to t1, r·cx·(sin t1 − sin t0) − r·cy·(cos t1 − cos t0)
 * + r²·(t1 − t0). Holes (clockwise) count negative, so this is the region's area.
 */
export function regionArea(region) {
  let twice = 0;
  for (const loop of region.loops) {
    for (const { a, b, arc } of loop) {
      if (arc) {
        const { c, r, t0, dt } = arc;
        const t1 = t0 + dt;
        twice += r * c[0] * (Math.sin(t1) - Math.sin(t0)) - r * c[1] * (Math.cos(t1) - Math.cos(t0)) + r * r * dt;
      } else {
        twice += a[0] * b[1] - b[0] * a[1];
      }
    }
  }
  return twice / 2;
}

/** The text of a verdict for the status chip: "unreachable · 0.83 from the reachable region". */
export function unreachableText(distance) {
  return `unreachable · ${formatDistance(distance)} from the reachable region`;
}

/** A distance with two significant decimals at least (0.83, 0.0042, 12.50). */
export function formatDistance(d) {
  if (!Number.isFinite(d)) return String(d);
  if (d === 0 || d >= 0.01) return d.toFixed(2);
  return d.toPrecision(2);
}
