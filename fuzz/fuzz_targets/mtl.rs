//! libFuzzer target: `ptsc::fuzz::mtl` on every input.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    ptsc::fuzz::mtl(data);
});
