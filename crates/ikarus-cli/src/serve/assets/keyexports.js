// The keyed motion's files, from the Keys bar (keyed.js): *Frames JSON* as /api/animate answered
// it; *Frames CSV* as `ikarus animate --keys --format csv` writes it (a rig's or the arm's written
// here, keys.js's rigFramesCsv; a character's asked of the server, format csv); *GIF* from
// POST /api/render (figure motion with the body and its keys) at the canvas's size. Each file is
// named after the body: `NAME-keys.json` / `.csv` / `.gif`.
import * as api from "./api.js";
import { gifSize, saveBlob, screenLook } from "./files.js";
import { characterAnimateRequest, rigFramesCsv } from "./keys.js";

const $ = (id) => document.getElementById(id);

/**
 * Wires the Keys bar's file buttons. `state` and `canvas` are the page's; `answer()` the keyed
 * answer shown (or null), `branch()` keys.js's keyedBranch of the rig or arm shown (null for a
 * character), `sent()` the keys as requests send them (with the Length), `showError(e)` the chip's, `syncBar()` keyed.js's (the buttons' states again).
 * Returns {gifOff()}: whether the GIF cannot be made here (no server to render it).
 */
export function wireKeyExports({ state, canvas, answer, branch, sent, showError, syncBar }) {
  /** The name of the files saved: the character's file without .json, the rig's or the arm's name. */
  const bodyName = () => (state.character ? state.character.name.replace(/\.(json|skel)$/i, "") : branch().name);
  /** The keys' /api/animate body (the character's, or the rig's or arm's with the solver options), with the Length (`sent()`). */
  const request = (format) => (state.character ? characterAnimateRequest(state.character, sent(), format) : branch().request(sent(), state.options));

  async function saved(make) {
    try {
      await make();
      showError(null);
    } catch (e) {
      showError(e);
    }
  }

  /** The frames as answered (JSON), or as `ikarus animate --keys --format csv` writes them. */
  function download(format) {
    const a = answer();
    if (!a) return;
    const name = `${bodyName()}-keys.${format}`;
    if (format === "csv" && state.character) {
      saved(async () => saveBlob(new Blob([await api.post("/api/animate", request("csv"), "blob")], { type: "text/csv" }), name));
      return;
    }
    const text = format === "csv" ? rigFramesCsv(branch().rig, a) : `${JSON.stringify(a, null, 2)}\n`;
    saveBlob(new Blob([text], { type: format === "csv" ? "text/csv" : "application/json" }), name);
  }

  /** The keyed motion as a GIF at the keys' fps and the canvas's size. */
  async function downloadGif() {
    const a = answer();
    if (!a) return;
    $("key-gif").disabled = true;
    await saved(async () => {
      const size = gifSize(a.frames.length, screenLook(state, canvas));
      saveBlob(await api.render({ figure: "motion", ...request("json"), format: "gif", ...size }), `${bodyName()}-keys.gif`);
    });
    syncBar();
  }

  // The GIF is rendered by the server: without one (the static build) the button says so and
  // stays disabled (syncBar asks gifOff()).
  let gifOff = false;
  api.backend().then((b) => {
    if (b.pictures) return;
    gifOff = true;
    $("key-gif").title = "needs `ikarus serve`: the keyed motion's GIF is rendered by the server (Frames JSON and CSV are made here)";
    syncBar();
  });

  $("key-gif").addEventListener("click", downloadGif);
  $("key-frames-json").addEventListener("click", () => download("json"));
  $("key-frames-csv").addEventListener("click", () => download("csv"));
  return { gifOff: () => gifOff };
}
