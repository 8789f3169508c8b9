// The Character fieldset's skin list and physics switch: which skin a pose takes (the file's
// `default` unless another is chosen; bones and constraints only a skin turns on take part with
// it) and whether the physics constraints play (the clip played from 0 at 60 frames a second, as a
// game shows it) or stay still. Both travel with every pose request (`skin`, `physics`).

const $ = (id) => document.getElementById(id);

/** The request fields of `c`'s choices: none when they are the defaults. */
export function optionFields(c) {
  return { ...(c.skin ? { skin: c.skin } : {}), ...(c.physics === false ? { physics: false } : {}) };
}

/** Whether the character has physics constraints (the switch shows only then). */
export function hasPhysics(character) {
  return (character.constraints || []).some((k) => k.kind === "physics");
}

/** Shows `c`'s skins (the list hidden with fewer than two) and its physics switch. */
export function showOptions(c) {
  const skins = c.character.skins || [];
  const list = $("character-skin");
  list.replaceChildren(...skins.map((name) => new Option(name, name)));
  list.value = c.skin || (skins.includes("default") ? "default" : skins[0] || "");
  $("character-skin-box").hidden = skins.length < 2;
  $("character-physics").checked = c.physics !== false;
  $("character-physics-box").hidden = !hasPhysics(c.character);
}

/** Wires the list and the switch: a change poses again (`repose`) and is one undo step. */
export function wireOptions(state, repose, act) {
  $("character-skin").addEventListener("change", (ev) => {
    if (!state.character) return;
    const skins = state.character.character.skins || [];
    const fallback = skins.includes("default") ? "default" : null;
    state.character.skin = ev.target.value === fallback ? null : ev.target.value;
    repose();
    act.edited(`Skin: ${ev.target.value}`);
  });
  $("character-physics").addEventListener("change", (ev) => {
    if (!state.character) return;
    state.character.physics = ev.target.checked;
    repose();
    act.edited(`Physics ${ev.target.checked ? "on" : "off"}`);
  });
}
