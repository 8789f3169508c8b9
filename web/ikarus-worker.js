// The static playground's solver thread: a module Web Worker that loads ikarus.js (the
// WebAssembly module) and answers the page's api.js, so that a long job (a traced path, the
// reachable region of a long arm) never freezes the page. Messages: it posts {ready: true} once
// the module is initialised (or {ready: false, error}); then each {id, path, body} gets
// {id, status, text}: 200 and the answer's text, or the server's status and `{"error": …}`.
//
// Character playback takes the typed path instead ({id, pose: {rig?, animation, time, targets}}):
// the worker keeps the last character file it was sent as an ikarus.Character (the page sends
// the file's text only when it changes) and answers {id, status: 200, typed: true, names,
// unsupported, numbers}: the bones' names and the file's unsupported constraints (what
// /api/pose says of the setup pose), and the pose's five numbers per bone (bit for bit the
// /api/pose answer's) — no JSON on the way. What the typed path does not take (a bone name the
// file lacks, a refused time) is asked of call("pose") with the same fields, for the server's
// status and line.
import * as ikarus from "./ikarus.js";

ikarus.init().then(
  () => postMessage({ ready: true }),
  (e) => postMessage({ ready: false, error: String(e && e.message ? e.message : e) }),
);

/** The last character file: its text, its ikarus.Character, names, unsupported and output array. */
let loaded = null;

/** {status, text} of call(path, body): the server's answer or its refusal. */
function answer(path, body) {
  try {
    return { status: 200, text: ikarus.call(path, body) };
  } catch (e) {
    const status = e instanceof ikarus.IkarusError ? e.status : 500;
    return { status, text: JSON.stringify({ error: e && e.message ? e.message : String(e) }) };
  }
}

/** The typed pose of `ask` ({rig?, animation, time, targets: [{bone, x, y}]}), or the JSON answer's {status, text}. */
function pose({ rig, animation, time, targets }) {
  if (rig !== undefined && (!loaded || loaded.text !== rig)) {
    if (loaded) loaded.character.free();
    loaded = null;
    const setup = answer("pose", JSON.stringify({ rig }));
    if (setup.status !== 200) return setup;
    const character = new ikarus.Character(rig);
    loaded = { text: rig, character, names: character.bones, unsupported: JSON.parse(setup.text).unsupported };
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
    if (!(e instanceof ikarus.IkarusError)) throw e;
    return answer("pose", JSON.stringify({ rig: loaded.text, ...fields }));
  }
}

onmessage = ({ data }) => {
  if (data.pose) {
    let reply;
    try {
      reply = pose(data.pose);
    } catch (e) {
      reply = { status: 500, text: JSON.stringify({ error: e && e.message ? e.message : String(e) }) };
    }
    if (reply.numbers) postMessage({ id: data.id, ...reply }, [reply.numbers.buffer]);
    else postMessage({ id: data.id, ...reply });
    return;
  }
  const { id, path, body } = data;
  postMessage({ id, ...answer(path, body) });
};
