// The bend handles on the canvas (keyed.js's): a small disc beside each two-bone limb's middle
// joint, a rig's (keys.js's bendHandles) or, in Key mode, a character's (one per two-bone IK
// constraint, characterBendHandles), on the side the limb bends; hovering names one, and a press
// keys the other side at the playhead (a bend key; with limits on, a rig's joint whose range
// cannot reach the other side says so instead).
import * as api from "./api.js";
import { canvasPoint } from "./bodyctl.js";
import { drawBendHandles } from "./drawkeys.js";
import { setBend, sideOf } from "./keys.js";
import { bendAllowed, bendHandleAt, bendHandles, characterBendHandles } from "./bendhandles.js";
import { toCanvas } from "./view.js";

/**
 * The bend handles of the body shown. `state` and `canvas` are the page's, `k` keyed.js's state
 * (its `mode`, playhead `t`, `selected` key and `hover`ed handle), `act` keyed.js's {showError,
 * say, requestDraw}, `commit(what)` records an edit of the keys. Returns {handles(), bendPress(ev),
 * hoverBend(ev), drawOver(ctx)}.
 */
export function wireBendHandles({ state, k, canvas, act, commit }) {
  /** The bend handles of the pose shown, in canvas pixels. */
  const handles = () => {
    const at = (x, y) => toCanvas(state.view, x, y);
    if (state.rig) return bendHandles(state.rig.rig, state.rig.pose_deg, at);
    const c = state.character;
    return c && k.mode ? characterBendHandles(c.character.ik, c.posed, at) : [];
  };

  const local = (ev) => canvasPoint(canvas, ev);

  /** A press on a bend handle flips that joint at the playhead (a bend key); true when it was on one. */
  function bendPress(ev) {
    const r = state.rig;
    if (!r && !state.character) return false;
    const hs = handles();
    const bone = bendHandleAt(hs, ...local(ev));
    if (!bone) return false;
    ev.preventDefault();
    const h = hs.find((x) => x.bone === bone);
    const to = h.side === "ccw" ? "cw" : "ccw";
    const f0 = state.motion && state.motion.frames[0];
    let from = h.side;
    if (r) {
      const i = r.rig.bones.findIndex((b) => b.name === bone);
      const def = r.rig.bones[i];
      if (!bendAllowed(def, to, state.options.limits)) {
        const [lo, hi] = def.limits_deg;
        act.showError(new api.Notice(`${bone}: its limits [${lo}°, ${hi}°] allow only ${h.side}; turn off Enforce joint limits to flip it`));
        return true;
      }
      if (f0) from = sideOf(f0.pose[i]);
    } else if (f0) {
      // A character: the side its knee bends in the motion's first frame.
      const first = characterBendHandles(state.character.character.ik, f0.bones, (x, y) => [x, -y]).find((x) => x.bone === bone);
      if (first) from = first.side;
    }
    state.keys = setBend(state.keys, bone, k.t, to, from);
    k.selected = null;
    if (!state.keys.tracks || !Object.keys(state.keys.tracks).length) act.say(`${bone} keyed to bend ${to}; key an effector to see the motion`);
    commit(`bend ${bone} ${to}`);
    return true;
  }

  /** The bend handle under the pointer, ringed and named; whether there is one (then it alone is named). */
  function hoverBend(ev) {
    if (!state.rig && !state.character) return false;
    const bone = bendHandleAt(handles(), ...local(ev));
    if (bone !== k.hover) {
      k.hover = bone;
      act.requestDraw();
    }
    return !!bone;
  }

  /** Over the rig on the canvas: the bend handles. */
  function drawOver(ctx) {
    if (state.rig || state.character) drawBendHandles(ctx, handles(), k.hover);
  }

  return { handles, bendPress, hoverBend, drawOver };
}
