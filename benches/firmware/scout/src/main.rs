//! Scout firmware with the generated code, in the echo harness (`../../echo.rs`): decode every
//! UART frame that arrives, decode its payload, and send the packet back. The Scout spec has
//! scaled fields (`f32` in Rust, 8- and 16-bit integers on the wire, one clamped and
//! truncated), so this binary shows what their arithmetic links in: `benches/footprint.sh`
//! lists its double-precision soft-float helpers.

#![no_std]
#![no_main]
#![forbid(unsafe_code)]

protocol_kit::protocol!("../../../specs/scout.toml");

include!("../../echo.rs");

echo_firmware!(scout);
