// Downloads: the frames of the last motion or traced path (JSON, CSV, with the CLI's column
// names, timed in the seconds the timeline played them), the figure (PNG, SVG: drawn by export.js as the screen is) and the motion (GIF,
// rendered by /api/render at the page's playback duration), and saving a Blob under a file
// name. It reads the page's state and never writes it.

import * as api from "./api.js";
import { figurePng, figureSvg } from "./export.js";

/** Frames per second of a downloaded GIF: a GIF's delays are hundredths of a second, so 25 fps is 4 each. */
export const GIF_FPS = 25;

const $ = (id) => document.getElementById(id);

/**
 * `time` of each frame (the motion's own: 0 to 1 for a clicked motion of N frames or a traced
 * path) in seconds of the playback, the last frame at `seconds` (the timeline's duration):
 * what was played is what is saved. Frames without a span (one frame) stay at 0.
 */
export function timesInSeconds(frames, seconds) {
  const end = frames.length ? frames[frames.length - 1].time : 0;
  const k = end > 0 && Number.isFinite(seconds) ? seconds / end : 0;
  // The last frame exactly at `seconds` (a product could miss it by a bit).
  return frames.map((f, i) => (i === frames.length - 1 && k > 0 ? seconds : f.time * k));
}

/**
 * The motion `anim` (a /api/animate answer, or the frames of a traced path or a glide) as the
 * playback showed it: its frames' `time` and its `duration` in seconds of a playback lasting
 * `seconds`.
 */
export function playedMotion(anim, seconds) {
  const times = timesInSeconds(anim.frames, seconds);
  return { ...anim, duration: times.length ? times[times.length - 1] : 0, frames: anim.frames.map((f, i) => ({ ...f, time: times[i] })) };
}

/**
 * A /api/track answer as the playback showed it: `duration` (seconds) and each sample's `time`
 * (seconds, first), one sample per frame of `frames` (paths.js's trackMotion of it).
 */
export function playedTrack(answer, frames, seconds) {
  const times = timesInSeconds(frames, seconds);
  return { ...answer, duration: times.length ? times[times.length - 1] : 0, samples: answer.samples.map((s, i) => ({ time: times[i], ...s })) };
}

/**
 * The frames of a /api/animate answer as CSV: time, every angle, every joint's x and y, in the
 * columns of `ikarus animate --format csv` (time, theta1_deg…, x0, y0, …). Give it the
 * motion as played (playedMotion) for times in seconds of the playback.
 */
export function framesCsv(anim) {
  const nj = anim.frames[0] ? anim.frames[0].angles_deg.length : 0;
  const head = ["time"];
  for (let i = 0; i < nj; i++) head.push(`theta${i + 1}_deg`);
  for (let i = 0; i <= nj; i++) head.push(`x${i}`, `y${i}`);
  const rows = anim.frames.map((f) => [f.time, ...f.angles_deg, ...f.joints.flat()].join(","));
  return [head.join(","), ...rows].join("\n") + "\n";
}

/** Offers `blob` as a download named `name`. */
export function saveBlob(blob, name) {
  const url = URL.createObjectURL(blob);
  const a = document.createElement("a");
  a.href = url;
  a.download = name;
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 1000);
}

/** The server's cap on a GIF, frames × width × height pixels (api/render.rs MAX_GIF_PIXELS). */
export const GIF_MAX_PIXELS = 100_000_000;

/** The sides a picture may have, pixels (the server's range). */
const GIF_SIDES = [16, 4096];

/**
 * What the screen shows of a motion, for its GIF: the canvas's size (CSS pixels), the shaded
 * reachable area (the exact region, or the sampled grid at its resolution) when it is shown,
 * and whether the traces and the ghosts are.
 */
export function screenLook(state, canvas) {
  const ws = state.showWorkspace && (state.region || state.areaOutline) ? state.workspace : null;
  return {
    width: canvas.clientWidth,
    height: canvas.clientHeight,
    workspace: !!ws,
    grid: ws && !ws.exact ? ws.resolution : null,
    traces: !!state.showTraces,
    ghosts: !!state.showGhosts,
  };
}

/**
 * {width, height} of a GIF of `frames` frames at the canvas's size (`look`: screenLook's), scaled
 * down keeping its aspect where the frames would pass the server's pixel cap.
 */
export function gifSize(frames, look) {
  const [w, h] = [Math.max(1, look.width), Math.max(1, look.height)];
  const fit = Math.min(1, Math.sqrt(GIF_MAX_PIXELS / (frames * w * h)), GIF_SIDES[1] / Math.max(w, h));
  const side = (v) => Math.min(Math.max(Math.floor(v * fit), GIF_SIDES[0]), GIF_SIDES[1]);
  return { width: side(w), height: side(h) };
}

/**
 * The /api/render request of the motion's GIF: the motion the page plays, sampled at GIF_FPS
 * over the page's playback duration (`seconds`), so that the GIF lasts as long as the playback
 * (to within half a frame's delay: the frame count is whole), and drawn as the screen `look`
 * (screenLook) shows it: at the canvas's size (scaled down, keeping its aspect, where the frames
 * would pass the server's pixel cap), with the area, traces and ghosts the screen shows.
 */
export function gifRequest(animationRequest, seconds, look) {
  // Every frame of a GIF is shown for its delay, the last one too, so frames 0..n span n + 1
  // delays: the motion itself takes one delay less than the playback.
  const duration = Math.max(seconds - 1 / GIF_FPS, 1 / GIF_FPS);
  const frames = Math.round(duration * GIF_FPS) + 1;
  const req = { figure: "motion", format: "gif", ...animationRequest, duration, fps: GIF_FPS };
  Object.assign(req, gifSize(frames, look), { workspace: look.workspace, traces: look.traces, ghosts: look.ghosts });
  if (look.workspace && look.grid) Object.assign(req, { grid: true, resolution: look.grid });
  delete req.frames;
  return req;
}

/**
 * Wires the download buttons; `showError(e)` shows a failure or a hint (null clears it), and
 * `duration()` is the timeline's playback duration in seconds.
 */
export function wireDownloads(state, showError, duration) {
  function framesOrSay() {
    if (state.animation) return state.animation;
    showError(new api.Notice("No motion yet: click on the canvas to make one."));
    return null;
  }

  async function renderFigure(format) {
    const button = $(`dl-${format}`);
    const label = button.textContent;
    try {
      let blob;
      if (format === "gif") {
        if (!framesOrSay()) return;
        if (!state.animationRequest) {
          showError(new api.Notice("The GIF is of a clicked motion; for a traced path, `ikarus track --out path.gif` draws one."));
          return;
        }
        button.disabled = true;
        button.textContent = "Rendering…";
        blob = await api.render(gifRequest(state.animationRequest, duration(), screenLook(state, $("plot"))));
      } else if (format === "png") {
        blob = await figurePng(state);
      } else {
        blob = new Blob([figureSvg(state)], { type: "image/svg+xml" });
      }
      showError(null);
      saveBlob(blob, `ikarus-${format === "gif" ? "motion" : state.character ? "character" : state.rig ? "rig" : "arm"}.${format}`);
    } catch (e) {
      showError(e);
    } finally {
      button.disabled = false;
      button.textContent = label;
    }
  }

  // The frames are saved in the playback's seconds (the timeline's duration), not the motion's
  // own 0 to 1.
  $("dl-json").addEventListener("click", () => {
    const anim = framesOrSay();
    if (!anim) return;
    // A traced path saves the /api/track answer (every sample's status and the flips).
    const [body, name] = state.track
      ? [playedTrack(state.track.answer, anim.frames, duration()), "ikarus-track.json"]
      : [playedMotion(anim, duration()), "ikarus-frames.json"];
    saveBlob(new Blob([JSON.stringify(body, null, 2)], { type: "application/json" }), name);
  });
  $("dl-csv").addEventListener("click", () => {
    const anim = framesOrSay();
    if (anim) saveBlob(new Blob([framesCsv(playedMotion(anim, duration()))], { type: "text/csv" }), "ikarus-frames.csv");
  });
  for (const format of ["png", "svg", "gif"]) $(`dl-${format}`).addEventListener("click", () => renderFigure(format));
  // The GIF is rendered by the server: without one (the static build) the button says so.
  api.backend().then((b) => {
    if (b.pictures) return;
    const gif = $("dl-gif");
    gif.disabled = true;
    gif.title = "needs `ikarus serve`: the GIF is rendered by the server (PNG and SVG are drawn here)";
  });
}
