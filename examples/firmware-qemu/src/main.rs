//! Firmware that runs on QEMU's `mps2-an386` (a Cortex-M4): it decodes every HFLink and
//! referee golden vector and the vectors' noisy streams with the generated codecs, prints what
//! it decoded over semihosting, then counts the instructions per decoded frame of the
//! generated HFLink decoder and of the hand-written one (`benches/firmware/hand/src/codec.rs`) on the same
//! noisy stream, and of the generated referee decoder (each generated one also with its framing
//! alone: frames found, not decoded into packets), and exits. `run.sh` runs it and checks its output against the
//! vectors (`protocol-benches`' `qemu-check`).
//!
//! Counting: QEMU has no DWT cycle counter, but with `-icount shift=0` its virtual clock runs
//! one nanosecond per instruction, and SysTick counts that clock at the board's 25 MHz: one
//! tick per 40 instructions. The firmware also times `cortex_m::asm::delay`, a loop of a known
//! instruction count, so that the checker derives the instructions per tick from the run
//! itself instead of trusting the constant.
//!
//! Output lines (one fact each, space-separated, parsed by the checker):
//! `frame SPEC NAME ok COMMAND HEX` (HEX: the packet encoded back), `frame SPEC NAME error
//! TEXT`, `stream SPEC NAME frame OFFSET HEX`, `stream SPEC NAME stats FRAMES SKIPPED REJECTED`,
//! `calibrate INSTRUCTIONS TICKS`, `measure SPEC DECODER FRAMES BYTES TICKS`, `done`.

#![no_std]
#![no_main]
#![forbid(unsafe_code)]

// The hand-written codec of the footprint firmware, its very source. Only its decoder is
// timed here; its encoders are the footprint firmware's business.
#[allow(dead_code)]
#[path = "../../../benches/firmware/hand/src/codec.rs"]
mod hand;
#[allow(dead_code)]
#[path = "../../../benches/firmware/hand/src/messages.rs"]
mod messages;

use core::fmt::{self, Write as _};
use core::hint::black_box;

use cortex_m::peripheral::SYST;
use cortex_m::peripheral::syst::SystClkSource;
use cortex_m_rt::entry;
use cortex_m_semihosting::{debug, hprintln};

protocol_kit::protocol!("../../specs/hflink.toml");
protocol_kit::protocol!("../../specs/referee.toml");

mod vectors {
    include!(concat!(env!("OUT_DIR"), "/vectors.rs"));
}

/// Passes over the workload for each measurement.
const PASSES: usize = 64;
/// Bytes per chunk fed to the decoders, as a UART driver's DMA half-buffer would hand over.
const CHUNK: usize = 64;

#[panic_handler]
fn panic(info: &core::panic::PanicInfo<'_>) -> ! {
    hprintln!("panic {}", info);
    debug::exit(debug::EXIT_FAILURE);
    loop {
        core::hint::spin_loop();
    }
}

/// One line of output, built on the stack and printed with one semihosting call.
struct Line {
    buf: [u8; 640],
    len: usize,
}

impl Line {
    fn new() -> Self {
        Line {
            buf: [0; 640],
            len: 0,
        }
    }

    fn print(&self) {
        hprintln!(
            "{}",
            core::str::from_utf8(&self.buf[..self.len]).unwrap_or("<not utf-8>")
        );
    }
}

impl fmt::Write for Line {
    fn write_str(&mut self, s: &str) -> fmt::Result {
        let end = self.len + s.len();
        self.buf
            .get_mut(self.len..end)
            .ok_or(fmt::Error)?
            .copy_from_slice(s.as_bytes());
        self.len = end;
        Ok(())
    }
}

struct Hex<'a>(&'a [u8]);

impl fmt::Display for Hex<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.0.iter().try_for_each(|b| write!(f, "{b:02x}"))
    }
}

/// The lines of one golden frame: decoded, then encoded back.
fn golden<P>(
    spec: &str,
    name: &str,
    bytes: &[u8],
    decode: impl Fn(&[u8]) -> Result<P, protocol_kit::DecodeError>,
    command: impl Fn(&P) -> &'static str,
    encode: impl Fn(&P, &mut [u8]) -> Result<usize, protocol_kit::EncodeError>,
) {
    let mut line = Line::new();
    let mut out = [0u8; 512];
    let _ = match decode(bytes) {
        Ok(p) => match encode(&p, &mut out) {
            Ok(n) => write!(
                line,
                "frame {spec} {name} ok {} {}",
                command(&p),
                Hex(&out[..n])
            ),
            Err(e) => write!(line, "frame {spec} {name} encode-error {e}"),
        },
        Err(e) => write!(line, "frame {spec} {name} error {e}"),
    };
    line.print();
}

/// The lines of one stream vector, fed in chunks of 7 bytes.
fn stream<L: protocol_kit::LayoutRef, const N: usize>(
    spec: &str,
    name: &str,
    bytes: &[u8],
    mut decoder: protocol_kit::StreamDecoder<L, N>,
    decodes: impl Fn(&[u8]) -> bool,
) {
    for chunk in bytes.chunks(7) {
        decoder.feed(chunk, |f| {
            let mut line = Line::new();
            let verdict = if decodes(f.bytes) { "" } else { " undecodable" };
            let _ = write!(
                line,
                "stream {spec} {name} frame {} {}{verdict}",
                f.offset,
                Hex(f.bytes)
            );
            line.print();
        });
    }
    while let Some(f) = decoder.flush() {
        hprintln!(
            "stream {} {} frame {} {}",
            spec,
            name,
            f.offset,
            Hex(f.bytes)
        );
    }
    let s = decoder.stats();
    hprintln!(
        "stream {} {} stats {} {} {}",
        spec,
        name,
        s.frames,
        s.skipped_bytes,
        s.rejected()
    );
}

/// SysTick as a free-running 24-bit down-counter of the core clock.
fn start_systick(syst: &mut SYST) {
    syst.set_clock_source(SystClkSource::Core);
    syst.set_reload(0x00FF_FFFF);
    syst.clear_current();
    syst.enable_counter();
}

/// Ticks taken by `f` (less than 2^24 of them: the counter wraps once every 671 million
/// instructions).
fn ticks(f: impl FnOnce()) -> u32 {
    let start = SYST::get_current();
    f();
    let end = SYST::get_current();
    start.wrapping_sub(end) & 0x00FF_FFFF
}

/// The noisy workload: every golden frame, then the vector's stream (garbage, a corrupt frame,
/// a truncated one), in one buffer.
fn workload<'b>(
    frames: &[(&str, &[u8])],
    streams: &[(&str, &[u8])],
    buf: &'b mut [u8],
) -> &'b [u8] {
    let mut len = 0;
    for (_, bytes) in frames.iter().chain(streams) {
        buf[len..len + bytes.len()].copy_from_slice(bytes);
        len += bytes.len();
    }
    &buf[..len]
}

fn measure(spec: &str, decoder: &str, frames: u32, bytes: usize, ticks: u32) {
    hprintln!(
        "measure {} {} {} {} {}",
        spec,
        decoder,
        frames,
        bytes,
        ticks
    );
}

#[entry]
fn main() -> ! {
    let Some(mut peripherals) = cortex_m::Peripherals::take() else {
        hprintln!("error: no peripherals");
        debug::exit(debug::EXIT_FAILURE);
        loop {
            core::hint::spin_loop();
        }
    };
    hprintln!("firmware-qemu: Cortex-M4, generated HFLink and referee codecs");

    for (name, bytes) in vectors::HFLINK_FRAMES {
        golden(
            "hflink",
            name,
            bytes,
            hflink::Packet::decode,
            |p| p.message.command().name(),
            |p, b| p.encode(b),
        );
    }
    for (name, bytes) in vectors::REFEREE_FRAMES {
        golden(
            "referee",
            name,
            bytes,
            referee::Packet::decode,
            |p| p.message.command().name(),
            |p, b| p.encode(b),
        );
    }
    for (name, bytes) in vectors::HFLINK_STREAMS {
        stream("hflink", name, bytes, hflink::decoder(), |f| {
            hflink::Packet::from_frame(f).is_ok()
        });
    }
    for (name, bytes) in vectors::REFEREE_STREAMS {
        stream("referee", name, bytes, referee::decoder(), |f| {
            referee::Packet::from_frame(f).is_ok()
        });
    }

    start_systick(&mut peripherals.SYST);
    const DELAY: u32 = 1_000_000;
    // `delay(n)` runs `subs; bne` n + 1 times.
    let t = ticks(|| cortex_m::asm::delay(black_box(DELAY)));
    hprintln!("calibrate {} {}", 2 * (u64::from(DELAY) + 1), t);

    let mut buf = [0u8; 4096];
    let hf = workload(vectors::HFLINK_FRAMES, vectors::HFLINK_STREAMS, &mut buf);
    let t = ticks(|| {
        for _ in 0..PASSES {
            for chunk in hf.chunks(CHUNK) {
                black_box(black_box(chunk).len());
            }
        }
    });
    measure("hflink", "loop", 0, hf.len() * PASSES, t);

    let mut n = 0u32;
    let mut decoder = hflink::decoder();
    let t = ticks(|| {
        for _ in 0..PASSES {
            for chunk in hf.chunks(CHUNK) {
                decoder.feed(black_box(chunk), |f| {
                    if let Ok(p) = hflink::Packet::from_frame(f.bytes) {
                        black_box(&p);
                        n += 1;
                    }
                });
            }
        }
    });
    measure("hflink", "generated", n, hf.len() * PASSES, t);

    // The framing alone: the frames the stream decoder yields, not decoded into packets.
    let mut n = 0u32;
    let mut decoder = hflink::decoder();
    let t = ticks(|| {
        for _ in 0..PASSES {
            for chunk in hf.chunks(CHUNK) {
                decoder.feed(black_box(chunk), |f| {
                    black_box(f.bytes);
                    n += 1;
                });
            }
        }
    });
    measure("hflink", "generated-framing", n, hf.len() * PASSES, t);

    let mut n = 0u32;
    let mut receiver = hand::Receiver::default();
    let t = ticks(|| {
        for _ in 0..PASSES {
            for chunk in hf.chunks(CHUNK) {
                receiver.feed(black_box(chunk), |f| {
                    if let Some(p) = hand::Packet::from_frame(f) {
                        black_box(&p);
                        n += 1;
                    }
                });
            }
        }
    });
    measure("hflink", "hand", n, hf.len() * PASSES, t);

    let mut buf = [0u8; 4096];
    let rf = workload(vectors::REFEREE_FRAMES, vectors::REFEREE_STREAMS, &mut buf);
    let t = ticks(|| {
        for _ in 0..PASSES {
            for chunk in rf.chunks(CHUNK) {
                black_box(black_box(chunk).len());
            }
        }
    });
    measure("referee", "loop", 0, rf.len() * PASSES, t);

    let mut n = 0u32;
    let mut decoder = referee::decoder();
    let t = ticks(|| {
        for _ in 0..PASSES {
            for chunk in rf.chunks(CHUNK) {
                decoder.feed(black_box(chunk), |f| {
                    if let Ok(p) = referee::Packet::from_frame(f.bytes) {
                        black_box(&p);
                        n += 1;
                    }
                });
            }
        }
    });
    measure("referee", "generated", n, rf.len() * PASSES, t);

    // The framing alone: the frames the stream decoder yields, not decoded into packets.
    let mut n = 0u32;
    let mut decoder = referee::decoder();
    let t = ticks(|| {
        for _ in 0..PASSES {
            for chunk in rf.chunks(CHUNK) {
                decoder.feed(black_box(chunk), |f| {
                    black_box(f.bytes);
                    n += 1;
                });
            }
        }
    });
    measure("referee", "generated-framing", n, rf.len() * PASSES, t);

    hprintln!("done");
    debug::exit(debug::EXIT_SUCCESS);
    loop {
        core::hint::spin_loop();
    }
}
