//! libFuzzer target: `ptsc::fuzz::obj` on every input.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    ptsc::fuzz::obj(data);
});
