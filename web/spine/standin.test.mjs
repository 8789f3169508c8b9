// The stand-in skeleton (web/spine/standin/) against Spine's own runtime: after `state.apply` and
// `skeleton.updateWorldTransform`, every bone's world transform matches the runtime's output
// (crates/ikarus-edge/tests/reference/*-full.json, spine-core 4.2.119: its protocol is in each
// file) within 1e-3, for every case of spineboy, the raptor, stretchyman (paths) and
// celestial-circus (physics stepped at 60 Hz); and the API's other promises (a mix written by
// JavaScript is the one posed, the placement, worldToLocal/localToWorld, refusals).
//
//   IKARUS_WEB_DIR=DIR node --test web/spine/standin.test.mjs   (DIR: what `bash web/build DIR` wrote)
//
// IKARUS_REFERENCE_DIR: the reference files' directory (default crates/ikarus-edge/tests/reference).
import { test } from "node:test";
import assert from "node:assert/strict";
import { readFileSync } from "node:fs";
import { dirname, join } from "node:path";
import { fileURLToPath, pathToFileURL } from "node:url";
import { loadStandIn, Physics, Inherit } from "./standin/index.js";

const root = join(dirname(fileURLToPath(import.meta.url)), "..", "..");
const dir = process.env.IKARUS_WEB_DIR;
if (!dir) throw new Error("IKARUS_WEB_DIR: the directory `bash web/build DIR` wrote");
const core = await import(pathToFileURL(join(dir, "ikarus_core.js")).href);
await core.default({ module_or_path: readFileSync(join(dir, "ikarus_core_bg.wasm")) });

// The repository's copies of Spine's runtime output (the edge's reference tests read them too).
const referenceDir = process.env.IKARUS_REFERENCE_DIR ?? join(root, "crates", "ikarus-edge", "tests", "reference");
const character = (name) => readFileSync(join(root, "examples", "characters", `spine-${name}-pro.json`), "utf8");

/** The largest difference of any bone's world numbers from the reference's, with where. */
function worst(skeleton, want) {
  let max = { d: 0, where: "" };
  for (const [name, w] of Object.entries(want)) {
    const b = skeleton.findBone(name);
    assert.ok(b, `bone ${name} of the reference is in the stand-in`);
    assert.equal(b.active, w.active, `${name}: active`);
    const got = [b.worldX, b.worldY, b.a, b.b, b.c, b.d];
    const ref = [w.x, w.y, w.a, w.b, w.c, w.d];
    for (let k = 0; k < 6; k++) {
      const d = Math.abs(got[k] - ref[k]);
      if (!(d <= max.d)) max = { d, where: `${name} ${["worldX", "worldY", "a", "b", "c", "d"][k]}: ${got[k]} vs ${ref[k]}` };
    }
  }
  return max;
}

/** Poses one reference case through the stand-in, as the reference's protocol says. */
function poseCase(skeleton, state, c) {
  skeleton.setToSetupPose();
  skeleton.time = 0;
  if (c.animation === undefined) {
    skeleton.updateWorldTransform(Physics.none);
    return;
  }
  const entry = state.setAnimation(0, c.animation, false);
  if (!c.physics) {
    entry.trackTime = c.time;
    state.apply(skeleton);
    skeleton.updateWorldTransform(Physics.none);
    return;
  }
  state.apply(skeleton);
  skeleton.updateWorldTransform(Physics.reset);
  const frames = Math.round(c.time * 60);
  for (let f = 0; f < frames; f++) {
    state.update(1 / 60);
    skeleton.update(1 / 60);
    state.apply(skeleton);
    skeleton.updateWorldTransform(Physics.update);
  }
}

for (const name of ["spineboy", "raptor", "stretchyman", "celestial-circus"]) {
  const file = join(referenceDir, `spine-${name}-pro-full.json`);
  test(`${name}: every case of Spine's runtime reference, every bone's world within 1e-3`, async () => {
    const ref = JSON.parse(readFileSync(file, "utf8"));
    const { skeleton, state } = await loadStandIn(character(name), { core });
    let all = 0;
    for (const c of ref.cases) {
      poseCase(skeleton, state, c.case);
      const w = worst(skeleton, c.bones);
      assert.ok(w.d <= 1e-3, `${name} ${JSON.stringify(c.case)}: ${w.where} (off by ${w.d})`);
      all = Math.max(all, w.d);
    }
    console.log(`${name}: ${ref.cases.length} cases, ${skeleton.bones.length} bones, largest difference ${all.toExponential(2)}`);
  });
}

test("the raptor's walk at 0.4 s (the single-case reference) within 1e-3", async () => {
  const file = join(referenceDir, "ref-raptor-walk-t0.4-spinecore4.2.119.json");
  const ref = JSON.parse(readFileSync(file, "utf8"));
  const { skeleton, state } = await loadStandIn(character("raptor"), { core });
  poseCase(skeleton, state, { animation: "walk", time: 0.4 });
  const bones = Object.fromEntries(Object.entries(ref.bones).map(([name, b]) => [name, { ...b, active: true }]));
  const w = worst(skeleton, bones);
  assert.ok(w.d <= 1e-3, w.where);
  console.log(`raptor walk 0.4 s: largest difference ${w.d.toExponential(2)}`);
});

test("the documented shape: bones, data, constraints, inherit as numbers in Spine's order", async () => {
  const { skeleton } = await loadStandIn(character("spineboy"), { core });
  assert.equal(skeleton.bones[0].parent, null);
  const fist = skeleton.findBone("front-fist");
  assert.equal(fist.parent, skeleton.findBone("front-bracer"));
  assert.equal(fist.data.parent, fist.parent.data);
  assert.equal(skeleton.bones[fist.data.index], fist);
  assert.ok(fist.data.length > 0);
  assert.equal(skeleton.findBone("nope"), null);
  assert.deepEqual(Object.keys(Inherit), ["normal", "onlyTranslation", "noRotationOrReflection", "noScale", "noScaleOrReflection"]);
  const json = JSON.parse(character("spineboy"));
  for (const b of json.bones) {
    const want = Inherit[b.inherit ?? "normal"];
    assert.equal(skeleton.findBone(b.name).data.inherit, want, `${b.name}: inherit ${b.inherit}`);
    // The setup rotation, through ikarus's radians: within rounding.
    assert.ok(Math.abs(skeleton.findBone(b.name).data.rotation - (b.rotation ?? 0)) < 1e-9, `${b.name}: setup rotation`);
  }
  const leg = skeleton.findIkConstraint("front-leg-ik");
  assert.deepEqual(leg.bones.map((b) => b.data.name), ["front-thigh", "front-shin"]);
  assert.equal(leg.target.data.name, "front-leg-target");
  assert.equal(leg.data.name, "front-leg-ik");
  assert.equal(skeleton.ikConstraints.length, json.ik.length);
  for (const k of json.ik) assert.equal(skeleton.findIkConstraint(k.name).mix, k.mix ?? 1, `${k.name}: mix`);
  // Plain number fields, not getters.
  for (const key of ["x", "rotation", "a", "worldX"]) assert.ok(Object.getOwnPropertyDescriptor(fist, key).writable, key);
});

test("a mix JavaScript writes is the one posed, and the next frame is the animation's again", async () => {
  const { skeleton, state } = await loadStandIn(character("spineboy"), { core });
  state.setAnimation(0, "walk", true);
  state.update(0.4);
  state.apply(skeleton);
  skeleton.updateWorldTransform(Physics.none);
  const thigh = skeleton.findBone("front-thigh");
  const keyed = [thigh.a, thigh.c];
  const leg = skeleton.findIkConstraint("front-leg-ik");
  leg.mix = 0;
  skeleton.updateWorldTransform(Physics.none);
  // Mix 0: the thigh at its own local rotation under its parent.
  const p = thigh.parent;
  const want = Math.atan2(p.c, p.a) + (thigh.rotation * Math.PI) / 180;
  const got = Math.atan2(thigh.c, thigh.a);
  assert.ok(Math.abs(Math.atan2(Math.sin(got - want), Math.cos(got - want))) < 1e-9, `${got} vs ${want}`);
  assert.notDeepEqual([thigh.a, thigh.c], keyed);
  leg.mix = 1;
  skeleton.updateWorldTransform(Physics.none);
  assert.deepEqual([thigh.a, thigh.c], keyed);
  // A bone the animation does not key keeps what JavaScript wrote (as a runtime's timelines do).
  const thighRotation = thigh.rotation;
  thigh.rotation += 10;
  state.apply(skeleton);
  assert.equal(thigh.rotation, thighRotation + 10);
  const fist = skeleton.findBone("front-fist");
  const fistRotation = fist.rotation;
  fist.rotation += 10;
  state.apply(skeleton);
  assert.equal(fist.rotation, fistRotation);
});

test("the placement moves and scales every bone, and the bone's conversions invert each other", async () => {
  const { skeleton, state } = await loadStandIn(character("spineboy"), { core });
  state.setAnimation(0, "walk", true);
  state.update(0.25);
  state.apply(skeleton);
  skeleton.updateWorldTransform(Physics.none);
  const before = skeleton.bones.map((b) => [b.worldX, b.worldY]);
  Object.assign(skeleton, { x: 100, y: -20, scaleX: -0.5, scaleY: 0.5 });
  skeleton.updateWorldTransform(Physics.none);
  skeleton.bones.forEach((b, i) => {
    assert.ok(Math.abs(b.worldX - (100 - 0.5 * before[i][0])) < 1e-9 && Math.abs(b.worldY - (-20 + 0.5 * before[i][1])) < 1e-9, b.data.name);
  });
  const fist = skeleton.findBone("front-fist");
  const p = fist.localToWorld({ x: 3, y: -4 });
  const back = fist.worldToLocal({ ...p });
  assert.ok(Math.abs(back.x - 3) < 1e-9 && Math.abs(back.y + 4) < 1e-9, JSON.stringify(back));
  const tip = fist.localToWorld({ x: fist.data.length, y: 0 });
  assert.ok(Math.abs(tip.x - (fist.worldX + fist.a * fist.data.length)) < 1e-12);
  const r = fist.worldToLocalRotation(fist.getWorldRotationX());
  assert.ok(Math.abs(fist.localToWorldRotation(r) - fist.getWorldRotationX()) < 1e-9);
});

test("bad input: a one-line error naming the bone or the field", async () => {
  await assert.rejects(loadStandIn("{", { core }), /^Error: jsonText: /);
  await assert.rejects(loadStandIn("{}", {}), /core: not the ikarus_core module/);
  const { skeleton, state } = await loadStandIn(character("spineboy"), { core });
  assert.throws(() => state.setAnimation(0, "wlk", true), /animation "wlk": no such animation/);
  assert.throws(() => state.setAnimation(1, "walk", true), /track: 1/);
  skeleton.findBone("hip").rotation = NaN;
  assert.throws(() => skeleton.updateWorldTransform(Physics.none), /^Error: updateWorldTransform: bone "hip": local number 2 is NaN, not finite$/);
  skeleton.findBone("hip").rotation = 0;
  skeleton.findIkConstraint("aim-ik").softness = Infinity;
  assert.throws(() => skeleton.updateWorldTransform(Physics.none), /IK constraint "aim-ik": number 1 is inf/);
  skeleton.findIkConstraint("aim-ik").softness = 0;
  assert.throws(() => skeleton.updateWorldTransform(7), /physics: 7/);
  skeleton.x = NaN;
  assert.throws(() => skeleton.updateWorldTransform(Physics.none), /placement: NaN/);
});
