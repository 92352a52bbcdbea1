//! A spec whose frames may be 4 GB long: on a target with 32-bit pointers (CI builds this crate
//! for `thumbv7em-none-eabihf`) the expansion must be refused with an error that names the
//! payload's spec line. On a 64-bit host it builds.

#![no_std]

protocol_kit::protocol!("../../protocol-codegen/tests/lints/decoder_buffer_above_bound.toml");
