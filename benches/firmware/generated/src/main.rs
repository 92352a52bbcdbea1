//! HFLink firmware with the generated code, in the echo harness (`../../echo.rs`): decode
//! every frame that arrives, decode its payload, and send the packet back.

#![no_std]
#![no_main]
#![forbid(unsafe_code)]

protocol_kit::protocol!("../../../specs/hflink.toml");

include!("../../echo.rs");

echo_firmware!(hflink);
