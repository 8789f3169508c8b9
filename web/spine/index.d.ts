// Types of ikarus-spine (index.js). Structural: any object with the part of spine-core 4.2's
// API the add-on reads (a spine-core `Skeleton` has it) is accepted, so the package needs no
// import of @esotericsoftware/spine-core.

/** The part of a Spine 4.2 `BoneData` the add-on reads. */
export interface SpineBoneData {
  name: string;
  length: number;
  /** Spine's `Inherit`: 0 normal, 1 onlyTranslation, 2 noRotationOrReflection, 3 noScale, 4 noScaleOrReflection (or those names). */
  inherit?: number | string;
}

/** The part of a Spine 4.2 `Bone` the add-on reads (and `rotation`, which it writes). */
export interface SpineBone {
  data: SpineBoneData;
  parent: SpineBone | null;
  x: number;
  y: number;
  rotation: number;
  scaleX: number;
  scaleY: number;
  shearX: number;
  shearY: number;
  a: number;
  b: number;
  c: number;
  d: number;
  worldX: number;
  worldY: number;
  active?: boolean;
}

/** The part of a Spine 4.2 `IkConstraint` the add-on uses (it sets `mix` to 0 for one update). */
export interface SpineIkConstraint {
  bones: SpineBone[];
  mix: number;
}

/** The part of a Spine 4.2 `Skeleton` the add-on uses. */
export interface SpineSkeleton {
  bones: SpineBone[];
  ikConstraints?: SpineIkConstraint[];
  x: number;
  y: number;
  scaleX: number;
  scaleY: number;
  updateWorldTransform(physics: number): void;
}

/** What `attach` takes besides the skeleton. */
export interface AttachOptions {
  /** Per bone name, [minDeg, maxDeg]: the range of the bone's local `rotation` when ikarus moves it. */
  limits?: Record<string, [number, number]>;
  /** What apply() passes to `skeleton.updateWorldTransform` (Spine's Physics; default 3, `Physics.pose`). */
  physics?: number;
  /** Where the WebAssembly comes from (see `load`); default the file beside the module. */
  wasm?: WasmSource;
}

/** What wasm-bindgen's loader takes: bytes, a URL (string or URL), a Response or a compiled module. */
export type WasmSource = BufferSource | string | URL | Response | Promise<Response> | WebAssembly.Module;

/** A goal's options. */
export interface GoalOptions {
  /** How many bones move, from the goal's bone up (default `DEFAULT_BONES`, 2). */
  bones?: number;
  /** The bone's world direction at the goal, degrees (default: free). */
  angle?: number;
  /** The goal's weight among goals of its priority, > 0 (default 1). */
  weight?: number;
  /** Primary goals are met first; secondary ones as well as the primary ones let them (default "primary"). */
  priority?: "primary" | "secondary";
  /** The sign of the goal bone's angle to its parent (the joint at its origin): "positive" counter-clockwise, "negative" clockwise (default "any"). */
  bend?: "any" | "positive" | "negative";
}

/** One goal's outcome in a report. */
export interface GoalReport {
  /** The goal's bone name. */
  bone: string;
  /** The distance of the bone's tip from its target after apply(), on the skeleton's world numbers. */
  error: number;
}

/** What apply() returns: the same object every frame, overwritten by the next apply(). */
export interface Report {
  /** The goals in the order given. */
  goals: GoalReport[];
  /** The names of the bones whose `rotation` apply() wrote: those the solve moved (in bone order), then bones of stepped-aside IK constraints it held. */
  moved: string[];
}

/** ikarus on one skeleton. */
export declare class Ik {
  private constructor();
  /** The report apply() returns (reused). */
  readonly report: Report;
  /** Drops the goals and pins given since the last clear(). */
  clear(): void;
  /** `bone`'s tip to (x, y), skeleton world coordinates. Throws an Error naming the field and the value on bad input. */
  goal(bone: string | SpineBone, x: number, y: number, options?: GoalOptions): void;
  /** `bone`'s tip (position and direction) stays where the animation put it this frame. */
  pin(bone: string | SpineBone): void;
  /** Solves, writes the moved bones' `rotation`, updates the skeleton's world transforms. */
  apply(): Report;
  /** Frees the module memory of this skeleton; the Ik is unusable afterwards. */
  dispose(): void;
}

/** The bones a goal moves when its options name none (2: the bone and its parent). */
export declare const DEFAULT_BONES: number;
/** Spine's `Physics.pose` (3), apply()'s default physics. */
export declare const PHYSICS_POSE: number;
/** Loads the WebAssembly once; attach() calls it. */
export declare function load(source?: WasmSource): Promise<unknown>;
/** Attaches ikarus to a Spine 4.2 skeleton. */
export declare function attach(skeleton: SpineSkeleton, options?: AttachOptions): Promise<Ik>;
