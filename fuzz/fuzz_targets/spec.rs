//! The spec loader and validator on arbitrary text (see `support::fuzz::spec`).
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    protocol_fuzz::support::fuzz::spec(data);
});
