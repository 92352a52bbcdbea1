//! The library behind the `protocol` command: the parts of the command worth testing without
//! a process: spec loading and diagnostics ([`spec`]), decoding sessions ([`session`],
//! [`table`]), CAN logs ([`candump`]), CSV and MCAP exports ([`export`]), lost and reordered
//! frames ([`counter`]), the capture report ([`report`]) with its signal plots ([`signals`]),
//! the device twin ([`twin`]), definitions of other languages read as specs ([`import`]) and,
//! on Linux, live SocketCAN input (`socketcan`). Decoding and encoding run on the
//! [`protocol_dynamic`] codec.
#![forbid(unsafe_code)]

pub mod candump;
pub mod counter;
pub mod export;
pub mod import;
pub mod report;
pub mod session;
pub mod signals;
#[cfg(target_os = "linux")]
pub mod socketcan;
pub mod spec;
pub mod table;
pub mod twin;
