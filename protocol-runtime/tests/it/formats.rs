//! A link of several frame formats, found by their syncs and decoded by one decoder: every
//! frame says its format, a rejected candidate costs one byte, and the frames do not depend on
//! how the stream was cut.
#![allow(
    clippy::unwrap_used,
    clippy::indexing_slicing,
    clippy::arithmetic_side_effects
)]

use protocol_runtime::Checksum;
use protocol_runtime::StreamDecoder;
use protocol_runtime::decoder::{Event, Reject};
use protocol_runtime::layout::{
    ByteOrder, Check, Formats, FrameLayout, LayoutRef, LengthRule, Pos, WordField,
};

/// `FE LEN ID PAYLOAD SUM`: a one-byte id, a sum over everything after the sync.
static SHORT: FrameLayout<'static> = FrameLayout {
    sync: &[0xFE],
    sync_set: &[],
    header_len: 2,
    min_len: 4,
    max_len: 20,
    length: LengthRule::Field {
        field: WordField::le(1, 1),
        adjust: 4,
    },
    constants: &[],
    header_checks: &[],
    frame_checks: &[Check {
        checksum: Checksum::Sum8,
        from: Pos::Start(1),
        to: Pos::End(1),
        at: Pos::End(1),
        order: ByteOrder::Little,
    }],
    markers: &[],
    escape: None,
};

/// `FD LEN ID ID PAYLOAD CRC16`: a two-byte id and a two-byte sum, longer frames.
static LONG: FrameLayout<'static> = FrameLayout {
    sync: &[0xFD],
    sync_set: &[],
    header_len: 2,
    min_len: 6,
    max_len: 60,
    length: LengthRule::Field {
        field: WordField::le(1, 1),
        adjust: 6,
    },
    constants: &[],
    header_checks: &[],
    frame_checks: &[Check {
        checksum: Checksum::Sum {
            width: 2,
            init: 0,
            xorout: 0,
        },
        from: Pos::Start(1),
        to: Pos::End(2),
        at: Pos::End(2),
        order: ByteOrder::Little,
    }],
    markers: &[],
    escape: None,
};

static OTHERS: [FrameLayout<'static>; 1] = [LONG];

/// The link as generated code holds it: a zero-sized type.
#[derive(Clone, Copy)]
struct Link;

impl LayoutRef for Link {
    #[inline(always)]
    fn layout(&self) -> &FrameLayout<'_> {
        &SHORT
    }
    #[inline(always)]
    fn others(&self) -> &[FrameLayout<'_>] {
        &OTHERS
    }
}

/// A sealed frame of the format `format` (0: `SHORT`, 1: `LONG`) with `payload`.
fn frame(format: usize, payload: &[u8]) -> Vec<u8> {
    let (layout, head) = if format == 0 {
        (&SHORT, vec![0xFE, payload.len() as u8, 0x07])
    } else {
        (&LONG, vec![0xFD, payload.len() as u8, 0x34, 0x12])
    };
    let mut bytes = head;
    bytes.extend_from_slice(payload);
    bytes.extend(std::iter::repeat_n(0, if format == 0 { 1 } else { 2 }));
    layout.seal(&mut bytes).unwrap();
    bytes
}

/// Frames found: offset, format, bytes.
type Found = Vec<(u64, usize, Vec<u8>)>;

/// Frames and rejections (offset) of `stream` fed in chunks of `chunk` bytes, then flushed.
type Seen = (Found, Vec<(u64, Reject)>);

fn decode<L: LayoutRef>(layout: L, stream: &[u8], chunk: usize) -> Seen {
    let mut decoder = StreamDecoder::<L, 64>::new(layout);
    let (mut frames, mut rejected) = (Vec::new(), Vec::new());
    let mut record = |event: Event<'_>| match event {
        Event::Frame(f) => frames.push((f.offset, f.format, f.bytes.to_vec())),
        Event::Rejected { offset, reason } => rejected.push((offset, reason)),
        Event::Skipped { .. } => {}
    };
    for piece in stream.chunks(chunk.max(1)) {
        let mut input = piece;
        while let Some(event) = decoder.next_event(&mut input) {
            record(event);
        }
    }
    while let Some(event) = decoder.flush_event() {
        record(event);
    }
    let stats = decoder.stats();
    assert_eq!(
        stats.frame_bytes + stats.skipped_bytes,
        stream.len() as u64,
        "every byte is accounted for"
    );
    (frames, rejected)
}

/// The frames of `stream` through `feed`, in chunks of `chunk` bytes.
fn feed<L: LayoutRef>(layout: L, stream: &[u8], chunk: usize) -> Found {
    let mut decoder = StreamDecoder::<L, 64>::new(layout);
    let mut frames = Vec::new();
    for piece in stream.chunks(chunk.max(1)) {
        decoder.feed(piece, |f| {
            frames.push((f.offset, f.format, f.bytes.to_vec()))
        });
    }
    while let Some(f) = decoder.flush() {
        frames.push((f.offset, f.format, f.bytes.to_vec()));
    }
    frames
}

/// A mixed stream: garbage, frames of both formats, a corrupt frame of each.
fn mixed() -> (Vec<u8>, Found) {
    let mut stream = vec![0x00, 0x11];
    let mut expected = Vec::new();
    let mut push = |stream: &mut Vec<u8>, format: usize, payload: &[u8], valid: bool| {
        let mut bytes = frame(format, payload);
        if valid {
            expected.push((stream.len() as u64, format, bytes.clone()));
        } else {
            let last = bytes.len() - 1;
            bytes[last] ^= 0x40;
        }
        stream.extend(bytes);
    };
    push(&mut stream, 0, &[1, 2, 3], true);
    push(&mut stream, 1, &[4; 30], true);
    push(&mut stream, 0, &[0xFD, 0x00], false);
    push(&mut stream, 1, &[0xFE, 1, 2], false);
    push(&mut stream, 1, &[], true);
    stream.push(0x55);
    push(&mut stream, 0, &[], true);
    push(&mut stream, 1, &[0xFE; 12], true);
    (stream, expected)
}

#[test]
fn each_format_is_found_by_its_sync_and_says_which_it_is() {
    let (stream, expected) = mixed();
    for chunk in 1..=stream.len() {
        assert_eq!(decode(Link, &stream, chunk).0, expected, "chunk {chunk}");
        assert_eq!(feed(Link, &stream, chunk), expected, "chunk {chunk}");
    }
}

#[test]
fn the_run_time_formats_decode_as_the_generated_ones() {
    let (stream, expected) = mixed();
    let formats = Formats {
        first: &SHORT,
        others: &OTHERS,
    };
    for chunk in [1, 2, 5, 64, stream.len()] {
        assert_eq!(
            decode(formats, &stream, chunk),
            decode(Link, &stream, chunk)
        );
        assert_eq!(feed(formats, &stream, chunk), expected);
    }
}

#[test]
fn a_candidate_is_probed_by_the_format_its_sync_selects() {
    // A `LONG` frame of 40 bytes: longer than `SHORT` allows, valid for `LONG`.
    let long = frame(1, &[9; 34]);
    assert_eq!(decode(Link, &long, 64).0, vec![(0, 1, long.clone())]);
    // The same bytes after an `FE` sync are a `SHORT` candidate of a bad length.
    let mut short = long.clone();
    short[0] = 0xFE;
    let (frames, rejected) = decode(Link, &short, 64);
    assert!(frames.is_empty());
    assert_eq!(rejected.first(), Some(&(0, Reject::BadLength)));
    // A single-format decoder finds only its own frames in the mixed stream.
    let (stream, expected) = mixed();
    let only_short: Vec<_> = expected.iter().filter(|f| f.1 == 0).cloned().collect();
    assert_eq!(decode(&SHORT, &stream, 7).0, only_short);
}
