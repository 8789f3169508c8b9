// The camera of the canvas: a zoom and a pan laid over the fitted view of the body shown (the
// arm's view.js fitView, a rig's rigView, a character's characterView). The page draws and picks
// through one view, `viewThrough(fit, camera)`: every world <-> canvas conversion (drawing, the
// grid, every pick and every world point read from the pointer) uses it, so picking is exact at
// every zoom. Pure: no DOM and no state of its own (node tests it: e2e/camera.unit.test.mjs);
// nav.js turns the wheel, pinches, drags and keys into its calls.
//
// A camera is {zoom, x, y}: the scale is the fit's times `zoom`, and the world point at the
// canvas's centre is the fit's centre moved by (x, y) world units. Kept relative to the fit, it
// survives a resized canvas (the same part of the world stays centred, at the same zoom).

import { toWorld } from "./view.js";

/** The zoom's range, as multiples of the fitted view's scale. */
export const ZOOM = { min: 0.05, max: 200 };

/** The camera of the fitted view: zoom 1, no pan. */
export const fittedCamera = () => ({ zoom: 1, x: 0, y: 0 });

/** Whether `camera` shows the fitted view itself. */
export const isFitted = (camera) => camera.zoom === 1 && camera.x === 0 && camera.y === 0;

/** `zoom` kept inside ZOOM. */
export const clampZoom = (zoom) => Math.min(Math.max(zoom, ZOOM.min), ZOOM.max);

/** The world point at the centre of the `fit` view's canvas. */
const centreOf = (fit) => toWorld(fit, fit.w / 2, fit.h / 2);

/**
 * The view `camera` shows of the fitted view `fit` ({cx, cy, scale, w, h}): canvas = (cx +
 * x·scale, cy − y·scale) with scale = fit.scale · zoom and the fit's centre moved by (x, y) to
 * the canvas's centre. The fitted camera gives the fit's own numbers (bit for bit). The view
 * keeps `fit` and `zoom`, for the camera's moves and the page's readout.
 */
export function viewThrough(fit, camera) {
  const { w, h } = fit;
  if (isFitted(camera)) return { cx: fit.cx, cy: fit.cy, scale: fit.scale, w, h, fit, zoom: 1 };
  const scale = fit.scale * camera.zoom;
  const [x0, y0] = centreOf(fit);
  const [x, y] = [x0 + camera.x, y0 + camera.y];
  return { cx: w / 2 - x * scale, cy: h / 2 + y * scale, scale, w, h, fit, zoom: camera.zoom };
}

/**
 * The camera whose view (of the same fit as `view`, a viewThrough answer) puts the world point
 * (x, y) at canvas pixel (px, py) at zoom `zoom` (clamped to ZOOM).
 */
function cameraPutting(view, x, y, px, py, zoom) {
  const z = clampZoom(zoom);
  const scale = view.fit.scale * z;
  // The view's centre world point when (x, y) sits at (px, py).
  const cx = x + (view.w / 2 - px) / scale;
  const cy = y - (view.h / 2 - py) / scale;
  const [x0, y0] = centreOf(view.fit);
  return { zoom: z, x: cx - x0, y: cy - y0 };
}

/**
 * The camera after zooming `view` (a viewThrough answer) by `factor` about the canvas pixel
 * (px, py): the world point under it stays under it. The zoom stops at ZOOM's ends (the point
 * still stays).
 */
export function zoomAbout(view, factor, px, py) {
  const [x, y] = toWorld(view, px, py);
  return cameraPutting(view, x, y, px, py, view.zoom * factor);
}

/**
 * The camera after dragging `view`'s world by (dx, dy) canvas pixels: what was under the pointer
 * follows it.
 */
export function panBy(view, dx, dy) {
  const [x, y] = toWorld(view, view.w / 2, view.h / 2);
  return cameraPutting(view, x, y, view.w / 2 + dx, view.h / 2 + dy, view.zoom);
}

/**
 * The camera of a pinch: the world point under the first midpoint `from` ([px, py]) goes under
 * the second `to`, the zoom times `factor` (the fingers' distance now over before).
 */
export function pinch(view, factor, from, to) {
  const [x, y] = toWorld(view, ...from);
  return cameraPutting(view, x, y, to[0], to[1], view.zoom * factor);
}

/** Pixels of wheel travel that zoom by e (a notch of 100 px: about 1.22×). */
const WHEEL_PIXELS_PER_E = 500;
/** The same for a pinch on a trackpad (sent as ctrl + wheel, in small steps). */
const PINCH_PIXELS_PER_E = 100;
/** The most one wheel event zooms by, as a power of e (a ctrl + wheel notch of a mouse). */
const MAX_STEP = 0.5;

/**
 * The zoom factor of a wheel event's `deltaY` in `deltaMode` units (0 pixels, 1 lines of 16
 * px, 2 pages of `page` px); `pinch` for a trackpad's pinch (ctrl + wheel). Up (negative)
 * zooms in.
 */
export function wheelFactor(deltaY, deltaMode = 0, pinchGesture = false, page = 800) {
  const px = deltaY * (deltaMode === 1 ? 16 : deltaMode === 2 ? page : 1);
  const e = -px / (pinchGesture ? PINCH_PIXELS_PER_E : WHEEL_PIXELS_PER_E);
  return Math.exp(Math.min(Math.max(e, -MAX_STEP), MAX_STEP));
}

/** The zoom for people: "100%", "2,000%", "5%" (whole per cent, "0.5%" below one). */
export function zoomText(zoom) {
  const pc = zoom * 100;
  return pc < 1 ? `${pc.toFixed(1)}%` : `${Math.round(pc).toLocaleString("en-US")}%`;
}
