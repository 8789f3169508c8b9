// Drawing on a 2D context: the grid and axes, the reachable area (the exact region of
// region.js, or the sampled grid's smooth edge), the reach circle, the joints' ranges (wedges)
// when limits are on, the motion (ghost poses and joint traces up to the playhead), the onion skins (onion.js), the wanted
// path of a traced path (or the stroke being drawn), the base, the arm, the flips and where a plan
// left the path, the via
// points, the goal and, for a goal out of reach, the nearest reachable point. It reads the
// page's state and never writes it; the geometry comes from view.js and region.js. The screen
// and the PNG and SVG downloads (export.js) are drawn by the same drawScene.

import { bodyForward, chainBody } from "./body.js";
import { drawOnion } from "./onion.js";
import { traceCurves, traceRegion } from "./region.js";
import { decimalsFor, ghostFrames, gridValues, inClear, maxReach, niceStep, placeLabels, toCanvas, toWorld } from "./view.js";

/**
 * The colours, the render crate's palette (`ikarus-render`'s style.rs, given by /api/meta's
 * `palette`, see usePalette) so that the page, its downloads and the CLI's pictures agree. The
 * values here are that palette too, for the moment before /api/meta answers.
 */
export const COLORS = {
  plot: "#ffffff",
  grid: "#e7eaee",
  axis: "#c3c9d1",
  label: "#6b7280",
  ink: "#26324a",
  reach: "#5f9e77",
  workspace: "#dceae1",
  goal: "#d62728",
  path: "#ec7f2d",
  joints: ["#4e79a7", "#76b7b2", "#b07aa1", "#9c755f", "#8cb369"],
  // The via points: the pictures have none, so this one is the page's own.
  via: "#7b3fa0",
  // A pinned effector of a rig (ikarus-render's style.rs PIN).
  pin: "#2b6cb0",
};

/** Takes the colours of /api/meta's `palette` (names as in COLORS). */
export function usePalette(palette) {
  for (const [name, value] of Object.entries(palette || {})) if (name in COLORS) COLORS[name] = value;
}

/** A new path: the diamond of half-diagonal `r` centred on (x, y) (the nearest reachable point, a key). */
export function diamondPath(ctx, x, y, r) {
  ctx.beginPath();
  ctx.moveTo(x, y - r);
  ctx.lineTo(x + r, y);
  ctx.lineTo(x, y + r);
  ctx.lineTo(x - r, y);
  ctx.closePath();
}

/** Sizes the canvas's backing store to its CSS size times the device pixel ratio; drawing is then in CSS pixels. */
export function fitCanvas(canvas, ctx) {
  const dpr = window.devicePixelRatio || 1;
  const w = Math.max(1, canvas.clientWidth);
  const h = Math.max(1, canvas.clientHeight);
  if (canvas.width !== Math.round(w * dpr) || canvas.height !== Math.round(h * dpr)) {
    canvas.width = Math.round(w * dpr);
    canvas.height = Math.round(h * dpr);
  }
  ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
}

/** Draws everything the state shows in the view `view` (from view.js's fitView). */
export function drawScene(ctx, view, state) {
  drawGrid(ctx, view);
  drawArea(ctx, view, state);
  drawReach(ctx, view, state.arm);
  drawRanges(ctx, view, state);
  drawMotion(ctx, view, state);
  drawOnion(ctx, view, state);
  drawWanted(ctx, view, state);
  drawBase(ctx, view, state.arm);
  drawArm(ctx, view, state.joints);
  drawFlips(ctx, view, state.track);
  drawOffPath(ctx, view, state.track);
  drawVia(ctx, view, state.via);
  drawGoal(ctx, view, state.goal);
  drawReachMiss(ctx, view, state);
}

/**
 * The path the tip should follow, dashed over the tip's trace (where the tip follows it, the
 * dashes lie on the trace): the stroke being drawn, else the traced path's goals.
 */
function drawWanted(ctx, view, state) {
  const points = state.stroke || (state.track && state.track.goals);
  if (!points || points.length < 2) return;
  ctx.setLineDash([6, 6]);
  // The wanted path in the pictures' colour of it (ikarus-render's path.rs: the first joint hue).
  ctx.strokeStyle = COLORS.joints[0];
  ctx.lineWidth = 1.5;
  ctx.lineCap = "round";
  polyline(ctx, view, points);
  ctx.stroke();
  ctx.setLineDash([]);
}

/** Red rings where the traced path flips (a joint steps more than the bound between samples). */
function drawFlips(ctx, view, track) {
  if (!track) return;
  ctx.strokeStyle = COLORS.goal;
  ctx.lineWidth = 2.5;
  for (const [x, y] of track.flips) {
    const [px, py] = toCanvas(view, x, y);
    ctx.beginPath();
    ctx.arc(px, py, 11, 0, 2 * Math.PI);
    ctx.stroke();
  }
}

/**
 * Where a traced path's plan left the path (the tip's way through its off-path poses, from the
 * sample before to the sample after): a dashed line in the goal's red on a white halo, with a
 * small red ring where the tip leaves the path and where it comes back.
 */
function drawOffPath(ctx, view, track) {
  if (!track || !track.offPath) return;
  ctx.lineCap = "round";
  ctx.lineJoin = "round";
  for (const run of track.offPath) {
    ctx.setLineDash([]);
    ctx.strokeStyle = COLORS.plot;
    ctx.lineWidth = 5;
    polyline(ctx, view, run);
    ctx.stroke();
    ctx.setLineDash([4, 4]);
    ctx.strokeStyle = COLORS.goal;
    ctx.lineWidth = 2;
    polyline(ctx, view, run);
    ctx.stroke();
    ctx.setLineDash([]);
    for (const [x, y] of [run[0], run.at(-1)]) {
      const [px, py] = toCanvas(view, x, y);
      ctx.beginPath();
      ctx.arc(px, py, 5, 0, 2 * Math.PI);
      ctx.lineWidth = 2;
      ctx.stroke();
    }
  }
}

/** The via points, numbered in the order the motion passes them. */
function drawVia(ctx, view, via) {
  ctx.font = "bold 11px system-ui, sans-serif";
  ctx.textAlign = "center";
  ctx.textBaseline = "middle";
  via.forEach((p, i) => {
    const [px, py] = toCanvas(view, p.x, p.y);
    ctx.beginPath();
    ctx.arc(px, py, 9, 0, 2 * Math.PI);
    ctx.fillStyle = "#fff";
    ctx.fill();
    ctx.lineWidth = 2;
    ctx.strokeStyle = COLORS.via;
    ctx.stroke();
    ctx.fillStyle = COLORS.via;
    ctx.fillText(String(i + 1), px, py + 0.5);
  });
}

export function drawGrid(ctx, view) {
  const { w, h } = view;
  // Over a character's art (artview.js: `view.under` "art") the canvas is see-through: the grid is drawn under the art.
  if (view.under === "art") {
    ctx.clearRect(0, 0, w, h);
    return;
  }
  ctx.fillStyle = COLORS.plot;
  ctx.fillRect(0, 0, w, h);
  const [x0, y1] = toWorld(view, 0, 0);
  const [x1, y0] = toWorld(view, w, h);
  const step = niceStep(Math.min(x1 - x0, y1 - y0));
  const decimals = decimalsFor(step);
  const xs = gridValues(x0, x1, step);
  const ys = gridValues(y0, y1, step);
  ctx.lineWidth = 1;
  ctx.strokeStyle = COLORS.grid;
  ctx.beginPath();
  for (const gx of xs) {
    const [px] = toCanvas(view, gx, 0);
    ctx.moveTo(Math.round(px) + 0.5, 0);
    ctx.lineTo(Math.round(px) + 0.5, h);
  }
  for (const gy of ys) {
    const [, py] = toCanvas(view, 0, gy);
    ctx.moveTo(0, Math.round(py) + 0.5);
    ctx.lineTo(w, Math.round(py) + 0.5);
  }
  ctx.stroke();
  // Axes through the origin (or along the edges when the origin is out of view).
  const [ox, oy] = toCanvas(view, 0, 0);
  const ax = Math.min(Math.max(ox, 0), w);
  const ay = Math.min(Math.max(oy, 0), h);
  ctx.strokeStyle = COLORS.axis;
  ctx.beginPath();
  ctx.moveTo(0, Math.round(ay) + 0.5);
  ctx.lineTo(w, Math.round(ay) + 0.5);
  ctx.moveTo(Math.round(ax) + 0.5, 0);
  ctx.lineTo(Math.round(ax) + 0.5, h);
  ctx.stroke();
  drawLabels(ctx, view, { ax, ay, xs, ys, decimals, step });
}

/** The height of an axis label's box, pixels (11 px text). */
const LABEL_HEIGHT = 12;

/**
 * The axis labels: the axes' names ("x" above the x axis at the right end, "y" right of the y
 * axis at the top, or under the chip when that covers the top), then the x ticks' values under the x axis (or above it, or above
 * what covers them, where that is covered) and the y ticks' left of the y
 * axis (or right of it where that is covered), each only where it is clear of the others and of
 * what the page lays over the canvas (`view.keepOut`, boxes in canvas pixels: the status chip,
 * the hint). The labels drawn are kept as `view.labels` ([{text, x, y, w, h}]).
 */
function drawLabels(ctx, view, { ax, ay, xs, ys, decimals, step }) {
  const { w, h } = view;
  ctx.fillStyle = COLORS.label;
  ctx.font = "11px system-ui, sans-serif";
  ctx.textAlign = "left";
  ctx.textBaseline = "top";
  const width = (text) => ctx.measureText(text).width;
  const at = (text, x, y) => ({ x, y, w: width(text), h: LABEL_HEIGHT });
  const candidates = [];
  const keepOut = view.keepOut || [];
  const xName = at("x", 0, 0);
  xName.x = w - 4 - xName.w;
  candidates.push({ text: "x", places: [{ ...xName, y: ay - 3 - LABEL_HEIGHT }, { ...xName, y: ay + 3 }] });
  // The y name at the top, either side of the axis, or just under what covers the top.
  const yName = at("y", ax + 5, 4);
  const tops = [4, ...keepOut.map((k) => k.y + k.h + 4)];
  candidates.push({ text: "y", places: tops.flatMap((y) => [{ ...yName, y }, { ...yName, y, x: ax - 5 - yName.w }]) });
  // The x ticks' values in one row: under the axis, else above it, else above what the page lays
  // over that row (the hint, the zoom box: an axis out of view runs along the bottom edge, under
  // them), the row where the most of them are clear; those it covers are left out.
  const below = Math.min(ay + 3, h - 14);
  const xBoxes = xs
    .filter((gx) => Math.abs(gx) >= step / 2)
    .map((gx) => {
      const text = gx.toFixed(decimals);
      const box = at(text, 0, below);
      box.x = toCanvas(view, gx, 0)[0] - box.w / 2;
      return { text, box };
    });
  const covers = keepOut.filter((k) => k.y < below + LABEL_HEIGHT && below < k.y + k.h);
  const rows = [below, ay - 3 - LABEL_HEIGHT, ...covers.map((k) => k.y - 3 - LABEL_HEIGHT)];
  const count = (y) => xBoxes.filter(({ box }) => inClear({ ...box, y }, keepOut, w, h)).length;
  const row = rows.reduce((best, y) => (count(y) > count(best) ? y : best), rows[0]);
  for (const { text, box } of xBoxes) candidates.push({ text, places: [{ ...box, y: row }] });
  for (const gy of ys) {
    if (Math.abs(gy) < step / 2) continue;
    const text = gy.toFixed(decimals);
    const [, py] = toCanvas(view, 0, gy);
    const box = at(text, 0, py - LABEL_HEIGHT / 2);
    box.x = Math.max(ax - 4, 28) - box.w;
    candidates.push({ text, places: [box, { ...box, x: ax + 4 }] });
  }
  view.labels = placeLabels(candidates, keepOut, w, h);
  for (const l of view.labels) ctx.fillText(l.text, l.x, l.y);
}

/**
 * The reachable area: the exact region (region.js, from the answer's `boundary`: arcs and lines,
 * filled with the nonzero rule, holes running the other way, and the curves of a region without
 * area stroked) when the server sent one, else the sampled grid's smoothed outline (filled
 * even-odd: holes stay empty); filled and outlined.
 */
function drawArea(ctx, view, state) {
  const region = state.region;
  if (!state.showWorkspace || !(region || state.areaOutline)) return;
  ctx.beginPath();
  if (region) {
    traceRegion(ctx, view, region);
  } else {
    for (const loop of state.areaOutline) {
      loop.forEach(([x, y], i) => {
        const [px, py] = toCanvas(view, x, y);
        if (i === 0) ctx.moveTo(px, py);
        else ctx.lineTo(px, py);
      });
      ctx.closePath();
    }
  }
  ctx.globalAlpha = 0.75;
  ctx.fillStyle = COLORS.workspace;
  ctx.fill(region ? "nonzero" : "evenodd");
  ctx.globalAlpha = region ? 0.9 : 0.6;
  ctx.strokeStyle = COLORS.reach;
  ctx.lineWidth = region ? 1.5 : 1;
  ctx.stroke();
  if (region && region.curves.length > 0) {
    ctx.beginPath();
    traceCurves(ctx, view, region);
    ctx.lineWidth = 3;
    ctx.lineCap = "round";
    ctx.stroke();
  }
  ctx.globalAlpha = 1;
}

/**
 * A goal out of the reachable region (state.reachMiss, for the goal shown): a dashed line from
 * the goal to the nearest reachable point, and there a diamond in the reach colour, drawn over
 * the arm (whose tip ends on it).
 */
function drawReachMiss(ctx, view, state) {
  const miss = state.reachMiss;
  if (!miss || miss.goal !== state.goal || !miss.nearest) return;
  const [gx, gy] = toCanvas(view, miss.goal.x, miss.goal.y);
  const [nx, ny] = toCanvas(view, ...miss.nearest);
  ctx.setLineDash([5, 4]);
  ctx.strokeStyle = COLORS.goal;
  ctx.lineWidth = 1.5;
  ctx.lineCap = "butt";
  ctx.beginPath();
  ctx.moveTo(gx, gy);
  ctx.lineTo(nx, ny);
  ctx.stroke();
  ctx.setLineDash([]);
  diamondPath(ctx, nx, ny, 9);
  ctx.globalAlpha = 0.35;
  ctx.fillStyle = COLORS.reach;
  ctx.fill();
  ctx.globalAlpha = 1;
  ctx.lineJoin = "miter";
  // A white halo first, so that the diamond stands out on the area's edge and the arm.
  ctx.lineWidth = 5;
  ctx.strokeStyle = COLORS.plot;
  ctx.stroke();
  ctx.lineWidth = 2.5;
  ctx.strokeStyle = COLORS.reach;
  ctx.stroke();
}

/**
 * Each limited joint's range as a wedge at the joint when limits are on: from the previous
 * link's direction turned by the minimum to the maximum, with a line at the joint's angle.
 */
function drawRanges(ctx, view, state) {
  if (!state.options.limits || state.joints.length !== state.arm.links.length + 1) return;
  const { parentHeadings } = bodyForward(chainBody(state.arm), state.pose_deg);
  state.arm.links.forEach((link, i) => {
    if (link.limits_deg) drawWedge(ctx, view, state.joints[i], parentHeadings[i], link.limits_deg, link.length);
  });
}

/**
 * A joint's range as a wedge at `at` (world): from the direction `heading` (degrees, the
 * parent's) turned by `limits` [min, max], its radius a share of the link's `length` on screen,
 * at most `most` pixels.
 */
export function drawWedge(ctx, view, at, heading, limits, length, most = 46) {
  const [px, py] = toCanvas(view, ...at);
  const r = Math.min(Math.max(length * view.scale * 0.4, 14), most);
  const lo = ((heading + limits[0]) * Math.PI) / 180;
  const hi = ((heading + limits[1]) * Math.PI) / 180;
  // World angles turn counter-clockwise; the canvas's y points down, so they are negated.
  ctx.beginPath();
  ctx.moveTo(px, py);
  ctx.arc(px, py, r, -hi, -lo);
  ctx.closePath();
  ctx.globalAlpha = 0.1;
  ctx.fillStyle = COLORS.ink;
  ctx.fill();
  ctx.globalAlpha = 0.45;
  ctx.strokeStyle = COLORS.ink;
  ctx.lineWidth = 1;
  ctx.stroke();
  ctx.globalAlpha = 1;
}

function drawReach(ctx, view, arm) {
  const [bx, by] = toCanvas(view, ...(arm.base || [0, 0]));
  ctx.setLineDash([6, 5]);
  ctx.strokeStyle = COLORS.reach;
  ctx.lineWidth = 1.5;
  ctx.beginPath();
  ctx.arc(bx, by, maxReach(arm) * view.scale, 0, 2 * Math.PI);
  ctx.stroke();
  ctx.setLineDash([]);
}

function polyline(ctx, view, points) {
  ctx.beginPath();
  points.forEach(([x, y], i) => {
    const [px, py] = toCanvas(view, x, y);
    if (i === 0) ctx.moveTo(px, py);
    else ctx.lineTo(px, py);
  });
}

function drawArm(ctx, view, joints, alpha = 1, width = 7) {
  ctx.globalAlpha = alpha;
  ctx.lineCap = "round";
  ctx.lineJoin = "round";
  ctx.strokeStyle = COLORS.ink;
  ctx.lineWidth = width;
  polyline(ctx, view, joints);
  ctx.stroke();
  if (alpha === 1) {
    joints.forEach(([x, y], i) => {
      const [px, py] = toCanvas(view, x, y);
      ctx.beginPath();
      ctx.arc(px, py, i === joints.length - 1 ? 4 : 5, 0, 2 * Math.PI);
      ctx.fillStyle = "#fff";
      ctx.fill();
      ctx.lineWidth = 2;
      ctx.strokeStyle = COLORS.ink;
      ctx.stroke();
    });
  }
  ctx.globalAlpha = 1;
}

export function drawBase(ctx, view, arm) {
  const [px, py] = toCanvas(view, ...(arm.base || [0, 0]));
  ctx.fillStyle = COLORS.ink;
  ctx.beginPath();
  ctx.moveTo(px, py);
  ctx.lineTo(px - 11, py + 15);
  ctx.lineTo(px + 11, py + 15);
  ctx.closePath();
  ctx.globalAlpha = 0.85;
  ctx.fill();
  ctx.globalAlpha = 1;
  ctx.fillRect(px - 16, py + 15, 32, 3);
}

/**
 * A dashed red line from the canvas point `a` to `b`: from a rig's tip, or a character's target
 * bone, to the goal it is not at.
 */
export function drawLeash(ctx, [ax, ay], [bx, by]) {
  ctx.setLineDash([4, 4]);
  ctx.strokeStyle = COLORS.goal;
  ctx.lineWidth = 1.2;
  ctx.globalAlpha = 0.7;
  ctx.beginPath();
  ctx.moveTo(ax, ay);
  ctx.lineTo(bx, by);
  ctx.stroke();
  ctx.globalAlpha = 1;
  ctx.setLineDash([]);
}

/** The goal: a red target, with an arrow along the wanted heading when a goal angle is set. */
export function drawGoal(ctx, view, goal) {
  if (!goal) return;
  const angleDeg = goal.angle_deg;
  const [px, py] = toCanvas(view, goal.x, goal.y);
  if (angleDeg !== undefined) {
    const a = (angleDeg * Math.PI) / 180;
    const [dx, dy] = [Math.cos(a), -Math.sin(a)];
    const [ex, ey] = [px + 30 * dx, py + 30 * dy];
    ctx.strokeStyle = COLORS.goal;
    ctx.lineWidth = 2;
    ctx.beginPath();
    ctx.moveTo(px, py);
    ctx.lineTo(ex, ey);
    ctx.moveTo(ex - 8 * dx - 5 * dy, ey - 8 * dy + 5 * dx);
    ctx.lineTo(ex, ey);
    ctx.lineTo(ex - 8 * dx + 5 * dy, ey - 8 * dy - 5 * dx);
    ctx.stroke();
  }
  ctx.strokeStyle = COLORS.goal;
  ctx.lineWidth = 2;
  ctx.beginPath();
  ctx.arc(px, py, 8, 0, 2 * Math.PI);
  ctx.moveTo(px - 13, py);
  ctx.lineTo(px + 13, py);
  ctx.moveTo(px, py - 13);
  ctx.lineTo(px, py + 13);
  ctx.stroke();
}

function drawMotion(ctx, view, state) {
  const anim = state.animation;
  if (!anim || !anim.frames || anim.frames.length === 0) return;
  // Up to the playhead: the frames before it, then the pose drawn (between two frames).
  const last = Math.min(state.playback.index, anim.frames.length - 1);
  const frames = anim.frames.slice(0, last + 1);
  if (state.playback.posed && state.joints.length === frames[0].joints.length) frames.push({ joints: state.joints });
  if (state.showGhosts) {
    for (const { index, alpha } of ghostFrames(anim.frames.length, last)) {
      drawArm(ctx, view, frames[index].joints, alpha, 5);
    }
  }
  if (state.showTraces && frames.length > 1) {
    const nj = frames[0].joints.length;
    ctx.lineWidth = 1.5;
    ctx.lineCap = "round";
    for (let j = 1; j < nj; j++) {
      const tip = j === nj - 1;
      ctx.strokeStyle = tip ? COLORS.path : COLORS.joints[(j - 1) % COLORS.joints.length];
      ctx.globalAlpha = tip ? 1 : 0.7;
      ctx.lineWidth = tip ? 2.5 : 1.5;
      polyline(ctx, view, frames.map((f) => f.joints[j]));
      ctx.stroke();
    }
    ctx.globalAlpha = 1;
  }
}
