// The arm being edited: the links table's edits (length, start angle, range, rate; add and
// remove), the base fields, arm files (load, save, the default arm) and keeping the arm across
// reloads. A bad cell is marked and named (controls.js's problems) and not applied; a new range
// takes the start angle and the pose into it. It changes `state.arm` and `state.pose_deg` and
// tells main.js through `act`.

import { defaultArm } from "./api.js";
import { loadArmFile, saveArmFile, storeArm } from "./armfile.js";
import { clampInto, clearProblem, numberProblem, renderLinks, setProblem, withLimit } from "./controls.js";

const $ = (id) => document.getElementById(id);

/** The most links an arm of the page may have (the server's default cap). */
export const MAX_LINKS = 64;

/**
 * Wires the links table, the base fields and the arm-file buttons. `act` is {applyControls(),
 * recheck(), controlsChanged(), setPose(pose), requestDraw(), refreshWorkspace(), clearPaths(),
 * forgetMotion(), showError(e), edited(label) (an undo step)}. Returns {showLinks(), showBase(), armChanged(), useArm(arm)}.
 */
export function wireArm(state, act) {
  /** A cell's text checked by `rule`; marks the cell and returns the number, or null when bad. */
  function cellNumber(el, text, label, rule) {
    const why = numberProblem(text, rule);
    if (why) {
      setProblem(el, `${label}: ${why}`);
      act.recheck();
      return null;
    }
    clearProblem(el);
    return Number(text);
  }

  /** Edits of the links table, applied to the arm. */
  const linkEdits = {
    length(i, v, el) {
      const length = cellNumber(el, v, `Link ${i + 1} length`, { above: 0, max: 1e6 });
      if (length === null) return;
      state.arm.links[i].length = length;
      armChanged();
      act.edited(`Link ${i + 1} length`);
    },
    start(i, v, el) {
      const link = state.arm.links[i];
      const angle = cellNumber(el, v, `Link ${i + 1} start angle`, { min: -360, max: 360 });
      if (angle === null) return;
      if (link.limits_deg && clampInto(angle, link.limits_deg) !== angle) {
        const [lo, hi] = link.limits_deg;
        setProblem(el, `Link ${i + 1} start angle: ${angle}° is outside its range [${lo}°, ${hi}°]`);
        act.recheck();
        return;
      }
      // The arm takes its new start pose at once (Reset pose goes back to it too).
      link.angle_deg = angle;
      state.pose_deg[i] = angle;
      armChanged();
      act.edited(`Link ${i + 1} start angle`);
    },
    limit(i, k, v, el) {
      const link = state.arm.links[i];
      const which = k === 0 ? "minimum" : "maximum";
      if (v !== "" && cellNumber(el, v, `Link ${i + 1} ${which} angle`, { min: -360, max: 360 }) === null) return;
      const limits = withLimit(link.limits_deg, k, v);
      if (limits && limits[0] > limits[1]) {
        setProblem(el, `Link ${i + 1} range: the minimum ${limits[0]}° is more than the maximum ${limits[1]}°`);
        act.recheck();
        return;
      }
      clearProblem(el);
      link.limits_deg = limits;
      // The start angle and the current pose move into the new range rather than fail.
      link.angle_deg = clampInto(link.angle_deg, limits);
      state.pose_deg[i] = clampInto(state.pose_deg[i], limits);
      showLinks();
      armChanged();
      act.edited(`Link ${i + 1} range`);
    },
    rate(i, v, el) {
      const rate = v === "" ? 1 : cellNumber(el, v, `Joint ${i + 1} rate`, { above: 0, max: 1e6 });
      if (rate === null) return;
      clearProblem(el);
      state.arm.links[i].rate = rate;
      act.controlsChanged();
      act.edited(`Joint ${i + 1} rate`);
    },
    remove(i) {
      state.arm.links.splice(i, 1);
      state.pose_deg.splice(i, 1);
      showLinks();
      armChanged();
      act.edited(`Remove link ${i + 1}`);
    },
  };

  const showLinks = () => renderLinks(state.arm.links, linkEdits);

  function addLink() {
    if (state.arm.links.length >= MAX_LINKS) return;
    const last = state.arm.links[state.arm.links.length - 1];
    state.arm.links.push({ length: last ? last.length : 1, angle_deg: 0, limits_deg: [-170, 170] });
    showLinks();
    armChanged();
    act.edited("Add link");
  }

  function armChanged() {
    // The pose keeps one angle per link; a new link starts straight.
    while (state.pose_deg.length < state.arm.links.length) state.pose_deg.push(0);
    state.pose_deg.length = state.arm.links.length;
    act.clearPaths();
    // The reachable area of the old arm stays drawn until the new one arrives.
    act.applyControls();
    act.recheck();
    act.setPose(state.pose_deg);
    showBase();
    storeArm(state.arm);
    act.requestDraw();
    act.refreshWorkspace();
  }

  /** The base fields show the arm's base. */
  function showBase() {
    const [x, y] = state.arm.base || [0, 0];
    for (const [id, v] of [["base-x", x], ["base-y", y]]) {
      const el = $(id);
      if (document.activeElement !== el || el.getAttribute("aria-invalid") !== "true") el.value = String(v);
    }
  }

  function baseEdited(k, el) {
    const v = cellNumber(el, el.value.trim(), `Base ${k === 0 ? "x" : "y"}`, { min: -1e6, max: 1e6 });
    if (v === null) return;
    const base = (state.arm.base || [0, 0]).slice();
    base[k] = v;
    state.arm.base = base;
    armChanged();
    act.edited(`Base ${k === 0 ? "x" : "y"}`);
  }

  /** A new arm (loaded from a file, the default, or kept from the last visit): its start pose, no motion. */
  function useArm(arm) {
    act.forgetMotion();
    state.arm = arm;
    state.pose_deg = arm.links.map((l) => l.angle_deg);
    showLinks();
    armChanged();
  }

  $("base-x").addEventListener("change", (ev) => baseEdited(0, ev.target));
  $("base-y").addEventListener("change", (ev) => baseEdited(1, ev.target));
  $("load-arm").addEventListener("click", () => $("arm-file").click());
  $("arm-file").addEventListener("change", async (ev) => {
    const file = ev.target.files[0];
    ev.target.value = "";
    if (!file) return;
    try {
      useArm(await loadArmFile(file));
      act.showError(null);
      act.edited(`Load ${file.name}`);
    } catch (e) {
      act.showError(e);
    }
  });
  $("save-arm").addEventListener("click", async () => {
    try {
      await saveArmFile(state.arm);
    } catch (e) {
      act.showError(e);
    }
  });
  $("default-arm").addEventListener("click", async () => {
    try {
      useArm(await defaultArm());
      act.showError(null);
      act.edited("Default arm");
    } catch (e) {
      act.showError(e);
    }
  });
  $("add-link").addEventListener("click", addLink);

  return { showLinks, showBase, armChanged, useArm };
}
