//! HFLink firmware written by hand, doing what `generated/` does: decode every frame that
//! arrives (resynchronising one byte after a rejected start), decode its payload by direction
//! and command, count what it dropped, and send the packet back.
//!
//! Written as a firmware engineer would for this one protocol: a 256-byte receive buffer
//! scanned in place, the sum in a plain loop, payload structs with hand-written readers and
//! writers (`codec.rs`, `messages.rs`). Built with the same profile as `generated/`, for the
//! footprint comparison.

#![no_std]
#![no_main]
#![forbid(unsafe_code)]

mod codec;
mod messages;

use core::hint::black_box;

use codec::{MAX_FRAME, Packet, Receiver, Stats};
use cortex_m_rt::entry;

#[panic_handler]
fn panic(_: &core::panic::PanicInfo<'_>) -> ! {
    loop {
        core::hint::spin_loop();
    }
}

#[entry]
fn main() -> ! {
    let mut receiver = Receiver {
        buf: [0; 256],
        len: 0,
        stats: Stats::default(),
    };
    let mut out = [0u8; MAX_FRAME];
    loop {
        // A chunk from the UART: unknown to the compiler.
        let rx = black_box([0u8; 64]);
        receiver.feed(&rx, |frame| {
            if let Some(n) = Packet::from_frame(frame).and_then(|p| p.encode(&mut out)) {
                black_box(&out[..n]);
            }
        });
        black_box(receiver.stats);
    }
}
