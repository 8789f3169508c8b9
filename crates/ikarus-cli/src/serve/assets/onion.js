// Onion skins: the poses a few frames before and after the playhead, faded with their distance
// from it, drawn behind the live pose (the frames before in one colour, those after in another).
// The frames are the motion's own (at its fps), not the display's: the arm's clicked motion
// (`state.animation.frames`: `joints`), a rig's keyed motion (`state.motion.frames`: `pose`, the
// joint values in the rig's bone order) or a character's (`state.motion.frames`: `bones`, as
// drawchar.js draws a pose). A character's clip played without a keyed motion has no frames of
// its own on the page (each pose is asked of the server as the playhead moves), so it shows
// none. Pure but for the drawing on a given context: node tests it (e2e/camera.unit.test.mjs).

import { bodyForward } from "./body.js";
import { toCanvas } from "./view.js";

/** The count's range and default: frames each side of the playhead. */
export const ONION = { min: 1, max: 10, count: 3 };

/** A fresh `state.onion`: {show, count}. */
export const newOnion = () => ({ show: false, count: ONION.count });

/** The skins' colours: the frames before the playhead, and after it. */
export const ONION_COLORS = { before: "#3b7dd8", after: "#2e9e5b" };

/** The opacity of the skin next to the playhead, and of the farthest. */
const ALPHA = { near: 0.5, far: 0.12 };

/** The opacity of the skin `k` frames from the playhead (1 = the nearest) of `count`. */
export const onionAlpha = (k, count) => ALPHA.near - ((ALPHA.near - ALPHA.far) * (k - 1)) / Math.max(1, count - 1);

/**
 * The skins around motion time `t` (seconds, as the frames' `time`): the `count` frames before
 * it and the `count` after it, [{index, side ("before" or "after"), alpha}], farthest first
 * (nearer skins are drawn over farther ones). A frame at the playhead itself (within a
 * billionth of the motion's length) is the live pose, not a skin.
 */
export function onionFrames(frames, t, count) {
  const n = frames.length;
  if (n === 0 || !(count >= 1)) return [];
  const eps = 1e-9 * Math.max(1, Math.abs(frames[n - 1].time));
  // The first frame after the playhead and the last one before it.
  let after = 0;
  while (after < n && frames[after].time <= t + eps) after++;
  let before = after - 1;
  if (before >= 0 && Math.abs(frames[before].time - t) <= eps) before--;
  const skins = [];
  for (let k = count; k >= 1; k--) {
    const b = before - (k - 1);
    const a = after + (k - 1);
    if (b >= 0) skins.push({ index: b, side: "before", alpha: onionAlpha(k, count) });
    if (a < n) skins.push({ index: a, side: "after", alpha: onionAlpha(k, count) });
  }
  return skins;
}

/**
 * The motion whose frames are skinned, for `state`: {frames, kind ("arm", "rig" or
 * "character"), t (the playhead's motion time)}, or null (no motion of two frames or more, or
 * the arm moved off the playhead, following the pointer). The playhead is the timeline's
 * (`state.playback.u`, the share of the last frame's time).
 */
export function onionMotion(state) {
  const kind = state.character ? "character" : state.rig ? "rig" : "arm";
  const motion = kind === "arm" ? state.animation : state.motion;
  const frames = motion && motion.frames;
  if (!frames || frames.length < 2) return null;
  if (kind === "arm" && !state.playback.posed) return null;
  const u = Math.min(Math.max(state.playback.u, 0), 1);
  return { frames, kind, t: u * frames[frames.length - 1].time };
}

/**
 * A frame's pose as world polylines ([[[x, y], …], …]): the arm's joints (one line), each of a
 * rig's bones from its start to its tip (from the frame's `pose`), each of a character's bones
 * from its origin to its tip.
 */
export function skinLines(frame, kind, rig) {
  if (kind === "arm") return frame.joints ? [frame.joints] : [];
  if (kind === "rig") {
    const pose = frame.pose || frame.angles_deg;
    if (!pose) return [];
    const { starts, tips } = bodyForward(rig, pose);
    return starts.map((s, i) => [s, tips[i]]);
  }
  return (frame.bones || []).map((b) => [[b.x, b.y], b.tip]);
}

/** The skins' stroke widths, CSS pixels, by kind (the arm is drawn 7 wide, a rig's bones 3 to 7). */
const WIDTH = { arm: 5, rig: 3, character: 2 };

/**
 * Draws the onion skins of `state` (when `state.onion.show`) in `view` on `ctx`, behind what is
 * drawn next; keeps how many of each side were drawn as `view.onion` ([before, after]).
 */
export function drawOnion(ctx, view, state) {
  view.onion = [0, 0];
  const motion = state.onion && state.onion.show ? onionMotion(state) : null;
  if (!motion) return;
  const rig = state.rig && state.rig.rig;
  ctx.lineCap = "round";
  ctx.lineJoin = "round";
  ctx.lineWidth = WIDTH[motion.kind];
  for (const skin of onionFrames(motion.frames, motion.t, state.onion.count)) {
    ctx.globalAlpha = skin.alpha;
    ctx.strokeStyle = ONION_COLORS[skin.side];
    ctx.beginPath();
    for (const line of skinLines(motion.frames[skin.index], motion.kind, rig)) {
      line.forEach(([x, y], i) => (i ? ctx.lineTo(...toCanvas(view, x, y)) : ctx.moveTo(...toCanvas(view, x, y))));
    }
    ctx.stroke();
    view.onion[skin.side === "before" ? 0 : 1]++;
  }
  ctx.globalAlpha = 1;
}
