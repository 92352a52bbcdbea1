//! The library behind the `protocol` command: the parts of the command worth testing without
//! a process: spec loading and diagnostics ([`spec`]), decoding sessions ([`session`],
//! [`table`]) and CAN logs ([`candump`]). Decoding and encoding run on the
//! [`protocol_dynamic`] codec.
#![forbid(unsafe_code)]

pub mod candump;
pub mod report;
pub mod session;
pub mod spec;
pub mod table;
