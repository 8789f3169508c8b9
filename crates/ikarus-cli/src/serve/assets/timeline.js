// The timeline under the canvas: plays the last motion at the display's rate, interpolating
// between its frames (view.js's poseAt), over a duration the reader sets or one proportional to
// the joint-space distance; play, pause, replay, a scrubber, the time, a small plot of the
// ease's s(t) with the playhead, and the buttons of the solver's iterations and the via points.
// A tap of Space plays and pauses when focus is not in a field or on a button (viewctl.js tells
// a tap from Space held to pan); `,` and `.` step one frame back and forward (on a rig or a
// character the left and right arrows too: on the arm they nudge its goal); with Loop ticked the
// playback starts again at the end instead of stopping (a view setting, not an undo step).
//
// It owns `state.playback` (below) and reads `state.animation` and `state.animationRequest`;
// everything else goes through main.js's actions.

import { fitCanvas } from "./paint.js";
import * as api from "./api.js";
import { ownsKeys } from "./input.js";
import { autoDuration, easeAt, freeJoints, jointDistance, poseAt } from "./view.js";

const $ = (id) => document.getElementById(id);

/** Steps of the scrubber over the whole motion. */
export const SCRUB_STEPS = 1000;

/** Samples of the ease plotted (from /api/ease): every 96th of the motion's time. */
const EASE_SAMPLES = 97;

/**
 * A fresh `state.playback`:
 *   u         the playhead, normalised motion time in [0, 1]
 *   playing   whether the clock runs
 *   clock     while playing, the anchor {wall (ms), u}: u grows by elapsed seconds / duration
 *   raf       the pending animation frame's id
 *   index     the frame at or before the playhead (draw.js draws ghosts and traces up to it)
 *   free      per joint, whether it interpolates the short way round (no limits to respect)
 *   distance  the motion's joint-space distance in radians (for the default duration)
 *   chosen    the duration the reader typed, in seconds, or null for the default
 *   auto      the default duration of this motion in seconds (a traced path's), or null for
 *             the one proportional to the joint-space distance
 *   ease      the ease the motion was made with ({kind, k1, k2}), for the s(t) plot
 *   solver    whether the motion is the solver's recorded iterations (from_solve)
 *   posed     whether the arm shows the playhead's pose (false once something else moved it)
 *   clip      a character's clip or a keyed motion played instead of a motion (characters.js,
 *             keyed.js): {seconds (its duration), fps (its frames per second; 30 if not
 *             given), show(t) (shows it at t seconds)}, or null
 */
export function newPlayback() {
  return { u: 0, playing: false, clock: null, raf: 0, index: 0, free: [], distance: 0, chosen: null, auto: null, ease: null, solver: false, posed: false, clip: null };
}

/**
 * Wires the timeline's controls. `act` is {showPose(angles, joints?), draw(), toggleSolver(),
 * clearVia(), ended(), canPlay(), arrowsStep()} (ended: the playback reached the end of the motion; canPlay:
 * whether the fields allow playing, else it has said why; arrowsStep: whether the arrow keys
 * step frames). Returns {load(), unload(), detach(),
 * play(), pause(), toggle(), replay(), seek(u), step(n), choose(seconds), duration(), sync(), loadClip(clip)}.
 */
export function wireTimeline(state, act) {
  const pb = state.playback;
  const frames = () => (state.animation && state.animation.frames) || [];
  const loaded = () => !!pb.clip || frames().length > 0;
  const auto = () => pb.auto ?? autoDuration(pb.distance);
  // A clip plays at its own pace (seconds are the file's): the Duration field is the motions'.
  const duration = () => (pb.clip ? pb.clip.seconds : pb.chosen ?? auto());

  function phase() {
    if (!loaded()) return "none";
    if (pb.playing) return "playing";
    return pb.u >= 1 ? "ended" : "paused";
  }

  /** The bar shows the playhead, the time, what can be pressed, and the s(t) plot. */
  function sync() {
    const has = loaded();
    const p = phase();
    document.body.dataset.playback = p;
    $("timeline").dataset.u = String(pb.u);
    $("timeline").dataset.source = pb.solver ? "solver" : "motion";
    const play = $("play");
    play.textContent = pb.playing ? "❚❚ Pause" : "▶ Play";
    play.setAttribute("aria-label", pb.playing ? "Pause" : "Play");
    for (const id of ["play", "replay", "scrubber"]) $(id).disabled = !has;
    $("solver").disabled = !state.animationRequest;
    $("solver").setAttribute("aria-pressed", String(pb.solver));
    const scrub = $("scrubber");
    if (document.activeElement !== scrub || pb.playing) scrub.value = String(Math.round(pb.u * SCRUB_STEPS));
    const d = duration();
    $("playtime").textContent = has ? `${(pb.u * d).toFixed(2)} / ${d.toFixed(2)} s` : "– / – s";
    $("duration").placeholder = `auto ${auto().toFixed(1)}`;
    const via = state.via.length;
    const clear = $("clear-via");
    clear.disabled = via === 0;
    clear.textContent = via === 0 ? "No via points" : `Clear ${via} via point${via === 1 ? "" : "s"}`;
    drawEase();
  }

  /** Ease curves from the backend by their request ({kind, k1, k2}): the curve, null while asked, false if refused. */
  const curves = new Map();

  /** The backend's curve of `ease`, or null until it has come (then the bar is drawn again). */
  function curveOf(ease) {
    const key = JSON.stringify(ease);
    if (!curves.has(key)) {
      curves.set(key, null);
      api.easeCurve(ease, EASE_SAMPLES).then(
        (c) => {
          curves.set(key, c);
          sync();
        },
        () => curves.set(key, false),
      );
    }
    return curves.get(key) || null;
  }

  /** The ease's s(t) over [0, 1] (the backend's samples), the playhead's time as a line and its progress as a dot. */
  function drawEase() {
    const canvas = $("ease-plot");
    const ctx = canvas.getContext("2d");
    fitCanvas(canvas, ctx);
    const w = canvas.clientWidth;
    const h = canvas.clientHeight;
    const m = 4;
    const X = (t) => m + t * (w - 2 * m);
    const Y = (s) => h - m - s * (h - 2 * m);
    ctx.clearRect(0, 0, w, h);
    ctx.strokeStyle = "#e7eaee";
    ctx.lineWidth = 1;
    ctx.strokeRect(m + 0.5, m + 0.5, w - 2 * m - 1, h - 2 * m - 1);
    const curve = curveOf(pb.ease || state.ease);
    if (!curve) return;
    ctx.strokeStyle = "#26324a";
    ctx.lineWidth = 1.5;
    ctx.beginPath();
    curve.t.forEach((t, i) => {
      if (i === 0) ctx.moveTo(X(t), Y(curve.s[i]));
      else ctx.lineTo(X(t), Y(curve.s[i]));
    });
    ctx.stroke();
    if (!loaded()) return;
    ctx.strokeStyle = "#ec7f2d";
    ctx.beginPath();
    ctx.moveTo(X(pb.u), m);
    ctx.lineTo(X(pb.u), h - m);
    ctx.stroke();
    ctx.fillStyle = "#ec7f2d";
    ctx.beginPath();
    ctx.arc(X(pb.u), Y(easeAt(curve, pb.u)), 3, 0, 2 * Math.PI);
    ctx.fill();
  }

  /** Moves the playhead to `u` and shows the pose there. */
  function show(u) {
    const f = frames();
    pb.u = Math.min(Math.max(u, 0), 1);
    if (pb.clip) {
      pb.posed = true;
      pb.clip.show(pb.u * pb.clip.seconds);
      sync();
      return;
    }
    const r = poseAt(f, pb.u, pb.free, pb.index);
    pb.index = r.index;
    pb.posed = true;
    act.showPose(r.angles, r.w === 0 ? f[r.index].joints : undefined);
    act.draw();
    sync();
  }

  function tick(now) {
    pb.raf = 0;
    if (!pb.playing) return;
    let u = pb.clock.u + Math.max(0, now - pb.clock.wall) / 1000 / duration();
    if (u >= 1 && $("loop").checked) {
      // Looping: on from the start by as much as it ran past the end.
      u %= 1;
      pb.clock = { wall: now, u };
      pb.loops = (pb.loops || 0) + 1;
      document.body.dataset.loops = String(pb.loops);
    } else if (u >= 1) {
      pb.playing = false;
      pb.clock = null;
    }
    show(u);
    if (pb.playing) pb.raf = requestAnimationFrame(tick);
    else if (act.ended) act.ended();
  }

  function play() {
    if (!loaded() || pb.playing || (act.canPlay && !act.canPlay())) return;
    if (pb.u >= 1) pb.u = 0;
    pb.playing = true;
    pb.clock = { wall: performance.now(), u: pb.u };
    pb.raf = requestAnimationFrame(tick);
    sync();
  }

  function pause() {
    if (!pb.playing) return;
    pb.playing = false;
    pb.clock = null;
    cancelAnimationFrame(pb.raf);
    pb.raf = 0;
    sync();
  }

  const toggle = () => (pb.playing ? pause() : play());

  function replay() {
    pause();
    pb.u = 0;
    pb.index = 0;
    play();
  }

  function seek(u) {
    pause();
    if (!loaded()) return;
    show(u);
    // Scrubbed to the end: the motion has been seen to its end.
    if (pb.u >= 1 && act.ended) act.ended();
  }

  /**
   * The playhead `n` frames on (back for a negative `n`), paused, within the motion: a clip's or
   * keyed motion's frames at its fps (frame ⌊t·fps⌉ then `n` more), a motion's frames one by one.
   */
  function step(n) {
    pause();
    if (!loaded()) return;
    if (pb.clip) {
      const fps = pb.clip.fps || 30;
      const d = pb.clip.seconds;
      const last = Math.floor(d * fps + 1e-9);
      const k = Math.min(Math.max(Math.round(pb.u * d * fps) + n, 0), last);
      show(k / fps / d);
    } else {
      const last = Math.max(frames().length - 1, 1);
      show((Math.round(pb.u * last) + n) / last);
    }
    if (pb.u >= 1 && act.ended) act.ended();
  }

  /**
   * Takes `state.animation` (made by `request`) as the motion to play, the playhead at 0;
   * `seconds` is its default duration (else one proportional to its joint-space distance).
   */
  function load(request, solver = false, seconds = null) {
    pause();
    pb.u = 0;
    pb.index = 0;
    pb.solver = solver;
    pb.auto = seconds;
    pb.ease = request.ease;
    pb.free = freeJoints(request.arm, !!(request.options && request.options.limits));
    pb.distance = jointDistance(frames());
    if (loaded()) show(0);
    else sync();
  }

  /**
   * Takes a character's clip ({seconds > 0, show(t)}) as what the timeline plays, the playhead
   * at 0 (shown at once).
   */
  function loadClip(clip) {
    unload();
    pb.clip = clip;
    show(0);
  }

  /**
   * The duration the reader chose (seconds, the *Duration* field once checked), or null for the
   * default; a motion playing goes on from its playhead at the new pace.
   */
  function choose(seconds) {
    if (pb.chosen === seconds) return;
    pb.chosen = seconds;
    if (pb.playing) pb.clock = { wall: performance.now(), u: pb.u };
    sync();
  }

  /** Something else moved the arm (following the pointer): the playhead no longer shows it. */
  function detach() {
    pause();
    pb.posed = false;
  }

  /** No motion any more (the arm changed, the pose was reset). */
  function unload() {
    pause();
    pb.u = 0;
    pb.index = 0;
    pb.solver = false;
    pb.posed = false;
    pb.ease = null;
    pb.auto = null;
    pb.distance = 0;
    pb.clip = null;
    sync();
  }

  $("play").addEventListener("click", toggle);
  $("replay").addEventListener("click", replay);
  $("scrubber").addEventListener("input", (ev) => seek(Number(ev.target.value) / SCRUB_STEPS));
  $("solver").addEventListener("click", () => act.toggleSolver());
  $("clear-via").addEventListener("click", () => act.clearVia());
  new ResizeObserver(drawEase).observe($("ease-plot"));
  document.addEventListener("keydown", (ev) => {
    if (ev.ctrlKey || ev.altKey || ev.metaKey || ownsKeys(ev.target, ev.key)) return;
    const arrows = act.arrowsStep && act.arrowsStep();
    const n = ev.key === "," || (arrows && ev.key === "ArrowLeft") ? -1 : ev.key === "." || (arrows && ev.key === "ArrowRight") ? 1 : 0;
    if (!n || !loaded()) return;
    ev.preventDefault();
    step(n);
  });

  return { load, loadClip, unload, detach, play, pause, toggle, replay, seek, step, choose, duration, sync };
}
