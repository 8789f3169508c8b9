// A character's art loaded with it: the files picked or dropped together (rigs.js hands them
// over) sorted by artfiles.js into the skeleton, its atlas and the atlas's page images. The
// skeleton loads as a lone file does (rigs.js's loadFile); the atlas's text goes to
// POST /api/atlas/parse (api.parseAtlas), the page images stay in the page (decoded once into
// ImageBitmaps, premultiplied unless the atlas says the page already is: artgl.js uploads them
// once), and the character gets its `atlas` and is posed again, its answers carrying `art`.
// What cannot be used (a page image not given, an atlas without a skeleton) is one notice.

import * as api from "./api.js";
import { artNotice, groupFiles, matchPages } from "./artfiles.js";

/**
 * A page image decoded for WebGL: an ImageBitmap premultiplied when the page is straight
 * (`pma` false) and left as it is when it is premultiplied already (WebGL ignores its unpack
 * flags for ImageBitmaps), no colour-space conversion (the texels as the file has them, as the
 * CLI reads them); an Image where there is no createImageBitmap.
 */
async function decodePage(file, pma) {
  if (typeof createImageBitmap === "function") {
    return createImageBitmap(file, { premultiplyAlpha: pma ? "none" : "premultiply", colorSpaceConversion: "none" });
  }
  const image = new Image();
  image.src = URL.createObjectURL(file);
  try {
    await image.decode();
  } finally {
    URL.revokeObjectURL(image.src);
  }
  return image;
}

/**
 * Reads the atlas file `file` with its page images (`images`, files): resolves with the art's
 * atlas {id, name, pages (/api/atlas/parse's), byFile (page file → index), images (by page,
 * null for one not given)} and `match` (artfiles.js's matchPages). A refusal is a Notice.
 */
export async function readAtlas(file, images) {
  const text = await file.text();
  const answer = await api.parseAtlas(text);
  const pages = answer.pages || [];
  const match = matchPages(pages, images);
  const decoded = await Promise.all(match.matched.map((f, i) => (f ? decodePage(f, !!pages[i].pma) : null)));
  const atlas = { id: answer.id, name: file.name, pages, byFile: new Map(pages.map((p, i) => [p.file, i])), images: decoded, regions: answer.regions };
  return { atlas, match };
}

/**
 * Whether the failure `e` of the pose request `req` of character `c` is its art's (the backend's
 * line starts with `atlas: `: a region the atlas lacks, an atlas not kept even when sent again):
 * then the character drops its atlas, keeps the line as its notice and is posed again as bones.
 */
export function artRefused(c, req, e) {
  if (!req.atlas || !c.atlas || !/^atlas: /.test(e && e.message)) return false;
  c.atlas = null;
  c.art = null;
  c.artNotice = e.message;
  c.pending = true;
  return true;
}

/**
 * Loads `files` (picked or dropped together): the skeleton by `loadFile(file)` (rigs.js's, which
 * shows the character or the rig), then the atlas onto the character shown. `act` is
 * {state, loadFile(file), characters (characters.js's: repose()), showError(e)}.
 */
export async function loadTogether(files, act) {
  const group = groupFiles(files);
  const before = act.state.character;
  if (group.skeleton) await act.loadFile(group.skeleton);
  const c = act.state.character;
  // A skeleton that did not load as a new character (its problem is shown): no art.
  if (group.skeleton && (!c || c === before)) return;
  if (!group.atlas || !group.skeleton) {
    const notice = artNotice(group, null);
    if (notice) act.showError(new api.Notice(notice));
    return;
  }
  try {
    const { atlas, match } = await readAtlas(group.atlas, group.images);
    // Another body may have taken the canvas meanwhile: the art is the character's it came with.
    c.atlas = atlas;
    c.artNotice = artNotice(group, match);
    if (c.artNotice) act.showError(new api.Notice(c.artNotice));
    if (act.state.character === c) act.characters.repose();
  } catch (e) {
    // An atlas refused: its line stays on the chip while the character is shown.
    c.artNotice = e.message;
    act.showError(e);
  }
}
