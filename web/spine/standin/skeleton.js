// A stand-in for spine-core 4.2's `Skeleton` and `IkConstraint` (the documented fields and
// methods the ikarus-spine add-on uses), posed by ikarus's runtime-exact posing in WebAssembly:
// `updateWorldTransform` copies every bone's local transform and every IK constraint's settings
// into the module's buffers, calls `Character.worldHere` (the character's constraints applied in
// their order, the skeleton placed at x, y, scaleX, scaleY) and copies the world transforms back
// onto the bones. Nothing is allocated per call (the views are re-made only when the module's
// memory grows).

import { Bone } from "./bone.js";

/** Spine's `Physics`, in the documented order. */
export const Physics = Object.freeze({ none: 0, reset: 1, update: 2, pose: 3 });

/** Numbers per bone / IK constraint in the module's buffers (crates/ikarus-wasm character_given.rs). */
export const LOCAL = 7;
export const IK = 5;
export const WORLD = 13;

/** An IK constraint: its data, bones, target, and the settings `updateWorldTransform` reads. */
export class IkConstraint {
  constructor(data, bones, target) {
    this.data = data;
    /** @type {Bone[]} */
    this.bones = bones;
    /** @type {Bone} */
    this.target = target;
    this.mix = 1;
    this.softness = 0;
    this.bendDirection = 1;
    this.compress = false;
    this.stretch = false;
    this.active = true;
  }

  /** Sets the settings to the setup pose's (the constraint's data). */
  setToSetupPose() {
    const d = this.data;
    this.mix = d.mix;
    this.softness = d.softness;
    this.bendDirection = d.bendDirection;
    this.compress = d.compress;
    this.stretch = d.stretch;
  }
}

/** The skeleton: bones (parents first), IK constraints, placement, clock. */
export class Skeleton {
  /**
   * @param {object} character the module's `Character` handle
   * @param {WebAssembly.Memory} memory the module's memory
   */
  constructor(character, memory) {
    this.character = character;
    this.memory = memory;
    /** @type {Bone[]} */
    this.bones = [];
    /** @type {IkConstraint[]} */
    this.ikConstraints = [];
    this.x = 0;
    this.y = 0;
    this.scaleX = 1;
    this.scaleY = 1;
    this.time = 0;
    this.data = null;
    this.byName = new Map();
    this.ikByName = new Map();
    this.views();
  }

  /** (Re-)makes the views over the module's buffers when the memory's buffer changed. */
  views() {
    if (this.buffer === this.memory.buffer) return;
    const c = this.character;
    this.buffer = this.memory.buffer;
    this.locals = new Float64Array(this.buffer, c.localsPtr, LOCAL * this.character.bones().length);
    this.iks = new Float64Array(this.buffer, c.ikPtr, IK * this.character.ikNames().length);
    this.worlds = new Float64Array(this.buffer, c.worldsPtr, WORLD * this.character.bones().length);
  }

  /** The bone named `name`, or null. */
  findBone(name) {
    return this.byName.get(name) ?? null;
  }

  /** The IK constraint named `name`, or null. */
  findIkConstraint(name) {
    return this.ikByName.get(name) ?? null;
  }

  /** Advances the skeleton's clock (physics steps to it), seconds. */
  update(delta) {
    this.time += delta;
  }

  /** Every bone and IK constraint to the setup pose. */
  setToSetupPose() {
    this.setBonesToSetupPose();
    for (const k of this.ikConstraints) k.setToSetupPose();
  }

  /** Every bone to the setup pose. */
  setBonesToSetupPose() {
    for (const b of this.bones) b.setToSetupPose();
  }

  /**
   * Poses the world transforms from the bones' local transforms and the IK constraints'
   * settings, the character's constraints applied in their order.
   * @param {number} physics a `Physics` value (default none)
   */
  updateWorldTransform(physics = Physics.none) {
    if (this.memory.buffer !== this.buffer) this.views();
    const { locals, iks, worlds, bones, ikConstraints } = this;
    for (let i = 0, o = 0; i < bones.length; i++, o += LOCAL) {
      const b = bones[i];
      locals[o] = b.x;
      locals[o + 1] = b.y;
      locals[o + 2] = b.rotation;
      locals[o + 3] = b.scaleX;
      locals[o + 4] = b.scaleY;
      locals[o + 5] = b.shearX;
      locals[o + 6] = b.shearY;
    }
    for (let k = 0, o = 0; k < ikConstraints.length; k++, o += IK) {
      const c = ikConstraints[k];
      iks[o] = c.mix;
      iks[o + 1] = c.softness;
      iks[o + 2] = c.bendDirection;
      iks[o + 3] = c.compress ? 1 : 0;
      iks[o + 4] = c.stretch ? 1 : 0;
    }
    if (!this.character.worldHere(this.x, this.y, this.scaleX, this.scaleY, physics, this.time)) {
      throw new Error(`updateWorldTransform: ${this.character.givenError}`);
    }
    if (this.memory.buffer !== this.buffer) this.views();
    const w = this.worlds;
    for (let i = 0, o = 0; i < bones.length; i++, o += WORLD) {
      const b = bones[i];
      b.a = w[o];
      b.b = w[o + 1];
      b.c = w[o + 2];
      b.d = w[o + 3];
      b.worldX = w[o + 4];
      b.worldY = w[o + 5];
      b.ax = w[o + 6];
      b.ay = w[o + 7];
      b.arotation = w[o + 8];
      b.ascaleX = w[o + 9];
      b.ascaleY = w[o + 10];
      b.ashearX = w[o + 11];
      b.ashearY = w[o + 12];
    }
  }
}
