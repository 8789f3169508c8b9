// ikarus-spine on the raptor's walk (76 bones, 9 Spine IK constraints, most of its legs driven by
// them), 600 frames at 60 Hz on the stand-in skeleton: goals on bones that Spine IK constraints
// drive win over them, the constraints' other bones keep the pose the constraint gave them, and
// every bone outside the moved limbs stays bit for bit where the runtime put it.
//   IKARUS_SPINE_DIR=… IKARUS_WEB_DIR=… node --test web/spine/raptor.test.mjs   (web/spine/test sets both)
import { test } from "node:test";
import assert from "node:assert/strict";
import { spinePackage, standIn, gameUpdate, tip, worlds, withDescendants } from "./common.mjs";

const { attach } = await spinePackage();
const FRAMES = 600;
const DT = 1 / 60;

/** `b`'s world 2×2 and origin in its parent's frame: what a constraint's applied rotation fixes. */
function relative(b) {
  const p = b.parent;
  const det = p.a * p.d - p.b * p.c;
  const dx = b.worldX - p.worldX;
  const dy = b.worldY - p.worldY;
  return [
    (p.d * b.a - p.b * b.c) / det,
    (p.d * b.b - p.b * b.d) / det,
    (p.a * b.c - p.c * b.a) / det,
    (p.a * b.d - p.c * b.b) / det,
    (p.d * dx - p.b * dy) / det,
    (p.a * dy - p.c * dx) / det,
  ];
}

test("raptor walk: a goal on front-leg3 (its own IK constraint front-foot-ik steps aside) is met; front-foot1 keeps the rotation the constraint gave it; other bones bit for bit", async () => {
  const raptor = await standIn("spine-raptor-pro", "walk");
  const { skeleton } = raptor;
  gameUpdate(raptor, 0);
  const ik = await attach(skeleton);
  const leg = skeleton.findBone("front-leg3");
  const foot = skeleton.findBone("front-foot1");
  const footIk = skeleton.findIkConstraint("front-foot-ik");
  const one = { bones: 1 };
  let worst = 0;
  for (let f = 0; f < FRAMES; f++) {
    gameUpdate(raptor, DT);
    const before = worlds(skeleton);
    const footBefore = relative(foot);
    const mix = footIk.mix;
    // The tip turned about the bone's origin by up to 20°: on the circle the bone alone reaches.
    const turn = (20 * Math.PI * Math.sin((2 * Math.PI * f) / 200)) / 180;
    const [tx, ty] = tip(leg);
    const [ox, oy] = [leg.worldX, leg.worldY];
    const x = ox + Math.cos(turn) * (tx - ox) - Math.sin(turn) * (ty - oy);
    const y = oy + Math.sin(turn) * (tx - ox) + Math.cos(turn) * (ty - oy);
    ik.clear();
    ik.goal(leg, x, y, one);
    const report = ik.apply();
    const [lx, ly] = tip(leg);
    const error = Math.hypot(lx - x, ly - y);
    assert.ok(error <= 1e-3, `frame ${f}: front-leg3's tip is ${error} from its goal`);
    assert.equal(footIk.mix, mix, `frame ${f}: front-foot-ik's mix restored`);
    assert.deepEqual(report.moved, ["front-leg3", "front-foot1"]);
    const footAfter = relative(foot);
    for (let k = 0; k < 6; k++)
      assert.ok(Math.abs(footAfter[k] - footBefore[k]) < 1e-9, `frame ${f}: front-foot1 left its applied pose relative to front-leg3 (${k}: ${footBefore[k]} → ${footAfter[k]})`);
    worst = Math.max(worst, error);
    const moved = withDescendants(skeleton, report.moved);
    const after = worlds(skeleton);
    for (let i = 0; i < after.length; i++)
      if (!moved.has(i)) assert.deepEqual(after[i], before[i], `frame ${f}: ${skeleton.bones[i].data.name} moved`);
  }
  console.log(`# raptor walk, goal on front-leg3: worst error ${worst.toExponential(2)} over ${FRAMES} frames`);
});

test("raptor walk: a 2-bone goal on front-leg2 (both bones of front-leg-ik) and back-foot1 pinned, every frame within 1e-3", async () => {
  const raptor = await standIn("spine-raptor-pro", "walk");
  const { skeleton } = raptor;
  gameUpdate(raptor, 0);
  const ik = await attach(skeleton);
  const thigh = skeleton.findBone("front-leg1");
  const shin = skeleton.findBone("front-leg2");
  const pinned = skeleton.findBone("back-foot1");
  const reach = thigh.data.length + shin.data.length;
  const two = { bones: 2 };
  for (let f = 0; f < FRAMES; f++) {
    gameUpdate(raptor, DT);
    const hold = tip(pinned);
    // Below the hip, on a circle the leg reaches (between 0.6 and 0.9 of its length).
    const t = (2 * Math.PI * f) / 300;
    const r = reach * (0.75 + 0.15 * Math.sin(3 * t));
    const x = thigh.worldX + r * Math.cos(-Math.PI / 2 + 0.5 * Math.sin(t));
    const y = thigh.worldY + r * Math.sin(-Math.PI / 2 + 0.5 * Math.sin(t));
    ik.clear();
    ik.goal("front-leg2", x, y, two);
    ik.pin(pinned);
    const report = ik.apply();
    assert.ok(report.goals[0].error <= 1e-3, `frame ${f}: front-leg2's tip is ${report.goals[0].error} from its goal`);
    const [px, py] = tip(pinned);
    assert.ok(Math.hypot(px - hold[0], py - hold[1]) <= 1e-3, `frame ${f}: back-foot1's tip moved`);
  }
});
