// A stand-in for spine-core 4.2's `BoneData` and `Bone` (the fields and methods the Spine Runtimes
// API reference documents that the ikarus-spine add-on reads): plain objects with number fields,
// posed by ikarus (see index.js). Not Spine's code: written from the documented API.

/** Spine's `Inherit`, in the documented order (`BoneData.inherit` holds one of these numbers). */
export const Inherit = Object.freeze({
  normal: 0,
  onlyTranslation: 1,
  noRotationOrReflection: 2,
  noScale: 3,
  noScaleOrReflection: 4,
});

const degRad = Math.PI / 180;

/** What a bone is in the file: its index, name, parent's data, length, setup pose, inherit. */
export class BoneData {
  constructor(index, name, parent) {
    this.index = index;
    this.name = name;
    /** @type {BoneData | null} */
    this.parent = parent;
    this.length = 0;
    this.x = 0;
    this.y = 0;
    this.rotation = 0;
    this.scaleX = 1;
    this.scaleY = 1;
    this.shearX = 0;
    this.shearY = 0;
    this.inherit = Inherit.normal;
    this.skinRequired = false;
  }
}

/** A posed bone: its local transform (read by `updateWorldTransform`) and its world transform. */
export class Bone {
  constructor(data, skeleton, parent) {
    this.data = data;
    this.skeleton = skeleton;
    /** @type {Bone | null} */
    this.parent = parent;
    /** @type {Bone[]} */
    this.children = [];
    this.x = 0;
    this.y = 0;
    this.rotation = 0;
    this.scaleX = 1;
    this.scaleY = 1;
    this.shearX = 0;
    this.shearY = 0;
    // The applied transform: the local transform as the constraints left it.
    this.ax = 0;
    this.ay = 0;
    this.arotation = 0;
    this.ascaleX = 1;
    this.ascaleY = 1;
    this.ashearX = 0;
    this.ashearY = 0;
    this.a = 1;
    this.b = 0;
    this.c = 0;
    this.d = 1;
    this.worldX = 0;
    this.worldY = 0;
    this.active = true;
  }

  /** Sets the local transform to the setup pose's. */
  setToSetupPose() {
    const d = this.data;
    this.x = d.x;
    this.y = d.y;
    this.rotation = d.rotation;
    this.scaleX = d.scaleX;
    this.scaleY = d.scaleY;
    this.shearX = d.shearX;
    this.shearY = d.shearY;
  }

  /** The world direction of the bone's x axis, degrees. */
  getWorldRotationX() {
    return Math.atan2(this.c, this.a) / degRad;
  }

  /** The world direction of the bone's y axis, degrees. */
  getWorldRotationY() {
    return Math.atan2(this.d, this.b) / degRad;
  }

  /** The length of the world x axis. */
  getWorldScaleX() {
    return Math.hypot(this.a, this.c);
  }

  /** The length of the world y axis. */
  getWorldScaleY() {
    return Math.hypot(this.b, this.d);
  }

  /** `world` ({x, y}, skeleton world coordinates) into this bone's own frame, in place; returns it. */
  worldToLocal(world) {
    const det = this.a * this.d - this.b * this.c;
    const x = world.x - this.worldX;
    const y = world.y - this.worldY;
    world.x = (x * this.d - y * this.b) / det;
    world.y = (y * this.a - x * this.c) / det;
    return world;
  }

  /** `local` ({x, y}, this bone's own frame) into world coordinates, in place; returns it. */
  localToWorld(local) {
    const { x, y } = local;
    local.x = this.a * x + this.b * y + this.worldX;
    local.y = this.c * x + this.d * y + this.worldY;
    return local;
  }

  /**
   * A world direction (degrees) as a local rotation: the `rotation` this bone needs for its x
   * axis to point that way (exact when its world scale is uniform): the direction's angle in the
   * bone's own frame (its world matrix inverted) plus its `rotation`.
   */
  worldToLocalRotation(worldRotation) {
    const sin = Math.sin(worldRotation * degRad);
    const cos = Math.cos(worldRotation * degRad);
    const sign = this.a * this.d - this.b * this.c < 0 ? -1 : 1;
    const inBone = Math.atan2(sign * (this.a * sin - this.c * cos), sign * (this.d * cos - this.b * sin)) / degRad;
    return inBone + this.rotation;
  }

  /** A local rotation (degrees) as the world direction (degrees) of this bone's x axis at it. */
  localToWorldRotation(localRotation) {
    const r = (localRotation - this.rotation) * degRad;
    const sin = Math.sin(r);
    const cos = Math.cos(r);
    return Math.atan2(cos * this.c + sin * this.d, cos * this.a + sin * this.b) / degRad;
  }
}
