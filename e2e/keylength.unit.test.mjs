// The pure parts of the page's keys as an animator uses them (issue 44): the Length sent as the
// keys' `duration`, the keyed targets and bends a drag poses with, the clip's time under keys that
// run longer than it, and what *Export Spine JSON* says it does. No browser, no server.
// Run by .ci/run:  node --test e2e/keylength.unit.test.mjs
import { test } from "node:test";
import assert from "node:assert/strict";
import { bendsAt, characterAnimateRequest, deleteKey, keyRows, keyedTargets, keysDuration, lengthKeys, localRotation, moveKey, setEase, setRotationKey, tidy } from "../crates/ikarus-cli/src/serve/assets/keys.js";
import { clipTime, exportState, poseRequest } from "../crates/ikarus-cli/src/serve/assets/character.js";

const keys = {
  fps: 30,
  tracks: { foot: [{ time: 0, x: 1, y: 2 }, { time: 0.6, x: 3, y: 4 }], hand: [{ time: 0, x: 0, y: 0 }] },
  bends: { shin: [{ time: 0, bend: "ccw" }, { time: 0.3, bend: "cw" }] },
  pins: [],
};

test("the Length is sent as the keys' duration, on a frame and never before the last key", () => {
  assert.equal(lengthKeys(keys, 2).duration, 2);
  assert.equal(lengthKeys(keys, 0.2).duration, 0.6, "the keys run longer than the Length");
  assert.equal(lengthKeys(keys, 1.01).duration, 1, "on a frame");
  assert.equal(lengthKeys({ ...keys, fps: 24 }, 1.3).duration, 31 / 24);
  assert.equal(keys.duration, undefined, "the keys themselves unchanged");
  const req = characterAnimateRequest({ text: "T", animation: "walk" }, lengthKeys(keys, 2));
  assert.equal(req.keys.duration, 2);
  assert.equal(characterAnimateRequest({ text: "T" }, keys).keys.duration, undefined);
});

test("a drag over keys poses with every keyed target where the frame has it and the bends in force", () => {
  const bones = [
    { name: "foot", x: 5, y: 6 },
    { name: "hand", x: 7, y: 8 },
    { name: "head", x: 9, y: 9 },
  ];
  assert.deepEqual([...keyedTargets(keys, bones)], [
    ["foot", { x: 5, y: 6 }],
    ["hand", { x: 7, y: 8 }],
  ]);
  assert.deepEqual(bendsAt(keys, 0.2), { shin: "ccw" });
  assert.deepEqual(bendsAt(keys, 0.3), { shin: "cw" });
  assert.deepEqual(bendsAt(null, 0.3), {});
  const character = { clips: [{ name: "walk", duration: 0.5 }] };
  const req = poseRequest({ text: "T", character, animation: "walk", time: 0.7, targets: keyedTargets(keys, bones), ik: "runtime", bends: bendsAt(keys, 0.7) });
  assert.deepEqual(req, {
    rig: "T",
    animation: "walk",
    time: 0.7 % 0.5,
    targets: [
      { bone: "foot", x: 5, y: 6 },
      { bone: "hand", x: 7, y: 8 },
    ],
    bends: { shin: "cw" },
  });
  assert.equal(poseRequest({ text: "T", targets: new Map(), bends: {} }).bends, undefined);
});

test("the clip loops under keys that run longer than it", () => {
  const character = { clips: [{ name: "walk", duration: 0.8 }] };
  assert.equal(clipTime(character, "walk", 0.5), 0.5);
  assert.equal(clipTime(character, "walk", 0.8), 0.8);
  assert.equal(clipTime(character, "walk", 1.0), 1.0 % 0.8);
  assert.equal(clipTime(character, "none", 3), 3);
});

test("Export Spine JSON says what it exports, and why not for DragonBones", () => {
  const dragon = exportState({ format: "dragonbones" }, null);
  assert.deepEqual(dragon, { disabled: true, title: "The Spine export takes a Spine file; this is a DragonBones character" });
  assert.equal(exportState({ format: "dragonbones" }, lengthKeys(keys, 2)).disabled, true);
  const keyed = exportState({ format: "spine" }, lengthKeys(keys, 2));
  assert.equal(keyed.disabled, false);
  assert.match(keyed.title, /made of your 5 keys \(2\.00 s, the Length, at 30 fps/);
  assert.match(exportState({ format: "spine" }, null).title, /moving the targets from the setup pose/);
});

test("a bone turned by hand keys its local rotation at the playhead, as a row of its own", () => {
  let k = setRotationKey(null, "head", 0.3, 40, 10);
  assert.deepEqual(k.rotations.head, [
    { time: 0, angle_deg: 10, ease: "sine" },
    { time: 0.3, angle_deg: 40, ease: "sine" },
  ]);
  k = setRotationKey(k, "head", 0.31, 45, 0);
  assert.equal(k.rotations.head[1].angle_deg, 45, "the same frame: the key takes the angle");
  k = setEase(k, "head", 1, { kind: "linear" }, "rotation");
  assert.equal(k.rotations.head[1].ease, "linear");
  assert.equal(keysDuration(k), 0.3);
  assert.deepEqual(keyRows(k, ["root", "head"]).map((r) => [r.kind, r.bone]), [["rotation", "head"]]);
  assert.equal(moveKey(k, { kind: "rotation", bone: "head" }, 1, 0.5).keys.rotations.head[1].time, 0.5);
  assert.equal(tidy(deleteKey(k, { kind: "rotation", bone: "head" }, 0)), null, "its first key deleted: no keys");
  const req = characterAnimateRequest({ text: "T" }, lengthKeys(k, 1));
  assert.deepEqual(req.keys.rotations, k.rotations);
  assert.equal(req.keys.duration, 1);
});

test("a bone's local rotation from a pose's world rotations, in (-180, 180]", () => {
  const bones = [
    { name: "neck", rotation_deg: 170 },
    { name: "head", rotation_deg: -170 },
    { name: "root", rotation_deg: 30 },
  ];
  const parent = (n) => ({ head: "neck", neck: "root" })[n] ?? null;
  assert.equal(localRotation(bones, parent, "head"), 20);
  assert.equal(localRotation(bones, parent, "neck"), 140);
  assert.equal(localRotation(bones, parent, "root"), 30);
  assert.ok(Number.isNaN(localRotation(bones, parent, "tail")));
});
