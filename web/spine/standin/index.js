// The stand-in for Spine's web runtime that the ikarus-spine add-on's tests and demo drive: a
// JavaScript object model offering the part of spine-core 4.2's documented API the add-on uses
// (Skeleton, Bone, BoneData, IkConstraint, AnimationState on one track), posed by ikarus's own
// runtime-exact posing compiled to WebAssembly (the `ikarus_core` module `bash web/build DIR`
// writes). Written from Spine's public API reference, not from Spine's code; it needs no Spine
// runtime and no licence.
//
//   import init, * as core from "DIR/ikarus_core.js";
//   await init({ module_or_path: wasmBytes });
//   const { skeleton, state } = await loadStandIn(jsonText, { core });
//   state.setAnimation(0, "walk", true);
//   state.update(dt); state.apply(skeleton); skeleton.update(dt); skeleton.updateWorldTransform(Physics.update);

import { Bone, BoneData, Inherit } from "./bone.js";
import { IkConstraint, Physics, Skeleton } from "./skeleton.js";
import { AnimationState, TrackEntry } from "./state.js";

export { AnimationState, Bone, BoneData, IkConstraint, Inherit, Physics, Skeleton, TrackEntry };

/**
 * A stand-in skeleton and animation state for the Spine JSON `jsonText`, in the setup pose with
 * its world transforms computed.
 * @param {string} jsonText a Spine 4.2 skeleton's JSON
 * @param {{core: object, memory?: WebAssembly.Memory}} options `core`: the initialised
 *   `ikarus_core` module; `memory`: its memory (default: the one `core.initSync()` returns once
 *   initialised)
 * @returns {Promise<{skeleton: Skeleton, state: AnimationState}>}
 */
export async function loadStandIn(jsonText, { core, memory } = {}) {
  if (!core || typeof core.Character !== "function") throw new Error("core: not the ikarus_core module (it has no Character)");
  const mem = memory ?? core.initSync().memory;
  let character;
  try {
    character = new core.Character(jsonText);
  } catch (e) {
    throw new Error(`jsonText: ${e.message ?? String(e)}`);
  }
  const names = character.bones();
  const data = character.boneData();
  const skeleton = new Skeleton(character, mem);
  // The setup pose's locals and IK settings.
  if (!character.sampleHere(0)) throw new Error(character.givenError);
  skeleton.views();
  const { locals, iks } = skeleton;
  for (let i = 0; i < names.length; i++) {
    const parentIndex = data[3 * i];
    const bd = new BoneData(i, names[i], parentIndex < 0 ? null : skeleton.bones[parentIndex].data);
    bd.length = data[3 * i + 1];
    bd.inherit = data[3 * i + 2];
    [bd.x, bd.y, bd.rotation, bd.scaleX, bd.scaleY, bd.shearX, bd.shearY] = locals.subarray(7 * i, 7 * i + 7);
    const parent = parentIndex < 0 ? null : skeleton.bones[parentIndex];
    const bone = new Bone(bd, skeleton, parent);
    if (parent) parent.children.push(bone);
    skeleton.bones.push(bone);
    skeleton.byName.set(bd.name, bone);
  }
  const ikNames = character.ikNames();
  const ikData = character.ikData();
  for (let k = 0; k < ikNames.length; k++) {
    const [target, first, second, uniform] = ikData.subarray(4 * k, 4 * k + 4);
    const bones = second < 0 ? [skeleton.bones[first]] : [skeleton.bones[first], skeleton.bones[second]];
    const [mix, softness, bendDirection, compress, stretch] = iks.subarray(5 * k, 5 * k + 5);
    const d = {
      name: ikNames[k],
      bones: bones.map((b) => b.data),
      target: skeleton.bones[target].data,
      mix,
      softness,
      bendDirection,
      compress: compress !== 0,
      stretch: stretch !== 0,
      uniform: uniform !== 0,
    };
    const ik = new IkConstraint(d, bones, skeleton.bones[target]);
    ik.setToSetupPose();
    skeleton.ikConstraints.push(ik);
    skeleton.ikByName.set(d.name, ik);
  }
  skeleton.data = { bones: skeleton.bones.map((b) => b.data), ikConstraints: skeleton.ikConstraints.map((k) => k.data) };
  skeleton.setToSetupPose();
  skeleton.updateWorldTransform(Physics.none);
  // A bone the default skin leaves off is posed at zeros, as the runtime leaves it.
  for (const b of skeleton.bones) b.active = !(b.a === 0 && b.b === 0 && b.c === 0 && b.d === 0);
  return { skeleton, state: new AnimationState(skeleton) };
}
