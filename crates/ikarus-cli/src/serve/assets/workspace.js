// The arm's reachable area (main.js's): asked of POST /api/workspace a moment after the arm or
// its limits change, while the area is shown or the limits are on; written to `state.workspace`,
// `state.region` (region.js's regionOf of its boundary: the exact region that judges each goal),
// `state.regionFor` and `state.areaOutline` (view.js's, from a server that sends no boundary).

import * as api from "./api.js";
import { armForRequest } from "./controls.js";
import { regionOf } from "./region.js";
import { areaOutline } from "./view.js";

/** The grid's resolution when the exact region cannot be had (the server could not build it). */
const WORKSPACE_RESOLUTION = 160;
const WORKSPACE_DEBOUNCE_MS = 120;

/**
 * Asks for the reachable area of the arm when it is shown, or when limits are on (its exact
 * region then judges each goal at once, shown or not), a moment after the last call: the
 * exact region, or the sampled grid's edge from a server that cannot build it. `act` is
 * {regionKey() (chip.js's: what the region is of), requestDraw(), showError(e)}.
 */
export function askWorkspace(state, act) {
  const jobs = state.jobs;
  clearTimeout(jobs.workspaceTimer);
  if (!state.arm || !(state.showWorkspace || state.options.limits)) return;
  jobs.workspaceTimer = setTimeout(async () => {
    const seq = ++jobs.workspaceSeq;
    const key = act.regionKey();
    const body = { arm: armForRequest(state.arm), limits: !!state.options.limits };
    try {
      // The exact region (no sampling fields: they would ask for the grid); where the server
      // cannot build it (a failure at run time), the sampled grid instead.
      let ws;
      try {
        ws = await api.workspace(body);
      } catch (e) {
        if (seq !== jobs.workspaceSeq) return;
        console.info("ikarus: no exact region, the sampled grid instead:", e.message);
        ws = await api.workspace({ ...body, grid: true, resolution: WORKSPACE_RESOLUTION });
      }
      if (seq !== jobs.workspaceSeq) return;
      state.workspace = ws;
      // The exact region when the server sends its boundary; else the sampled grid's edge.
      state.region = regionOf(ws.boundary, ws.curves);
      state.regionFor = state.region ? key : null;
      state.areaOutline = state.region ? null : areaOutline(ws);
      act.requestDraw();
    } catch (e) {
      if (seq === jobs.workspaceSeq) act.showError(e);
    }
  }, WORKSPACE_DEBOUNCE_MS);
}
