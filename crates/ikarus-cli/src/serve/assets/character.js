// Characters (Spine and DragonBones skeletons, read by POST /api/rig/parse), the pure parts: the
// bones an IK constraint aims at (the handles the reader drags), the view that fits the setup
// pose, the /api/pose and /api/animate (Spine export) requests made of the page's choices, the
// Spine-like shape of a posed bone on the canvas, and which bone or handle the pointer is on.
// No DOM and no state of its own: node tests it (e2e/character.unit.test.mjs). The page's wiring
// is characters.js; the drawing is drawchar.js.

import { fitBox } from "./view.js";
import { optionFields } from "./charoptions.js";

/** A pointer press within this many CSS pixels of a target's handle grabs it. */
export const HANDLE_PIXELS = 12;

/** The pointer within this many CSS pixels of a bone's shape names it. */
export const BONE_PIXELS = 5;

/** A zero-length bone's circle, CSS pixels across (its radius). */
export const POINT_BONE_PIXELS = 3.5;

/** The margin around the setup pose in the view, as a share of its larger side (room for clips and drags). */
export const CHARACTER_VIEW_ROOM = 0.12;

/** The names of the bones the IK constraints aim at (`ik[].target`), each once, in file order. */
export function ikTargets(character) {
  return [...new Set((character.ik || []).map((k) => k.target))];
}

/** A clip's duration in seconds (`clips[].duration`), or 0 for none or an unknown name. */
export function clipSeconds(character, name) {
  const clip = (character.clips || []).find((c) => c.name === name);
  return clip ? clip.duration : 0;
}

/** The world box {x0, x1, y0, y1} of posed bones ([{x, y, tip: [x, y]}]): every origin and tip. */
export function posedBox(bones) {
  const xs = bones.flatMap((b) => [b.x, b.tip[0]]);
  const ys = bones.flatMap((b) => [b.y, b.tip[1]]);
  return { x0: Math.min(...xs), x1: Math.max(...xs), y0: Math.min(...ys), y1: Math.max(...ys) };
}

/** The smallest box holding boxes `a` and `b` (either may be null). */
export function unionBox(a, b) {
  if (!a || !b) return a || b || null;
  return { x0: Math.min(a.x0, b.x0), x1: Math.max(a.x1, b.x1), y0: Math.min(a.y0, b.y0), y1: Math.max(a.y1, b.y1) };
}

/** The clip's poses the view is fitted to before it plays: `n` + 1 times evenly over its `seconds`. */
export function surveyTimes(seconds, n = 8) {
  return Array.from({ length: n + 1 }, (_, k) => (seconds * k) / n);
}

/**
 * The transform that fits `box` (the setup pose's, posedBox, with the clip's survey) with CHARACTER_VIEW_ROOM of its
 * larger side around it into a `w` × `h` canvas (the page's fitBox). It depends on the setup pose
 * and the clip's survey only, so the view stays still while a clip plays or a target is dragged.
 */
export function fitCharacterView(box, w, h) {
  const side = Math.max(box.x1 - box.x0, box.y1 - box.y0, 1e-3);
  return fitBox(box, side * CHARACTER_VIEW_ROOM, w, h);
}

/**
 * How a request names the character `c` (characters.js's state: its file's `text`, and
 * `character`, /api/rig/parse's answer): by the id the backend answered when it read the file,
 * `{character: ID}` (a few bytes instead of the whole file every frame), else by the text.
 */
export function characterRef({ text, character }) {
  return character && character.id ? { character: character.id } : { rig: text };
}

/**
 * The /api/pose body of the page's choices: the character (characterRef), the clip and its time
 * (none for the setup pose; past the clip's end it loops, as under keys: clipTime), every dragged
 * target (`targets`, a Map bone → {x, y}, in the order they were first dragged; in Key mode every
 * keyed target too), the bends in force (`bends`, {lower bone: "ccw" | "cw"}, keys only), the
 * bones turned by hand (`turns`, a Map bone → its local rotation in degrees, sent as
 * `rotations`), and `ik: "ikarus"` when the reader chose ikarus's solver (the runtime's rules are
 * the endpoint's default, so the field is left out for them), and `atlas` (its id, from
 * /api/atlas/parse) when the character has art (`atlas`: {id, …}): the answer then has `art`.
 */
export function poseRequest({ text, character, animation, time, targets, ik, bends, turns, skin, physics, atlas }) {
  return {
    ...characterRef({ text, character }),
    ...optionFields({ skin, physics }),
    ...(animation ? { animation, time: clipTime(character, animation, time) } : {}),
    targets: [...targets].map(([bone, t]) => ({ bone, x: t.x, y: t.y })),
    ...(ik === "ikarus" ? { ik: "ikarus" } : {}),
    ...(bends && Object.keys(bends).length ? { bends } : {}),
    ...(turns && turns.size ? { rotations: Object.fromEntries(turns) } : {}),
    ...(atlas && atlas.id ? { atlas: atlas.id } : {}),
  };
}

/**
 * The clip's time at `t` seconds of a keyed motion over it: `t`, or past the clip's end `t % its
 * duration` (the clip loops under keys that run longer, as the server's keyed motion has it).
 */
export function clipTime(character, animation, t) {
  const length = clipSeconds(character || {}, animation);
  return length > 0 && t > length ? t % length : t;
}

/** The seconds of the motion an *Export Spine JSON* bakes, its frames per second and its ease. */
export const EXPORT = { duration: 1.0, fps: 30, ease: "sine", animation_name: "ikarus" };

/**
 * The /api/animate body of an *Export Spine JSON*: the file's text and the dragged targets; the
 * answer is the file with one added animation (EXPORT.animation_name) moving the targets from
 * the setup pose to where they were dragged.
 */
export function exportRequest({ text, character, targets }) {
  return {
    ...characterRef({ text, character }),
    targets: [...targets].map(([bone, t]) => ({ bone, x: t.x, y: t.y })),
    duration: EXPORT.duration,
    fps: EXPORT.fps,
    ease: EXPORT.ease,
    format: "spine",
    animation_name: EXPORT.animation_name,
  };
}

/**
 * What *Export Spine JSON* does for `character` (the /api/rig/parse answer's) and the keys as
 * sent (`keys`, with their `duration`; null without keys): {disabled, title}. A DragonBones
 * character cannot take it (the export adds an animation to a Spine file); with keys it exports
 * them, else the targets dragged from the setup pose.
 */
export function exportState(character, keys) {
  if (character && character.format === "dragonbones") {
    return { disabled: true, title: "The Spine export takes a Spine file; this is a DragonBones character" };
  }
  if (keys) {
    const n = [keys.tracks, keys.bends, keys.rotations].flatMap((lists) => Object.values(lists || {}).flat()).length;
    const length = Number(keys.duration ?? 0);
    return {
      disabled: false,
      title: `Download the file with one added animation, ${EXPORT.animation_name}, made of your ${n} key${n === 1 ? "" : "s"} (${length.toFixed(2)} s, the Length, at ${keys.fps} fps, over the clip chosen), to play in Spine or its runtimes`,
    };
  }
  return {
    disabled: false,
    title: `Download the file with one added animation, ${EXPORT.animation_name}, moving the targets from the setup pose to where you put them (${EXPORT.duration} s, ${EXPORT.fps} fps, ${EXPORT.ease} ease), to play in Spine or its runtimes`,
  };
}

/**
 * The download's name of a character file `name`'s export: `spineboy.json` → `spineboy-ikarus.json`;
 * a Spine binary export's too (`spineboy.skel` → `spineboy-ikarus.json`): ikarus writes JSON,
 * which Spine's editor imports.
 */
export function exportName(name) {
  const stem = String(name || "character").replace(/\.(json|skel)$/i, "") || "character";
  return `${stem}-${EXPORT.animation_name}.json`;
}

/**
 * A posed bone's shape on the canvas, from its origin `o` and tip `t` (canvas pixels): a slim
 * kite (Spine's bone shape) from the origin to the tip, widest a fifth of the way along, at most
 * 7 pixels across each side, as {kind: "kite", points: [[x, y] × 4]}; a bone of no length (in the
 * file) or shorter than a pixel on the screen is a small circle, {kind: "circle", at, r}.
 */
export function boneShape(o, t, length) {
  const dx = t[0] - o[0];
  const dy = t[1] - o[1];
  const l = Math.hypot(dx, dy);
  if (!(length > 0) || l < 1) return { kind: "circle", at: o, r: POINT_BONE_PIXELS };
  const [ux, uy] = [dx / l, dy / l];
  const [nx, ny] = [-uy, ux];
  const w = Math.min(7, Math.max(1.5, l * 0.1));
  const s = l * 0.2;
  const at = [o[0] + ux * s, o[1] + uy * s];
  return {
    kind: "kite",
    points: [o, [at[0] + nx * w, at[1] + ny * w], t, [at[0] - nx * w, at[1] - ny * w]],
  };
}

/** The distance from (px, py) to the segment from `a` to `b`. */
function segmentDistance(a, b, px, py) {
  const [dx, dy] = [b[0] - a[0], b[1] - a[1]];
  const l2 = dx * dx + dy * dy;
  const u = l2 > 0 ? Math.min(1, Math.max(0, ((px - a[0]) * dx + (py - a[1]) * dy) / l2)) : 0;
  return Math.hypot(a[0] + u * dx - px, a[1] + u * dy - py);
}

/**
 * The index of the bone under the canvas point (px, py): the nearest of the drawn bones
 * (`bonesPx`, [{o, t}] in canvas pixels, bone order) whose segment from origin to tip passes
 * within `radius` pixels (a zero-length bone: its circle); on a tie the later bone, drawn last.
 * -1 when none is.
 */
export function boneAt(bonesPx, px, py, radius = BONE_PIXELS) {
  let best = -1;
  let bestD = Infinity;
  bonesPx.forEach(({ o, t }, i) => {
    const d = segmentDistance(o, t, px, py);
    if (d <= radius && d <= bestD) {
      best = i;
      bestD = d;
    }
  });
  return best;
}

/** The target (a name of `handlesPx`, a Map name → [x, y] in canvas pixels) nearest (px, py) within `radius`, or null. */
export function handleAt(handlesPx, px, py, radius = HANDLE_PIXELS) {
  let best = null;
  let bestD = Infinity;
  for (const [name, [x, y]] of handlesPx) {
    const d = Math.hypot(x - px, y - py);
    if (d <= radius && d < bestD) {
      best = name;
      bestD = d;
    }
  }
  return best;
}

/** The constraints ikarus leaves inactive, one line each: "transform constraint shoulder" (none: []). */
export function unsupportedLines(character) {
  return (character.unsupported || []).map((u) => `${u.kind} ${u.name}`);
}

/**
 * What ikarus's solver says of a pose (the /api/pose answer's `ik`: {solver, status,
 * constraints: [{name, active, error}]}) for the chip: "ikarus solver reached", or its status and
 * each active constraint missed by more than `tolerance` with its error ("ikarus solver
 * unreachable · front-leg-ik 3.5"). The runtime's rules (no `ik`): "Spine rules".
 */
export function solverLine(ik, tolerance = 1e-3) {
  if (!ik) return "Spine rules";
  const missed = (ik.constraints || []).filter((k) => k.active && k.error > tolerance);
  return [`ikarus solver ${ik.status}`, ...missed.map((k) => `${k.name} ${Number(k.error.toPrecision(2))}`)].join(" · ");
}

/**
 * The chip's line of a character: "Spine character spineboy · 67 bones · 7 IK, 8 transform
 * constraints" (its constraints counted by kind, in the order IK, transform, path, physics).
 */
export function characterSummary(name, character) {
  const kind = character.format === "dragonbones" ? "DragonBones" : "Spine";
  const bones = character.bones.length;
  const all = character.constraints || (character.ik || []).map(() => ({ kind: "ik" }));
  const counts = ["ik", "transform", "path", "physics"]
    .map((k) => [k, all.filter((c) => c.kind === k).length])
    .filter(([, count]) => count > 0)
    .map(([k, count]) => `${count} ${k === "ik" ? "IK" : k}`);
  const total = all.length;
  const constraints = total ? `${counts.join(", ")} constraint${total === 1 ? "" : "s"}` : "no constraints";
  return `${kind} character ${name} · ${bones} bone${bones === 1 ? "" : "s"} · ${constraints}`;
}

/**
 * What each target's handle does (`character` the /api/rig/parse answer): a Map target →
 * {inactive, drives: [bone names], note}. `note` is the handle's hover text: the bones it turns
 * and by which IK constraint (every other constraint then follows them, as in Spine), or why
 * dragging it moves nothing: every IK constraint aiming at it has mix 0 (spineboy's crosshair in
 * the setup pose).
 */
export function handleNotes(character) {
  const iks = character.ik || [];
  const notes = new Map();
  for (const target of ikTargets(character)) {
    const aiming = iks.filter((k) => k.target === target);
    const active = aiming.filter((k) => k.mix !== 0);
    const drives = [...new Set(active.flatMap((k) => k.bones))];
    const by = (list) => list.map((k) => k.name).join(", ");
    const inactive = !active.length;
    const note = inactive
      ? `${target}: its IK constraint${aiming.length > 1 ? "s" : ""} ${by(aiming)} ${aiming.length > 1 ? "have" : "has"} mix 0: dragging it moves nothing`
      : `${target}: drags ${drives.join(", ")} (IK constraint ${by(active)})`;
    notes.set(target, { inactive, drives, note });
  }
  return notes;
}

/**
 * A fresh `state.character` for the file `name` (its `text`) read as `character` (the
 * /api/rig/parse answer's `character`: {format, bones, ik, clips, unsupported, …}):
 *   targetNames  the bones the IK constraints aim at (the handles);  ikBones  the bones they move (a Set)
 *   notes        Map target → {inactive, drives, note} (character.js's handleNotes): the handle's hover text
 *   animation    the clip shown ("" for the setup pose);  time  its time, seconds
 *   targets      Map bone → {x, y}, the targets the reader put somewhere (in the order first dragged;
 *                with keys, keyed.js puts every keyed target of the frame shown here)
 *   bends        with keys, the bends in force at the frame shown ({lower bone: "ccw" | "cw"}, keyed.js)
 *   turns        Map bone → its local rotation (degrees): bones turned by hand (a drag on a bone
 *                that no IK constraint moves turns it about its origin; with keys, keyed.js puts
 *                the keyed ones of the frame shown here)
 *   ik           "runtime" (Spine's rules) or "ikarus" (ikarus's solver)
 *   skin, physics  the skin chosen (null: the file's default) and whether physics plays (charoptions.js)
 *   posed        the last /api/pose answer's bones;  box  the setup pose's world box (the view fits it)
 *   clipBoxes    Map clip → the world box of its poses at surveyTimes (the view fits it too)
 *   survey       {name, times, box}: the clip being surveyed, the times still to ask, the box so far; or null
 *   request      the request of `posed`;  poses  answers received
 *   ikReport     what ikarus's solver said of `posed` (the answer's `ik`), or null under Spine's rules
 *   atlas        the art's atlas (artload.js's: {id, name, pages, byFile, images}) or null;  art  the
 *                last answer's `art` (drawn under the bones: artview.js), `artOf` its bones;  artNotice  what of it was left out
 *   busy, pending  a pose is in flight; the choices changed since it left (ask again)
 *   hover, grabbed the bone or target under the pointer, the target being dragged (names) or null
 */
export function newCharacterState(name, text, character) {
  return {
    name,
    text,
    character,
    targetNames: ikTargets(character),
    notes: handleNotes(character),
    parentOf: new Map((character.bones || []).map((b) => [b.name, b.parent])),
    ikBones: new Set((character.ik || []).flatMap((k) => k.bones)),
    animation: "",
    time: 0,
    targets: new Map(),
    bends: {},
    turns: new Map(),
    ik: "runtime",
    skin: null,
    physics: true,
    posed: null,
    box: null,
    clipBoxes: new Map(),
    survey: null,
    request: null,
    ikReport: null,
    poses: 0,
    atlas: null,
    art: null,
    artNotice: null,
    busy: false,
    pending: false,
    hover: null,
    grabbed: null,
  };
}
