// Unit tests of the playground's keys module (keys.js; no browser, no server): frames and
// snapping, the first-key rule, moving, deleting and copying keys, eases, bends and pins, the
// /api/animate request of a rig's keys, the frame shown at a time, the two-bone limbs with their
// bend handles, and the rows' geometry (drawkeys.js). Run by e2e/run and .ci/run:
//   node --test e2e/keys.unit.test.mjs
import { test } from "node:test";
import assert from "node:assert/strict";
import {
  armAnimateRequest,
  armBones,
  bendAt,
  characterAnimateRequest,
  characterMotion,
  deleteKey,
  emptyKeys,
  frameAt,
  keyedBranch,
  keyRows,
  keysDuration,
  moveKey,
  pasteKey,
  rigAnimateRequest,
  rigFramesCsv,
  rigMotion,
  rustNumber,
  setBend,
  setEase,
  setKey,
  sideOf,
  snapTime,
  tidy,
  togglePinKey,
} from "../crates/ikarus-cli/src/serve/assets/keys.js";
import { bendAllowed, bendHandleAt, bendHandles, bendLimbs, characterBendHandles } from "../crates/ikarus-cli/src/serve/assets/bendhandles.js";
import { pickKey, rowAxis } from "../crates/ikarus-cli/src/serve/assets/drawkeys.js";
import { bodyForward } from "../crates/ikarus-cli/src/serve/assets/body.js";

/** A leg (thigh, shin, foot) and a two-bone arm (upper, lower) beside a head on the hip. */
const RIG = {
  name: "test",
  base: [0, 0],
  bones: [
    { name: "hip", length: 0.1, angle_deg: 90 },
    { name: "thigh", parent: null, length: 0.5, angle_deg: -90, limits_deg: [-120, 30] },
    { name: "shin", parent: "thigh", length: 0.5, angle_deg: -10, limits_deg: [-150, 0] },
    { name: "foot", parent: "shin", length: 0.2, angle_deg: 90 },
    { name: "upper", parent: "hip", length: 0.3, angle_deg: -170 },
    { name: "lower", parent: "upper", length: 0.3, angle_deg: 20 },
    { name: "head", parent: "hip", length: 0.2, angle_deg: 0 },
  ],
};

test("times snap to the nearest frame as k / fps, never below 0", () => {
  assert.equal(snapTime(0.51, 30), 15 / 30);
  assert.equal(snapTime(0.5, 30), 0.5);
  assert.equal(snapTime(1 / 3, 30), 10 / 30);
  assert.equal(snapTime(-0.2, 30), 0);
  assert.equal(snapTime(0.016, 30), 0);
  assert.equal(snapTime(0.017, 30), 1 / 30);
});

test("the first key of a track away from 0 also keys the bone's current place at 0", () => {
  const k = setKey(null, "foot", 0.52, 1, 2, [0.1, -0.9]);
  assert.deepEqual(k.tracks.foot, [
    { time: 0, x: 0.1, y: -0.9, ease: "sine" },
    { time: 16 / 30, x: 1, y: 2, ease: "sine" },
  ]);
  assert.equal(k.fps, 30);
  // At 0 the one key is the one set.
  const at0 = setKey(null, "foot", 0.01, 3, 4, [0.1, -0.9]);
  assert.deepEqual(at0.tracks.foot, [{ time: 0, x: 3, y: 4, ease: "sine" }]);
});

test("a key on a keyed frame takes the new target and keeps its ease; a new one takes the ease before it", () => {
  let k = setKey(null, "foot", 0, 0, 0);
  k = setEase(k, "foot", 0, { kind: "parent", k1: 0.2, k2: 0.8 });
  k = setKey(k, "foot", 1, 1, 1);
  assert.deepEqual(k.tracks.foot[1], { time: 1, x: 1, y: 1, ease: "parent", k1: 0.2, k2: 0.8 });
  k = setKey(k, "foot", 0.99, 5, 6);
  assert.equal(k.tracks.foot.length, 2, "0.99 s is frame 30: the key at 1 s");
  assert.deepEqual(k.tracks.foot[1], { time: 1, x: 5, y: 6, ease: "parent", k1: 0.2, k2: 0.8 });
  k = setKey(k, "foot", 0.5, 2, 2);
  assert.deepEqual(
    k.tracks.foot.map((q) => q.time),
    [0, 0.5, 1],
  );
  // Back to sine drops k1 and k2.
  k = setEase(k, "foot", 1, { kind: "sine", k1: 0.2, k2: 0.8 });
  assert.deepEqual(k.tracks.foot[1], { time: 0.5, x: 2, y: 2, ease: "sine" });
});

test("edits leave the keys they were given as they were (undo keeps them)", () => {
  const a = setKey(null, "foot", 0, 0, 0);
  const frozen = JSON.stringify(a);
  setKey(a, "foot", 1, 1, 1);
  moveKey(a, { kind: "track", bone: "foot" }, 0, 1);
  deleteKey(a, { kind: "track", bone: "foot" }, 0);
  togglePinKey(a, "foot");
  assert.equal(JSON.stringify(a), frozen);
});

test("a key moves snapped to frames, never onto or past its neighbours, the first never off 0", () => {
  let k = emptyKeys();
  for (const [t, x] of [
    [0, 0],
    [0.5, 1],
    [1, 2],
  ])
    k = setKey(k, "foot", t, x, 0);
  const row = { kind: "track", bone: "foot" };
  assert.equal(moveKey(k, row, 1, 0.71).time, 21 / 30);
  assert.equal(moveKey(k, row, 1, 5).time, 29 / 30, "stops a frame before the next key");
  assert.equal(moveKey(k, row, 1, -1).time, 1 / 30, "stops a frame after the previous key");
  assert.equal(moveKey(k, row, 0, 0.4).time, 0, "the first key stays at 0");
  assert.equal(moveKey(k, row, 2, 7).time, 7, "the last key may go later");
  assert.deepEqual(
    moveKey(k, row, 1, 0.7).keys.tracks.foot.map((q) => q.x),
    [0, 1, 2],
  );
  assert.equal(keysDuration(moveKey(k, row, 2, 3).keys), 3);
});

test("deleting a key; deleting a track's first key deletes the track", () => {
  let k = setKey(setKey(null, "foot", 0, 0, 0), "foot", 1, 1, 1);
  k = setKey(k, "lower", 0, 5, 5);
  const row = { kind: "track", bone: "foot" };
  assert.deepEqual(deleteKey(k, row, 1).tracks.foot.length, 1);
  const gone = deleteKey(k, row, 0);
  assert.equal(gone.tracks.foot, undefined);
  assert.ok(gone.tracks.lower);
  assert.equal(tidy(deleteKey(gone, { kind: "track", bone: "lower" }, 0)), null, "nothing keyed: null");
});

test("a copied key pastes at the playhead, replacing one on that frame; onto a new track at 0", () => {
  let k = setKey(setKey(null, "foot", 0, 0, 0, null), "foot", 1, 1, 1);
  k = setEase(k, "foot", 1, { kind: "linear" });
  const row = { kind: "track", bone: "foot" };
  const key = k.tracks.foot[1];
  const p = pasteKey(k, row, key, 2.01);
  assert.deepEqual(p.tracks.foot[2], { time: 2, x: 1, y: 1, ease: "linear" });
  const q = pasteKey(k, row, k.tracks.foot[0], 1);
  assert.deepEqual(q.tracks.foot[1], { time: 1, x: 0, y: 0, ease: "sine" });
  const other = pasteKey(k, { kind: "track", bone: "lower" }, key, 1.5);
  assert.deepEqual(other.tracks.lower, [{ time: 0, x: 1, y: 1, ease: "linear" }]);
});

test("bends are step keys: the first away from 0 holds the side it had at 0", () => {
  let k = setKey(null, "foot", 0, 0, 0);
  k = setBend(k, "shin", 0.5, "ccw", "cw");
  assert.deepEqual(k.bends.shin, [
    { time: 0, bend: "cw" },
    { time: 0.5, bend: "ccw" },
  ]);
  assert.equal(bendAt(k, "shin", 0.2), "cw");
  assert.equal(bendAt(k, "shin", 0.5), "ccw");
  assert.equal(bendAt(k, "shin", 2), "ccw");
  assert.equal(bendAt(k, "thigh", 2), null);
  k = setBend(k, "shin", 0.5, "cw", "cw");
  assert.equal(k.bends.shin.length, 2, "the same frame keyed again");
  assert.equal(sideOf(-5), "cw");
  assert.equal(sideOf(5), "ccw");
  assert.equal(sideOf(355), "cw");
  assert.equal(keysDuration(setBend(k, "shin", 3, "ccw", "cw")), 3);
});

test("a pin is a row of its own, and drops the bone's track; a key unpins", () => {
  let k = setKey(null, "foot", 0, 0, 0);
  k = togglePinKey(k, "foot");
  assert.deepEqual(k.pins, ["foot"]);
  assert.equal(k.tracks.foot, undefined);
  k = setKey(k, "foot", 0, 1, 1);
  assert.deepEqual(k.pins, []);
  k = togglePinKey(togglePinKey(k, "lower"), "lower");
  assert.deepEqual(k.pins, []);
});

test("the rows: tracks, then bends, then pins, each in bone order", () => {
  let k = setKey(null, "lower", 0, 0, 0);
  k = setKey(k, "foot", 0, 0, 0);
  k = setBend(k, "shin", 0, "ccw", "cw");
  k = togglePinKey(k, "upper");
  const rows = keyRows(
    k,
    RIG.bones.map((b) => b.name),
  );
  assert.deepEqual(
    rows.map((r) => `${r.kind} ${r.bone}`),
    ["track foot", "track lower", "bend shin", "pin upper"],
  );
  assert.deepEqual(keyRows(null, []), []);
});

test("the request: the rig as sent, the keys as they are, the options without rates", () => {
  const keys = setKey(null, "foot", 0, 0.1, -0.9);
  const req = rigAnimateRequest(RIG, keys, { method: "dls", limits: true, rates: [1, 2] });
  assert.deepEqual(req.keys, keys);
  assert.deepEqual(req.options, { method: "dls", limits: true });
  assert.equal(req.format, undefined, "a rig's answer is JSON");
  assert.equal(req.rig.bones.length, RIG.bones.length);
  assert.equal(req.rig.bones[2].parent, "thigh");
  assert.deepEqual(req.rig.bones[2].limits_deg, [-150, 0]);
});

test("the frame shown at t is frame round(t·fps), within the frames; the pose in bone order", () => {
  const answer = {
    fps: 10,
    duration: 0.2,
    frames: [0, 1, 2].map((i) => ({ time: i / 10, angles_deg: { thigh: -90 + i, shin: -10 - i }, joints: {}, targets: {} })),
  };
  const m = rigMotion(RIG, answer);
  assert.equal(m.frames.length, 3);
  assert.deepEqual(m.frames[1].pose, [90, -89, -11, 90, -170, 20, 0]);
  assert.equal(frameAt(m, 0.149), m.frames[1]);
  assert.equal(frameAt(m, 0.15), m.frames[2]);
  assert.equal(frameAt(m, 9), m.frames[2]);
  assert.equal(frameAt(m, 0), m.frames[0]);
  assert.equal(frameAt(null, 0), null);
});

test("two-bone limbs: the knee above a foot, the joint of a two-bone arm", () => {
  assert.deepEqual(bendLimbs(RIG), [
    { bone: "shin", upper: "thigh", end: "foot" },
    { bone: "lower", upper: "upper", end: "lower" },
  ]);
  // A root with two children is no limb's upper bone.
  const fork = { bones: [{ name: "a", length: 1, angle_deg: 0 }, { name: "b", parent: "a", length: 1, angle_deg: 0 }, { name: "c", parent: "a", length: 1, angle_deg: 0 }] };
  assert.deepEqual(bendLimbs(fork), []);
});

test("a bend handle sits beside the middle joint on the side it bends, and is picked exactly there", () => {
  const toCanvas = (x, y) => [200 + 100 * x, 200 - 100 * y];
  const pose = RIG.bones.map((b) => b.angle_deg);
  const hs = bendHandles(RIG, pose, toCanvas);
  const knee = hs.find((h) => h.bone === "shin");
  const fk = bodyForward(RIG, pose);
  assert.deepEqual(knee.joint, toCanvas(...fk.starts[2]));
  assert.equal(knee.side, "cw");
  // The handle is on the knee's side of the hip–ankle line.
  const hip = toCanvas(...fk.starts[1]);
  const ankle = toCanvas(...fk.tips[2]);
  const cross = (p) => (ankle[0] - hip[0]) * (p[1] - hip[1]) - (ankle[1] - hip[1]) * (p[0] - hip[0]);
  assert.equal(Math.sign(cross(knee.at)), Math.sign(cross(knee.joint)));
  assert.ok(Math.abs(Math.hypot(knee.at[0] - knee.joint[0], knee.at[1] - knee.joint[1]) - 18) < 1e-9);
  assert.equal(bendHandleAt(hs, knee.at[0] + 5, knee.at[1]), "shin");
  assert.equal(bendHandleAt(hs, knee.at[0] + 9, knee.at[1]), null);
  // Flipped, the handle goes to the other side.
  const flipped = pose.slice();
  flipped[2] = 10;
  const k2 = bendHandles(RIG, flipped, toCanvas).find((h) => h.bone === "shin");
  const f2 = bodyForward(RIG, flipped);
  const a2 = toCanvas(...f2.tips[2]);
  const cross2 = (p) => (a2[0] - hip[0]) * (p[1] - hip[1]) - (a2[1] - hip[1]) * (p[0] - hip[0]);
  assert.equal(k2.side, "ccw");
  assert.equal(Math.sign(cross2(k2.at)), -Math.sign(cross(knee.at)));
});

test("a bend is allowed only where the limits reach that side (with limits on)", () => {
  const shin = RIG.bones[2];
  assert.equal(bendAllowed(shin, "ccw", true), false);
  assert.equal(bendAllowed(shin, "cw", true), true);
  assert.equal(bendAllowed(shin, "ccw", false), true);
  assert.equal(bendAllowed(RIG.bones[5], "ccw", true), true);
});

test("the rows' axis and picking: a key within 7 pixels, else the time under the pointer", () => {
  const axis = rowAxis(528, 2);
  assert.equal(axis.x(0), 128);
  assert.equal(axis.x(2), 518);
  assert.equal(axis.t(323), 1);
  assert.equal(axis.t(0), 0);
  assert.equal(axis.t(9999), 2);
  const k = setKey(setKey(null, "foot", 0, 0, 0), "foot", 1, 1, 1);
  const rows = keyRows(k, ["foot"]);
  assert.deepEqual(pickKey(rows, axis, 329, 9).index, 1);
  const miss = pickKey(rows, axis, 340, 9);
  assert.equal(miss.index, -1);
  assert.ok(Math.abs(miss.t - ((340 - 128) / 390) * 2) < 1e-12);
  assert.equal(pickKey(rows, axis, 329, 40), null, "below the rows");
});

test("numbers as Rust's {:?} writes them, and the CSV of `animate --keys --format csv`", () => {
  assert.equal(rustNumber(1), "1.0");
  assert.equal(rustNumber(-90), "-90.0");
  assert.equal(rustNumber(0), "0.0");
  assert.equal(rustNumber(0.1), "0.1");
  assert.equal(rustNumber(1 / 30), "0.03333333333333333");
  assert.equal(rustNumber(1.5e-5), "1.5e-5");
  assert.equal(rustNumber(0.0001), "0.0001");
  assert.equal(rustNumber(2e16), "2e16");
  const rig = { bones: [{ name: "a", length: 1, angle_deg: 0 }, { name: "b", parent: "a", length: 1, angle_deg: 5, joint: "prismatic" }] };
  const answer = { frames: [{ time: 0, angles_deg: { a: 10.5 }, extensions: { b: 0.25 }, joints: { a: [1, 0], b: [2, 0.5] } }] };
  assert.equal(rigFramesCsv(rig, answer), "time,a_deg,b_deg,b_ext,a.x,a.y,b.x,b.y\n0.0,10.5,5.0,0.25,1.0,0.0,2.0,0.5\n");
});

test("a character's request: the file's text, the tracks only, the clip, the IK switch, the format", () => {
  let keys = setKey(null, "front-foot-target", 0, 1, 2);
  keys = togglePinKey(keys, "hip");
  const c = { text: "{…}", animation: "walk", ik: "runtime" };
  assert.deepEqual(characterAnimateRequest(c, keys), { rig: "{…}", keys: { fps: 30, tracks: keys.tracks }, animation: "walk", format: "json" });
  assert.deepEqual(characterAnimateRequest({ ...c, animation: "", ik: "ikarus" }, keys, "spine"), {
    rig: "{…}",
    keys: { fps: 30, tracks: keys.tracks },
    ik: "ikarus",
    format: "spine",
    animation_name: "ikarus",
  });
  // The physics switch off goes as `"physics": false` (on, the default, is left out).
  assert.equal(characterAnimateRequest({ ...c, physics: false }, keys).physics, false);
  assert.equal("physics" in characterAnimateRequest({ ...c, physics: true }, keys), false);
  // Bends go with the tracks when there are some.
  const bent = { ...keys, bends: { shin: [{ time: 0, bend: "cw" }] } };
  assert.deepEqual(characterAnimateRequest(c, bent).keys, { fps: 30, tracks: keys.tracks, bends: bent.bends });
  const m = characterMotion({ frames: [{ time: 0, bones: [] }, { time: 1 / 30, bones: [] }] }, 30);
  assert.equal(m.fps, 30);
  assert.equal(m.duration, 1 / 30);
  assert.equal(frameAt(m, 0.03), m.frames[1]);
});

test("the arm's request: the arm as its requests send it, its tip's track link N-1, the options as they are; its branch is a rig's", () => {
  const arm = { name: "seed", base: [0, 0], links: [{ length: 3, angle_deg: 0 }, { length: 2, angle_deg: 10, limits_deg: [-90, 90] }, { length: 1, angle_deg: 0 }], extra: true };
  assert.deepEqual(armBones(arm), ["link0", "link1", "link2"]);
  const keys = setKey(setKey(null, "link2", 0, 4, 2), "link2", 0.4, 2, 4, [4, 2]);
  const req = armAnimateRequest(arm, keys, { method: "fabrik", rates: [1, 2, 3] });
  assert.deepEqual(Object.keys(req).sort(), ["arm", "keys", "options"]);
  assert.deepEqual(req.arm, { name: "seed", base: [0, 0], links: [{ length: 3, angle_deg: 0 }, { length: 2, angle_deg: 10, limits_deg: [-90, 90] }, { length: 1, angle_deg: 0 }] });
  assert.equal(req.keys, keys);
  assert.deepEqual(req.options, { method: "fabrik", rates: [1, 2, 3] }, "the arm's options keep their rates");
  assert.deepEqual(armAnimateRequest(arm, keys).options, {});
  // The arm as the keys' one body: its one-branch rig, its name, the same request.
  const branch = keyedBranch(null, arm);
  assert.equal(branch.name, "seed");
  assert.deepEqual(branch.request(keys, { method: "fabrik" }), armAnimateRequest(arm, keys, { method: "fabrik" }));
  const answer = { fps: 10, duration: 0.1, frames: [{ time: 0, angles_deg: { link0: 5, link1: 6, link2: 7 }, joints: { link0: [1, 0], link1: [2, 0], link2: [3, 0] } }, { time: 0.1, angles_deg: { link0: 8, link2: 9 }, joints: { link0: [1, 0.5], link1: [2, 0.5], link2: [3, 0.25] } }] };
  // Its answer's frames: each pose the link angles in order, a missing one held from before.
  const m = rigMotion(branch.rig, answer);
  assert.deepEqual(m.frames.map((f) => f.pose), [[5, 6, 7], [8, 6, 9]]);
  assert.equal(m.fps, 10);
  // Its CSV: the rig CSV of the one-branch rig link0…, as `ikarus animate --keys --format csv` (a missing angle: the link's start).
  assert.equal(
    rigFramesCsv(branch.rig, answer),
    "time,link0_deg,link1_deg,link2_deg,link0.x,link0.y,link1.x,link1.y,link2.x,link2.y\n0.0,5.0,6.0,7.0,1.0,0.0,2.0,0.0,3.0,0.0\n0.1,8.0,10.0,9.0,1.0,0.5,2.0,0.5,3.0,0.25\n",
  );
  // A rig's branch is the rig itself, its request the rig's.
  const rig = { name: "r", bones: [{ name: "a", length: 1, angle_deg: 0 }] };
  const rb = keyedBranch(rig, arm);
  assert.equal(rb.rig, rig);
  assert.equal(rb.name, "r");
  assert.deepEqual(rb.request(keys, { method: "fabrik", rates: [1] }), rigAnimateRequest(rig, keys, { method: "fabrik", rates: [1] }));
});

test("a character's bend handles: one per two-bone IK constraint, at its lower bone, on the side the knee turns", () => {
  const toCanvas = (x, y) => [200 + x, 200 - y];
  const ik = [
    { name: "leg", bones: ["thigh", "shin"], target: "t" },
    { name: "aim", bones: ["arm"], target: "a" },
  ];
  // The thigh straight down from (0, 0), the shin turned 30° counter-clockwise from it at (0, -10).
  const bone = (name, x, y, deg, len) => ({ name, x, y, rotation_deg: deg, tip: [x + len * Math.cos((deg * Math.PI) / 180), y + len * Math.sin((deg * Math.PI) / 180)] });
  const posed = [bone("thigh", 0, 0, -90, 10), bone("shin", 0, -10, -60, 10), bone("arm", 5, 5, 0, 3)];
  const [h, ...rest] = characterBendHandles(ik, posed, toCanvas);
  assert.deepEqual(rest, []);
  assert.equal(h.bone, "shin");
  assert.equal(h.side, "ccw");
  assert.deepEqual(h.joint, toCanvas(0, -10));
  // The knee sticks out left of the hip–ankle line (x < 0 on the screen), and so does the handle.
  assert.ok(h.at[0] < h.joint[0], `the handle at ${h.at}, the knee at ${h.joint}`);
  // Turned the other way, the side says so and the handle goes over.
  const other = [posed[0], bone("shin", 0, -10, -120, 10)];
  const [g] = characterBendHandles(ik, other, toCanvas);
  assert.equal(g.side, "cw");
  assert.ok(g.at[0] > g.joint[0]);
  // Bones not posed (yet): no handle.
  assert.deepEqual(characterBendHandles(ik, [], toCanvas), []);
});
