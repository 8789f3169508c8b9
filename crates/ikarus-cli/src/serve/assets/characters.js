// A character on the page (a Spine or DragonBones skeleton, read by POST /api/rig/parse; rigs.js
// hands it over from *Load rig or character…* or a dropped file): posed by POST /api/pose (in
// the static build by the WebAssembly module's typed path, without JSON: api.pose), one request
// in flight and only the latest choices waiting (latest wins), from the setup pose, a
// clip of the file at a time the timeline plays (timeline.js's loadClip), and the IK targets the
// reader dragged (each stays where it was put while a clip plays), by Spine's rules or ikarus's
// solver. The Character fieldset lists the clips, the constraints left inactive, the switch
// between the two ways of solving, and *Export Spine JSON* (POST /api/animate: the file with one
// added animation moving the targets from the setup pose to where they are). The pure parts are
// character.js; the drawing is drawchar.js. It writes `state.character` (its fields: character.js's newCharacterState).

import * as api from "./api.js";
import { artRefused } from "./artload.js";
import { saveBlob } from "./files.js";
import { boneAt, characterRef, newCharacterState, characterSummary, solverLine, clipSeconds, exportName, exportRequest, exportState, handleNotes, handleAt, ikTargets, poseRequest, posedBox, surveyTimes, unionBox, unsupportedLines } from "./character.js";
import { showOptions, wireOptions } from "./charoptions.js";
import { bonesOnCanvas, handlesOnCanvas } from "./drawchar.js";
import { localRotation } from "./keys.js";
import { isDrag, toWorld } from "./view.js";

const $ = (id) => document.getElementById(id);

/**
 * Wires the Character fieldset and the character's pointer on `canvas`. `act` is
 * {forgetMotion(), timeline (timeline.js's), keyed (keyed.js's: a dragged target keyed in Key
 * mode; with keys the timeline plays them, and the export bakes them), requestDraw(),
 * showError(e), setStatus(s), say(text), edited(label) (an undo step)}. Returns {enter(name,
 * text, character), ensure(name, text, character), setWork(work), loaded(), resume(), leave(),
 * reset(), settled(), clipBack() (the clip on the timeline again), repose() (pose again: the art changed)}.
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
    const select = $("body-kind");
    let option = [...select.options].find((o) => o.value === "character");
    if (!option) {
      option = new Option("", "character");
      select.append(option);
    }
    option.textContent = `Character: ${c.name}`;
    select.value = "character";
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
    const hint = $("hint");
    hint.textContent = state.drawPath ? hint.dataset.drawing : hint.dataset.normal;
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
    pump();
  }

  async function pump() {
    const c = state.character;
    if (!c || c.busy) return;
    // A clip's survey goes first: the view is fitted to it before the clip is seen moving.
    const s = c.survey && c.survey.times.length ? c.survey : null;
    if (!s && !c.pending) return;
    c.busy = true;
    let req;
    if (s) {
      req = { ...characterRef(c), animation: s.name, time: s.times.shift(), targets: [] };
    } else {
      c.pending = false;
      // A drag over keys poses with the bends in force (keyed.js keeps them), never without keys.
      req = poseRequest({ ...c, bends: state.keys ? c.bends : null });
    }
    try {
      const answer = await api.pose(req);
      if (state.character === c && s) surveyed(c, s, answer);
      else if (state.character === c) apply(c, req, answer);
    } catch (e) {
      // Art the backend refuses (a region the atlas lacks): the character goes on as bones, the notice kept.
      if (state.character === c && artRefused(c, req, e)) act.showError(e);
      else if (state.character === c) {
        act.showError(e);
        act.setStatus("error");
      }
    }
    // One answer per displayed frame: the next request leaves on the next one.
    requestAnimationFrame(() => {
      c.busy = false;
      if (state.character === c) pump();
    });
  }

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

  // ---- The pointer -------------------------------------------------------------------------

  const local = (ev) => {
    const rect = canvas.getBoundingClientRect();
    return [ev.clientX - rect.left, ev.clientY - rect.top];
  };

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

  let press = null;

  /** Whether a drag on bone `name` turns it: no IK constraint moves it and it is no target (those are dragged). */
  const turnable = (c, name) => !!name && !c.ikBones.has(name) && !c.targetNames.includes(name);

  /** The pointer's direction from a bone's origin `o` (world), degrees. */
  const bearing = (o, ev) => {
    const [x, y] = toWorld(state.view, ...local(ev));
    return (Math.atan2(y - o[1], x - o[0]) * 180) / Math.PI;
  };

  canvas.addEventListener("pointerdown", (ev) => {
    const c = state.character;
    if (!c || !c.posed || ev.button !== 0 || act.keyed.bendPress(ev)) return;
    const name = handleUnder(ev);
    if (!name) {
      // A plain bone: turned about its origin by the drag (forward kinematics).
      const over = under(ev);
      const bone = turnable(c, over) && c.posed.find((b) => b.name === over);
      if (!bone) return;
      const start = c.turns.has(over) ? c.turns.get(over) : localRotation(c.posed, (n) => c.parentOf.get(n), over);
      press = { kind: "turn", x: ev.clientX, y: ev.clientY, name: over, origin: [bone.x, bone.y], a0: bearing([bone.x, bone.y], ev), start, dragging: false };
      canvas.setPointerCapture(ev.pointerId);
      return;
    }
    const bone = c.posed.find((b) => b.name === name);
    press = { kind: "target", x: ev.clientX, y: ev.clientY, name, from: bone ? [bone.x, bone.y] : null, dragging: false };
    canvas.setPointerCapture(ev.pointerId);
  });

  canvas.addEventListener("pointermove", (ev) => {
    const c = state.character;
    if (!c || !c.posed) return;
    if (!press) {
      // A bend handle (Key mode) first: ringed and named alone.
      const bend = act.keyed.hoverBend(ev);
      const hover = bend ? null : under(ev);
      const note = hover && c.notes.get(hover);
      const turns = !note && turnable(c, hover);
      canvas.style.cursor = bend ? "pointer" : note ? (note.inactive ? "not-allowed" : "grab") : turns ? "alias" : "";
      if (hover !== c.hover) {
        c.hover = hover;
        // A handle says what it drags (or why it moves nothing); a bone its name.
        canvas.title = note ? note.note : turns ? `${hover}: drag to turn it about its origin (a click lets a turned bone go)` : hover ? `${hover}: moved by an IK constraint; drag its target` : "";
        act.requestDraw();
      }
      return;
    }
    if (!press.dragging && isDrag(press, ev.clientX, ev.clientY)) {
      press.dragging = true;
      c.grabbed = press.name;
      canvas.style.cursor = "grabbing";
    }
    if (!press.dragging) return;
    if (press.kind === "turn") {
      const a = press.start + bearing(press.origin, ev) - press.a0;
      c.turns = new Map(c.turns).set(press.name, a - 360 * Math.ceil((a - 180) / 360));
      act.requestDraw();
      poseSoon();
      return;
    }
    const [x, y] = toWorld(state.view, ...local(ev));
    c.targets = new Map(c.targets).set(press.name, { x, y });
    act.requestDraw();
    poseSoon();
  });

  canvas.addEventListener("pointerup", () => {
    const c = state.character;
    if (!c || !press) return;
    const { name, dragging, from, kind, start } = press;
    press = null;
    c.grabbed = null;
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
      act.requestDraw();
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
    act.requestDraw();
  });

  canvas.addEventListener("pointerleave", () => {
    const c = state.character;
    if (!c || press || !c.hover) return;
    c.hover = null;
    canvas.style.cursor = "";
    act.requestDraw();
  });

  canvas.addEventListener("pointercancel", () => {
    if (!state.character) return;
    press = null;
    state.character.grabbed = null;
    act.requestDraw();
  });

  canvas.addEventListener("keydown", (ev) => {
    if (state.character && ev.key === "Escape") {
      ev.preventDefault();
      clearTargets();
      act.edited("Clear targets");
    }
  });

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

  return { enter, ensure, setWork, loaded, resume, leave, reset, settled, clipBack, repose: poseSoon };
}
