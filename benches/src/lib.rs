//! Benchmarks of the codecs generated from `specs/hflink.toml` and `specs/referee.toml` against
//! baselines written for the occasion, and the tools behind `BENCHMARKS.md` and
//! `benches/footprint.sh`.
//!
//! This crate owns the workloads and every decoder and encoder the criterion target
//! (`benches/codec.rs`) times:
//!
//! - [`workload`]: fixed-seed 16 MiB streams, clean and noisy, with their ground truth;
//! - [`generated`]: the code `protocol_kit::protocol!` generates, driven the way a user
//!   drives it;
//! - [`hand`]: hand-written, optimized decoders and encoders (slice scan, memchr, masked sums,
//!   slicing-by-16 CRC, zero-copy, small-chunk staging);
//! - [`port`]: ports of the C originals' byte-at-a-time state machines, written from their
//!   behaviour, driven as one loop or with one call per byte;
//! - [`floor`]: a lower bound for any decoder, frames found by their length fields alone;
//! - [`verify`]: running any decoder over a workload and comparing its frames with the ground
//!   truth, which the benchmark does before it times anything;
//! - [`synth`]: synthetic specs of N commands, for the size and expansion-time scaling.
//!
//! It does not own the runtime or the code generator: what it measures about them is in
//! `BENCHMARKS.md`.

// The one exception: the carry-less-multiply CRC-16 of the hand-written baseline is called
// through a run-time CPU feature check (`hand::referee::RefereeClmul`).
#![deny(unsafe_code)]

pub mod encode;
pub mod floor;
pub mod generated;
pub mod hand;
pub mod port;
pub mod synth;
pub mod verify;
pub mod workload;

/// The lengths the `crc16-mcrf4xx` benchmark group times the CRC-16 alone at, from a short
/// frame to a long one (`bench-report` tables the same lengths).
pub const CRC_LENGTHS: [usize; 11] = [16, 32, 48, 64, 80, 96, 112, 128, 256, 1024, 4096];

/// A frame decoder fed a stream in chunks: the one interface the benchmark and the checks drive
/// every decoder through. The sink is generic, not `dyn`: every decoder is monomorphised with
/// the benchmark's sink, as a user's code would be.
pub trait ChunkDecoder {
    /// Feeds one chunk; `sink` gets every frame it completes, in stream order.
    fn feed<F: FnMut(&[u8])>(&mut self, chunk: &[u8], sink: &mut F);
    /// Declares the end of the stream; `sink` gets the frames still held back, if any.
    fn finish<F: FnMut(&[u8])>(&mut self, sink: &mut F);
}

/// Feeds `stream` to `decoder` in chunks of `chunk` bytes (the whole stream at once if `chunk`
/// is at least its length) and calls `sink` for every frame.
#[inline]
pub fn run<D: ChunkDecoder, F: FnMut(&[u8])>(
    decoder: &mut D,
    stream: &[u8],
    chunk: usize,
    sink: &mut F,
) {
    for piece in stream.chunks(chunk.max(1)) {
        decoder.feed(piece, sink);
    }
    decoder.finish(sink);
}
