// The page's one `state` object (main.js owns it and hands it to every other module): what it
// holds, field by field, and its value when the page opens. Modules that own a part of it
// document that part's fields (timeline.js's newPlayback, rigs.js's newRigState, character.js's
// newCharacterState, keyed.js and keybody.js's newKeyed).

import { fittedCamera } from "./camera.js";
import { newOnion } from "./onion.js";
import { newPlayback } from "./timeline.js";

/** Everything of the page that changes, as it is when the page opens. */
export function newState() {
  return {
    // The arm file as JSON ({name, base, links: [{length, angle_deg, limits_deg, rate}]}), its
    // current pose (degrees) and joint positions ([[x, y], …], base first), and the goal ({x, y}, and angle_deg with a goal angle).
    arm: null,
    pose_deg: [],
    joints: [],
    goal: null,
    // The select lists' source (/api/meta) and the limit mode the reader last chose.
    meta: null,
    limitModeChoice: null,
    // The settings of the next requests, read from the controls (controls.js's readControls).
    options: {},
    ease: { kind: "sine" },
    frames: 60,
    // The orientation goal (degrees), when "Goal angle" is on; else undefined.
    goalAngle: undefined,
    // Iterations between two poses of the solver's replay ("Replay every").
    recordEvery: 1,
    // The step bound of following and traced paths, degrees (max_step_deg of /api/track).
    maxStepDeg: 10,
    // The playback duration the reader chose ("Duration", seconds), or null for the default.
    duration: null,
    // The View checkboxes.
    follow: false,
    showGhosts: true,
    showTraces: true,
    showWorkspace: false,
    // The world <-> canvas transform of the last drawing: the body's fitted view (view.js's
    // fitView, drawrig.js's rigView, drawchar.js's characterView) under the camera (camera.js's
    // viewThrough of `camera`, {zoom, x, y}). Every pick reads it.
    view: { cx: 0, cy: 0, scale: 1, w: 1, h: 1 },
    camera: fittedCamera(),
    // The onion skins: shown or not, and how many frames each side of the playhead (onion.js).
    onion: newOnion(),
    // The last /api/workspace answer and what is drawn of it, kept until the next answer arrives
    // so that the area does not blink while it recomputes: the exact region (region.js's regionOf
    // of its `boundary`) and the arm and limits it belongs to (regionKey), or, from a server that
    // sends no boundary, the sampled grid's edge (view.js's areaOutline).
    workspace: null,
    region: null,
    regionFor: null,
    areaOutline: null,
    // A goal out of the reachable region: {goal (the state.goal it is about), nearest ([x, y], the
    // nearest reachable point), distance}, from the page's region at once and then from the
    // solve's answer (the authority); drawn and told while that goal is the one shown.
    reachMiss: null,
    // The motion the timeline plays: the last /api/animate answer and its request (a GIF renders
    // the same motion), or a traced path's frames (paths.js's trackMotion; no request then).
    animation: null,
    animationRequest: null,
    // The stats of the motion being played: shown (and its status, "reached" or not) once the
    // playback ends; until then the chip says the arm is moving.
    pendingStats: null,
    // Whether the message shown is a bad field's (cleared when the field is fixed).
    fieldShown: false,
    // Paths (track.js): whether a drag draws a path, the stroke being drawn ([[x, y], …]), and the
    // last traced path, {request, answer (/api/track's), goals (the wanted path), flips (tips)}.
    drawPath: false,
    stroke: null,
    track: null,
    // The timeline's playhead, clock and duration (timeline.js's newPlayback documents the fields).
    playback: newPlayback(),
    // The via points ({x, y}, in order) the next click's motion passes through. They stay after the
    // motion, as an animator's keyframes do, until "Clear via points".
    via: [],
    // The pointer press on the canvas: {x, y, dragging}.
    press: null,
    // The rig the canvas shows and solves instead of the arm, or null (rigs.js's newRigState
    // documents its fields). The arm stays in `arm` meanwhile and comes back as it was.
    rig: null,
    // The character (a Spine or DragonBones file) the canvas poses instead, or null
    // (character.js's newCharacterState documents its fields).
    character: null,
    // Whether the character's bones are drawn over its art (the switch *Bones over the art*, artview.js).
    showBones: true,
    // Keyframes of the rig shown (keyed.js): the KEYS object of `ikarus animate --keys`, or null,
    // and the keyed motion played ({fps, duration, frames with `pose`}), or null.
    keys: null,
    motion: null,
    // Work in flight. A sequence number is bumped by each new motion so that a stale answer is
    // dropped; following keeps one request in flight and only the latest goal waiting, asked again
    // (followChases times) while the bound holds the arm back.
    jobs: { animateSeq: 0, workspaceSeq: 0, workspaceTimer: 0, followGoal: null, followBusy: false, followChases: 0, drawQueued: false },
  };
}
