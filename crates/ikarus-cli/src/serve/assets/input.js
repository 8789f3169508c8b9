// The canvas's pointer and keyboard. A click animates to the point (through the via points);
// a shift-click adds a via point; a drag, or any move in follow mode, follows the pointer; in
// draw-path mode a drag draws a stroke that the tip then traces. The arrow keys nudge the goal
// (following at once in follow mode) and Enter animates to it. The state stays main.js's: it is
// passed in, with main.js's actions.

import { isDrag, nudge, toWorld } from "./view.js";

/**
 * Listens to `canvas`. Reads `state.arm`, `view`, `follow`, `drawPath`, `joints` and `goal`;
 * writes `state.press` (the pointer press: {x, y, dragging}) and `state.goal`. `act` is
 * {animateTo(x, y), followTo(x, y), addVia(x, y), cancelMotion(), requestDraw(),
 * startStroke(x, y), extendStroke(x, y), endStroke(trace = true)}.
 */
export function wireInput(canvas, state, act) {
  const eventWorld = (ev) => {
    const r = canvas.getBoundingClientRect();
    return toWorld(state.view, ev.clientX - r.left, ev.clientY - r.top);
  };

  // A rig on the canvas has its own pointer (rigs.js): these are the arm's.
  canvas.addEventListener("pointerdown", (ev) => {
    if (!state.arm || state.rig || ev.button !== 0) return;
    state.press = { x: ev.clientX, y: ev.clientY, dragging: false };
    canvas.setPointerCapture(ev.pointerId);
    if (state.drawPath) act.startStroke(...eventWorld(ev));
  });

  canvas.addEventListener("pointermove", (ev) => {
    if (!state.arm || state.rig) return;
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
    const wasDrag = state.press.dragging;
    state.press = null;
    if (state.drawPath) {
      act.extendStroke(...eventWorld(ev));
      act.endStroke();
      return;
    }
    if (wasDrag) return;
    const [x, y] = eventWorld(ev);
    if (ev.shiftKey) act.addVia(x, y);
    else if (!state.follow) act.animateTo(x, y);
  });

  canvas.addEventListener("pointercancel", () => {
    state.press = null;
    if (state.drawPath) act.endStroke(false);
  });

  canvas.addEventListener("keydown", (ev) => {
    if (!state.arm || state.rig) return;
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
