//! A `#![no_std]`, heap-free crate that expands the real specs, built for
//! `thumbv7em-none-eabihf` in CI: proof that the runtime and all generated code need neither
//! `std` nor `alloc`, and that generated code passes `deny(warnings, missing_docs)`.

#![no_std]
#![forbid(unsafe_code)]
#![deny(warnings, missing_docs)]

protocol_runtime::protocol!("../../specs/hflink.toml");

use hflink::{Header, Message, Packet, Request};

/// Encode a speed command, then decode every frame of `input`, as firmware would: a static
/// decoder, a stack buffer, no allocation. Returns the number of frames decoded.
pub fn firmware_step(input: &[u8], out: &mut [u8; hflink::MAX_FRAME_LEN]) -> usize {
    let speed = hflink::ChassisCoord {
        x: 0.5,
        y: 0.0,
        z: 0.1,
    };
    let packet = Packet {
        header: Header {
            sender: 0x01,
            receiver: 0x11,
        },
        message: Message::Request(Request::SetRobotSpeed(speed)),
    };
    let _ = packet.encode(out);
    let mut decoder = hflink::decoder();
    let mut rest = input;
    let mut n = 0;
    while let Some(frame) = decoder.decode(&mut rest) {
        if Packet::from_frame(frame.bytes).is_ok() {
            n += 1;
        }
    }
    n
}
