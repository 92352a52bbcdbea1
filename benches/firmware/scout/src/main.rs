//! Scout firmware with the generated code: decode every UART frame that arrives, decode its
//! payload, and send the packet back. The Scout spec has scaled fields (`f32` in Rust, 8- and
//! 16-bit integers on the wire, one clamped and truncated), so this binary shows what their
//! arithmetic links in: `benches/footprint.sh` lists its double-precision soft-float helpers.
//!
//! The received bytes come from `black_box`, so nothing is constant folded.

#![no_std]
#![no_main]
#![forbid(unsafe_code)]

use core::hint::black_box;

use cortex_m_rt::entry;

protocol::protocol!("../../../specs/scout.toml");

use scout::Packet;

#[panic_handler]
fn panic(_: &core::panic::PanicInfo<'_>) -> ! {
    loop {
        core::hint::spin_loop();
    }
}

#[entry]
fn main() -> ! {
    let mut decoder = scout::decoder();
    let mut out = [0u8; scout::MAX_FRAME_LEN];
    loop {
        // A chunk from the UART: unknown to the compiler.
        let rx = black_box([0u8; 64]);
        let mut input = &rx[..];
        while let Some(frame) = decoder.decode(&mut input) {
            let echoed = Packet::from_frame(frame.bytes)
                .ok()
                .and_then(|p| p.encode(&mut out).ok());
            if let Some(n) = echoed {
                black_box(&out[..n]);
            }
        }
        black_box(decoder.stats());
    }
}
