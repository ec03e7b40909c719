//! Fuzz target; the check lives in `src/lib.rs`, where tests/fuzz_corpus.rs replays it on
//! stable Rust.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| condt_fuzz::parse_formats(data));
