// Downloads: the frames of a motion as CSV, and saving a Blob under a file name.

/** The frames of a /api/animate answer as CSV: time, every angle, every joint's x and y. */
export function framesCsv(anim) {
  const nj = anim.frames[0] ? anim.frames[0].angles_deg.length : 0;
  const head = ["time"];
  for (let i = 0; i < nj; i++) head.push(`angle${i + 1}_deg`);
  for (let i = 0; i <= nj; i++) head.push(`x${i}`, `y${i}`);
  const rows = anim.frames.map((f) => [f.time, ...f.angles_deg, ...f.joints.flat()].join(","));
  return [head.join(","), ...rows].join("\n") + "\n";
}

/** Offers `blob` as a download named `name`. */
export function saveBlob(blob, name) {
  const url = URL.createObjectURL(blob);
  const a = document.createElement("a");
  a.href = url;
  a.download = name;
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 1000);
}
