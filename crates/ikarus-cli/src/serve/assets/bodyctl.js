// What the rig's and the character's controllers (rigs.js, characters.js) share: the one set of
// pointer handlers on the canvas for the body shown (a press grabs something of it, a drag moves
// it, a release ends the drag or is a click, Esc clears what was placed), the one request in
// flight with only the latest choices waiting (latest wins, the next request on the next displayed
// frame), the Body list's entries and the hint the arm gets back. Each controller says what its
// body does at each step; the steps themselves are written here once.

import { isDrag } from "./view.js";

const $ = (id) => document.getElementById(id);

/** Where the pointer event `ev` is on `canvas`, in canvas pixels: [x, y]. */
export function canvasPoint(canvas, ev) {
  const rect = canvas.getBoundingClientRect();
  return [ev.clientX - rect.left, ev.clientY - rect.top];
}

/** The Body list's entry `value` (added at the end when missing), named `text`. */
export function listBody(value, text) {
  const select = $("body-kind");
  let option = [...select.options].find((o) => o.value === value);
  if (!option) {
    option = new Option("", value);
    select.append(option);
  }
  option.textContent = text;
}

/** The canvas's hint for the arm (in draw-path mode, the drawing one). */
export function armHint(state) {
  const hint = $("hint");
  hint.textContent = state.drawPath ? hint.dataset.drawing : hint.dataset.normal;
}

/**
 * Sends the next request of the body shown when none of its requests is in flight, and answers
 * for a body no longer shown are dropped. `body` is {shown() (the body's state, with its `busy`
 * flag, or null while another body shows), next(b) (the job to send now, or null: nothing
 * waits), send(job) (a promise of the answer), done(b, job, answer), failed(b, job, e)}. The next
 * request leaves on the next displayed frame: one answer per frame.
 */
export async function sendLatest(body) {
  const b = body.shown();
  if (!b || b.busy) return;
  const job = body.next(b);
  if (!job) return;
  b.busy = true;
  try {
    const answer = await body.send(job);
    if (body.shown() === b) body.done(b, job, answer);
  } catch (e) {
    if (body.shown() === b) body.failed(b, job, e);
  }
  requestAnimationFrame(() => {
    b.busy = false;
    if (body.shown() === b) sendLatest(body);
  });
}

/**
 * The pointer of the rig or the character shown, on `canvas`. Each of `bodies` is {shown() (its
 * state, with `hover` and `grabbed`, or null), ready(b) (whether it takes the pointer yet),
 * grab(ev, b) (what a press there takes hold of: {name, …} or null), under(ev, b) (the name
 * under the pointer, or null), cursor(name, b) (the cursor over it), hovered(name, b) (the
 * name under the pointer changed), drag(press, ev, b) (a drag moved), release(press, ev, b) (let
 * go: `press.dragging` tells a drag from a click), clear() and `clearLabel` (Esc on the canvas
 * and its undo step)}. A press is {x, y, dragging, …what grab returned}. `act` is {keyed
 * (keyed.js's: a press tries the bend handles first, hovering names them first), requestDraw(),
 * edited(label)}.
 */
export function wireBodyPointer(canvas, bodies, act) {
  /** The body shown and its state, or null (the arm is shown). */
  const shown = () => {
    for (const body of bodies) {
      const b = body.shown();
      if (b) return { body, b };
    }
    return null;
  };
  /** The press being held: {body (whose), press}, or null. */
  let held = null;
  /** The press held on the body `body`, or null. */
  const pressOn = (body) => (held && held.body === body ? held.press : null);

  canvas.addEventListener("pointerdown", (ev) => {
    const s = shown();
    if (!s || !s.body.ready(s.b) || ev.button !== 0 || act.keyed.bendPress(ev)) return;
    const grabbed = s.body.grab(ev, s.b);
    if (!grabbed) return;
    held = { body: s.body, press: { x: ev.clientX, y: ev.clientY, dragging: false, ...grabbed } };
    canvas.setPointerCapture(ev.pointerId);
  });

  canvas.addEventListener("pointermove", (ev) => {
    const s = shown();
    if (!s || !s.body.ready(s.b)) return;
    const { body, b } = s;
    const press = pressOn(body);
    if (!press) {
      // A bend handle (Key mode) first: ringed and named alone.
      const bend = act.keyed.hoverBend(ev);
      const over = bend ? null : body.under(ev, b);
      canvas.style.cursor = bend ? "pointer" : body.cursor(over, b);
      if (over !== b.hover) {
        b.hover = over;
        body.hovered(over, b);
        act.requestDraw();
      }
      return;
    }
    if (!press.dragging && isDrag(press, ev.clientX, ev.clientY)) {
      press.dragging = true;
      b.grabbed = press.name;
      canvas.style.cursor = "grabbing";
    }
    if (press.dragging) body.drag(press, ev, b);
  });

  canvas.addEventListener("pointerup", (ev) => {
    const s = shown();
    const press = s && pressOn(s.body);
    if (!press) return;
    held = null;
    s.b.grabbed = null;
    s.body.release(press, ev, s.b);
    act.requestDraw();
  });

  // The pointer left the canvas: nothing is under it (nor ringed on the screen or in a download).
  canvas.addEventListener("pointerleave", () => {
    const s = shown();
    if (!s || pressOn(s.body) || !s.b.hover) return;
    s.b.hover = null;
    canvas.style.cursor = "";
    act.requestDraw();
  });

  canvas.addEventListener("pointercancel", () => {
    const s = shown();
    if (!s) return;
    if (pressOn(s.body)) held = null;
    s.b.grabbed = null;
    act.requestDraw();
  });

  canvas.addEventListener("keydown", (ev) => {
    const s = shown();
    if (s && ev.key === "Escape") {
      ev.preventDefault();
      s.body.clear();
      act.edited(s.body.clearLabel);
    }
  });
}
