// ikarus-spine on spineboy's walk, 600 frames at 60 Hz, on the stand-in skeleton (spine-core's
// documented API posed by ikarus's runtime-exact code; spine-core itself is never installed):
// goals met and pins held on the skeleton's own world numbers, limits kept, every other bone
// exactly where the runtime put it, unreachable goals nearest and continuous.
//   IKARUS_SPINE_DIR=… IKARUS_WEB_DIR=… node --test web/spine/spineboy.test.mjs   (web/spine/test sets both)
import { test } from "node:test";
import assert from "node:assert/strict";
import { spinePackage, standIn, gameUpdate, tip, worlds, withDescendants } from "./common.mjs";

const { attach } = await spinePackage();
const FRAMES = 600;
const DT = 1 / 60;
const ARM = ["front-upper-arm", "front-bracer", "front-fist"];

/** The length of the front arm (upper arm, bracer, fist) and the shoulder bone. */
function arm(skeleton) {
  const bones = ARM.map((n) => skeleton.findBone(n));
  return { shoulder: bones[0], reach: bones.reduce((s, b) => s + b.data.length, 0), bones };
}

const turn = (d) => d - 360 * Math.round(d / 360);

test("spineboy walk: a 3-bone goal on front-fist on a reachable circle and rear-foot pinned, every frame within 1e-3; other bones bit for bit", async () => {
  const boy = await standIn("spine-spineboy-pro", "walk");
  const { skeleton } = boy;
  gameUpdate(boy, 0);
  const ik = await attach(skeleton);
  const { shoulder, reach } = arm(skeleton);
  const [cx, cy] = [shoulder.worldX, shoulder.worldY];
  const radius = 0.55 * reach;
  const fist = skeleton.findBone("front-fist");
  const foot = skeleton.findBone("rear-foot");
  const three = { bones: 3 };
  let worst = 0;
  let worstPin = 0;
  for (let f = 0; f < FRAMES; f++) {
    gameUpdate(boy, DT);
    const before = worlds(skeleton);
    const pinned = tip(foot);
    const pinnedDir = Math.atan2(foot.c, foot.a);
    const t = (2 * Math.PI * f) / 240;
    const x = cx + radius * Math.cos(t);
    const y = cy + radius * Math.sin(t);
    const d = Math.hypot(x - shoulder.worldX, y - shoulder.worldY);
    assert.ok(d < 0.95 * reach, `frame ${f}: the test's target must be reachable (${d} of ${reach})`);
    ik.clear();
    ik.goal("front-fist", x, y, three);
    ik.pin("rear-foot");
    const report = ik.apply();
    const [fx, fy] = tip(fist);
    const error = Math.hypot(fx - x, fy - y);
    assert.ok(error <= 1e-3, `frame ${f}: the fist's tip is ${error} from its goal`);
    assert.equal(report.goals[0].error, error, "the report's error is the skeleton's");
    const [px, py] = tip(foot);
    const held = Math.hypot(px - pinned[0], py - pinned[1]);
    assert.ok(held <= 1e-3, `frame ${f}: the pinned foot's tip moved ${held}`);
    assert.ok(Math.abs(turn((Math.atan2(foot.c, foot.a) - pinnedDir) * 57.29577951308232)) <= 1e-3 * 57.3, `frame ${f}: the pinned foot turned`);
    worst = Math.max(worst, error);
    worstPin = Math.max(worstPin, held);
    const moved = withDescendants(skeleton, report.moved);
    const after = worlds(skeleton);
    for (let i = 0; i < after.length; i++)
      if (!moved.has(i)) assert.deepEqual(after[i], before[i], `frame ${f}: ${skeleton.bones[i].data.name} is outside the moved limbs but moved`);
    for (const name of ARM) assert.ok(report.moved.includes(name), `frame ${f}: ${name} not moved`);
  }
  console.log(`# spineboy walk: worst goal error ${worst.toExponential(2)}, worst pin drift ${worstPin.toExponential(2)} over ${FRAMES} frames`);
});

test("spineboy walk: given limits hold on the bones' rotation every frame", async () => {
  const boy = await standIn("spine-spineboy-pro", "walk");
  const { skeleton } = boy;
  gameUpdate(boy, 0);
  const limits = { "front-bracer": [-40, 60], "front-fist": [-30, 30], "front-upper-arm": [-120, 120] };
  const ik = await attach(skeleton, { limits });
  const { shoulder, reach } = arm(skeleton);
  const three = { bones: 3 };
  for (let f = 0; f < FRAMES; f++) {
    gameUpdate(boy, DT);
    const t = (2 * Math.PI * f) / 150;
    ik.clear();
    ik.goal("front-fist", shoulder.worldX + 0.8 * reach * Math.cos(t), shoulder.worldY + 0.8 * reach * Math.sin(t), three);
    ik.apply();
    for (const [name, [lo, hi]] of Object.entries(limits)) {
      const r = skeleton.findBone(name).rotation;
      assert.ok(r >= lo - 1e-9 && r <= hi + 1e-9, `frame ${f}: ${name}.rotation ${r} outside [${lo}, ${hi}]`);
    }
  }
});

test("spineboy walk: an unreachable goal ends at the nearest pose, with no flip from frame to frame", async () => {
  const boy = await standIn("spine-spineboy-pro", "walk");
  const { skeleton } = boy;
  gameUpdate(boy, 0);
  const ik = await attach(skeleton);
  const { shoulder, reach, bones } = arm(skeleton);
  const three = { bones: 3 };
  let last = null;
  let worstTurn = 0;
  for (let f = 0; f < FRAMES; f++) {
    gameUpdate(boy, DT);
    const t = (2 * Math.PI * f) / 300;
    const x = shoulder.worldX + 2.5 * reach * Math.cos(t);
    const y = shoulder.worldY + 2.5 * reach * Math.sin(t);
    ik.clear();
    ik.goal("front-fist", x, y, three);
    const report = ik.apply();
    const nearest = Math.hypot(x - shoulder.worldX, y - shoulder.worldY) - reach;
    assert.ok(report.goals[0].error - nearest <= 1e-3, `frame ${f}: error ${report.goals[0].error}, the nearest pose's ${nearest}`);
    const now = bones.map((b) => Math.atan2(b.c, b.a) * 57.29577951308232);
    if (last)
      for (let k = 0; k < 3; k++) {
        const d = Math.abs(turn(now[k] - last[k]));
        worstTurn = Math.max(worstTurn, d);
        assert.ok(d < 10, `frame ${f}: ${ARM[k]} turned ${d} degrees in one frame`);
      }
    last = now;
  }
  console.log(`# spineboy walk, unreachable goal: largest turn of an arm bone in one frame ${worstTurn.toFixed(3)} degrees`);
});

test("spineboy: bad input names the field and the value", async () => {
  const boy = await standIn("spine-spineboy-pro", "walk");
  gameUpdate(boy, 0);
  const ik = await attach(boy.skeleton);
  assert.throws(() => ik.goal("front-fits", 0, 0), /^Error: ikarus-spine: goal: bone: no bone named "front-fits" in the skeleton$/);
  assert.throws(() => ik.goal("front-fist", 0, NaN, { bones: 3 }), /goal\(front-fist\): y: must be a finite number, got NaN/);
  assert.throws(() => ik.goal("front-fist", 0, 0, { bones: 12 }), /goal\(front-fist\): bones: 12 goes past the root \(front-fist has 9 bones up to it\)/);
  assert.throws(() => ik.pin("rear-fot"), /pin: bone: no bone named "rear-fot"/);
  await assert.rejects(attach(boy.skeleton, { limits: { "front-bracer": [120, -40] } }), /limits\["front-bracer"\]: must be \[minDeg, maxDeg\] with min <= max, got "\[120,-40\]"/);
});
