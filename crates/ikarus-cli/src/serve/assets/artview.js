// The character's art on the page: a WebGL canvas (artgl.js) laid under the page's 2D canvas
// (and over a 2D canvas of its own with the grid: the art hides the grid, the bones are drawn over it),
// drawn in the same view (zoom, pan) with each draw of the character, the art of the pose shown
// (the last /api/pose answer's `art`, characters.js) over the onion skins' art (the keyed
// motion's frames before and after the playhead, onion.js's, each posed with the atlas once and
// kept until the motion changes, drawn faded). The switch *Bones over the art* hides the bones
// (drawchar.js reads `state.showBones`). While keys play, the bones shown are the keyed frame's
// (keyed.js): the art of that frame is asked (characters.js's repose) when the pose shown is not
// the one the art was drawn for (`c.artOf`).

import * as api from "./api.js";
import { artRenderer } from "./artgl.js";
import { poseRequest } from "./character.js";
import { drawGrid, fitCanvas } from "./paint.js";
import { bendsAt, keyedTargets, localRotation } from "./keys.js";
import { onionFrames, onionMotion } from "./onion.js";

const $ = (id) => document.getElementById(id);

/**
 * The /api/pose body of the keyed motion's frame `f` of character `c` with its art: the frame's
 * time, every keyed target where the frame has it, the bends in force and the bones keyed by
 * hand (as keyed.js shows a frame), and the atlas.
 */
export function framePoseRequest(c, keys, f) {
  const turns = new Map(Object.keys(keys.rotations || {}).map((b) => [b, localRotation(f.bones, (n) => c.parentOf.get(n), b)]));
  return poseRequest({ ...c, time: f.time, targets: keyedTargets(keys, f.bones), bends: bendsAt(keys, f.time), turns });
}

/**
 * Wires the art's canvas under `canvas` (the page's 2D canvas) and the bones switch. `act` is
 * {requestDraw(), repose() (characters.js's: pose the character shown again)}. Returns {draw(view)
 * (the art of `state.character` in `view`; whether any was drawn: the 2D canvas then leaves the grid
 * and background to it), hide(), slots() (the slots last drawn), draws() (draws with art so far)}.
 */
export function wireArt(state, canvas, act) {
  const layer = document.createElement("canvas");
  layer.id = "art";
  const backdrop = document.createElement("canvas");
  backdrop.id = "art-grid";
  for (const c of [backdrop, layer]) {
    c.setAttribute("aria-hidden", "true");
    c.hidden = true;
    canvas.before(c);
  }
  const grid = backdrop.getContext("2d");
  /** The renderer, made with the first art (a page without a character makes no WebGL context). */
  let renderer;
  let drawn = 0;
  /** Draws made with art (for the frame-rate script, e2e/art-fps.mjs). */
  let draws = 0;
  /** The onion skins' art: of `motion` (with `atlas`), by frame index: the answer's art, or null while asked. */
  let onion = { motion: null, atlas: null, arts: new Map() };
  /** The frame whose art is being asked, or -1. */
  let asking = -1;
  /** The pose shown whose art was last asked (asked once: a refused pose is not asked again at each draw). */
  let askedFor = null;

  $("show-bones").addEventListener("change", (ev) => {
    state.showBones = ev.target.checked;
    act.requestDraw();
  });

  /** The onion skins to draw as art: [{art, alpha}] farthest first, asking for those not yet had. */
  function onionLayers(c) {
    const motion = state.onion && state.onion.show && state.keys ? onionMotion(state) : null;
    if (!motion) return [];
    if (onion.motion !== motion.frames || onion.atlas !== c.atlas) onion = { motion: motion.frames, atlas: c.atlas, arts: new Map() };
    const out = [];
    for (const skin of onionFrames(motion.frames, motion.t, state.onion.count)) {
      const art = onion.arts.get(skin.index);
      if (art) out.push({ art, alpha: skin.alpha, atlas: c.atlas });
      else if (art === undefined && asking < 0) ask(c, onion, skin.index);
    }
    return out;
  }

  /** Asks the art of frame `index` of the onion skins' motion; a draw follows its answer. */
  async function ask(c, skins, index) {
    asking = index;
    skins.arts.set(index, null);
    try {
      const answer = await api.pose(framePoseRequest(c, state.keys, skins.motion[index]));
      skins.arts.set(index, answer.art || null);
    } catch (_) {
      // Left out (the pose itself says what is wrong); not asked again for this motion.
    }
    asking = -1;
    act.requestDraw();
  }

  /** The WebGL renderer, or null (no WebGL, or its shaders refused: the character is drawn as bones). */
  function makeRenderer() {
    try {
      return artRenderer(layer);
    } catch (e) {
      console.warn("ikarus: the art cannot be drawn here:", e);
      return null;
    }
  }

  function hide() {
    if (renderer) renderer.clear();
    layer.hidden = true;
    backdrop.hidden = true;
    drawn = 0;
  }

  function draw(view) {
    const c = state.character;
    // The switch only where there is art to show under the bones.
    $("show-bones").parentElement.hidden = !(c && c.atlas);
    if (!c || !c.atlas) {
      hide();
      return false;
    }
    // A keyed frame shown without its art: asked (the answer brings its bones and art together).
    if (c.posed && c.artOf !== c.posed && askedFor !== c.posed) {
      askedFor = c.posed;
      act.repose();
    }
    const layers = onionLayers(c);
    if (c.art) layers.push({ art: c.art, alpha: 1, atlas: c.atlas });
    if (renderer === undefined) renderer = makeRenderer();
    if (!renderer) {
      // Said once on the chip (with the next pose) and kept while the character is shown.
      c.artNotice = c.artNotice || "atlas: this browser draws no WebGL, so the art is left out; the character is drawn as bones";
      hide();
      return false;
    }
    layer.hidden = false;
    backdrop.hidden = false;
    fitCanvas(backdrop, grid);
    drawGrid(grid, view);
    renderer.size(view.w, view.h, window.devicePixelRatio || 1);
    drawn = renderer.draw(view, layers);
    draws++;
    layer.dataset.slots = String(drawn);
    return true;
  }

  return { draw, hide, slots: () => drawn, draws: () => draws };
}
