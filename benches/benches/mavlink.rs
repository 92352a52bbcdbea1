//! MAVLink 2 against the `mavlink` crate's reader (rust-mavlink 0.21, the common dialect), on
//! the same bytes: a fixed-seed stream of 4 MiB of HEARTBEAT, SYS_STATUS, SYSTEM_TIME,
//! GPS_RAW_INT, ATTITUDE, GLOBAL_POSITION_INT and RC_CHANNELS frames (the messages of
//! `specs/mavlink.toml` the crate writes without enumerations to draw), written by the crate,
//! fed whole and in 64-byte chunks.
//!
//! Rows, in groups `mavlink-{whole,64}`:
//! - `generated` / `mavlink-raw`: framing and checks (CRC-16/MCRF4XX then CRC_EXTRA): the
//!   generated `spec::decoder()`, and the crate's `read_raw_message`;
//! - `generated-typed` / `mavlink-typed`: framing and the typed packet: each frame read into
//!   the generated `Packet` (`Packet::from_frame`), and the crate's `read_message` into its
//!   `MavMessage`;
//! - `generated-as`: framing and the typed struct as a program that handles a few messages
//!   reads it: `Packet::from_frame_as` of each of the seven structs in turn until one matches
//!   (each miss compares the frame's id with a constant);
//! - `common` / `common-typed`: the `generated` rows with the code generated from the whole
//!   common dialect (`specs/mavlink-common.toml`, 234 messages, imported from its XML) instead
//!   of the twelve messages of `specs/mavlink.toml`;
//! - `hand`: an upper bound for the framing rows: a minimal hand-written MAVLink 2 framer (the
//!   sync found by `memchr`, the length and flags read, CRC_EXTRA from a 256-entry table, the
//!   runtime's slicing-by-16 CRC-16 then one step for the extra byte; chunks appended to a
//!   2 KiB buffer). It counts no rejection and keeps no statistics.
//!
//! Every decoder must return every frame of the stream (the typed ones every message) before
//! it is timed. Times are the thread's CPU time, as in the `codec` benchmark:
//!
//! ```text
//! PROTOCOL_BENCH_QUICK=1 cargo bench -p protocol-benches --bench mavlink
//! ```

// `criterion_group!` generates an undocumented public function.
#![allow(missing_docs)]

use std::hint::black_box;
use std::io::Read;
use std::time::Duration;

use ::mavlink::dialects::common::{
    ATTITUDE_DATA, GLOBAL_POSITION_INT_DATA, GPS_RAW_INT_DATA, HEARTBEAT_DATA, MavMessage,
    RC_CHANNELS_DATA, SYS_STATUS_DATA, SYSTEM_TIME_DATA,
};
use ::mavlink::{MavHeader, MavlinkReader, MavlinkVersion};
use criterion::measurement::{Measurement, ValueFormatter, WallTime};
use criterion::{Criterion, Throughput, criterion_group, criterion_main};

mod ours {
    protocol_kit::protocol!("../specs/mavlink.toml");
}
use ours::mavlink as spec;

mod dialect {
    protocol_kit::protocol!("../specs/mavlink-common.toml");
}
use dialect::mavlink_common as common;

/// Bytes of the stream (the last frame that fits ends it).
const STREAM: usize = 4 << 20;
/// The chunk size of the chunked rows.
const CHUNK: usize = 64;

/// Thread CPU time, as the `codec` benchmark measures (its docs say why).
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
        .without_plots()
}

/// A xorshift64 generator: the same stream on every run, without a dependency.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    fn u32(&mut self) -> u32 {
        (self.next() >> 16) as u32
    }
    fn u16(&mut self) -> u16 {
        (self.next() >> 24) as u16
    }
    fn u8(&mut self) -> u8 {
        (self.next() >> 32) as u8
    }
    fn f32(&mut self) -> f32 {
        (self.u32() as f32 / u32::MAX as f32 - 0.5) * 6.0
    }
}

/// One message of the seven, its values drawn from `rng`.
fn message(rng: &mut Rng) -> MavMessage {
    match rng.next() % 7 {
        0 => MavMessage::HEARTBEAT(HEARTBEAT_DATA {
            custom_mode: rng.u32(),
            mavlink_version: 3,
            ..HEARTBEAT_DATA::default()
        }),
        1 => MavMessage::SYS_STATUS(SYS_STATUS_DATA {
            load: rng.u16(),
            voltage_battery: rng.u16(),
            current_battery: rng.u16() as i16,
            drop_rate_comm: rng.u16(),
            errors_comm: rng.u16(),
            errors_count1: rng.u16(),
            battery_remaining: rng.u8() as i8,
            ..SYS_STATUS_DATA::default()
        }),
        2 => MavMessage::SYSTEM_TIME(SYSTEM_TIME_DATA {
            time_unix_usec: rng.next(),
            time_boot_ms: rng.u32(),
        }),
        3 => MavMessage::GPS_RAW_INT(GPS_RAW_INT_DATA {
            time_usec: rng.next(),
            lat: rng.u32() as i32,
            lon: rng.u32() as i32,
            alt: rng.u32() as i32,
            eph: rng.u16(),
            epv: rng.u16(),
            vel: rng.u16(),
            cog: rng.u16(),
            satellites_visible: rng.u8(),
            alt_ellipsoid: rng.u32() as i32,
            h_acc: rng.u32(),
            v_acc: rng.u32(),
            vel_acc: rng.u32(),
            hdg_acc: rng.u32(),
            yaw: rng.u16(),
            ..GPS_RAW_INT_DATA::default()
        }),
        4 => MavMessage::ATTITUDE(ATTITUDE_DATA {
            time_boot_ms: rng.u32(),
            roll: rng.f32(),
            pitch: rng.f32(),
            yaw: rng.f32(),
            rollspeed: rng.f32(),
            pitchspeed: rng.f32(),
            yawspeed: rng.f32(),
        }),
        5 => MavMessage::GLOBAL_POSITION_INT(GLOBAL_POSITION_INT_DATA {
            time_boot_ms: rng.u32(),
            lat: rng.u32() as i32,
            lon: rng.u32() as i32,
            alt: rng.u32() as i32,
            relative_alt: rng.u32() as i32,
            vx: rng.u16() as i16,
            vy: rng.u16() as i16,
            vz: rng.u16() as i16,
            hdg: rng.u16(),
        }),
        _ => MavMessage::RC_CHANNELS(RC_CHANNELS_DATA {
            time_boot_ms: rng.u32(),
            chancount: 18,
            chan1_raw: rng.u16(),
            chan2_raw: rng.u16(),
            chan3_raw: rng.u16(),
            chan4_raw: rng.u16(),
            chan8_raw: rng.u16(),
            chan18_raw: rng.u16(),
            rssi: rng.u8(),
            ..RC_CHANNELS_DATA::default()
        }),
    }
}

/// The stream and its number of frames, written by the `mavlink` crate.
fn stream() -> (Vec<u8>, usize) {
    let mut rng = Rng(0x4D41_564C);
    let (mut out, mut frames, mut frame) = (Vec::with_capacity(STREAM), 0, Vec::new());
    loop {
        let header = MavHeader {
            system_id: u32::from(1 + rng.u8() % 8),
            component_id: 1,
            sequence: frames as u8,
        };
        frame.clear();
        ::mavlink::write_v2_msg(&mut frame, header, &message(&mut rng)).expect("written");
        if out.len() + frame.len() > STREAM {
            return (out, frames);
        }
        out.extend_from_slice(&frame);
        frames += 1;
    }
}

/// The stream handed over at most `chunk` bytes per read.
struct Chunked<'a> {
    rest: &'a [u8],
    chunk: usize,
}

impl Read for Chunked<'_> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = buf.len().min(self.chunk).min(self.rest.len());
        let (now, rest) = self.rest.split_at(n);
        buf[..n].copy_from_slice(now);
        self.rest = rest;
        Ok(n)
    }
}

/// The row function of a generated module: the frames its decoder returns, and (typed) the
/// packets read from them.
macro_rules! generated_rows {
    ($name:ident, $module:ident) => {
        fn $name(stream: &[u8], chunk: usize, typed: bool) -> usize {
            let mut decoder = $module::decoder();
            let mut count = 0usize;
            let mut sink = |frame: protocol_kit::Frame<'_>| {
                if typed {
                    if let Ok(packet) = $module::Packet::from_frame(frame.bytes) {
                        black_box(&packet);
                        count += 1;
                    }
                } else {
                    black_box(frame.bytes);
                    count += 1;
                }
            };
            for piece in stream.chunks(chunk) {
                decoder.feed(piece, &mut sink);
            }
            while let Some(frame) = decoder.flush() {
                sink(frame);
            }
            count
        }
    };
}

generated_rows!(generated, spec);
generated_rows!(generated_common, common);

/// Whether `frame` is one of the seven messages, read by `Packet::from_frame_as` of each of
/// their structs in turn.
fn read_as(frame: &[u8]) -> bool {
    macro_rules! first_of {
        ($($m:ident),*) => {$(
            if let Ok(Some(read)) = spec::Packet::from_frame_as::<spec::$m>(frame) {
                black_box(&read);
                return true;
            }
        )*};
    }
    first_of!(
        Heartbeat,
        SysStatus,
        SystemTime,
        GpsRawInt,
        Attitude,
        GlobalPositionInt,
        RcChannels
    );
    false
}

/// The `generated-as` row: the frames of the generated decoder that [`read_as`] reads.
fn generated_as(stream: &[u8], chunk: usize, _typed: bool) -> usize {
    let mut decoder = spec::decoder();
    let mut count = 0usize;
    let mut sink = |frame: protocol_kit::Frame<'_>| count += usize::from(read_as(frame.bytes));
    for piece in stream.chunks(chunk) {
        decoder.feed(piece, &mut sink);
    }
    while let Some(frame) = decoder.flush() {
        sink(frame);
    }
    count
}

/// Frames (or typed messages) the `mavlink` crate's reader returns until the stream ends.
fn crate_reader(stream: &[u8], chunk: usize, typed: bool) -> usize {
    let mut reader = MavlinkReader::new(Chunked {
        rest: stream,
        chunk,
    });
    let mut count = 0usize;
    if typed {
        while let Ok(m) = reader.read_message::<MavMessage>(MavlinkVersion::V2) {
            black_box(&m);
            count += 1;
        }
    } else {
        while let Ok(raw) = reader.read_raw_message::<MavMessage>(MavlinkVersion::V2) {
            black_box(&raw);
            count += 1;
        }
    }
    count
}

/// The CRC-16/MCRF4XX of the `hand` row: the runtime's slicing-by-16 tables.
static HAND_CRC: protocol_runtime::checksum::Slicing16<u16> =
    protocol_runtime::checksum::Slicing16::<u16>::new(&crc::CRC_16_MCRF4XX);

/// The `hand` row's CRC_EXTRA by message id: `0x100 | byte` for the twelve messages of
/// `specs/mavlink.toml`, 0 for the others.
static HAND_EXTRAS: [u16; 256] = {
    let pairs: [(usize, u8); 12] = [
        (0, 50),
        (1, 124),
        (2, 137),
        (22, 220),
        (24, 24),
        (30, 39),
        (33, 104),
        (65, 118),
        (76, 152),
        (77, 143),
        (147, 154),
        (253, 83),
    ];
    let mut table = [0u16; 256];
    let mut i = 0;
    while i < pairs.len() {
        table[pairs[i].0] = 0x100 | pairs[i].1 as u16;
        i += 1;
    }
    table
};

/// The `hand` row's scan: counts the MAVLink 2 frames of `data` from its start and returns the
/// bytes done with (up to a frame that needs more bytes than there are).
#[inline(always)]
fn hand_scan(data: &[u8], count: &mut usize) -> usize {
    let mut at = 0;
    loop {
        let Some(rest) = data.get(at..) else {
            return at;
        };
        let skip = if rest.first() == Some(&0xFD) {
            0
        } else {
            match memchr::memchr(0xFD, rest) {
                Some(i) => i,
                None => return data.len(),
            }
        };
        at += skip;
        let Some(header) = data.get(at..).and_then(|r| r.get(..10)) else {
            return at;
        };
        let (len, flags) = (usize::from(header[1]), header[2]);
        let id =
            usize::from(header[7]) | usize::from(header[8]) << 8 | usize::from(header[9]) << 16;
        let extra = HAND_EXTRAS.get(id).copied().unwrap_or(0);
        if flags & 0xFE != 0 || extra == 0 {
            at += 1;
            continue;
        }
        let body = len + 12;
        let total = body + if flags & 1 != 0 { 13 } else { 0 };
        let Some(frame) = data.get(at..at + total) else {
            return at;
        };
        let crc = HAND_CRC.checksum_prefix_then(&frame[1..], len + 9, extra as u8);
        if u16::from_le_bytes([frame[body - 2], frame[body - 1]]) != crc {
            at += 1;
            continue;
        }
        black_box(frame);
        *count += 1;
        at += total;
    }
}

/// The `hand` row: the frames [`hand_scan`] finds, the stream whole or in `chunk`-byte pieces.
fn hand(stream: &[u8], chunk: usize, _typed: bool) -> usize {
    let mut count = 0;
    if chunk >= stream.len() {
        hand_scan(stream, &mut count);
        return count;
    }
    let mut buf = [0u8; 2048];
    let (mut start, mut end) = (0usize, 0usize);
    for piece in stream.chunks(chunk) {
        if end + piece.len() > buf.len() {
            buf.copy_within(start..end, 0);
            end -= start;
            start = 0;
        }
        buf[end..end + piece.len()].copy_from_slice(piece);
        end += piece.len();
        start += hand_scan(&buf[start..end], &mut count);
    }
    count
}

/// A row's decoder: the stream, the chunk size and whether typed, to the frames it returns.
type Decode = fn(&[u8], usize, bool) -> usize;

fn decode(c: &mut Criterion<ThreadCpuTime>) {
    let (stream, frames) = stream();
    for (feed, chunk) in [("whole", stream.len()), ("64", CHUNK)] {
        let rows: [(&str, Decode, bool); 8] = [
            ("hand", hand, false),
            ("generated", generated, false),
            ("common", generated_common, false),
            ("mavlink-raw", crate_reader, false),
            ("generated-typed", generated, true),
            ("generated-as", generated_as, true),
            ("common-typed", generated_common, true),
            ("mavlink-typed", crate_reader, true),
        ];
        let mut g = c.benchmark_group(format!("mavlink-{feed}"));
        g.throughput(Throughput::Bytes(stream.len() as u64));
        for (id, run, typed) in rows {
            assert_eq!(run(&stream, chunk, typed), frames, "{id} ({feed})");
            g.bench_function(id, |b| b.iter(|| run(black_box(&stream), chunk, typed)));
        }
        g.finish();
    }
}

criterion_group! {
    name = benches;
    config = config();
    targets = decode
}
criterion_main!(benches);
