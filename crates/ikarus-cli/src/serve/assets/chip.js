// The chip on the canvas (#chip) and what it says: the status line and the message, visible at
// every width and whatever the panel shows, neutral while the page works or the arm moves, red
// for an error, a bad field, or a goal not reached; the first bad field named (and, when the
// reader tried to act, shown and focused); the solve's stats; and the reach verdict of the goal
// shown (the page's own, from the exact region of the arm and limits, or the solve's word).
// Moved out of main.js, which wires it first: the other modules report through it.

import { Notice } from "./api.js";
import { armForRequest, firstProblem, problemOf } from "./controls.js";
import { formatDistance, unreachableText, verdict } from "./region.js";
import { solveTime } from "./view.js";

const $ = (id) => document.getElementById(id);

/**
 * Wires the chip over `state` (main.js's: it reads `goal`, `options`, `region`, `regionFor`,
 * `meta` and writes `reachMiss`, `fieldShown`). `act` is {setCollapsed(c)} (the panel opened
 * to show a bad field). Returns {showError(e), setStatus(s), fieldsOk(point), durationOk(),
 * recheck(), setStats(s), regionKey(), currentRegion(), missShown(), missNote(status,
 * distance), judge(goal), solvedVerdict(goal, status, reachDistance, tip)}.
 */
export function wireChip(state, act) {
  /** Statuses that are not trouble: the chip stays neutral. */
  const CALM = new Set(["loading", "ready", "solving", "moving", "reached", "limited"]);

  function syncChip() {
    const bad = !$("error").hidden || !CALM.has(document.body.dataset.status) || !!missShown();
    // For scripts and tests: "outside" while the goal shown is out of the reachable region.
    if (missShown()) document.body.dataset.reach = "outside";
    else delete document.body.dataset.reach;
    $("chip").dataset.kind = bad ? "bad" : "neutral";
  }

  function showError(e) {
    const el = $("error");
    if (!e) {
      el.hidden = true;
      el.textContent = "";
    } else {
      el.textContent = e.message || String(e);
      el.hidden = false;
      if (!(e instanceof Notice)) console.warn("ikarus:", e);
    }
    syncChip();
  }

  /** The page's status (loading, ready, solving, moving, reached, …, error), as body[data-status]. */
  function setStatus(status) {
    document.body.dataset.status = status;
    if (status === "error") $("stats").textContent = "status error";
    if (status === "moving") {
      const miss = missShown();
      $("stats").textContent = miss ? `${unreachableText(miss.distance)} · moving to the nearest reachable point…` : "moving…";
    }
    syncChip();
  }

  /**
   * Whether every field holds a good value. If not, the first bad one is named on the chip, and
   * when `point` is set (the reader tried to act) it is shown: the panel opens, the field scrolls
   * into view and takes the focus.
   */
  function fieldsOk(point = true) {
    const p = firstProblem();
    if (!p) return true;
    showProblem(p, point);
    return false;
  }

  /** Names the bad field `p` ({el, message}) on the chip; with `point`, shows and focuses it. */
  function showProblem(p, point) {
    showError(new Notice(p.message));
    state.fieldShown = true;
    if (point) {
      // A field of the panel opens it (the timeline's Duration is always in view).
      if (p.el.closest("#panel")) act.setCollapsed(false);
      p.el.scrollIntoView({ block: "center" });
      p.el.focus({ preventScroll: true });
    }
  }

  /** Whether the Duration field allows playing; if not, it is named and shown instead. */
  function durationOk() {
    const el = $("duration");
    const message = problemOf(el);
    if (message) showProblem({ el, message }, true);
    return !message;
  }

  /** After an edit: the message of the first bad field, or none (a fixed field clears it). */
  function recheck() {
    const p = firstProblem();
    if (p) {
      showError(new Notice(p.message));
      state.fieldShown = true;
    } else if (state.fieldShown) {
      showError(null);
      state.fieldShown = false;
    }
  }

  function setStats(s) {
    const parts = [`status ${s.status}`];
    const miss = missShown();
    const distance = s.status === "unreachable" && Number.isFinite(s.reach_distance) ? s.reach_distance : miss && miss.distance;
    if (Number.isFinite(distance)) parts.push(missNote(s.status, distance));
    if (s.iterations !== undefined) parts.push(`${s.iterations} iteration${s.iterations === 1 ? "" : "s"}`);
    if (s.restarts) parts.push(`${s.restarts} restart${s.restarts === 1 ? "" : "s"}`);
    if (s.error !== undefined) parts.push(`error ${Number(s.error).toExponential(2)}`);
    if (s.solve_us !== undefined) parts.push(solveTime(s.solve_us));
    $("stats").textContent = parts.join(" · ");
  }

  // ---- Reach: a goal out of the reachable region -------------------------------------------

  /** Which arm and limits a region is of: the workspace request's arm and limits. */
  const regionKey = () => JSON.stringify([armForRequest(state.arm), !!state.options.limits]);

  /** The exact region of the current arm and limits (the last workspace answer's), or null. */
  function currentRegion() {
    return state.region && state.regionFor === regionKey() ? state.region : null;
  }

  /** The miss of the goal shown, or null. */
  function missShown() {
    const miss = state.reachMiss;
    return miss && state.goal && miss.goal === state.goal ? miss : null;
  }

  /** "0.83 from the reachable region" after a status that says unreachable already, else "unreachable · 0.83 …". */
  function missNote(status, distance) {
    return status === "unreachable" ? `${formatDistance(distance)} from the reachable region` : unreachableText(distance);
  }

  /**
   * The page's own verdict on `goal` with limits on, from the region of the current arm: a goal
   * outside it (farther than the solver's tolerance) becomes state.reachMiss, with the nearest
   * reachable point. None for an orientation goal (its region is another) or without a region.
   */
  function judge(goal) {
    state.reachMiss = null;
    const region = state.options.limits && goal.angle_deg === undefined ? currentRegion() : null;
    if (region) {
      const tolerance = state.options.tolerance ?? (state.meta && state.meta.defaults && state.meta.defaults.tolerance) ?? 1e-6;
      const v = verdict(region, [goal.x, goal.y], tolerance);
      if (!v.reachable) state.reachMiss = { goal, nearest: v.nearest, distance: v.distance };
    }
    syncChip();
    return state.reachMiss;
  }

  /**
   * The solve's word on `goal`, which overrides the page's: `unreachable` with its
   * `reach_distance`, the nearest point being where its pose puts the tip (`tip`); `reached`
   * clears a miss.
   */
  function solvedVerdict(goal, status, reachDistance, tip) {
    if (status === "unreachable" && Number.isFinite(reachDistance) && tip) {
      state.reachMiss = { goal, nearest: tip, distance: reachDistance };
    } else if (status === "reached") {
      state.reachMiss = null;
    }
    syncChip();
  }

  return { showError, setStatus, fieldsOk, durationOk, recheck, setStats, regionKey, currentRegion, missShown, missNote, judge, solvedVerdict };
}
