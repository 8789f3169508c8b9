// Drawing the keys (keyed.js): the rows under the timeline (one per keyed effector, bend and
// pin: its name, a diamond per key at its time, the selected key filled, the playhead as a line)
// with the geometry that picks a key or a time from a point, and the bend handles on the canvas
// (keys.js's bendHandles: a small half-moon beside each knee and elbow, on the side it bends).
// It reads and never writes the state.

import { COLORS, diamondPath, fitCanvas } from "./paint.js";
import { drawRingLabel } from "./drawrig.js";

/** A row's height, the names' column and the margin at the rows' right end, CSS pixels. */
export const ROW = { height: 18, names: 128, right: 10 };

/** A press within this many CSS pixels of a diamond picks its key. */
export const KEY_PICK_PIXELS = 7;

/** The time axis of rows `w` pixels wide over `length` seconds: x(t) and t(x) (clamped to [0, length]). */
export function rowAxis(w, length) {
  const x0 = ROW.names;
  const span = Math.max(1, w - ROW.names - ROW.right);
  const L = Math.max(length, 1e-9);
  return {
    x: (t) => x0 + (t / L) * span,
    t: (x) => Math.min(Math.max(((x - x0) / span) * L, 0), L),
  };
}

/**
 * What the point (px, py) of the rows (`rows`: keys.js's keyRows) is on: {row, index} of the key
 * nearest within KEY_PICK_PIXELS on the row under it, else {row, index: -1, t} (the time under
 * it), or null outside the rows.
 */
export function pickKey(rows, axis, px, py) {
  const r = Math.floor(py / ROW.height);
  const row = rows[r];
  if (!row) return null;
  let index = -1;
  let best = Infinity;
  row.keys.forEach((k, i) => {
    const d = Math.abs(axis.x(k.time) - px);
    if (d <= KEY_PICK_PIXELS && d < best) {
      index = i;
      best = d;
    }
  });
  return { row, index, t: axis.t(px) };
}

/** The rows' label: "left_foot", "left_shin bend", "right_foot pin". */
export const rowName = (row) => (row.kind === "track" ? row.bone : `${row.bone} ${row.kind}`);

/**
 * Draws `rows` on the rows canvas over `length` seconds: names, a line per row, a diamond per
 * key (a bend key: a half-filled one, its side), the selected key (`selected`: {kind, bone,
 * index}) filled orange, the playhead at `t`.
 */
export function drawRows(canvas, rows, length, t, selected) {
  canvas.style.height = `${Math.max(1, rows.length) * ROW.height}px`;
  const ctx = canvas.getContext("2d");
  fitCanvas(canvas, ctx);
  const w = canvas.clientWidth;
  const h = canvas.clientHeight;
  const axis = rowAxis(w, length);
  ctx.clearRect(0, 0, w, h);
  ctx.font = "12px system-ui, sans-serif";
  ctx.textBaseline = "middle";
  if (!rows.length) {
    ctx.fillStyle = COLORS.label;
    ctx.fillText("No keys: turn Key mode on and drag an effector", 8, ROW.height / 2 + 1);
  }
  rows.forEach((row, r) => {
    const y = r * ROW.height + ROW.height / 2;
    ctx.fillStyle = COLORS.ink;
    ctx.textAlign = "left";
    ctx.fillText(rowName(row), 6, y + 0.5, ROW.names - 10);
    ctx.strokeStyle = COLORS.grid;
    ctx.lineWidth = 1;
    ctx.beginPath();
    ctx.moveTo(axis.x(0), y + 0.5);
    ctx.lineTo(axis.x(length), y + 0.5);
    ctx.stroke();
    if (row.kind === "pin") {
      ctx.fillStyle = COLORS.pin;
      ctx.fillRect(axis.x(0), y - 2, axis.x(length) - axis.x(0), 4);
    }
    row.keys.forEach((k, i) => {
      const on = selected && selected.kind === row.kind && selected.bone === row.bone && selected.index === i;
      drawDiamond(ctx, axis.x(k.time), y, on, row.kind === "bend" ? k.bend : null);
    });
  });
  const px = axis.x(Math.min(t, length));
  ctx.strokeStyle = COLORS.path;
  ctx.lineWidth = 1.5;
  ctx.beginPath();
  ctx.moveTo(px, 0);
  ctx.lineTo(px, h);
  ctx.stroke();
}

/** A key's diamond; a bend key's is half filled (the side it keys: ccw's left half, cw's right). */
function drawDiamond(ctx, x, y, selected, bend) {
  const r = 5.5;
  diamondPath(ctx, x, y, r);
  ctx.fillStyle = selected ? COLORS.path : "#fff";
  ctx.fill();
  ctx.lineWidth = 1.5;
  ctx.strokeStyle = selected ? COLORS.path : COLORS.ink;
  ctx.stroke();
  if (bend) {
    ctx.beginPath();
    const s = bend === "ccw" ? -1 : 1;
    ctx.moveTo(x, y - r);
    ctx.lineTo(x + s * r, y);
    ctx.lineTo(x, y + r);
    ctx.closePath();
    ctx.fillStyle = COLORS.ink;
    ctx.fill();
  }
}

/**
 * The bend handles (keys.js's bendHandles, in canvas pixels) on the rig's canvas: a small disc
 * beside each middle joint with a curved arrow round it, joined to the joint by a short line; the
 * handle under the pointer (`hover`, a bone name) ringed, with its name and side.
 */
export function drawBendHandles(ctx, handles, hover) {
  for (const h of handles) {
    const [x, y] = h.at;
    ctx.strokeStyle = COLORS.joints[2];
    ctx.lineWidth = 1.5;
    ctx.beginPath();
    ctx.moveTo(...h.joint);
    ctx.lineTo(x, y);
    ctx.stroke();
    ctx.beginPath();
    ctx.arc(x, y, 5, 0, 2 * Math.PI);
    ctx.fillStyle = COLORS.joints[2];
    ctx.fill();
    ctx.lineWidth = 1.5;
    ctx.strokeStyle = "#fff";
    ctx.stroke();
    // A curved arrow: "flip".
    ctx.beginPath();
    ctx.arc(x, y, 9, -0.2 * Math.PI, 0.9 * Math.PI);
    ctx.strokeStyle = COLORS.joints[2];
    ctx.stroke();
    if (hover === h.bone) drawRingLabel(ctx, h.at, 12, `${h.bone} bends ${h.side} · click to flip`);
  }
}
