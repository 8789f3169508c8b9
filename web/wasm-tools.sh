# What web/build (the playground) and web/spine/build (the ikarus-spine package) share, sourced
# by both from the repository's root: the wasm32 target, the pinned wasm-bindgen (web/bindgen)
# and wasm-opt. Each function reports through `say` (the caller defines it).

# wasm_target: installs the wasm32-unknown-unknown target when rustup lacks it.
wasm_target() {
  if ! rustup target list --installed | grep -qx wasm32-unknown-unknown; then
    say "installing the wasm32-unknown-unknown target"
    rustup target add wasm32-unknown-unknown
  fi
}

# wasm_bindgen_tool: builds web/bindgen and sets $bindgen to it.
# web/bindgen is a dozen lines over wasm-bindgen-cli-support (the library the `wasm-bindgen`
# command is made of) with its own committed Cargo.lock, pinned to exactly the wasm-bindgen of the
# root Cargo.lock (the generated glue and the module must match). Built once into target/bindgen
# (1 min 36 s on 2 quiet cores, once); later runs find it up to date. Not `cargo install
# wasm-bindgen-cli`: its locked install pins TLS crates (for its test runner's downloads) that the
# registry index may lack, and unlocked it compiles a TLS stack for half an hour.
wasm_bindgen_tool() {
  local version pinned
  version=$(awk '/^name = "wasm-bindgen"$/ { getline; gsub(/[^0-9.]/, ""); print; exit }' Cargo.lock)
  [ -n "$version" ] || { say "no wasm-bindgen in Cargo.lock"; return 1; }
  pinned=$(awk '/^name = "wasm-bindgen-cli-support"$/ { getline; gsub(/[^0-9.]/, ""); print; exit }' web/bindgen/Cargo.lock)
  if [ "$pinned" != "$version" ]; then
    say "web/bindgen is pinned to wasm-bindgen-cli-support $pinned but Cargo.lock has wasm-bindgen $version:"
    say "set both to one version (the = requirement in web/bindgen/Cargo.toml, then cargo update in web/bindgen)"
    return 1
  fi
  say "building web/bindgen (wasm-bindgen-cli-support $version; once, then up to date)"
  cargo build --quiet --release --locked --manifest-path web/bindgen/Cargo.toml --target-dir target/bindgen
  bindgen=target/bindgen/release/ikarus-bindgen
}

# wasm_opt_tool: sets $opt_tool to the wasm-opt to use ("" for none): $WASM_OPT, else
# web/node_modules/.bin/wasm-opt ((cd web && npm ci) installs binaryen 132 from npm there; it is
# installed here when missing), else wasm-opt on the PATH. WASM_OPT=none asks for none.
# Its output must still load (Debian bookworm's binaryen 108 turns wasm-bindgen's externref table
# into a funcref one, and the module then fails to initialise): wasm_optimise checks.
wasm_opt_tool() {
  opt_tool=${WASM_OPT:-}
  if [ -z "$opt_tool" ] && [ ! -x web/node_modules/.bin/wasm-opt ] && command -v npm >/dev/null; then
    say "installing wasm-opt (binaryen, from npm) into web/node_modules: npm ci in web/"
    (cd web && npm ci --no-audit --no-fund --loglevel=error)
  fi
  [ "$opt_tool" != none ] || opt_tool=
  [ -n "$opt_tool" ] || [ "${WASM_OPT:-}" = none ] || { [ -x web/node_modules/.bin/wasm-opt ] && opt_tool=web/node_modules/.bin/wasm-opt; } || true
  [ -n "$opt_tool" ] || [ "${WASM_OPT:-}" = none ] || opt_tool=$(command -v wasm-opt || true)
}

# wasm_optimise DIR NAME: runs $opt_tool -Oz on DIR/NAME_bg.wasm, keeps the output only when the
# glue DIR/NAME.js initialises with it in node (and its `version()`, when it has one, answers),
# says what became of it (sizes in bytes) and sets $optimised to 1 or 0.
wasm_optimise() {
  local wasm="$1/$2_bg.wasm" before opt
  before=$(stat -c %s "$wasm")
  optimised=0
  opt="not optimised further: no wasm-opt (see web/wasm-tools.sh)"
  if [ -n "$opt_tool" ] && command -v node >/dev/null; then
    # The features rustc enables by default for wasm32-unknown-unknown, named for wasm-opt.
    "$opt_tool" -Oz --enable-bulk-memory --enable-nontrapping-float-to-int --enable-sign-ext \
      --enable-mutable-globals --enable-reference-types --enable-multivalue \
      "$wasm" -o "$wasm.opt"
    if node --input-type=module -e '
        import { readFileSync } from "node:fs";
        const m = await import(process.argv[1]);
        await m.default({ module_or_path: readFileSync(process.argv[2]) });
        if (m.version && !m.version()) process.exit(1);' "$1/$2.js" "$wasm.opt" 2>/dev/null; then
      mv "$wasm.opt" "$wasm"
      optimised=1
      opt="after $("$opt_tool" --version) -Oz: $(stat -c %s "$wasm") bytes"
    else
      rm -f "$wasm.opt"
      opt="not optimised: the output of $("$opt_tool" --version) does not load (too old a binaryen?); (cd web && npm ci) installs one that works"
    fi
  elif [ -n "$opt_tool" ]; then
    opt="not optimised: no node to check wasm-opt's output with"
  fi
  say "$2_bg.wasm: $before bytes from wasm-bindgen, $opt; $(gzip -9 -c "$wasm" | wc -c) bytes gzipped"
}
