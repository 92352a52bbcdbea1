//! The link decoder of `specs/msp.toml` (`any_decoder()`: MSP v1 and v2 frames) on arbitrary
//! bytes (see `support::fuzz::stream`).
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    protocol_fuzz::support::fuzz::stream::<protocol_fuzz::support::msp::AnyPacket>(data);
});
