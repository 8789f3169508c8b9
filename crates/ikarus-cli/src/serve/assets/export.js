// The figure downloads (PNG and SVG) drawn by draw.js's drawScene, the function that draws the
// screen: what you see is what you download — the same layers (reachable area, ranges, ghosts,
// traces, paths, via points, goal), the same palette, at the playhead's pose. The PNG is drawn
// on an offscreen canvas; the SVG by a small recording context (svgContext) that writes the
// same calls as SVG elements.

import { drawScene } from "./draw.js";
import { drawRigScene, rigView } from "./drawrig.js";
import { characterView, drawCharacterScene } from "./drawchar.js";
import { fitView } from "./view.js";

/** The side of a downloaded figure, CSS pixels. */
export const FIGURE_SIDE = 800;

const esc = (t) => String(t).replace(/&/g, "&amp;").replace(/</g, "&lt;").replace(/>/g, "&gt;").replace(/"/g, "&quot;");
const n = (v) => String(Math.round(v * 100) / 100);

/**
 * A stand-in for a canvas 2D context of `w` × `h` that records what draw.js draws as SVG: paths
 * (lines and arcs), rectangles and text, with their colours, widths, dashes and alpha.
 * `svg()` is the document.
 */
export function svgContext(w, h) {
  const out = [];
  let d = "";
  let dash = [];
  let current = null;
  const ctx = {
    fillStyle: "#000",
    strokeStyle: "#000",
    lineWidth: 1,
    lineCap: "butt",
    lineJoin: "miter",
    globalAlpha: 1,
    font: "10px sans-serif",
    textAlign: "start",
    textBaseline: "alphabetic",
    imageSmoothingEnabled: true,
    setTransform() {},
    setLineDash(a) {
      dash = a.slice();
    },
    beginPath() {
      d = "";
      current = null;
    },
    moveTo(x, y) {
      d += `M${n(x)} ${n(y)}`;
      current = [x, y];
    },
    lineTo(x, y) {
      d += `${current ? "L" : "M"}${n(x)} ${n(y)}`;
      current = [x, y];
    },
    closePath() {
      d += "Z";
    },
    arc(cx, cy, r, a0, a1, ccw = false) {
      const at = (a) => [cx + r * Math.cos(a), cy + r * Math.sin(a)];
      const [sx, sy] = at(a0);
      d += `${current ? "L" : "M"}${n(sx)} ${n(sy)}`;
      const turn = ccw ? a0 - a1 : a1 - a0;
      if (turn >= 2 * Math.PI - 1e-9) {
        // A whole circle: two half arcs.
        const [mx, my] = at(a0 + Math.PI);
        const sweep = ccw ? 0 : 1;
        d += `A${n(r)} ${n(r)} 0 1 ${sweep} ${n(mx)} ${n(my)}A${n(r)} ${n(r)} 0 1 ${sweep} ${n(sx)} ${n(sy)}`;
        current = [sx, sy];
        return;
      }
      const delta = ((turn % (2 * Math.PI)) + 2 * Math.PI) % (2 * Math.PI);
      const [ex, ey] = at(a1);
      d += `A${n(r)} ${n(r)} 0 ${delta > Math.PI ? 1 : 0} ${ccw ? 0 : 1} ${n(ex)} ${n(ey)}`;
      current = [ex, ey];
    },
    stroke() {
      if (!d) return;
      const dashes = dash.length ? ` stroke-dasharray="${dash.map(n).join(" ")}"` : "";
      out.push(
        `<path d="${d}" fill="none" stroke="${esc(ctx.strokeStyle)}" stroke-width="${n(ctx.lineWidth)}" stroke-linecap="${ctx.lineCap}" stroke-linejoin="${ctx.lineJoin}"${dashes}${opacity()}/>`,
      );
    },
    fill(rule = "nonzero") {
      if (d) out.push(`<path d="${d}" fill="${esc(ctx.fillStyle)}" fill-rule="${rule}"${opacity()}/>`);
    },
    fillRect(x, y, rw, rh) {
      out.push(`<rect x="${n(x)}" y="${n(y)}" width="${n(rw)}" height="${n(rh)}" fill="${esc(ctx.fillStyle)}"${opacity()}/>`);
    },
    clearRect() {},
    // The text's width as the browser's system-ui roughly sets it (0.6 of the size a character).
    measureText(text) {
      const size = Number((/(\d+(?:\.\d+)?)px/.exec(ctx.font) || [0, 10])[1]);
      return { width: String(text).length * size * 0.6 };
    },
    fillText(text, x, y) {
      const size = (/(\d+(?:\.\d+)?)px/.exec(ctx.font) || [0, 10])[1];
      const bold = /bold/.test(ctx.font) ? ` font-weight="bold"` : "";
      const anchor = { center: "middle", right: "end", end: "end" }[ctx.textAlign] || "start";
      const base = { top: "hanging", middle: "central", bottom: "text-after-edge" }[ctx.textBaseline] || "alphabetic";
      out.push(
        `<text x="${n(x)}" y="${n(y)}" font-family="system-ui, sans-serif" font-size="${size}"${bold} text-anchor="${anchor}" dominant-baseline="${base}" fill="${esc(ctx.fillStyle)}"${opacity()}>${esc(text)}</text>`,
      );
    },
    svg() {
      return `<svg xmlns="http://www.w3.org/2000/svg" width="${w}" height="${h}" viewBox="0 0 ${w} ${h}">\n${out.join("\n")}\n</svg>\n`;
    },
  };
  const opacity = () => (ctx.globalAlpha < 1 ? ` opacity="${n(ctx.globalAlpha)}"` : "");
  return ctx;
}

/** The scene of `state` (the rig when one is shown, else the arm) drawn on `ctx` at `side` × `side` (the view fitted to that size). */
function drawFigure(ctx, state, side) {
  if (state.character && state.character.box) drawCharacterScene(ctx, characterView(state, side, side), state);
  else if (state.rig) drawRigScene(ctx, rigView(state, side, side), state);
  else drawScene(ctx, fitView(state.arm, side, side), state);
}

/** The figure as SVG text. */
export function figureSvg(state, side = FIGURE_SIDE) {
  const ctx = svgContext(side, side);
  drawFigure(ctx, state, side);
  return ctx.svg();
}

/** The figure as a PNG Blob, drawn on an offscreen canvas. */
export function figurePng(state, side = FIGURE_SIDE) {
  const canvas = document.createElement("canvas");
  canvas.width = side;
  canvas.height = side;
  drawFigure(canvas.getContext("2d"), state, side);
  return new Promise((resolve, reject) => canvas.toBlob((b) => (b ? resolve(b) : reject(new Error("the PNG could not be made"))), "image/png"));
}
