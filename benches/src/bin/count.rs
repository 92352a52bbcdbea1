//! Decodes one benchmark workload once, for instruction counting under valgrind: a measure of
//! a decoder's cost that, unlike a timing, does not depend on what else the machine runs.
//!
//! Usage: `count PROTOCOL NOISE FEED DECODER [BYTES]`, with `PROTOCOL` `hflink` or `referee`,
//! `NOISE` `clean` or `noisy`, `FEED` `whole` or a chunk size in bytes (`64`), `DECODER` one of
//! `generated`, `generated-small` (the same with the 384-byte buffer microcontrollers get),
//! `generated-ref` (the layout read through a reference, as the run-time codec reads its own),
//! `hand` (the staged slice scan), `best` (the 2 KiB appending feed, the carry-less CRC-16),
//! `crcfast` (`best` with the `crc-fast` crate's CRC-16), `best-slicing` (`best` with a
//! slicing-by-16 CRC-16) or `best-early` (`best` with the early-truncation rule in its cheapest
//! form, [`Early`]), and `BYTES` the stream's length (default 1 MiB: the workloads of
//! [`workload`](protocol_benches::workload) with another length, drawn from the same seeds).
//!
//! The stream is drawn and the decoder's frames are checked against the ground truth first;
//! then the stream is decoded once more inside `timed_decode`, the one function to count:
//!
//! ```text
//! cargo build --release -p protocol-benches --bin count
//! valgrind --tool=callgrind --collect-atstart=no --toggle-collect='*timed_decode*' \
//!     target/release/count hflink clean 64 generated
//! ```
//!
//! It prints the frames and frame bytes the counted run returned, so that callgrind's total
//! divides into instructions per frame. `benches/count.sh` runs every workload, feed and
//! decoder this way and prints the table.

use std::hint::black_box;
use std::process::ExitCode;

use protocol_benches::hand::{
    self, Staged,
    appending::{Appending, Early},
};
use protocol_benches::workload::{Noise, Protocol, Workload};
use protocol_benches::{ChunkDecoder, generated, verify};

/// The counted work: one decoder, new, over the whole stream. Out of line, so that callgrind
/// can collect exactly its instructions.
#[inline(never)]
fn timed_decode<D: ChunkDecoder>(mut decoder: D, stream: &[u8], chunk: usize) -> (usize, usize) {
    verify::count(&mut decoder, black_box(stream), chunk)
}

/// Checks `make`'s frames on `w` against the ground truth, then decodes once more, counted.
fn run<D: ChunkDecoder>(w: &Workload, chunk: usize, make: impl Fn() -> D) -> Result<(), String> {
    let out = verify::collect(&mut make(), &w.stream, chunk);
    verify::exact(w, &out)?;
    let (frames, bytes) = timed_decode(make(), &w.stream, chunk);
    println!(
        "{} stream_bytes={} frames={frames} frame_bytes={bytes}",
        w.name(),
        w.stream.len()
    );
    Ok(())
}

/// Which decoder to count.
#[derive(Clone, Copy)]
enum Decoder {
    Generated,
    Hand,
    Best,
    /// `best` with the `crc-fast` crate's CRC-16 (the referee only).
    CrcFast,
    /// `best` with a slicing-by-16 CRC-16 (the referee only).
    BestSlicing,
    /// `best` with the early-truncation rule.
    BestEarly,
    /// The generated decoder with the 384-byte buffer microcontrollers get (hosts get 2 KiB).
    GeneratedSmall,
    /// The generated decoder with its layout read through a reference, as the run-time codec
    /// reads its own.
    GeneratedByRef,
}

fn parse(args: &[String]) -> Result<(Workload, usize, Decoder), String> {
    let usage = "usage: count hflink|referee clean|noisy whole|CHUNK generated|generated-small|generated-ref|hand|best|crcfast|best-slicing|best-early [BYTES]";
    let [protocol, noise, feed, decoder, rest @ ..] = args else {
        return Err(usage.into());
    };
    let protocol = match protocol.as_str() {
        "hflink" => Protocol::HfLink,
        "referee" => Protocol::Referee,
        _ => return Err(usage.into()),
    };
    let noise = match noise.as_str() {
        "clean" => Noise::Clean,
        "noisy" => Noise::Noisy,
        _ => return Err(usage.into()),
    };
    let decoder = match decoder.as_str() {
        "generated" => Decoder::Generated,
        "hand" => Decoder::Hand,
        "best" => Decoder::Best,
        "crcfast" => Decoder::CrcFast,
        "best-slicing" => Decoder::BestSlicing,
        "best-early" => Decoder::BestEarly,
        "generated-small" => Decoder::GeneratedSmall,
        "generated-ref" => Decoder::GeneratedByRef,
        _ => return Err(usage.into()),
    };
    let len = match rest {
        [] => 1 << 20,
        [bytes] => bytes.parse().map_err(|e| format!("BYTES: {e}"))?,
        _ => return Err(usage.into()),
    };
    // The seeds of the standard workloads, at another length.
    let seed = Workload::standard_seed(protocol, noise);
    let w = Workload::generate(protocol, noise, len, seed);
    let chunk = match feed.as_str() {
        "whole" => w.stream.len(),
        n => n.parse().map_err(|e| format!("CHUNK: {e}"))?,
    };
    Ok((w, chunk, decoder))
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let result = parse(&args).and_then(|(w, chunk, decoder)| match (w.protocol, decoder) {
        (Protocol::HfLink, Decoder::Generated) => run(&w, chunk, generated::hflink_decoder),
        (Protocol::HfLink, Decoder::GeneratedSmall) => {
            run(&w, chunk, generated::hflink_decoder_small)
        }
        (Protocol::Referee, Decoder::GeneratedSmall) => {
            run(&w, chunk, generated::referee_decoder_small)
        }
        (Protocol::HfLink, Decoder::GeneratedByRef) => {
            run(&w, chunk, generated::hflink_decoder_by_ref)
        }
        (Protocol::Referee, Decoder::GeneratedByRef) => {
            run(&w, chunk, generated::referee_decoder_by_ref)
        }
        (Protocol::HfLink, Decoder::Hand) => {
            run(&w, chunk, Staged::<hand::hflink::HfLink>::default)
        }
        (Protocol::HfLink, Decoder::Best | Decoder::CrcFast | Decoder::BestSlicing) => {
            run(&w, chunk, Appending::<hand::hflink::HfLink>::default)
        }
        (Protocol::HfLink, Decoder::BestEarly) => {
            run(&w, chunk, Early::<hand::hflink::HfLink>::default)
        }
        (Protocol::Referee, Decoder::BestEarly) => {
            run(&w, chunk, Early::<hand::referee::RefereeClmul>::default)
        }
        (Protocol::Referee, Decoder::Generated) => run(&w, chunk, generated::referee_decoder),
        (Protocol::Referee, Decoder::Hand) => {
            run(&w, chunk, Staged::<hand::referee::Referee>::default)
        }
        (Protocol::Referee, Decoder::Best) => {
            run(&w, chunk, Appending::<hand::referee::RefereeClmul>::default)
        }
        (Protocol::Referee, Decoder::CrcFast) => run(
            &w,
            chunk,
            Appending::<hand::referee::RefereeCrcFast>::default,
        ),
        (Protocol::Referee, Decoder::BestSlicing) => {
            run(&w, chunk, Appending::<hand::referee::Referee>::default)
        }
    });
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("count: {e}");
            ExitCode::FAILURE
        }
    }
}
