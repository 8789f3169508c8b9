// What the browser tests of a rig on the playground share: where a bone's tip is drawn, the
// world point under the pointer, keying by real drags at the playhead (the puppet's walk-like
// cycle), the frame shown, and a knee flipped with its bend handle. Used by keys.test.mjs,
// zoom.test.mjs, project.test.mjs and animator.test.mjs.

import { openPage, ready } from "./browser.mjs";

/** A new page of `browser` at the playground `url`, the puppet shown and Key mode on: {page, errors}. */
export async function keyingPuppet(browser, url) {
  const { page, errors } = await openPage(browser);
  await page.goto(url);
  await ready(page);
  await page.selectOption("#body-kind", "rig:puppet");
  await page.click("#key-mode");
  return { page, errors };
}

/** Seconds of the four keys of the walk (frames 0, 12, 24, 36 at 30 fps). */
export const TIMES = [0, 0.4, 0.8, 1.2];

/**
 * A walk-like cycle of the puppet, reachable with its limits: bone → a target per key time. At
 * 0.8 s the left foot is lifted (a high step), nearer the hip than the straight leg reaches, so
 * that its knee must bend one way or the other.
 */
export const WALK = {
  left_foot: [
    [0.3, -0.86],
    [0.18, -0.8],
    [0.22, -0.62],
    [0.3, -0.86],
  ],
  right_foot: [
    [0.0, -0.9],
    [0.15, -0.84],
    [0.28, -0.86],
    [0.0, -0.9],
  ],
  left_hand: [
    [0.05, -0.27],
    [0.15, -0.25],
    [0.25, -0.2],
    [0.05, -0.27],
  ],
  right_hand: [
    [0.22, -0.2],
    [0.1, -0.26],
    [-0.05, -0.27],
    [0.22, -0.2],
  ],
};

/** How near a key's target an effector must be at its key time (the targets are reachable). */
export const TOLERANCE = 1e-3;

/** Resolves once no keyed motion and no rig solve is in flight or waiting. */
export const keysSettled = (page) => page.waitForFunction(() => window.ikarus.keys.settled() && window.ikarus.rigs.settled(), null, { timeout: 60000 });

/** Client coordinates of rig bone `name`'s tip as drawn now. */
export const tipClient = (page, name) =>
  page.evaluate((n) => {
    const r = window.ikarus.state.rig;
    return window.ikarus.toClient(...r.tips[r.rig.bones.findIndex((b) => b.name === n)]);
  }, name);

/** The world point under client point (x, y) in the view last drawn (the one picks read). */
export const worldAt = (page, x, y) =>
  page.evaluate(([x, y]) => {
    const v = window.ikarus.state.view;
    const r = document.getElementById("plot").getBoundingClientRect();
    return [(x - r.left - v.cx) / v.scale, (v.cy - (y - r.top)) / v.scale];
  }, [x, y]);

/**
 * Drags bone `name`'s tip to the world point `to` in eight even moves and lets go; waits for the
 * keyed motion. `moved()` runs after each move (a screen recording's frame, say).
 */
export async function dragTip(page, name, to, moved = async () => {}) {
  const from = await tipClient(page, name);
  const end = await page.evaluate(([x, y]) => window.ikarus.toClient(x, y), to);
  await page.mouse.move(...from);
  await page.mouse.down();
  for (let i = 1; i <= 8; i++) {
    await page.mouse.move(from[0] + ((end[0] - from[0]) * i) / 8, from[1] + ((end[1] - from[1]) * i) / 8);
    await moved();
  }
  await page.mouse.up();
  await keysSettled(page);
}

/** The playhead to `t` seconds, the frame there shown. */
export async function seek(page, t) {
  await page.evaluate((s) => window.ikarus.keys.seek(s), t);
  await keysSettled(page);
}

/**
 * Keys the puppet's walk (Key mode on): at each key time, each of the four effectors dragged to
 * its target. `after(bone, k)` runs after each drag (to record the keys, say), `moved()` after
 * each pointer move of a drag.
 */
export async function keyWalk(page, after = async () => {}, moved = async () => {}) {
  for (let k = 0; k < TIMES.length; k++) {
    await seek(page, TIMES[k]);
    for (const [bone, targets] of Object.entries(WALK)) {
      await dragTip(page, bone, targets[k], moved);
      await after(bone, k);
    }
  }
}

/** What the page shows now: each bone's drawn tip, the frame's `joints` and angles, the frame index. */
export const shown = (page) =>
  page.evaluate(() => {
    const s = window.ikarus.state;
    const r = s.rig;
    const tips = Object.fromEntries(r.rig.bones.map((b, i) => [b.name, r.tips[i]]));
    const index = Number(document.body.dataset.keyFrame);
    const frame = s.motion.frames[index];
    return { tips, index, frame: { time: frame.time, status: frame.status, joints: frame.joints, angles_deg: frame.angles_deg } };
  });

/** The side a joint at `deg` bends to, as the bend keys name it. */
export const side = (deg) => (deg >= 0 ? "ccw" : "cw");

/**
 * The bend handle of `bone` at the playhead clicked: resolves with the frame shown before and
 * after, and the handle ({side, at: client point}). `hovered()` runs with the pointer on the
 * handle before the click (a screenshot, say).
 */
export async function flipBend(page, bone, hovered = async () => {}) {
  const before = await shown(page);
  const handle = await page.evaluate((b) => {
    const h = window.ikarus.keys.handles().find((x) => x.bone === b);
    const r = document.getElementById("plot").getBoundingClientRect();
    return { side: h.side, at: [r.left + h.at[0], r.top + h.at[1]] };
  }, bone);
  await page.mouse.move(...handle.at);
  await hovered();
  await page.mouse.click(...handle.at);
  await keysSettled(page);
  return { before, after: await shown(page), handle };
}
