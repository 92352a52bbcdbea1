// The harness of the generated firmware (`generated/`, `scout/`, `synth/`), included by each:
// `echo_firmware!(module)` is the panic handler and the entry point that decode every frame
// that arrives with the module's decoder, decode its payload, and send the packet back (so
// that every command's encoder and decoder is reachable, as in a node that both sends and
// receives every command).
//
// The received bytes come from `black_box`, so nothing is constant folded; no panic is
// reachable (the handler is never linked in a way that matters to the sizes).

macro_rules! echo_firmware {
    ($module:ident) => {
        #[panic_handler]
        fn panic(_: &core::panic::PanicInfo<'_>) -> ! {
            loop {
                core::hint::spin_loop();
            }
        }

        #[cortex_m_rt::entry]
        fn main() -> ! {
            let mut decoder = $module::decoder();
            let mut out = [0u8; $module::MAX_FRAME_LEN];
            loop {
                // A chunk from the UART: unknown to the compiler.
                let rx = core::hint::black_box([0u8; 64]);
                let mut input = &rx[..];
                while let Some(frame) = decoder.decode(&mut input) {
                    let echoed = $module::Packet::from_frame(frame.bytes)
                        .ok()
                        .and_then(|p| p.encode(&mut out).ok());
                    if let Some(n) = echoed {
                        core::hint::black_box(&out[..n]);
                    }
                }
                core::hint::black_box(decoder.stats());
            }
        }
    };
}
