//! libFuzzer target: `ptsc::fuzz::state` on every input.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    ptsc::fuzz::state(data);
});
