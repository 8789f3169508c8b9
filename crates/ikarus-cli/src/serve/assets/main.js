// The ikarus playground: draws the arm on a canvas and asks the JSON API (same origin) to solve,
// animate, get the reachable region and render pictures. Plain ES modules, no dependencies, no
// build step. This module wires the page: it owns the one `state` object (state.js documents
// it), and every other module either computes (view.js; region.js, the exact reachable region:
// its path, which goals it holds and the nearest reachable point), talks to the server (api.js),
// draws what the state shows (draw.js), reads and fills the form (controls.js), turns pointer and
// keys into actions (input.js), moves the arm to a clicked goal (armmotion.js), asks for its
// reachable area (workspace.js), plays motions on the timeline (timeline.js, which owns
// `state.playback`), follows the pointer and traces paths (track.js, with the pure parts in
// paths.js), edits the arm (links.js, with arm files in armfile.js), shows and solves a rig
// instead of the arm (rigs.js, with the pure parts in rig.js and the drawing in drawrig.js),
// poses a character (characters.js, with the pure parts in character.js and the drawing in
// drawchar.js; the pointer and the one request in flight of both are bodyctl.js's), keys them
// (keyed.js) or saves files (files.js, with the figures drawn by export.js). The view drawn and
// picked through is the body's fitted view under the camera (camera.js: zoom and pan, moved by
// viewctl.js, which also holds the onion skins' fields; onion.js draws them). The chip on the
// canvas (status, messages, bad fields, the goal's reach) is chip.js's.

import * as api from "./api.js";
import { fillSelects, firstProblem, readControls, syncEnabled, syncLimitModes, syncMethods } from "./controls.js";
import { storedArm } from "./armfile.js";
import { wireArm } from "./links.js";
import { wireArmMotion } from "./armmotion.js";
import { drawScene } from "./draw.js";
import { fitCanvas, usePalette } from "./paint.js";
import { drawRigScene, rigView } from "./drawrig.js";
import { characterView, drawCharacterScene } from "./drawchar.js";
import { wireArt } from "./artview.js";
import { armHint, wireBodyPointer } from "./bodyctl.js";
import { wireCharacters } from "./characters.js";
import { wireRigs } from "./rigs.js";
import { wireKeyed } from "./keyed.js";
import { wireDownloads } from "./files.js";
import { wireInput } from "./input.js";
import { newState } from "./state.js";
import { wireTimeline } from "./timeline.js";
import { wireViewControls } from "./viewctl.js";
import { wireTrack } from "./track.js";
import { wireProject } from "./projects.js";
import { wireChip } from "./chip.js";
import { askWorkspace } from "./workspace.js";
import { fitView, forward, toCanvas } from "./view.js";

const $ = (id) => document.getElementById(id);
const canvas = $("plot");
const ctx = canvas.getContext("2d");

/** Everything of the page that changes (state.js documents its fields). */
const state = newState();

/** The chip on the canvas: status, messages, bad fields and the goal's reach (chip.js). */
const chip = wireChip(state, { setCollapsed });
const { showError, setStatus, fieldsOk, durationOk, recheck, regionKey, missShown, missNote } = chip;

/** Undo, redo and project files (projects.js), wired last: the others report their edits here. */
let project = null;
const edited = (label) => project && project.edited(label);
const amend = () => project && project.amend();
const projectFiles = { isProject: (text) => !!project && project.isProject(text), open: (name, text) => project.open(name, text) };

/** The timeline under the canvas (timeline.js): it shows poses and redraws through these. */
// The arrow keys step frames on a rig or a character (on the arm they nudge its goal: input.js).
const arrowsStep = () => !!(state.rig || state.character);
const timeline = wireTimeline(state, {
  showPose: setPose,
  draw,
  toggleSolver: (solver) => motions.toggleSolver(solver),
  clearVia: () => motions.clearVia(),
  ended: () => motions.motionEnded(),
  canPlay: durationOk,
  arrowsStep,
});

/** Zoom, pan, Fit and the onion skins' fields (viewctl.js). */
const views = wireViewControls(state, canvas, { draw, toggle: () => timeline.toggle(), requestDraw, recheck });

/** Following and traced paths (track.js). */
const paths = wireTrack(state, {
  timeline,
  setPose,
  draw,
  requestDraw,
  cancelMotion: () => motions.cancelMotion(),
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

/** The arm's motions: a click's, the solver's replay, the glide into range (armmotion.js). */
const motions = wireArmMotion(state, { timeline, paths, chip, setPose, requestDraw, edited, amend });
const { animateTo, cancelMotion, forgetMotion, glideIntoRange, settleIntoRange, traceShape, followGoal, addVia, toggleSolver } = motions;

/** The arm's reachable area (workspace.js), asked again as the arm or its limits change. */
const refreshWorkspace = () => askWorkspace(state, { regionKey, requestDraw, showError });

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

/** Draw-path mode on or off: a drag on the canvas draws a stroke for the tip to trace. */
function setDrawPath(on) {
  state.drawPath = on;
  state.stroke = null;
  $("draw-path").setAttribute("aria-pressed", String(on));
  document.body.classList.toggle("drawing", on);
  armHint(state);
  requestDraw();
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

function resetPose() {
  if (state.character) {
    characters.reset();
    return;
  }
  if (state.rig) {
    rigs.reset();
    return;
  }
  motions.reset();
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
