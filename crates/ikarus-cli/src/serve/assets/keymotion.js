// The keyed motion (keyed.js's): after every edit of the keys, POST /api/animate with the rig (or
// the character file's text, its clip and IK choice, or the arm), `keys` and the solver options,
// one request in flight and only the latest keys waiting (latest wins); the answer becomes
// `state.motion` ({fps, duration, frames}, each frame with `pose` in bone order) and is shown at
// the playhead when the keys own the timeline.

import * as api from "./api.js";
import { branchShown, keyedBody, ownsTimeline, sentKeys } from "./keybody.js";
import { characterAnimateRequest, characterMotion, rigMotion } from "./keys.js";

/** The chip's line for a keyed answer: `keyed motion · 25 frames at 30 fps · 25 reached` (a character's without reached). */
export function keyedSummary(state, answer) {
  const reached = answer.frames.filter((f) => f.status === "reached").length;
  return `keyed motion · ${answer.frames.length} frames at ${answer.fps ?? state.keys.fps} fps${state.character ? "" : ` · ${reached} reached`}`;
}

/**
 * The keyed motion's requests. `state` is the page's, `k` keyed.js's (its `busy`, `pending` and
 * `answer` are written here), `act` is {showAt(t) (keyplay.js's), syncBar() (keybar.js's),
 * showError(e), setStatus(s), say(text)}. Returns {request() (the keys changed: ask again),
 * settled() (no motion in flight or waiting)}.
 */
export function wireKeyMotion({ state, k, act }) {
  function request() {
    k.pending = true;
    pump();
  }

  async function pump() {
    const b = keyedBody(state);
    if (!b || k.busy || !k.pending) return;
    k.pending = false;
    const keys = state.keys;
    if (!keys || !(Object.keys(keys.tracks).length || Object.keys(keys.rotations || {}).length)) {
      state.motion = null;
      k.answer = null;
      act.syncBar();
      return;
    }
    k.busy = true;
    const req = state.character ? characterAnimateRequest(state.character, sentKeys(keys, k), "json") : branchShown(state).request(sentKeys(keys, k), state.options);
    act.setStatus("solving");
    try {
      const answer = await api.animate(req);
      if (keyedBody(state) === b && state.keys === keys) shown(answer, keys);
    } catch (e) {
      if (keyedBody(state) === b) {
        act.showError(e);
        act.setStatus("error");
      }
    }
    k.busy = false;
    pump();
  }

  /** The answer for `keys` (still the keys shown) becomes the motion. */
  function shown(answer, keys) {
    state.motion = state.character ? characterMotion(answer, keys.fps) : rigMotion(branchShown(state).rig, answer);
    k.answer = answer;
    const reached = answer.frames.filter((f) => f.status === "reached").length;
    act.showError(null);
    act.setStatus(state.character || reached === answer.frames.length ? "ready" : "unreachable");
    act.say(keyedSummary(state, answer));
    // The arm's keys out of Key mode: their motion is ready, the arm's own motion stays shown.
    if (ownsTimeline(state, k)) act.showAt(k.t);
    else act.syncBar();
  }

  /** Whether no motion is in flight or waiting (for tests and scripts). */
  const settled = () => !k.busy && !k.pending;

  return { request, settled };
}
