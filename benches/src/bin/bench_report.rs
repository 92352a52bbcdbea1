//! Turns the medians criterion saved after `cargo bench -p protocol-benches` into the Markdown
//! tables of `BENCHMARKS.md`: throughput, time per frame, and the ratios its targets are set
//! on.
//!
//! Usage: `bench-report [CRITERION_DIR]`; by default `$CARGO_TARGET_DIR/criterion`, else
//! `target/criterion`. It draws the workloads again (they are fixed-seed) to count their frames.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use protocol_benches::CRC_LENGTHS;
use protocol_benches::encode::FRAMES;
use protocol_benches::workload::{Noise, Protocol, Workload};

/// The median of one benchmark, in nanoseconds per iteration.
fn median(dir: &Path, group: &str, id: &str) -> Option<f64> {
    let path = dir.join(group).join(id).join("new").join("estimates.json");
    let text = std::fs::read_to_string(path).ok()?;
    let v: serde_json::Value = serde_json::from_str(&text).ok()?;
    v["median"]["point_estimate"].as_f64()
}

fn cell(ns: Option<f64>, bytes: usize, frames: usize) -> String {
    match ns {
        Some(ns) => format!(
            "{:.2} ms, {:.2} GB/s, {:.1} ns/frame",
            ns / 1e6,
            bytes as f64 / ns,
            ns / frames as f64
        ),
        None => "not run".into(),
    }
}

fn ratio(num: Option<f64>, den: Option<f64>) -> String {
    match (num, den) {
        (Some(a), Some(b)) if b > 0.0 => format!("{:.2}x", a / b),
        _ => "-".into(),
    }
}

/// Benchmark ids timed on clean streams only (the floors).
const CLEAN_ONLY: [&str; 2] = ["floor", "floor-checked"];

/// Prints one decoder table under its header line `head`: a row per stream and feed of `rows`,
/// its frame count when `frames` is set, a cell for each of the first `shown` ids of `ids` (the
/// others are read for the ratios only), then for each `(a, b)` of `ratios` the ratio of
/// `ids[a]`'s median to `ids[b]`'s (`ids[b]`'s throughput against `ids[a]`'s).
fn decoder_table(
    dir: &Path,
    rows: &[(&Workload, String, &str)],
    head: &str,
    frames: bool,
    (ids, shown): (&[&str], usize),
    ratios: &[(usize, usize)],
) {
    println!("{head}");
    let mut sep = String::from("|---|---|");
    if frames {
        sep.push_str("---:|");
    }
    sep.push_str(&"---|".repeat(shown));
    sep.push_str(&"---:|".repeat(ratios.len()));
    println!("{sep}");
    for (w, group, feed_name) in rows {
        let (bytes, count) = (w.stream.len(), w.frames.len());
        let medians: Vec<Option<f64>> = ids.iter().map(|id| median(dir, group, id)).collect();
        let mut line = format!("| {} | {feed_name} |", w.name());
        if frames {
            line.push_str(&format!(" {count} |"));
        }
        for (id, &m) in ids.iter().zip(&medians).take(shown) {
            let text = if CLEAN_ONLY.contains(id) && w.noise != Noise::Clean {
                "(clean streams only)".into()
            } else {
                cell(m, bytes, count)
            };
            line.push_str(&format!(" {text} |"));
        }
        for &(a, b) in ratios {
            let at = |i: usize| medians.get(i).copied().flatten();
            line.push_str(&format!(" {} |", ratio(at(a), at(b))));
        }
        println!("{line}");
    }
    println!();
}

fn main() -> ExitCode {
    let dir = std::env::args()
        .nth(1)
        .map(PathBuf::from)
        .unwrap_or_else(|| {
            std::env::var_os("CARGO_TARGET_DIR")
                .map(PathBuf::from)
                .unwrap_or_else(|| PathBuf::from("target"))
                .join("criterion")
        });
    if !dir.is_dir() {
        eprintln!("bench-report: no criterion results in {}", dir.display());
        return ExitCode::FAILURE;
    }
    // The workloads are drawn once (fixed seeds); both tables read them.
    let workloads: Vec<Workload> = [Protocol::HfLink, Protocol::Referee]
        .into_iter()
        .flat_map(|p| [Noise::Clean, Noise::Noisy].map(|n| Workload::standard(p, n)))
        .collect();
    let rows = || {
        workloads.iter().flat_map(|w| {
            [("whole", "whole"), ("64", "64-byte chunks")]
                .map(|(feed, feed_name)| (w, format!("{}-{feed}", w.name()), feed_name))
        })
    };
    let all: Vec<_> = rows().collect();
    let referee: Vec<_> = rows()
        .filter(|(w, ..)| w.protocol == Protocol::Referee)
        .collect();
    decoder_table(
        &dir,
        &all,
        "| stream | feed | frames | generated | hand-written | byte-at-a-time port | generated, layout by reference | generated vs hand | generated vs port | hand vs port | by reference vs hand |",
        true,
        (&["generated", "hand", "port", "generated-by-ref"], 4),
        &[(1, 0), (2, 0), (2, 1), (1, 3)],
    );
    // Against the best baseline known: the 2 KiB appending feed and the carry-less CRC-16.
    // `generated-crcfast`: the generated decoder built with the `crc-fast` host feature
    // (`cargo bench -p protocol-benches --features runtime-crc-fast`), "not run" otherwise.
    decoder_table(
        &dir,
        &all,
        "| stream | feed | generated | generated, crc-fast | best baseline | staged hand-written | generated vs best | crc-fast vs best | hand vs best |",
        false,
        (&["generated", "generated-crcfast", "best", "hand"], 4),
        &[(2, 0), (2, 1), (2, 3)],
    );
    // What a decoder without `unsafe` can reach on the referee: the best baseline's feed and
    // scan with the CRC-16s safe code has (slicing-by-16; the `crc-fast` crate), against the
    // best baseline, and the generated decoder in each build against the ceiling of its CRC.
    decoder_table(
        &dir,
        &referee,
        "| stream | feed | best baseline | best, slicing-by-16 CRC | best, crc-fast CRC | generated | generated, crc-fast | best-slicing vs best | best-crcfast vs best | generated vs best-slicing | crc-fast vs best-crcfast |",
        false,
        (
            &[
                "best",
                "best-slicing",
                "best-crcfast",
                "generated",
                "generated-crcfast",
            ],
            5,
        ),
        &[(0, 1), (0, 2), (1, 3), (2, 4)],
    );
    // What the rows can reach: the floors (framing only, and framing with the runtime's checks;
    // clean streams only) against the port, and the port driven with one call per byte, the
    // originals' interface.
    decoder_table(
        &dir,
        &all,
        "| stream | feed | generated | floor: length walk | floor: length walk and checks | port, one call per byte | floor vs port | checked floor vs port | generated vs checked floor | generated vs port per byte |",
        false,
        // `port` is read for the ratios only.
        (
            &[
                "generated",
                "floor",
                "floor-checked",
                "port-per-byte",
                "port",
            ],
            4,
        ),
        &[(4, 1), (4, 2), (2, 0), (3, 0)],
    );
    println!(
        "| encoder (1M frames) | frame bytes | generated | hand-written | generated, crc-fast | generated vs hand | crc-fast vs hand |"
    );
    println!("|---|---:|---|---|---|---:|---:|");
    for (group, frame) in [("hflink-encode", 28usize), ("referee-encode", 25)] {
        let [g, h, c] =
            ["generated", "hand", "generated-crcfast"].map(|id| median(&dir, group, id));
        let bytes = frame * FRAMES as usize;
        println!(
            "| {group} | {frame} | {} | {} | {} | {} | {} |",
            cell(g, bytes, FRAMES as usize),
            cell(h, bytes, FRAMES as usize),
            cell(c, bytes, FRAMES as usize),
            ratio(h, g),
            ratio(h, c),
        );
    }
    println!();
    // The CRC-16 alone: slicing-by-16 (the default build) against the `crc-fast` crate (the
    // build with `runtime-crc-fast`) and the runtime's carry-less folding (the build with
    // `runtime-clmul` for a CPU with `pclmulqdq`), from a short frame to a long one. Criterion
    // files a benchmark named `a/b` under `a_b`.
    println!(
        "| bytes | slicing-by-16 | crc-fast | clmul | crc-fast vs slicing-by-16 | clmul vs slicing-by-16 |"
    );
    println!("|---:|---:|---:|---:|---:|---:|");
    for len in CRC_LENGTHS {
        let [s, f, c] = ["slicing-16", "crc-fast", "clmul"]
            .map(|id| median(&dir, "crc16-mcrf4xx", &format!("{id}_{len}")));
        let ns = |v: Option<f64>| v.map_or_else(|| "not run".into(), |v| format!("{v:.1} ns"));
        println!(
            "| {len} | {} | {} | {} | {} | {} |",
            ns(s),
            ns(f),
            ns(c),
            ratio(s, f),
            ratio(s, c)
        );
    }
    ExitCode::SUCCESS
}
