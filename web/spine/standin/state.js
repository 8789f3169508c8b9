// A stand-in for spine-core 4.2's `AnimationState` on one track: `setAnimation(0, name, loop)`,
// `update(delta)`, `apply(skeleton)`. `apply` samples the animation at the track's time with
// ikarus (`Character.sampleHere`) and writes what the animation keys (and only that, as a
// runtime's timelines do) into the bones' local transforms and the IK constraints' settings.

import { IK, LOCAL } from "./skeleton.js";

/** The animation playing on track 0. */
export class TrackEntry {
  constructor(animation, loop) {
    this.animation = animation;
    this.loop = loop;
    this.trackTime = 0;
    this.timeScale = 1;
  }

  /** The animation's time: the track's time, wrapped when looping, held at the end otherwise. */
  getAnimationTime() {
    const d = this.animation.duration;
    if (this.loop) return d > 0 ? this.trackTime % d : 0;
    return Math.min(this.trackTime, d);
  }
}

/** One track of animation over a stand-in skeleton's character. */
export class AnimationState {
  constructor(skeleton) {
    this.skeleton = skeleton;
    /** @type {(TrackEntry | null)[]} */
    this.tracks = [null];
    this.timeScale = 1;
    this.keyedLocals = new Uint8Array(0);
    this.keyedIks = new Uint8Array(0);
  }

  /**
   * Plays the animation `name` on track 0 from its start.
   * @returns {TrackEntry}
   */
  setAnimation(track, name, loop = false) {
    if (track !== 0) throw new Error(`track: ${track}: the stand-in plays track 0 only`);
    const c = this.skeleton.character;
    try {
      c.setAnimation(name);
    } catch (e) {
      throw new Error(e.message ?? String(e));
    }
    this.keyedLocals = c.keyedLocals();
    this.keyedIks = c.keyedIks();
    const entry = new TrackEntry({ name, duration: c.duration }, loop);
    this.tracks[0] = entry;
    return entry;
  }

  /** The entry on `track`, or null. */
  getCurrent(track) {
    return this.tracks[track] ?? null;
  }

  /** Advances the tracks' time, seconds. */
  update(delta) {
    const e = this.tracks[0];
    if (e) e.trackTime += delta * this.timeScale * e.timeScale;
  }

  /** Writes the animation at the track's time into `skeleton`'s bones and IK constraints. */
  apply(skeleton) {
    const e = this.tracks[0];
    if (!e) return false;
    const c = skeleton.character;
    if (!c.sampleHere(e.getAnimationTime())) throw new Error(`apply: ${c.givenError}`);
    if (skeleton.memory.buffer !== skeleton.buffer) skeleton.views();
    const { locals, iks, bones, ikConstraints } = skeleton;
    const keyed = this.keyedLocals;
    for (let i = 0, o = 0; i < bones.length; i++, o += LOCAL) {
      const b = bones[i];
      if (keyed[o]) b.x = locals[o];
      if (keyed[o + 1]) b.y = locals[o + 1];
      if (keyed[o + 2]) b.rotation = locals[o + 2];
      if (keyed[o + 3]) b.scaleX = locals[o + 3];
      if (keyed[o + 4]) b.scaleY = locals[o + 4];
      if (keyed[o + 5]) b.shearX = locals[o + 5];
      if (keyed[o + 6]) b.shearY = locals[o + 6];
    }
    for (let k = 0, o = 0; k < ikConstraints.length; k++, o += IK) {
      if (!this.keyedIks[k]) continue;
      const ik = ikConstraints[k];
      ik.mix = iks[o];
      ik.softness = iks[o + 1];
      ik.bendDirection = iks[o + 2];
      ik.compress = iks[o + 3] !== 0;
      ik.stretch = iks[o + 4] !== 0;
    }
    return true;
  }
}
