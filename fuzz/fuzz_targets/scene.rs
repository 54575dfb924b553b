//! libFuzzer target: `ptsc::fuzz::scene` on every input.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    ptsc::fuzz::scene(data);
});
