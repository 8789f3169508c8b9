// The tip on paths, through POST /api/track: following the pointer (follow mode and drags) one
// bounded step at a time, and tracing a drawn stroke or a line, circle or figure-8 (plan),
// played on the timeline with the wanted path, the tip's trace and the flips drawn.
//
// Following sends each pointer position as a one-sample `follow` path from the current pose with
// `bound_first` (api.follow: in the static build, the worker's typed ikarus.Chain, no JSON), so no joint moves more than the step bound between two answers, and at most one
// answer is shown per displayed frame: the arm never jumps. One request is in flight and only
// the latest goal waits; when an answer was cut short by the bound (`limited`, or on its way to
// the nearest pose of an `unreachable` goal), the same goal is asked again on the next frame, so
// the arm catches up as an arm with a top speed would. The state stays main.js's: this module
// writes `state.track`, `state.stroke` and the follow fields of `state.jobs`.

import * as api from "./api.js";
import { armForRequest } from "./controls.js";
import { flipTips, offPathRuns, resampleStroke, SHAPE_SAMPLES, shapeDefaults, STROKE_SPACING, trackMotion, trackSeconds, trackStatus, trackSummaryText } from "./paths.js";
import { maxReach } from "./view.js";

/** At most this many repeated asks for one goal (36 of them turn a joint a full turn at 10°). */
const MAX_CHASES = 200;

/**
 * Wires the paths. `act` is {timeline, setPose(angles, joints), draw(), requestDraw(),
 * cancelMotion(), showError(e), setStatus(s), say(text), showWhenEnded(status, text)}. Returns {followTo(x, y),
 * startStroke(x, y), extendStroke(x, y), endStroke(go), traceShape(kind), clear()}.
 */
export function wireTrack(state, act) {
  const jobs = state.jobs;

  /** The fields every track request shares: the arm, the pose, the bound and the solver. */
  const base = () => ({
    arm: armForRequest(state.arm),
    start_deg: state.pose_deg.slice(),
    max_step_deg: state.maxStepDeg,
    options: state.options,
  });

  // ---- Following -------------------------------------------------------------------------

  function followTo(x, y) {
    state.goal = { x, y };
    jobs.followGoal = { x, y };
    jobs.followChases = 0;
    act.requestDraw();
    pump();
  }

  async function pump() {
    if (jobs.followBusy || !jobs.followGoal) return;
    const goal = jobs.followGoal;
    jobs.followGoal = null;
    jobs.followBusy = true;
    const seq = jobs.animateSeq;
    const n = state.pose_deg.length;
    let chase = false;
    try {
      const s = await api.follow({ ...base(), x: goal.x, y: goal.y });
      // Dropped when a click's motion started meanwhile or the arm changed.
      if (seq === jobs.animateSeq && !state.playback.playing && s.angles_deg.length === n && state.arm.links.length === n) {
        clear();
        act.showError(null);
        act.setPose(s.angles_deg, s.joints);
        act.say(`status ${s.status} · step ${s.step_deg.toFixed(2)}° · error ${Number(s.error).toExponential(2)}`);
        act.setStatus(s.status);
        act.draw();
        chase = s.step_deg >= state.maxStepDeg * (1 - 1e-9) && ++jobs.followChases <= MAX_CHASES;
      }
    } catch (e) {
      act.showError(e);
      act.setStatus("error");
    }
    // One answer per displayed frame: the next request leaves on the next one.
    requestAnimationFrame(() => {
      jobs.followBusy = false;
      if (!jobs.followGoal && chase && seq === jobs.animateSeq) jobs.followGoal = goal;
      pump();
    });
  }

  // ---- Tracing a path --------------------------------------------------------------------

  function startStroke(x, y) {
    act.cancelMotion();
    state.stroke = [[x, y]];
    act.requestDraw();
  }

  function extendStroke(x, y) {
    if (!state.stroke) return;
    state.stroke.push([x, y]);
    act.requestDraw();
  }

  /** Ends the stroke and traces it, or with `go` false (the pointer was cancelled) drops it. */
  function endStroke(go = true) {
    const stroke = state.stroke;
    state.stroke = null;
    if (!stroke || !go) {
      act.requestDraw();
      return;
    }
    const path = resampleStroke(stroke, STROKE_SPACING * maxReach(state.arm));
    if (!path) {
      act.showError(new api.Notice("Drag on the canvas to draw a path for the tip."));
      act.requestDraw();
      return;
    }
    trace({ path });
  }

  /** Traces the default `kind` (line, circle or figure8) of paths.js's shapeDefaults. */
  function traceShape(kind) {
    const shape = shapeDefaults(state.arm, !!state.options.limits)[kind];
    trace({ [kind]: shape, samples: SHAPE_SAMPLES });
  }

  /** Plans the path (`path`, or a shape and its samples) from the current pose and plays it. */
  async function trace(shape) {
    act.cancelMotion();
    const seq = jobs.animateSeq;
    const req = { ...base(), ...shape, mode: "plan" };
    act.setStatus("solving");
    try {
      const answer = await api.track(req);
      if (seq !== jobs.animateSeq) return;
      act.showError(null);
      // The wanted path is the samples' goals (an off-path pose repeats the next sample's goal).
      const goals = answer.samples.filter((s) => s.status !== "off_path").map((s) => s.goal);
      state.track = { request: req, answer, goals, flips: flipTips(answer), offPath: offPathRuns(answer) };
      state.animation = trackMotion(answer);
      state.animationRequest = null;
      state.goal = null;
      // Its summary and status show once the tip has traced it (the chip says "moving…" until then).
      act.showWhenEnded(trackStatus(answer), trackSummaryText(answer));
      document.body.dataset.flips = String(answer.summary.flips);
      document.body.dataset.offPath = String(answer.summary.off_path || 0);
      // The timeline plays it as any motion: linearly, one sample per 1/25 s unless a duration is set.
      act.timeline.load({ arm: req.arm, options: req.options, ease: { kind: "linear" } }, false, trackSeconds(answer));
      act.timeline.play();
    } catch (e) {
      if (seq !== jobs.animateSeq) return;
      act.showError(e);
      act.setStatus("error");
      act.requestDraw();
    }
  }

  /** Forgets the last motion or traced path: its ghosts, traces and flips are no longer drawn. */
  function clear() {
    if (!state.animation && !state.track) return;
    state.animation = null;
    state.animationRequest = null;
    state.track = null;
    delete document.body.dataset.flips;
    delete document.body.dataset.offPath;
    act.timeline.unload();
  }

  return { followTo, startStroke, extendStroke, endStroke, traceShape, clear };
}
