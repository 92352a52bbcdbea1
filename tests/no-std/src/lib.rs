//! A `#![no_std]`, heap-free crate that expands the real specs, built for
//! `thumbv7em-none-eabihf` in CI: proof that the runtime and all generated code need neither
//! `std` nor `alloc`, and that generated code passes `deny(warnings, missing_docs)`.
//!
//! The [`derived`] module expands specs again with `derive(serde, defmt)`: the same proof for
//! the serde and defmt impls of generated types, and generated packets logged with
//! `defmt::info!` as firmware would (built, not linked: the firmware's defmt logger and its
//! host decoder are not part of this check).
//!
//! The [`session`] module holds HFLink's session requester on an async UART, as firmware does.

#![no_std]
#![forbid(unsafe_code)]
#![deny(warnings, missing_docs)]

// Every bundled spec of the registry (`tests/catalogue.toml`), written by the build script.
include!(concat!(env!("OUT_DIR"), "/specs.rs"));
// The payload types beyond fixed-width primitives: 24-bit integers, kept bitfield bits,
// bit-packed arrays, text.
protocol_kit::protocol!("../../protocol-codegen/tests/features/int24.toml");
protocol_kit::protocol!("../../protocol-codegen/tests/features/reserved_bits.toml");
protocol_kit::protocol!("../../protocol-codegen/tests/features/packed.toml");
protocol_kit::protocol!("../../protocol-codegen/tests/features/text.toml");

pub mod session;

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

/// Decode a Scout CAN frame, as a CAN interrupt handler would.
pub fn scout_can(id: u32, data: &[u8]) -> Option<scout::Message> {
    let frame = protocol_kit::CanFrame::new(id, data).ok()?;
    scout::CanPacket::decode(&frame).ok().map(|p| p.message)
}

/// Count the valid frames of each serial spec in `input`.
pub fn count_frames(input: &[u8]) -> [usize; 4] {
    let mut counts = [0; 4];
    let (mut a, mut b, mut c, mut d) = (
        referee::decoder(),
        referee2018::decoder(),
        scout::decoder(),
        roborts::decoder(),
    );
    let (mut ia, mut ib, mut ic, mut id) = (input, input, input, input);
    while a.decode(&mut ia).is_some() {
        counts[0] += 1;
    }
    while b.decode(&mut ib).is_some() {
        counts[1] += 1;
    }
    while c.decode(&mut ic).is_some() {
        counts[2] += 1;
    }
    while let Some(f) = d.decode(&mut id) {
        if roborts::Packet::from_frame(f.bytes).is_ok() {
            counts[3] += 1;
        }
    }
    counts
}

/// Decode a Dynamixel status packet (byte-stuffed) and a feedback frame, as firmware would.
pub fn dynamixel(input: &[u8]) -> (usize, usize) {
    let (mut packets, mut feedback) = (dynamixel::decoder(), dynamixel::feedback_decoder());
    let (mut a, mut b) = (input, input);
    let (mut n, mut m) = (0, 0);
    while let Some(f) = packets.decode(&mut a) {
        if dynamixel::Packet::from_frame(f.bytes).is_ok() {
            n += 1;
        }
    }
    while let Some(f) = feedback.decode(&mut b) {
        if dynamixel::FeedbackPacket::from_frame(f.bytes).is_ok() {
            m += 1;
        }
    }
    (n, m)
}

/// Specs expanded with `derive(serde, defmt)`: directions (HFLink), bytes (CRSF), repeated
/// groups, optional fields and text (u-blox), a frame format without commands (S.BUS), CAN
/// (Scout), byte stuffing and a second format (Dynamixel), bit-packed arrays and texts.
pub mod derived {
    // defmt's logging macros name `defmt::...`: the facade's re-export under that name.
    use protocol_kit::defmt;

    protocol_kit::protocol!("../../specs/hflink.toml", derive(serde, defmt));
    protocol_kit::protocol!("../../specs/crsf.toml", derive(serde, defmt));
    protocol_kit::protocol!("../../specs/ubx.toml", derive(serde, defmt));
    protocol_kit::protocol!("../../specs/sbus.toml", derive(serde, defmt));
    protocol_kit::protocol!("../../specs/scout.toml", derive(serde, defmt));
    protocol_kit::protocol!("../../specs/dynamixel.toml", derive(serde, defmt));
    protocol_kit::protocol!(
        "../../protocol-codegen/tests/features/packed.toml",
        derive(serde, defmt)
    );
    protocol_kit::protocol!(
        "../../protocol-codegen/tests/features/text.toml",
        derive(serde, defmt)
    );

    /// Decode every HFLink frame of `input` and log each packet with `defmt::info!` (the
    /// generated `Format` impls), or the error of a frame that does not decode.
    pub fn log_hflink(input: &[u8]) -> usize {
        let mut decoder = hflink::decoder();
        let mut rest = input;
        let mut n = 0;
        while let Some(frame) = decoder.decode(&mut rest) {
            match hflink::Packet::from_frame(frame.bytes) {
                Ok(packet) => {
                    defmt::info!("frame at {}: {}", frame.offset, packet);
                    n += 1;
                }
                Err(e) => defmt::warn!("frame at {}: {}", frame.offset, e),
            }
        }
        n
    }

    /// Log a u-blox and a Scout CAN packet, whose payloads hold groups, texts, optional fields
    /// and kept unknown enum values.
    pub fn log_others(ubx_frame: &[u8], can: &protocol_kit::CanFrame) {
        if let Ok(packet) = ubx::Packet::decode(ubx_frame) {
            defmt::info!("u-blox: {}", packet);
        }
        if let Ok(packet) = scout::CanPacket::decode(can) {
            defmt::info!("scout: {}", packet);
        }
    }
}

/// The RAM a generated module's docs state of its decoder, from `decoder_ram`, is the decoder's
/// size on the target built for: this crate is built for thumbv7em (32-bit pointers) by CI and
/// for the host (64-bit) by the workspace's tests, so both figures of the docs are checked.
const fn stated_ram(max_frame: usize) -> usize {
    let ram = protocol_kit::decoder::decoder_ram(max_frame, size_of::<usize>());
    ram.buffer + ram.state
}
const _: () = assert!(size_of::<hflink::Decoder>() == stated_ram(hflink::MAX_FRAME_LEN));
const _: () = assert!(size_of::<crsf::Decoder>() == stated_ram(crsf::MAX_FRAME_LEN));
const _: () = assert!(size_of::<ubx::Decoder>() == stated_ram(ubx::MAX_FRAME_LEN));
const _: () = assert!(size_of::<roborts::Decoder>() == stated_ram(roborts::MAX_FRAME_LEN));
