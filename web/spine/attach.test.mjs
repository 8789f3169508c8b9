// ikarus-spine on a small hand-made skeleton (toy.mjs): the API's contract without a character.
//   IKARUS_SPINE_DIR=DIR node --test web/spine/attach.test.mjs   (DIR: what `bash web/spine/build DIR` wrote)
import { test } from "node:test";
import assert from "node:assert/strict";
import { readFileSync } from "node:fs";
import { join } from "node:path";
import { fileURLToPath, pathToFileURL } from "node:url";
import { execFileSync } from "node:child_process";
import { toySkeleton, tip } from "./toy.mjs";

const dir = process.env.IKARUS_SPINE_DIR;
if (!dir) throw new Error("IKARUS_SPINE_DIR: the directory `bash web/spine/build DIR` wrote (web/spine/test sets it)");
const spine = await import(pathToFileURL(join(dir, "index.js")).href);
const { attach } = spine;

const worlds = (s) => s.bones.map((b) => [b.a, b.b, b.c, b.d, b.worldX, b.worldY]);

test("a reachable goal is met on the skeleton's own world numbers; bones outside the limb keep their pose exactly", async () => {
  const s = toySkeleton();
  const ik = await attach(s);
  const before = worlds(s);
  const hand = s.findBone("hand");
  ik.clear();
  ik.goal("hand", 60, 150, { bones: 3 });
  const report = ik.apply();
  const [x, y] = tip(hand);
  assert.ok(Math.hypot(x - 60, y - 150) <= 1e-3, `hand tip at ${x}, ${y}`);
  assert.equal(report.goals.length, 1);
  assert.equal(report.goals[0].bone, "hand");
  assert.ok(Math.abs(report.goals[0].error - Math.hypot(x - 60, y - 150)) < 1e-12);
  assert.deepEqual(report.moved, ["upper", "lower", "hand"]);
  const after = worlds(s);
  for (const name of ["root", "hip", "thigh", "shin", "foot", "tail", "foot-target"]) {
    const i = s.bones.indexOf(s.findBone(name));
    assert.deepEqual(after[i], before[i], `${name} moved`);
  }
  assert.equal(s.lastPhysics, spine.PHYSICS_POSE, "apply() updates with Physics.pose by default");
});

test("the report is the same object every frame, and clear() drops goals and pins", async () => {
  const s = toySkeleton();
  const ik = await attach(s);
  ik.goal("hand", 60, 150, { bones: 3 });
  const r1 = ik.apply();
  ik.clear();
  const r2 = ik.apply();
  assert.equal(r1, r2);
  assert.equal(r2.goals.length, 0);
  assert.equal(r2.moved.length, 0);
});

test("a goal moving a Spine IK constraint's bone: mix 0 for that update, restored after, so the goal wins", async () => {
  const s = toySkeleton();
  const footIk = s.findIkConstraint("foot-ik");
  footIk.mix = 0.75;
  s.updateWorldTransform(0);
  const ik = await attach(s);
  const mixes = [];
  const update = s.updateWorldTransform;
  s.updateWorldTransform = function (physics) {
    mixes.push(footIk.mix);
    update.call(this, physics);
  };
  ik.goal("foot", 10, 30, { bones: 3 });
  const report = ik.apply();
  assert.deepEqual(mixes, [0], "the constraint steps aside during the update");
  assert.equal(footIk.mix, 0.75, "and gets its mix back");
  const [x, y] = tip(s.findBone("foot"));
  assert.ok(Math.hypot(x - 10, y - 30) <= 1e-3, `the foot's tip at ${x}, ${y}`);
  assert.ok(report.goals[0].error <= 1e-3);
});

test("a pin under no moving bone stays out of the solve: its Spine IK constraint keeps its mix and the bone its place", async () => {
  const s = toySkeleton();
  s.findBone("foot-target").x = 60; // the constraint turns the foot well away from its own rotation
  s.updateWorldTransform(0);
  const ik = await attach(s);
  const foot = s.findBone("foot");
  const footIk = s.findIkConstraint("foot-ik");
  const before = tip(foot);
  const mixes = [];
  const update = s.updateWorldTransform;
  s.updateWorldTransform = function (physics) {
    mixes.push(footIk.mix);
    update.call(this, physics);
  };
  ik.goal("hand", 60, 150, { bones: 3 }); // the arm: nothing above the foot moves
  ik.pin("foot");
  const report = ik.apply();
  assert.deepEqual(mixes, [1], "the constraint did not step aside");
  assert.deepEqual(report.moved, ["upper", "lower", "hand"]);
  const after = tip(foot);
  assert.ok(Math.hypot(after[0] - before[0], after[1] - before[1]) <= 1e-12, `foot tip moved to ${after} from ${before}`);
});

test("a bone of a touched Spine IK constraint that the goal does not move keeps the pose the constraint gave it", async () => {
  const s = toySkeleton();
  const ik = await attach(s);
  const foot = s.findBone("foot");
  const before = [foot.a, foot.c];
  // The goal moves thigh and shin; the foot (aimed by foot-ik at mix 1) is below them, not moved:
  // the constraint keeps its mix and aims it again.
  ik.goal("shin", 35, 40, { bones: 2 });
  ik.apply();
  const target = s.findBone("foot-target");
  const aim = Math.atan2(target.worldY - foot.worldY, target.worldX - foot.worldX);
  assert.ok(Math.abs(Math.atan2(foot.c, foot.a) - aim) < 1e-9, "foot-ik still aims the foot");
  assert.notDeepEqual([foot.a, foot.c], before);
});

test("limits hold on the bone's rotation", async () => {
  const s = toySkeleton();
  const ik = await attach(s, { limits: { lower: [0, 30], upper: [-60, 10] } });
  for (const [x, y] of [[60, 150], [-40, 190], [110, 60], [0, 120]]) {
    ik.clear();
    ik.goal("hand", x, y, { bones: 3 });
    ik.apply();
    const lower = s.findBone("lower").rotation;
    const upper = s.findBone("upper").rotation;
    assert.ok(lower >= -1e-9 && lower <= 30 + 1e-9, `lower ${lower} for ${x}, ${y}`);
    assert.ok(upper >= -60 - 1e-9 && upper <= 10 + 1e-9, `upper ${upper} for ${x}, ${y}`);
  }
});

test("an unreachable goal ends at the nearest pose, with no flip from frame to frame", async () => {
  const s = toySkeleton();
  const ik = await attach(s);
  const hand = s.findBone("hand");
  const rotations = [];
  for (let f = 0; f < 120; f++) {
    const t = (f / 120) * 2 * Math.PI;
    const x = 20 + 300 * Math.cos(t);
    const y = 100 + 300 * Math.sin(t);
    ik.clear();
    ik.goal("hand", x, y, { bones: 3 });
    const r = ik.apply();
    // Nearest: the arm stretched along the line from its shoulder to the goal.
    const reach = 50 + 40 + 15;
    const shoulder = s.findBone("upper");
    const far = Math.hypot(x - shoulder.worldX, y - shoulder.worldY);
    assert.ok(Math.abs(r.goals[0].error - (far - reach)) < 1e-3, `frame ${f}: error ${r.goals[0].error}, nearest ${far - reach}`);
    const [hx, hy] = tip(hand);
    assert.ok(Math.hypot(hx - shoulder.worldX, hy - shoulder.worldY) > reach - 1e-3);
    rotations.push(["upper", "lower", "hand"].map((n) => s.findBone(n).rotation));
  }
  for (let f = 1; f < rotations.length; f++)
    for (let k = 0; k < 3; k++) {
      let d = rotations[f][k] - rotations[f - 1][k];
      d -= 360 * Math.round(d / 360);
      assert.ok(Math.abs(d) < 10, `frame ${f}: bone ${k} turned ${d} degrees`);
    }
});

test("bad input: one-line errors naming the field and the value", async () => {
  const s = toySkeleton();
  const ik = await attach(s);
  const cases = [
    [() => ik.goal("hnad", 0, 0), /goal: bone: no bone named "hnad"/],
    [() => ik.goal({}, 0, 0), /goal: bone: must be a bone's name/],
    [() => ik.goal("hand", NaN, 0), /goal\(hand\): x: must be a finite number, got NaN/],
    [() => ik.goal("hand", 0, Infinity), /goal\(hand\): y: .*Infinity/],
    [() => ik.goal("hand", 0, 0, { bones: 6 }), /goal\(hand\): bones: 6 goes past the root/],
    [() => ik.goal("hand", 0, 0, { bones: 0 }), /goal\(hand\): bones: .* got 0/],
    [() => ik.goal("hand", 0, 0, { bones: 1.5 }), /goal\(hand\): bones: .* got 1.5/],
    [() => ik.goal("hand", 0, 0, { angle: NaN }), /goal\(hand\): angle: .* got NaN/],
    [() => ik.goal("hand", 0, 0, { weight: 0 }), /goal\(hand\): weight: .* got 0/],
    [() => ik.goal("hand", 0, 0, { priority: "first" }), /goal\(hand\): priority: .* got "first"/],
    [() => ik.goal("hand", 0, 0, { bend: "toString" }), /goal\(hand\): bend: .* got "toString"/],
    [() => ik.pin("nope"), /pin: bone: no bone named "nope"/],
  ];
  for (const [call, message] of cases) {
    assert.throws(call, (e) => e instanceof Error && message.test(e.message) && !e.message.includes("\n"), String(message));
  }
  await assert.rejects(attach(s, { limits: { nope: [0, 1] } }), /limits: no bone named "nope"/);
  await assert.rejects(attach(s, { limits: { hand: [10, -10] } }), /limits\["hand"\]: must be \[minDeg, maxDeg\]/);
  await assert.rejects(attach(s, { limits: { hand: [NaN, 1] } }), /limits\["hand"\]/);
  await assert.rejects(attach({}, {}), /skeleton: must be a Spine Skeleton/);
  // Nothing half-given survives a refusal: the next apply() solves only what was accepted.
  assert.equal(ik.apply().goals.length, 0);
});

test("no allocation per frame: nothing allocated by the package's code in 20000 frames, the module's memory stays put (alloc.mjs)", () => {
  // In a process of its own: the JIT state of a game calling one goal shape every frame, not
  // that of this file's other tests.
  const out = execFileSync(process.execPath, [fileURLToPath(new URL("alloc.mjs", import.meta.url))], { env: process.env, encoding: "utf8" });
  const r = JSON.parse(out);
  assert.equal(r.moduleMemoryGrew, 0, "the module's memory grew");
  // By the file of the function that allocated; the JIT may inline the glue into index.js, so
  // the two count together.
  const ours = (r.bytesPerFrame["index.js"] ?? 0) + (r.bytesPerFrame["ikarus_spine.js"] ?? 0);
  assert.ok(r.applyFrame, "the module answers applyFrame (one plain number: no array per frame)");
  assert.ok(ours < 1, `allocated per frame: ${out}`);
});

test("index.d.ts declares every export of index.js, and nothing else", () => {
  const types = readFileSync(join(dir, "index.d.ts"), "utf8");
  const declared = [...types.matchAll(/^export declare (?:function|const|class) (\w+)/gm)].map((m) => m[1]).sort();
  assert.deepEqual(declared, Object.keys(spine).sort());
  for (const name of ["clear", "goal", "pin", "apply", "dispose"])
    assert.ok(new RegExp(`^  ${name}\\(`, "m").test(types) && typeof spine.Ik.prototype[name] === "function", name);
});

test("package.json: ikarus-spine at the workspace's version, spine-core a peer dependency only", () => {
  const pkg = JSON.parse(readFileSync(join(dir, "package.json"), "utf8"));
  const cargo = readFileSync(new URL("../../Cargo.toml", import.meta.url), "utf8");
  assert.equal(pkg.name, "ikarus-spine");
  assert.equal(pkg.version, /\[workspace\.package\][^[]*?\nversion = "([^"]+)"/.exec(cargo)[1]);
  assert.equal(pkg.type, "module");
  assert.deepEqual(pkg.peerDependencies, { "@esotericsoftware/spine-core": "^4.2.0" });
  assert.equal(pkg.dependencies, undefined);
  assert.equal(pkg.devDependencies, undefined);
  for (const f of pkg.files) assert.ok(readFileSync(join(dir, f)).length > 0, f);
  // Nor anything the repository installs: its licence asks every user for a Spine Editor licence.
  for (const file of ["web/package.json", "web/package-lock.json", "e2e/package.json", "e2e/package-lock.json"])
    assert.ok(!readFileSync(new URL(`../../${file}`, import.meta.url), "utf8").includes("@esotericsoftware"), file);
});
