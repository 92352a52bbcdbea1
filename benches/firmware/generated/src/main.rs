//! HFLink firmware with the generated code: decode every frame that arrives, decode its
//! payload, and send a frame back (the packet itself, so that every command's encoder and
//! decoder is reachable, as in a node that both sends and receives every command).
//!
//! The received bytes come from `black_box`, so nothing is constant folded; no panic is
//! reachable (the handler is never linked in a way that matters to the sizes).

#![no_std]
#![no_main]
#![forbid(unsafe_code)]

use core::hint::black_box;

use cortex_m_rt::entry;

protocol::protocol!("../../../specs/hflink.toml");

use hflink::Packet;

#[panic_handler]
fn panic(_: &core::panic::PanicInfo<'_>) -> ! {
    loop {
        core::hint::spin_loop();
    }
}

#[entry]
fn main() -> ! {
    let mut decoder = hflink::decoder();
    let mut out = [0u8; hflink::MAX_FRAME_LEN];
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
