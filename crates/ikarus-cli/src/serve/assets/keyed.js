// Keyframes on the page for a rig, a character or the arm (issue 28): the keys bar and rows under the
// timeline, Key mode (a drag of an effector or an IK target keys its target at the playhead; on
// a rig a click pins the tip for the whole animation), the bend handles at a rig's or a
// character's knees and elbows (keybends.js), and the keyed motion: after every edit
// of the keys POST /api/animate with the rig (or the character file's text, its clip and IK
// choice), `keys` and the solver options (one request in flight, latest wins), played by the
// timeline (timeline.js's loadClip: frame ⌊t·fps⌉ of the answer shown, never blended), and its
// frames saved as JSON, CSV and GIF (keyexports.js). A character without keys leaves the
// timeline to its clip (characters.js) and keys at the clip's time. The pure parts are keys.js,
// the drawing drawkeys.js.
//
// It writes `state.keys` (the KEYS object of `ikarus animate --keys`, or null) and
// `state.motion` ({fps, duration, frames}, each frame with `pose` in bone order, or null).

import * as api from "./api.js";
import { bodyForward } from "./body.js";
import { ownsKeys } from "./input.js";
import { exportState } from "./character.js";
import {
  armBones,
  bendsAt,
  characterAnimateRequest,
  characterMotion,
  DEFAULT_LENGTH,
  deleteKey,
  frameAt,
  frameOf,
  KEY_LENGTH,
  keyedBranch,
  keyedTargets,
  keyRows,
  keysDuration,
  lengthKeys,
  listsOf,
  localRotation,
  moveKey,
  pasteKey,
  rigMotion,
  setEase,
  setKey,
  setRotationKey,
  tidy,
  togglePinKey,
} from "./keys.js";
import { drawRows, pickKey, rowAxis } from "./drawkeys.js";
import { wireBendHandles } from "./keybends.js";
import { wireKeyExports } from "./keyexports.js";

const $ = (id) => document.getElementById(id);

/**
 * Wires the keys of a rig, a character or the arm. `act` is {timeline (timeline.js's), draw(), setPose(pose) (the arm's),
 * requestDraw(), showError(e), setStatus(s), say(text), edited(what) (called once after each
 * edit of the keys: undo records it), clipBack() (a character's clip takes the timeline again)}.
 * Returns {enter(), leave(), resume() (the body shown gets back the keys it left with), setLength(s),
 * length() (the keys' Length, seconds), mode() (Key mode on), clipChanged(), spineRequest(), applyKeys(keys), resolve(), handles()
 * (the bend handles in canvas pixels), hovering(), dragEnded(bone, goal, from), pinToggled(bone),
 * bendPress(ev), hoverBend(ev), drawOver(ctx), settled(), setMode(on), seek(t), fillEases(meta)}.
 */
export function wireKeyed(state, canvas, act) {
  /**
   * mode       Key mode on (drags key, clicks pin for the animation)
   * length     the animation's length the reader chose, seconds (the timeline spans at least the last key)
   * t          the playhead, seconds;  selected  {kind, bone, index} of the selected key, or null
   * clipboard  {row, key} copied by Ctrl-C;  drag  a key being dragged along its row, or null
   * busy, pending, answer  a motion request in flight, the keys changed since (ask again), the last answer
   * hover      the bend handle under the pointer (a bone name), or null
   * loaded     the seconds of the keys the timeline plays, or null while it plays something else
   */
  const k = { mode: false, length: DEFAULT_LENGTH, t: 0, selected: null, clipboard: null, drag: null, busy: false, pending: false, answer: null, hover: null, loaded: null };
  state.keys = null;
  state.motion = null;
  /** The files' buttons (keyexports.js), once wired. */
  let exportsBar = null;

  const fps = () => (state.keys && state.keys.fps) || 30;
  const seconds = () => Math.max(k.length, keysDuration(state.keys));
  /** `keys` as the requests send them: with the Length as their `duration` (keys.js's lengthKeys). */
  const sent = (keys) => lengthKeys(keys, k.length);
  /** Whether the arm is shown (no rig, no character): its tip's track is `linkN-1`. */
  const armShown = () => !state.rig && !state.character && !!state.arm;
  /** The body keyed: the rig, the character or the arm shown. */
  const body = () => state.rig || state.character || (armShown() ? state.arm : null);
  const boneNames = () => (state.rig ? state.rig.rig.bones.map((b) => b.name) : state.character ? state.character.character.bones.map((b) => b.name) : state.arm ? armBones(state.arm) : []);
  const rows = () => (body() ? keyRows(state.keys, boneNames()) : []);
  /** A rig's or the arm's keys as one body (keys.js's keyedBranch: its rig, file name, request); null for a character. */
  const branch = () => (state.character ? null : keyedBranch(state.rig ? state.rig.rig : null, state.arm));
  /**
   * Whether the timeline plays the keys: a rig's always, a character's once it has keys, the
   * arm's once it has keys and while Key mode is on (off, its clicks' motions take the timeline).
   */
  const owns = () => !!state.rig || (!!state.character && !!state.keys) || (armShown() && !!state.keys && k.mode);
  /**
   * Each body's keys while another body shows (by slot(): a rig's state object, a character, or
   * ARM, the arm whatever its links), given back by resume(); `owner` is the slot of the body
   * `state.keys` belong to.
   */
  const kept = new WeakMap();
  const ARM = {};
  const slot = () => state.rig || state.character || (armShown() ? ARM : null);
  let owner = null;
  /** The keys shown kept with their body (none: nothing kept), as the canvas changes body. */
  function stash() {
    if (owner && state.keys) kept.set(owner, state.keys);
    else if (owner) kept.delete(owner);
    owner = null;
  }

  // ---- The timeline ----------------------------------------------------------------------

  /** The timeline to the keys (or a character's clip without keys), the playhead kept at `k.t`. */
  function takeTimeline() {
    if (owns()) loadClip();
    else if (state.character) {
      k.loaded = null;
      act.clipBack();
    } else if (k.loaded !== null) {
      // The arm without keys: the timeline to its own motions again.
      k.loaded = null;
      act.timeline.unload();
    }
  }

  /** The timeline plays the keyed animation (its length), the playhead kept at `k.t`. */
  function loadClip() {
    const at = k.t;
    const s = seconds();
    k.loaded = s;
    act.timeline.loadClip({ seconds: s, fps: fps(), show: showAt });
    if (at > 0) act.timeline.seek(Math.min(at / s, 1));
  }

  /** The playhead at `t` seconds: the motion's frame there shown (its pose, targets and pins). */
  function showAt(t) {
    k.t = t;
    const r = state.rig;
    const c = state.character;
    const f = frameAt(state.motion, t);
    if (c && f) {
      // The frame's time: a drag poses at it (characters.js), every key applied there.
      c.time = f.time;
      c.posed = f.bones;
      // Every keyed target where the frame has it and the bends in force, so that a drag moves
      // one target and poses with all the others held on their keys.
      c.targets = keyedTargets(state.keys, f.bones);
      c.bends = bendsAt(state.keys, f.time);
      // The bones keyed by hand there, each one's local rotation.
      c.turns = new Map(Object.keys(state.keys.rotations || {}).map((b) => [b, localRotation(f.bones, (n) => c.parentOf.get(n), b)]));
      document.body.dataset.keyFrame = String(Math.min(frameOf(t, state.motion.fps), state.motion.frames.length - 1));
    } else if (r && f) {
      r.pose_deg = f.pose.slice();
      Object.assign(r, bodyForward(r.rig, r.pose_deg));
      r.goals = new Map(Object.entries(f.targets || {}).map(([b, [x, y]]) => [b, { x, y }]));
      r.pins = new Set(state.keys ? state.keys.pins : []);
      document.body.dataset.keyFrame = String(Math.min(frameOf(t, state.motion.fps), state.motion.frames.length - 1));
    } else if (armShown() && f) {
      act.setPose(f.pose);
      // The tip's keyed target there is the goal drawn (not the last followed one).
      const target = (f.targets || {})[`link${state.arm.links.length - 1}`];
      state.goal = target ? { x: target[0], y: target[1] } : null;
      document.body.dataset.keyFrame = String(Math.min(frameOf(t, state.motion.fps), state.motion.frames.length - 1));
    }
    syncBar();
    act.draw();
  }

  /** The bar's buttons and the rows. */
  function syncBar() {
    const mode = $("key-mode");
    mode.setAttribute("aria-pressed", String(k.mode));
    $("arm-key-mode").checked = k.mode;
    // The arm's keys bar shows in Key mode or once it has keys (the CSS hides it else); while its
    // keys play, its click motions' controls (duration, ease, via points, replay) step aside.
    document.body.classList.toggle("arm-keys", k.mode || !!state.keys);
    document.body.classList.toggle("arm-keyed", armShown() && k.loaded !== null);
    const sel = selectedKey();
    const ease = $("key-ease");
    ease.disabled = !sel || (k.selected.kind !== "track" && k.selected.kind !== "rotation");
    if (!ease.disabled) ease.value = sel.ease || "sine";
    $("key-delete").disabled = !sel;
    $("key-frames-json").disabled = !k.answer;
    $("key-gif").disabled = !k.answer || (!!exportsBar && exportsBar.gifOff());
    $("key-frames-csv").disabled = !k.answer;
    if (state.character) {
      // *Export Spine JSON* says what it exports (the keys when there are) or why it cannot.
      const e = exportState(state.character.character, state.keys ? sent(state.keys) : null);
      Object.assign($("export-spine"), { disabled: e.disabled, title: e.title });
    }
    drawRows($("key-rows"), rows(), seconds(), k.t, k.selected);
  }

  function selectedKey() {
    const s = k.selected;
    if (!s || !state.keys) return null;
    const list = listsOf(state.keys, s.kind)[s.bone];
    return (list && list[s.index]) || null;
  }

  // ---- Edits -----------------------------------------------------------------------------

  /** After an edit: the keys kept tidy, the timeline as long as they are, undo told, the motion asked again. */
  function commit(what) {
    state.keys = tidy(state.keys);
    if (!selectedKey()) k.selected = null;
    // The timeline as long as the keys, or back to a character's clip without them (the arm's
    // own motions may have taken it meanwhile: its keys take it back).
    if (armShown() || (owns() ? seconds() !== k.loaded : k.loaded !== null)) takeTimeline();
    owner = slot();
    act.edited(what);
    requestMotion();
    syncBar();
  }

  /** Where `bone`'s tip (a character: its origin) is at time 0 of the motion shown, if it has one. */
  function tipAtStart(bone) {
    const f = state.motion && state.motion.frames[0];
    if (f && f.bones) {
      const b = f.bones.find((x) => x.name === bone);
      return b ? [b.x, b.y] : null;
    }
    return f && f.joints && f.joints[bone] ? f.joints[bone] : null;
  }

  /**
   * A drag of `bone`'s goal (a rig's effector, a character's IK target) ended at `goal` ({x, y})
   * from `from` (where it was when grabbed): in Key mode, a key at the playhead (a character
   * without keys yet: at its clip's time).
   */
  function dragEnded(bone, goal, from) {
    if (!k.mode || !goal) return false;
    if (state.character && !state.keys) k.t = state.character.time;
    state.keys = setKey(state.keys, bone, k.t, goal.x, goal.y, tipAtStart(bone) || from);
    const list = state.keys.tracks[bone];
    k.selected = { kind: "track", bone, index: list.findIndex((q) => frameOf(q.time, fps()) === frameOf(k.t, fps())) };
    commit(`key ${bone} at ${(frameOf(k.t, fps()) / fps()).toFixed(2)} s`);
    return true;
  }

  /**
   * A drag of a character's bone turned it to `angle` (its local rotation, degrees) from
   * `start` (where it was when grabbed): in Key mode, a rotation key at the playhead (a character
   * without keys yet: at its clip's time).
   */
  function turnEnded(bone, angle, start) {
    if (!k.mode || !Number.isFinite(angle)) return false;
    if (state.character && !state.keys) k.t = state.character.time;
    const f = state.motion && state.motion.frames[0];
    const current = f && f.bones ? localRotation(f.bones, (n) => state.character.parentOf.get(n), bone) : start;
    state.keys = setRotationKey(state.keys, bone, k.t, angle, Number.isFinite(current) ? current : start);
    const list = state.keys.rotations[bone];
    k.selected = { kind: "rotation", bone, index: list.findIndex((q) => frameOf(q.time, fps()) === frameOf(k.t, fps())) };
    commit(`key ${bone}'s turn at ${(frameOf(k.t, fps()) / fps()).toFixed(2)} s`);
    return true;
  }

  /** A click on `bone`'s tip: in Key mode, pinned (or unpinned) for the whole animation. */
  function pinToggled(bone) {
    if (!k.mode) return false;
    state.keys = togglePinKey(state.keys, bone);
    commit(`${state.keys.pins.includes(bone) ? "pin" : "unpin"} ${bone}`);
    return true;
  }

  const { handles, bendPress, hoverBend, drawOver } = wireBendHandles({ state, k, canvas, act, commit });

  // ---- The motion ------------------------------------------------------------------------

  /** The chip's line for a keyed answer: `keyed motion · 25 frames at 30 fps · 25 reached` (a character's without reached). */
  function keyedSummary(answer) {
    const reached = answer.frames.filter((f) => f.status === "reached").length;
    return `keyed motion · ${answer.frames.length} frames at ${answer.fps ?? state.keys.fps} fps${state.character ? "" : ` · ${reached} reached`}`;
  }

  function requestMotion() {
    k.pending = true;
    pump();
  }

  async function pump() {
    const b = body();
    if (!b || k.busy || !k.pending) return;
    k.pending = false;
    const keys = state.keys;
    if (!keys || !(Object.keys(keys.tracks).length || Object.keys(keys.rotations || {}).length)) {
      state.motion = null;
      k.answer = null;
      syncBar();
      return;
    }
    k.busy = true;
    const req = state.character ? characterAnimateRequest(state.character, sent(keys), "json") : branch().request(sent(keys), state.options);
    act.setStatus("solving");
    try {
      const answer = await api.animate(req);
      if (body() === b && state.keys === keys) {
        state.motion = state.character ? characterMotion(answer, keys.fps) : rigMotion(branch().rig, answer);
        k.answer = answer;
        const reached = answer.frames.filter((f) => f.status === "reached").length;
        act.showError(null);
        act.setStatus(state.character || reached === answer.frames.length ? "ready" : "unreachable");
        act.say(keyedSummary(answer));
        // The arm's keys out of Key mode: their motion is ready, the arm's own motion stays shown.
        if (owns()) showAt(k.t);
        else syncBar();
      }
    } catch (e) {
      if (body() === b) {
        act.showError(e);
        act.setStatus("error");
      }
    }
    k.busy = false;
    pump();
  }

  /** Whether no motion is in flight or waiting (for tests and scripts). */
  const settled = () => !k.busy && !k.pending;

  // ---- Entering and leaving a rig, restoring keys ----------------------------------------

  /**
   * A rig or a character took the canvas (the keys shown before are kept with their body): no
   * keys yet (resume() gives back its own); a rig's timeline spans the length.
   */
  function enter() {
    stash();
    owner = slot();
    k.loaded = null;
    state.keys = null;
    state.motion = null;
    k.answer = null;
    k.selected = null;
    k.t = 0;
    if (state.rig) loadClip();
    syncBar();
  }

  /** A character's clip changed: the keyed motion is made over the new one. */
  function clipChanged() {
    loadClip();
    requestMotion();
  }

  /** The body shown leaves the canvas: its keys kept with it (resume() gives them back). */
  function leave() {
    stash();
    k.loaded = null;
    state.keys = null;
    state.motion = null;
    k.answer = null;
    k.selected = null;
    syncBar();
  }

  /** The body shown again (a rig, a character, the arm): the keys it had when it left, if any. */
  function resume() {
    const b = slot();
    const keys = b && kept.get(b);
    if (!keys) return;
    kept.delete(b);
    applyKeys(keys);
  }

  /** Keys restored (undo, an opened project, resume): shown and solved, without recording an edit. */
  function applyKeys(keys) {
    owner = slot();
    state.keys = tidy(keys);
    k.selected = null;
    takeTimeline();
    requestMotion();
    syncBar();
  }

  /** The solver's settings changed: the keyed motion is solved again with them. */
  function resolve() {
    if (state.keys) requestMotion();
  }

  function setMode(on) {
    k.mode = on;
    // The arm's keys take the timeline in Key mode and give it back to its motions out of it;
    // the chip says which plays.
    if (armShown() && state.keys) {
      takeTimeline();
      act.say(on && k.answer ? keyedSummary(k.answer) : "Key mode off · the arm's keys kept · a click moves the arm");
    }
    syncBar();
  }

  // ---- The bar and rows ------------------------------------------------------------------

  $("key-mode").addEventListener("click", () => setMode(!k.mode));
  $("arm-key-mode").addEventListener("change", (ev) => setMode(ev.target.checked));
  /** The keyed animation's length, `v` seconds (in KEY_LENGTH): the field shows it, the timeline spans it. */
  function setLength(v) {
    const changed = k.length !== v;
    k.length = v;
    $("key-length").value = String(v);
    if (owns()) loadClip();
    // The motion runs to the Length: asked again.
    if (changed && state.keys) requestMotion();
    syncBar();
  }
  $("key-length").addEventListener("change", (ev) => {
    const v = Number(ev.target.value);
    if (!(v >= KEY_LENGTH.min && v <= KEY_LENGTH.max)) {
      act.showError(new api.Notice(`Length: ${ev.target.value} is not a number of seconds from ${KEY_LENGTH.min} to ${KEY_LENGTH.max}`));
      return;
    }
    act.showError(null);
    setLength(v);
    act.edited(`Length ${v} s`);
  });
  $("key-ease").addEventListener("change", (ev) => {
    const s = k.selected;
    if (!s || (s.kind !== "track" && s.kind !== "rotation")) return;
    const m = state.meta || {};
    state.keys = setEase(state.keys, s.bone, s.index, { kind: ev.target.value, k1: m.default_k1, k2: m.default_k2 }, s.kind);
    commit(`ease ${s.bone} ${ev.target.value}`);
  });
  $("key-delete").addEventListener("click", deleteSelected);

  function deleteSelected() {
    const s = k.selected;
    if (!s || !selectedKey()) return;
    state.keys = deleteKey(state.keys, s, s.index);
    k.selected = null;
    commit(`delete key of ${s.bone}`);
  }

  exportsBar = wireKeyExports({ state, canvas, answer: () => k.answer, branch, sent: () => sent(state.keys), showError: act.showError, syncBar });

  const rowsCanvas = $("key-rows");
  // The rows are drawn inside the canvas's border: a point is measured from there too.
  const rowPoint = (ev) => {
    const rect = rowsCanvas.getBoundingClientRect();
    return [ev.clientX - rect.left - rowsCanvas.clientLeft, ev.clientY - rect.top - rowsCanvas.clientTop];
  };
  rowsCanvas.addEventListener("pointerdown", (ev) => {
    if (!body() || ev.button !== 0) return;
    const axis = rowAxis(rowsCanvas.clientWidth, seconds());
    const [px, py] = rowPoint(ev);
    const pick = pickKey(rows(), axis, px, py);
    if (pick && pick.index >= 0) {
      k.selected = { kind: pick.row.kind, bone: pick.row.bone, index: pick.index };
      k.drag = { base: state.keys, row: k.selected, moved: false };
      rowsCanvas.setPointerCapture(ev.pointerId);
      syncBar();
      return;
    }
    // Elsewhere on the rows: the playhead goes there.
    k.selected = null;
    if (owns()) act.timeline.seek(axis.t(px) / seconds());
    syncBar();
  });
  rowsCanvas.addEventListener("pointermove", (ev) => {
    if (!k.drag) return;
    const axis = rowAxis(rowsCanvas.clientWidth, seconds());
    const moved = moveKey(k.drag.base, k.drag.row, k.drag.row.index, axis.t(rowPoint(ev)[0]));
    if (moved.time !== selectedKeyTime(k.drag.base)) k.drag.moved = true;
    state.keys = moved.keys;
    syncBar();
  });
  const selectedKeyTime = (keys) => {
    const s = k.selected;
    const list = listsOf(keys, s.kind)[s.bone];
    return list[s.index].time;
  };
  rowsCanvas.addEventListener("pointerup", () => {
    if (!k.drag) return;
    const { moved, row } = k.drag;
    k.drag = null;
    if (moved) commit(`move key of ${row.bone}`);
  });

  document.addEventListener("keydown", (ev) => {
    if (!body() || ev.altKey || ownsKeys(ev.target, ev.key)) return;
    const ctrl = ev.ctrlKey || ev.metaKey;
    if (!ctrl && (ev.key === "Delete" || ev.key === "Backspace") && k.selected) {
      ev.preventDefault();
      deleteSelected();
    } else if (ctrl && ev.key.toLowerCase() === "c" && selectedKey()) {
      k.clipboard = { row: { kind: k.selected.kind, bone: k.selected.bone }, key: { ...selectedKey() } };
    } else if (ctrl && ev.key.toLowerCase() === "v" && k.clipboard) {
      ev.preventDefault();
      const { row, key } = k.clipboard;
      state.keys = pasteKey(state.keys, row, key, k.t);
      const list = listsOf(state.keys, row.kind)[row.bone];
      k.selected = { ...row, index: list.findIndex((q) => frameOf(q.time, fps()) === frameOf(list.length > 1 ? k.t : 0, fps())) };
      commit(`paste key of ${row.bone}`);
    } else if (!ctrl && ev.key.toLowerCase() === "k") {
      setMode(!k.mode);
    }
  });
  new ResizeObserver(syncBar).observe(rowsCanvas);

  /** Fills the ease list from /api/meta's eases. */
  function fillEases(meta) {
    $("key-ease").replaceChildren(...meta.eases.map((e) => Object.assign(new Option(e.label, e.name), { title: e.summary })));
  }

  const seek = (t) => (owns() ? act.timeline.seek(Math.min(t / seconds(), 1)) : undefined);

  /** The /api/animate body of a character's keys as Spine JSON (the export), or null without keys. */
  const spineRequest = () => (state.character && state.keys ? characterAnimateRequest(state.character, sent(state.keys), "spine") : null);

  return { enter, leave, resume, setLength, length: () => k.length, sent: () => (state.keys ? sent(state.keys) : null), mode: () => k.mode, clipChanged, spineRequest, applyKeys, resolve, handles, hovering: () => !!k.hover, dragEnded, turnEnded, pinToggled, bendPress, hoverBend, drawOver, settled, setMode, seek, fillEases };
}
