// The work of the page as one plain JSON object, the pure part: `snapshot(state, settings,
// timing)` of everything a reader edits (the body, the arm, its pose, goal and via points, a
// rig's goals, pins and pose, a character's clip, time, IK switch and placed targets, the keys
// and their Length, the panel's settings and the playhead in seconds), the key that compares two
// snapshots, the project file made of one (`{"ikarus_project": 1, "saved_by": "ikarus VERSION",
// …snapshot, "key_mode", "camera"}`: the view of the work, Key mode and the zoom and pan, is
// saved with it but is not an edit, so undo never steps through it) and the file read back,
// checked field by field with one-line messages that name the field and the value, missing
// fields taken from the page's defaults and named (a file of the earlier shape, its playhead a
// fraction of the timeline in `playhead`, opens too). No DOM: node tests it
// (e2e/project.unit.test.mjs); projects.js wires it (Save, Open, drop, undo).
//
// The body: `{"kind": "arm"}` (the arm is the top-level `arm`), `{"kind": "rig", "rig": "puppet"}`
// (a shipped rig by name), `{"kind": "rig", "file": RIG}` (a loaded rig file's JSON, as
// /api/rig/parse answers it), or `{"kind": "character", "character": {"name", "format", "size",
// "sha256", "text"?}}`: an imported character by reference, its text embedded when it is under
// EMBED_BYTES so that the project opens alone. A project whose character is not embedded opens
// only while that very character (same size and SHA-256) is loaded; otherwise it says so.

/** The project-file version this page writes and reads. */
export const PROJECT_VERSION = 1;

/** A character file smaller than this (bytes of UTF-8) is embedded in the project file. */
export const EMBED_BYTES = 2 * 1024 * 1024;

import { fittedCamera, ZOOM } from "./camera.js";
import { DEFAULT_LENGTH, KEY_LENGTH } from "./keys.js";

/** A deep copy of plain JSON data. */
const copy = (v) => (v === undefined || v === null ? null : JSON.parse(JSON.stringify(v)));

const points = (map) => [...map].map(([bone, p]) => ({ bone, x: p.x, y: p.y }));

/**
 * The work of the page: `state` (main.js's), `settings` (the panel's controls by id: text of a
 * field, true/false of a check box) and `timing` ({key_length: the keys' Length, playhead_s: the
 * playhead, both seconds}). A character's text and its parse answer are held by reference
 * (`text`, `parsed`: never copied, never compared, never saved as such).
 */
export function snapshot(state, settings, timing = {}) {
  const c = state.character;
  const r = state.rig;
  let body = { kind: "arm" };
  if (c) body = { kind: "character", character: { name: c.name, format: c.character.format, text: c.text, parsed: c.character } };
  else if (r) body = r.source.startsWith("rig:") ? { kind: "rig", rig: r.source.slice(4) } : { kind: "rig", file: copy(r.rig) };
  const goal = state.goal;
  return {
    body,
    arm: copy(state.arm),
    pose_deg: state.pose_deg.slice(),
    goal: goal ? { x: goal.x, y: goal.y, ...(goal.angle_deg !== undefined ? { angle_deg: goal.angle_deg } : {}) } : null,
    via: state.via.map((p) => ({ x: p.x, y: p.y })),
    rig: r ? { goals: points(r.goals), pins: [...r.pins], pose_deg: r.pose_deg.slice() } : null,
    character: c ? { animation: c.animation, time: c.time, ik: c.ik, targets: points(c.targets), skin: c.skin, physics: c.physics } : null,
    keys: copy(state.keys),
    key_length: timing.key_length ?? DEFAULT_LENGTH,
    settings: { ...settings },
    playhead_s: timing.playhead_s ?? 0,
  };
}

/** FNV-1a of a string (32 bits, hex): tells two characters' texts apart cheaply. */
export function textHash(text) {
  let h = 0x811c9dc5;
  for (let i = 0; i < text.length; i++) {
    h ^= text.charCodeAt(i);
    h = Math.imul(h, 0x01000193) >>> 0;
  }
  return h.toString(16).padStart(8, "0");
}

let lastText = null;
let lastHash = "";

/** The string that compares two snapshots: equal strings, the same work. */
export function workKey(snap) {
  const body = snap.body;
  if (body.kind !== "character") return JSON.stringify(snap);
  const { text, parsed: _, ...rest } = body.character;
  if (text !== lastText) {
    lastText = text;
    lastHash = typeof text === "string" ? textHash(text) : "";
  }
  return JSON.stringify({ ...snap, body: { kind: body.kind, character: { ...rest, hash: lastHash } } });
}

/** Whether `text` is a project file (a JSON object with `ikarus_project`), not a rig or character. */
export function isProjectText(text) {
  if (!/^\s*\{/.test(text) || !text.includes('"ikarus_project"')) return false;
  try {
    const v = JSON.parse(text);
    return !!v && typeof v === "object" && !Array.isArray(v) && "ikarus_project" in v;
  } catch (_) {
    return false;
  }
}

/**
 * The project file of `snap`: `savedBy` ("ikarus 0.9.0"); for a character, `size` (its bytes)
 * and `sha256` (hex) of its text, which is embedded below EMBED_BYTES; `view` ({key_mode,
 * camera}: Key mode on or off, the camera's {zoom, x, y}), saved beside the work.
 */
export function projectFile(snap, savedBy, character = {}, view = {}) {
  const out = { ikarus_project: PROJECT_VERSION, saved_by: savedBy, ...snap, key_mode: !!view.key_mode, camera: { ...fittedCamera(), ...view.camera } };
  if (snap.body.kind === "character") {
    const { name, format, text } = snap.body.character;
    const ref = { name, format, size: character.size, ...(character.sha256 ? { sha256: character.sha256 } : {}) };
    if (character.size < EMBED_BYTES) ref.text = text;
    out.body = { kind: "character", character: ref };
  }
  return out;
}

/** The file name a project is saved under: the character's, rig's or arm's name + ".ikarus.json". */
export function projectName(snap) {
  const b = snap.body;
  const name = b.kind === "character" ? b.character.name.replace(/\.(json|skel)$/i, "") : b.kind === "rig" ? b.rig || (b.file && b.file.name) : snap.arm && snap.arm.name;
  return `${String(name || "ikarus").replace(/[^A-Za-z0-9_-]+/g, "-")}.ikarus.json`;
}

// ---- Reading a project file -----------------------------------------------------------------

/** A value as a message quotes it: JSON, cut at 40 characters. */
function quote(v) {
  const s = JSON.stringify(v);
  if (s === undefined) return String(v);
  return s.length > 40 ? `${s.slice(0, 39)}…` : s;
}

/** The one-line refusal of field `path` holding `v`. */
const refuse = (path, v, why) => new Error(`project file: ${path} = ${quote(v)} ${why}`);

const isObject = (v) => !!v && typeof v === "object" && !Array.isArray(v);

function num(v, path) {
  if (typeof v !== "number" || !Number.isFinite(v)) throw refuse(path, v, "is not a number");
  return v;
}

function str(v, path) {
  if (typeof v !== "string") throw refuse(path, v, "is not a string");
  return v;
}

function bool(v, path) {
  if (typeof v !== "boolean") throw refuse(path, v, "is not true or false");
  return v;
}

function obj(v, path) {
  if (!isObject(v)) throw refuse(path, v, "is not an object");
  return v;
}

function list(v, path) {
  if (!Array.isArray(v)) throw refuse(path, v, "is not a list");
  return v;
}

/** `v` (a number) when it is from `range.min` to `range.max`, else the refusal naming them (and `unit`). */
function within(v, path, range, unit) {
  if (v < range.min || v > range.max) throw refuse(path, v, `is not from ${range.min} to ${range.max}${unit}`);
  return v;
}

function oneOf(v, path, choices) {
  if (!choices.includes(v)) throw refuse(path, v, `is not one of ${choices.join(", ")}`);
  return v;
}

function point(p, path) {
  obj(p, path);
  return { x: num(p.x, `${path}.x`), y: num(p.y, `${path}.y`) };
}

function bonePoints(v, path, bones) {
  return list(v, path).map((p, i) => {
    const at = `${path}[${i}]`;
    obj(p, at);
    const bone = str(p.bone, `${at}.bone`);
    if (bones && !bones.includes(bone)) throw refuse(`${at}.bone`, bone, "is not a bone of the body");
    return { bone, ...point(p, at) };
  });
}

function checkArm(arm, path) {
  obj(arm, path);
  const links = list(arm.links, `${path}.links`);
  if (links.length === 0) throw refuse(`${path}.links`, links, "has no link");
  links.forEach((l, i) => {
    const at = `${path}.links[${i}]`;
    obj(l, at);
    if (num(l.length, `${at}.length`) <= 0) throw refuse(`${at}.length`, l.length, "is not above 0");
    num(l.angle_deg, `${at}.angle_deg`);
    if (l.limits_deg !== undefined && l.limits_deg !== null) {
      const lim = list(l.limits_deg, `${at}.limits_deg`);
      if (lim.length !== 2) throw refuse(`${at}.limits_deg`, lim, "is not [min, max]");
      lim.forEach((v, k) => num(v, `${at}.limits_deg[${k}]`));
    }
    if (l.rate !== undefined) num(l.rate, `${at}.rate`);
  });
  if (arm.base !== undefined) list(arm.base, `${path}.base`).forEach((v, k) => num(v, `${path}.base[${k}]`));
  return copy(arm);
}

function angles(v, path, n) {
  const a = list(v, path).map((x, i) => num(x, `${path}[${i}]`));
  if (a.length !== n) throw refuse(path, v, `has ${a.length} values, not ${n}`);
  return a;
}

/** The KEYS object (the shape of `ikarus animate --keys`), checked for types; the server checks the rest. */
export function checkKeys(keys, path = "keys") {
  obj(keys, path);
  if (keys.fps !== undefined) num(keys.fps, `${path}.fps`);
  for (const [field, row] of [
    ["tracks", (k, at) => (num(k.x, `${at}.x`), num(k.y, `${at}.y`), k.ease !== undefined && str(k.ease, `${at}.ease`), ["k1", "k2", "angle_deg"].forEach((f) => k[f] !== undefined && num(k[f], `${at}.${f}`)))],
    ["bends", (k, at) => oneOf(k.bend, `${at}.bend`, ["ccw", "cw"])],
  ]) {
    if (keys[field] === undefined) continue;
    for (const [bone, track] of Object.entries(obj(keys[field], `${path}.${field}`))) {
      list(track, `${path}.${field}.${bone}`).forEach((k, i) => {
        const at = `${path}.${field}.${bone}[${i}]`;
        obj(k, at);
        num(k.time, `${at}.time`);
        row(k, at);
      });
    }
  }
  if (keys.pins !== undefined) list(keys.pins, `${path}.pins`).forEach((p, i) => str(p, `${path}.pins[${i}]`));
  return copy(keys);
}

/**
 * The project file `file` (parsed JSON) read against the page: `page` is {defaults (a snapshot
 * of the page as it starts: its arm and settings), rigs (Map shipped rig name -> rig JSON),
 * choices (the values a list of the settings offers, by id: a value outside them is refused)}.
 * Returns {snap (its playhead `playhead_s`, or `playhead`, a fraction, from a file of the earlier
 * shape), view ({key_mode, camera}), defaulted (the fields missing and taken from the
 * defaults)}, or throws an Error
 * with a one-line message naming the field and its value. A character that is not embedded comes
 * back with `text` undefined (projects.js matches it with the one loaded).
 */
export function readProject(file, page) {
  if (!isObject(file)) throw new Error(`project file: not a JSON object (${quote(file)})`);
  const version = file.ikarus_project;
  if (!Number.isInteger(version) || version < 1) throw refuse("ikarus_project", version, "is not a version number");
  if (version > PROJECT_VERSION) throw new Error(`project file: version ${version} is newer than this page reads (${PROJECT_VERSION}); update ikarus`);
  const defaulted = [];
  const field = (name) => {
    if (file[name] === undefined) defaulted.push(name);
    return file[name];
  };
  const d = page.defaults;

  const rawBody = field("body") ?? { kind: "arm" };
  obj(rawBody, "body");
  const kind = oneOf(rawBody.kind, "body.kind", ["arm", "rig", "character"]);
  let body = { kind };
  let bones = null;
  if (kind === "rig" && rawBody.rig !== undefined) {
    const name = str(rawBody.rig, "body.rig");
    if (!page.rigs.has(name)) throw refuse("body.rig", name, `is not a shipped rig (${[...page.rigs.keys()].join(", ")})`);
    body.rig = name;
    bones = page.rigs.get(name).bones.map((b) => b.name);
  } else if (kind === "rig") {
    const rig = obj(rawBody.file, "body.file");
    const list_ = list(rig.bones, "body.file.bones");
    if (list_.length === 0) throw refuse("body.file.bones", list_, "has no bone");
    list_.forEach((b, i) => (obj(b, `body.file.bones[${i}]`), str(b.name, `body.file.bones[${i}].name`), num(b.length, `body.file.bones[${i}].length`)));
    body.file = copy(rig);
    bones = list_.map((b) => b.name);
  } else if (kind === "character") {
    const c = obj(rawBody.character, "body.character");
    const ref = { name: str(c.name, "body.character.name"), format: c.format === undefined ? undefined : str(c.format, "body.character.format") };
    if (c.size !== undefined) ref.size = num(c.size, "body.character.size");
    if (c.sha256 !== undefined) ref.sha256 = str(c.sha256, "body.character.sha256");
    if (c.text !== undefined) ref.text = str(c.text, "body.character.text");
    else if (!ref.sha256) throw refuse("body.character", { name: ref.name }, "has neither text nor sha256: it cannot be found");
    body.character = ref;
  }

  const arm = file.arm === undefined ? (defaulted.push("arm"), copy(d.arm)) : checkArm(file.arm, "arm");
  const n = arm.links.length;
  const pose = field("pose_deg");
  const snap = {
    body,
    arm,
    pose_deg: pose === undefined ? arm.links.map((l) => l.angle_deg) : angles(pose, "pose_deg", n),
    goal: null,
    via: [],
    rig: null,
    character: null,
    keys: null,
    key_length: d.key_length ?? DEFAULT_LENGTH,
    settings: {},
    playhead_s: 0,
  };
  const goal = field("goal");
  if (goal !== undefined && goal !== null) {
    snap.goal = point(goal, "goal");
    if (goal.angle_deg !== undefined) snap.goal.angle_deg = num(goal.angle_deg, "goal.angle_deg");
  }
  const via = field("via");
  if (via !== undefined) snap.via = list(via, "via").map((p, i) => point(p, `via[${i}]`));

  if (kind === "rig") {
    const r = field("rig") ?? {};
    obj(r, "rig");
    const rig = body.file || page.rigs.get(body.rig);
    snap.rig = {
      goals: r.goals === undefined ? [] : bonePoints(r.goals, "rig.goals", bones),
      pins: r.pins === undefined ? [] : list(r.pins, "rig.pins").map((p, i) => oneOf(str(p, `rig.pins[${i}]`), `rig.pins[${i}]`, bones)),
      pose_deg: r.pose_deg === undefined ? null : angles(r.pose_deg, "rig.pose_deg", rig.bones.length),
    };
  }
  if (kind === "character") {
    const c = field("character") ?? {};
    obj(c, "character");
    snap.character = {
      animation: c.animation === undefined ? "" : str(c.animation, "character.animation"),
      time: c.time === undefined ? 0 : num(c.time, "character.time"),
      ik: c.ik === undefined ? "runtime" : oneOf(c.ik, "character.ik", ["runtime", "ikarus"]),
      targets: c.targets === undefined ? [] : bonePoints(c.targets, "character.targets", null),
      // A project saved before these were: the file's default skin, physics on (nothing to say).
      skin: c.skin === undefined || c.skin === null ? null : str(c.skin, "character.skin"),
      physics: c.physics === undefined ? true : bool(c.physics, "character.physics"),
    };
  }
  const keys = field("keys");
  if (keys !== undefined && keys !== null) snap.keys = checkKeys(keys);
  const length = field("key_length");
  if (length !== undefined) snap.key_length = within(num(length, "key_length"), "key_length", KEY_LENGTH, " seconds");

  const settings = field("settings") ?? {};
  obj(settings, "settings");
  for (const [id, def] of Object.entries(d.settings)) {
    const v = settings[id];
    if (v === undefined) {
      if (file.settings !== undefined) defaulted.push(`settings.${id}`);
      snap.settings[id] = def;
    } else if (typeof def === "boolean") {
      if (typeof v !== "boolean") throw refuse(`settings.${id}`, v, "is not true or false");
      snap.settings[id] = v;
    } else {
      if (typeof v !== "string" && !(typeof v === "number" && Number.isFinite(v))) throw refuse(`settings.${id}`, v, "is not a value of the field");
      const choices = page.choices && page.choices[id];
      if (choices) oneOf(String(v), `settings.${id}`, choices);
      snap.settings[id] = String(v);
    }
  }
  // The playhead in seconds; a file of the earlier shape holds a fraction of its timeline instead.
  if (file.playhead_s !== undefined) {
    if (num(file.playhead_s, "playhead_s") < 0) throw refuse("playhead_s", file.playhead_s, "is below 0 seconds");
    snap.playhead_s = file.playhead_s;
  } else if (file.playhead !== undefined) {
    num(file.playhead, "playhead");
    if (file.playhead < 0 || file.playhead > 1) throw refuse("playhead", file.playhead, "is not from 0 to 1");
    delete snap.playhead_s;
    snap.playhead = file.playhead;
  } else defaulted.push("playhead_s");

  // The view saved with the work: Key mode and the camera.
  const view = { key_mode: false, camera: fittedCamera() };
  const mode = field("key_mode");
  if (mode !== undefined) {
    if (typeof mode !== "boolean") throw refuse("key_mode", mode, "is not true or false");
    view.key_mode = mode;
  }
  const camera = field("camera");
  if (camera !== undefined) {
    obj(camera, "camera");
    view.camera = { zoom: within(num(camera.zoom, "camera.zoom"), "camera.zoom", ZOOM, ""), x: num(camera.x, "camera.x"), y: num(camera.y, "camera.y") };
  }
  return { snap, view, defaulted };
}
