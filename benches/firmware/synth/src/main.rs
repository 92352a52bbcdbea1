//! The generated firmware of `generated/`, built from a synthetic spec of N commands that
//! `footprint.sh` writes to a temporary directory and names with `PROTOCOL_SPEC_DIR` (the
//! `protocol!` macro's override of the directory spec paths are relative to).

#![no_std]
#![no_main]
#![forbid(unsafe_code)]

use core::hint::black_box;

use cortex_m_rt::entry;

protocol::protocol!("synth.toml");

use synth::Packet;

#[panic_handler]
fn panic(_: &core::panic::PanicInfo<'_>) -> ! {
    loop {
        core::hint::spin_loop();
    }
}

#[entry]
fn main() -> ! {
    let mut decoder = synth::decoder();
    let mut out = [0u8; synth::MAX_FRAME_LEN];
    loop {
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
