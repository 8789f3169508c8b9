// The static playground's solver thread: a module Web Worker that loads ikarus.js (the
// WebAssembly module) and answers the page's api.js, so that a long job (a traced path, the
// reachable region of a long arm) never freezes the page. Messages: it posts {ready: true} once
// the module is initialised (or {ready: false, error}); then each {id, path, body} gets
// {id, status, text}: 200 and the answer's text, or the server's status and `{"error": …}` (a
// body that is an ArrayBuffer is a file's bytes: /api/rig/parse?text=1's answer for them). A
// reply with `restart: true` says the module trapped (out of memory, a panic): ikarus.js has
// restarted it, but this worker's handles were made in the stopped one, so the page
// (ikarus-thread.js) replaces the worker; it also replaces one whose job outlives its budget.
//
// Character playback takes the typed path instead ({id, pose: {rig?, animation, time, targets}}):
// the worker keeps the last character file it was sent as an ikarus.Character (the page sends
// the file's text only when it changes) and answers {id, status: 200, typed: true, names,
// unsupported, numbers}: the bones' names and the file's unsupported constraints (what
// /api/pose says of the setup pose), and the pose's five numbers per bone (bit for bit the
// /api/pose answer's) — no JSON on the way. What the typed path does not take (a bone name the
// file lacks, a refused time) is asked of call("pose") with the same fields, for the server's
// status and line.
//
// Following the pointer takes a typed path too ({id, follow: {chain?: {arm, options}, start_deg,
// max_step_deg, x, y}}): the worker keeps an ikarus.Chain of the last arm and options it was sent
// (sent only when they change) and answers {id, status: 200, typed: true, numbers} with the
// chain's follow record (Chain.followHere: bit for bit /api/track's one-sample follow with
// bound_first). What the chain refuses (an arm with offsets or slides, a refused value) is asked
// of call("track") with the same fields, for the server's answer or its status and line.
//
// It loads the small module first (ikarus_core_bg.wasm: the typed handles; ready as soon as it
// is), and the full one (ikarus_wasm_bg.wasm) on the first message that needs `call`. The GET
// endpoints' answers (/api/meta, /api/arm/default, /api/rigs) do not change: `web/build` writes
// them beside this file (api-meta.json, …) and they are read from there, so the page's first
// lists need no module at all.
import * as ikarus from "./ikarus.js";

/** The GET endpoints answered from the files `web/build` writes (the full module's answers). */
const FILES = { meta: "api-meta.json", "arm/default": "api-arm-default.json", rigs: "api-rigs.json" };

ikarus.initCore().then(
  () => postMessage({ ready: true }),
  (e) => postMessage({ ready: false, error: String(e && e.message ? e.message : e) }),
);

/** The last character file: its text, its ikarus.Character, names, unsupported and output array. */
let loaded = null;

/** {status, text} of call(path, body): the server's answer or its refusal; loads the full module first. */
async function answer(path, body) {
  const file = FILES[path.replace(/^\/?(api\/)?/, "")];
  if (file) {
    const res = await fetch(new URL(file, import.meta.url));
    if (res.ok) return { status: 200, text: await res.text() };
  }
  try {
    await ikarus.init();
    return { status: 200, text: ikarus.call(path, body) };
  } catch (e) {
    return failed(e);
  }
}

/**
 * {status, text} of POST /api/rig/parse?text=1 with `bytes` (an ArrayBuffer: a `.skel`, sent as
 * application/octet-stream): the server's answer, or its status and line.
 */
async function answerBytes(bytes) {
  try {
    await ikarus.init();
    return { status: 200, text: JSON.stringify(ikarus.parseRigBytes(bytes)) };
  } catch (e) {
    return failed(e);
  }
}

/** The reply for what a job threw: its status and line; `restart` when the module trapped (the page then replaces this worker). */
function failed(e) {
  const status = e instanceof ikarus.IkarusError ? e.status : 500;
  const text = JSON.stringify({ error: e && e.message ? e.message : String(e) });
  return e instanceof ikarus.IkarusError && e.restarted ? { status, text, restart: true } : { status, text };
}

/** Whether the typed path may hand `e` to call()'s answer: a refusal, not a trap. */
const refused = (e) => e instanceof ikarus.IkarusError && !e.restarted;

/** The typed pose of `ask` ({rig?, animation, time, targets: [{bone, x, y}]}), or the JSON answer's {status, text}. */
async function pose({ rig, animation, time, targets }) {
  if (rig !== undefined && (!loaded || loaded.text !== rig)) {
    if (loaded) loaded.character.free();
    loaded = null;
    let character;
    try {
      character = new ikarus.Character(rig);
    } catch (e) {
      // The server's status and line (the small module words a bad value without its path).
      if (refused(e)) return answer("pose", JSON.stringify({ rig }));
      throw e;
    }
    loaded = { text: rig, character, names: character.bones, unsupported: character.unsupported };
  }
  if (!loaded) return { status: 500, text: JSON.stringify({ error: "ikarus-worker: a pose before its character file" }) };
  const fields = { ...(animation ? { animation, time } : {}), targets };
  const indices = targets.map((t) => loaded.names.indexOf(t.bone));
  if (indices.some((i) => i < 0)) return answer("pose", JSON.stringify({ rig: loaded.text, ...fields }));
  try {
    loaded.character.setAnimation(animation || undefined);
    const flat = new Float64Array(3 * targets.length);
    targets.forEach((t, k) => flat.set([indices[k], t.x, t.y], 3 * k));
    const numbers = new Float64Array(loaded.character.poseLen);
    loaded.character.pose(animation ? (time ?? 0) : 0, flat, numbers);
    return { status: 200, typed: true, numbers, names: loaded.names, unsupported: loaded.unsupported };
  } catch (e) {
    if (!refused(e)) throw e;
    return answer("pose", JSON.stringify({ rig: loaded.text, ...fields }));
  }
}

/** The last arm and options of a follow: {arm, options, chain (an ikarus.Chain, or null when it refused them)}. */
let following = null;

/** The typed follow of `ask` ({chain?: {arm, options}, start_deg, max_step_deg, x, y}), or call("track")'s {status, text}. */
async function follow({ chain, start_deg, max_step_deg, x, y }) {
  if (chain) {
    if (following && following.chain) following.chain.free();
    following = { ...chain, chain: null };
    try {
      following.chain = new ikarus.Chain(chain.arm, chain.options);
    } catch (e) {
      if (!refused(e)) throw e;
    }
  }
  if (!following) return { status: 500, text: JSON.stringify({ error: "ikarus-worker: a follow before its arm" }) };
  const { arm, options } = following;
  const asked = () => answer("track", JSON.stringify({ arm, options, start_deg, max_step_deg, path: [[x, y]], mode: "follow", bound_first: true }));
  if (!following.chain) return asked();
  try {
    following.chain.followHere(start_deg, x, y, max_step_deg);
  } catch (e) {
    if (!refused(e)) throw e;
    return asked();
  }
  return { status: 200, typed: true, numbers: following.chain.followRecord.slice() };
}

onmessage = async ({ data }) => {
  if (data.pose || data.follow) {
    let reply;
    try {
      reply = await (data.pose ? pose(data.pose) : follow(data.follow));
    } catch (e) {
      reply = failed(e);
    }
    if (reply.numbers) postMessage({ id: data.id, ...reply }, [reply.numbers.buffer]);
    else postMessage({ id: data.id, ...reply });
    return;
  }
  const { id, path, body } = data;
  postMessage({ id, ...(await (body instanceof ArrayBuffer ? answerBytes(body) : answer(path, body))) });
};
