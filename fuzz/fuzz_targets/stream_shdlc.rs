//! The stream decoder of `specs/shdlc.toml` on arbitrary bytes (see `support::fuzz::stream`): a
//! link that escapes its frames between flags, decoded as requests.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    protocol_fuzz::support::fuzz::stream::<protocol_fuzz::support::shdlc::Packet>(data);
});
