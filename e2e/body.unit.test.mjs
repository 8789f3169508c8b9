// Unit tests of the page's one forward kinematics (body.js; no browser, no server): offsets and
// prismatic joints against positions worked out by hand; the shipped rigs bit for bit, and the
// shipped arms to rounding, against the two copies the page had before (rig.js's rigForward and
// view.js's forward, kept here as references). Run by e2e/run and .ci/run:
//   node --test e2e/body.unit.test.mjs
import { test } from "node:test";
import assert from "node:assert/strict";
import { readFileSync, readdirSync } from "node:fs";
import { join } from "node:path";
import { DEG, bodyForward, chainBody } from "../crates/ikarus-cli/src/serve/assets/body.js";
import { forward } from "../crates/ikarus-cli/src/serve/assets/view.js";

const close = (p, q, eps = 1e-12) => assert.ok(Math.abs(p[0] - q[0]) <= eps && Math.abs(p[1] - q[1]) <= eps, `${p} is not ${q}`);

// ---- Hand-computed positions -----------------------------------------------------------------

test("an offset is in the parent's frame, from the parent's start", () => {
  // The parent points up from (1, 2), length 2; the child's joint is 0.5 along it and 0.25 to
  // its left (−x), not at its tip; the child points 90° left of the parent: along −x.
  const body = {
    base: [1, 2],
    bones: [
      { name: "up", length: 2, angle_deg: 90 },
      { name: "side", parent: "up", offset: [0.5, 0.25], length: 1, angle_deg: 90 },
      { name: "tip", parent: "up", length: 1, angle_deg: 0 },
    ],
  };
  const f = bodyForward(body);
  close(f.starts[0], [1, 2]);
  close(f.tips[0], [1, 4]);
  close(f.starts[1], [0.75, 2.5]);
  close(f.tips[1], [-0.25, 2.5]);
  assert.deepEqual(f.headings, [90, 180, 90]);
  // No offset: the parent's tip, as before.
  close(f.starts[2], [1, 4]);
  close(f.tips[2], [1, 5]);
  // A root's offset is from the base, in the world's frame.
  const root = bodyForward({ base: [1, 2], bones: [{ name: "r", offset: [3, -1], length: 1, angle_deg: 180 }] });
  close(root.starts[0], [4, 1]);
  close(root.tips[0], [3, 1]);
});

test("a prismatic bone slides along its slide, in its parent's frame, by its extension", () => {
  // A PRR arm: a carriage sliding along +x from the base (slide default: along the bone, 0°),
  // then two revolute links. Extension 1.5 puts the carriage's start at (1.5, 0).
  const prr = {
    base: [0, 0],
    bones: [
      { name: "carriage", joint: "prismatic", length: 0.5, angle_deg: 0, extension: 1.5, limits: [0, 3] },
      { name: "upper", parent: "carriage", length: 1, angle_deg: 90 },
      { name: "lower", parent: "upper", length: 1, angle_deg: -90 },
    ],
  };
  const f = bodyForward(prr);
  close(f.joints[0], [0, 0]);
  close(f.starts[0], [1.5, 0]);
  close(f.tips[0], [2, 0]);
  close(f.slides[0], [1, 0]);
  close(f.tips[1], [2, 1]);
  close(f.tips[2], [3, 1]);
  // The pose's value for a prismatic bone is its extension.
  close(bodyForward(prr, [0.25, 90, -90]).tips[2], [1.75, 1]);
  // An RRP arm: the last bone slides along a slide of its own, [0, 1] in its parent's frame
  // (to the parent's left), with its rest angle 90° (pointing that way too).
  const rrp = {
    base: [0, 0],
    bones: [
      { name: "a", length: 1, angle_deg: 0 },
      { name: "b", parent: "a", length: 1, angle_deg: 90 },
      { name: "ram", parent: "b", joint: "prismatic", slide: [0, 1], length: 0.5, angle_deg: 90, extension: 0.25 },
    ],
  };
  const g = bodyForward(rrp, [0, 90, 0.75]);
  // b ends at (1, 1) heading up; its left is −x: the ram's joint at b's tip, slid 0.75 along −x.
  close(g.joints[2], [1, 1]);
  close(g.slides[2], [-1, 0]);
  close(g.starts[2], [0.25, 1]);
  close(g.tips[2], [-0.25, 1]);
  assert.equal(g.headings[2], 180);
  // The rest value is the extension; its angle does not move with the pose.
  close(bodyForward(rrp, [0, 90]).starts[2], [0.75, 1]);
});

test("a prismatic bone's slide turns with its parent", () => {
  const body = {
    base: [0, 0],
    bones: [
      { name: "arm", length: 2, angle_deg: 30 },
      { name: "ram", parent: "arm", joint: "prismatic", length: 1, angle_deg: 0, extension: 0.5 },
    ],
  };
  const f = bodyForward(body);
  const u = [Math.cos(30 * DEG), Math.sin(30 * DEG)];
  close(f.starts[1], [2.5 * u[0], 2.5 * u[1]]);
  close(f.tips[1], [3.5 * u[0], 3.5 * u[1]]);
});

// ---- Bit for bit as the page's two copies before -----------------------------------------------

/** view.js's forward before body.js: radians added link by link. */
function chainBefore(arm, pose) {
  const [bx, by] = arm.base || [0, 0];
  const joints = [[bx, by]];
  let [x, y, a] = [bx, by, 0];
  arm.links.forEach((link, i) => {
    a += (pose[i] ?? link.angle_deg) * DEG;
    x += link.length * Math.cos(a);
    y += link.length * Math.sin(a);
    joints.push([x, y]);
  });
  return joints;
}

/** rig.js's rigForward before body.js: degrees added bone by bone (bones parent-first here). */
function rigBefore(rig, pose) {
  const index = new Map(rig.bones.map((b, i) => [b.name, i]));
  const tips = [];
  const headings = [];
  rig.bones.forEach((b, i) => {
    const p = b.parent ? index.get(b.parent) : undefined;
    const start = p === undefined ? rig.base : tips[p];
    const h = (p === undefined ? 0 : headings[p]) + (pose[i] ?? b.angle_deg);
    tips[i] = [start[0] + b.length * Math.cos(h * DEG), start[1] + b.length * Math.sin(h * DEG)];
    headings[i] = h;
  });
  return tips;
}

/** The shipped files' `base` and `[[links]]` or `[[bones]]` (one key per line, as they are written). */
function readFile(path, table) {
  const out = { base: [0, 0], [table]: [] };
  for (const line of readFileSync(path, "utf8").split("\n")) {
    if (line.startsWith(`[[${table}]]`)) out[table].push({});
    const m = /^(\w+) = (.*)$/.exec(line);
    if (!m) continue;
    const value = JSON.parse(m[2]);
    if (out[table].length) out[table].at(-1)[m[1]] = value;
    else if (m[1] === "base") out.base = value;
  }
  return out;
}

const examples = join(import.meta.dirname, "..", "examples");
const poses = (n, seed) => {
  // A few poses per file: its own, and angles from a fixed sequence (every range of degrees).
  const out = [[]];
  let s = seed;
  for (let k = 0; k < 8; k++) {
    out.push(Array.from({ length: n }, () => {
      s = (s * 16807) % 2147483647;
      return (s / 2147483647) * 720 - 360;
    }));
  }
  return out;
};

// The two copies did not agree in the last bits: the chain's added radians, the rig's degrees
// (then one conversion per bone). One module can match only one of them bit for bit; it adds
// degrees (the headings it reports are then exact degrees), so a chain's joints agree with the
// old chain copy to rounding (1e-13 of the reach here), and the rigs' bit for bit.
test("a chain's joints are what view.js's forward gave to rounding, for the shipped arms and the seed", () => {
  const arms = readdirSync(join(examples, "arms")).filter((f) => f.endsWith(".toml"));
  assert.ok(arms.length >= 3);
  let differ = 0;
  for (const file of arms) {
    const arm = readFile(join(examples, "arms", file), "links");
    // An arm with joint keys (rrp.toml's slide) is a one-branch rig, not a chain: the page's
    // arm refuses it, and the old chain copy knew nothing of slides.
    const keys = ["offset", "joint", "slide", "extension", "limits"];
    if (arm.links.some((l) => keys.some((k) => k in l))) continue;
    const reach = arm.links.reduce((s, l) => s + l.length, 0);
    for (const pose of poses(arm.links.length, 7)) {
      const now = forward(arm, pose);
      const before = chainBefore(arm, pose);
      assert.equal(now.length, before.length);
      now.forEach((p, k) => close(p, before[k], 1e-13 * reach));
      differ += now.some((p, k) => p[0] !== before[k][0] || p[1] !== before[k][1]) ? 1 : 0;
      assert.deepEqual(bodyForward(chainBody(arm), pose).tips, now.slice(1), file);
    }
  }
  // Whole degrees (the files' own angles) add exactly either way.
  const seed = readFile(join(examples, "arms", "seed.toml"), "links");
  assert.deepEqual(forward(seed, []), chainBefore(seed, []));
  assert.ok(differ > 0, "the random poses show the last-bit difference the comment speaks of");
});

test("a rig's tips are bit for bit what rig.js's rigForward gave, for the shipped rigs", () => {
  const rigs = readdirSync(join(examples, "rigs")).filter((f) => f.endsWith(".toml"));
  assert.ok(rigs.length >= 2);
  for (const file of rigs) {
    const rig = readFile(join(examples, "rigs", file), "bones");
    for (const pose of poses(rig.bones.length, 11)) {
      assert.deepEqual(bodyForward(rig, pose).tips, rigBefore(rig, pose), `${file} ${pose}`);
    }
  }
});
