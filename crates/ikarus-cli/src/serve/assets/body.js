// The page's one forward kinematics, for every body: a rig (a tree of bones) and a chain (an arm,
// a body of one branch: link i's parent is link i − 1). No DOM and no state of its own: node
// tests it (e2e/body.unit.test.mjs). view.js (the arm's joints), rig.js and drawrig.js read it.
//
// A bone, as the API's rig answers carry it:
//   parent      the parent bone's name (absent or null: a root, whose parent frame is the base's:
//               at `base`, heading +x)
//   offset      [x, y], where the bone's joint sits in its parent's frame (x along the parent's
//               heading, y to its left), from the parent's start; absent: the parent's tip
//               ([parent length, 0]), or the base for a root
//   length      from the bone's start to its tip
//   angle_deg   a revolute bone's angle (degrees, from its parent's heading); a prismatic bone's
//               fixed rest angle
//   joint       "revolute" (absent) or "prismatic": the bone slides by `extension` (length units,
//               within `limits`) along `slide` ([dx, dy], a unit vector in the parent's frame;
//               absent: along the bone's rest direction) from its joint
// The pose holds one joint value per bone (bone order): degrees for a revolute bone, a length for
// a prismatic one; a missing value is the bone's own (`angle_deg`, or `extension`, 0 if none).

export const DEG = Math.PI / 180;

const isRoot = (b) => b.parent === undefined || b.parent === null;

/** Whether `bone` is prismatic (its joint value is a length along its slide). */
export const isPrismatic = (bone) => bone.joint === "prismatic";

/** A bone's own joint value: its angle (degrees) or, prismatic, its extension (0 if none). */
export const restValue = (bone) => (isPrismatic(bone) ? bone.extension ?? 0 : bone.angle_deg);

/** Bone indices with every parent before its children (roots and siblings in file order). */
export function boneOrder(body) {
  const index = new Map(body.bones.map((b, i) => [b.name, i]));
  const children = body.bones.map(() => []);
  const roots = [];
  body.bones.forEach((b, i) => {
    const p = isRoot(b) ? undefined : index.get(b.parent);
    if (p === undefined) roots.push(i);
    else children[p].push(i);
  });
  const order = [];
  const seen = new Set();
  // Depth first without recursion; a bone is visited once (a cycle, which the server refuses,
  // would leave its bones out rather than loop).
  const stack = roots.slice().reverse();
  while (stack.length && order.length < body.bones.length) {
    const i = stack.pop();
    if (seen.has(i)) continue;
    seen.add(i);
    order.push(i);
    for (let k = children[i].length - 1; k >= 0; k--) stack.push(children[i][k]);
  }
  return order;
}

/**
 * A chain (an arm: {base, links}) as a body of one branch: link i is bone `link{i + 1}`, whose
 * parent is link i. The links' keys (length, angle_deg, limits_deg, and offset, joint, slide,
 * extension, limits) carry over.
 */
export function chainBody(arm) {
  return {
    name: arm.name,
    base: arm.base || [0, 0],
    bones: arm.links.map((link, i) => ({ ...link, name: `link${i + 1}`, parent: i === 0 ? null : `link${i}` })),
  };
}

/**
 * Forward kinematics of `pose` (joint values in bone order, see above), in world coordinates:
 *   starts          [x, y] per bone, where it starts (its joint moved along its slide)
 *   tips            [x, y] per bone, start + length · (cos h, sin h)
 *   headings        each bone's direction from +x, degrees: its parent's plus its angle
 *   parentHeadings  the direction its angle is measured from (its parent's, 0 for a root)
 *   joints          [x, y] per bone, where its joint sits (the start of a revolute bone; for a
 *                   prismatic one, the sleeve's end the bone slides from)
 *   slides          per bone, the slide's world direction [dx, dy] (prismatic), else null
 * Headings add in degrees and turn into radians once per bone.
 */
export function bodyForward(body, pose = []) {
  const n = body.bones.length;
  const index = new Map(body.bones.map((b, i) => [b.name, i]));
  const base = body.base || [0, 0];
  const out = { starts: new Array(n), tips: new Array(n), headings: new Array(n), parentHeadings: new Array(n), joints: new Array(n), slides: new Array(n) };
  for (const i of boneOrder(body)) {
    const b = body.bones[i];
    const p = isRoot(b) ? undefined : index.get(b.parent);
    const from = p === undefined ? 0 : out.headings[p];
    // The parent's frame: its origin (the parent's start, or the base) and heading.
    const origin = p === undefined ? base : out.starts[p];
    const [c, s] = [Math.cos(from * DEG), Math.sin(from * DEG)];
    const inFrame = ([x, y]) => [origin[0] + c * x - s * y, origin[1] + s * x + c * y];
    const joint = b.offset ? inFrame(b.offset) : p === undefined ? [base[0], base[1]] : out.tips[p].slice();
    const value = pose[i] ?? restValue(b);
    let start = joint;
    let h;
    if (isPrismatic(b)) {
      h = from + b.angle_deg;
      const [dx, dy] = b.slide ?? [Math.cos(b.angle_deg * DEG), Math.sin(b.angle_deg * DEG)];
      const dir = [c * dx - s * dy, s * dx + c * dy];
      start = [joint[0] + value * dir[0], joint[1] + value * dir[1]];
      out.slides[i] = dir;
    } else {
      h = from + value;
      out.slides[i] = null;
    }
    out.joints[i] = joint;
    out.starts[i] = [start[0], start[1]];
    out.tips[i] = [start[0] + b.length * Math.cos(h * DEG), start[1] + b.length * Math.sin(h * DEG)];
    out.headings[i] = h;
    out.parentHeadings[i] = from;
  }
  return out;
}
