//! Three MAVLink messages (`../three.rs`) on the whole common dialect, imported from its XML,
//! handed to a `Handler` (`dispatch`).

#![no_std]
#![no_main]
#![forbid(unsafe_code)]

protocol_kit::protocol!("../../../specs/mavlink-common.toml");

include!("../three.rs");

three_messages!(mavlink_common, handler);
