//! The generated firmware of `generated/`, built from a synthetic spec of N commands that
//! `footprint.sh` writes to a temporary directory and names with `PROTOCOL_SPEC_DIR` (the
//! `protocol!` macro's override of the directory spec paths are relative to), in the echo
//! harness (`../../echo.rs`).

#![no_std]
#![no_main]
#![forbid(unsafe_code)]

protocol_kit::protocol!("synth.toml");

include!("../../echo.rs");

echo_firmware!(synth);
