//! The library behind the `protocol` command: the interpreter that encodes and decodes any
//! checked spec at run time on the runtime's own engine ([`interp`]), and the parts of the
//! command worth testing without a process: spec loading and diagnostics ([`spec`]), decoding
//! sessions ([`session`], [`table`]), CAN logs ([`candump`]) and the compatibility report
//! ([`compat`]).
#![forbid(unsafe_code)]

pub mod candump;
pub mod compat;
pub mod interp;
pub mod session;
pub mod spec;
pub mod table;
