// Paths for the tip, the pure parts (no page, no server): a drawn stroke resampled into evenly
// spaced samples, the default line, circle and figure-8 around the arm, and a /api/track answer
// turned into frames the timeline plays, its flips and its one-line summary.

import { maxReach } from "./view.js";

/** At most this many samples in a drawn path (the server's cap is larger). */
export const STROKE_MAX_SAMPLES = 200;

/** Samples of a line, circle or figure-8. */
export const SHAPE_SAMPLES = 120;

/** The finest spacing of a drawn path's samples, as a fraction of the arm's reach. */
export const STROKE_SPACING = 1 / 150;

/** Frames per second of a traced path's default playback: one sample per frame of a 25 fps film. */
export const TRACK_FPS = 25;

/** The length of a polyline [[x, y], …]. */
export function polylineLength(points) {
  let sum = 0;
  for (let k = 1; k < points.length; k++) sum += Math.hypot(points[k][0] - points[k - 1][0], points[k][1] - points[k - 1][1]);
  return sum;
}

/**
 * The stroke `points` ([[x, y], …], as the pointer gave them) resampled at evenly spaced arc
 * lengths: its first and last points and samples between them, `spacing` apart or more, at most
 * `max` in all. Null when the stroke is shorter than `spacing` (a click, not a path).
 */
export function resampleStroke(points, spacing, max = STROKE_MAX_SAMPLES) {
  const pts = points.filter((p) => Number.isFinite(p[0]) && Number.isFinite(p[1]));
  const total = polylineLength(pts);
  if (!(spacing > 0) || !(total >= spacing)) return null;
  const n = Math.min(Math.max(2, max), Math.floor(total / spacing) + 1);
  const out = [pts[0].slice()];
  let seg = 1;
  let before = 0; // arc length at pts[seg - 1]
  for (let k = 1; k < n - 1; k++) {
    const s = (k * total) / (n - 1);
    let len = Math.hypot(pts[seg][0] - pts[seg - 1][0], pts[seg][1] - pts[seg - 1][1]);
    while (before + len < s && seg < pts.length - 1) {
      before += len;
      seg++;
      len = Math.hypot(pts[seg][0] - pts[seg - 1][0], pts[seg][1] - pts[seg - 1][1]);
    }
    const w = len > 0 ? Math.min(Math.max((s - before) / len, 0), 1) : 0;
    const [a, b] = [pts[seg - 1], pts[seg]];
    out.push([a[0] + w * (b[0] - a[0]), a[1] + w * (b[1] - a[1])]);
  }
  out.push(pts[pts.length - 1].slice());
  return out;
}

/**
 * The default shapes of an arm, as /api/track takes them, around the point 0.68 of the reach
 * out from the base in the middle of the first joint's range (its limits when it has them and
 * `limits` is on, else straight along x): `line` [x0, y0, x1, y1] across that direction, half
 * a reach long; `circle` [cx, cy, r] of radius 0.16 reach; `figure8` [cx, cy, a] 0.4 reach wide
 * and 0.2 high. For the seed arm (reach 6, first joint ±45°), the centre is (4.08, 0): inside
 * what the limited arm reaches, so that every shape is traced without flips.
 */
export function shapeDefaults(arm, limits = true) {
  const reach = maxReach(arm);
  const [bx, by] = arm.base || [0, 0];
  const first = arm.links[0];
  const range = limits && first && first.limits_deg;
  const phi = (range ? (range[0] + range[1]) / 2 : 0) * (Math.PI / 180);
  const [ux, uy] = [Math.cos(phi), Math.sin(phi)];
  const [cx, cy] = [bx + 0.68 * reach * ux, by + 0.68 * reach * uy];
  const half = 0.25 * reach;
  return {
    line: [cx + half * uy, cy - half * ux, cx - half * uy, cy + half * ux],
    circle: [cx, cy, 0.16 * reach],
    figure8: [cx, cy, 0.2 * reach],
  };
}

/**
 * A /api/track answer as a motion the timeline plays: one frame per sample, evenly timed
 * (sample k at k/(n−1)), each with its angles and joints.
 */
export function trackMotion(answer) {
  const n = answer.samples.length;
  const frames = answer.samples.map((s, k) => ({
    time: n > 1 ? k / (n - 1) : 0,
    angles_deg: s.angles_deg,
    joints: s.joints,
  }));
  return { arm: answer.arm, mode: answer.mode, frames };
}

/** The tip's positions at a track's flips (summary.flip_samples), for marking them. */
export function flipTips(answer) {
  return (answer.summary.flip_samples || []).map((k) => answer.samples[k].joints.at(-1));
}

/**
 * Where a plan left the path: for each run of `off_path` poses (inserted where two samples' poses
 * lie further apart than the bound, so that the arm moves between them within it), the tip's
 * positions from the sample before the run to the sample after it, [[x, y], …].
 */
export function offPathRuns(answer) {
  const runs = [];
  const samples = answer.samples;
  samples.forEach((s, k) => {
    if (s.status !== "off_path") return;
    const tip = s.joints.at(-1);
    if (k > 0 && samples[k - 1].status === "off_path") runs.at(-1).push(tip);
    else runs.push(k > 0 ? [samples[k - 1].joints.at(-1), tip] : [tip]);
    if (k + 1 < samples.length && samples[k + 1].status !== "off_path") runs.at(-1).push(samples[k + 1].joints.at(-1));
  });
  return runs;
}

/** The default playback length of a traced path, seconds: TRACK_FPS samples a second, at least 1 s. */
export const trackSeconds = (answer) => Math.max(1, answer.samples.length / TRACK_FPS);

/**
 * The page's status for a traced path: reached when every sample is, else the first other status
 * met (the poses off the path between samples are not samples).
 */
export function trackStatus(answer) {
  const other = answer.samples.find((s) => s.status !== "reached" && s.status !== "off_path");
  return other ? other.status : "reached";
}

/**
 * One line about a traced path: mode, samples reached, the poses off the path (where a plan left
 * it to move between two samples within the bound), flips, the largest step and error.
 */
export function trackSummaryText(answer) {
  const s = answer.summary;
  const parts = [
    `${answer.mode} · ${s.reached} of ${s.samples} reached`,
    `${s.flips} flip${s.flips === 1 ? "" : "s"}`,
    `largest step ${s.max_step_deg.toFixed(1)}°`,
    `error ${Number(s.max_error).toExponential(2)}`,
  ];
  if (s.off_path) parts.splice(1, 0, `${s.off_path} off path`);
  if (s.limited) parts.splice(1, 0, `${s.limited} limited`);
  return parts.join(" · ");
}
