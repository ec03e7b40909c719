//! `reconstruct` in WebAssembly without an operating system (`wasm32-unknown-unknown`, the
//! target of a web page's module), with the default features: std's clock panics there, and
//! every call trapped until the pipeline's clock learned to read zero on it (a web developer's
//! check). `.ci/run` builds this package as a module and calls it from Node (`run.mjs`):
//!
//! ```sh
//! cargo build --manifest-path .ci/wasm-probe/Cargo.toml --target wasm32-unknown-unknown \
//!     --target-dir target/wasm-probe
//! node .ci/wasm-probe/run.mjs \
//!     target/wasm-probe/wasm32-unknown-unknown/debug/condt_wasm_probe.wasm
//! ```

/// The number of edges `condt::reconstruct` finds through `n` points on an ellipse (`n` on a
/// closed curve), or `u32::MAX` for an error.
#[no_mangle]
pub extern "C" fn ellipse_edges(n: u32) -> u32 {
    let points: Vec<condt::Point> = (0..n)
        .map(|k| {
            let t = k as f64 * std::f64::consts::TAU / n as f64;
            condt::Point::new(2.0 * t.cos(), t.sin())
        })
        .collect();
    match condt::reconstruct(&points, &condt::Params::default()) {
        Ok(result) => result.edges().len() as u32,
        Err(_) => u32::MAX,
    }
}
