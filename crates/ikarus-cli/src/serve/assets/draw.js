// Drawing the arm's scene on a 2D context: the grid and axes (paint.js's), the reachable area (the
// exact region of region.js, or the sampled grid's smooth edge), the reach circle, the joints'
// ranges (wedges) when limits are on, the motion (ghost poses and joint traces up to the
// playhead), the onion skins (onion.js), the wanted path of a traced path (or the stroke being
// drawn), the base, the arm, the flips and where a plan left the path, the via points, the goal
// and, for a goal out of reach, the nearest reachable point; the marks a rig's and a
// character's scenes share with it (the wedge, the base, the leash, the goal). It reads the
// page's state and never writes it; the geometry comes from view.js and region.js. The screen
// and the PNG and SVG downloads (export.js) are drawn by the same drawScene.

import { bodyForward, chainBody } from "./body.js";
import { drawOnion } from "./onion.js";
import { traceCurves, traceRegion } from "./region.js";
import { COLORS, diamondPath, drawGrid } from "./paint.js";
import { ghostFrames, maxReach, toCanvas } from "./view.js";

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
