// The arm's motions (main.js's): a click solves for the goal and plays the motion there, through
// the via points a shift-click added (POST /api/solve and /api/animate; a goal out of the
// reachable region said at once, chip.js), the solver's recorded iterations played instead
// (*Replay solver*), the glide into range when limits are turned on with the pose outside them,
// and a motion stopped or forgotten. Following the pointer and traced paths are track.js's; this
// module takes the pose into range before them. It writes `state.goal`, `state.via`,
// `state.animation`, `state.animationRequest` and `state.pendingStats`.

import * as api from "./api.js";
import { armForRequest } from "./controls.js";
import { unreachableText } from "./region.js";
import { glideFrames, poseIntoLimits } from "./view.js";

/** Frames of the glide into range (the ease's samples from /api/ease). */
const GLIDE_FRAMES = 24;

const $ = (id) => document.getElementById(id);

/** The stats of a motion through via points: its goals' solves added up (status of the last). */
function motionStats(anim) {
  const solves = anim.solves || [];
  const last = solves[solves.length - 1] || {};
  return { status: last.status, iterations: solves.reduce((n, s) => n + s.iterations, 0), error: last.error, reach_distance: last.reach_distance };
}

/** "limits on: joint 1 moved into its range, 73.6° → 45°" (several: "joints 1 and 3 … their ranges, …"). */
function intoRangeText(moved) {
  const deg = (a) => `${Number(a.toFixed(1))}°`;
  const joints = moved.map((m) => m.joint);
  const which = joints.length === 1 ? `joint ${joints[0]}` : `joints ${joints.slice(0, -1).join(", ")} and ${joints.at(-1)}`;
  const steps = moved.map((m) => `${deg(m.from)} → ${deg(m.to)}`).join(", ");
  return `limits on: ${which} moved into ${joints.length === 1 ? "its range" : "their ranges"}, ${steps}`;
}

/**
 * Wires the arm's motions. `act` is {timeline (timeline.js's), paths (track.js's), chip (chip.js's
 * wireChip: fieldsOk, judge, setStatus, showError, setStats, solvedVerdict, missShown),
 * setPose(pose, joints?), requestDraw(), edited(label) (an undo step), amend() (the last step
 * settled)}. Returns {animateTo(x, y), toggleSolver(solver?), motionEnded(), cancelMotion(),
 * forgetMotion(), reset(), glideIntoRange(), settleIntoRange(), traceShape(kind), followGoal(x,
 * y), addVia(x, y), clearVia()}.
 */
export function wireArmMotion(state, act) {
  const { timeline, paths, setPose, requestDraw, edited, amend } = act;
  const { fieldsOk, judge, setStatus, showError, setStats, solvedVerdict, missShown } = act.chip;

  // ---- A click: solve and animate ------------------------------------------------------

  /** Solves for the goal (x, y) through the via points and plays the motion there. */
  async function animateTo(x, y) {
    if (!fieldsOk()) return;
    cancelMotion();
    settleIntoRange();
    const goal = state.goalAngle === undefined ? { x, y } : { x, y, angle_deg: state.goalAngle };
    // The goal drawn: with its heading, an arrow.
    state.goal = goal;
    edited("Move the goal");
    const seq = state.jobs.animateSeq;
    const base = {
      arm: armForRequest(state.arm),
      start_deg: state.pose_deg.slice(),
      goal,
      options: state.options,
    };
    const via = state.via.map((p) => [p.x, p.y]);
    const animReq = { ...base, ...(via.length ? { via } : {}), ease: state.ease, frames: state.frames };
    // Out of the region: said at once, the nearest reachable point drawn, while the solve runs.
    const miss = judge(goal);
    setStatus(miss ? "unreachable" : "solving");
    if (miss) $("stats").textContent = unreachableText(miss.distance);
    requestDraw();
    try {
      // Through via points the stats are the motion's own solves; straight there, /api/solve's.
      const [solved, anim] = await Promise.all([via.length ? null : api.solve(base), api.animate(animReq)]);
      if (seq !== state.jobs.animateSeq) return;
      const stats = solved || motionStats(anim);
      const end = solved ? solved.end_effector : null;
      const lastFrame = anim.frames && anim.frames[anim.frames.length - 1];
      const tip = end ? [end.x, end.y] : lastFrame && lastFrame.joints[lastFrame.joints.length - 1];
      solvedVerdict(goal, stats.status, stats.reach_distance, tip);
      showMotion(anim, animReq, stats);
    } catch (e) {
      failed(e, seq);
    }
  }

  /**
   * Plays the solver's recorded iterations of the last motion (`from_solve`), from its start pose
   * through its via points; pressed again, the eased motion.
   */
  async function toggleSolver(solver = !state.playback.solver) {
    if (!state.animationRequest || !fieldsOk()) return;
    cancelMotion();
    const seq = state.jobs.animateSeq;
    const req = { ...state.animationRequest, from_solve: solver };
    // The replay records one pose every "Replay every" iterations; the eased motion does not use it.
    req.options = { ...req.options, record_every: state.recordEvery };
    if (req.from_solve) {
      // One frame per recorded pose: the eased motion's solves tell how many iterations each goal
      // took (the replay's own solves say the same: they are deterministic), and a pose is recorded every "Replay every".
      const solves = (state.animation && state.animation.solves) || [];
      const poses = solves.reduce((n, s) => n + Math.ceil(s.iterations / state.recordEvery), 1);
      req.frames = Math.min(Math.max(poses, 2), 2000);
    } else {
      delete req.from_solve;
      delete req.options.record_every;
      req.frames = state.frames;
    }
    setStatus("solving");
    try {
      const anim = await api.animate(req);
      if (seq !== state.jobs.animateSeq) return;
      showMotion(anim, req, motionStats(anim));
    } catch (e) {
      failed(e, seq);
    }
  }

  function showMotion(anim, req, stats) {
    showError(null);
    paths.clear();
    state.animation = anim;
    state.animationRequest = req;
    state.pendingStats = stats;
    setStatus("moving");
    timeline.load(req, !!req.from_solve);
    timeline.play();
  }

  /** The playback reached the end: the motion's stats and status ("reached" only now). */
  function motionEnded() {
    const stats = state.pendingStats;
    if (!stats) return;
    state.pendingStats = null;
    const frames = state.playback.solver && state.animation ? ` · ${state.animation.frames.length} poses replayed` : "";
    if (stats.text) $("stats").textContent = stats.text;
    else setStats(stats);
    if (frames) $("stats").textContent += frames;
    setStatus(stats.status);
    // The undo step of the motion's goal holds the pose it reached.
    amend();
  }

  function failed(e, seq) {
    if (seq !== state.jobs.animateSeq) return;
    showError(e);
    setStatus("error");
    requestDraw();
  }

  /** Stops the motion being played and drops the answers of the one being asked for. */
  function cancelMotion() {
    timeline.pause();
    state.jobs.animateSeq++;
    // A motion stopped before its end did not reach anything: its outcome is not shown.
    if (state.pendingStats) {
      state.pendingStats = null;
      setStatus("ready");
      $("stats").textContent = "stopped";
    }
  }

  // ---- Limits turned on: the pose into range --------------------------------------------

  /**
   * Limits turned on with the pose outside them (a motion made without them): each joint goes to
   * the nearest angle its range allows (view.js's poseIntoLimits), played as a short motion, and
   * the chip says which joints moved and where. Nothing to do for a pose inside, or for a rig
   * (its solve takes the pose in).
   */
  async function glideIntoRange() {
    if (state.rig || !state.options.limits || !state.arm) return;
    const { pose, moved } = poseIntoLimits(state.arm, state.pose_deg);
    if (moved.length === 0) {
      setPose(pose);
      return;
    }
    cancelMotion();
    const seq = state.jobs.animateSeq;
    let curve;
    try {
      curve = await api.easeCurve(state.ease, GLIDE_FRAMES);
    } catch (e) {
      // The ease's fields are checked before: take the pose in range at once.
      setPose(pose);
      showError(e);
      return;
    }
    // Something else moved the arm meanwhile.
    if (seq !== state.jobs.animateSeq) return;
    paths.clear();
    const from = state.pose_deg.slice();
    const frames = glideFrames(state.arm, from, pose, curve);
    state.goal = null;
    state.animation = { arm: state.arm.name, ease: state.ease.kind, duration: 1, frames };
    state.animationRequest = null;
    state.pendingStats = { status: "ready", text: intoRangeText(moved) };
    showError(null);
    timeline.load({ arm: armForRequest(state.arm), options: state.options, ease: state.ease });
    setStatus("moving");
    $("stats").textContent = `${state.pendingStats.text}…`;
    timeline.play();
  }

  /**
   * Before a solve, follow or trace from the pose: with the limits on, a pose still outside them
   * (its glide into range stopped by this very action) takes the in-range angles at once, so that
   * no request starts outside the limits.
   */
  function settleIntoRange() {
    if (state.rig || !state.options.limits) return;
    const { pose, moved } = poseIntoLimits(state.arm, state.pose_deg);
    if (moved.length > 0) setPose(pose);
  }

  /** Traces a default shape (track.js) from the pose, taken into range first. */
  function traceShape(kind) {
    settleIntoRange();
    paths.traceShape(kind);
  }

  // ---- Via points, following, a new arm -------------------------------------------------

  function addVia(x, y) {
    state.via.push({ x, y });
    timeline.sync();
    requestDraw();
    edited("Add a via point");
  }

  function clearVia() {
    state.via = [];
    timeline.sync();
    requestDraw();
    edited("Clear via points");
  }

  /** Follows the pointer to (x, y) (track.js), judging the goal first (a miss shows at once). */
  function followGoal(x, y) {
    settleIntoRange();
    paths.followTo(x, y);
    judge(state.goal);
    const miss = missShown();
    if (miss) $("stats").textContent = unreachableText(miss.distance);
  }


  /** A new arm: no motion, goal, via points or replay of the old one. */
  function forgetMotion() {
    cancelMotion();
    paths.clear();
    state.goal = null;
    state.animation = null;
    state.animationRequest = null;
    state.pendingStats = null;
    state.via = [];
    timeline.unload();
    setStatus("ready");
    $("stats").textContent = "ready";
  }

  /** The arm back in its start pose: no motion, goal or message. */
  function reset() {
    cancelMotion();
    paths.clear();
    state.goal = null;
    state.pendingStats = null;
    setPose(state.arm.links.map((l) => l.angle_deg));
    setStatus("ready");
    $("stats").textContent = "ready";
    showError(null);
    requestDraw();
  }

  return { animateTo, toggleSolver, motionEnded, cancelMotion, forgetMotion, reset, glideIntoRange, settleIntoRange, traceShape, followGoal, addVia, clearVia };
}
