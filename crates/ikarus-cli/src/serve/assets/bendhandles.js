// The bend handles, the pure parts: the two-bone limbs of a rig that get one (bendLimbs), each
// handle posed on the canvas for a rig (bendHandles) or a character (characterBendHandles), the
// handle under the pointer, and whether a joint's limits let it bend to a side. No DOM: node tests
// it (e2e/keys.unit.test.mjs). The page's wiring is keybends.js; the keys they make, keys.js.

import { bodyForward } from "./body.js";
import { rigChildren } from "./rig.js";
import { sideOf } from "./keys.js";

/**
 * The two-bone limbs of a rig that get a bend handle, as [{bone, upper, end}]: `bone` is the
 * lower bone, at whose start the middle joint (knee, elbow) bends (the bend key's name),
 * `upper` its parent, `end` the effector. For each effector (a leaf) E: if E's parent B has E as
 * its only child and B's parent A has B as its only child, the limb is A–B with E on its end
 * (a leg with a foot: the knee at B's start); else if E's parent has E as its only child, the
 * limb is that parent and E (a two-bone arm: the joint at E's start). File order, each bone once.
 */
export function bendLimbs(rig) {
  const children = rigChildren(rig);
  const index = new Map(rig.bones.map((b, i) => [b.name, i]));
  const parentOf = (i) => {
    const p = rig.bones[i].parent;
    return p === undefined || p === null ? undefined : index.get(p);
  };
  const only = (p, c) => p !== undefined && children[p].length === 1 && children[p][0] === c;
  const revolute = (i) => rig.bones[i].joint !== "prismatic";
  const out = new Map();
  rig.bones.forEach((_, e) => {
    if (children[e].length) return;
    const b = parentOf(e);
    const a = b === undefined ? undefined : parentOf(b);
    let limb = null;
    if (only(b, e) && only(a, b)) limb = { bone: b, upper: a, end: e };
    else if (only(b, e)) limb = { bone: e, upper: b, end: e };
    if (limb && revolute(limb.bone) && !out.has(limb.bone)) {
      out.set(limb.bone, { bone: rig.bones[limb.bone].name, upper: rig.bones[limb.upper].name, end: rig.bones[limb.end].name });
    }
  });
  return [...out.keys()].sort((x, y) => x - y).map((i) => out.get(i));
}

/** A bend handle's distance from its joint, CSS pixels (beside the knee, not on the thigh's tip). */
export const BEND_OFFSET_PIXELS = 18;

/** A press within this many CSS pixels of a bend handle flips it. */
export const BEND_PICK_PIXELS = 8;

/**
 * Each bend handle of `rig` posed by `pose` in canvas pixels, through `toCanvas(x, y)` (the
 * page's view): [{bone, side, at: [x, y], joint: [x, y]}] (handleOf); `side` is the lower
 * bone's bend now.
 */
export function bendHandles(rig, pose, toCanvas) {
  const fk = bodyForward(rig, pose);
  const index = new Map(rig.bones.map((b, i) => [b.name, i]));
  return bendLimbs(rig).map(({ bone, upper }) => {
    const i = index.get(bone);
    const side = sideOf(pose[i] ?? rig.bones[i].angle_deg);
    return handleOf(bone, side, toCanvas(...fk.starts[index.get(upper)]), toCanvas(...fk.starts[i]), toCanvas(...fk.tips[i]));
  });
}

/**
 * Each bend handle of a character: one per two-bone IK constraint (`ik`, the file's as
 * /api/rig/parse lists them, `bones` [upper, lower]), at its lower bone's origin as `posed` (the
 * bones as /api/pose answers them: {name, x, y, rotation_deg, tip}) has it, in canvas pixels;
 * `side` the way the lower bone turns from the upper one on the screen ("ccw" or "cw", as a bend
 * key names it).
 */
export function characterBendHandles(ik, posed, toCanvas) {
  const at = new Map((posed || []).map((b) => [b.name, b]));
  return (ik || [])
    .filter((k) => k.bones.length === 2 && at.has(k.bones[0]) && at.has(k.bones[1]))
    .map((k) => {
      const [u, l] = k.bones.map((b) => at.get(b));
      const side = Math.sin(((l.rotation_deg - u.rotation_deg) * Math.PI) / 180) >= 0 ? "ccw" : "cw";
      return handleOf(l.name, side, toCanvas(u.x, u.y), toCanvas(l.x, l.y), toCanvas(...l.tip));
    });
}

/**
 * The bend handle of the limb root → joint → tip (canvas pixels) whose lower bone is `bone`,
 * bending `side`: {bone, side, at, joint}, the handle BEND_OFFSET_PIXELS from the joint on the
 * side the joint points to (away from the line from the limb's root to its end), so that it shows
 * which way the limb bends.
 */
function handleOf(bone, side, root, joint, tip) {
  // Away from the root–tip line, through the joint; a straight limb: to the side it would bend.
  const [dx, dy] = [tip[0] - root[0], tip[1] - root[1]];
  const l = Math.hypot(dx, dy) || 1;
  // The canvas's y points down: a ccw bend puts the joint to the right of root → tip on the screen.
  let [nx, ny] = [-dy / l, dx / l];
  const off = (joint[0] - root[0]) * nx + (joint[1] - root[1]) * ny;
  if (Math.abs(off) > 0.5) {
    if (off < 0) [nx, ny] = [-nx, -ny];
  } else if (side === "ccw") [nx, ny] = [-nx, -ny];
  return { bone, side, joint, at: [joint[0] + nx * BEND_OFFSET_PIXELS, joint[1] + ny * BEND_OFFSET_PIXELS] };
}

/** The bone of the bend handle nearest (px, py) within BEND_PICK_PIXELS, or null. */
export function bendHandleAt(handles, px, py, radius = BEND_PICK_PIXELS) {
  let best = null;
  let bestD = Infinity;
  for (const h of handles) {
    const d = Math.hypot(h.at[0] - px, h.at[1] - py);
    if (d <= radius && d < bestD) {
      best = h.bone;
      bestD = d;
    }
  }
  return best;
}

/**
 * Whether `bone`'s joint range (limits_deg, when `limits` are on) lets it bend to `side`: a cw
 * side needs some of [−180°, 0°), ccw some of (0°, 180°]. No limits: always.
 */
export function bendAllowed(boneDef, side, limits) {
  if (!limits || !boneDef.limits_deg) return true;
  const [lo, hi] = boneDef.limits_deg;
  return side === "ccw" ? hi > 0 : lo < 0;
}
