//! The link decoder of `specs/mavlink.toml` (`any_decoder()`: MAVLink 1 and 2 frames, signed
//! ones included) on arbitrary bytes (see `support::fuzz::stream`).
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    protocol_fuzz::support::fuzz::stream::<protocol_fuzz::support::mavlink::AnyPacket>(data);
});
