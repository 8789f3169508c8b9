// The JSON API of ikarus, from one of two backends: `ikarus serve` (same origin, fetch), or the
// WebAssembly module of the static build (`bash web/build DIR`), which runs the server's own
// code in the page: the same requests, the same answers, the same one-line messages. The static
// build's index.html says so (<meta name="ikarus-backend" content="wasm">, written by web/build);
// the page then starts ./ikarus-worker.js, a module worker running ./ikarus.js, and if it loads
// and initialises, every JSON endpoint goes through it (no network round trip); otherwise, and
// always under `ikarus serve` (whose page has no such tag, so nothing asks it for a file it does
// not have), requests are fetched. Pictures (/api/render) need the server. The other modules
// see only the functions below; an error answer becomes a Notice carrying the one-line message.

/**
 * A failure meant for the reader rather than a fault of the page: the server's error message
 * (a bad request, an unreachable setting) or a hint. The page shows it and does not log it.
 */
export class Notice extends Error {
  constructor(message) {
    super(message);
    this.name = "Notice";
  }
}

/** The server's `{"error": …}` message of a failed answer, else "path: HTTP status". */
async function failure(path, res) {
  let message = `${path}: HTTP ${res.status}`;
  try {
    const e = await res.json();
    if (e && e.error) message = e.error;
  } catch (_) {
    /* not JSON: keep the status line */
  }
  return new Notice(forPeople(message));
}

/**
 * A server message with its indices numbered from 1, as the page's tables and labels number
 * links and joints: `links[0].angle_deg` → `link 1 angle_deg`, `start_deg[2]` → `joint 3 angle`,
 * and the start pose by name (`start_deg: joint 1 at 73.6° …` → `start pose: joint 1 at 73.6° …`).
 */
export function forPeople(message) {
  return message
    .replace(/\blinks\[(\d+)\]\.?/g, (_, i) => `link ${Number(i) + 1} `)
    .replace(/\b(start_deg|pose_deg|rates)\[(\d+)\]/g, (_, f, i) => `joint ${Number(i) + 1} ${f === "rates" ? "rate" : "angle"}`)
    .replace(/\bstart_deg: /g, "start pose: ")
    .replace(/ {2,}/g, " ")
    .replace(/ :/g, ":");
}

/**
 * The WebAssembly solver when the page is the static build and its module loads: a module Web
 * Worker (ikarus-worker.js, which imports ikarus.js) answering `ask(path, body)` with
 * {status, text}, one request at a time in order, off the page's thread so that a long job does
 * not freeze the page. ikarus-thread.js keeps it answering: a job over its budget (`?budget_ms=`,
 * 10 s by default) is answered 503 and the worker replaced, as is one whose module trapped.
 * Else null: the server answers.
 */
const wasm =
  typeof document !== "undefined" && document.querySelector('meta[name="ikarus-backend"][content="wasm"]') ? startWorker() : Promise.resolve(null);

async function startWorker() {
  try {
    const { solverThread, budgetOf } = await import("./ikarus-thread.js");
    // A new worker holds no character file nor chain: send them again with the next pose or follow.
    const forget = () => {
      workerRig = null;
      workerChain = null;
    };
    const thread = await solverThread(new URL("./ikarus-worker.js", import.meta.url), budgetOf(location.search), forget);
    return {
      ask: (path, body) => thread.ask({ path, body }),
      askPose: (ask) => thread.ask({ pose: ask }),
      askFollow: (ask) => thread.ask({ follow: ask }),
    };
  } catch (why) {
    console.warn("ikarus: the WebAssembly module did not load; asking the server instead:", why);
    return null;
  }
}

const PICTURES_NEED_SERVER = "Pictures (PNG and GIF from /api/render) are drawn by `ikarus serve`; this page runs without it";

/**
 * The module's answer to `path` as a fetch Response: 200 with the answer's text, or the status
 * and `{"error": message}` body the server answers for a refused request.
 */
async function wasmResponse(m, path, body) {
  const answer = (status, text, type = "application/json") => new Response(text, { status, headers: { "content-type": type } });
  if (path === "/api/render") return answer(501, JSON.stringify({ error: PICTURES_NEED_SERVER }));
  // A file's bytes (an ArrayBuffer, a `.skel`) go as they are: the worker answers them as the server does.
  const { status, text } = await m.ask(path, typeof body === "string" || body instanceof ArrayBuffer ? body : "");
  return answer(status, text, status === 200 && path === "/api/arm/toml" ? "application/toml" : "application/json");
}

/** fetch(path, init) through the backend: the module in the static build, else the server. */
async function send(path, init = {}) {
  const m = await wasm;
  return m ? wasmResponse(m, path, init.body) : fetch(path, init);
}

/**
 * Which backend answers: `{kind: "wasm" | "server", label, pictures}` (pictures: whether
 * /api/render can be asked).
 */
export async function backend() {
  return (await wasm)
    ? { kind: "wasm", label: "running in your browser (WebAssembly)", pictures: false }
    : { kind: "server", label: "running on ikarus serve", pictures: true };
}

/** GETs `path` and resolves with its JSON; rejects with a Notice on an error answer. */
export async function get(path) {
  const res = await send(path);
  if (!res.ok) throw await failure(path, res);
  return res.json();
}

/**
 * The character files /api/rig/parse read, by the id it answered: requests name a character by
 * its id (`{"character": ID}`), and when the backend no longer keeps it (404: it keeps a few,
 * the least recently used let go) the file is sent again once and the request retried.
 */
const characterTexts = new Map();

/** The atlas texts /api/atlas/parse read, by the id it answered (sent again on a 404 as the characters are). */
const atlasTexts = new Map();

/**
 * A texture atlas's text read by POST /api/atlas/parse (the page images stay in the page):
 * resolves with the answer ({id, pages: [{file, width, height, pma, image}], regions}) and keeps
 * the text for the id; a refusal is a Notice with the server's line.
 */
export async function parseAtlas(text) {
  const res = await send("/api/atlas/parse", { method: "POST", headers: { "content-type": "application/json" }, body: JSON.stringify({ atlas: text }) });
  if (!res.ok) throw await failure("/api/atlas/parse", res);
  const answer = await res.json();
  if (answer.id) atlasTexts.set(answer.id, text);
  return answer;
}

/** POSTs `body` as JSON to `path`; resolves with the JSON answer, or a Blob when `as` is "blob". */
export async function post(path, body, as = "json") {
  const init = { method: "POST", headers: { "content-type": "application/json" }, body: JSON.stringify(body) };
  let res = await send(path, init);
  const again = body && (characterTexts.has(body.character) || atlasTexts.has(body.atlas));
  if (res.status === 404 && again) {
    // The backend let the character file or the atlas go: both sent again (the ids are the same), then the request.
    if (characterTexts.has(body.character)) await postText("/api/rig/parse", characterTexts.get(body.character), "application/toml");
    if (atlasTexts.has(body.atlas)) await parseAtlas(atlasTexts.get(body.atlas));
    res = await send(path, init);
  }
  if (!res.ok) throw await failure(path, res);
  return as === "blob" ? res.blob() : res.json();
}

/** POSTs `body` (text of content type `type`) to `path` and resolves with the answer's text; a refusal is a Notice with the server's message. */
export async function postText(path, body, type) {
  const res = await send(path, { method: "POST", headers: { "content-type": type }, body });
  if (!res.ok) throw await failure(path, res);
  const text = await res.text();
  if (path === "/api/rig/parse" && text.includes('"id"')) {
    try {
      const id = JSON.parse(text).character?.id;
      if (id) characterTexts.set(id, body);
    } catch (_) {
      /* not a character: nothing to keep */
    }
  }
  return text;
}

/**
 * POSTs a file's bytes (an ArrayBuffer: a Spine binary export, `.skel`) to /api/rig/parse as
 * application/octet-stream, asking for the JSON text it decodes into (`?text=1`); resolves with
 * the answer (`{character, text}`, or `{rig}`) and keeps `text` for the character's id as
 * postText keeps a file's text. A file that cannot be read is a Notice with the server's line.
 */
export async function postFile(bytes) {
  const init = { method: "POST", headers: { "content-type": "application/octet-stream" }, body: bytes };
  const res = await send("/api/rig/parse?text=1", init);
  if (!res.ok) throw await failure("/api/rig/parse", res);
  const answer = await res.json();
  if (answer.character && answer.character.id && typeof answer.text === "string") characterTexts.set(answer.character.id, answer.text);
  return answer;
}

/** The names and defaults of the select lists: methods (with their limit modes), limit modes, eases. */
export const meta = () => get("/api/meta");

/** The default arm (the seed arm), in the arm file's shape. */
export const defaultArm = () => get("/api/arm/default");

/**
 * Poses and follow steps made by the WebAssembly module's typed paths (ikarus.Character and
 * ikarus.Chain in the worker, no JSON), counted for tests: `typed.poses`, `typed.follows`.
 */
export const typed = { poses: 0, follows: 0 };

/** The character file the worker holds (sent again only when it changes). */
let workerRig = null;

/**
 * A character posed (POST /api/pose's body and answer). In the static build, a pose by the
 * runtime's rules with the default skin and physics goes through the worker's typed path (the
 * file sent once, then the clip, time and targets; the answer's numbers bit for bit /api/pose's),
 * anything else through /api/pose.
 */
export async function pose(body) {
  const m = await wasm;
  const { rig: text, character, ...ask } = body;
  const rig = text ?? characterTexts.get(character);
  const typedTakes = !(body.atlas || body.ik || body.goals || body.pins || body.bends || body.rotations || body.skin || body.physics === false);
  if (!m || !typedTakes || rig === undefined) return post("/api/pose", body);
  const reply = await m.askPose(rig === workerRig ? ask : { rig, ...ask });
  if (reply.status === 200 && reply.typed) {
    workerRig = rig;
    typed.poses++;
    const n = reply.numbers;
    const bones = reply.names.map((name, i) => ({ name, x: n[5 * i], y: n[5 * i + 1], rotation_deg: n[5 * i + 2], tip: [n[5 * i + 3], n[5 * i + 4]] }));
    return { bones, unsupported: reply.unsupported };
  }
  // The worker's file is unknown after a refusal of it: send it with the next pose.
  if (reply.status !== 200) workerRig = null;
  const res = new Response(reply.text, { status: reply.status, headers: { "content-type": "application/json" } });
  if (!res.ok) throw await failure("/api/pose", res);
  return res.json();
}

/** The arm and options the worker's follow chain holds (JSON text; sent again only when they change). */
let workerChain = null;

/** The follow record's status names (ikarus.js's FOLLOW_STATUS). */
const FOLLOW_STATUS = ["reached", "limited", "unreachable", "stalled", "iteration_limit", "interrupted", "off_path"];

/**
 * One step of following the pointer: `{arm, options, start_deg, max_step_deg, x, y}` →
 * /api/track's one sample of a follow from `start_deg` toward (x, y) with `bound_first`
 * ({status, error, angles_deg, joints, step_deg}). In the static build it goes through the
 * worker's typed path (ikarus.Chain.followHere: the arm and options sent once, then the pose and
 * the goal; the numbers bit for bit /api/track's), anything it refuses through /api/track.
 */
export async function follow({ arm, options, start_deg, max_step_deg, x, y }) {
  const m = await wasm;
  const body = { arm, options, start_deg, max_step_deg, path: [[x, y]], mode: "follow", bound_first: true };
  if (!m) return (await track(body)).samples[0];
  const key = JSON.stringify([arm, options]);
  const reply = await m.askFollow(key === workerChain ? { start_deg, max_step_deg, x, y } : { chain: { arm, options }, start_deg, max_step_deg, x, y });
  if (reply.status !== 200) {
    workerChain = null;
    throw await failure("/api/track", new Response(reply.text, { status: reply.status }));
  }
  workerChain = key;
  if (!reply.typed) return JSON.parse(reply.text).samples[0];
  typed.follows++;
  const r = reply.numbers;
  const n = start_deg.length;
  const joints = [];
  for (let j = 0; j <= n; j++) joints.push([r[n + 2 * j], r[n + 2 * j + 1]]);
  return { status: FOLLOW_STATUS[r[3 * n + 4]], error: r[3 * n + 2], angles_deg: Array.from(r.subarray(0, n)), joints, step_deg: r[3 * n + 3] };
}

export const solve = (body) => post("/api/solve", body);
export const animate = (body) => post("/api/animate", body);
/** The ease `ease` ({kind, k1, k2}) at `samples` evenly spaced times: {t, s} (the library's curve). */
export const easeCurve = (ease, samples) => post("/api/ease", { ease, samples });
export const workspace = (body) => post("/api/workspace", body);
/** The tip along a path (`ikarus track`): per-sample poses and a summary with the flips. */
export const track = (body) => post("/api/track", body);
/** A picture (PNG, SVG or GIF) as a Blob; only from `ikarus serve` (backend().pictures). */
export const render = (body) => post("/api/render", body, "blob");
