// The Keys bar under the timeline (keyed.js's): Key mode, the Length, the selected key's ease and
// Delete, the files (keyexports.js), the rows of keys (drawkeys.js: a press selects a key and a
// drag moves it along its row, a press elsewhere moves the playhead) and the keys' shortcuts
// (Delete or Backspace, Ctrl-C and Ctrl-V at the playhead, K for Key mode); and the bar shown as
// the keys stand (syncBar).

import * as api from "./api.js";
import { exportState } from "./character.js";
import { drawRows, pickKey, rowAxis } from "./drawkeys.js";
import { ownsKeys } from "./input.js";
import { armShown, branchShown, keyedBody, keyFps, keySeconds, ownsTimeline, rowsShown, sentKeys } from "./keybody.js";
import { wireKeyExports } from "./keyexports.js";
import { deleteKey, frameOf, KEY_LENGTH, listsOf, moveKey, pasteKey, setEase } from "./keys.js";

const $ = (id) => document.getElementById(id);

/**
 * Wires the Keys bar. `state` and `canvas` are the page's, `k` keyed.js's (keybody.js's newKeyed:
 * `selected`, `clipboard` and `drag` are written here), `act` is {commit(what) (keyed.js's: an
 * edit of `state.keys` made), setMode(on), setLength(seconds), timeline (timeline.js's: a press
 * on the rows moves its playhead), showError(e), edited(what)}. Returns {sync() (the bar as the keys stand), selectedKey() (the
 * selected key, or null), fillEases(meta)}.
 */
export function wireKeyBar({ state, k, canvas, act }) {
  /** The files' buttons (keyexports.js), once wired. */
  let exportsBar = null;

  /** The bar's buttons and the rows. */
  function sync() {
    const mode = $("key-mode");
    mode.setAttribute("aria-pressed", String(k.mode));
    $("arm-key-mode").checked = k.mode;
    // The arm's keys bar shows in Key mode or once it has keys (the CSS hides it else); while its
    // keys play, its click motions' controls (duration, ease, via points, replay) step aside.
    document.body.classList.toggle("arm-keys", k.mode || !!state.keys);
    document.body.classList.toggle("arm-keyed", armShown(state) && k.loaded !== null);
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
      const e = exportState(state.character.character, state.keys ? sentKeys(state.keys, k) : null);
      Object.assign($("export-spine"), { disabled: e.disabled, title: e.title });
    }
    drawRows($("key-rows"), rowsShown(state), keySeconds(state, k), k.t, k.selected);
  }

  function selectedKey() {
    const s = k.selected;
    if (!s || !state.keys) return null;
    const list = listsOf(state.keys, s.kind)[s.bone];
    return (list && list[s.index]) || null;
  }

  function deleteSelected() {
    const s = k.selected;
    if (!s || !selectedKey()) return;
    state.keys = deleteKey(state.keys, s, s.index);
    k.selected = null;
    act.commit(`delete key of ${s.bone}`);
  }

  // ---- The buttons -----------------------------------------------------------------------

  $("key-mode").addEventListener("click", () => act.setMode(!k.mode));
  $("arm-key-mode").addEventListener("change", (ev) => act.setMode(ev.target.checked));
  $("key-length").addEventListener("change", (ev) => {
    const v = Number(ev.target.value);
    if (!(v >= KEY_LENGTH.min && v <= KEY_LENGTH.max)) {
      act.showError(new api.Notice(`Length: ${ev.target.value} is not a number of seconds from ${KEY_LENGTH.min} to ${KEY_LENGTH.max}`));
      return;
    }
    act.showError(null);
    act.setLength(v);
    act.edited(`Length ${v} s`);
  });
  $("key-ease").addEventListener("change", (ev) => {
    const s = k.selected;
    if (!s || (s.kind !== "track" && s.kind !== "rotation")) return;
    const m = state.meta || {};
    state.keys = setEase(state.keys, s.bone, s.index, { kind: ev.target.value, k1: m.default_k1, k2: m.default_k2 }, s.kind);
    act.commit(`ease ${s.bone} ${ev.target.value}`);
  });
  $("key-delete").addEventListener("click", deleteSelected);

  exportsBar = wireKeyExports({ state, canvas, answer: () => k.answer, branch: () => branchShown(state), sent: () => sentKeys(state.keys, k), showError: act.showError, syncBar: sync });

  // ---- The rows --------------------------------------------------------------------------

  const rowsCanvas = $("key-rows");
  // The rows are drawn inside the canvas's border: a point is measured from there too.
  const rowPoint = (ev) => {
    const rect = rowsCanvas.getBoundingClientRect();
    return [ev.clientX - rect.left - rowsCanvas.clientLeft, ev.clientY - rect.top - rowsCanvas.clientTop];
  };
  rowsCanvas.addEventListener("pointerdown", (ev) => {
    if (!keyedBody(state) || ev.button !== 0) return;
    const axis = rowAxis(rowsCanvas.clientWidth, keySeconds(state, k));
    const [px, py] = rowPoint(ev);
    const pick = pickKey(rowsShown(state), axis, px, py);
    if (pick && pick.index >= 0) {
      k.selected = { kind: pick.row.kind, bone: pick.row.bone, index: pick.index };
      k.drag = { base: state.keys, row: k.selected, moved: false };
      rowsCanvas.setPointerCapture(ev.pointerId);
      sync();
      return;
    }
    // Elsewhere on the rows: the playhead goes there.
    k.selected = null;
    if (ownsTimeline(state, k)) act.timeline.seek(axis.t(px) / keySeconds(state, k));
    sync();
  });
  rowsCanvas.addEventListener("pointermove", (ev) => {
    if (!k.drag) return;
    const axis = rowAxis(rowsCanvas.clientWidth, keySeconds(state, k));
    const moved = moveKey(k.drag.base, k.drag.row, k.drag.row.index, axis.t(rowPoint(ev)[0]));
    if (moved.time !== selectedKeyTime(k.drag.base)) k.drag.moved = true;
    state.keys = moved.keys;
    sync();
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
    if (moved) act.commit(`move key of ${row.bone}`);
  });

  // ---- The shortcuts ---------------------------------------------------------------------

  document.addEventListener("keydown", (ev) => {
    if (!keyedBody(state) || ev.altKey || ownsKeys(ev.target, ev.key)) return;
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
      const fps = keyFps(state);
      k.selected = { ...row, index: list.findIndex((q) => frameOf(q.time, fps) === frameOf(list.length > 1 ? k.t : 0, fps)) };
      act.commit(`paste key of ${row.bone}`);
    } else if (!ctrl && ev.key.toLowerCase() === "k") {
      act.setMode(!k.mode);
    }
  });
  new ResizeObserver(sync).observe(rowsCanvas);

  /** Fills the ease list from /api/meta's eases. */
  function fillEases(meta) {
    $("key-ease").replaceChildren(...meta.eases.map((e) => Object.assign(new Option(e.label, e.name), { title: e.summary })));
  }

  return { sync, selectedKey, fillEases };
}
