//! A format whose frames are escaped between flags (Sensirion SHDLC's framing, written by
//! hand): the stream engine unescapes as bytes come, a flag always ends a candidate, and a
//! damaged frame (a bad escape, a bad checksum, a cut frame) never costs the frame after it,
//! however the stream is cut into chunks.
#![allow(
    clippy::unwrap_used,
    clippy::indexing_slicing,
    clippy::arithmetic_side_effects
)]

use protocol_runtime::Checksum;
use protocol_runtime::StreamDecoder;
use protocol_runtime::decoder::{Event, Reject};
use protocol_runtime::escape::Escape;
use protocol_runtime::layout::{ByteOrder, Check, FrameLayout, LengthRule, Marker, Pos, WordField};

/// `7E ADR CMD LEN DATA CHK 7E`, the check the one's complement of the sum of `ADR..DATA`;
/// `7E 7D 11 13` escaped as `7D` and the byte XOR `0x20`.
static SHDLC: FrameLayout<'static> = FrameLayout {
    sync: &[0x7E],
    sync_set: &[],
    header_len: 4,
    min_len: 6,
    max_len: 40,
    length: LengthRule::Field {
        field: WordField::le(3, 1),
        adjust: 6,
    },
    constants: &[],
    header_checks: &[],
    frame_checks: &[Check {
        checksum: Checksum::Sum {
            width: 1,
            init: 0,
            xorout: 0xFF,
        },
        from: Pos::Start(1),
        to: Pos::End(2),
        at: Pos::End(2),
        order: ByteOrder::Little,
    }],
    markers: &[Marker {
        at: Pos::End(1),
        bytes: &[0x7E],
    }],
    escape: Some(Escape {
        flag: 0x7E,
        escape: 0x7D,
        pairs: &[[0x7E, 0x5E], [0x7D, 0x5D], [0x11, 0x31], [0x13, 0x33]],
    }),
};

/// The unescaped frame of `adr cmd data`.
fn frame(adr: u8, cmd: u8, data: &[u8]) -> Vec<u8> {
    let mut f = vec![0x7E, adr, cmd, data.len() as u8];
    f.extend_from_slice(data);
    let sum = f[1..].iter().fold(0u8, |s, b| s.wrapping_add(*b));
    f.push(!sum);
    f.push(0x7E);
    f
}

/// `frame` escaped for the wire.
fn wire(unescaped: &[u8]) -> Vec<u8> {
    let mut buf = unescaped.to_vec();
    buf.resize(unescaped.len() * 2, 0);
    let n = SHDLC
        .escape
        .unwrap()
        .escape_in_place(&mut buf, unescaped.len())
        .unwrap();
    buf.truncate(n);
    buf
}

fn decode_all(stream: &[u8], chunk: usize) -> (Vec<(Vec<u8>, u64)>, protocol_runtime::Stats) {
    let mut d = StreamDecoder::<_, 64>::new(&SHDLC);
    let mut out = Vec::new();
    for piece in stream.chunks(chunk) {
        d.feed(piece, |f| out.push((f.bytes.to_vec(), f.offset)));
        let s = d.stats();
        assert_eq!(
            s.frame_bytes + s.skipped_bytes + d.pending() as u64,
            d.position(),
            "every byte fed is a frame's, skipped or pending"
        );
    }
    while let Some(f) = d.flush() {
        out.push((f.bytes.to_vec(), f.offset));
    }
    (out, *d.stats())
}

#[test]
fn reserved_bytes_are_escaped_and_frames_unescaped() {
    let f = frame(0x7E, 0x11, &[0x13, 0x7D, 0x00]);
    let w = wire(&f);
    assert_eq!(
        w[..6],
        [0x7E, 0x7D, 0x5E, 0x7D, 0x31, 0x03],
        "address 7E and command 11 escaped"
    );
    assert!(!w[1..w.len() - 1].contains(&0x7E));
    let (frames, stats) = decode_all(&w, w.len());
    assert_eq!(frames, [(f.clone(), 0)]);
    assert_eq!(stats.frame_bytes, w.len() as u64, "stats count wire bytes");
    let mut out = [0u8; 40];
    assert_eq!(SHDLC.parse_wire(&w, &mut out).unwrap(), &f[..]);
}

#[test]
fn damaged_frames_never_cost_the_next_in_any_chunking() {
    let good: Vec<Vec<u8>> = (0..6u8)
        .map(|i| frame(i, 0xD0 ^ i, &vec![0x7E ^ i; usize::from(i) * 3]))
        .collect();
    let mut stream = vec![0x00, 0x13, 0x7D];
    let mut expected = Vec::new();
    for (i, f) in good.iter().enumerate() {
        expected.push((f.clone(), stream.len() as u64));
        stream.extend_from_slice(&wire(f));
        if i % 2 == 1 {
            // A frame sharing its opening flag with the closing flag of the one before.
            let g = frame(0x40 + i as u8, 1, &[i as u8]);
            stream.pop();
            expected.push((g.clone(), stream.len() as u64));
            stream.extend_from_slice(&wire(&g));
        }
        // Damage between the good frames: a bad escape, a bad checksum, a cut frame, idle
        // flags, garbage.
        let mut bad = wire(&frame(9, 9, &[1, 2, 3]));
        match i % 4 {
            0 => bad.splice(2..3, [0x7D, 0x00]).for_each(drop),
            1 => bad[5] ^= 0x01,
            2 => bad.truncate(4),
            _ => bad = vec![0x7E, 0x7E, 0x55, 0xAA],
        }
        stream.extend_from_slice(&bad);
    }
    for chunk in 1..=stream.len() {
        let (frames, stats) = decode_all(&stream, chunk);
        assert_eq!(frames, expected, "chunks of {chunk}");
        assert_eq!(
            stats.frame_bytes + stats.skipped_bytes,
            stream.len() as u64,
            "every byte counted once, chunks of {chunk}"
        );
        assert!(stats.rejected() >= 4, "chunks of {chunk}: {stats:?}");
    }
}

#[test]
fn events_name_each_rejection() {
    let good = wire(&frame(1, 2, &[3]));
    let mut bad_escape = good.clone();
    bad_escape.splice(2..3, [0x7D, 0x01]).for_each(drop);
    let mut bad_sum = good.clone();
    bad_sum[4] ^= 0xFF;
    let mut long = vec![0x7E];
    long.extend(std::iter::repeat_n(0x01, 50));
    let mut stream = Vec::new();
    for part in [&bad_escape, &bad_sum, &long, &good] {
        stream.extend_from_slice(part);
    }
    let mut d = StreamDecoder::<_, 64>::new(&SHDLC);
    let mut input = &stream[..];
    let mut reasons = Vec::new();
    let mut frames = 0;
    while let Some(e) = d.next_event(&mut input) {
        match e {
            Event::Rejected { reason, .. } => reasons.push(reason),
            Event::Frame(f) => {
                assert_eq!(f.bytes, &frame(1, 2, &[3])[..]);
                frames += 1;
            }
            Event::Skipped { .. } => {}
        }
    }
    assert_eq!(frames, 1);
    assert_eq!(
        reasons,
        [Reject::BadEscape, Reject::BadChecksum, Reject::BadLength]
    );
}

/// A frame cut by the end of the input is truncated when the input ends, wherever it is cut
/// after its first byte; a lone opening flag is skipped.
#[test]
fn a_frame_cut_by_the_end_of_the_input_is_truncated() {
    let good = wire(&frame(1, 2, &[3, 4]));
    for cut in 1..good.len() - 1 {
        let mut d = StreamDecoder::<_, 64>::new(&SHDLC);
        let mut input = &good[..cut];
        while d.next_event(&mut input).is_some() {}
        let mut reasons = Vec::new();
        while let Some(e) = d.flush_event() {
            if let Event::Rejected { reason, .. } = e {
                reasons.push(reason);
            }
        }
        let truncated = cut > 1;
        assert_eq!(
            reasons,
            if truncated {
                vec![Reject::Truncated]
            } else {
                vec![]
            },
            "{cut}"
        );
        assert_eq!(d.stats().truncated, u64::from(truncated), "{cut}");
    }
}

#[test]
fn a_length_that_disagrees_with_the_flags_is_rejected() {
    // A whole valid 7-byte frame (its closing 7E escaped) and one byte more before the flag.
    let inner = frame(1, 2, &[3]);
    let mut longer = inner.clone();
    longer.push(0x7E);
    let (frames, stats) = decode_all(&wire(&longer), 3);
    assert!(frames.is_empty());
    assert_eq!(stats.bad_length, 1);
    // A length that claims more bytes than the flags hold.
    let mut short = frame(1, 2, &[3, 4]);
    short[3] = 9;
    let (frames, stats) = decode_all(&wire(&short), 3);
    assert!(frames.is_empty());
    assert_eq!(stats.bad_length, 1);
}
