//! The benchmarks behind `BENCHMARKS.md`, in one run so that ratios compare like with like:
//!
//! - decoders (generated, hand-written, byte-at-a-time port) on 16 MiB streams of HFLink and
//!   referee frames, clean and noisy, fed whole and in 64-byte chunks: 8 groups; in each, the
//!   port is also driven with one call per byte, and on clean streams the two length-walk floors
//!   are timed (framing only, and framing with the runtime's checks); with
//!   `PROTOCOL_BENCH_ABLATION=1`, also the generated decoder reading its layout through a
//!   reference, as the run-time codec does, and with the 384-byte buffer microcontrollers get
//!   (`generated-small`; hosts get 2 KiB), and the best baseline with the early-truncation rule
//!   as one masked block test per chunk (`best-early`: the generated decoder's semantics); in
//!   the referee groups, the best baseline's feed and scan also with the two CRC-16s open to code without `unsafe` (`best-slicing`: slicing-by-16;
//!   `best-crcfast`: the `crc-fast` crate), the ceilings of a safe decoder;
//! - encoders (generated, hand-written): a million frames into a reused buffer, for each
//!   protocol.
//!
//! Before a decoder is timed, its frames on that stream and feed are compared with the ground
//! truth: the generated and hand-written decoders must return exactly the untouched
//! frames, the port (which, like the originals, does not rescan) a subset of them, in order,
//! with no frame of its own. Encoders must write the same bytes, which the generated decoder
//! reads back.
//!
//! Times are the benchmark thread's CPU time ([`ThreadCpuTime`]). Run: `cargo bench -p
//! protocol-benches` (about 4 minutes; 5 with the ablation), or with `PROTOCOL_BENCH_QUICK=1`
//! (10 samples of 1 s, under 2 minutes). Criterion's own arguments work too, e.g. `cargo bench
//! -p protocol-benches -- hflink-clean`. `bench-report` turns the saved medians into the tables
//! of `BENCHMARKS.md`. With `--features runtime-crc-fast`, the generated code is timed with the
//! facade's `crc-fast` host feature, as `generated-crcfast`. With `--features runtime-clmul`
//! and `RUSTFLAGS="-C target-feature=+pclmulqdq"` (best in a target directory of its own), the
//! runtime folds reflected CRCs with carry-less multiplication: the generated decoders fold the
//! referee's CRC-16 as `best` does (`best-slicing` keeps its tables), and the CRC-16 alone is
//! timed as `clmul/LEN`.

// `criterion_group!` generates an undocumented public function.
#![allow(missing_docs)]

use std::hint::black_box;
use std::time::Duration;

use criterion::measurement::{Measurement, ValueFormatter, WallTime};
use criterion::{
    BenchmarkGroup, Criterion, SamplingMode, Throughput, criterion_group, criterion_main,
};
use protocol_benches::encode::{self, FRAMES};
use protocol_benches::floor::{CheckedWalk, HfLinkFormat, LengthWalk, RefereeFormat};
use protocol_benches::hand::{
    self, Staged,
    appending::{Appending, Early},
};
use protocol_benches::port::{OneCallPerByte, hflink::HfLinkPort, referee::RefereePort};
use protocol_benches::verify::{self, Output};
use protocol_benches::workload::{Noise, Protocol, Workload};
use protocol_benches::{CRC_LENGTHS, ChunkDecoder, generated};
use protocol_runtime::checksum::Slicing16;

/// Bytes per chunk of the chunked feed.
const CHUNK: usize = 64;

/// The generated decoders' and encoders' benchmark id: `generated-crcfast` when built with the
/// `runtime-crc-fast` feature (the facade's `crc-fast` host feature: CRCs by the `crc-fast`
/// crate), so that criterion keeps the results of both builds side by side for `bench-report`.
const GENERATED: &str = if cfg!(feature = "runtime-crc-fast") {
    "generated-crcfast"
} else {
    "generated"
};

/// [`GENERATED`] for the layout read through a reference.
const GENERATED_BY_REF: &str = if cfg!(feature = "runtime-crc-fast") {
    "generated-crcfast-by-ref"
} else {
    "generated-by-ref"
};

/// Whether to also time the generated decoders with the layout read through a reference (as
/// the run-time codec does), to show what a compile-time layout buys.
fn ablation() -> bool {
    std::env::var_os("PROTOCOL_BENCH_ABLATION").is_some_and(|v| v != "0")
}

/// Thread CPU time instead of wall time: the machines this runs on share their cores with
/// other work, and wall time counts the time the benchmark thread waits for a core (on the
/// 2-core machine of `BENCHMARKS.md`, under a load average of 5-8, wall-time medians of the same
/// decoder varied 2x from one group to the next). CPU time of the one thread that decodes is
/// what a decoder costs. Values and units are printed as criterion prints durations.
struct ThreadCpuTime;

static WALL: WallTime = WallTime;

impl Measurement for ThreadCpuTime {
    type Intermediate = cpu_time::ThreadTime;
    type Value = Duration;

    fn start(&self) -> Self::Intermediate {
        cpu_time::ThreadTime::now()
    }
    fn end(&self, start: Self::Intermediate) -> Self::Value {
        start.elapsed()
    }
    fn add(&self, a: &Self::Value, b: &Self::Value) -> Self::Value {
        *a + *b
    }
    fn zero(&self) -> Self::Value {
        Duration::ZERO
    }
    fn to_f64(&self, value: &Self::Value) -> f64 {
        value.as_nanos() as f64
    }
    fn formatter(&self) -> &dyn ValueFormatter {
        WALL.formatter()
    }
}

fn config() -> Criterion<ThreadCpuTime> {
    let quick = std::env::var_os("PROTOCOL_BENCH_QUICK").is_some_and(|v| v != "0");
    let (samples, warm_up, measure) = if quick {
        (10, Duration::from_millis(300), Duration::from_secs(1))
    } else {
        (30, Duration::from_secs(1), Duration::from_secs(3))
    };
    Criterion::default()
        .with_measurement(ThreadCpuTime)
        .sample_size(samples)
        .warm_up_time(warm_up)
        .measurement_time(measure)
        .nresamples(10_000)
        .without_plots()
}

/// Which decoders a stream is checked and timed with.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Kind {
    /// Must return exactly the ground truth.
    Exact,
    /// The byte-at-a-time port: a subset of the ground truth, no frame of its own.
    Port,
}

/// Checks a decoder's frames, then times it.
fn bench_decoder<D: ChunkDecoder>(
    g: &mut BenchmarkGroup<'_, ThreadCpuTime>,
    id: &str,
    w: &Workload,
    chunk: usize,
    kind: Kind,
    make: impl Fn() -> D,
) {
    let out: Output = verify::collect(&mut make(), &w.stream, chunk);
    match kind {
        Kind::Exact => {
            if let Err(e) = verify::exact(w, &out) {
                panic!("{id}: {e}");
            }
        }
        Kind::Port => {
            let loss = verify::compare(w, &out);
            let clean = w.noise == Noise::Clean;
            assert!(
                loss.extra == 0 && (loss.lost == 0 || !clean),
                "{id} on {}: {loss}",
                w.name()
            );
            eprintln!(
                "{} {id}: {} of {} frames ({loss}, {:.3}% lost)",
                w.name(),
                out.frames(),
                w.frames.len(),
                100.0 * loss.lost as f64 / w.frames.len() as f64
            );
        }
    }
    g.bench_function(id, |b| {
        b.iter(|| {
            let mut decoder = make();
            verify::count(&mut decoder, black_box(&w.stream), chunk)
        });
    });
}

fn decode(c: &mut Criterion<ThreadCpuTime>) {
    for protocol in [Protocol::HfLink, Protocol::Referee] {
        for noise in [Noise::Clean, Noise::Noisy] {
            let w = Workload::standard(protocol, noise);
            for (feed, chunk) in [("whole", w.stream.len()), ("64", CHUNK)] {
                let mut group = c.benchmark_group(format!("{}-{feed}", w.name()));
                let g = &mut group;
                g.throughput(Throughput::Bytes(w.stream.len() as u64));
                // Every iteration is long (a 16 MiB stream): the same count per sample.
                g.sampling_mode(SamplingMode::Flat);
                match protocol {
                    Protocol::HfLink => {
                        let generated = generated::hflink_decoder;
                        bench_decoder(g, GENERATED, &w, chunk, Kind::Exact, generated);
                        let hand = Staged::<hand::hflink::HfLink>::default;
                        bench_decoder(g, "hand", &w, chunk, Kind::Exact, hand);
                        let best = Appending::<hand::hflink::HfLink>::default;
                        bench_decoder(g, "best", &w, chunk, Kind::Exact, best);
                        bench_decoder(g, "port", &w, chunk, Kind::Port, HfLinkPort::default);
                        let per_byte = OneCallPerByte::<HfLinkPort>::default;
                        bench_decoder(g, "port-per-byte", &w, chunk, Kind::Port, per_byte);
                        if noise == Noise::Clean {
                            let floor = LengthWalk::<HfLinkFormat>::default;
                            bench_decoder(g, "floor", &w, chunk, Kind::Exact, floor);
                            let checked = CheckedWalk::<HfLinkFormat>::default;
                            bench_decoder(g, "floor-checked", &w, chunk, Kind::Exact, checked);
                        }
                        if ablation() {
                            let by_ref = generated::hflink_decoder_by_ref;
                            bench_decoder(g, GENERATED_BY_REF, &w, chunk, Kind::Exact, by_ref);
                            let small = generated::hflink_decoder_small;
                            bench_decoder(g, "generated-small", &w, chunk, Kind::Exact, small);
                            let early = Early::<hand::hflink::HfLink>::default;
                            bench_decoder(g, "best-early", &w, chunk, Kind::Exact, early);
                        }
                    }
                    Protocol::Referee => {
                        let generated = generated::referee_decoder;
                        bench_decoder(g, GENERATED, &w, chunk, Kind::Exact, generated);
                        let hand = Staged::<hand::referee::Referee>::default;
                        bench_decoder(g, "hand", &w, chunk, Kind::Exact, hand);
                        let best = Appending::<hand::referee::RefereeClmul>::default;
                        bench_decoder(g, "best", &w, chunk, Kind::Exact, best);
                        // The best baseline's feed and scan with the CRC-16s that code without
                        // `unsafe` has: what such a decoder can reach at best.
                        let slicing = Appending::<hand::referee::Referee>::default;
                        bench_decoder(g, "best-slicing", &w, chunk, Kind::Exact, slicing);
                        let crc_fast = Appending::<hand::referee::RefereeCrcFast>::default;
                        bench_decoder(g, "best-crcfast", &w, chunk, Kind::Exact, crc_fast);
                        bench_decoder(g, "port", &w, chunk, Kind::Port, RefereePort::default);
                        let per_byte = OneCallPerByte::<RefereePort>::default;
                        bench_decoder(g, "port-per-byte", &w, chunk, Kind::Port, per_byte);
                        if noise == Noise::Clean {
                            let floor = LengthWalk::<RefereeFormat>::default;
                            bench_decoder(g, "floor", &w, chunk, Kind::Exact, floor);
                            let checked = CheckedWalk::<RefereeFormat>::default;
                            bench_decoder(g, "floor-checked", &w, chunk, Kind::Exact, checked);
                        }
                        if ablation() {
                            let by_ref = generated::referee_decoder_by_ref;
                            bench_decoder(g, GENERATED_BY_REF, &w, chunk, Kind::Exact, by_ref);
                            let small = generated::referee_decoder_small;
                            bench_decoder(g, "generated-small", &w, chunk, Kind::Exact, small);
                            let early = Early::<hand::referee::RefereeClmul>::default;
                            bench_decoder(g, "best-early", &w, chunk, Kind::Exact, early);
                        }
                    }
                }
                group.finish();
            }
        }
    }
}

/// Checks that two encoders write the same frames and that the generated decoder reads them all
/// back, then times both.
fn bench_encoders(
    c: &mut Criterion<ThreadCpuTime>,
    group: &str,
    frame_len: usize,
    [generated, hand]: [fn(&mut [u8], u32) -> usize; 2],
    count_frames: impl Fn(&[u8]) -> usize,
) {
    let a = encode::encode_all(FRAMES, generated);
    let b = encode::encode_all(FRAMES, hand);
    assert_eq!(
        a.len(),
        frame_len * FRAMES as usize,
        "{group}: generated frame length"
    );
    assert!(a == b, "{group}: the encoders disagree");
    assert_eq!(
        count_frames(&a),
        FRAMES as usize,
        "{group}: frames decoded back"
    );
    let mut buf = vec![0u8; encode::BUFFER];
    let mut g = c.benchmark_group(group);
    g.throughput(Throughput::Bytes((frame_len * FRAMES as usize) as u64));
    g.sampling_mode(SamplingMode::Flat);
    g.bench_function(GENERATED, |bench| {
        bench.iter(|| encode::encode_wrapping(black_box(&mut buf), FRAMES, generated));
    });
    g.bench_function("hand", |bench| {
        bench.iter(|| encode::encode_wrapping(black_box(&mut buf), FRAMES, hand));
    });
    g.finish();
}

fn encoders(c: &mut Criterion<ThreadCpuTime>) {
    bench_encoders(
        c,
        "hflink-encode",
        hand::hflink::SYSTEM_INFO_FRAME,
        [
            |buf, i| {
                generated::encode_system_info(buf, 0x11, 0x01, encode::system_info(i)).unwrap_or(0)
            },
            |buf, i| {
                hand::hflink::encode_system_info(buf, 0x11, 0x01, encode::system_info(i))
                    .unwrap_or(0)
            },
        ],
        |bytes| verify::count(&mut generated::hflink_decoder(), bytes, bytes.len()).0,
    );
    bench_encoders(
        c,
        "referee-encode",
        hand::referee::ROBOT_POS_FRAME,
        [
            |buf, i| generated::encode_robot_pos(buf, i as u8, encode::robot_pos(i)).unwrap_or(0),
            |buf, i| {
                hand::referee::encode_robot_pos(buf, i as u8, encode::robot_pos(i)).unwrap_or(0)
            },
        ],
        |bytes| verify::count(&mut generated::referee_decoder(), bytes, bytes.len()).0,
    );
}

/// The runtime's CRC-16/MCRF4XX (the referee's): slicing-by-16, the `crc-fast` crate in the
/// build with `runtime-crc-fast` (from 128 bytes on), or the runtime's carry-less folding in
/// the build with `runtime-clmul` for a CPU with `pclmulqdq` (from 9 bytes on). Its id names
/// which.
static CRC16: Slicing16<u16> = Slicing16::<u16>::new(&crc::CRC_16_MCRF4XX);

/// [`CRC16`]'s benchmark id in this build.
const CRC_ID: &str = if cfg!(feature = "runtime-crc-fast") {
    "crc-fast"
} else if cfg!(all(feature = "runtime-clmul", target_feature = "pclmulqdq")) {
    "clmul"
} else {
    "slicing-16"
};

/// The CRC of `data` with the tables read through a reference the compiler cannot see
/// through, as a decoder does where its layout is not a constant: the `crc-fast` call then
/// dispatches on an algorithm read at run time.
#[inline(never)]
fn crc16_of(table: &Slicing16<u16>, data: &[u8]) -> u16 {
    table.checksum(data)
}

/// The CRC-16 alone at lengths from a short frame to a long one: where the `crc-fast` crate's
/// carry-less folding starts to beat slicing-by-16 (compare the two builds' ids).
fn crcs(c: &mut Criterion<ThreadCpuTime>) {
    let data: Vec<u8> = (0..4096u32)
        .map(|i| (i.wrapping_mul(2_654_435_761) >> 24) as u8)
        .collect();
    let reference = crc::Crc::<u16>::new(&crc::CRC_16_MCRF4XX);
    let mut g = c.benchmark_group("crc16-mcrf4xx");
    for len in CRC_LENGTHS {
        let bytes = &data[..len];
        assert_eq!(
            crc16_of(&CRC16, bytes),
            reference.checksum(bytes),
            "{CRC_ID} {len}"
        );
        g.throughput(Throughput::Bytes(len as u64));
        g.bench_function(format!("{CRC_ID}/{len}"), |b| {
            b.iter(|| crc16_of(black_box(&CRC16), black_box(bytes)));
        });
    }
    g.finish();
}

criterion_group! {
    name = benches;
    config = config();
    targets = decode, encoders, crcs
}
criterion_main!(benches);
