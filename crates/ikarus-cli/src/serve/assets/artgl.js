// A character's art drawn with WebGL on its own canvas, laid under the page's 2D canvas (which
// draws the grid lines, the bones and the handles over it). The art is /api/pose's `art`
// (api.md): slots in draw order, each with its page, blend, tint (`color`, straight 0..1) and
// two-colour `dark`, world `vertices`, page `uvs` (v down) and `triangles`.
//
// Why WebGL rather than canvas 2D: a textured triangle in canvas 2D is a clip path plus an
// affine drawImage per triangle, whose anti-aliased clip edges leave hairline seams between
// neighbouring triangles and which has no per-slot tint, dark colour nor multiply/screen of the
// texture alone; WebGL draws every triangle of a slot in one call, seamless (shared edges are
// rasterised once), with the tint in the shader.
//
// The rules (the same as crates/ikarus-render/src/art_raster.rs, the CLI's pictures):
//  - Colours are premultiplied: each page is uploaded once (per atlas) with
//    UNPACK_PREMULTIPLY_ALPHA_WEBGL when the atlas says the page is not premultiplied (`pma`).
//  - Tint: with t the premultiplied texel, L = (r, g, b) and a the slot's straight colour and D
//    its dark colour (black when none), out.rgb = a·(t.rgb·L + (t.a − t.rgb)·D), out.a = t.a·a:
//    white becomes L and black becomes D, linearly between (two-colour tinting, "tint black").
//    A fade f (the onion skins) multiplies a.
//  - Blend per slot, premultiplied: normal ONE/ONE_MINUS_SRC_ALPHA, additive ONE/ONE, multiply
//    DST_COLOR/ONE_MINUS_SRC_ALPHA, screen ONE/ONE_MINUS_SRC_COLOR.
//  - Vertices go world → canvas by the page's view (view.js's toCanvas), in the shader.
// No allocation per frame once the buffers have grown to the art's size.

const VERTEX = `
attribute vec2 a_pos;
attribute vec2 a_uv;
uniform vec4 u_xf;
varying vec2 v_uv;
void main() {
  gl_Position = vec4(a_pos.x * u_xf.x + u_xf.y, a_pos.y * u_xf.z + u_xf.w, 0.0, 1.0);
  v_uv = a_uv;
}`;

const FRAGMENT = `
precision mediump float;
uniform sampler2D u_tex;
uniform vec4 u_light;
uniform vec3 u_dark;
varying vec2 v_uv;
void main() {
  vec4 t = texture2D(u_tex, v_uv);
  float a = u_light.a;
  gl_FragColor = vec4(a * (t.rgb * u_light.rgb + max(t.a - t.rgb, 0.0) * u_dark), t.a * a);
}`;

/** The blend factors of each blend mode (premultiplied colours), as [src, dst] GL enum names. */
export const BLENDS = {
  normal: ["ONE", "ONE_MINUS_SRC_ALPHA"],
  additive: ["ONE", "ONE"],
  multiply: ["DST_COLOR", "ONE_MINUS_SRC_ALPHA"],
  screen: ["ONE", "ONE_MINUS_SRC_COLOR"],
};

/**
 * The shader's transform of world points to clip space for `view` ({cx, cy, scale, w, h}, the
 * page's: canvas x = cx + x·scale, y = cy − y·scale, CSS pixels): [sx, ox, sy, oy] with
 * clip x = x·sx + ox, clip y = y·sy + oy.
 */
export function clipTransform(view) {
  return [(2 * view.scale) / view.w, (2 * view.cx) / view.w - 1, (2 * view.scale) / view.h, 1 - (2 * view.cy) / view.h];
}

function compile(gl, type, source) {
  const s = gl.createShader(type);
  gl.shaderSource(s, source);
  gl.compileShader(s);
  if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error(`art shader: ${gl.getShaderInfoLog(s)}`);
  return s;
}

/**
 * The art renderer on `canvas` (a canvas laid under the page's 2D canvas, the same size), or
 * null when the browser has no WebGL. Returns {draw(view, layers), clear(), size(w, h, dpr)}:
 * `layers` is [{art, alpha, atlas}] drawn in order (the onion skins first, the pose last), with
 * `atlas` the page's atlas ({pages: [{file, pma}], byFile: Map file → page index, images:
 * [ImageBitmap | Image | null] by page}): a slot whose page has no image is left out.
 */
export function artRenderer(canvas) {
  const gl = canvas.getContext("webgl", { alpha: true, premultipliedAlpha: true, antialias: true, preserveDrawingBuffer: true });
  if (!gl) return null;
  const program = gl.createProgram();
  gl.attachShader(program, compile(gl, gl.VERTEX_SHADER, VERTEX));
  gl.attachShader(program, compile(gl, gl.FRAGMENT_SHADER, FRAGMENT));
  gl.linkProgram(program);
  if (!gl.getProgramParameter(program, gl.LINK_STATUS)) throw new Error(`art program: ${gl.getProgramInfoLog(program)}`);
  gl.useProgram(program);
  const at = { pos: gl.getAttribLocation(program, "a_pos"), uv: gl.getAttribLocation(program, "a_uv") };
  const u = {
    xf: gl.getUniformLocation(program, "u_xf"),
    tex: gl.getUniformLocation(program, "u_tex"),
    light: gl.getUniformLocation(program, "u_light"),
    dark: gl.getUniformLocation(program, "u_dark"),
  };
  gl.uniform1i(u.tex, 0);
  gl.enableVertexAttribArray(at.pos);
  gl.enableVertexAttribArray(at.uv);
  gl.enable(gl.BLEND);
  const vbo = gl.createBuffer();
  const ibo = gl.createBuffer();
  gl.bindBuffer(gl.ARRAY_BUFFER, vbo);
  gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, ibo);
  // The frame's vertices (x, y, u, v interleaved) and triangles (slot-local indices), grown by doubling.
  let verts = new Float32Array(4096);
  let tris = new Uint16Array(4096);
  let vboSize = 0;
  let iboSize = 0;
  /** Each atlas's textures, uploaded once: atlas object → [WebGLTexture | null] by page. */
  const textures = new WeakMap();
  const blends = Object.fromEntries(Object.entries(BLENDS).map(([k, [s, d]]) => [k, [gl[s], gl[d]]]));
  /** The slots of the frame: [{texture, blend, light, dark, vertex (first), index (first), count}], reused. */
  const runs = [];

  function texturesOf(atlas) {
    let t = textures.get(atlas);
    if (t) return t;
    t = atlas.images.map((image, i) => {
      if (!image) return null;
      const tex = gl.createTexture();
      gl.bindTexture(gl.TEXTURE_2D, tex);
      gl.pixelStorei(gl.UNPACK_PREMULTIPLY_ALPHA_WEBGL, !(atlas.pages[i] && atlas.pages[i].pma));
      gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA, gl.RGBA, gl.UNSIGNED_BYTE, image);
      gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.LINEAR);
      gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.LINEAR);
      gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_S, gl.CLAMP_TO_EDGE);
      gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_T, gl.CLAMP_TO_EDGE);
      return tex;
    });
    textures.set(atlas, t);
    return t;
  }

  /** Sizes the drawing buffer to `w` × `h` CSS pixels at `dpr` device pixels each. */
  function size(w, h, dpr) {
    const [pw, ph] = [Math.max(1, Math.round(w * dpr)), Math.max(1, Math.round(h * dpr))];
    if (canvas.width !== pw || canvas.height !== ph) {
      canvas.width = pw;
      canvas.height = ph;
    }
    gl.viewport(0, 0, pw, ph);
  }

  function clear() {
    gl.clearColor(0, 0, 0, 0);
    gl.clear(gl.COLOR_BUFFER_BIT);
  }

  /** Fills `verts`, `tris` and `runs` with the layers' slots; returns [floats, indices] used. */
  function pack(layers) {
    let nv = 0;
    let ni = 0;
    let nr = 0;
    for (const { art, alpha, atlas } of layers) {
      if (!art || !atlas) continue;
      const texs = texturesOf(atlas);
      const pages = art.pages || [];
      for (const s of art.slots || []) {
        // The slot's page by its file name among the atlas's pages (the art's own order otherwise).
        const texture = texs[atlas.byFile.get(pages[s.page]) ?? s.page];
        const v = s.vertices;
        const n = v.length >> 1;
        if (!texture || n < 3 || n > 65536 || !s.triangles.length) continue;
        while (verts.length < nv + 4 * n) verts = grow(verts);
        while (tris.length < ni + s.triangles.length) tris = grow(tris);
        for (let k = 0; k < n; k++) {
          const o = nv + 4 * k;
          verts[o] = v[2 * k];
          verts[o + 1] = v[2 * k + 1];
          verts[o + 2] = s.uvs[2 * k];
          verts[o + 3] = s.uvs[2 * k + 1];
        }
        tris.set(s.triangles, ni);
        const c = s.color;
        const a = c[3] * alpha;
        const run = runs[nr] || (runs[nr] = { light: new Float32Array(4), dark: new Float32Array(3) });
        run.texture = texture;
        run.blend = blends[s.blend] || blends.normal;
        run.light.set([c[0], c[1], c[2], a]);
        run.dark.set(s.dark || [0, 0, 0]);
        run.vertex = nv / 4;
        run.index = ni;
        run.count = s.triangles.length;
        nr++;
        nv += 4 * n;
        ni += s.triangles.length;
      }
    }
    runs.length = nr;
    return [nv, ni];
  }

  /** Draws `layers` (see above) in `view` over a cleared canvas; returns the slots drawn. */
  function draw(view, layers) {
    clear();
    const [nv, ni] = pack(layers);
    if (!runs.length) return 0;
    if (nv > vboSize) {
      vboSize = verts.length;
      gl.bufferData(gl.ARRAY_BUFFER, vboSize * 4, gl.DYNAMIC_DRAW);
    }
    if (ni > iboSize) {
      iboSize = tris.length;
      gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, iboSize * 2, gl.DYNAMIC_DRAW);
    }
    gl.bufferSubData(gl.ARRAY_BUFFER, 0, verts.subarray(0, nv));
    gl.bufferSubData(gl.ELEMENT_ARRAY_BUFFER, 0, tris.subarray(0, ni));
    gl.uniform4fv(u.xf, clipTransform(view));
    gl.activeTexture(gl.TEXTURE0);
    for (const r of runs) {
      gl.bindTexture(gl.TEXTURE_2D, r.texture);
      gl.blendFunc(r.blend[0], r.blend[1]);
      gl.uniform4fv(u.light, r.light);
      gl.uniform3fv(u.dark, r.dark);
      // Slot-local indices: the attributes start at the slot's first vertex.
      gl.vertexAttribPointer(at.pos, 2, gl.FLOAT, false, 16, r.vertex * 16);
      gl.vertexAttribPointer(at.uv, 2, gl.FLOAT, false, 16, r.vertex * 16 + 8);
      gl.drawElements(gl.TRIANGLES, r.count, gl.UNSIGNED_SHORT, r.index * 2);
    }
    return runs.length;
  }

  return { draw, clear, size };
}

/** A typed array of twice the length with the same contents. */
function grow(a) {
  const b = new a.constructor(a.length * 2);
  b.set(a);
  return b;
}
