//! Times the generated decoder and its baselines in turn, one 16 MiB pass each, many times over,
//! and prints the ratios pass by pass: ratios that a host whose speed drifts cannot fake.
//!
//! Criterion times one benchmark's samples back to back and the next benchmark seconds later;
//! on a shared or virtual machine the host's speed moves between the two by more than the
//! differences being measured (`BENCHMARKS.md` shows the same code reading 0.88x - 1.28x of
//! itself across benchmarks of one run). Here every pass decodes the same stream once with each
//! decoder of a row, one right after the other (milliseconds apart), in an order that rotates
//! from pass to pass; a pass's ratio compares times taken under the same conditions, and the
//! median of many passes is what a drift of the host cannot move. Times are the thread's CPU
//! time, as in the criterion benchmark.
//!
//! Usage: `paired [PASSES] [ROW]` (default 100 passes; `ROW`: only the rows whose name contains
//! it, e.g. `referee` or `-64`), built as the benchmark is (release profile: fat LTO,
//! one codegen unit):
//!
//! ```text
//! cargo run --release -p protocol-benches --bin paired
//! RUSTFLAGS="-C target-feature=+pclmulqdq" CARGO_TARGET_DIR=target/clmul \
//!     cargo run --release -p protocol-benches --features runtime-clmul --bin paired
//! ```
//!
//! With the runtime's early-truncation rule ablated (the measurement `cfg` of the runtime's
//! decoder docs; other flags, so a target directory of its own):
//!
//! ```text
//! RUSTFLAGS="--cfg protocol_ablate_early_truncation" CARGO_TARGET_DIR=target/ablated \
//!     cargo run --release -p protocol-benches --bin paired
//! ```
//!
//! Rows: the eight decoder rows of the benchmark (HFLink and referee, clean and noisy, whole
//! streams and 64-byte chunks). Decoders: `generated`, `best` (the 2 KiB appending feed, the
//! referee's CRC-16 folded with carry-less multiplication), `best-early` (`best` with the
//! early-truncation rule as one masked block test per chunk: the generated decoder's
//! semantics) and, on the referee, `best-slicing` (`best` with a slicing-by-16 CRC-16: the ceiling of a decoder
//! without `unsafe` in a build without `pclmulqdq`). Every decoder's frames are checked against
//! the ground truth before it is timed.
//!
//! For each row and comparison it prints the throughput ratio (the baseline's time over the
//! other's; above 1 the first named is faster) as the median of the passes' ratios, their
//! 10th and 90th percentiles, and the share of passes at 0.9 or more.

use std::hint::black_box;
use std::process::ExitCode;
use std::time::Duration;

use protocol_benches::hand::{
    self,
    appending::{Appending, Early},
};
use protocol_benches::workload::{Noise, Protocol, Workload};
use protocol_benches::{ChunkDecoder, generated, verify};

/// The benchmark's chunk size for chunked rows.
const CHUNK: usize = 64;
/// Passes run before the timed ones (page faults, caches, branch predictors).
const WARM_UP: usize = 3;

/// One decoder of a row: its name and one timed pass over the row's stream.
struct Contender<'a> {
    name: &'static str,
    pass: Box<dyn FnMut() -> Duration + 'a>,
}

/// Checks `make`'s frames on `w` fed in `chunk`s, then returns its timed pass.
fn contender<'a, D: ChunkDecoder + 'a>(
    name: &'static str,
    w: &'a Workload,
    chunk: usize,
    make: impl Fn() -> D + 'a,
) -> Result<Contender<'a>, String> {
    let out = verify::collect(&mut make(), &w.stream, chunk);
    verify::exact(w, &out).map_err(|e| format!("{name} on {}: {e}", w.name()))?;
    let pass = Box::new(move || {
        let start = cpu_time::ThreadTime::now();
        let mut decoder = make();
        black_box(verify::count(&mut decoder, black_box(&w.stream), chunk));
        start.elapsed()
    });
    Ok(Contender { name, pass })
}

/// The decoders timed on `w`'s row.
fn contenders(w: &Workload, chunk: usize) -> Result<Vec<Contender<'_>>, String> {
    Ok(match w.protocol {
        Protocol::HfLink => vec![
            contender("generated", w, chunk, generated::hflink_decoder)?,
            contender("best", w, chunk, Appending::<hand::hflink::HfLink>::default)?,
            contender(
                "best-early",
                w,
                chunk,
                Early::<hand::hflink::HfLink>::default,
            )?,
        ],
        Protocol::Referee => vec![
            contender("generated", w, chunk, generated::referee_decoder)?,
            contender(
                "best",
                w,
                chunk,
                Appending::<hand::referee::RefereeClmul>::default,
            )?,
            contender(
                "best-early",
                w,
                chunk,
                Early::<hand::referee::RefereeClmul>::default,
            )?,
            contender(
                "best-slicing",
                w,
                chunk,
                Appending::<hand::referee::Referee>::default,
            )?,
        ],
    })
}

/// Every contender's time of every pass: `times[contender][pass]`. The order within a pass
/// rotates, so that no decoder always runs first (after the previous row's last pass) or
/// always right after the same other one.
fn time_passes(contenders: &mut [Contender<'_>], passes: usize) -> Vec<Vec<Duration>> {
    let n = contenders.len();
    let mut times = vec![Vec::with_capacity(passes); n];
    for pass in 0..WARM_UP + passes {
        for k in 0..n {
            let i = (k + pass) % n;
            let t = (contenders[i].pass)();
            if pass >= WARM_UP {
                times[i].push(t);
            }
        }
    }
    times
}

/// The `q`-quantile of sorted `values` (nearest rank).
fn quantile(sorted: &[f64], q: f64) -> f64 {
    let rank = (q * (sorted.len() - 1) as f64).round() as usize;
    sorted[rank]
}

/// One comparison's line: `first` against `baseline`, pass by pass.
fn compare(row: &str, names: [&str; 2], [first, baseline]: [&[Duration]; 2]) {
    let mut ratios: Vec<f64> = baseline
        .iter()
        .zip(first)
        .map(|(b, f)| b.as_secs_f64() / f.as_secs_f64())
        .collect();
    ratios.sort_by(f64::total_cmp);
    let met = ratios.iter().filter(|&&r| r >= 0.9).count();
    println!(
        "| {row} | {} vs {} | {:.3} | {:.3} - {:.3} | {}/{} |",
        names[0],
        names[1],
        quantile(&ratios, 0.5),
        quantile(&ratios, 0.1),
        quantile(&ratios, 0.9),
        met,
        ratios.len()
    );
}

/// The median of `times` in nanoseconds per frame of `w`.
fn ns_per_frame(times: &[Duration], w: &Workload) -> f64 {
    let mut ns: Vec<f64> = times.iter().map(|t| t.as_nanos() as f64).collect();
    ns.sort_by(f64::total_cmp);
    quantile(&ns, 0.5) / w.frames.len() as f64
}

fn run(passes: usize, only: &str) -> Result<(), String> {
    let config = if cfg!(feature = "runtime-clmul") {
        "generated decoders with the `clmul` feature"
    } else {
        "default build"
    };
    let rule = if cfg!(protocol_ablate_early_truncation) {
        ", the early-truncation rule ablated"
    } else {
        ""
    };
    println!("{passes} passes per row, {config}{rule}\n");
    println!("| row | decoders | median | 10% - 90% | passes >= 0.9 |");
    println!("|---|---|---:|---:|---:|");
    let mut medians = Vec::new();
    for protocol in [Protocol::HfLink, Protocol::Referee] {
        for noise in [Noise::Clean, Noise::Noisy] {
            let w = Workload::standard(protocol, noise);
            for (feed, chunk) in [("whole", w.stream.len()), ("64", CHUNK)] {
                let row = format!("{}-{feed}", w.name());
                if !row.contains(only) {
                    continue;
                }
                let mut contenders = contenders(&w, chunk)?;
                let times = time_passes(&mut contenders, passes);
                let names: Vec<&str> = contenders.iter().map(|c| c.name).collect();
                let by = |name: &str| names.iter().position(|&n| n == name);
                let pairs = [
                    ("generated", "best"),
                    ("generated", "best-early"),
                    ("best-early", "best"),
                    ("generated", "best-slicing"),
                ];
                for (first, baseline) in pairs {
                    if let (Some(f), Some(b)) = (by(first), by(baseline)) {
                        compare(&row, [first, baseline], [&times[f], &times[b]]);
                    }
                }
                for (name, t) in names.iter().zip(&times) {
                    medians.push(format!("| {row} | {name} | {:.2} |", ns_per_frame(t, &w)));
                }
            }
        }
    }
    println!("\n| row | decoder | median ns/frame |\n|---|---|---:|");
    for line in medians {
        println!("{line}");
    }
    Ok(())
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let usage = "usage: paired [PASSES] [ROW] (PASSES a positive number, default 100)";
    let passes = match args.first().map(|a| a.parse::<usize>()) {
        None => Ok(100),
        Some(Ok(n)) if n > 0 && args.len() <= 2 => Ok(n),
        Some(_) => Err(usage.to_string()),
    };
    let only = args.get(1).map_or("", String::as_str);
    match passes.and_then(|passes| run(passes, only)) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("paired: {e}");
            ExitCode::FAILURE
        }
    }
}
