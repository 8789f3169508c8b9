// What every drawing of the page paints with: the palette (the pictures' colours), the canvas's
// backing store at the device's pixel ratio, the grid with its axes and their labels (clear of
// what the page lays over the canvas), and the diamond mark. The arm's scene (draw.js), the rig's
// (drawrig.js), the character's (drawchar.js and its art, artview.js), the key rows (drawkeys.js)
// and the timeline's ease plot draw on it.

import { decimalsFor, gridValues, inClear, niceStep, placeLabels, toCanvas, toWorld } from "./view.js";

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

/** The grid, the axes through the origin (or along the edges) and their labels, over the plot's background. */
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
