//! Fault injection for every spec: long streams of valid frames with seeded faults (see
//! `support::fault`), fed whole, in random chunks and byte by byte. For every stream:
//!
//! - every frame no fault touched is decoded, in order, unless an accepted false frame (a check
//!   collision) overlaps it, or (fed in chunks only) a valid frame lies inside it: the
//!   decoder's documented rule (module docs of `protocol_kit::decoder`);
//! - every frame the decoder accepts that was not sent as such really passes its checks,
//!   verified here independently of the runtime (sums and CRCs from the spec's IR, via the
//!   `crc` crate); their number is compared with what the checks' widths predict;
//! - the counters add up to the input length after every call (`support::stream::run`).
//!
//! Run with `--nocapture` to see the numbers per spec. Adding a spec to
//! `support::for_each_spec!` adds it here.

use std::collections::BTreeMap;
use std::fmt::Write as _;

use crate::support::fault::{FaultStream, Kind, build};
use crate::support::model::{Model, length_field, model};
use crate::support::oracle::params as intern;
use crate::support::stream::run;
use crate::support::{Rng, Source, Spec, hex, unescaped, wire_len};
use protocol_codegen::ir;
use protocol_kit::decoder::Probe;

/// Frames per stream (of short frames; fewer of long ones).
const FRAMES: usize = 1200;

/// Streams per spec: 3, or `FAULT_SEEDS` (for longer runs than CI's).
fn seeds() -> u64 {
    std::env::var("FAULT_SEEDS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(3)
}

/// What the streams of one spec gave.
#[derive(Debug, Default)]
struct Tally {
    bytes: u64,
    sent: u64,
    untouched: u64,
    delivered: u64,
    lost_to_collision: u64,
    lost_nested: u64,
    lost_to_reassembled: u64,
    /// Touched frames decoded as sent all the same (their neighbours made them whole again).
    reassembled: u64,
    /// Accepted frames that were not sent as such, by what the frame their first byte
    /// belongs to had suffered (`None`: garbage between frames).
    collisions: BTreeMap<Option<Kind>, u64>,
    /// Candidates that reached the frame checks without being a frame sent as such.
    trials: u64,
    bad_header_check: u64,
    bad_length: u64,
    truncated: u64,
    touched: BTreeMap<Kind, u64>,
    /// The first false frames, for the report.
    examples: Vec<String>,
    /// False frames a complemented sum accepts by construction ([`extended_by_its_check`]).
    extended_by_check: u64,
    /// Untouched frames delivered, per frame format of the link (by name).
    delivered_by_format: BTreeMap<String, u64>,
    /// Delivered frames with a flag trailer (a signed MAVLink 2 frame).
    delivered_flagged: u64,
}

/// A complemented 8-bit sum (`xorout = 0xFF`, Dynamixel 1.0's) over bytes that end with their
/// own check sums to 0xFF: a frame whose length claims one byte more than a valid frame's (a
/// forged or stale length) passes its check exactly when the byte after it is 0xFF, the first
/// sync byte of the next frame. Such a false frame is certain, not one in 256, so it is counted
/// apart from the collisions the check width predicts. True when `bytes` is one: its last byte
/// is 0xFF, and without it, its length one less, it is a valid frame.
fn extended_by_its_check(m: &Model, bytes: &[u8]) -> bool {
    let m = m.format_for(bytes);
    let complemented = m.frame().checks.iter().any(|c| {
        matches!(
            c.algorithm,
            ir::Algorithm::Sum {
                width: 1,
                init: 0,
                xorout: 0xFF
            }
        )
    });
    let (Some((field, _)), Some((&0xFF, shorter))) = (length_field(m.layout), bytes.split_last())
    else {
        return false;
    };
    let mut frame = shorter.to_vec();
    let Some(len) = field.read(&frame).filter(|&l| l > 0) else {
        return false;
    };
    complemented
        && field.write(&mut frame, len - 1).is_some()
        && m.layout.probe(&frame) == Probe::Frame(frame.len())
}

impl Tally {
    fn collisions(&self) -> u64 {
        self.collisions.values().sum()
    }
}

/// The chance that a random candidate passes the frame checks: one in the number of values
/// each check can take.
fn pass_rate(frame: &ir::Frame) -> f64 {
    frame
        .checks
        .iter()
        .filter(|c| !c.header)
        .map(|c| match &c.algorithm {
            ir::Algorithm::Sum8 | ir::Algorithm::Xor8 | ir::Algorithm::Xor { .. } => 1.0 / 256.0,
            ir::Algorithm::SumMod255 => 1.0 / 255.0,
            ir::Algorithm::Sum { width, .. } => 0.5f64.powi(8 * i32::from(*width)),
            ir::Algorithm::Fletcher16 => 1.0 / (255.0 * 255.0),
            ir::Algorithm::Fletcher16Mod256 => 1.0 / 65536.0,
            ir::Algorithm::Crc8(p) => 0.5f64.powi(i32::from(p.params.width)),
            ir::Algorithm::Crc16(p) => 0.5f64.powi(i32::from(p.params.width)),
            ir::Algorithm::Crc32(p) => 0.5f64.powi(i32::from(p.params.width)),
            ir::Algorithm::Crc64(p) => 0.5f64.powi(i32::from(p.params.width)),
        })
        .product()
}

/// Bytes of `bytes` before its flag trailer (all of them without one, or with its flag
/// clear): the checks resolve their end positions against them.
fn body_len(frame: &ir::Frame, bytes: &[u8]) -> usize {
    let flagged = frame.flag_trailer.as_ref().filter(|t| {
        crate::support::model::word_field(&frame.values[t.flag])
            .read(bytes)
            .is_some_and(|v| v != 0)
    });
    bytes.len() - flagged.map_or(0, |t| t.len).min(bytes.len())
}

/// Whether `a` and `b` are as long and differ only in bytes that no check covers or stores.
fn same_but_unchecked(frame: &ir::Frame, a: &[u8], b: &[u8]) -> bool {
    if a.len() != b.len() {
        return false;
    }
    let len = body_len(frame, a);
    if len != body_len(frame, b) {
        return false;
    }
    let at = |p: ir::Pos| match p {
        ir::Pos::Start(n) => n,
        ir::Pos::End(n) => len - n,
    };
    let checked = |i: usize| {
        frame.checks.iter().any(|c| {
            (at(c.from)..at(c.to)).contains(&i) || (at(c.at)..at(c.at) + c.size).contains(&i)
        })
    };
    (0..len).all(|i| a[i] == b[i] || !checked(i))
}

/// Whether every check of the spec holds on `bytes`, computed from the IR with the `crc` crate
/// and plain arithmetic: an oracle independent of the runtime's checksum code (a CRC by the
/// `crc` crate's own implementation, not the runtime's tables, on the spec's parameters).
fn checks_hold(frame: &ir::Frame, bytes: &[u8]) -> bool {
    let len = body_len(frame, bytes);
    let bare = frame.bare_len == Some(len);
    let at = |p: ir::Pos| match p {
        ir::Pos::Start(n) => n,
        ir::Pos::End(n) => len - n,
    };
    frame.checks.iter().filter(|c| c.header || !bare).all(|c| {
        let data = &bytes[at(c.from)..at(c.to)];
        // A per-command byte after the covered bytes, looked up by the key they hold: a key
        // without a byte never verifies.
        let extra: Option<u8> = match &c.extra {
            None => None,
            Some(e) => {
                let key = e.key.read(data).and_then(|k| u32::try_from(k).ok());
                match e.bytes.iter().find(|(k, _)| Some(*k) == key) {
                    Some(&(_, b)) => Some(b),
                    None => return false,
                }
            }
        };
        let sum = data.iter().map(|&b| u64::from(b)).sum::<u64>();
        let fletcher = |modulus: u64| {
            let (a, b) = data.iter().fold((0u64, 0u64), |(a, b), &x| {
                let a = (a + u64::from(x)) % modulus;
                (a, (b + a) % modulus)
            });
            (b << 8) | a
        };
        let expected = match &c.algorithm {
            ir::Algorithm::Sum8 => sum % 256,
            ir::Algorithm::SumMod255 => sum % 255,
            ir::Algorithm::Sum {
                width,
                init,
                xorout,
            } => ((sum + u64::from(*init)) % (1 << (8 * u32::from(*width)))) ^ u64::from(*xorout),
            ir::Algorithm::Xor8 => u64::from(data.iter().fold(0, |a, b| a ^ b)),
            ir::Algorithm::Xor { init } => u64::from(data.iter().fold(*init, |a, b| a ^ b)),
            ir::Algorithm::Fletcher16 => fletcher(255),
            ir::Algorithm::Fletcher16Mod256 => fletcher(256),
            ir::Algorithm::Crc8(p) => {
                let crc = crc::Crc::<u8>::new(intern(&p.params));
                let mut d = crc.digest();
                d.update(data);
                d.update(extra.as_slice());
                u64::from(d.finalize())
            }
            ir::Algorithm::Crc16(p) => {
                let crc = crc::Crc::<u16>::new(intern(&p.params));
                let mut d = crc.digest();
                d.update(data);
                d.update(extra.as_slice());
                u64::from(d.finalize())
            }
            ir::Algorithm::Crc32(p) => {
                let crc = crc::Crc::<u32>::new(intern(&p.params));
                let mut d = crc.digest();
                d.update(data);
                d.update(extra.as_slice());
                u64::from(d.finalize())
            }
            ir::Algorithm::Crc64(p) => {
                let crc = crc::Crc::<u64>::new(intern(&p.params));
                let mut d = crc.digest();
                d.update(data);
                d.update(extra.as_slice());
                d.finalize()
            }
        };
        let stored = &bytes[at(c.at)..at(c.at) + c.size];
        let stored = match c.endian {
            ir::ByteOrder::Little => stored
                .iter()
                .rev()
                .fold(0u64, |a, &b| (a << 8) | u64::from(b)),
            ir::ByteOrder::Big => stored.iter().fold(0u64, |a, &b| (a << 8) | u64::from(b)),
        };
        stored == expected
    })
}

/// Feeds one stream in `sizes` and checks it; `chunked` allows the documented nested case. The
/// frames sent are compared as the decoder yields them (unescaped, on a format that escapes its
/// frames), and the decoder's frames span their bytes on the wire.
fn check_stream<S: Spec>(
    m: &Model,
    fs: &FaultStream,
    sizes: &[usize],
    chunked: bool,
    t: &mut Tally,
) {
    let r = run::<S>(&fs.bytes, sizes);
    let sent_at: BTreeMap<usize, usize> = fs
        .sent
        .iter()
        .enumerate()
        .map(|(i, s)| (s.offset, i))
        .collect();
    let mut delivered = vec![false; fs.sent.len()];
    let mut last = None;
    let mut false_frames = Vec::new();
    let yielded = |wire: &[u8]| unescaped(m.format_for(wire).layout, wire);
    for (offset, bytes) in &r.frames {
        assert!(
            checks_hold(m.format_for(bytes).frame(), bytes),
            "{}: accepted {} with a failing check",
            S::NAME,
            hex(bytes)
        );
        let at = *offset as usize;
        match sent_at.get(&at) {
            Some(&i) if !fs.sent[i].kind.touches() && yielded(&fs.sent[i].bytes) == *bytes => {
                assert!(last < Some(i), "{}: frame {i} out of order", S::NAME);
                last = Some(i);
                delivered[i] = true;
                let format = m.format_for(bytes).frame();
                *t.delivered_by_format
                    .entry(format.name.clone())
                    .or_default() += 1;
                t.delivered_flagged += u64::from(body_len(format, bytes) < bytes.len());
            }
            _ => {
                let end = at + wire_len(m.format_for(bytes).layout, bytes);
                let owner = sent_at.range(..=at).next_back().map(|(_, &i)| &fs.sent[i]);
                let owner = owner.filter(|s| at < s.offset + s.bytes.len());
                // A touched frame's own bytes, made whole again by its neighbours: a sync word
                // inserted right after the sync bytes leaves the frame whole behind a stray
                // byte; a frame cut before its last byte, followed by a frame that starts with
                // that byte, or a frame that lost its first byte after garbage that ends with
                // it, are the frame sent. Not a check collision: the bytes are the frame.
                let mut overlapping = fs
                    .sent
                    .iter()
                    .filter(|s| s.offset < end && at < s.offset + s.bytes.len());
                // So is a frame that differs from the one sent only in bytes no check covers
                // (CRSF's address, a sync from a set: a set value inserted after it, or a bit
                // flip that makes it another value of the set): no check can see those.
                if overlapping.any(|s| {
                    let original = yielded(&s.original);
                    s.kind.touches()
                        && (original == *bytes
                            || same_but_unchecked(
                                m.format_for(&s.original).frame(),
                                &original,
                                bytes,
                            ))
                }) {
                    t.reassembled += 1;
                    false_frames.push((at, end, false));
                    continue;
                }
                if extended_by_its_check(m, bytes) {
                    t.extended_by_check += 1;
                    false_frames.push((at, end, true));
                    continue;
                }
                *t.collisions.entry(owner.map(|s| s.kind)).or_default() += 1;
                if t.examples.len() < 4 {
                    let from = at.saturating_sub(16);
                    let sent = owner.map(|s| (s.offset, hex(&s.original)));
                    t.examples.push(format!(
                        "at {at}: {} (stream from {from}: {}; sent there: {sent:?})",
                        hex(bytes),
                        hex(&fs.bytes[from..(end + 16).min(fs.bytes.len())])
                    ));
                }
                false_frames.push((at, end, true));
            }
        }
    }
    for (i, s) in fs
        .sent
        .iter()
        .enumerate()
        .filter(|(_, s)| !s.kind.touches())
    {
        t.untouched += 1;
        if delivered[i] {
            t.delivered += 1;
            continue;
        }
        let (start, end) = (s.offset, s.offset + s.bytes.len());
        let inside = r.frames.iter().any(|(o, b)| {
            *o as usize > start && *o as usize + wire_len(m.format_for(b).layout, b) <= end
        });
        if chunked && inside {
            t.lost_nested += 1;
        } else if let Some(&(_, _, collision)) =
            false_frames.iter().find(|&&(a, b, _)| a < end && start < b)
        {
            if collision {
                t.lost_to_collision += 1;
            } else {
                t.lost_to_reassembled += 1;
            }
        } else {
            let from = start.saturating_sub(48);
            panic!(
                "{}: untouched frame {i} ({:?}) at {start} lost, chunks {sizes:?}\n\
                 stream from {from}: {}\nframes near: {:?}",
                S::NAME,
                s.kind,
                hex(&fs.bytes[from..(end + 48).min(fs.bytes.len())]),
                r.frames
                    .iter()
                    .filter(|(o, _)| (*o as usize).abs_diff(start) < 2048)
                    .map(|f| f.0)
                    .collect::<Vec<_>>()
            );
        }
    }
    let st = r.stats;
    t.trials += st.bad_checksum + st.bad_trailer + false_frames.len() as u64;
    t.bad_header_check += st.bad_header_check;
    t.bad_length += st.bad_length;
    t.truncated += st.truncated;
    t.bytes += fs.bytes.len() as u64;
}

fn faults<S: Spec>() {
    let m = model::<S>();
    let mut t = Tally::default();
    for seed in 1..=seeds() {
        let mut rng = Rng(seed ^ 0x5EED);
        // Streams of long frames get fewer of them: the byte count, not the frame count, sets
        // the run time.
        let frames = FRAMES * 64 / m.max_len().clamp(64, 512);
        let fs = build(m, &mut rng, frames, 3);
        t.sent += fs.sent.len() as u64;
        for s in &fs.sent {
            *t.touched.entry(s.kind).or_default() += 1;
        }
        check_stream::<S>(m, &fs, &[fs.bytes.len()], false, &mut t);
        let sizes: Vec<usize> = (0..32)
            .map(|_| rng.below(2 * m.max_len() as u64) as usize + 1)
            .collect();
        check_stream::<S>(m, &fs, &sizes, true, &mut t);
        if seed == 1 {
            check_stream::<S>(m, &fs, &[1], true, &mut t);
        }
    }
    // On a link, the weakest format's checks: the most false frames any format lets through.
    let rate = m
        .formats()
        .map(|f| pass_rate(f.frame()))
        .fold(0.0, f64::max);
    let expected = t.trials as f64 * rate;
    let observed = t.collisions();
    let mut report = String::new();
    let _ = writeln!(
        report,
        "{}: {} frames sent, {} bytes fed (3 feedings per stream)",
        S::NAME,
        t.sent,
        t.bytes
    );
    let _ = writeln!(report, "  faults: {:?}", t.touched);
    let _ = writeln!(
        report,
        "  untouched {} runs: delivered {}, lost to a collision {}, to a reassembled frame {}, \
         to the nested rule {}; touched frames reassembled by their neighbours {}",
        t.untouched,
        t.delivered,
        t.lost_to_collision,
        t.lost_to_reassembled,
        t.lost_nested,
        t.reassembled
    );
    let _ = writeln!(
        report,
        "  rejected: bad header check {}, bad length {}, truncated {}; reached the frame check {}",
        t.bad_header_check, t.bad_length, t.truncated, t.trials
    );
    let _ = writeln!(
        report,
        "  false frames accepted (checks really collide): {observed} (by fault {:?}); \
         predicted {expected:.2} at {rate:.3e} per candidate",
        t.collisions
    );
    if t.extended_by_check > 0 {
        let _ = writeln!(
            report,
            "  false frames a complemented sum accepts by construction (a length one too long, \
             then 0xFF): {}",
            t.extended_by_check
        );
    }
    if !m.others.is_empty() || t.delivered_flagged > 0 {
        let _ = writeln!(
            report,
            "  delivered per frame format {:?}, {} of them with a flag trailer",
            t.delivered_by_format, t.delivered_flagged
        );
    }
    for e in &t.examples {
        let _ = writeln!(report, "    {e}");
    }
    eprint!("{report}");
    assert_eq!(
        t.delivered + t.lost_to_collision + t.lost_to_reassembled + t.lost_nested,
        t.untouched
    );
    // A link's decoder delivers frames of every format; a format with a flag trailer, some
    // with it.
    for f in m.formats() {
        assert!(
            t.delivered_by_format.get(&f.frame().name) > Some(&0),
            "{report}no frame of format `{}` delivered",
            f.frame().name
        );
        assert!(
            f.frame().flag_trailer.is_none() || t.delivered_flagged > 0,
            "{report}no frame with a flag trailer delivered"
        );
    }
    // Every untouched frame lost is explained by a false frame over it, and those are as rare
    // as the checks' width says: within four standard deviations of the prediction (the
    // faults are not random bytes, so the prediction is a guide, not an exact law).
    let bound = expected + 4.0 * expected.sqrt() + 4.0;
    assert!(
        (observed as f64) <= bound,
        "{report}more false frames than the check width predicts"
    );
}

macro_rules! fault_suite {
    ($name:ident, $path:literal $(, $given:tt)*) => {
        #[test]
        fn $name() {
            faults::<crate::support::packet!($name $(, $given)*)>();
        }
    };
}

crate::support::for_each_spec!(fault_suite);
