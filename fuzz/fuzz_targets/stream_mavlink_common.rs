//! The link decoder of `specs/mavlink-common.toml` (the whole common dialect, imported from its
//! XML: MAVLink 1 and 2 frames, signed ones included) on arbitrary bytes (see
//! `support::fuzz::stream`).
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    protocol_fuzz::support::fuzz::stream::<protocol_fuzz::support::mavlink_common::AnyPacket>(data);
});
