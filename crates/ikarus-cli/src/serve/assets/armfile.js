// Arm files: load one (TOML, the format of `ikarus --arm` and examples/arms/) through
// POST /api/arm/parse, save the page's arm as one through POST /api/arm/toml, and keep the last
// arm across reloads (localStorage).

import { Notice, forPeople, postText } from "./api.js";
import { saveBlob } from "./files.js";

export { postText };

const KEY = "ikarus.arm";

/** The page's arm from arm-file text; a bad file rejects with a Notice of the CLI's one-line error. */
export async function parseArm(text) {
  const answer = JSON.parse(await postText("/api/arm/parse", text, "application/toml"));
  if (answer.problem) throw new Notice(forPeople(answer.problem));
  return answer.arm;
}

/** The arm read from a File the reader picked. */
export async function loadArmFile(file) {
  return parseArm(await file.text());
}

/** The arm-file text of the page's arm. */
export const armToml = (arm) => postText("/api/arm/toml", JSON.stringify({ arm: pageArm(arm) }), "application/json");

/** Offers the page's arm as an arm file download. */
export async function saveArmFile(arm) {
  const text = await armToml(arm);
  const name = `${(arm.name || "arm").replace(/[^A-Za-z0-9_-]+/g, "-")}.toml`;
  saveBlob(new Blob([text], { type: "application/toml" }), name);
}

/** The arm's fields that a file holds (name, base, links with their rates). */
function pageArm(arm) {
  return {
    name: arm.name || "arm",
    base: arm.base || [0, 0],
    links: arm.links.map((l) => ({
      length: l.length,
      angle_deg: l.angle_deg,
      ...(l.limits_deg ? { limits_deg: l.limits_deg } : {}),
      ...(l.rate !== undefined && l.rate !== 1 ? { rate: l.rate } : {}),
    })),
  };
}

/** Keeps `arm` for the next visit. */
export function storeArm(arm) {
  try {
    localStorage.setItem(KEY, JSON.stringify(pageArm(arm)));
  } catch (_) {
    /* storage full or off: the arm is not kept, nothing else changes */
  }
}

/** The arm kept by the last visit, or null (none, or not an arm). */
export function storedArm() {
  try {
    const arm = JSON.parse(localStorage.getItem(KEY));
    const ok = arm && Array.isArray(arm.links) && arm.links.length > 0 && arm.links.every((l) => Number.isFinite(l.length) && l.length > 0);
    return ok ? arm : null;
  } catch (_) {
    return null;
  }
}
