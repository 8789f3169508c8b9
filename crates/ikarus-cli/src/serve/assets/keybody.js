// What the keys on the page belong to and how long they run (keyed.js and its parts: keyplay.js,
// keymotion.js, keybar.js): the body shown (a rig, a character or the arm), its rows, the keyed
// animation's seconds and frames per second, and `k`, the keys' state on the page. Functions of
// the page's `state` and of `k`; nothing here writes either.

import { armBones, DEFAULT_LENGTH, keyedBranch, keyRows, keysDuration, lengthKeys } from "./keys.js";

/**
 * keyed.js's state of the keys on the page:
 *   mode       Key mode on (drags key, clicks pin for the animation)
 *   length     the animation's length the reader chose, seconds (the timeline spans at least the last key)
 *   t          the playhead, seconds;  selected  {kind, bone, index} of the selected key, or null
 *   clipboard  {row, key} copied by Ctrl-C;  drag  a key being dragged along its row, or null
 *   busy, pending, answer  a motion request in flight, the keys changed since (ask again), the last answer
 *   hover      the bend handle under the pointer (a bone name), or null
 *   loaded     the seconds of the keys the timeline plays, or null while it plays something else
 */
export function newKeyed() {
  return { mode: false, length: DEFAULT_LENGTH, t: 0, selected: null, clipboard: null, drag: null, busy: false, pending: false, answer: null, hover: null, loaded: null };
}

/** The keys' frames per second (30 without keys). */
export const keyFps = (state) => (state.keys && state.keys.fps) || 30;

/** The keyed animation's seconds: the Length, or longer to reach the last key. */
export const keySeconds = (state, k) => Math.max(k.length, keysDuration(state.keys));

/** `keys` as the requests send them: with the Length as their `duration` (keys.js's lengthKeys). */
export const sentKeys = (keys, k) => lengthKeys(keys, k.length);

/** Whether the arm is shown (no rig, no character): its tip's track is `linkN-1`. */
export const armShown = (state) => !state.rig && !state.character && !!state.arm;

/** The body keyed: the rig, the character or the arm shown (or null). */
export const keyedBody = (state) => state.rig || state.character || (armShown(state) ? state.arm : null);

/** The bones of the body shown, by name (the arm's links as keys.js's armBones names them). */
function boneNames(state) {
  if (state.rig) return state.rig.rig.bones.map((b) => b.name);
  if (state.character) return state.character.character.bones.map((b) => b.name);
  return state.arm ? armBones(state.arm) : [];
}

/** The key rows of the body shown (keys.js's keyRows), none without a body. */
export const rowsShown = (state) => (keyedBody(state) ? keyRows(state.keys, boneNames(state)) : []);

/** A rig's or the arm's keys as one body (keys.js's keyedBranch: its rig, file name, request); null for a character. */
export const branchShown = (state) => (state.character ? null : keyedBranch(state.rig ? state.rig.rig : null, state.arm));

/**
 * Whether the timeline plays the keys: a rig's always, a character's once it has keys, the
 * arm's once it has keys and while Key mode is on (off, its clicks' motions take the timeline).
 */
export const ownsTimeline = (state, k) => !!state.rig || (!!state.character && !!state.keys) || (armShown(state) && !!state.keys && k.mode);
