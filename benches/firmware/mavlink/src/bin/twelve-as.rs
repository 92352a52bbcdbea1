//! Three MAVLink messages (`../three.rs`) on the twelve messages of `specs/mavlink.toml`, each
//! decoded alone (`Packet::from_frame_as`).

#![no_std]
#![no_main]
#![forbid(unsafe_code)]

protocol_kit::protocol!("../../../specs/mavlink.toml");

include!("../three.rs");

three_messages!(mavlink, from_frame_as);
