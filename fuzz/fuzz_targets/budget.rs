//! libFuzzer target: `ptsc::fuzz::budget` on every input.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    ptsc::fuzz::budget(data);
});
