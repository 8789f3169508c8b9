// Keyframes per effector, the pure parts: the KEYS object of `ikarus animate --keys` and
// `POST /api/animate` with `keys` ({fps, tracks: {BONE: [{time, x, y, ease, k1?, k2?}]}, bends:
// {BONE: [{time, bend}]}, pins: [BONE…], rotations?: {BONE: [{time, angle_deg, ease}]}}), edited as an animator edits keys: set at the playhead
// (snapped to a frame; a track's first key is at 0), moved along its row (snapped, never past a
// neighbour, the first never off 0), deleted, copied to the playhead, eased; bends keyed as steps;
// pins listed. Every edit returns a new KEYS object (the old one stays as it was: undo keeps it).
// Also rotation keys (a character's bones turned by hand), the /api/animate requests of a rig's
// and a character's keys (with the Length as their `duration`), and the frame shown at a time.
// No DOM and no state of its own: node tests it (e2e/keys.unit.test.mjs). The page's wiring is
// keyed.js; the bend handles' geometry is bendhandles.js.

import { armForRequest } from "./controls.js";
import { answerPose, rigForRequest } from "./rig.js";
import { characterRef } from "./character.js";

/** Frames per second of new keys (the CLI's default). */
export const KEYS_FPS = 30;

/** The keyed animation's length before any key is past it, seconds. */
export const DEFAULT_LENGTH = 2;

/** The range of the keys' Length, seconds (the Length field and a project file's `key_length`). */
export const KEY_LENGTH = { min: 0.1, max: 60 };

/** An empty KEYS object. */
export const emptyKeys = (fps = KEYS_FPS) => ({ fps, tracks: {}, bends: {}, pins: [] });

/**
 * The lists of `keys` holding a row's keys by its kind: "track" → tracks, "bend" → bends,
 * "rotation" → rotations (a character's bones turned by hand: {BONE: [{time, angle_deg, ease}]},
 * each key the bone's local rotation in degrees, in place of the clip's).
 */
export const listsOf = (keys, kind) => (kind === "bend" ? keys.bends : kind === "rotation" ? keys.rotations : keys.tracks) || {};

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
    ...(k.rotations ? { rotations: Object.fromEntries(Object.entries(k.rotations).map(([b, list]) => [b, list.map((x) => ({ ...x }))])) } : {}),
  };
}

/** `keys` as the page keeps it: null when nothing is keyed (no track, bend or pin). */
export function tidy(keys) {
  const k = copy(keys);
  for (const [b, list] of Object.entries(k.bends)) if (!list.length) delete k.bends[b];
  for (const [b, list] of Object.entries(k.tracks)) if (!list.length) delete k.tracks[b];
  if (k.rotations) for (const [b, list] of Object.entries(k.rotations)) if (!list.length) delete k.rotations[b];
  if (k.rotations && !Object.keys(k.rotations).length) delete k.rotations;
  return Object.keys(k.tracks).length || Object.keys(k.bends).length || k.pins.length || k.rotations ? k : null;
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
 * A rotation key of `bone` at the playhead `t` (snapped to a frame): its local rotation
 * `angle` (degrees). An existing key on that frame takes the angle (its ease kept); a new one the
 * previous key's ease (else sine). The first key of a bone also puts one at time 0 on `current`
 * (the bone's local rotation now) when the playhead is not at 0. Returns new keys.
 */
export function setRotationKey(keys, bone, t, angle, current) {
  const k = copy(keys);
  const fps = k.fps;
  const time = snapTime(t, fps);
  k.rotations = k.rotations || {};
  const list = k.rotations[bone] || [];
  if (list.length === 0 && time > 0 && Number.isFinite(current)) list.push({ time: 0, angle_deg: current, ease: "sine" });
  const i = keyAtFrame(list, time, fps);
  if (i >= 0) list[i] = { ...list[i], angle_deg: angle };
  else {
    const before = list.filter((q) => q.time < time).at(-1);
    place(list, { time, angle_deg: angle, ...easeOf(before) }, fps);
  }
  k.rotations[bone] = list;
  return k;
}

/**
 * A bone's local rotation in degrees from a pose's world rotations (`bones`: /api/pose's, by
 * name, `parentOf` bone → parent name): its world rotation less its parent's, in (−180°, 180°].
 * Exact for parents without shear or unequal scale (a turned bone's key is what the server
 * poses; this is where a drag starts from).
 */
export function localRotation(bones, parentOf, bone) {
  const at = new Map((bones || []).map((b) => [b.name, b]));
  const b = at.get(bone);
  if (!b) return NaN;
  const p = parentOf(bone);
  const d = b.rotation_deg - (p && at.has(p) ? at.get(p).rotation_deg : 0);
  return d - 360 * Math.ceil((d - 180) / 360);
}

/** Every bone's bend in force at `t` by `keys` ({BONE: "ccw" | "cw"}; bendAt of each bend track). */
export function bendsAt(keys, t) {
  return Object.fromEntries(Object.keys((keys && keys.bends) || {}).map((b) => [b, bendAt(keys, b, t)]));
}

/**
 * The keyed targets of a character's frame: a Map bone → {x, y} of each tracked bone where the
 * frame's `bones` (/api/pose's) have its origin (the keyed motion puts it on its track there).
 */
export function keyedTargets(keys, bones) {
  const at = new Map((bones || []).map((b) => [b.name, b]));
  return new Map(
    Object.keys((keys && keys.tracks) || {})
      .filter((b) => at.has(b))
      .map((b) => [b, { x: at.get(b).x, y: at.get(b).y }]),
  );
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

/** The list of a row: `{kind: "track" | "bend" | "rotation", bone}`. */
const listOf = (k, row) => listsOf(k, row.kind)[row.bone] || [];

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
  const lists = listsOf(k, row.kind);
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
  if (row.kind === "rotation") k.rotations = k.rotations || {};
  const lists = listsOf(k, row.kind);
  const list = lists[row.bone] || [];
  place(list, { ...key, time: list.length ? snapTime(t, k.fps) : 0 }, k.fps);
  lists[row.bone] = list;
  if (row.kind === "track") k.pins = k.pins.filter((p) => p !== row.bone);
  return k;
}

/**
 * Key `index` of track `bone` (of the rotation `bone` when `kind` is "rotation") eased by `ease`
 * ({kind, k1, k2}; k1 and k2 only with "parent"). Returns new keys.
 */
export function setEase(keys, bone, index, ease, kind = "track") {
  const k = copy(keys);
  const list = listsOf(k, kind)[bone];
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

/** The keys' duration: the largest key time over tracks, bends and rotations (0 for none). */
export function keysDuration(keys) {
  if (!keys) return 0;
  const times = [...Object.values(keys.tracks || {}), ...Object.values(keys.bends || {}), ...Object.values(keys.rotations || {})].flat().map((k) => k.time);
  return times.length ? Math.max(...times) : 0;
}

/**
 * `keys` as a request sends them: with `duration`, the keyed motion's length, `length` seconds
 * (the Length field) or the last key's time if later, on a frame (the server's frames, CSV, GIF
 * and export run to it, each track holding its last key after its end). `keys` itself is left
 * as it is (its Length is the page's, kept apart from the keys).
 */
export function lengthKeys(keys, length) {
  const fps = keys.fps ?? KEYS_FPS;
  return { ...keys, duration: frameOf(Math.max(length || 0, keysDuration(keys)), fps) / fps };
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
    ...order(Object.keys(keys.rotations || {})).map((bone) => ({ kind: "rotation", bone, keys: keys.rotations[bone] })),
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
 * a character has no pins; `duration` when the keys have it: keyed.js gives them the Length),
 * the clip posed under them (none: the setup pose), `ik: "ikarus"` when the reader chose
 * ikarus's solver, `physics: false` when the physics switch is off, and the format: "json" (the
 * frames) or "spine" (the file with the animation `ikarus` added).
 */
export function characterAnimateRequest(c, keys, format = "json") {
  return {
    ...characterRef(c),
    keys: {
      fps: keys.fps,
      tracks: keys.tracks,
      ...(Object.keys(keys.bends || {}).length ? { bends: keys.bends } : {}),
      ...(Object.keys(keys.rotations || {}).length ? { rotations: keys.rotations } : {}),
      ...(keys.duration !== undefined ? { duration: keys.duration } : {}),
    },
    ...(c.animation ? { animation: c.animation } : {}),
    ...(c.ik === "ikarus" ? { ik: "ikarus" } : {}),
    // The physics switch off: the frames posed each on its own (on, they play as a game's).
    ...(c.physics === false ? { physics: false } : {}),
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
