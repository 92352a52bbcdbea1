//! Layouts of the reference protocols written by hand, a deterministic random generator, and a
//! reference model of the stream engine, shared by the integration tests.
#![allow(dead_code)]

use protocol_runtime::checksum::{Checksum, CrcImpl, Slicing16};
use protocol_runtime::decoder::{Probe, Reject};
use protocol_runtime::layout::{
    ByteOrder, Check, Constant, FrameLayout, LayoutRef, LengthRule, Marker, Pos, WordField,
};
use protocol_runtime::{Event, StreamDecoder};

/// Bytes from a hex string (whitespace ignored).
pub fn hex(s: &str) -> Vec<u8> {
    let digits: Vec<u8> = s.bytes().filter(|b| !b.is_ascii_whitespace()).collect();
    assert!(digits.len() % 2 == 0, "odd hex length");
    digits
        .chunks(2)
        .map(|pair| u8::from_str_radix(std::str::from_utf8(pair).unwrap(), 16).unwrap())
        .collect()
}

/// `FF FF sender receiver len(u16 BE) command payload sum`, `len` counting command + payload.
pub static HFLINK: FrameLayout<'static> = FrameLayout {
    sync: &[0xFF, 0xFF],
    sync_set: &[],
    header_len: 6,
    min_len: 8,
    max_len: 127,
    length: LengthRule::Field {
        field: WordField {
            at: Pos::Start(4),
            size: 2,
            order: ByteOrder::Big,
            shift: 0,
            width: 16,
        },
        adjust: 7,
    },
    constants: &[],
    header_checks: &[],
    frame_checks: &[Check {
        checksum: Checksum::SumMod255,
        from: Pos::Start(0),
        to: Pos::End(1),
        at: Pos::End(1),
        order: ByteOrder::Big,
    }],
    markers: &[],
    escape: None,
};

pub const HFLINK_GOLDEN: [&str; 4] = [
    "ffff0111000d000000404000008040db0f4940d4",
    "ffff110100010013",
    "ffff11010015010000f742000035420000c03e9a9949410000af4289",
    "ffff1101000315d50000",
];

pub const HFLINK_STREAM: &str = "0013fe7effff11010015010000f742000035420000c03e9a9949410000af4289\
    ffff110100010c1effff1101000d0d8fc2f53e00000000000040bfb2ff00ffff110100010013ffff110100251ae3\
    07070effff11010015180ad7233c0ad7a3bcc3f5c83f000048410000b4420555";

static DJI_CRC8: crc::Algorithm<u8> = crc::Algorithm {
    width: 8,
    poly: 0x31,
    init: 0xFF,
    refin: true,
    refout: true,
    xorout: 0,
    check: 0x0B,
    residue: 0,
};
static DJI_CRC16: crc::Algorithm<u16> = crc::Algorithm {
    width: 16,
    poly: 0x8005,
    init: 0xC55C,
    refin: true,
    refout: true,
    xorout: 0,
    check: 0x2752,
    residue: 0,
};
static DJI_CRC32: crc::Algorithm<u32> = crc::Algorithm {
    width: 32,
    poly: 0x04C1_1DB7,
    init: 0xC55C_0000,
    refin: true,
    refout: true,
    xorout: 0,
    check: 0xE4D9_DC14,
    residue: 0,
};
static REFEREE_CRC8: crc::Crc<u8, crc::Table<1>> = crc::Crc::<u8, crc::Table<1>>::new(&DJI_CRC8);
static REFEREE_CRC16: Slicing16<u16> = Slicing16::<u16>::new(&crc::CRC_16_MCRF4XX);
static ROBORTS_CRC16: crc::Crc<u16, crc::NoTable> = crc::Crc::<u16, crc::NoTable>::new(&DJI_CRC16);
static ROBORTS_CRC32: Slicing16<u32> = Slicing16::<u32>::new(&DJI_CRC32);

/// `A5 len(u16 LE, payload only) seq crc8 | cmd(u16 LE) data crc16(LE)`.
pub static REFEREE: FrameLayout<'static> = FrameLayout {
    sync: &[0xA5],
    sync_set: &[],
    header_len: 5,
    min_len: 9,
    max_len: 9 + 128,
    length: LengthRule::Field {
        field: WordField {
            at: Pos::Start(1),
            size: 2,
            order: ByteOrder::Little,
            shift: 0,
            width: 16,
        },
        adjust: 9,
    },
    constants: &[],
    header_checks: &[Check {
        checksum: Checksum::Crc8(CrcImpl::Table1(&REFEREE_CRC8)),
        from: Pos::Start(0),
        to: Pos::Start(4),
        at: Pos::Start(4),
        order: ByteOrder::Little,
    }],
    frame_checks: &[Check {
        checksum: Checksum::Crc16(CrcImpl::Table16(&REFEREE_CRC16)),
        from: Pos::Start(0),
        to: Pos::End(2),
        at: Pos::End(2),
        order: ByteOrder::Little,
    }],
    markers: &[],
    escape: None,
};

pub const REFEREE_GOLDEN: &str = "a503000027010043b40091fe";

/// RoboRTS-like: `AA {len:10, version:6}(u16 LE) session sender receiver res(2) seq(2) crc16 |
/// data crc32`, the 10-bit length counting the whole frame, the version a constant 0.
pub static ROBORTS: FrameLayout<'static> = FrameLayout {
    sync: &[0xAA],
    sync_set: &[],
    header_len: 12,
    min_len: 16,
    max_len: 300,
    length: LengthRule::Field {
        field: WordField {
            at: Pos::Start(1),
            size: 2,
            order: ByteOrder::Little,
            shift: 0,
            width: 10,
        },
        adjust: 0,
    },
    constants: &[Constant {
        field: WordField {
            at: Pos::Start(1),
            size: 2,
            order: ByteOrder::Little,
            shift: 10,
            width: 6,
        },
        value: 0,
    }],
    header_checks: &[Check {
        checksum: Checksum::Crc16(CrcImpl::NoTable(&ROBORTS_CRC16)),
        from: Pos::Start(0),
        to: Pos::Start(10),
        at: Pos::Start(10),
        order: ByteOrder::Little,
    }],
    frame_checks: &[Check {
        checksum: Checksum::Crc32(CrcImpl::Table16(&ROBORTS_CRC32)),
        from: Pos::Start(0),
        to: Pos::End(4),
        at: Pos::End(4),
        order: ByteOrder::Little,
    }],
    markers: &[],
    escape: None,
};

/// `5A len(u8) payload xor 1F 2F`, `len` counting the payload.
pub static TRAILER: FrameLayout<'static> = FrameLayout {
    sync: &[0x5A],
    sync_set: &[],
    header_len: 2,
    min_len: 5,
    max_len: 64,
    length: LengthRule::Field {
        field: WordField {
            at: Pos::Start(1),
            size: 1,
            order: ByteOrder::Big,
            shift: 0,
            width: 8,
        },
        adjust: 5,
    },
    constants: &[],
    header_checks: &[],
    frame_checks: &[Check {
        checksum: Checksum::Xor8,
        from: Pos::Start(0),
        to: Pos::End(3),
        at: Pos::End(3),
        order: ByteOrder::Big,
    }],
    markers: &[Marker {
        at: Pos::End(2),
        bytes: &[0x1F, 0x2F],
    }],
    escape: None,
};

static CRSF_CRC8: crc::Crc<u8, crc::Table<1>> =
    crc::Crc::<u8, crc::Table<1>>::new(&crc::CRC_8_DVB_S2);

/// CRSF: `address(one of C8 EA EE EC 00) len type payload crc8`, `len` counting type, payload
/// and CRC; the CRC-8/DVB-S2 over type and payload. The sync is a set of values.
pub static CRSF: FrameLayout<'static> = FrameLayout {
    sync: &[],
    sync_set: &[0xC8, 0xEA, 0xEE, 0xEC, 0x00],
    header_len: 2,
    min_len: 4,
    max_len: 64,
    length: LengthRule::Field {
        field: WordField {
            at: Pos::Start(1),
            size: 1,
            order: ByteOrder::Little,
            shift: 0,
            width: 8,
        },
        adjust: 2,
    },
    constants: &[],
    header_checks: &[],
    frame_checks: &[Check {
        checksum: Checksum::Crc8(CrcImpl::Table1(&CRSF_CRC8)),
        from: Pos::Start(2),
        to: Pos::End(1),
        at: Pos::End(1),
        order: ByteOrder::Little,
    }],
    markers: &[],
    escape: None,
};

/// A CRSF heartbeat (type 0x0B, origin 0x00EA) to the flight controller: the `heartbeat` frame
/// of the CRSF golden vectors (`tests/vectors/crsf.json`).
pub const CRSF_GOLDEN: &str = "c8040b00ea36";

/// A sync set followed by sync bytes: `(A1 | B2) 5A len payload sum8`.
pub static SET_THEN_SYNC: FrameLayout<'static> = FrameLayout {
    sync: &[0x5A],
    sync_set: &[0xA1, 0xB2],
    header_len: 3,
    min_len: 4,
    max_len: 40,
    length: LengthRule::Field {
        field: WordField {
            at: Pos::Start(2),
            size: 1,
            order: ByteOrder::Little,
            shift: 0,
            width: 8,
        },
        adjust: 4,
    },
    constants: &[],
    header_checks: &[],
    frame_checks: &[Check {
        checksum: Checksum::Sum8,
        from: Pos::Start(0),
        to: Pos::End(1),
        at: Pos::End(1),
        order: ByteOrder::Little,
    }],
    markers: &[],
    escape: None,
};

/// Every layout above with a name.
pub fn layouts() -> [(&'static str, &'static FrameLayout<'static>); 6] {
    [
        ("hflink", &HFLINK),
        ("referee", &REFEREE),
        ("roborts", &ROBORTS),
        ("trailer", &TRAILER),
        ("crsf", &CRSF),
        ("set_then_sync", &SET_THEN_SYNC),
    ]
}

/// The xorshift64 generator: deterministic, dependency-free test data.
pub struct Rng(pub u64);

impl Rng {
    pub fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    /// A value in `0..n` (`n > 0`).
    pub fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }

    pub fn byte(&mut self) -> u8 {
        (self.next() >> 32) as u8
    }

    pub fn fill(&mut self, buf: &mut [u8]) {
        buf.iter_mut().for_each(|b| *b = self.byte());
    }
}

/// A sealed frame of `layout` of total length `len`, other bytes random.
pub fn random_frame(rng: &mut Rng, layout: &FrameLayout<'_>, len: usize) -> Vec<u8> {
    let mut frame = vec![0u8; len];
    rng.fill(&mut frame);
    if !layout.sync_set.is_empty() {
        frame[0] = layout.sync_set[rng.below(layout.sync_set.len())];
    }
    layout.seal(&mut frame).unwrap();
    assert_eq!(layout.probe(&frame), Probe::Frame(len));
    frame
}

/// What a decoder reported, with skipped runs merged (their split depends on the chunking).
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Seen {
    Frame { offset: u64, bytes: Vec<u8> },
    Rejected { offset: u64, reason: Reject },
    Skipped { offset: u64, len: usize },
}

pub fn push(seen: &mut Vec<Seen>, event: Event<'_>) {
    match event {
        Event::Frame(f) => seen.push(Seen::Frame {
            offset: f.offset,
            bytes: f.bytes.to_vec(),
        }),
        Event::Rejected { offset, reason } => seen.push(Seen::Rejected { offset, reason }),
        Event::Skipped { offset, len } => {
            assert!(len > 0, "empty skipped run at {offset}");
            if let Some(Seen::Skipped { offset: o, len: l }) = seen.last_mut() {
                if *o + *l as u64 == offset {
                    *l += len;
                    return;
                }
            }
            seen.push(Seen::Skipped { offset, len });
        }
    }
}

/// Feeds `stream` in chunks of the given sizes (cycled), checking the accounting after every
/// event, then flushes if asked. Returns every event.
pub fn run<const N: usize>(
    layout: &FrameLayout<'_>,
    stream: &[u8],
    sizes: &[usize],
    flush: bool,
) -> Vec<Seen> {
    let mut decoder = StreamDecoder::<_, N>::new(layout);
    let mut seen = Vec::new();
    let mut fed = 0usize;
    let mut rest = stream;
    let mut i = 0;
    while !rest.is_empty() {
        let size = sizes[i % sizes.len()].clamp(1, rest.len());
        i += 1;
        let (mut chunk, tail) = rest.split_at(size);
        rest = tail;
        fed += size;
        while let Some(event) = decoder.next_event(&mut chunk) {
            push(&mut seen, event);
        }
        assert!(chunk.is_empty(), "input left unconsumed");
        check_accounting(&decoder, fed, &seen);
        assert!(decoder.pending() <= N);
    }
    if flush {
        while let Some(event) = decoder.flush_event() {
            push(&mut seen, event);
        }
        assert_eq!(decoder.pending(), 0);
        check_accounting(&decoder, fed, &seen);
    }
    seen
}

/// The stats account for every byte fed, and agree with the events.
pub fn check_accounting<L: LayoutRef, const N: usize>(
    decoder: &StreamDecoder<L, N>,
    fed: usize,
    seen: &[Seen],
) {
    let s = decoder.stats();
    assert_eq!(decoder.position(), fed as u64);
    assert_eq!(
        s.frame_bytes + s.skipped_bytes + decoder.pending() as u64,
        fed as u64,
        "{s:?}"
    );
    let (mut frames, mut frame_bytes, mut skipped, mut rejected) = (0, 0, 0, 0);
    for e in seen {
        match e {
            Seen::Frame { bytes, .. } => {
                frames += 1;
                frame_bytes += bytes.len() as u64;
            }
            Seen::Rejected { .. } => rejected += 1,
            Seen::Skipped { len, .. } => skipped += *len as u64,
        }
    }
    assert_eq!((s.frames, s.frame_bytes), (frames, frame_bytes));
    assert_eq!(s.rejected(), rejected);
    assert_eq!(s.skipped_bytes, skipped + rejected);
}

/// Where chunks of the given sizes (cycled, as [`run`] feeds them) end in a stream of `len`.
pub fn chunk_ends(len: usize, sizes: &[usize]) -> Vec<usize> {
    let mut ends = Vec::new();
    let mut end = 0;
    let mut i = 0;
    while end < len {
        end += sizes[i % sizes.len()].clamp(1, len - end);
        i += 1;
        ends.push(end);
    }
    ends
}

/// The engine's rules as an executable specification over the whole stream, with `probe`.
///
/// After each chunk, the engine decides what the bytes received so far decide: a candidate
/// whose bytes have not all arrived waits, unless a complete valid frame starts inside the
/// bytes it holds (then it is taken for a truncated frame), or the input is declared ended
/// (`flush`). The streaming decoder must match this for the same chunking, with a buffer of at
/// least `max_len` (or with `max_len` capped to its buffer).
pub fn reference(
    layout: &FrameLayout<'_>,
    stream: &[u8],
    sizes: &[usize],
    flush: bool,
) -> Vec<Seen> {
    let mut horizons: Vec<(usize, bool)> = chunk_ends(stream.len(), sizes)
        .into_iter()
        .map(|end| (end, false))
        .collect();
    if flush {
        horizons.push((stream.len(), true));
    }
    let mut seen = Vec::new();
    let mut pos = 0;
    for (end, at_end) in horizons {
        while pos < end {
            let avail = &stream[pos..end];
            // A value of the sync set, if any, then the sync bytes (as far as they have come).
            let lead = usize::from(!layout.sync_set.is_empty());
            let in_set = lead == 0 || layout.sync_set.contains(&avail[0]);
            let rest = &avail[lead.min(avail.len())..];
            let n = rest.len().min(layout.sync.len());
            if !in_set || rest[..n] != layout.sync[..n] {
                push(
                    &mut seen,
                    Event::Skipped {
                        offset: pos as u64,
                        len: 1,
                    },
                );
                pos += 1;
                continue;
            }
            let frame_inside =
                || (1..avail.len()).any(|k| matches!(layout.probe(&avail[k..]), Probe::Frame(_)));
            let reason = match layout.probe(avail) {
                Probe::Frame(len) => {
                    seen.push(Seen::Frame {
                        offset: pos as u64,
                        bytes: avail[..len].to_vec(),
                    });
                    pos += len;
                    continue;
                }
                Probe::Reject(reason) => reason,
                Probe::Need(_) if at_end || frame_inside() => Reject::Truncated,
                Probe::Need(_) => break,
            };
            seen.push(Seen::Rejected {
                offset: pos as u64,
                reason,
            });
            pos += 1;
        }
    }
    seen
}

/// Runs the decoder and checks it against [`reference`] for the same chunking.
pub fn check<const N: usize>(
    layout: &FrameLayout<'_>,
    stream: &[u8],
    sizes: &[usize],
    flush: bool,
) -> Vec<Seen> {
    let seen = run::<N>(layout, stream, sizes, flush);
    let capped = FrameLayout {
        max_len: layout.max_len.min(N),
        ..*layout
    };
    assert_eq!(
        seen,
        reference(&capped, stream, sizes, flush),
        "chunks {sizes:?} flush {flush} N={N}"
    );
    seen
}
