//! `ikarus-bindgen IN.wasm OUT_DIR`: what `wasm-bindgen --target web --no-typescript --out-dir
//! OUT_DIR IN.wasm` does, for `web/build`, which checks that this crate's Cargo.lock pins
//! wasm-bindgen-cli-support to the root Cargo.lock's wasm-bindgen (glue and module must agree).

use std::process::ExitCode;

use wasm_bindgen_cli_support::Bindgen;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [input, out_dir] = args.as_slice() else {
        eprintln!("usage: ikarus-bindgen IN.wasm OUT_DIR");
        return ExitCode::from(2);
    };
    // Bindings for the web target (an ES module whose default export loads the module), no
    // TypeScript declarations. The library omits the default module path unless told (the
    // command line keeps it): without it `init()` has no `ikarus_wasm_bg.wasm` beside
    // `import.meta.url` to fetch, and the page's worker could not load the module.
    // With `__wbg_reset_state` (`--experimental-reset-state-function`): after a trap (out of
    // memory, a panic, both `unreachable` on wasm32) the module is dead for good, and ikarus.js
    // calls it to instantiate the compiled module afresh, at once; objects made by the stopped
    // instance are then refused by the glue instead of reaching the new one's memory.
    let made = Bindgen::new()
        .input_path(input)
        .web(true)
        .and_then(|b| b.typescript(false).omit_default_module_path(false).reset_state_function(true).generate(out_dir));
    match made {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("ikarus-bindgen: {input}: {e:#}");
            ExitCode::FAILURE
        }
    }
}
