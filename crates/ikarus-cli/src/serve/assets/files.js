// Downloads: the frames of the last motion or traced path (JSON, CSV), the figure (PNG, SVG)
// and the motion (GIF, rendered by /api/render), and saving a Blob under a file name. It reads
// the page's state and never writes it.

import * as api from "./api.js";
import { armForRequest } from "./controls.js";

const $ = (id) => document.getElementById(id);

/** The frames of a /api/animate answer as CSV: time, every angle, every joint's x and y. */
export function framesCsv(anim) {
  const nj = anim.frames[0] ? anim.frames[0].angles_deg.length : 0;
  const head = ["time"];
  for (let i = 0; i < nj; i++) head.push(`angle${i + 1}_deg`);
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

/** Wires the download buttons; `showError(e)` shows a failure or a hint (null clears it). */
export function wireDownloads(state, showError) {
  function framesOrSay() {
    if (state.animation) return state.animation;
    showError(new api.Notice("No motion yet: click on the canvas to make one."));
    return null;
  }

  async function renderFigure(format) {
    const button = $(`dl-${format}`);
    const label = button.textContent;
    try {
      let body;
      if (format === "gif") {
        if (!framesOrSay()) return;
        if (!state.animationRequest) {
          showError(new api.Notice("The GIF is of a clicked motion; for a traced path, `ikarus track --out path.gif` draws one."));
          return;
        }
        body = { figure: "motion", format, width: 480, height: 480, ...state.animationRequest };
      } else {
        body = {
          figure: "arm",
          format,
          width: 800,
          height: 800,
          arm: armForRequest(state.arm),
          pose_deg: state.pose_deg.slice(),
          ...(state.goal ? { goal: state.goal } : {}),
          ...(state.showWorkspace ? { workspace: true, limits: !!state.options.limits } : {}),
        };
      }
      button.disabled = true;
      button.textContent = "Rendering…";
      const blob = await api.render(body);
      showError(null);
      saveBlob(blob, `ikarus-${format === "gif" ? "motion" : "arm"}.${format}`);
    } catch (e) {
      showError(e);
    } finally {
      button.disabled = false;
      button.textContent = label;
    }
  }

  $("dl-json").addEventListener("click", () => {
    const anim = framesOrSay();
    if (!anim) return;
    // A traced path saves the /api/track answer (every sample's status and the flips).
    const [body, name] = state.track ? [state.track.answer, "ikarus-track.json"] : [anim, "ikarus-frames.json"];
    saveBlob(new Blob([JSON.stringify(body, null, 2)], { type: "application/json" }), name);
  });
  $("dl-csv").addEventListener("click", () => {
    const anim = framesOrSay();
    if (anim) saveBlob(new Blob([framesCsv(anim)], { type: "text/csv" }), "ikarus-frames.csv");
  });
  for (const format of ["png", "svg", "gif"]) $(`dl-${format}`).addEventListener("click", () => renderFigure(format));
}
