// A small hand-made skeleton with the part of Spine 4.2's Skeleton API that ikarus-spine reads,
// for the package's tests that do not need a real character (the stand-in, web/spine/standin/,
// poses real ones). Bones inherit normally; world transforms follow Spine's documented bone
// transform (local a b c d from rotation, scale and shear; world = parent's world × local; the
// skeleton's x, y, scaleX, scaleY place the root). One kind of IK constraint: a single bone aimed
// at a target bone, blended by `mix`, applied after the bones, as an IK constraint applies on the
// bones' applied rotation without changing their `rotation`.

const rad = Math.PI / 180;

/** A Bone with Spine's fields. */
function bone(name, parent, length, x, y, rotation) {
  return {
    data: { name, length, inherit: 0, index: 0, parent: parent ? parent.data : null },
    parent,
    x,
    y,
    rotation,
    scaleX: 1,
    scaleY: 1,
    shearX: 0,
    shearY: 0,
    a: 1,
    b: 0,
    c: 0,
    d: 1,
    worldX: 0,
    worldY: 0,
    active: true,
  };
}

/** Sets `b`'s world numbers from its parent's and the local transform with rotation `rotation`. */
function place(skeleton, b, rotation) {
  const ry = rotation + 90 + b.shearY;
  const la = Math.cos((rotation + b.shearX) * rad) * b.scaleX;
  const lb = Math.cos(ry * rad) * b.scaleY;
  const lc = Math.sin((rotation + b.shearX) * rad) * b.scaleX;
  const ld = Math.sin(ry * rad) * b.scaleY;
  const p = b.parent;
  if (!p) {
    const sx = skeleton.scaleX;
    const sy = skeleton.scaleY;
    b.a = la * sx;
    b.b = lb * sx;
    b.c = lc * sy;
    b.d = ld * sy;
    b.worldX = b.x * sx + skeleton.x;
    b.worldY = b.y * sy + skeleton.y;
    return;
  }
  b.worldX = p.a * b.x + p.b * b.y + p.worldX;
  b.worldY = p.c * b.x + p.d * b.y + p.worldY;
  b.a = p.a * la + p.b * lc;
  b.b = p.a * lb + p.b * ld;
  b.c = p.c * la + p.d * lc;
  b.d = p.c * lb + p.d * ld;
}

/**
 * root ─ hip ┬ upper ─ lower ─ hand      (an arm, 50 + 40 + 15 long)
 *            ├ thigh ─ shin ─ foot        (a leg; `foot-ik` aims the foot at `foot-target`)
 *            └ tail
 * root ─ foot-target
 */
export function toySkeleton() {
  const root = bone("root", null, 0, 0, 0, 0);
  const hip = bone("hip", root, 20, 0, 100, 90);
  const upper = bone("upper", hip, 50, 20, 0, -30);
  const lower = bone("lower", upper, 40, 50, 0, 20);
  const hand = bone("hand", lower, 15, 40, 0, 10);
  const thigh = bone("thigh", hip, 45, 0, 0, 180);
  const shin = bone("shin", thigh, 40, 45, 0, 10);
  const foot = bone("foot", shin, 20, 40, 0, 80);
  const tail = bone("tail", hip, 30, 0, 0, 135);
  const target = bone("foot-target", root, 0, 30, 10, 0);
  const bones = [root, hip, upper, lower, hand, thigh, shin, foot, tail, target];
  bones.forEach((b, i) => (b.data.index = i));
  const footIk = { data: { name: "foot-ik" }, bones: [foot], target, mix: 1, bendDirection: 1, active: true };
  const applied = new Float64Array(bones.length);
  const skeleton = {
    bones,
    ikConstraints: [footIk],
    x: 0,
    y: 0,
    scaleX: 1,
    scaleY: 1,
    updates: 0,
    physics: [],
    findBone: (name) => bones.find((b) => b.data.name === name) ?? null,
    findIkConstraint: (name) => (name === "foot-ik" ? footIk : null),
    updateWorldTransform(physics) {
      this.updates++;
      this.lastPhysics = physics;
      for (let i = 0; i < bones.length; i++) {
        applied[i] = bones[i].rotation;
        place(this, bones[i], applied[i]);
      }
      if (footIk.mix !== 0) {
        // Aim the foot's x axis at the target: turn its local rotation by the world angle missing.
        const f = footIk.bones[0];
        const want = Math.atan2(target.worldY - f.worldY, target.worldX - f.worldX) / rad;
        let turn = want - Math.atan2(f.c, f.a) / rad;
        turn -= 360 * Math.round(turn / 360);
        const i = bones.indexOf(f);
        applied[i] = f.rotation + footIk.mix * turn;
        for (let j = i; j < bones.length; j++) if (j === i || isBelow(bones[j], f)) place(this, bones[j], applied[j]);
      }
    },
  };
  skeleton.updateWorldTransform(0);
  return skeleton;
}

const isBelow = (b, above) => {
  for (let p = b.parent; p; p = p.parent) if (p === above) return true;
  return false;
};

/** The tip of `b` (its origin plus its length along its x axis) in world coordinates. */
export function tip(b) {
  return [b.worldX + b.a * b.data.length, b.worldY + b.c * b.data.length];
}
