// The ikarus playground: draws the arm on a canvas and asks the JSON API (same origin) to solve,
// animate, get the reachable region and render pictures. Plain ES modules, no dependencies, no
// build step. This module wires the page: it owns the one `state` object, and every other module
// either computes (view.js; region.js, the exact reachable region: its path, which goals it
// holds and the nearest reachable point), talks to the server (api.js), draws what the state
// shows (draw.js), reads and fills the form (controls.js), turns pointer and keys into actions
// (input.js), plays motions on the timeline (timeline.js, which owns `state.playback`), follows
// the pointer and traces paths (track.js, with the pure parts in paths.js), edits the arm
// (links.js, with arm files in armfile.js), shows and solves a rig instead of the arm (rigs.js,
// with the pure parts in rig.js and the drawing in drawrig.js), poses a character (characters.js,
// with the pure parts in character.js and the drawing in drawchar.js; the pointer and the one
// request in flight of both are bodyctl.js's) or saves files (files.js,
// with the figures drawn by export.js). The view drawn and picked through is the body's fitted
// view under the camera (camera.js: zoom and pan, moved by viewctl.js, which also holds the
// onion skins' fields; onion.js draws them). The chip on the canvas (status, messages, bad
// fields, the goal's reach) is chip.js's.

import * as api from "./api.js";
import { armForRequest, fillSelects, firstProblem, readControls, syncEnabled, syncLimitModes, syncMethods } from "./controls.js";
import { storedArm } from "./armfile.js";
import { wireArm } from "./links.js";
import { drawScene, fitCanvas, usePalette } from "./draw.js";
import { drawRigScene, rigView } from "./drawrig.js";
import { characterView, drawCharacterScene } from "./drawchar.js";
import { wireArt } from "./artview.js";
import { armHint, wireBodyPointer } from "./bodyctl.js";
import { wireCharacters } from "./characters.js";
import { wireRigs } from "./rigs.js";
import { wireKeyed } from "./keyed.js";
import { regionOf, unreachableText } from "./region.js";
import { wireDownloads } from "./files.js";
import { wireInput } from "./input.js";
import { newPlayback, wireTimeline } from "./timeline.js";
import { fittedCamera } from "./camera.js";
import { newOnion } from "./onion.js";
import { wireViewControls } from "./viewctl.js";
import { wireTrack } from "./track.js";
import { wireProject } from "./projects.js";
import { wireChip } from "./chip.js";
import { areaOutline, fitView, forward, glideFrames, poseIntoLimits, toCanvas } from "./view.js";

/** The grid's resolution when the exact region cannot be had (the server could not build it). */
const WORKSPACE_RESOLUTION = 160;
const WORKSPACE_DEBOUNCE_MS = 120;
/** Frames of the glide into range (the ease's samples from /api/ease). */
const GLIDE_FRAMES = 24;

const $ = (id) => document.getElementById(id);
const canvas = $("plot");
const ctx = canvas.getContext("2d");

/** Everything of the page that changes. */
const state = {
  // The arm file as JSON ({name, base, links: [{length, angle_deg, limits_deg, rate}]}), its
  // current pose (degrees) and joint positions ([[x, y], …], base first), and the goal ({x, y}, and angle_deg with a goal angle).
  arm: null,
  pose_deg: [],
  joints: [],
  goal: null,
  // The select lists' source (/api/meta) and the limit mode the reader last chose.
  meta: null,
  limitModeChoice: null,
  // The settings of the next requests, read from the controls (controls.js's readControls).
  options: {},
  ease: { kind: "sine" },
  frames: 60,
  // The orientation goal (degrees), when "Goal angle" is on; else undefined.
  goalAngle: undefined,
  // Iterations between two poses of the solver's replay ("Replay every").
  recordEvery: 1,
  // The step bound of following and traced paths, degrees (max_step_deg of /api/track).
  maxStepDeg: 10,
  // The playback duration the reader chose ("Duration", seconds), or null for the default.
  duration: null,
  // The View checkboxes.
  follow: false,
  showGhosts: true,
  showTraces: true,
  showWorkspace: false,
  // The world <-> canvas transform of the last drawing: the body's fitted view (view.js's
  // fitView, drawrig.js's rigView, drawchar.js's characterView) under the camera (camera.js's
  // viewThrough of `camera`, {zoom, x, y}). Every pick reads it.
  view: { cx: 0, cy: 0, scale: 1, w: 1, h: 1 },
  camera: fittedCamera(),
  // The onion skins: shown or not, and how many frames each side of the playhead (onion.js).
  onion: newOnion(),
  // The last /api/workspace answer and what is drawn of it, kept until the next answer arrives
  // so that the area does not blink while it recomputes: the exact region (region.js's regionOf
  // of its `boundary`) and the arm and limits it belongs to (regionKey), or, from a server that
  // sends no boundary, the sampled grid's edge (view.js's areaOutline).
  workspace: null,
  region: null,
  regionFor: null,
  areaOutline: null,
  // A goal out of the reachable region: {goal (the state.goal it is about), nearest ([x, y], the
  // nearest reachable point), distance}, from the page's region at once and then from the
  // solve's answer (the authority); drawn and told while that goal is the one shown.
  reachMiss: null,
  // The motion the timeline plays: the last /api/animate answer and its request (a GIF renders
  // the same motion), or a traced path's frames (paths.js's trackMotion; no request then).
  animation: null,
  animationRequest: null,
  // The stats of the motion being played: shown (and its status, "reached" or not) once the
  // playback ends; until then the chip says the arm is moving.
  pendingStats: null,
  // Whether the message shown is a bad field's (cleared when the field is fixed).
  fieldShown: false,
  // Paths (track.js): whether a drag draws a path, the stroke being drawn ([[x, y], …]), and the
  // last traced path, {request, answer (/api/track's), goals (the wanted path), flips (tips)}.
  drawPath: false,
  stroke: null,
  track: null,
  // The timeline's playhead, clock and duration (timeline.js's newPlayback documents the fields).
  playback: newPlayback(),
  // The via points ({x, y}, in order) the next click's motion passes through. They stay after the
  // motion, as an animator's keyframes do, until "Clear via points".
  via: [],
  // The pointer press on the canvas: {x, y, dragging}.
  press: null,
  // The rig the canvas shows and solves instead of the arm, or null (rigs.js's newRigState
  // documents its fields). The arm stays in `arm` meanwhile and comes back as it was.
  rig: null,
  // The character (a Spine or DragonBones file) the canvas poses instead, or null
  // (characters.js's newCharacterState documents its fields).
  character: null,
  // Whether the character's bones are drawn over its art (the switch *Bones over the art*, artview.js).
  showBones: true,
  // Keyframes of the rig shown (keyed.js): the KEYS object of `ikarus animate --keys`, or null,
  // and the keyed motion played ({fps, duration, frames with `pose`}), or null.
  keys: null,
  motion: null,
  // Work in flight. A sequence number is bumped by each new motion so that a stale answer is
  // dropped; following keeps one request in flight and only the latest goal waiting, asked again
  // (followChases times) while the bound holds the arm back.
  jobs: { animateSeq: 0, workspaceSeq: 0, workspaceTimer: 0, followGoal: null, followBusy: false, followChases: 0, drawQueued: false },
};

/** The chip on the canvas: status, messages, bad fields and the goal's reach (chip.js). */
const { showError, setStatus, fieldsOk, durationOk, recheck, setStats, regionKey, missShown, missNote, judge, solvedVerdict } = wireChip(state, { setCollapsed });

/** Undo, redo and project files (projects.js), wired last: the others report their edits here. */
let project = null;
const edited = (label) => project && project.edited(label);
const amend = () => project && project.amend();
const projectFiles = { isProject: (text) => !!project && project.isProject(text), open: (name, text) => project.open(name, text) };

/** The timeline under the canvas (timeline.js): it shows poses and redraws through these. */
// The arrow keys step frames on a rig or a character (on the arm they nudge its goal: input.js).
const arrowsStep = () => !!(state.rig || state.character);
const timeline = wireTimeline(state, { showPose: setPose, draw, toggleSolver, clearVia, ended: motionEnded, canPlay: durationOk, arrowsStep });

/** Zoom, pan, Fit and the onion skins' fields (viewctl.js). */
const views = wireViewControls(state, canvas, { draw, toggle: () => timeline.toggle(), requestDraw, recheck });

/** Following and traced paths (track.js). */
const paths = wireTrack(state, {
  timeline,
  setPose,
  draw,
  requestDraw,
  cancelMotion,
  showError,
  setStatus,
  // A followed goal out of the region says so after the status of each answer.
  say: (text) => {
    const miss = missShown();
    const status = /^status (\S+)/.exec(text);
    $("stats").textContent = miss && status ? text.replace(status[0], `${status[0]} · ${missNote(status[1], miss.distance)}`) : text;
    // A followed goal's answer after the drag: the drag's undo step holds the pose it reached.
    if (!state.press) amend();
  },
  showWhenEnded: (status, text) => {
    state.pendingStats = { status, text };
    setStatus("moving");
  },
});

/** The links table, the base and arm files (links.js). */
const armEditor = wireArm(state, {
  applyControls,
  recheck,
  controlsChanged,
  setPose,
  requestDraw,
  refreshWorkspace,
  clearPaths: () => paths.clear(),
  forgetMotion,
  showError,
  edited,
});

/** What the bodies' modules (keys, characters, rigs) share of main.js: drawing, the chip, and undo (each edit reported). */
const bodyActs = { requestDraw, showError, setStatus, say: (text) => ($("stats").textContent = text), edited };

/** The keys of a rig or a character, their motion and the bend handles (keyed.js). */
const keyed = wireKeyed(state, canvas, { ...bodyActs, timeline, draw, setPose, clipBack: () => characters.clipBack() });

/** A character: its clips on the timeline, its targets dragged, its export (characters.js). */
const characters = wireCharacters(state, canvas, { ...bodyActs, forgetMotion, timeline, keyed });

/** The character's art under the canvas (artview.js). */
const art = wireArt(state, canvas, { requestDraw, repose: () => characters.repose() });

/** The Body list and the rig's pointer (rigs.js). */
const rigs = wireRigs(state, canvas, { ...bodyActs, characters, keyed, forgetMotion, controlsChanged, fieldsOk, draw, amend, project: projectFiles });

/** The canvas's pointer over a rig or a character: one set of handlers, each body saying its part (bodyctl.js). */
wireBodyPointer(canvas, [characters.pointer, rigs.pointer], { keyed, requestDraw, edited });

project = wireProject(state, {
  rigs,
  characters,
  useArm: (arm) => armEditor.useArm(arm),
  setPose,
  settingsChanged,
  forgetMotion,
  applyKeys: (keys) => keyed.applyKeys(keys),
  keyed,
  timeline,
  views,
  seek: (u) => (state.playback.clip || state.animation ? timeline.seek(u) : (state.playback.u = u)),
  requestDraw,
  showError,
  say: bodyActs.say,
});

// ---- Drawing ------------------------------------------------------------------------------

/**
 * What the page lays over the canvas (the status chip, the hint, the collapsed panel's button)
 * as boxes in canvas pixels: the axis labels keep clear of them.
 */
function overlays() {
  const c = canvas.getBoundingClientRect();
  const boxes = [];
  for (const el of [$("chip"), $("hint"), $("zoom-box"), document.body.classList.contains("collapsed") ? $("panel") : null]) {
    if (!el) continue;
    const r = el.getBoundingClientRect();
    if (r.width > 0 && r.height > 0) boxes.push({ x: r.left - c.left, y: r.top - c.top, w: r.width, h: r.height });
  }
  return boxes;
}

function draw() {
  if (!state.arm || (state.character && !state.character.box)) return;
  fitCanvas(canvas, ctx);
  const [w, h] = [canvas.clientWidth, canvas.clientHeight];
  const fit = state.character ? characterView(state, w, h) : state.rig ? rigView(state, w, h) : fitView(state.arm, w, h);
  // The one view drawn and picked through: the fit under the camera.
  state.view = views.look(fit);
  state.view.keepOut = overlays();
  if (state.character) {
    // The art first, under the canvas: the canvas leaves it its background.
    if (art.draw(state.view)) state.view.under = "art";
    // The bones drawn, for scripts and tests.
    canvas.dataset.bones = String(drawCharacterScene(ctx, state.view, state));
    keyed.drawOver(ctx);
  } else if (state.rig) {
    art.hide();
    drawRigScene(ctx, state.view, state);
    keyed.drawOver(ctx);
    canvas.dataset.pose = state.rig.pose_deg.map((a) => a.toFixed(6)).join(" ");
  } else {
    art.hide();
    drawScene(ctx, state.view, state);
    // The pose drawn, for scripts and tests: joint angles in degrees.
    canvas.dataset.pose = state.pose_deg.map((a) => a.toFixed(6)).join(" ");
  }
  // The onion skins drawn, for scripts and tests: "before after".
  canvas.dataset.onion = state.view.onion.join(" ");
}

function requestDraw() {
  if (state.jobs.drawQueued) return;
  state.jobs.drawQueued = true;
  requestAnimationFrame(() => {
    state.jobs.drawQueued = false;
    draw();
  });
}

function setPose(pose, joints) {
  state.pose_deg = pose.slice();
  state.joints = joints || forward(state.arm, state.pose_deg);
}

// ---- Click: solve and animate -------------------------------------------------------------

/** The stats of a motion through via points: its goals' solves added up (status of the last). */
function motionStats(anim) {
  const solves = anim.solves || [];
  const last = solves[solves.length - 1] || {};
  return { status: last.status, iterations: solves.reduce((n, s) => n + s.iterations, 0), error: last.error, reach_distance: last.reach_distance };
}

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

// ---- Limits turned on: the pose into range ------------------------------------------------

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

/** "limits on: joint 1 moved into its range, 73.6° → 45°" (several: "joints 1 and 3 … their ranges, …"). */
function intoRangeText(moved) {
  const deg = (a) => `${Number(a.toFixed(1))}°`;
  const joints = moved.map((m) => m.joint);
  const which = joints.length === 1 ? `joint ${joints[0]}` : `joints ${joints.slice(0, -1).join(", ")} and ${joints.at(-1)}`;
  const steps = moved.map((m) => `${deg(m.from)} → ${deg(m.to)}`).join(", ");
  return `limits on: ${which} moved into ${joints.length === 1 ? "its range" : "their ranges"}, ${steps}`;
}

/** Traces a default shape (track.js) from the pose, taken into range first. */
function traceShape(kind) {
  settleIntoRange();
  paths.traceShape(kind);
}

// ---- Via points ---------------------------------------------------------------------------

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

/** Draw-path mode on or off: a drag on the canvas draws a stroke for the tip to trace. */
function setDrawPath(on) {
  state.drawPath = on;
  state.stroke = null;
  $("draw-path").setAttribute("aria-pressed", String(on));
  document.body.classList.toggle("drawing", on);
  armHint(state);
  requestDraw();
}

// ---- Workspace ----------------------------------------------------------------------------

/**
 * Asks for the reachable area of the arm when it is shown, or when limits are on (its exact
 * region then judges each goal at once, shown or not).
 */
function refreshWorkspace() {
  const jobs = state.jobs;
  clearTimeout(jobs.workspaceTimer);
  if (!state.arm || !(state.showWorkspace || state.options.limits)) return;
  jobs.workspaceTimer = setTimeout(async () => {
    const seq = ++jobs.workspaceSeq;
    const key = regionKey();
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
      requestDraw();
    } catch (e) {
      if (seq === jobs.workspaceSeq) showError(e);
    }
  }, WORKSPACE_DEBOUNCE_MS);
}

// ---- Controls and the arm -----------------------------------------------------------------

/** Brings the fields in line with each other and reads the settings of the next requests. */
function applyControls() {
  if (state.meta) {
    syncMethods(state.meta, state.arm.links.length, $("use-goal-angle").checked, !!state.rig);
    syncLimitModes(state.meta, state.limitModeChoice);
  }
  syncEnabled(state.meta);
  Object.assign(state, readControls(state.arm.links));
  timeline.choose(state.duration);
}

/**
 * The settings' fields were set all at once (an undo, a project opened): the page reads them as
 * their own handlers would.
 */
function settingsChanged() {
  state.limitModeChoice = $("limit-mode").value;
  state.follow = $("follow").checked;
  state.showGhosts = $("show-ghosts").checked;
  state.showTraces = $("show-traces").checked;
  state.showWorkspace = $("show-workspace").checked;
  state.reachMiss = null;
  controlsChanged();
  refreshWorkspace();
}

function controlsChanged() {
  if (!state.arm) return;
  applyControls();
  recheck();
  timeline.sync();
  requestDraw();
  // A rig's goals (or its keyed motion) are solved again with the new settings.
  if (state.rig) state.keys ? keyed.resolve() : rigs.resolve();
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

function resetPose() {
  if (state.character) {
    characters.reset();
    return;
  }
  if (state.rig) {
    rigs.reset();
    return;
  }
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

// ---- Wiring -------------------------------------------------------------------------------

/** The panel hidden (the canvas takes the whole width) or shown. */
function setCollapsed(c) {
  const toggle = $("panel-toggle");
  if (document.body.classList.contains("collapsed") === c) return;
  document.body.classList.toggle("collapsed", c);
  toggle.setAttribute("aria-expanded", String(!c));
  toggle.textContent = c ? "Show controls" : "Hide controls";
  requestDraw();
}

function wire() {
  const { extendStroke, endStroke } = paths;
  // Nothing is asked of the server while a field holds a bad value: the field is shown instead.
  const followTo = (x, y) => fieldsOk(false) && followGoal(x, y);
  const startStroke = (x, y) => fieldsOk() && (settleIntoRange(), paths.startStroke(x, y));
  // In Key mode a drag of the arm's tip keys its track (link N-1) at the drop point instead.
  const dragEnded = (x, y, from) => keyed.dragEnded(`link${state.arm.links.length - 1}`, { x, y }, from) || edited("Follow the pointer");
  wireInput(canvas, state, { animateTo, followTo, addVia, cancelMotion, requestDraw, startStroke, extendStroke, endStroke, dragEnded });
  wireDownloads(state, showError, () => timeline.duration());
  for (const id of ["method", "restarts", "lambda", "tolerance", "max-iterations", "ease", "k1", "k2", "frames", "max-step", "use-goal-angle", "goal-angle", "duration"]) {
    $(id).addEventListener("change", controlsChanged);
  }
  // A new "Replay every" shows at once when the solver's replay is on.
  $("record-every").addEventListener("change", () => {
    controlsChanged();
    if (state.playback.solver && !firstProblem()) toggleSolver(true);
  });
  $("limit-mode").addEventListener("change", (ev) => {
    state.limitModeChoice = ev.target.value;
    controlsChanged();
  });
  $("limits").addEventListener("change", () => {
    state.reachMiss = null;
    controlsChanged();
    glideIntoRange();
    refreshWorkspace();
  });
  $("follow").addEventListener("change", (ev) => {
    state.follow = ev.target.checked;
  });
  $("draw-path").addEventListener("click", () => setDrawPath(!state.drawPath));
  for (const kind of ["line", "circle", "figure8"]) {
    $(`trace-${kind}`).addEventListener("click", () => state.arm && fieldsOk() && traceShape(kind));
  }
  $("show-ghosts").addEventListener("change", (ev) => {
    state.showGhosts = ev.target.checked;
    requestDraw();
  });
  $("show-traces").addEventListener("change", (ev) => {
    state.showTraces = ev.target.checked;
    requestDraw();
  });
  $("show-workspace").addEventListener("change", (ev) => {
    state.showWorkspace = ev.target.checked;
    if (state.showWorkspace) refreshWorkspace();
    requestDraw();
  });
  $("reset").addEventListener("click", () => {
    resetPose();
    edited("Reset pose");
  });
  const narrow = window.matchMedia("(max-width: 720px)");
  $("panel-toggle").addEventListener("click", () => setCollapsed(!document.body.classList.contains("collapsed")));
  if (narrow.matches) setCollapsed(true);
  new ResizeObserver(requestDraw).observe(canvas);
  // The labels keep clear of the chip: a chip that grows or shrinks redraws them.
  new ResizeObserver(requestDraw).observe($("chip"));
  window.addEventListener("resize", requestDraw);
}

async function init() {
  wire();
  // Where the solver runs, under the controls and as body[data-backend] ("server" or "wasm").
  api.backend().then((b) => {
    $("backend").textContent = b.label;
    document.body.dataset.backend = b.kind;
  });
  try {
    const [meta, arm] = await Promise.all([api.meta(), api.defaultArm(), rigs.load()]);
    state.meta = meta;
    usePalette(meta.palette);
    state.limitModeChoice = meta.default_limit_mode;
    fillSelects(meta);
    keyed.fillEases(meta);
    // The arm of the last visit, else the server's default.
    state.arm = storedArm() || arm;
    armEditor.showLinks();
    applyControls();
    armEditor.showBase();
    setPose(state.arm.links.map((l) => l.angle_deg));
    setStatus("ready");
    $("stats").textContent = "ready";
    timeline.sync();
    project.start();
    window.ikarus.ready = true;
    draw();
  } catch (e) {
    showError(e);
    setStatus("error");
  }
}

// For scripts and browser tests: the page's state and a few actions.
window.ikarus = {
  state,
  ready: false,
  animateTo,
  followTo: (x, y) => fieldsOk() && followGoal(x, y),
  traceShape: (kind) => fieldsOk() && traceShape(kind),
  resetPose,
  /** Shows the arm ("arm") or a rig of the Body list ("rig:puppet", "file"); whether no rig solve is in flight or waiting. */
  rigs: { use: (value) => rigs.use(value), settled: () => rigs.settled() },
  /** A rig's keys: restore a KEYS object (undo, projects), whether no keyed motion is asked, Key mode, the playhead (seconds), the bend handles (canvas pixels). */
  keys: { apply: (k) => keyed.applyKeys(k), settled: () => keyed.settled(), mode: (on) => keyed.setMode(on), seek: (t) => keyed.seek(t), handles: () => keyed.handles(), sent: () => keyed.sent() },
  /** Whether no pose of the character shown is in flight or waiting. */
  characters: { settled: () => characters.settled() },
  /** The slots of the character's art last drawn, and the draws with art so far (artview.js). */
  art: { slots: () => art.slots(), draws: () => art.draws() },
  /** Undo, redo, save and open (projects.js), the work as a snapshot, and whether it is unsaved. */
  project: {
    undo: () => project.undo(),
    redo: () => project.redo(),
    save: () => project.save(),
    open: (name, text) => project.open(name, text),
    sizes: () => project.sizes(),
    dirty: () => project.dirty(),
  },
  /** The timeline's playback duration, seconds. */
  duration: () => timeline.duration(),
  /** Puts the playhead at `t` seconds of the playback (a clip's own seconds for a character). */
  seek: (t) => timeline.seek(t / timeline.duration()),
  /** Client coordinates of a world point, for clicking on it. */
  toClient(x, y) {
    const r = canvas.getBoundingClientRect();
    const [px, py] = toCanvas(state.view, x, y);
    return [r.left + px, r.top + py];
  },
};

init();
