//! libFuzzer target: `ptsc::fuzz::ply` on every input.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    ptsc::fuzz::ply(data);
});
