// Rigs on the page: choosing what the canvas solves (the arm, a shipped rig from GET /api/rigs,
// or a rig file read by POST /api/rig/parse), and the rig's pointer: a press on a bone's tip
// grabs it, a drag moves its goal and the whole rig follows (POST /api/solve with `rig`, one
// request in flight, always from the pose shown, and only the latest goals wait: latest wins),
// a click (no drag) pins or unpins the tip. Goals stay where they were dragged, so several
// effectors hold their goals at once, until "Clear goals" (or Esc on the canvas) drops them;
// pins stay until clicked again or "Unpin all". The pure parts are rig.js; the drawing is
// drawrig.js; the pointer's handlers and the one request in flight are bodyctl.js's, shared with
// characters.js. It writes `state.rig` (below) and tells main.js through `act`. A character file
// (Spine, DragonBones), picked or dropped anywhere on the page, goes to characters.js.

import * as api from "./api.js";
import { postText } from "./armfile.js";
import { loadTogether } from "./artload.js";
import { bodyForward, restValue } from "./body.js";
import { armHint, canvasPoint, listBody, sendLatest } from "./bodyctl.js";
import { dragGoal, answerPose, rigSolveRequest, rigSummary, shownEffectors, tipAt, togglePin } from "./rig.js";
import { toCanvas, toWorld } from "./view.js";

const $ = (id) => document.getElementById(id);

/**
 * A fresh `state.rig` for `rig` (a rig file's JSON: {name, base, bones: [{name, parent, length,
 * angle_deg, limits_deg}]}):
 *   rig        the rig;  source  where it came from ("rig:puppet", "file")
 *   pose_deg   the pose shown (body.js's joint values: degrees, or lengths for prismatic bones; bone order); starts, tips, headings, parentHeadings: its
 *              forward kinematics (body.js's bodyForward)
 *   goals      Map bone name -> {x, y}, in the order they were made;  pins  Set of bone names
 *   grabbed    the bone being dragged, or null;  hover  the effector under the pointer, or null
 *   busy       a solve is in flight;  pending  the goals changed since it left (ask again)
 *   answer     the last /api/solve answer;  request  its request;  solves  answers received
 */
function newRigState(rig, source) {
  const r = {
    rig,
    source,
    pose_deg: rig.bones.map(restValue),
    goals: new Map(),
    pins: new Set(),
    grabbed: null,
    hover: null,
    busy: false,
    pending: false,
    answer: null,
    request: null,
    solves: 0,
  };
  return Object.assign(r, bodyForward(rig, r.pose_deg));
}

/**
 * Wires the Body fieldset and the rig's pointer on `canvas`. `act` is {characters
 * (characters.js's), keyed (keyed.js's: keys from drags and pin clicks in Key mode, the bend
 * handles, which a press tries first), forgetMotion(),
 * controlsChanged(), fieldsOk(point), draw(), requestDraw(), showError(e), setStatus(s),
 * say(text), edited(label) (an undo step), amend() (the last step settled), project
 * (projects.js's: a project file picked or dropped opens there)}. Returns {load() (the shipped
 * rigs into the list), use(value), useRig(value or rig JSON), shipped(), setWork(work), reset(),
 * resolve(), settled(), names(), pointer (the rig's part of bodyctl.js's wireBodyPointer)}.
 */
export function wireRigs(state, canvas, act) {
  /** The rigs the list offers by value ("rig:puppet", "file"). */
  const rigs = new Map();
  /** The limits checkbox of the arm, given back when the arm returns (a rig turns limits on). */
  let armLimits = null;
  /** Each rig's work when another body took the canvas: list value -> {r (its rig state)} (keyed.js keeps its keys). */
  const kept = new Map();

  const names = () => state.rig.rig.bones.map((b) => b.name);

  function show(text) {
    act.say(text);
  }

  function idle() {
    const r = state.rig;
    act.setStatus("ready");
    show(`rig ${r.rig.name || "rig"} · ${r.rig.bones.length} bones · drag an effector, click one to pin it`);
  }

  /**
   * The rig `value` of the list (or the arm): the canvas solves it from its start pose, or, when
   * `resume` and it was shown before, as it was left (an undo or a project sets its work itself).
   */
  function use(value, resume = true) {
    const select = $("body-kind");
    // Its work kept for its return; its keys (or the arm's) leave with it, kept by keyed.js,
    // before anything solves the next body.
    if (state.rig) kept.set(state.rig.source, { r: state.rig });
    if (!(value === "character" && state.character)) act.keyed.leave();
    if (value === "character") {
      if (state.rig) use("arm");
      act.characters.resume();
      return;
    }
    act.characters.leave();
    if (value === "arm") {
      if (!state.rig) {
        // From a character: the arm's keys, if it had any when it left.
        act.keyed.resume();
        return;
      }
      state.rig = null;
      act.keyed.leave();
      document.body.classList.remove("rig");
      delete document.body.dataset.failed;
      if (armLimits !== null) $("limits").checked = armLimits;
      armLimits = null;
      armHint(state);
      select.value = "arm";
      act.forgetMotion();
      act.showError(null);
      act.controlsChanged();
      // The arm's keys, if it had any when it left.
      act.keyed.resume();
      act.requestDraw();
      return;
    }
    const rig = rigs.get(value);
    if (!rig) return;
    act.forgetMotion();
    if (!state.rig) {
      // A rig is a body with joint ranges: it is solved with them unless the reader turns them off.
      armLimits = $("limits").checked;
      $("limits").checked = true;
    }
    // A rig shown before comes back as it was left: its goals, pins, pose and keys.
    const back = resume ? kept.get(value) : undefined;
    state.rig = back && back.r.rig === rig ? Object.assign(back.r, { grabbed: null, hover: null, busy: false, pending: false }) : newRigState(rig, value);
    document.body.classList.add("rig");
    delete document.body.dataset.failed;
    $("hint").textContent = $("hint").dataset.rig;
    select.value = value;
    act.showError(null);
    act.controlsChanged();
    idle();
    act.keyed.enter();
    // A rig resumed: its keys (a new rig state has none).
    act.keyed.resume();
    act.requestDraw();
  }

  /** The shipped rigs (GET /api/rigs) into the list. */
  async function load() {
    try {
      const answer = await api.get("/api/rigs");
      const select = $("body-kind");
      for (const { name, rig } of answer.rigs || []) {
        const value = `rig:${name}`;
        rigs.set(value, rig);
        select.append(new Option(`Rig: ${name}`, value));
      }
    } catch (e) {
      // The list keeps the arm and "Load rig…"; the reason is said, not thrown.
      act.showError(e);
    }
  }

  /**
   * A rig file, a character file or a project file the reader picked or dropped: a project
   * (a JSON object with `ikarus_project`) goes to projects.js; the others are read by the server
   * (the format told from the content); a bad one is its one-line problem. A Spine binary export
   * (`.skel`, or any file that is not UTF-8 text) is sent as its bytes, and the character is
   * then the JSON text the server decoded it into (what the page keeps, poses and exports).
   */
  async function loadFile(file) {
    try {
      const bytes = await file.arrayBuffer();
      const text = fileText(file.name, bytes);
      if (text === null) {
        const answer = await api.postFile(bytes);
        useRead(file.name, answer, answer.text);
        return;
      }
      if (act.project.isProject(text)) {
        await act.project.open(file.name, text);
        return;
      }
      const answer = JSON.parse(await postText("/api/rig/parse", text, "application/toml"));
      if (answer.problem) throw new api.Notice(api.forPeople(answer.problem));
      useRead(file.name, answer, text);
    } catch (e) {
      act.showError(e);
    }
  }

  /** The file `name` as the server read it (`answer`: its `character` or `rig`; `text`: a character's JSON text) on the canvas: one undo step. */
  function useRead(name, answer, text) {
    if (answer.character) {
      if (state.rig) use("arm");
      act.characters.enter(name, text, answer.character);
    } else {
      useRigFile(answer.rig, name);
    }
    act.edited(`Load ${name}`);
  }

  /**
   * Files picked or dropped together: one skeleton, rig or project file loads as it is
   * (loadFile); a skeleton with its atlas and page images loads with its art (artload.js).
   */
  function loadFiles(files) {
    if (files.length === 1 && !/\.(atlas|png|jpe?g|webp)$/i.test(files[0].name)) return loadFile(files[0]);
    if (files.length) return loadTogether(files, { state, loadFile, characters: act.characters, showError: act.showError });
  }

  /** A file's text, or null for a file sent as bytes: a `.skel`, or one that is not UTF-8 text. */
  function fileText(name, bytes) {
    if (/\.skel$/i.test(name)) return null;
    try {
      return new TextDecoder("utf-8", { fatal: true }).decode(bytes);
    } catch (_) {
      return null;
    }
  }

  /** A rig file's JSON (`name`: the file's, when the rig has none) shown as the list's "Rig file: …". */
  function useRigFile(rig, name = "rig") {
    listBody("file", `Rig file: ${rig.name || name}`);
    rigs.set("file", rig);
    use("file");
  }

  /** A shipped rig by its list value ("rig:puppet") or a rig file's JSON: shown from its start pose. */
  const useRig = (rig) => (typeof rig === "string" ? use(rig, false) : useRigFile(rig));

  /** The shipped rigs: Map name -> rig JSON. */
  const shipped = () => new Map([...rigs].filter(([v]) => v.startsWith("rig:")).map(([v, rig]) => [v.slice(4), rig]));

  /**
   * The rig's work put back (an undo, a project opened): `goals` [{bone, x, y}], `pins` [bone],
   * `pose_deg` (the pose shown; the start pose when absent). No solve: the pose is the one saved.
   */
  function setWork({ goals, pins, pose_deg }) {
    const r = state.rig;
    if (!r) return;
    r.goals = new Map(goals.map((g) => [g.bone, { x: g.x, y: g.y }]));
    r.pins = new Set(pins);
    r.pending = false;
    r.pose_deg = pose_deg ? pose_deg.slice() : r.rig.bones.map(restValue);
    Object.assign(r, bodyForward(r.rig, r.pose_deg));
    idle();
    act.requestDraw();
  }

  // ---- Solving ---------------------------------------------------------------------------

  /** The goals or pins changed: solve (now, or when the solve in flight is back). */
  function solveSoon() {
    state.rig.pending = true;
    sendLatest(solves);
  }

  /** The rig's solves, one in flight (bodyctl.js's sendLatest), always from the pose shown. */
  const solves = {
    shown: () => state.rig,
    next(r) {
      if (!r.pending) return null;
      r.pending = false;
      if (r.goals.size === 0 || !act.fieldsOk(false)) return null;
      return rigSolveRequest(r.rig, r.pose_deg, r.goals, r.pins, state.options);
    },
    send: (req) => api.solve(req),
    done: apply,
    failed(r, req, e) {
      act.showError(e);
      act.setStatus("error");
    },
  };

  function apply(r, req, answer) {
    r.pose_deg = answerPose(r.rig, answer, r.pose_deg);
    Object.assign(r, bodyForward(r.rig, r.pose_deg));
    r.answer = answer;
    r.request = req;
    r.solves++;
    const s = rigSummary(answer);
    act.showError(null);
    show(s.text);
    document.body.dataset.failed = s.failed.join(" ");
    act.setStatus(answer.status);
    act.draw();
    // The last solve of a drag came back: the undo step of the drag holds its pose.
    if (!r.pending && !r.grabbed) act.amend();
  }

  /** Whether no solve is in flight or waiting (for tests and scripts). */
  const settled = () => !!state.rig && !state.rig.busy && !state.rig.pending;

  /** Solves again with the current goals (the solver's settings changed). */
  function resolve() {
    if (state.rig && state.rig.goals.size) solveSoon();
  }

  function setGoalsAndPins({ goals, pins }) {
    state.rig.goals = goals;
    state.rig.pins = pins;
  }

  function clearGoals() {
    const r = state.rig;
    if (!r) return;
    r.goals = new Map();
    r.pending = false;
    delete document.body.dataset.failed;
    act.showError(null);
    idle();
    act.requestDraw();
  }

  function unpinAll() {
    if (!state.rig) return;
    state.rig.pins = new Set();
    act.requestDraw();
  }

  /** Back to the start pose, with no goals (the pins stay: they hold the tips where they are). */
  function reset() {
    const r = state.rig;
    r.pose_deg = r.rig.bones.map(restValue);
    Object.assign(r, bodyForward(r.rig, r.pose_deg));
    clearGoals();
  }

  // ---- The pointer (bodyctl.js's wireBodyPointer) ---------------------------------------

  /** The bone whose tip is under the event, effectors first. */
  function tipUnder(ev) {
    const r = state.rig;
    const tipsPx = r.tips.map(([x, y]) => toCanvas(state.view, x, y));
    return tipAt(r.rig, tipsPx, ...canvasPoint(canvas, ev), new Set(shownEffectors(r.rig, r.goals, r.pins)));
  }

  /** The rig's part of the canvas's pointer: a press on a tip grabs its goal; a click pins it. */
  const pointer = {
    shown: () => state.rig,
    ready: () => true,
    grab(ev, r) {
      const bone = tipUnder(ev);
      return bone ? { name: bone, from: r.tips[names().indexOf(bone)] } : null;
    },
    under: (ev) => tipUnder(ev),
    cursor: (bone) => (bone ? "grab" : ""),
    hovered() {},
    drag(press, ev, r) {
      const [x, y] = toWorld(state.view, ...canvasPoint(canvas, ev));
      setGoalsAndPins(dragGoal(r.goals, r.pins, press.name, x, y));
      act.requestDraw();
      solveSoon();
    },
    release({ name: bone, dragging, from }, ev, r) {
      if (dragging) act.keyed.dragEnded(bone, r.goals.get(bone), from);
      r.hover = tipUnder(ev);
      canvas.style.cursor = r.hover ? "grab" : "";
      if (dragging) {
        act.edited(`Move ${bone} goal`);
        return;
      }
      setGoalsAndPins(togglePin(r.goals, r.pins, bone));
      act.keyed.pinToggled(bone);
      act.edited(`${r.pins.has(bone) ? "Pin" : "Unpin"} ${bone}`);
      show(`${bone} ${r.pins.has(bone) ? "pinned" : "unpinned"} · ${r.pins.size} pin${r.pins.size === 1 ? "" : "s"}, ${r.goals.size} goal${r.goals.size === 1 ? "" : "s"}`);
      // A pin dropped a goal: the others are solved again without it.
      if (r.goals.size) solveSoon();
    },
    clear: clearGoals,
    clearLabel: "Clear goals",
  };

  $("body-kind").addEventListener("change", (ev) => {
    use(ev.target.value);
    act.edited(`Body: ${ev.target.selectedOptions[0].textContent}`);
  });
  $("load-rig").addEventListener("click", () => $("rig-file").click());
  $("rig-file").addEventListener("change", (ev) => {
    const files = [...ev.target.files];
    ev.target.value = "";
    loadFiles(files);
  });
  // A file dropped anywhere on the page is loaded as if picked.
  document.addEventListener("dragover", (ev) => {
    if (ev.dataTransfer && [...ev.dataTransfer.types].includes("Files")) ev.preventDefault();
  });
  document.addEventListener("drop", (ev) => {
    const files = ev.dataTransfer ? [...ev.dataTransfer.files] : [];
    if (!files.length) return;
    ev.preventDefault();
    loadFiles(files);
  });
  $("clear-goals").addEventListener("click", () => {
    clearGoals();
    act.edited("Clear goals");
  });
  $("unpin-all").addEventListener("click", () => {
    unpinAll();
    act.edited("Unpin all");
  });

  return { load, use, useRig, shipped, setWork, reset, resolve, settled, names, pointer };
}
