// Keyframes on the page for a rig, a character or the arm: Key mode (a drag of an effector or an
// IK target keys its target at the playhead, a drag of a character's free bone keys its turn; on
// a rig a click pins the tip for the whole animation), each body's keys kept while another body
// shows, and the parts: the Keys bar and rows under the timeline (keybar.js), the bend handles at
// a rig's or a character's knees and elbows (keybends.js), the keyed motion asked after every
// edit of the keys (keymotion.js), played by the timeline (keyplay.js) and saved as JSON, CSV and
// GIF (keyexports.js). A character without keys leaves the timeline to its clip (characters.js)
// and keys at the clip's time. What the keys belong to is keybody.js's; the pure parts are
// keys.js, the drawing drawkeys.js.
//
// It writes `state.keys` (the KEYS object of `ikarus animate --keys`, or null) and
// `state.motion` ({fps, duration, frames}, each frame with `pose` in bone order, or null).

import { armShown, keyFps, keySeconds, newKeyed, ownsTimeline, sentKeys } from "./keybody.js";
import { characterAnimateRequest, frameOf, localRotation, setKey, setRotationKey, tidy, togglePinKey } from "./keys.js";
import { wireBendHandles } from "./keybends.js";
import { wireKeyBar } from "./keybar.js";
import { keyedSummary, wireKeyMotion } from "./keymotion.js";
import { wireKeyPlay } from "./keyplay.js";

/**
 * Wires the keys of a rig, a character or the arm. `act` is {timeline (timeline.js's), draw(), setPose(pose) (the arm's),
 * requestDraw(), showError(e), setStatus(s), say(text), edited(what) (called once after each
 * edit of the keys: undo records it), clipBack() (a character's clip takes the timeline again)}.
 * Returns {enter(), leave(), resume() (the body shown gets back the keys it left with), setLength(s),
 * length() (the keys' Length, seconds), mode() (Key mode on), clipChanged(), spineRequest(), applyKeys(keys), resolve(), handles()
 * (the bend handles in canvas pixels), dragEnded(bone, goal, from), turnEnded(bone, angle, start), pinToggled(bone),
 * bendPress(ev), hoverBend(ev), drawOver(ctx), settled(), setMode(on), seek(t), fillEases(meta), sent()}.
 */
export function wireKeyed(state, canvas, act) {
  const k = newKeyed();
  state.keys = null;
  state.motion = null;

  const fps = () => keyFps(state);
  const play = wireKeyPlay({ state, k, act: { timeline: act.timeline, clipBack: act.clipBack, setPose: act.setPose, draw: act.draw, syncBar: () => bar.sync() } });
  const motion = wireKeyMotion({ state, k, act: { showAt: play.showAt, syncBar: () => bar.sync(), showError: act.showError, setStatus: act.setStatus, say: act.say } });

  /**
   * Each body's keys while another body shows (by slot(): a rig's state object, a character, or
   * ARM, the arm whatever its links), given back by resume(); `owner` is the slot of the body
   * `state.keys` belong to.
   */
  const kept = new WeakMap();
  const ARM = {};
  const slot = () => state.rig || state.character || (armShown(state) ? ARM : null);
  let owner = null;
  /** The keys shown kept with their body (none: nothing kept), as the canvas changes body. */
  function stash() {
    if (owner && state.keys) kept.set(owner, state.keys);
    else if (owner) kept.delete(owner);
    owner = null;
  }

  // ---- Edits -----------------------------------------------------------------------------

  /** After an edit: the keys kept tidy, the timeline as long as they are, undo told, the motion asked again. */
  function commit(what) {
    state.keys = tidy(state.keys);
    if (!bar.selectedKey()) k.selected = null;
    // The timeline as long as the keys, or back to a character's clip without them (the arm's
    // own motions may have taken it meanwhile: its keys take it back).
    if (armShown(state) || (ownsTimeline(state, k) ? keySeconds(state, k) !== k.loaded : k.loaded !== null)) play.takeTimeline();
    owner = slot();
    act.edited(what);
    motion.request();
    bar.sync();
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

  /** The index in `list` of the key at the playhead's frame. */
  const keyAtPlayhead = (list) => list.findIndex((q) => frameOf(q.time, fps()) === frameOf(k.t, fps()));

  /**
   * A drag of `bone`'s goal (a rig's effector, a character's IK target) ended at `goal` ({x, y})
   * from `from` (where it was when grabbed): in Key mode, a key at the playhead (a character
   * without keys yet: at its clip's time).
   */
  function dragEnded(bone, goal, from) {
    if (!k.mode || !goal) return false;
    if (state.character && !state.keys) k.t = state.character.time;
    state.keys = setKey(state.keys, bone, k.t, goal.x, goal.y, tipAtStart(bone) || from);
    k.selected = { kind: "track", bone, index: keyAtPlayhead(state.keys.tracks[bone]) };
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
    k.selected = { kind: "rotation", bone, index: keyAtPlayhead(state.keys.rotations[bone]) };
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

  // ---- Entering and leaving a body, restoring keys ---------------------------------------

  /** No keys shown: no motion, answer or selection. */
  function drop() {
    k.loaded = null;
    state.keys = null;
    state.motion = null;
    k.answer = null;
    k.selected = null;
  }

  /**
   * A rig or a character took the canvas (the keys shown before are kept with their body): no
   * keys yet (resume() gives back its own); a rig's timeline spans the length.
   */
  function enter() {
    stash();
    owner = slot();
    drop();
    k.t = 0;
    if (state.rig) play.loadClip();
    bar.sync();
  }

  /** A character's clip changed: the keyed motion is made over the new one. */
  function clipChanged() {
    play.loadClip();
    motion.request();
  }

  /** The body shown leaves the canvas: its keys kept with it (resume() gives them back). */
  function leave() {
    stash();
    drop();
    bar.sync();
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
    play.takeTimeline();
    motion.request();
    bar.sync();
  }

  /** The solver's settings changed: the keyed motion is solved again with them. */
  function resolve() {
    if (state.keys) motion.request();
  }

  function setMode(on) {
    k.mode = on;
    // The arm's keys take the timeline in Key mode and give it back to its motions out of it;
    // the chip says which plays.
    if (armShown(state) && state.keys) {
      play.takeTimeline();
      act.say(on && k.answer ? keyedSummary(state, k.answer) : "Key mode off · the arm's keys kept · a click moves the arm");
    }
    bar.sync();
  }

  /** The keyed animation's length, `v` seconds (in KEY_LENGTH): the field shows it, the timeline spans it. */
  function setLength(v) {
    const changed = k.length !== v;
    k.length = v;
    document.getElementById("key-length").value = String(v);
    if (ownsTimeline(state, k)) play.loadClip();
    // The motion runs to the Length: asked again.
    if (changed && state.keys) motion.request();
    bar.sync();
  }

  const bar = wireKeyBar({ state, k, canvas, act: { commit, setMode, setLength, timeline: act.timeline, showError: act.showError, edited: act.edited } });

  const seek = (t) => (ownsTimeline(state, k) ? act.timeline.seek(Math.min(t / keySeconds(state, k), 1)) : undefined);

  /** The /api/animate body of a character's keys as Spine JSON (the export), or null without keys. */
  const spineRequest = () => (state.character && state.keys ? characterAnimateRequest(state.character, sentKeys(state.keys, k), "spine") : null);

  return {
    enter,
    leave,
    resume,
    setLength,
    length: () => k.length,
    sent: () => (state.keys ? sentKeys(state.keys, k) : null),
    mode: () => k.mode,
    clipChanged,
    spineRequest,
    applyKeys,
    resolve,
    handles,
    dragEnded,
    turnEnded,
    pinToggled,
    bendPress,
    hoverBend,
    drawOver,
    settled: motion.settled,
    setMode,
    seek,
    fillEases: (meta) => bar.fillEases(meta),
  };
}
