// Keyframes per effector, the pure parts: the KEYS object of `ikarus animate --keys` and
// `POST /api/animate` with `keys` ({fps, tracks: {BONE: [{time, x, y, ease, k1?, k2?}]}, bends:
// {BONE: [{time, bend}]}, pins: [BONE…]}), edited as an animator edits keys: set at the playhead
// (snapped to a frame; a track's first key is at 0), moved along its row (snapped, never past a
// neighbour, the first never off 0), deleted, copied to the playhead, eased; bends keyed as steps;
// pins listed. Every edit returns a new KEYS object (the old one stays as it was: undo keeps it).
// Also the /api/animate request of a rig's keys, the frame shown at a time, and the two-bone
// limbs that get a bend handle. No DOM and no state of its own: node tests it
// (e2e/keys.unit.test.mjs). The page's wiring is keyed.js.

import { bodyForward } from "./body.js";
import { armForRequest } from "./controls.js";
import { answerPose, rigChildren, rigForRequest } from "./rig.js";
import { characterRef } from "./character.js";

/** Frames per second of new keys (the CLI's default). */
export const KEYS_FPS = 30;

/** The keyed animation's length before any key is past it, seconds. */
export const DEFAULT_LENGTH = 2;

/** The range of the keys' Length, seconds (the Length field and a project file's `key_length`). */
export const KEY_LENGTH = { min: 0.1, max: 60 };

/** An empty KEYS object. */
export const emptyKeys = (fps = KEYS_FPS) => ({ fps, tracks: {}, bends: {}, pins: [] });

/** `t` seconds snapped to the nearest frame at `fps` (k / fps, as the server computes frame times); never below 0. */
export function snapTime(t, fps) {
  const k = Math.max(0, Math.round(t * fps));
  return k / fps;
}

/** The frame index of `t` seconds at `fps`. */
export const frameOf = (t, fps) => Math.max(0, Math.round(t * fps));

/** A deep copy of `keys` with every list present (null: an empty KEYS). */
function copy(keys) {
  const k = keys || emptyKeys();
  return {
    fps: k.fps ?? KEYS_FPS,
    tracks: Object.fromEntries(Object.entries(k.tracks || {}).map(([b, list]) => [b, list.map((x) => ({ ...x }))])),
    bends: Object.fromEntries(Object.entries(k.bends || {}).map(([b, list]) => [b, list.map((x) => ({ ...x }))])),
    pins: [...(k.pins || [])],
  };
}

/** `keys` as the page keeps it: null when nothing is keyed (no track, bend or pin). */
export function tidy(keys) {
  const k = copy(keys);
  for (const [b, list] of Object.entries(k.bends)) if (!list.length) delete k.bends[b];
  for (const [b, list] of Object.entries(k.tracks)) if (!list.length) delete k.tracks[b];
  return Object.keys(k.tracks).length || Object.keys(k.bends).length || k.pins.length ? k : null;
}

/** The index of the key of `list` at frame time `t` (same frame), or -1. */
function keyAtFrame(list, t, fps) {
  return list.findIndex((k) => frameOf(k.time, fps) === frameOf(t, fps));
}

/** Puts `key` (its time a frame) into the time-ordered `list`, replacing a key on the same frame. */
function place(list, key, fps) {
  const i = keyAtFrame(list, key.time, fps);
  if (i >= 0) list[i] = key;
  else {
    list.push(key);
    list.sort((a, b) => a.time - b.time);
  }
}

/**
 * A key of bone `bone` at the playhead `t` (snapped to a frame) with target (x, y). An existing
 * key on that frame takes the new target and keeps its ease; a new key takes the ease `ease`
 * ({kind, k1, k2}: the previous key's, else sine). The first key of a track also puts one at time
 * 0 on `current` ([x, y], where the bone's tip is now) when the playhead is not at 0: a track
 * starts at 0. Returns new keys.
 */
export function setKey(keys, bone, t, x, y, current) {
  const k = copy(keys);
  const fps = k.fps;
  const time = snapTime(t, fps);
  const list = k.tracks[bone] || [];
  if (list.length === 0 && time > 0 && current) list.push({ time: 0, x: current[0], y: current[1], ease: "sine" });
  const i = keyAtFrame(list, time, fps);
  if (i >= 0) list[i] = { ...list[i], x, y };
  else {
    const before = list.filter((q) => q.time < time).at(-1);
    place(list, { time, x, y, ...easeOf(before) }, fps);
  }
  k.tracks[bone] = list;
  k.pins = k.pins.filter((p) => p !== bone);
  return k;
}

/** A key's ease fields ({ease, k1?, k2?}), sine for none. */
function easeOf(key) {
  if (!key) return { ease: "sine" };
  return { ease: key.ease || "sine", ...(key.ease === "parent" ? { k1: key.k1, k2: key.k2 } : {}) };
}

/** The list of a row: `{kind: "track" | "bend", bone}`. */
const listOf = (k, row) => (row.kind === "bend" ? k.bends : k.tracks)[row.bone] || [];

/**
 * Key `index` of `row` ({kind, bone}) moved to `t` seconds: snapped to a frame, kept strictly
 * between its neighbours' frames; the first key stays at 0. Returns {keys, index (its index
 * after: unchanged), time}.
 */
export function moveKey(keys, row, index, t) {
  const k = copy(keys);
  const list = listOf(k, row);
  const fps = k.fps;
  if (!list[index]) return { keys: k, index, time: NaN };
  if (index === 0) return { keys: k, index, time: 0 };
  const lo = frameOf(list[index - 1].time, fps) + 1;
  const hi = index + 1 < list.length ? frameOf(list[index + 1].time, fps) - 1 : Infinity;
  const f = Math.min(Math.max(frameOf(t, fps), lo), hi);
  list[index] = { ...list[index], time: f / fps };
  return { keys: k, index, time: list[index].time };
}

/**
 * Key `index` of `row` deleted. Deleting a track's first key (at 0) deletes the whole track: a
 * track must start at 0, and no other key's target stands for the start. Returns new keys.
 */
export function deleteKey(keys, row, index) {
  const k = copy(keys);
  const lists = row.kind === "bend" ? k.bends : k.tracks;
  const list = lists[row.bone];
  if (!list || !list[index]) return k;
  if (index === 0) delete lists[row.bone];
  else list.splice(index, 1);
  return k;
}

/**
 * A copy of `key` (a key of `row`, as copied) at the playhead `t` (snapped): the same target (or
 * bend) and ease, replacing a key on that frame; the first key of a new track goes at 0 whatever
 * the playhead (a track starts at 0). Returns new keys.
 */
export function pasteKey(keys, row, key, t) {
  const k = copy(keys);
  if (!key) return k;
  const lists = row.kind === "bend" ? k.bends : k.tracks;
  const list = lists[row.bone] || [];
  place(list, { ...key, time: list.length ? snapTime(t, k.fps) : 0 }, k.fps);
  lists[row.bone] = list;
  if (row.kind === "track") k.pins = k.pins.filter((p) => p !== row.bone);
  return k;
}

/** Key `index` of track `bone` eased by `ease` ({kind, k1, k2}; k1 and k2 only with "parent"). Returns new keys. */
export function setEase(keys, bone, index, ease) {
  const k = copy(keys);
  const list = k.tracks[bone];
  if (!list || !list[index]) return k;
  const { k1: _k1, k2: _k2, ...rest } = list[index];
  list[index] = { ...rest, ease: ease.kind, ...(ease.kind === "parent" ? { k1: ease.k1, k2: ease.k2 } : {}) };
  return k;
}

/** The bend in force on `bone` at `t` by `keys` (the last step key at or before t), or null. */
export function bendAt(keys, bone, t) {
  const list = (keys && keys.bends && keys.bends[bone]) || [];
  const fps = (keys && keys.fps) || KEYS_FPS;
  let side = null;
  for (const k of list) if (frameOf(k.time, fps) <= frameOf(t, fps)) side = k.bend;
  return side;
}

/**
 * A bend key on `bone` at the playhead `t` (snapped) for the side `bend` ("ccw" | "cw"); the
 * first bend key of a bone also holds `from` (the side it bends at 0 now) at 0 when the
 * playhead is not at 0. Returns new keys.
 */
export function setBend(keys, bone, t, bend, from) {
  const k = copy(keys);
  const time = snapTime(t, k.fps);
  const list = k.bends[bone] || [];
  if (list.length === 0 && time > 0) list.push({ time: 0, bend: from });
  place(list, { time, bend }, k.fps);
  k.bends[bone] = list;
  return k;
}

/** The side a joint angle (degrees) bends: "ccw" for [0°, 180°], "cw" else (the rig solve's `bend`). */
export function sideOf(angleDeg) {
  const a = ((((angleDeg + 180) % 360) + 360) % 360) - 180;
  return a >= 0 ? "ccw" : "cw";
}

/** `bone` pinned for the whole animation, or unpinned (a pinned bone has no track). Returns new keys. */
export function togglePinKey(keys, bone) {
  const k = copy(keys);
  if (k.pins.includes(bone)) k.pins = k.pins.filter((p) => p !== bone);
  else {
    k.pins.push(bone);
    delete k.tracks[bone];
  }
  return k;
}

/** The keys' duration: the largest key time over tracks and bends (0 for none). */
export function keysDuration(keys) {
  if (!keys) return 0;
  const times = [...Object.values(keys.tracks || {}), ...Object.values(keys.bends || {})].flat().map((k) => k.time);
  return times.length ? Math.max(...times) : 0;
}

/**
 * The rows the keys timeline shows, in the rig's bone order: each track ({kind: "track", bone,
 * keys}), each bend ({kind: "bend", bone, keys}) and each pin ({kind: "pin", bone, keys: []}).
 */
export function keyRows(keys, boneNames) {
  if (!keys) return [];
  const order = (names) => [...names].sort((a, b) => boneNames.indexOf(a) - boneNames.indexOf(b));
  return [
    ...order(Object.keys(keys.tracks || {})).map((bone) => ({ kind: "track", bone, keys: keys.tracks[bone] })),
    ...order(Object.keys(keys.bends || {})).map((bone) => ({ kind: "bend", bone, keys: keys.bends[bone] })),
    ...order(keys.pins || []).map((bone) => ({ kind: "pin", bone, keys: [] })),
  ];
}

/**
 * The /api/animate body of a rig's keys: the rig as a request sends it (rig.js's rigForRequest),
 * the keys as they are, the page's solver options without the arm-only rates.
 */
export function rigAnimateRequest(rig, keys, options) {
  const { rates: _rates, ...opts } = options || {};
  return { rig: rigForRequest(rig), keys, options: opts };
}

/** An arm's links as the keys name them (the arm solved as its one-branch rig): link0, link1, …, the tip's the last. */
export const armBones = (arm) => arm.links.map((_, i) => `link${i}`);

/** The arm as that one-branch rig, enough for answerPose: bones link0… with their angles. */
const armRig = (arm) => ({ bones: arm.links.map((l, i) => ({ name: `link${i}`, angle_deg: l.angle_deg })) });

/**
 * The /api/animate body of the arm's keys: the arm as the arm's requests send it (controls.js's
 * armForRequest), the keys as they are, the page's solver options (the arm's, rates and all).
 */
export function armAnimateRequest(arm, keys, options) {
  return { arm: armForRequest(arm), keys, options: options || {} };
}

/**
 * A rig's or the arm's keys as one body: `rig` (the rig, or the arm as its one-branch rig
 * link0…: enough for the poses of rigMotion and the columns of rigFramesCsv), `name` (of the
 * files saved) and `request(keys, options)` (the /api/animate body, which is also the keyed part
 * of /api/render's figure `motion`). `arm` is used when `rig` is null.
 */
export function keyedBranch(rig, arm) {
  if (rig) return { rig, name: rig.name || "rig", request: (keys, options) => rigAnimateRequest(rig, keys, options) };
  return { rig: armRig(arm), name: arm.name || "arm", request: (keys, options) => armAnimateRequest(arm, keys, options) };
}

/**
 * A number as Rust's `{:?}` writes an f64 (the CLI's CSV): the shortest text that reads back
 * to it, `.0` on a whole number, an exponent (no `+`) below 1e-4 or from 1e16 on.
 */
export function rustNumber(v) {
  const a = Math.abs(v);
  if (!Number.isFinite(v)) return Number.isNaN(v) ? "NaN" : v > 0 ? "inf" : "-inf";
  if (a !== 0 && (a < 1e-4 || a >= 1e16)) return v.toExponential().replace("e+", "e");
  return Number.isInteger(v) ? v.toFixed(1) : String(v);
}

/**
 * A rig's keyed /api/animate answer as the CSV of `ikarus animate --rig FILE --keys KEYS
 * --format csv`: `time`, each bone's `NAME_deg` then each prismatic bone's `NAME_ext`, then each
 * bone's tip `NAME.x,NAME.y`, one row per frame (time in seconds).
 */
export function rigFramesCsv(rig, answer) {
  const prismatic = rig.bones.filter((b) => b.joint === "prismatic");
  const head = ["time", ...rig.bones.map((b) => `${b.name}_deg`), ...prismatic.map((b) => `${b.name}_ext`), ...rig.bones.map((b) => `${b.name}.x,${b.name}.y`)];
  const rows = (answer.frames || []).map((f) => {
    const a = f.angles_deg || {};
    const e = f.extensions || {};
    const j = f.joints || {};
    return [f.time, ...rig.bones.map((b) => a[b.name] ?? b.angle_deg), ...prismatic.map((b) => e[b.name]), ...rig.bones.flatMap((b) => j[b.name] || [NaN, NaN])].map(rustNumber).join(",");
  });
  return [head.join(","), ...rows].join("\n") + "\n";
}

/**
 * A keyed /api/animate answer as `state.motion`: {fps, duration, frames}, each frame also given
 * `pose` (the joint values in bone order, as state.rig.pose_deg holds them).
 */
export function rigMotion(rig, answer) {
  let pose = [];
  const frames = (answer.frames || []).map((f) => {
    pose = answerPose(rig, f, pose);
    return { ...f, pose };
  });
  return { fps: answer.fps, duration: answer.duration, frames };
}

/**
 * The /api/animate body of a character's keys (`c`: characters.js's state.character): the file's
 * text, the keys (tracks, and bends when there are: a bend keys a two-bone IK constraint's side;
 * a character has no pins),
 * the clip posed under them (none: the setup pose), `ik: "ikarus"` when the reader chose
 * ikarus's solver, and the format: "json" (the frames) or "spine" (the file with the animation
 * `ikarus` added).
 */
export function characterAnimateRequest(c, keys, format = "json") {
  return {
    ...characterRef(c),
    keys: { fps: keys.fps, tracks: keys.tracks, ...(Object.keys(keys.bends || {}).length ? { bends: keys.bends } : {}) },
    ...(c.animation ? { animation: c.animation } : {}),
    ...(c.ik === "ikarus" ? { ik: "ikarus" } : {}),
    format,
    ...(format === "spine" ? { animation_name: "ikarus" } : {}),
  };
}

/**
 * A character's keyed /api/animate answer as `state.motion`: {fps (the keys'), duration, frames}
 * (each frame's `bones` as /api/pose answers them).
 */
export function characterMotion(answer, fps) {
  const frames = answer.frames || [];
  return { fps: answer.fps ?? fps, duration: answer.duration ?? (frames.length ? frames[frames.length - 1].time : 0), frames };
}

/** The frame of `motion` shown at `t` seconds: frame ⌊t·fps⌉, within the frames; null for none. */
export function frameAt(motion, t) {
  if (!motion || !motion.frames || !motion.frames.length) return null;
  const i = Math.min(frameOf(t, motion.fps), motion.frames.length - 1);
  return motion.frames[i];
}

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
