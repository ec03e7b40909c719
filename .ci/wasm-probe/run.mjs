// Calls the probe built for wasm32-unknown-unknown (src/lib.rs says how and why): an
// ellipse of n points must come back as one closed curve of n edges, below and above the size
// from which the stages may use threads (65,536 points), which that target cannot start.
import { readFileSync } from "node:fs";
import assert from "node:assert/strict";

const { instance } = await WebAssembly.instantiate(readFileSync(process.argv[2]), {});
for (const n of [100, 70000]) {
  assert.equal(instance.exports.ellipse_edges(n), n, `an ellipse of ${n} points`);
}
console.log("wasm probe passed");
