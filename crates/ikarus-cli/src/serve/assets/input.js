// The canvas's pointer and keyboard. A click animates to the point (through the via points);
// a shift-click adds a via point; a drag, or any move in follow mode, follows the pointer; in
// draw-path mode a drag draws a stroke that the tip then traces. The arrow keys nudge the goal
// (following at once in follow mode) and Enter animates to it, wherever the focus is but in a
// field or on a button (ownsKeys). The state stays main.js's: it is passed in, with main.js's
// actions.

import { isDrag, nudge, toWorld } from "./view.js";

/**
 * Listens to `canvas`. Reads `state.arm`, `view`, `follow`, `drawPath`, `joints` and `goal`;
 * writes `state.press` (the pointer press: {x, y, dragging, tip (the arm's tip then)}) and `state.goal`. `act` is
 * {animateTo(x, y), followTo(x, y), addVia(x, y), cancelMotion(), requestDraw(),
 * startStroke(x, y), extendStroke(x, y), endStroke(trace = true), dragEnded(x, y, from) (a
 * followed drag ended at (x, y), the tip at [from] when pressed: one undo step, or in Key mode a key)}.
 */
export function wireInput(canvas, state, act) {
  const eventWorld = (ev) => {
    const r = canvas.getBoundingClientRect();
    return toWorld(state.view, ev.clientX - r.left, ev.clientY - r.top);
  };

  // A rig on the canvas has its own pointer (rigs.js): these are the arm's.
  canvas.addEventListener("pointerdown", (ev) => {
    if (!state.arm || state.rig || state.character || ev.button !== 0) return;
    state.press = { x: ev.clientX, y: ev.clientY, dragging: false, tip: state.joints[state.joints.length - 1].slice() };
    canvas.setPointerCapture(ev.pointerId);
    if (state.drawPath) act.startStroke(...eventWorld(ev));
  });

  canvas.addEventListener("pointermove", (ev) => {
    if (!state.arm || state.rig || state.character) return;
    const press = state.press;
    if (state.drawPath) {
      if (press) act.extendStroke(...eventWorld(ev));
      return;
    }
    if (press && !press.dragging && isDrag(press, ev.clientX, ev.clientY)) {
      press.dragging = true;
      act.cancelMotion();
    }
    if (state.follow || (press && press.dragging)) {
      const [x, y] = eventWorld(ev);
      act.followTo(x, y);
    }
  });

  canvas.addEventListener("pointerup", (ev) => {
    if (!state.press) return;
    const { dragging: wasDrag, tip } = state.press;
    state.press = null;
    if (state.drawPath) {
      act.extendStroke(...eventWorld(ev));
      act.endStroke();
      return;
    }
    if (wasDrag) {
      act.dragEnded(...eventWorld(ev), tip);
      return;
    }
    const [x, y] = eventWorld(ev);
    if (ev.shiftKey) act.addVia(x, y);
    else if (!state.follow) act.animateTo(x, y);
  });

  canvas.addEventListener("pointercancel", () => {
    state.press = null;
    if (state.drawPath) act.endStroke(false);
  });

  // The keys act anywhere on the page but in a field or on a button (which own them).
  document.addEventListener("keydown", (ev) => {
    if (!state.arm || state.rig || state.character || ev.ctrlKey || ev.altKey || ev.metaKey || ownsKeys(ev.target, ev.key)) return;
    const tip = state.joints[state.joints.length - 1];
    const g = nudge(state.arm, state.goal || { x: tip[0], y: tip[1] }, ev.key);
    if (g) {
      ev.preventDefault();
      if (state.follow) act.followTo(g.x, g.y);
      else {
        state.goal = g;
        act.requestDraw();
      }
    } else if (ev.key === "Enter" && state.goal) {
      ev.preventDefault();
      act.animateTo(state.goal.x, state.goal.y);
    }
  });
}

/** Keys a range input (the timeline's scrubber) moves itself with. */
const RANGE_KEYS = new Set(["ArrowLeft", "ArrowRight", "ArrowUp", "ArrowDown", "Home", "End", "PageUp", "PageDown"]);

/**
 * Whether a press of `key` belongs to the focused element `el` rather than to the page: a field
 * (text, number, check box, list), a button, or for the keys that move it, a slider. Elsewhere
 * (the canvas, the page itself, a label) the page's keys act.
 */
export function ownsKeys(el, key) {
  if (!el || el === document.body || el === document.documentElement) return false;
  if (el.isContentEditable) return true;
  const tag = el.tagName;
  if (tag === "INPUT") return el.type !== "range" || RANGE_KEYS.has(key);
  return tag === "TEXTAREA" || tag === "SELECT" || tag === "BUTTON";
}
