// The page's work kept and given back: undo and redo of every edit (history.js's stack of
// project.js's snapshots), *Save project* (a `NAME.ikarus.json` download), *Open project…* and a
// project file dropped on the page (rigs.js hands it over: a JSON object with `ikarus_project`),
// and the warning before a reload would lose edits made since the last save or open. A snapshot
// is put back through the page's own actions (`act`), never by half-filling the form. A file also
// holds the view (Key mode, the camera's zoom and pan), put back when it opens; undo does not
// step through the view (zooming is not an edit).
//
// What is an edit: every change of a panel setting (listened to here), and what the other
// modules report through `edited(label)` (main.js, links.js, rigs.js, characters.js, the keys):
// a goal or target moved (at the end of the drag), a pin, a link, a clip, a body, a key. Ctrl-Z
// undoes, Ctrl-Shift-Z and Ctrl-Y redo (Cmd on macOS), unless the focus is in a text field,
// whose own undo works there.

import { Notice, forPeople, get, postText } from "./api.js";
import { saveBlob } from "./files.js";
import { newHistory } from "./history.js";
import { isProjectText, projectFile, projectName, readProject, snapshot, workKey } from "./project.js";

const $ = (id) => document.getElementById(id);

/** The panel's settings by id (the other fields of #panel-body are found too: a new control is saved). */
const SETTINGS = ["method", "limits", "limit-mode", "restarts", "lambda", "tolerance", "max-iterations", "record-every", "use-goal-angle", "goal-angle", "ease", "k1", "k2", "frames", "max-step", "duration", "follow", "show-ghosts", "show-traces", "show-workspace"];

/**
 * Fields of the panel that are not settings: Key mode (the arm's), the body, files, a
 * character's clip, skin and physics switch (its state), the base (the arm's), and the onion skins and the bones over a
 * character's art (view settings, like zoom: no undo step).
 */
const NOT_SETTINGS = new Set(["arm-key-mode", "body-kind", "rig-file", "arm-file", "project-file", "character-animation", "character-skin", "character-physics", "base-x", "base-y", "onion", "onion-count", "show-bones"]);

/** Every setting's element: the known ones, then any other named field of the panel. */
function settingFields() {
  const known = SETTINGS.map($).filter(Boolean);
  const more = [...document.querySelectorAll("#panel-body input[id], #panel-body select[id]")].filter(
    (el) => !SETTINGS.includes(el.id) && !NOT_SETTINGS.has(el.id) && !el.closest("#links-body") && !["file", "radio", "range", "button"].includes(el.type),
  );
  return [...known, ...more];
}

const isCheck = (el) => el.type === "checkbox";

/** The panel's settings: a check box's true/false, another field's text. */
export function readSettings() {
  return Object.fromEntries(settingFields().map((el) => [el.id, isCheck(el) ? el.checked : el.value]));
}

/** The name of a field, for an undo step's label. */
function fieldLabel(el) {
  const label = (el.id && document.querySelector(`label[for="${el.id}"]`)) || el.closest("label");
  const text = (label ? label.textContent : el.getAttribute("aria-label") || el.id).trim().replace(/\s+/g, " ");
  return text.replace(/ s$/, "");
}

/** SHA-256 of `bytes`, hex (the page's secure context has crypto.subtle; else none). */
async function sha256(bytes) {
  if (!globalThis.crypto || !crypto.subtle) return undefined;
  const d = new Uint8Array(await crypto.subtle.digest("SHA-256", bytes));
  return [...d].map((b) => b.toString(16).padStart(2, "0")).join("");
}

/**
 * Wires undo, redo and project files. `act` is {rigs (rigs.js's), characters (characters.js's),
 * useArm(arm) (links.js's), setPose(pose), settingsChanged() (the settings' fields were set: the
 * page reads them), forgetMotion(), applyKeys(keys) (keyed.js's: the keys shown and their motion
 * asked), keyed (keyed.js's: setLength, length, mode, setMode), timeline (timeline.js's:
 * duration), views (viewctl.js's: setCamera), seek(u) (the playhead to a fraction of the
 * timeline), requestDraw(), showError(e), say(text)}. Returns {start(), edited(label),
 * amend(), undo(), redo(), save(), open(name, text), isProject(text), dirty(), sizes(),
 * restoring()}.
 */
export function wireProject(state, act) {
  /** The work as the page starts (its arm and settings are the defaults of a file missing them). */
  let defaults = null;
  let history = null;
  let savedKey = "";
  /** A snapshot is being put back (its actions' edits are not new steps), or a file opened. */
  let restoring = false;

  /** The timeline's length now, seconds (0 when it has none). */
  const seconds = () => {
    const d = act.timeline.duration();
    return Number.isFinite(d) && d > 0 ? d : 0;
  };
  const take = () => snapshot(state, readSettings(), { key_length: act.keyed.length(), playhead_s: state.playback.u * seconds() });
  const dirty = () => !!history && workKey(history.present()) !== savedKey;

  function sync() {
    if (!history) return;
    const [u, r] = [history.undoLabel(), history.redoLabel()];
    const mac = /Mac|iPhone|iPad/.test(navigator.platform);
    $("undo").disabled = u === null;
    $("undo").title = u === null ? "Nothing to undo" : `Undo: ${u} (${mac ? "⌘Z" : "Ctrl+Z"})`;
    $("redo").disabled = r === null;
    $("redo").title = r === null ? "Nothing to redo" : `Redo: ${r} (${mac ? "⇧⌘Z" : "Ctrl+Shift+Z or Ctrl+Y"})`;
    document.body.dataset.dirty = String(dirty());
  }

  /** The page is ready: its work now is the first step and the defaults of files. */
  function start() {
    defaults = take();
    history = newHistory(defaults, workKey);
    savedKey = workKey(defaults);
    sync();
  }

  /** An edit was made (already applied): one undo step named `label`. */
  function edited(label) {
    if (!history || restoring) return;
    if (history.record(take(), label)) sync();
  }

  /** What the last edit led to has settled (a solve came back): the step holds it, no new step. */
  function amend() {
    if (!history || restoring) return;
    history.amend(take());
    sync();
  }

  /**
   * Puts `snap` back through the page's actions, and `view` ({key_mode, camera}: an opened
   * file's; undo has none) with it.
   */
  function restore(snap, view = null) {
    restoring = true;
    try {
      act.forgetMotion();
      // The arm (kept while a rig or character shows) is set again only when it differs.
      if (JSON.stringify(state.arm) !== JSON.stringify(snap.arm)) act.useArm(JSON.parse(JSON.stringify(snap.arm)));
      const b = snap.body;
      if (b.kind === "rig") act.rigs.useRig(b.rig ? `rig:${b.rig}` : JSON.parse(JSON.stringify(b.file)));
      else if (b.kind === "arm" || state.rig) act.rigs.use("arm");
      if (b.kind === "character") act.characters.ensure(b.character.name, b.character.text, b.character.parsed);
      applySettings(snap.settings);
      if (b.kind === "arm") {
        state.goal = snap.goal ? { ...snap.goal } : null;
        state.via = snap.via.map((p) => ({ ...p }));
        act.setPose(snap.pose_deg);
      }
      if (snap.rig) act.rigs.setWork(snap.rig);
      if (snap.character) act.characters.setWork(snap.character);
      // Key mode and the Length before the keys: they decide what the timeline plays and how long.
      if (view) act.keyed.setMode(view.key_mode);
      act.keyed.setLength(snap.key_length);
      const keys = snap.keys ? JSON.parse(JSON.stringify(snap.keys)) : null;
      act.applyKeys(keys);
      // The playhead in seconds (a file of the earlier shape: a fraction of the timeline).
      const d = seconds();
      act.seek(snap.playhead_s === undefined ? snap.playhead : d > 0 ? Math.min(snap.playhead_s / d, 1) : 0);
      if (view) act.views.setCamera(view.camera);
      act.requestDraw();
    } finally {
      restoring = false;
    }
  }

  /** Sets the settings' fields to `settings` and lets the page read them. */
  function applySettings(settings) {
    const changed = [];
    for (const el of settingFields()) {
      const v = settings[el.id];
      if (v === undefined) continue;
      const before = isCheck(el) ? el.checked : el.value;
      if (isCheck(el)) el.checked = v;
      else el.value = v;
      if (before !== v && !SETTINGS.includes(el.id)) changed.push(el);
    }
    act.settingsChanged();
    // Another module's control (not one main.js reads) hears its change as from the reader.
    for (const el of changed) el.dispatchEvent(new Event("change", { bubbles: true }));
  }

  function step(which) {
    if (!history || restoring) return;
    history.amend(take());
    const s = which === "undo" ? history.undo() : history.redo();
    if (!s) return;
    restore(history.present());
    history.amend(take());
    act.showError(null);
    act.say(`${which === "undo" ? "undid" : "redid"}: ${s.label}`);
    sync();
  }

  /** The version that saves: `ikarus X.Y.Z` from the server (GET /api/health), else plain "ikarus". */
  let savedBy = null;
  async function version() {
    if (savedBy) return savedBy;
    try {
      const h = await get("/api/health");
      savedBy = h.version ? `ikarus ${h.version}` : "ikarus";
    } catch (_) {
      savedBy = "ikarus";
    }
    return savedBy;
  }

  /** Downloads the work as `NAME.ikarus.json`; the page is not dirty after it. */
  async function save() {
    if (!history) return;
    amend();
    const snap = history.present();
    try {
      const extra = {};
      if (snap.body.kind === "character") {
        const bytes = new TextEncoder().encode(snap.body.character.text);
        extra.size = bytes.length;
        extra.sha256 = await sha256(bytes);
      }
      const file = projectFile(snap, await version(), extra, { key_mode: act.keyed.mode(), camera: state.camera });
      const name = projectName(snap);
      saveBlob(new Blob([JSON.stringify(file, null, 1)], { type: "application/json" }), name);
      savedKey = workKey(snap);
      act.showError(null);
      act.say(`saved ${name}`);
      sync();
    } catch (e) {
      act.showError(e);
    }
  }

  /**
   * The character of a project found: its embedded text (parsed by the server, unless it is the
   * one loaded), or the loaded character of the same name, size and SHA-256. Sets `ref.text` and
   * `ref.parsed`, or throws why not.
   */
  async function findCharacter(ref) {
    const loaded = [state.character, act.characters.loaded()].filter((c) => c && c.name === ref.name);
    if (ref.text !== undefined) {
      const same = loaded.find((c) => c.text === ref.text);
      if (same) {
        ref.parsed = same.character;
        return;
      }
      const answer = JSON.parse(await postText("/api/rig/parse", ref.text, "application/toml"));
      if (answer.problem) throw new Error(`project file: body.character.text: ${forPeople(answer.problem)}`);
      if (!answer.character) throw new Error(`project file: body.character.text is a rig file, not a character`);
      ref.parsed = answer.character;
      return;
    }
    for (const c of loaded) {
      const bytes = new TextEncoder().encode(c.text);
      if ((ref.size === undefined || bytes.length === ref.size) && (await sha256(bytes)) === ref.sha256) {
        ref.text = c.text;
        ref.parsed = c.character;
        return;
      }
    }
    const size = ref.size === undefined ? "" : ` (${(ref.size / 1048576).toFixed(1)} MB)`;
    throw new Error(`project file: the character ${ref.name}${size} is not embedded and not loaded; load ${ref.name} (Load rig or character…), then open the project again`);
  }

  /**
   * Opens the project file `name` (its `text`): the work it holds replaces the page's (one undo
   * step). A bad file is one line on the chip and changes nothing.
   */
  async function open(name, text) {
    if (!history || restoring) return;
    try {
      let file;
      try {
        file = JSON.parse(text);
      } catch (e) {
        throw new Error(`project file: not JSON (${e.message})`);
      }
      const { snap, view, defaulted } = readProject(file, { defaults, rigs: act.rigs.shipped(), choices: choices() });
      if (snap.body.kind === "character") {
        await findCharacter(snap.body.character);
        // The skin saved is one of the character's (a file of another character's is refused).
        const skins = snap.body.character.parsed.skins || [];
        const skin = snap.character.skin;
        if (skin !== null && !skins.includes(skin)) throw new Error(`project file: character.skin = ${JSON.stringify(skin)} is not one of the character's skins (${skins.join(", ") || "none"})`);
      }
      if (snap.rig && snap.rig.pose_deg === null) delete snap.rig.pose_deg;
      amend();
      restore(snap, view);
      history.record(take(), `Open ${name}`);
      savedKey = workKey(history.present());
      act.showError(null);
      act.say(`opened ${name}${defaulted.length ? ` · defaulted: ${defaulted.join(", ")}` : ""}`);
      sync();
    } catch (e) {
      act.showError(new Notice(e.message));
    }
  }

  /** The values each list of the settings offers. */
  const choices = () => Object.fromEntries(settingFields().filter((el) => el.tagName === "SELECT").map((el) => [el.id, [...el.options].map((o) => o.value)]));

  // A setting changed by the reader: one step (after the page's own handler has read it).
  document.addEventListener("change", (ev) => {
    const el = ev.target;
    if (!el.id || !settingFields().includes(el)) return;
    edited(fieldLabel(el));
  });
  document.addEventListener("keydown", (ev) => {
    if (!(ev.ctrlKey || ev.metaKey) || ev.altKey) return;
    const key = ev.key.toLowerCase();
    if (key !== "z" && key !== "y") return;
    // A text field keeps its own undo.
    const el = ev.target;
    const textual = el && (el.isContentEditable || el.tagName === "TEXTAREA" || (el.tagName === "INPUT" && !["checkbox", "radio", "range", "button", "file"].includes(el.type)));
    if (textual) return;
    ev.preventDefault();
    step(key === "y" || ev.shiftKey ? "redo" : "undo");
  });
  $("undo").addEventListener("click", () => step("undo"));
  $("redo").addEventListener("click", () => step("redo"));
  $("save-project").addEventListener("click", save);
  $("open-project").addEventListener("click", () => $("project-file").click());
  $("project-file").addEventListener("change", async (ev) => {
    const file = ev.target.files[0];
    ev.target.value = "";
    if (file) open(file.name, await file.text());
  });
  window.addEventListener("beforeunload", (ev) => {
    if (!dirty()) return;
    ev.preventDefault();
    ev.returnValue = "";
  });

  return {
    start,
    edited,
    amend,
    undo: () => step("undo"),
    redo: () => step("redo"),
    save,
    open,
    /** Whether `text` is a project file (rigs.js routes a picked or dropped file by it). */
    isProject: isProjectText,
    dirty,
    sizes: () => (history ? history.sizes() : { undo: 0, redo: 0 }),
    restoring: () => restoring,
  };
}
