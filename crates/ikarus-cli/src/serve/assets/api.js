// The JSON API of `ikarus serve` (same origin): fetch wrappers that turn an error answer into a
// Notice carrying the server's one-line message.

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
 * links and joints: `links[0].angle_deg` → `link 1 angle_deg`, `start_deg[2]` → `joint 3 start`.
 */
export function forPeople(message) {
  return message
    .replace(/\blinks\[(\d+)\]\.?/g, (_, i) => `link ${Number(i) + 1} `)
    .replace(/\b(start_deg|pose_deg|rates)\[(\d+)\]/g, (_, f, i) => `joint ${Number(i) + 1} ${f === "rates" ? "rate" : "angle"}`)
    .replace(/ {2,}/g, " ")
    .replace(/ :/g, ":");
}

/** GETs `path` and resolves with its JSON; rejects with a Notice on an error answer. */
export async function get(path) {
  const res = await fetch(path);
  if (!res.ok) throw await failure(path, res);
  return res.json();
}

/** POSTs `body` as JSON to `path`; resolves with the JSON answer, or a Blob when `as` is "blob". */
export async function post(path, body, as = "json") {
  const res = await fetch(path, {
    method: "POST",
    headers: { "content-type": "application/json" },
    body: JSON.stringify(body),
  });
  if (!res.ok) throw await failure(path, res);
  return as === "blob" ? res.blob() : res.json();
}

/** The names and defaults of the select lists: methods (with their limit modes), limit modes, eases. */
export const meta = () => get("/api/meta");

/** The server's default arm, in the arm file's shape. */
export const defaultArm = () => get("/api/arm/default");

export const solve = (body) => post("/api/solve", body);
export const animate = (body) => post("/api/animate", body);
export const workspace = (body) => post("/api/workspace", body);
/** The tip along a path (`ikarus track`): per-sample poses and a summary with the flips. */
export const track = (body) => post("/api/track", body);
/** A picture (PNG, SVG or GIF) as a Blob. */
export const render = (body) => post("/api/render", body, "blob");
