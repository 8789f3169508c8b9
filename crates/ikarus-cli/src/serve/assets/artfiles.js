// The files the reader picked or dropped together, sorted into what they are for a character's
// art: the skeleton (`.json` or `.skel`), its texture atlas (`.atlas`, Spine's text format whose
// pages name their images) and the atlas's page images (`.png`, or any image), in any order; and
// the one-line notices the page shows when a part is missing (a page image the atlas names that
// was not given, an atlas without a skeleton). Pure: node tests it (e2e/artfiles.unit.test.mjs).

/** Whether `name` is an atlas file. */
const isAtlas = (name) => /\.atlas(\.txt)?$/i.test(name);

/** Whether `name` is an image file (an atlas page). */
const isImage = (name) => /\.(png|jpe?g|webp)$/i.test(name);

/** The last path segment of `name` (a page named "images/spineboy.png" is the file spineboy.png). */
export const baseName = (name) => String(name).split(/[\\/]/).pop();

/**
 * Sorts `files` (anything with a `name`) into {skeleton, atlas, images, others}: `skeleton` the
 * first file that is neither an atlas nor an image (a `.json`, `.skel` or `.toml`: the body
 * loaded as today), or null; `atlas` the first `.atlas` file, or null; `images` every image;
 * `others` the files left (a second skeleton or atlas: the notice names them).
 */
export function groupFiles(files) {
  const out = { skeleton: null, atlas: null, images: [], others: [] };
  for (const f of files) {
    if (isImage(f.name)) out.images.push(f);
    else if (isAtlas(f.name)) {
      if (out.atlas) out.others.push(f);
      else out.atlas = f;
    } else if (out.skeleton) out.others.push(f);
    else out.skeleton = f;
  }
  return out;
}

/**
 * The image of `images` (anything with a `name`) that is the atlas page `page` (its `file` as
 * the atlas names it): the same file name, else the same name ignoring case; or null.
 */
export function pageImage(page, images) {
  const want = baseName(page);
  return images.find((f) => baseName(f.name) === want) || images.find((f) => baseName(f.name).toLowerCase() === want.toLowerCase()) || null;
}

/**
 * Matches the atlas's pages (the /api/atlas/parse answer's `pages`: [{file, …}]) with the given
 * `images`: {matched (per page, its image or null), missing (the page files not given), unused
 * (the images no page names)}.
 */
export function matchPages(pages, images) {
  const matched = pages.map((p) => pageImage(p.file, images));
  const missing = pages.filter((_, i) => !matched[i]).map((p) => p.file);
  const unused = images.filter((f) => !matched.includes(f)).map((f) => f.name);
  return { matched, missing, unused };
}

/**
 * The one-line notice of what could not be used of the files loaded together, or null when all
 * of them were: `group` is groupFiles's, `match` matchPages's (null when no atlas was read).
 */
export function artNotice(group, match) {
  const parts = [];
  if (group.atlas && !group.skeleton) parts.push(`atlas ${group.atlas.name}: no skeleton given with it (.json or .skel); drop them together`);
  if (!group.atlas && group.images.length) parts.push(`${group.images.map((f) => f.name).join(", ")}: no atlas given with ${group.images.length === 1 ? "it" : "them"} (.atlas)`);
  if (match && match.missing.length) {
    const s = match.missing.length === 1 ? "" : "s";
    parts.push(`atlas ${group.atlas.name}: page image${s} ${match.missing.join(", ")} not given, its slots not drawn; drop ${match.missing.length === 1 ? "it" : "them"} with the skeleton and the atlas`);
  }
  if (match && match.unused.length) parts.push(`${match.unused.join(", ")}: no page of atlas ${group.atlas.name}`);
  if (group.others.length) parts.push(`${group.others.map((f) => f.name).join(", ")}: one skeleton and one atlas at a time; left out`);
  return parts.length ? parts.join(" · ") : null;
}
