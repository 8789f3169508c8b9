// The form fields of the panel <-> the settings of a request: the select lists filled from
// /api/meta, which fields are enabled, the solver options, ease and frame count read from the
// fields, the links table, and the arm as a request sends it. It owns no state: the page's state
// lives in main.js, and the links table reports its edits through callbacks.

import { solvesRigs } from "./rig.js";

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

/**
 * Fills the method, limit-mode and ease lists, the k1/k2 fields and the solver's fields from a
 * /api/meta answer: the page starts with the settings `ikarus solve` uses (limits off).
 */
export function fillSelects(meta) {
  fillSelect($("method"), meta.methods, meta.default_method);
  fillSelect($("limit-mode"), offeredLimitModes(meta), meta.default_limit_mode);
  fillSelect($("ease"), meta.eases, meta.default_ease);
  $("k1").value = String(meta.default_k1);
  $("k2").value = String(meta.default_k2);
  const d = meta.defaults;
  $("limits").checked = d.limits;
  $("restarts").value = String(d.restarts);
  $("lambda").value = String(d.lambda);
  $("tolerance").value = String(d.tolerance);
  $("max-iterations").value = String(d.max_iterations);
}

/**
 * Whether `method` (a /api/meta method) solves an arm of `links` links, with or without an
 * orientation goal; with `rig`, whether it solves rigs (rig.js's solvesRigs).
 */
export const methodApplies = (method, links, orientation, rig = false) =>
  rig ? solvesRigs(method) : !method.shapes || method.shapes.some(([n, o]) => n === links && o === orientation);

/**
 * Offers only the methods that solve this arm (the closed form: two links, or three with a goal
 * angle), or with `rig` those that solve rigs; a method that no longer applies gives way to the
 * default. Returns the method shown.
 */
export function syncMethods(meta, links, orientation, rig = false) {
  const select = $("method");
  for (const option of select.options) {
    const m = meta.methods.find((x) => x.name === option.value);
    const ok = methodApplies(m, links, orientation, rig);
    option.hidden = !ok;
    option.disabled = !ok;
  }
  if (select.selectedOptions[0] && select.selectedOptions[0].disabled) select.value = meta.default_method;
  return select.value;
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
  // A method with one way of handling limits (CCD and FABRIK clamp) offers no choice.
  select.dataset.only = String(method.limit_modes.filter((m) => m !== "ignore").length <= 1);
  if (method.limit_modes.includes(preferred)) select.value = preferred;
  else if (!method.limit_modes.includes(select.value)) select.value = method.default_limit_mode;
  return select.value;
}

/**
 * Whether the method named `name` reads λ (its `uses_lambda` in the /api/meta answer `meta`:
 * damped least squares and Levenberg–Marquardt); false before the answer has come.
 */
export const usesLambda = (meta, name) => !!meta?.methods.find((m) => m.name === name)?.uses_lambda;

/** Enables the fields that matter for the current method (as `meta` describes it), limits and ease. */
export function syncEnabled(meta) {
  $("lambda").disabled = !usesLambda(meta, $("method").value);
  const modes = $("limit-mode");
  modes.disabled = !$("limits").checked || modes.dataset.only === "true";
  modes.title = modes.dataset.only === "true" ? "This method has one way of keeping joints in range" : "";
  $("goal-angle").disabled = !$("use-goal-angle").checked;
  const parent = $("ease").value === "parent";
  $("k1").disabled = !parent;
  $("k2").disabled = !parent;
}

// ---- Checking the fields ---------------------------------------------------------------------
//
// The page checks every field before it asks the server, so that a bad value is named by its
// control ("Restarts: must be a whole number from 0 to 64") and no request is rejected. A field
// with a problem is marked (aria-invalid) until it is fixed; `firstProblem()` is the one shown.

/** Problems by field: element -> message. */
const problems = new Map();

/** Marks `el` as holding a bad value, with the message for people. */
export function setProblem(el, message) {
  problems.set(el, message);
  el.setAttribute("aria-invalid", "true");
  el.title = message;
}

/** The value of `el` is fine again. */
export function clearProblem(el) {
  if (!problems.delete(el)) return;
  el.removeAttribute("aria-invalid");
  el.title = "";
}

/** The message of `el`'s bad value, or undefined when it holds a good one. */
export const problemOf = (el) => problems.get(el);

/** The first field with a bad value, in the page's order: {el, message}, or null. */
export function firstProblem() {
  for (const [el, message] of problems) {
    if (!el.isConnected) problems.delete(el);
  }
  const els = [...problems.keys()].sort((a, b) => (a.compareDocumentPosition(b) & Node.DOCUMENT_POSITION_FOLLOWING ? -1 : 1));
  return els.length ? { el: els[0], message: problems.get(els[0]) } : null;
}

/**
 * The rule of a number: `whole` (an integer), `min`/`max` (inclusive), `above` (exclusive).
 * Returns the reason a value breaks it, or null.
 */
export function numberProblem(text, rule) {
  const v = Number(text);
  const range = () => {
    const lo = rule.above !== undefined ? `> ${rule.above}` : rule.min !== undefined ? `≥ ${rule.min}` : "";
    if (rule.max !== undefined && rule.min !== undefined) return `from ${rule.min} to ${rule.max}`;
    return [lo, rule.max !== undefined ? `≤ ${rule.max}` : ""].filter(Boolean).join(" and ");
  };
  const what = `must be a ${rule.whole ? "whole number" : "number"}${range() ? " " + range() : ""}`;
  if (text === "" || !Number.isFinite(v)) return what;
  if (rule.whole && !Number.isInteger(v)) return what;
  if (rule.min !== undefined && v < rule.min) return what;
  if (rule.max !== undefined && v > rule.max) return what;
  if (rule.above !== undefined && !(v > rule.above)) return what;
  return null;
}

/**
 * The playback durations the *Duration* field takes, seconds: a tenth of a second to a minute
 * (a minute's GIF at 25 frames a second is 1500 frames, under the server's cap of 2000).
 */
export const CHOSEN_DURATION = { min: 0.1, max: 60 };

/** The solver's and motion's number fields: id, request key, label, rule, whether it may be empty. */
const NUMBER_FIELDS = [
  ["restarts", "restarts", "Restarts", { whole: true, min: 0, max: 64 }],
  ["lambda", "lambda", "λ (damping)", { min: 0 }],
  ["tolerance", "tolerance", "Tolerance", { above: 0 }],
  ["max-iterations", "max_iterations", "Max iterations", { whole: true, min: 1, max: 100000 }],
  ["record-every", "record_every", "Replay every", { whole: true, min: 1 }, true],
  ["goal-angle", null, "Goal angle", { min: -1e6, max: 1e6 }],
  ["k1", null, "k1", { min: 0, max: 1 }],
  ["k2", null, "k2", { min: 0, max: 1 }],
  ["frames", null, "Frames", { whole: true, min: 2, max: 2000 }],
  ["max-step", null, "Step bound", { above: 0, max: 180 }, true],
  ["duration", null, "Duration", { min: CHOSEN_DURATION.min, max: CHOSEN_DURATION.max }, true],
];

/** Checks the form's number fields (enabled ones only); marks and unmarks them. */
function checkFields() {
  for (const [id, , label, rule, optional] of NUMBER_FIELDS) {
    const el = $(id);
    const text = el.value.trim();
    const why = el.disabled || (optional && text === "") ? null : numberProblem(text, rule);
    if (why) setProblem(el, `${label}: ${why}`);
    else clearProblem(el);
  }
  if (!$("k1").disabled && problems.get($("k1")) === undefined && problems.get($("k2")) === undefined && Number($("k1").value) > Number($("k2").value)) {
    setProblem($("k1"), "k1: must not exceed k2");
  }
}

/** A number field's value, or undefined when it is empty. */
function num(id) {
  const v = $(id).value.trim();
  return v === "" ? undefined : Number(v);
}

/**
 * The settings of the next requests, read from the fields: `options` (a request's solver
 * options; an empty field is left to the server's default), `ease`, `frames`, `maxStepDeg`
 * (the step bound of following and traced paths, 10° when empty) and `duration` (the playback's
 * seconds the reader chose; null when the field is empty or bad: the default). The joint rates come from
 * the links.
 */
export function readControls(links) {
  checkFields();
  const options = { method: $("method").value, limits: $("limits").checked };
  if (options.limits) options.limit_mode = $("limit-mode").value;
  for (const [id, key] of NUMBER_FIELDS) {
    const v = num(id);
    // "Replay every" shapes the solver's replay only (timeline), not the clicked motion.
    if (key && key !== "record_every" && v !== undefined) options[key] = v;
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
  const recordEvery = num("record-every");
  const goalAngle = $("use-goal-angle").checked ? num("goal-angle") : undefined;
  const duration = problemOf($("duration")) ? undefined : num("duration");
  return {
    duration: duration === undefined ? null : duration,
    options,
    ease,
    frames: frames === undefined ? 60 : frames,
    maxStepDeg: maxStep === undefined ? 10 : maxStep,
    recordEvery: recordEvery === undefined ? 1 : recordEvery,
    goalAngle,
  };
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
 * The limits after setting bound `k` (0 min, 1 max) to the field's text `v`. An empty field is
 * the open end of that side (−180 for the min, 180 for the max) and the other bound stays; both
 * ends open (−180 and 180) is no limits at all (null). A link without limits starts from
 * [-180, 180].
 */
export function withLimit(limits, k, v) {
  const cur = limits ? limits.slice() : [-180, 180];
  cur[k] = v === "" ? (k === 0 ? -180 : 180) : Number(v);
  return cur[0] === -180 && cur[1] === 180 ? null : cur;
}

/** `angle` moved into `limits` ([min, max] degrees, or null for none). */
export const clampInto = (angle, limits) => (limits ? Math.min(Math.max(angle, limits[0]), limits[1]) : angle);

function cellInput(value, label, onChange, step = "any") {
  const input = document.createElement("input");
  input.type = "number";
  input.step = step;
  input.value = value === undefined || value === null ? "" : String(value);
  input.setAttribute("aria-label", label);
  input.addEventListener("change", () => onChange(input.value.trim(), input));
  const td = document.createElement("td");
  td.append(input);
  return td;
}

/**
 * Rebuilds the links table for `links`. Edits are reported, not applied: `edit.length(i, text)`,
 * `edit.start(i, text)`, `edit.limit(i, k, text)`, `edit.rate(i, text)` and `edit.remove(i)`;
 * each gets the cell too (`edit.length(i, text, input)`) to mark a bad value.
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
      cellInput(link.length, `Link ${i + 1} length`, (v, el) => edit.length(i, v, el), "0.1"),
      cellInput(link.angle_deg, `Link ${i + 1} start angle, degrees`, (v, el) => edit.start(i, v, el), "1"),
      cellInput(lim[0], `Link ${i + 1} minimum angle, degrees`, (v, el) => edit.limit(i, 0, v, el), "1"),
      cellInput(lim[1], `Link ${i + 1} maximum angle, degrees`, (v, el) => edit.limit(i, 1, v, el), "1"),
      cellInput(link.rate === undefined ? 1 : link.rate, `Joint ${i + 1} rate`, (v, el) => edit.rate(i, v, el), "0.1"),
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
