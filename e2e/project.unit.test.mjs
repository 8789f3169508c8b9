// Unit tests of the playground's undo stack and project files (history.js, project.js; no
// browser, no server): a snapshot of a fake page's state and its file read back, the history's
// steps (undo, redo, the cap, a new edit dropping the redo steps), and the exact one-line
// messages of a file this page cannot read. Run by e2e/run and .ci/run:
//   node --test e2e/project.unit.test.mjs
import { test } from "node:test";
import assert from "node:assert/strict";
import { HISTORY_CAP, newHistory } from "../crates/ikarus-cli/src/serve/assets/history.js";
import { EMBED_BYTES, PROJECT_VERSION, isProjectText, projectFile, projectName, readProject, snapshot, workKey } from "../crates/ikarus-cli/src/serve/assets/project.js";

const PUPPET = { name: "puppet", base: [0, 0], bones: ["pelvis", "left_foot", "right_hand"].map((name, i) => ({ name, parent: i ? "pelvis" : null, length: 0.3, angle_deg: 0 })) };

const ARM = { name: "three", base: [0.5, -0.25], links: [{ length: 1, angle_deg: 10, limits_deg: [-90, 90], rate: 2 }, { length: 0.75, angle_deg: -20 }] };

const SETTINGS = { method: "dls", limits: true, "limit-mode": "clamp", restarts: "0", lambda: "0.1", frames: "60", "show-ghosts": true };

const KEYS = { fps: 30, tracks: { left_foot: [{ time: 0, x: 0.1, y: -0.9, ease: "sine" }, { time: 0.5, x: 0.3, y: -0.8, ease: "parent", k1: 0.2, k2: 0.8 }] }, bends: { left_foot: [{ time: 0, bend: "ccw" }] }, pins: ["pelvis"] };

/** A page's state with a rig shown, as main.js and rigs.js keep it. */
function rigState() {
  return {
    arm: structuredClone(ARM),
    pose_deg: [12.5, -33.25],
    goal: { x: 1.25, y: 0.5, angle_deg: 30 },
    via: [{ x: 0.1, y: 0.2 }],
    rig: { source: "rig:puppet", rig: PUPPET, goals: new Map([["right_hand", { x: 0.4, y: 1.1 }]]), pins: new Set(["left_foot"]), pose_deg: [90.1, -12.000000000000002, 33] },
    character: null,
    keys: structuredClone(KEYS),
    playback: { u: 0.375 },
  };
}

const page = { defaults: { arm: structuredClone(ARM), settings: SETTINGS }, rigs: new Map([["puppet", PUPPET]]), choices: { method: ["dls", "ccd"], "limit-mode": ["clamp", "project"] } };

/** A snapshot through its file and back: the text a download holds, parsed and read. */
const roundTrip = (snap, view) => readProject(JSON.parse(JSON.stringify(projectFile(snap, "ikarus 1.0.0", {}, view))), page);

test("a rig's work survives a project file bit for bit", () => {
  const snap = snapshot(rigState(), SETTINGS);
  assert.deepEqual(snap.body, { kind: "rig", rig: "puppet" });
  assert.deepEqual(snap.rig, { goals: [{ bone: "right_hand", x: 0.4, y: 1.1 }], pins: ["left_foot"], pose_deg: [90.1, -12.000000000000002, 33] });
  const file = projectFile(snap, "ikarus 1.0.0");
  assert.equal(file.ikarus_project, PROJECT_VERSION);
  assert.equal(file.saved_by, "ikarus 1.0.0");
  const { snap: back, defaulted } = roundTrip(snap);
  assert.deepEqual(defaulted, []);
  assert.deepEqual(back, snap);
  assert.equal(workKey(back), workKey(snap));
  assert.equal(projectName(snap), "puppet.ikarus.json");
});

test("the keys' Length, the playhead in seconds, Key mode and the camera survive a project file", () => {
  const snap = snapshot(rigState(), SETTINGS, { key_length: 3.5, playhead_s: 1.2333333333333334 });
  assert.equal(snap.key_length, 3.5);
  assert.equal(snap.playhead_s, 1.2333333333333334);
  assert.equal(snap.playhead, undefined, "no fraction any more");
  const view = { key_mode: true, camera: { zoom: 4.5, x: -0.125, y: 0.75 } };
  const file = projectFile(snap, "ikarus 1.0.0", {}, view);
  assert.equal(file.key_mode, true);
  assert.deepEqual(file.camera, view.camera);
  const { snap: back, view: viewBack, defaulted } = roundTrip(snap, view);
  assert.deepEqual(defaulted, []);
  assert.deepEqual(back, snap);
  assert.deepEqual(viewBack, view);
  // The view is not the work: two snapshots differ by their Length, never by a camera.
  assert.notEqual(workKey(snapshot(rigState(), SETTINGS, { key_length: 2 })), workKey(snap));
  // Without a view, Key mode off and the fitted camera are written.
  const plain = projectFile(snap, "ikarus 1.0.0");
  assert.deepEqual([plain.key_mode, plain.camera], [false, { zoom: 1, x: 0, y: 0 }]);
});

test("a file of the earlier shape (its playhead a fraction, no Length, Key mode or camera) opens with the defaults named", () => {
  const old = { ikarus_project: 1, saved_by: "ikarus 0.9.0", body: { kind: "rig", rig: "puppet" }, arm: ARM, pose_deg: [10, -20], goal: null, via: [], rig: { goals: [], pins: [], pose_deg: [90, 0, 0] }, character: null, keys: KEYS, settings: SETTINGS, playhead: 0.25 };
  const { snap, view, defaulted } = readProject(old, page);
  assert.deepEqual(defaulted, ["key_length", "key_mode", "camera"]);
  assert.equal(snap.playhead, 0.25, "the fraction kept, for the page to seek to");
  assert.equal(snap.playhead_s, undefined);
  assert.equal(snap.key_length, 2);
  assert.deepEqual(view, { key_mode: false, camera: { zoom: 1, x: 0, y: 0 } });
  assert.deepEqual(snap.keys, KEYS);
});

test("a snapshot is a copy: later edits of the state do not reach it", () => {
  const state = rigState();
  const snap = snapshot(state, SETTINGS);
  state.arm.links[0].length = 9;
  state.keys.tracks.left_foot[0].x = 9;
  state.rig.goals.set("left_foot", { x: 0, y: 0 });
  state.rig.pose_deg[0] = 9;
  assert.equal(snap.arm.links[0].length, 1);
  assert.equal(snap.keys.tracks.left_foot[0].x, 0.1);
  assert.equal(snap.rig.goals.length, 1);
  assert.equal(snap.rig.pose_deg[0], 90.1);
});

test("a character is embedded below the size limit and referenced above it", () => {
  const state = { ...rigState(), rig: null, character: { name: "spineboy.json", text: '{"skeleton":{}}', character: { format: "spine" }, animation: "walk", time: 0.25, ik: "ikarus", targets: new Map([["front-foot-target", { x: 10, y: -3 }]]), skin: "hero", physics: false } };
  const snap = snapshot(state, SETTINGS);
  assert.equal(snap.body.character.parsed, state.character.character, "the parse answer is held, not copied");
  const small = projectFile(snap, "ikarus", { size: 15, sha256: "ab" });
  assert.deepEqual(small.body, { kind: "character", character: { name: "spineboy.json", format: "spine", size: 15, sha256: "ab", text: '{"skeleton":{}}' } });
  const big = projectFile(snap, "ikarus", { size: EMBED_BYTES, sha256: "ab" });
  assert.equal(big.body.character.text, undefined);
  const { snap: back } = readProject(JSON.parse(JSON.stringify(small)), page);
  assert.deepEqual(back.character, { animation: "walk", time: 0.25, ik: "ikarus", targets: [{ bone: "front-foot-target", x: 10, y: -3 }], skin: "hero", physics: false });
  // A file saved before the skin and the physics switch were: the file's default skin, physics
  // on, and neither named as defaulted.
  const older = JSON.parse(JSON.stringify(small));
  delete older.character.skin;
  delete older.character.physics;
  const { snap: old, defaulted } = readProject(older, page);
  assert.deepEqual([old.character.skin, old.character.physics], [null, true]);
  assert.deepEqual(defaulted, []);
  for (const [field, value, why] of [["skin", 3, "is not a string"], ["physics", "off", "is not true or false"]]) {
    const bad = JSON.parse(JSON.stringify(small));
    bad.character[field] = value;
    assert.throws(() => readProject(bad, page), { message: `project file: character.${field} = ${JSON.stringify(value)} ${why}` });
  }
  assert.equal(back.body.character.text, '{"skeleton":{}}');
  assert.equal(projectName(snap), "spineboy.ikarus.json");
  // Two characters of one name are told apart by their text.
  const other = snapshot({ ...state, character: { ...state.character, text: '{"skeleton":{"x":1}}' } }, SETTINGS);
  assert.notEqual(workKey(other), workKey(snap));
  assert.equal(workKey(snapshot(state, SETTINGS)), workKey(snap));
  assert.throws(() => readProject({ ikarus_project: 1, body: { kind: "character", character: { name: "a.json" } } }, page), {
    message: 'project file: body.character = {"name":"a.json"} has neither text nor sha256: it cannot be found',
  });
});

test("an older file opens with the page's defaults and names them", () => {
  const { snap, defaulted } = readProject({ ikarus_project: 1, body: { kind: "arm" }, settings: { method: "ccd" } }, page);
  assert.deepEqual(defaulted, ["arm", "pose_deg", "goal", "via", "keys", "key_length", "settings.limits", "settings.limit-mode", "settings.restarts", "settings.lambda", "settings.frames", "settings.show-ghosts", "playhead_s", "key_mode", "camera"]);
  assert.deepEqual(snap.arm, ARM);
  assert.deepEqual(snap.pose_deg, [10, -20]);
  assert.equal(snap.settings.method, "ccd");
  assert.equal(snap.settings.limits, true);
  assert.equal(snap.keys, null);
});

test("a file this page cannot read says exactly why", () => {
  const bad = (file, message) => assert.throws(() => readProject(file, page), { message });
  bad({ ikarus_project: 99 }, "project file: version 99 is newer than this page reads (1); update ikarus");
  bad({ ikarus_project: "1" }, 'project file: ikarus_project = "1" is not a version number');
  bad([1], "project file: not a JSON object ([1])");
  bad({ ikarus_project: 1, keys: { tracks: { left_foot: [{ time: 0, x: 0, y: 0 }, { time: "x", x: 0, y: 0 }] } } }, 'project file: keys.tracks.left_foot[1].time = "x" is not a number');
  bad({ ikarus_project: 1, keys: { bends: { knee: [{ time: 0, bend: "up" }] } } }, 'project file: keys.bends.knee[0].bend = "up" is not one of ccw, cw');
  bad({ ikarus_project: 1, body: { kind: "rig", rig: "robot" } }, 'project file: body.rig = "robot" is not a shipped rig (puppet)');
  bad({ ikarus_project: 1, body: { kind: "rig", rig: "puppet" }, rig: { pins: ["tail"] } }, 'project file: rig.pins[0] = "tail" is not one of pelvis, left_foot, right_hand');
  bad({ ikarus_project: 1, body: { kind: "rig", rig: "puppet" }, rig: { pose_deg: [1, 2] } }, "project file: rig.pose_deg = [1,2] has 2 values, not 3");
  bad({ ikarus_project: 1, body: { kind: "ghost" } }, 'project file: body.kind = "ghost" is not one of arm, rig, character');
  bad({ ikarus_project: 1, arm: { links: [{ length: -1, angle_deg: 0 }] } }, "project file: arm.links[0].length = -1 is not above 0");
  bad({ ikarus_project: 1, settings: { limits: "yes" } }, 'project file: settings.limits = "yes" is not true or false');
  bad({ ikarus_project: 1, settings: { method: "magic" } }, 'project file: settings.method = "magic" is not one of dls, ccd');
  bad({ ikarus_project: 1, playhead: 2 }, "project file: playhead = 2 is not from 0 to 1");
  bad({ ikarus_project: 1, playhead_s: -1 }, "project file: playhead_s = -1 is below 0 seconds");
  bad({ ikarus_project: 1, key_length: 0 }, "project file: key_length = 0 is not from 0.1 to 60 seconds");
  bad({ ikarus_project: 1, key_length: "2" }, 'project file: key_length = "2" is not a number');
  bad({ ikarus_project: 1, key_mode: 1 }, "project file: key_mode = 1 is not true or false");
  bad({ ikarus_project: 1, camera: { zoom: 1000, x: 0, y: 0 } }, "project file: camera.zoom = 1000 is not from 0.05 to 200");
  bad({ ikarus_project: 1, camera: { zoom: 2, x: "a", y: 0 } }, 'project file: camera.x = "a" is not a number');
  bad({ ikarus_project: 1, camera: [1] }, "project file: camera = [1] is not an object");
});

test("only a JSON object with ikarus_project is a project (rigs and characters are not)", () => {
  assert.equal(isProjectText('{"ikarus_project": 1}'), true);
  assert.equal(isProjectText(' \n{"saved_by": "x", "ikarus_project": 99}'), true);
  assert.equal(isProjectText('{"skeleton": {"spine": "4.1"}, "note": "ikarus_project"}'), false);
  assert.equal(isProjectText('name = "ikarus_project"'), false);
  assert.equal(isProjectText('{"ikarus_project": 1'), false);
});

test("undo and redo walk the steps; a new edit drops the redo steps", () => {
  const h = newHistory({ n: 0 });
  assert.equal(h.undo(), null);
  assert.equal(h.record({ n: 0 }, "nothing"), false, "an edit that changes nothing is no step");
  h.record({ n: 1 }, "one");
  h.record({ n: 2 }, "two");
  assert.equal(h.undoLabel(), "two");
  assert.equal(h.undo().label, "two");
  assert.deepEqual(h.present(), { n: 1 });
  assert.equal(h.redoLabel(), "two");
  assert.equal(h.undo().label, "one");
  assert.deepEqual(h.present(), { n: 0 });
  assert.equal(h.undo(), null);
  assert.equal(h.redo().label, "one");
  assert.deepEqual(h.present(), { n: 1 });
  h.record({ n: 5 }, "five");
  assert.equal(h.redo(), null, "the new edit dropped the redo step");
  assert.deepEqual(h.sizes(), { undo: 2, redo: 0 });
  h.amend({ n: 6 });
  assert.equal(h.undo().label, "five");
  assert.equal(h.redo().label, "five");
  assert.deepEqual(h.present(), { n: 6 }, "redo comes back to the amended step");
});

test("the history keeps its cap of steps, at least 100", () => {
  assert.ok(HISTORY_CAP >= 100);
  const h = newHistory({ n: 0 });
  for (let n = 1; n <= HISTORY_CAP + 50; n++) h.record({ n }, `edit ${n}`);
  assert.deepEqual(h.sizes(), { undo: HISTORY_CAP, redo: 0 });
  let steps = 0;
  while (h.undo()) steps++;
  assert.equal(steps, HISTORY_CAP);
  assert.deepEqual(h.present(), { n: 50 }, "the oldest steps were forgotten");
  while (h.redo()) steps--;
  assert.equal(steps, 0);
  assert.deepEqual(h.present(), { n: HISTORY_CAP + 50 });
});
