// Drawing a character (characters.js's `state.character`) on a 2D context: the grid, the onion
// skins of a keyed motion (onion.js), each posed
// bone as Spine draws bones (character.js's boneShape: a slim kite from the origin to the tip, a
// small circle for a bone of no length), the bones an IK constraint moves tinted, every IK
// target as a handle (an orange ring with a cross; red and filled once dragged, with a dashed
// line from its bone when the bone is not there, draw.js's drawLeash), and the name of the bone or target under the
// pointer in a label. It reads the state and never writes it. The screen and the PNG and SVG
// downloads (export.js) are drawn by the same drawCharacterScene.

import { drawLeash } from "./draw.js";
import { COLORS, drawGrid } from "./paint.js";
import { boneShape, fitCharacterView, unionBox } from "./character.js";
import { drawOnion } from "./onion.js";
import { toCanvas } from "./view.js";

/** A target's handle, CSS pixels (its ring's radius). */
const HANDLE_RADIUS = 7;

/**
 * The view of `state` in a `w` × `h` canvas: the character's setup pose fitted, with the poses of
 * the clip shown once surveyed (pose-independent).
 */
export const characterView = (state, w, h) => {
  const c = state.character;
  return fitCharacterView(unionBox(c.box, c.clipBoxes.get(c.animation)), w, h);
};

/**
 * Each posed bone of `c` (state.character) with its origin and tip in canvas pixels, bone
 * order: [{o, t}]. Empty before the first pose has come.
 */
export function bonesOnCanvas(view, c) {
  return (c.posed || []).map((b) => ({ o: toCanvas(view, b.x, b.y), t: toCanvas(view, b.tip[0], b.tip[1]) }));
}

/**
 * Each IK target's handle in canvas pixels: a Map name → [x, y], where the reader put it (a
 * dragged target), else where the posed bone's origin is.
 */
export function handlesOnCanvas(view, c) {
  const at = new Map((c.posed || []).map((b) => [b.name, b]));
  const out = new Map();
  for (const name of c.targetNames) {
    const goal = c.targets.get(name);
    const b = at.get(name);
    if (goal) out.set(name, toCanvas(view, goal.x, goal.y));
    else if (b) out.set(name, toCanvas(view, b.x, b.y));
  }
  return out;
}

/** Draws `state.character` in `view` (its bones unless `state.showBones` is false); returns how many bones it has posed. */
export function drawCharacterScene(ctx, view, state) {
  const c = state.character;
  drawGrid(ctx, view);
  // The bones overlay off (artview.js's switch): the art alone, with the targets' handles.
  const bones = state.showBones !== false;
  if (bones) drawOnion(ctx, view, state);
  else view.onion = [0, 0];
  const px = bonesOnCanvas(view, c);
  const index = new Map(c.character.bones.map((b, i) => [b.name, i]));
  c.character.bones.forEach((bone, i) => {
    if (!px[i] || !bones) return;
    drawBone(ctx, boneShape(px[i].o, px[i].t, bone.length), c.ikBones.has(bone.name), c.hover === bone.name);
  });
  const handles = handlesOnCanvas(view, c);
  for (const [name, at] of handles) {
    const placed = c.targets.has(name);
    const bone = px[index.get(name)];
    if (placed && bone && Math.hypot(bone.o[0] - at[0], bone.o[1] - at[1]) > 3) drawLeash(ctx, bone.o, at);
    const note = c.notes && c.notes.get(name);
    drawHandle(ctx, at, placed, c.grabbed === name || c.hover === name, !!(note && note.inactive));
  }
  const focus = c.grabbed || c.hover;
  const at = focus && (handles.get(focus) || (px[index.get(focus)] && px[index.get(focus)].o));
  if (at) drawName(ctx, view, at, focus);
  return px.length;
}

/** A bone: its kite filled pale and outlined in ink (tinted when an IK constraint moves it), or its circle. */
function drawBone(ctx, shape, ik, hovered) {
  ctx.beginPath();
  if (shape.kind === "circle") {
    ctx.arc(shape.at[0], shape.at[1], shape.r, 0, 2 * Math.PI);
  } else {
    shape.points.forEach(([x, y], k) => (k ? ctx.lineTo(x, y) : ctx.moveTo(x, y)));
    ctx.closePath();
  }
  const ink = ik ? COLORS.joints[0] : COLORS.ink;
  ctx.globalAlpha = hovered ? 0.9 : 0.35;
  ctx.fillStyle = hovered ? COLORS.path : ink;
  ctx.fill();
  ctx.globalAlpha = 1;
  ctx.lineWidth = 1;
  ctx.strokeStyle = ink;
  ctx.stroke();
}

/**
 * A target's handle: a ring with a cross; filled red once the reader has put it somewhere, ringed
 * wider under the pointer; a handle that moves nothing (`inactive`: character.js's handleNotes)
 * grey and dashed.
 */
function drawHandle(ctx, [x, y], placed, focused, inactive) {
  const r = HANDLE_RADIUS;
  if (inactive) {
    ctx.beginPath();
    ctx.arc(x, y, r, 0, 2 * Math.PI);
    ctx.fillStyle = "#fff";
    ctx.globalAlpha = 0.7;
    ctx.fill();
    ctx.globalAlpha = 1;
    ctx.setLineDash([3, 3]);
    ctx.lineWidth = 1.5;
    ctx.strokeStyle = COLORS.axis;
    ctx.stroke();
    ctx.setLineDash([]);
    ctx.beginPath();
    ctx.moveTo(x - r + 3, y - r + 3);
    ctx.lineTo(x + r - 3, y + r - 3);
    ctx.stroke();
    if (focused) {
      ctx.beginPath();
      ctx.arc(x, y, r + 4, 0, 2 * Math.PI);
      ctx.stroke();
    }
    return;
  }
  ctx.beginPath();
  ctx.arc(x, y, r, 0, 2 * Math.PI);
  ctx.fillStyle = placed ? COLORS.goal : "#fff";
  ctx.globalAlpha = placed ? 0.85 : 0.9;
  ctx.fill();
  ctx.globalAlpha = 1;
  ctx.lineWidth = 2;
  ctx.strokeStyle = placed ? COLORS.goal : COLORS.path;
  ctx.stroke();
  ctx.beginPath();
  ctx.moveTo(x - r + 2.5, y);
  ctx.lineTo(x + r - 2.5, y);
  ctx.moveTo(x, y - r + 2.5);
  ctx.lineTo(x, y + r - 2.5);
  ctx.lineWidth = 1.5;
  ctx.strokeStyle = placed ? "#fff" : COLORS.path;
  ctx.stroke();
  if (focused) {
    ctx.beginPath();
    ctx.arc(x, y, r + 4, 0, 2 * Math.PI);
    ctx.lineWidth = 2;
    ctx.strokeStyle = COLORS.path;
    ctx.stroke();
  }
}

/** The name under the pointer: in a white box beside `at`, kept inside the canvas. */
function drawName(ctx, view, [x, y], name) {
  ctx.font = "12px system-ui, sans-serif";
  const w = ctx.measureText(name).width + 8;
  const h = 18;
  const bx = Math.min(Math.max(x + 12, 2), view.w - w - 2);
  const by = Math.min(Math.max(y - 12 - h, 2), view.h - h - 2);
  ctx.fillStyle = "#fff";
  ctx.globalAlpha = 0.92;
  ctx.fillRect(bx, by, w, h);
  ctx.globalAlpha = 1;
  ctx.lineWidth = 1;
  ctx.strokeStyle = COLORS.axis;
  // A path, not strokeRect: the SVG download's context draws paths.
  ctx.beginPath();
  ctx.moveTo(bx + 0.5, by + 0.5);
  ctx.lineTo(bx + w - 0.5, by + 0.5);
  ctx.lineTo(bx + w - 0.5, by + h - 0.5);
  ctx.lineTo(bx + 0.5, by + h - 0.5);
  ctx.closePath();
  ctx.stroke();
  ctx.fillStyle = COLORS.ink;
  ctx.textAlign = "left";
  ctx.textBaseline = "middle";
  ctx.fillText(name, bx + 4, by + h / 2 + 0.5);
}
