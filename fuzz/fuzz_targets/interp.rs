//! The interpreter against generated code, on arbitrary bytes of any spec (the first byte picks
//! the spec; see `support::fuzz::interp`).
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    protocol_fuzz::support::fuzz::interp_any(data);
});
