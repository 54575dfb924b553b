//! libFuzzer target: `ptsc::fuzz::gltf` on every input.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    ptsc::fuzz::gltf(data);
});
