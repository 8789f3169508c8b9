// The form fields of the panel <-> the settings of a request: the select lists filled from
// /api/meta, which fields are enabled, the solver options, ease and frame count read from the
// fields, the links table, and the arm as a request sends it. It owns no state: the page's state
// lives in main.js, and the links table reports its edits through callbacks.

const $ = (id) => document.getElementById(id);

/** Limit modes the select offers: every one but "ignore", which is the limits checkbox turned off. */
const offeredLimitModes = (meta) => meta.limit_modes.filter((m) => m.name !== "ignore");

function fillSelect(select, choices, selected) {
  select.textContent = "";
  for (const c of choices) {
    const option = new Option(c.label, c.name, false, c.name === selected);
    option.title = c.summary;
    select.append(option);
  }
}

/** Fills the method, limit-mode and ease lists and the k1/k2 fields from a /api/meta answer. */
export function fillSelects(meta) {
  fillSelect($("method"), meta.methods, meta.default_method);
  fillSelect($("limit-mode"), offeredLimitModes(meta), meta.default_limit_mode);
  fillSelect($("ease"), meta.eases, meta.default_ease);
  $("k1").value = String(meta.default_k1);
  $("k2").value = String(meta.default_k2);
}

/**
 * Keeps the limit-mode list consistent with the chosen method: modes the method does not honour
 * are disabled, and if the selected one is among them the list shows `preferred` (the reader's
 * last choice) when the method supports it, else the method's default. Returns the mode shown.
 */
export function syncLimitModes(meta, preferred) {
  const method = meta.methods.find((m) => m.name === $("method").value);
  const select = $("limit-mode");
  if (!method) return select.value;
  for (const option of select.options) option.disabled = !method.limit_modes.includes(option.value);
  if (method.limit_modes.includes(preferred)) select.value = preferred;
  else if (!method.limit_modes.includes(select.value)) select.value = method.default_limit_mode;
  return select.value;
}

/** Enables the fields that matter for the current method, limits and ease. */
export function syncEnabled() {
  const method = $("method").value;
  $("lambda").disabled = method !== "dls" && method !== "lm";
  $("limit-mode").disabled = !$("limits").checked;
  const parent = $("ease").value === "parent";
  $("k1").disabled = !parent;
  $("k2").disabled = !parent;
}

/** A number field's value, or undefined when it is empty. */
function num(id) {
  const v = $(id).value.trim();
  return v === "" ? undefined : Number(v);
}

const NUMBER_OPTIONS = [
  ["restarts", "restarts"],
  ["lambda", "lambda"],
  ["tolerance", "tolerance"],
  ["max_iterations", "max-iterations"],
  ["record_every", "record-every"],
];

/**
 * The settings of the next requests, read from the fields: `options` (a request's solver
 * options; an empty field is left to the server's default), `ease`, `frames` and `maxStepDeg`
 * (the step bound of following and traced paths, 10° when empty). The joint rates come from
 * the links.
 */
export function readControls(links) {
  const options = { method: $("method").value, limits: $("limits").checked };
  if (options.limits) options.limit_mode = $("limit-mode").value;
  for (const [key, id] of NUMBER_OPTIONS) {
    const v = num(id);
    if (v !== undefined) options[key] = v;
  }
  options.rates = links.map((l) => (l.rate === undefined ? 1 : l.rate));
  const ease = { kind: $("ease").value };
  if (ease.kind === "parent") {
    const k1 = num("k1");
    const k2 = num("k2");
    if (k1 !== undefined) ease.k1 = k1;
    if (k2 !== undefined) ease.k2 = k2;
  }
  const frames = num("frames");
  const maxStep = num("max-step");
  return { options, ease, frames: frames === undefined ? 60 : frames, maxStepDeg: maxStep === undefined ? 10 : maxStep };
}

/** The arm as a request sends it: the arm file's fields only (no rates). */
export function armForRequest(arm) {
  return {
    name: arm.name,
    base: arm.base,
    links: arm.links.map((l) => ({
      length: l.length,
      angle_deg: l.angle_deg,
      ...(l.limits_deg ? { limits_deg: l.limits_deg } : {}),
    })),
  };
}

/**
 * The limits after setting bound `k` (0 min, 1 max) to the field's text `v`: an empty field
 * removes the limits; a link without limits starts from [-180, 180].
 */
export function withLimit(limits, k, v) {
  if (v === "") return null;
  const cur = limits ? limits.slice() : [-180, 180];
  cur[k] = Number(v);
  return cur;
}

function cellInput(value, label, onChange, step = "any") {
  const input = document.createElement("input");
  input.type = "number";
  input.step = step;
  input.value = value === undefined || value === null ? "" : String(value);
  input.setAttribute("aria-label", label);
  input.addEventListener("change", () => onChange(input.value.trim()));
  const td = document.createElement("td");
  td.append(input);
  return td;
}

/**
 * Rebuilds the links table for `links`. Edits are reported, not applied: `edit.length(i, text)`,
 * `edit.limit(i, k, text)`, `edit.rate(i, text)` and `edit.remove(i)`.
 */
export function renderLinks(links, edit) {
  const body = $("links-body");
  body.textContent = "";
  links.forEach((link, i) => {
    const tr = document.createElement("tr");
    const n = document.createElement("td");
    n.textContent = String(i + 1);
    tr.append(n);
    const lim = link.limits_deg || [null, null];
    tr.append(
      cellInput(link.length, `Link ${i + 1} length`, (v) => edit.length(i, v), "0.1"),
      cellInput(lim[0], `Link ${i + 1} minimum angle, degrees`, (v) => edit.limit(i, 0, v), "1"),
      cellInput(lim[1], `Link ${i + 1} maximum angle, degrees`, (v) => edit.limit(i, 1, v), "1"),
      cellInput(link.rate === undefined ? 1 : link.rate, `Joint ${i + 1} rate`, (v) => edit.rate(i, v), "0.1"),
    );
    const td = document.createElement("td");
    const rm = document.createElement("button");
    rm.type = "button";
    rm.textContent = "×";
    rm.setAttribute("aria-label", `Remove link ${i + 1}`);
    rm.disabled = links.length <= 1;
    rm.addEventListener("click", () => edit.remove(i));
    td.append(rm);
    tr.append(td);
    body.append(tr);
  });
}
