// A character on the page (a Spine or DragonBones skeleton, read by POST /api/rig/parse; rigs.js
// hands it over from *Load rig or character…* or a dropped file): posed by POST /api/pose (in
// the static build by the WebAssembly module's typed path, without JSON: api.pose), one request
// in flight and only the latest choices waiting (latest wins), from the setup pose, a
// clip of the file at a time the timeline plays (timeline.js's loadClip), and the IK targets the
// reader dragged (each stays where it was put while a clip plays), by Spine's rules or ikarus's
// solver. The Character fieldset lists the clips, the constraints left inactive, the switch
// between the two ways of solving, and *Export Spine JSON* (POST /api/animate: the file with one
// added animation moving the targets from the setup pose to where they are). The pure parts are
// character.js; the drawing is drawchar.js; the pointer's handlers and the one request in flight
// are bodyctl.js's, shared with rigs.js. It writes `state.character` (its fields: character.js's newCharacterState).

import * as api from "./api.js";
import { artRefused } from "./artload.js";
import { armHint, canvasPoint, listBody, sendLatest } from "./bodyctl.js";
import { saveBlob } from "./files.js";
import { boneAt, characterRef, newCharacterState, characterSummary, solverLine, clipSeconds, exportName, exportRequest, exportState, handleNotes, handleAt, ikTargets, poseRequest, posedBox, surveyTimes, unionBox, unsupportedLines } from "./character.js";
import { showOptions, wireOptions } from "./charoptions.js";
import { bonesOnCanvas, handlesOnCanvas } from "./drawchar.js";
import { localRotation } from "./keys.js";
import { toWorld } from "./view.js";

const $ = (id) => document.getElementById(id);

/**
 * Wires the Character fieldset and the character's pointer on `canvas`. `act` is
 * {forgetMotion(), timeline (timeline.js's), keyed (keyed.js's: a dragged target keyed in Key
 * mode; with keys the timeline plays them, and the export bakes them), requestDraw(),
 * showError(e), setStatus(s), say(text), edited(label) (an undo step)}. Returns {enter(name,
 * text, character), ensure(name, text, character), setWork(work), loaded(), resume(), leave(),
 * reset(), settled(), clipBack() (the clip on the timeline again), repose() (pose again: the art changed),
 * pointer (the character's part of bodyctl.js's wireBodyPointer)}.
 */
export function wireCharacters(state, canvas, act) {
  /** The last character loaded: the Body list's "Character: …" shows it again. */
  let last = null;

  function say() {
    const c = state.character;
    const when = c.animation ? `${c.animation} ${c.time.toFixed(2)} s` : "setup pose";
    const targets = c.targets.size ? ` · ${c.targets.size} target${c.targets.size === 1 ? "" : "s"} placed` : "";
    act.say(`${characterSummary(c.name, c.character)} · ${when}${targets} · ${solverLine(c.ikReport)}`);
  }

  /** Shows the character `c` on the canvas (its clips, inactive constraints, the switch). */
  function show(c) {
    act.forgetMotion();
    state.character = c;
    last = c;
    act.keyed.enter();
    document.body.classList.add("character");
    $("hint").textContent = $("hint").dataset.character;
    listBody("character", `Character: ${c.name}`);
    $("body-kind").value = "character";
    const list = $("character-animation");
    list.replaceChildren(new Option("Setup pose", ""), ...(c.character.clips || []).map((k) => new Option(`${k.name} (${k.duration.toFixed(2)} s)`, k.name)));
    list.value = c.animation;
    for (const radio of document.querySelectorAll('input[name="character-ik"]')) radio.checked = radio.value === c.ik;
    showOptions(c);
    const lines = unsupportedLines(c.character);
    $("character-unsupported").replaceChildren(...lines.map((l) => Object.assign(document.createElement("li"), { textContent: l })));
    $("character-unsupported-box").hidden = lines.length === 0;
    act.showError(null);
    act.setStatus("ready");
    playClip(c);
    poseSoon();
    act.keyed.resume();
  }

  /** A character file read by /api/rig/parse: shown from its setup pose. */
  function enter(name, text, character) {
    show(newCharacterState(name, text, character));
  }

  /**
   * The character `name` (its `text`, read as `character`) on the canvas: the one shown or the
   * last one stays as it is when it is the same file, else it is shown from its setup pose.
   */
  function ensure(name, text, character) {
    const same = (c) => c && c.name === name && c.text === text;
    if (same(state.character)) return;
    if (same(last)) show(last);
    else enter(name, text, character);
  }

  /**
   * The character's work put back (an undo, a project opened): the clip `animation` at `time`,
   * the IK switch `ik`, the placed `targets` [{bone, x, y}], the skin (null: the file's
   * default) and the physics switch (a snapshot without them: the default skin, physics on).
   */
  function setWork({ animation, time, ik, targets, skin = null, physics = true }) {
    const c = state.character;
    if (!c) return;
    c.ik = ik;
    c.skin = skin;
    c.physics = physics;
    showOptions(c);
    for (const radio of document.querySelectorAll('input[name="character-ik"]')) radio.checked = radio.value === ik;
    c.targets = new Map(targets.map((t) => [t.bone, { x: t.x, y: t.y }]));
    const known = animation === "" || (c.character.clips || []).some((k) => k.name === animation);
    $("character-animation").value = known ? animation : "";
    if (c.animation !== animation) choose(known ? animation : "");
    c.time = time;
    playClip(c);
    poseSoon();
  }

  /** The last character loaded (shown or not), or null. */
  const loaded = () => last;

  /** The last character again (the Body list's "Character: …"), as it was left. */
  function resume() {
    if (last && state.character !== last) show(last);
  }

  /** The arm or a rig takes the canvas: the character's controls step aside (it is kept for resume). */
  function leave() {
    if (!state.character) return;
    // Its keys kept with it (keyed.js), for its return (show).
    state.character = null;
    act.keyed.leave();
    document.body.classList.remove("character");
    canvas.style.cursor = "";
    armHint(state);
    act.forgetMotion();
    act.requestDraw();
  }

  /** The clip chosen onto the timeline (paused at its time), or none for the setup pose. */
  function playClip(c) {
    // With keys the timeline plays them, over the clip.
    if (state.keys) {
      act.keyed.clipChanged();
      return;
    }
    const seconds = clipSeconds(c.character, c.animation);
    if (!c.animation || !(seconds > 0)) {
      act.timeline.unload();
      return;
    }
    // Loading shows the clip's start: a character shown again goes back to its time after.
    const at = c.time;
    act.timeline.loadClip({
      seconds,
      show: (t) => {
        if (state.character !== c) return;
        c.time = t;
        poseSoon();
      },
    });
    if (at > 0) act.timeline.seek(at / seconds);
  }

  function choose(name) {
    const c = state.character;
    if (!c) return;
    c.animation = name;
    c.time = 0;
    // The clip's poses are surveyed first (in the one line of requests), so that the view fits them.
    const seconds = clipSeconds(c.character, name);
    if (name && !c.clipBoxes.has(name)) c.survey = { name, times: seconds > 0 ? surveyTimes(seconds) : [0], box: null };
    playClip(c);
    poseSoon();
  }

  // ---- Posing ------------------------------------------------------------------------------

  function poseSoon() {
    const c = state.character;
    if (!c) return;
    c.pending = true;
    sendLatest(poses);
  }

  /**
   * The character's poses, one in flight (bodyctl.js's sendLatest): a clip's survey goes first
   * (the view is fitted to it before the clip is seen moving), then the latest choices.
   */
  const poses = {
    shown: () => state.character,
    next(c) {
      const s = c.survey && c.survey.times.length ? c.survey : null;
      if (s) return { s, req: { ...characterRef(c), animation: s.name, time: s.times.shift(), targets: [] } };
      if (!c.pending) return null;
      c.pending = false;
      // A drag over keys poses with the bends in force (keyed.js keeps them), never without keys.
      return { s: null, req: poseRequest({ ...c, bends: state.keys ? c.bends : null }) };
    },
    send: ({ req }) => api.pose(req),
    done: (c, { s, req }, answer) => (s ? surveyed(c, s, answer) : apply(c, req, answer)),
    failed(c, { req }, e) {
      // Art the backend refuses (a region the atlas lacks): the character goes on as bones, the notice kept.
      const refused = artRefused(c, req, e);
      act.showError(e);
      if (!refused) act.setStatus("error");
    },
  };

  /** A pose of the clip's survey: its box grows; the last one gives the view its box. */
  function surveyed(c, s, answer) {
    s.box = unionBox(s.box, posedBox(answer.bones));
    if (s.times.length || c.survey !== s) return;
    c.clipBoxes.set(s.name, s.box);
    c.survey = null;
    act.requestDraw();
  }

  function apply(c, req, answer) {
    c.posed = answer.bones;
    c.art = answer.art || null;
    c.artOf = answer.bones;
    c.ikReport = answer.ik || null;
    // The view fits the first pose, the setup pose, and stays.
    if (!c.box) c.box = posedBox(answer.bones);
    c.request = req;
    c.poses++;
    act.showError(c.artNotice ? new api.Notice(c.artNotice) : null);
    if (document.body.dataset.status === "error") act.setStatus("ready");
    say();
    act.requestDraw();
  }

  /** Whether no pose is in flight or waiting (for tests and scripts). */
  const settled = () => {
    const c = state.character;
    return !!c && !c.busy && !c.pending && !(c.survey && c.survey.times.length);
  };

  function clearTargets() {
    const c = state.character;
    if (!c) return;
    c.targets = new Map();
    c.turns = new Map();
    poseSoon();
  }

  /** The setup pose: no clip, no targets (the switch stays). */
  function reset() {
    const c = state.character;
    if (!c) return;
    c.targets = new Map();
    c.turns = new Map();
    $("character-animation").value = "";
    choose("");
  }

  async function exportSpine() {
    const c = state.character;
    if (!c || exportState(c.character, null).disabled) return;
    // The keys when there are, else the targets from the setup pose to where they were put.
    const keyed = act.keyed.spineRequest();
    if (!keyed && c.targets.size === 0) {
      act.showError(new api.Notice("Drag a target first: the export moves the targets from the setup pose to where you put them (or key them in Key mode)"));
      return;
    }
    const button = $("export-spine");
    button.disabled = true;
    try {
      const text = await api.postText("/api/animate", JSON.stringify(keyed || exportRequest(c)), "application/json");
      saveBlob(new Blob([text], { type: "application/json" }), exportName(c.name));
      act.showError(null);
    } catch (e) {
      act.showError(e);
    } finally {
      button.disabled = exportState(c.character, null).disabled;
    }
  }

  // ---- The pointer (bodyctl.js's wireBodyPointer) -----------------------------------------

  const local = (ev) => canvasPoint(canvas, ev);

  /** The target whose handle is under the event, or null. */
  function handleUnder(ev) {
    return handleAt(handlesOnCanvas(state.view, state.character), ...local(ev));
  }

  /** What the pointer names: a target's handle first, else the bone under it, else null. */
  function under(ev) {
    const c = state.character;
    const h = handleUnder(ev);
    if (h) return h;
    const i = boneAt(bonesOnCanvas(state.view, c), ...local(ev));
    return i < 0 ? null : c.character.bones[i].name;
  }

  /** Whether a drag on bone `name` turns it: no IK constraint moves it and it is no target (those are dragged). */
  const turnable = (c, name) => !!name && !c.ikBones.has(name) && !c.targetNames.includes(name);

  /** The pointer's direction from a bone's origin `o` (world), degrees. */
  const bearing = (o, ev) => {
    const [x, y] = toWorld(state.view, ...local(ev));
    return (Math.atan2(y - o[1], x - o[0]) * 180) / Math.PI;
  };

  /**
   * The character's part of the canvas's pointer: a press on an IK target's handle drags the
   * target, one on a bone no constraint moves turns it about its origin; a click lets either go.
   */
  const pointer = {
    shown: () => state.character,
    ready: (c) => !!c.posed,
    grab(ev, c) {
      const name = handleUnder(ev);
      if (!name) {
        // A plain bone: turned about its origin by the drag (forward kinematics).
        const over = under(ev);
        const bone = turnable(c, over) && c.posed.find((b) => b.name === over);
        if (!bone) return null;
        const start = c.turns.has(over) ? c.turns.get(over) : localRotation(c.posed, (n) => c.parentOf.get(n), over);
        return { kind: "turn", name: over, origin: [bone.x, bone.y], a0: bearing([bone.x, bone.y], ev), start };
      }
      const bone = c.posed.find((b) => b.name === name);
      return { kind: "target", name, from: bone ? [bone.x, bone.y] : null };
    },
    under: (ev) => under(ev),
    cursor(name, c) {
      const note = name && c.notes.get(name);
      return note ? (note.inactive ? "not-allowed" : "grab") : turnable(c, name) ? "alias" : "";
    },
    hovered(name, c) {
      // A handle says what it drags (or why it moves nothing); a bone its name.
      const note = name && c.notes.get(name);
      const turns = !note && turnable(c, name);
      canvas.title = note ? note.note : turns ? `${name}: drag to turn it about its origin (a click lets a turned bone go)` : name ? `${name}: moved by an IK constraint; drag its target` : "";
    },
    drag(press, ev, c) {
      if (press.kind === "turn") {
        const a = press.start + bearing(press.origin, ev) - press.a0;
        c.turns = new Map(c.turns).set(press.name, a - 360 * Math.ceil((a - 180) / 360));
      } else {
        const [x, y] = toWorld(state.view, ...local(ev));
        c.targets = new Map(c.targets).set(press.name, { x, y });
      }
      act.requestDraw();
      poseSoon();
    },
    release({ name, dragging, from, kind, start }, ev, c) {
      if (kind === "turn") {
        if (dragging) {
          act.keyed.turnEnded(name, c.turns.get(name), start);
          act.edited(`Turn ${name}`);
        } else if (c.turns.has(name)) {
          // A click on a turned bone lets it go: the clip turns it again.
          c.turns = new Map(c.turns);
          c.turns.delete(name);
          poseSoon();
          act.edited(`Let ${name} go`);
        }
        canvas.style.cursor = "";
        return;
      }
      if (dragging) act.keyed.dragEnded(name, c.targets.get(name), from);
      canvas.style.cursor = "grab";
      // A click (no drag) on a placed target lets it go: the clip and the constraints move it again.
      if (!dragging && c.targets.has(name)) {
        c.targets = new Map(c.targets);
        c.targets.delete(name);
        poseSoon();
        act.edited(`Let ${name} go`);
      }
      if (dragging) act.edited(`Move ${name} target`);
    },
    clear: clearTargets,
    clearLabel: "Clear targets",
  };

  $("character-animation").addEventListener("change", (ev) => {
    choose(ev.target.value);
    act.edited(`Animation: ${ev.target.value || "setup pose"}`);
  });
  for (const radio of document.querySelectorAll('input[name="character-ik"]')) {
    radio.addEventListener("change", (ev) => {
      if (!state.character || !ev.target.checked) return;
      state.character.ik = ev.target.value;
      if (state.keys) act.keyed.resolve();
      else poseSoon();
      act.edited(`IK by ${ev.target.value === "ikarus" ? "ikarus's solver" : "Spine's rules"}`);
    });
  }
  $("clear-targets").addEventListener("click", () => {
    clearTargets();
    act.edited("Clear targets");
  });
  $("export-spine").addEventListener("click", exportSpine);
  wireOptions(state, () => (state.keys ? act.keyed.resolve() : poseSoon()), act);

  const clipBack = () => state.character && playClip(state.character);

  return { enter, ensure, setWork, loaded, resume, leave, reset, settled, clipBack, repose: poseSoon, pointer };
}
