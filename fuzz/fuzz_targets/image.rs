//! libFuzzer target: `ptsc::fuzz::image` on every input.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    ptsc::fuzz::image(data);
});
