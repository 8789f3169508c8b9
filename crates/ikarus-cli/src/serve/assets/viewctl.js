// The canvas's view controls: zoom and pan (camera.js's camera over the fitted view), the Fit
// button, and the onion skins' toggle and count (onion.js draws them).
//
//   wheel                  zooms about the pointer (the world point under it stays under it)
//   ctrl + wheel           a trackpad's pinch: the same, in finer steps
//   two fingers            pinch: zoom about their midpoint, and pan as it moves
//   Space held + drag      pans, on every body (a tap of Space still plays and pauses)
//   middle button drag     pans, on every body
//   drag on empty space    pans a rig or a character: a press that grabs nothing (no effector,
//                          no target's handle). On the arm a press sets a goal, so it does not pan
//   + and -                zoom in and out about the canvas's centre (= is +)
//   Fit, or F              back to the fitted view (F, + and - when the focus is not in a field)
//
// The camera resets when the body changes (the arm, a rig, a character) and stays while it moves
// or plays. Pans are taken before the canvas's other listeners (rigs.js, characters.js,
// input.js) see the events (a capture listener on the canvas's box), so a pan never also sets a
// goal or moves an effector.

import { fittedCamera, isFitted, panBy, pinch, viewThrough, wheelFactor, zoomAbout, zoomText } from "./camera.js";
import { clearProblem, numberProblem, setProblem } from "./controls.js";
import { ownsKeys } from "./input.js";
import { ONION } from "./onion.js";

const $ = (id) => document.getElementById(id);

/** The keys that zoom about the canvas's centre, and by how much. */
const KEY_ZOOM = { "+": 1.25, "=": 1.25, "-": 0.8 };

/**
 * Wires the view controls of `canvas`. Writes `state.camera` (camera.js's {zoom, x, y}) and
 * `state.onion` ({show, count}). `act` is {draw() (draws at once: the view picks use is the one
 * drawn), toggle() (plays or pauses the timeline), requestDraw(), recheck() (shows or clears
 * the first bad field's message)}. Returns {look(fit): the view to draw and pick through, of the
 * fitted view `fit` of the body shown; fit(); setCamera(camera): that camera on the body shown}.
 */
export function wireViewControls(state, canvas, act) {
  const box = canvas.parentElement;
  /** The body the camera is of (it resets when another comes). */
  let cameraFor = null;

  const bodyKey = () => state.character || (state.rig && state.rig.rig) || "arm";

  function look(fit) {
    const key = bodyKey();
    if (key !== cameraFor) {
      cameraFor = key;
      state.camera = fittedCamera();
    }
    const view = viewThrough(fit, state.camera);
    $("zoom-level").textContent = zoomText(view.zoom);
    canvas.dataset.zoom = String(view.zoom);
    $("fit").disabled = isFitted(state.camera);
    return view;
  }

  /** The camera `camera` shown at once (the next pick reads its view). */
  function move(camera) {
    state.camera = camera;
    act.draw();
  }

  const fit = () => move(fittedCamera());

  /** The camera `camera` of the body shown now (an opened project's): kept as that body's, shown at once. */
  function setCamera(camera) {
    cameraFor = bodyKey();
    move({ ...camera });
  }

  const local = (ev) => {
    const r = canvas.getBoundingClientRect();
    return [ev.clientX - r.left, ev.clientY - r.top];
  };

  // ---- Wheel and trackpad pinch ----------------------------------------------------------

  canvas.addEventListener(
    "wheel",
    (ev) => {
      if (!state.view.fit || ev.deltaY === 0) return;
      ev.preventDefault();
      const factor = wheelFactor(ev.deltaY, ev.deltaMode, ev.ctrlKey, canvas.clientHeight);
      move(zoomAbout(state.view, factor, ...local(ev)));
    },
    { passive: false },
  );

  // ---- Pans and pinches ------------------------------------------------------------------

  /** Every pointer down on the canvas: id → its last canvas point. */
  const down = new Map();
  /** The pointers this module moves the camera with (one pans, two pinch): id → canvas point. */
  const pans = new Map();
  /** Space held (a pan instead of a press): {panned} once held, null when up. */
  let space = null;

  function take(ev, at) {
    pans.set(ev.pointerId, at);
    try {
      canvas.setPointerCapture(ev.pointerId);
    } catch {
      // A pointer the browser does not know (a synthetic event): its events come to the canvas anyway.
    }
    if (space) space.panned = true;
    document.body.classList.add("panning");
  }

  /** The two pinching pointers' midpoint and distance. */
  function spread() {
    const [[ax, ay], [bx, by]] = [...pans.values()];
    return { mid: [(ax + bx) / 2, (ay + by) / 2], d: Math.hypot(bx - ax, by - ay) };
  }

  // Before the canvas's own listeners: Space or the middle button pans; a second finger pinches
  // (the first one's press, whoever had it, is cancelled).
  box.addEventListener(
    "pointerdown",
    (ev) => {
      if (ev.target !== canvas || !state.view.fit) return;
      const at = local(ev);
      const other = [...down.keys()].find((id) => id !== ev.pointerId);
      down.set(ev.pointerId, at);
      const pinching = ev.pointerType === "touch" && other !== undefined && pans.size < 2;
      if (!(space || ev.button === 1 || pinching)) return;
      ev.stopPropagation();
      ev.preventDefault();
      if (pinching && !pans.has(other)) {
        // The first finger's press belonged to the canvas's other listeners: they let it go.
        canvas.dispatchEvent(new PointerEvent("pointercancel", { pointerId: other, pointerType: "touch" }));
        pans.set(other, down.get(other));
      }
      take(ev, at);
    },
    { capture: true },
  );

  // After them: a left press on a rig or a character that nothing grabbed (no pointer capture) pans.
  box.addEventListener("pointerdown", (ev) => {
    if (ev.target !== canvas || ev.button !== 0 || pans.has(ev.pointerId) || !(state.rig || state.character)) return;
    if (canvas.hasPointerCapture(ev.pointerId)) return;
    take(ev, local(ev));
  });

  box.addEventListener(
    "pointermove",
    (ev) => {
      if (down.has(ev.pointerId)) down.set(ev.pointerId, local(ev));
      if (!pans.has(ev.pointerId)) return;
      ev.stopPropagation();
      const at = local(ev);
      if (pans.size === 2) {
        const before = spread();
        pans.set(ev.pointerId, at);
        const after = spread();
        if (before.d > 0 && after.d > 0) move(pinch(state.view, after.d / before.d, before.mid, after.mid));
        return;
      }
      const [x, y] = pans.get(ev.pointerId);
      pans.set(ev.pointerId, at);
      move(panBy(state.view, at[0] - x, at[1] - y));
    },
    { capture: true },
  );

  function release(ev) {
    down.delete(ev.pointerId);
    if (!pans.has(ev.pointerId)) return;
    ev.stopPropagation();
    pans.delete(ev.pointerId);
    if (pans.size === 0) document.body.classList.remove("panning");
  }
  box.addEventListener("pointerup", release, { capture: true });
  // The middle button pans: no autoscroll.
  canvas.addEventListener("mousedown", (ev) => ev.button === 1 && ev.preventDefault());
  box.addEventListener("pointercancel", (ev) => ev.isTrusted && release(ev), { capture: true });

  // ---- Keys ------------------------------------------------------------------------------

  // Space: held, it turns a press into a pan; a tap (no pan meanwhile) plays or pauses.
  document.addEventListener("keydown", (ev) => {
    if (ev.ctrlKey || ev.altKey || ev.metaKey || ownsKeys(ev.target, ev.key)) return;
    if (ev.key === " ") {
      ev.preventDefault();
      if (ev.repeat || space) return;
      space = { panned: false };
      document.body.classList.add("space-held");
    } else if ((ev.key === "f" || ev.key === "F") && !ev.repeat && !ev.shiftKey) {
      ev.preventDefault();
      fit();
    } else if (KEY_ZOOM[ev.key] && state.view.fit) {
      ev.preventDefault();
      move(zoomAbout(state.view, KEY_ZOOM[ev.key], state.view.w / 2, state.view.h / 2));
    }
  });
  document.addEventListener("keyup", (ev) => {
    if (ev.key !== " " || !space) return;
    const tap = !space.panned;
    space = null;
    document.body.classList.remove("space-held");
    if (tap) act.toggle();
  });
  window.addEventListener("blur", () => {
    space = null;
    document.body.classList.remove("space-held");
  });

  // ---- The buttons and the onion skins' fields -------------------------------------------

  $("fit").addEventListener("click", fit);
  $("onion").addEventListener("change", (ev) => {
    state.onion.show = ev.target.checked;
    act.requestDraw();
  });
  $("onion-count").addEventListener("change", (ev) => {
    const el = ev.target;
    const why = numberProblem(el.value.trim(), { whole: true, min: ONION.min, max: ONION.max });
    if (why) setProblem(el, `Onion skins: ${why}`);
    else {
      clearProblem(el);
      state.onion.count = Number(el.value);
    }
    act.recheck();
    act.requestDraw();
  });

  return { look, fit, setCamera };
}
