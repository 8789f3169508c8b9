// The static playground's solver thread: a module Web Worker that loads ikarus.js (the
// WebAssembly module) and answers the page's api.js, so that a long job (a traced path, the
// reachable region of a long arm) never freezes the page. Messages: it posts {ready: true} once
// the module is initialised (or {ready: false, error}); then each {id, path, body} gets
// {id, status, text}: 200 and the answer's text, or the server's status and `{"error": …}`.
import * as ikarus from "./ikarus.js";

ikarus.init().then(
  () => postMessage({ ready: true }),
  (e) => postMessage({ ready: false, error: String(e && e.message ? e.message : e) }),
);

onmessage = ({ data: { id, path, body } }) => {
  try {
    postMessage({ id, status: 200, text: ikarus.call(path, body) });
  } catch (e) {
    const status = e instanceof ikarus.IkarusError ? e.status : 500;
    postMessage({ id, status, text: JSON.stringify({ error: e && e.message ? e.message : String(e) }) });
  }
};
