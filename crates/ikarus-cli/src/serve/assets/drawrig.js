// Drawing a rig (a skeleton) on a 2D context, as the render crate's skeleton pictures do: the
// grid, the joints' ranges as wedges when limits are on (the arm's wedges, draw.js's drawWedge),
// the onion skins of a keyed motion (onion.js),
// the bones, the base, the joints (a white ring where bones start), the effectors (ink dots on
// the tips the reader can drag; a ring on the one under the pointer or being dragged, with its
// name), the pins (blue squares) and the goals (red targets, a dashed line from the tip to its
// goal while it is not there), and each prismatic joint as a sleeve along its slide with its
// limits as a bar. It reads the page's state and never writes it. The screen and the
// PNG and SVG downloads (export.js) are drawn by the same drawRigScene.

import { drawBase, drawGoal, drawLeash, drawWedge } from "./draw.js";
import { COLORS, drawGrid } from "./paint.js";
import { drawOnion } from "./onion.js";
import { fitRigView, shownEffectors } from "./rig.js";
import { toCanvas } from "./view.js";

/** The largest radius of a rig's limit wedge, CSS pixels. */
const RIG_WEDGE_PIXELS = 30;

/** The view of `state` in a `w` × `h` canvas: the rig's when a rig is shown (pose-independent). */
export const rigView = (state, w, h) => fitRigView(state.rig.rig, w, h);

/** Draws the rig of `state.rig` (see rigs.js for its fields) in the view `view`. */
export function drawRigScene(ctx, view, state) {
  const r = state.rig;
  drawGrid(ctx, view);
  if (state.options.limits) {
    r.rig.bones.forEach((b, i) => {
      // Smaller than an arm's: several bones start at one joint (the hips, the knuckles).
      if (b.limits_deg) drawWedge(ctx, view, r.starts[i], r.parentHeadings[i], b.limits_deg, b.length, RIG_WEDGE_PIXELS);
    });
  }
  drawOnion(ctx, view, state);
  drawSleeves(ctx, view, r, state.options.limits);
  drawBones(ctx, view, r);
  drawBase(ctx, view, r.rig);
  drawJoints(ctx, view, r);
  const names = r.rig.bones.map((b) => b.name);
  const tipOf = (name) => r.tips[names.indexOf(name)];
  const effectors = shownEffectors(r.rig, r.goals, r.pins);
  for (const name of effectors) if (!r.pins.has(name)) drawEffector(ctx, view, tipOf(name));
  for (const name of names.filter((n) => r.pins.has(n))) drawPin(ctx, view, tipOf(name));
  for (const [name, goal] of r.goals) {
    const tip = tipOf(name);
    const [tx, ty] = toCanvas(view, ...tip);
    const [gx, gy] = toCanvas(view, goal.x, goal.y);
    if (Math.hypot(gx - tx, gy - ty) > 10) drawLeash(ctx, [tx, ty], [gx, gy]);
    drawGoal(ctx, view, goal);
  }
  const focus = r.grabbed || r.hover;
  if (focus && names.includes(focus)) drawFocus(ctx, view, tipOf(focus), focus);
}

function drawBones(ctx, view, r) {
  ctx.lineCap = "round";
  ctx.strokeStyle = COLORS.ink;
  // Thinner bones when they are short on screen (a hand's finger bones).
  const shortest = Math.min(...r.rig.bones.map((b) => b.length)) * view.scale;
  ctx.lineWidth = Math.min(7, Math.max(3, shortest / 5));
  ctx.beginPath();
  r.rig.bones.forEach((_, i) => {
    const [sx, sy] = toCanvas(view, ...r.starts[i]);
    const [tx, ty] = toCanvas(view, ...r.tips[i]);
    ctx.moveTo(sx, sy);
    ctx.lineTo(tx, ty);
  });
  ctx.stroke();
}

/** A prismatic joint's sleeve, CSS pixels across. */
const SLEEVE_PIXELS = 12;

/**
 * Each prismatic joint (body.js): a sleeve, a wider rectangle along the slide from the joint to
 * where the bone starts now (at least a short stub when it is not out), and, when limits are
 * on, its limits as a bar beside it along the slide, from joint + lo to joint + hi, with a tick
 * at each end.
 */
function drawSleeves(ctx, view, r, limits) {
  r.rig.bones.forEach((b, i) => {
    const dir = r.slides[i];
    if (!dir) return;
    const at = r.joints[i];
    const [jx, jy] = toCanvas(view, ...at);
    // On the canvas y points down.
    const [ux, uy] = [dir[0], -dir[1]];
    const [nx, ny] = [-uy, ux];
    // The bar runs beside the sleeve (to its right), so that the bone does not hide it.
    const aside = SLEEVE_PIXELS / 2 + 5;
    const along = (d) => [jx + ux * d * view.scale - nx * aside, jy + uy * d * view.scale - ny * aside];
    if (limits && b.limits) {
      const [[ax, ay], [bx, by]] = [along(b.limits[0]), along(b.limits[1])];
      const t = SLEEVE_PIXELS * 0.8;
      ctx.globalAlpha = 0.45;
      ctx.strokeStyle = COLORS.ink;
      ctx.lineWidth = 2;
      ctx.beginPath();
      ctx.moveTo(ax, ay);
      ctx.lineTo(bx, by);
      for (const [x, y] of [[ax, ay], [bx, by]]) {
        ctx.moveTo(x - (nx * t) / 2, y - (ny * t) / 2);
        ctx.lineTo(x + (nx * t) / 2, y + (ny * t) / 2);
      }
      ctx.stroke();
      ctx.globalAlpha = 1;
    }
    const [sx, sy] = toCanvas(view, ...r.starts[i]);
    let len = Math.hypot(sx - jx, sy - jy);
    const sign = (sx - jx) * ux + (sy - jy) * uy < 0 ? -1 : 1;
    len = Math.max(len, SLEEVE_PIXELS) * sign;
    const h = SLEEVE_PIXELS / 2;
    ctx.beginPath();
    ctx.moveTo(jx + nx * h, jy + ny * h);
    ctx.lineTo(jx + ux * len + nx * h, jy + uy * len + ny * h);
    ctx.lineTo(jx + ux * len - nx * h, jy + uy * len - ny * h);
    ctx.lineTo(jx - nx * h, jy - ny * h);
    ctx.closePath();
    ctx.fillStyle = "#fff";
    ctx.fill();
    ctx.lineWidth = 2;
    ctx.strokeStyle = COLORS.ink;
    ctx.stroke();
  });
}

/** A white ring where bones start (once per point: several bones may start at one joint). */
function drawJoints(ctx, view, r) {
  const seen = new Set();
  for (const at of r.starts) {
    const [px, py] = toCanvas(view, ...at);
    const key = `${Math.round(px)},${Math.round(py)}`;
    if (seen.has(key)) continue;
    seen.add(key);
    ctx.beginPath();
    ctx.arc(px, py, 4.5, 0, 2 * Math.PI);
    ctx.fillStyle = "#fff";
    ctx.fill();
    ctx.lineWidth = 2;
    ctx.strokeStyle = COLORS.ink;
    ctx.stroke();
  }
}

/** An effector: an ink dot with a white rim on the tip. */
function drawEffector(ctx, view, tip) {
  const [px, py] = toCanvas(view, ...tip);
  ctx.beginPath();
  ctx.arc(px, py, 5.5, 0, 2 * Math.PI);
  ctx.fillStyle = COLORS.ink;
  ctx.fill();
  ctx.lineWidth = 1.6;
  ctx.strokeStyle = "#fff";
  ctx.stroke();
}

/** A pin: a blue square with a white border on the tip (the render crate's marker). */
function drawPin(ctx, view, tip) {
  const [px, py] = toCanvas(view, ...tip);
  const half = 6.5;
  ctx.beginPath();
  ctx.moveTo(px - half, py - half);
  ctx.lineTo(px + half, py - half);
  ctx.lineTo(px + half, py + half);
  ctx.lineTo(px - half, py + half);
  ctx.closePath();
  ctx.fillStyle = COLORS.pin;
  ctx.fill();
  ctx.lineWidth = 1.6;
  ctx.strokeStyle = "#fff";
  ctx.stroke();
}

/** The effector under the pointer or being dragged: an orange ring and its name. */
function drawFocus(ctx, view, tip, name) {
  drawRingLabel(ctx, toCanvas(view, ...tip), 10, name);
}

/** An orange ring of `radius` round (px, py) in canvas pixels, with `label` above to its right (the thing under the pointer). */
export function drawRingLabel(ctx, [px, py], radius, label) {
  ctx.beginPath();
  ctx.arc(px, py, radius, 0, 2 * Math.PI);
  ctx.lineWidth = 2;
  ctx.strokeStyle = COLORS.path;
  ctx.stroke();
  ctx.font = "12px system-ui, sans-serif";
  ctx.textAlign = "left";
  ctx.textBaseline = "middle";
  ctx.fillStyle = COLORS.ink;
  ctx.fillText(label, px + radius + 4, py - 12);
}
