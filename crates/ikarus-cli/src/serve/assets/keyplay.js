// The keys on the timeline (keyed.js's): the keyed motion played by timeline.js's loadClip (frame
// ⌊t·fps⌉ of the answer shown, never blended) and the frame at the playhead put on the body shown:
// a rig's pose, goals and pins; a character's pose with its keyed targets, bends and turned bones;
// the arm's pose and its tip's keyed target. A character without keys leaves the timeline to its
// clip (characters.js); the arm without keys to its own motions.

import { bodyForward } from "./body.js";
import { armShown, keyFps, keySeconds, ownsTimeline } from "./keybody.js";
import { bendsAt, frameAt, frameOf, keyedTargets, localRotation } from "./keys.js";

/**
 * The keys' playback. `state` is the page's, `k` keyed.js's (keybody.js's newKeyed: the playhead
 * `t` and `loaded` are written here), `act` is {timeline (timeline.js's), clipBack() (a
 * character's clip takes the timeline again), setPose(pose) (the arm's), draw(), syncBar()
 * (keybar.js's)}. Returns {takeTimeline(), loadClip(), showAt(t)}.
 */
export function wireKeyPlay({ state, k, act }) {
  /** The timeline to the keys (or a character's clip without keys), the playhead kept at `k.t`. */
  function takeTimeline() {
    if (ownsTimeline(state, k)) loadClip();
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
    const s = keySeconds(state, k);
    k.loaded = s;
    act.timeline.loadClip({ seconds: s, fps: keyFps(state), show: showAt });
    if (at > 0) act.timeline.seek(Math.min(at / s, 1));
  }

  /** The playhead at `t` seconds: the motion's frame there shown (its pose, targets and pins). */
  function showAt(t) {
    k.t = t;
    const f = frameAt(state.motion, t);
    if (f && showFrame(f)) document.body.dataset.keyFrame = String(Math.min(frameOf(t, state.motion.fps), state.motion.frames.length - 1));
    act.syncBar();
    act.draw();
  }

  /** The keyed motion's frame `f` on the body shown; whether there was one to show it on. */
  function showFrame(f) {
    const r = state.rig;
    const c = state.character;
    if (c) {
      // The frame's time: a drag poses at it (characters.js), every key applied there.
      c.time = f.time;
      c.posed = f.bones;
      // Every keyed target where the frame has it and the bends in force, so that a drag moves
      // one target and poses with all the others held on their keys.
      c.targets = keyedTargets(state.keys, f.bones);
      c.bends = bendsAt(state.keys, f.time);
      // The bones keyed by hand there, each one's local rotation.
      c.turns = new Map(Object.keys(state.keys.rotations || {}).map((b) => [b, localRotation(f.bones, (n) => c.parentOf.get(n), b)]));
    } else if (r) {
      r.pose_deg = f.pose.slice();
      Object.assign(r, bodyForward(r.rig, r.pose_deg));
      r.goals = new Map(Object.entries(f.targets || {}).map(([b, [x, y]]) => [b, { x, y }]));
      r.pins = new Set(state.keys ? state.keys.pins : []);
    } else if (armShown(state)) {
      act.setPose(f.pose);
      // The tip's keyed target there is the goal drawn (not the last followed one).
      const target = (f.targets || {})[`link${state.arm.links.length - 1}`];
      state.goal = target ? { x: target[0], y: target[1] } : null;
    } else return false;
    return true;
  }

  return { takeTimeline, loadClip, showAt };
}
