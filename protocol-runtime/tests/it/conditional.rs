//! Frames whose parts depend on header values (`LengthRule::Conditional`): a wider length that
//! a marker value announces (MSP v1 jumbo frames) and bytes after the check that a flag
//! announces (a MAVLink-2-like signature), alone and together, sealed, probed at every prefix
//! and streamed at every chunk size.
#![allow(clippy::unwrap_used, clippy::indexing_slicing)]

use protocol_runtime::decoder::{Probe, Reject};
use protocol_runtime::layout::{
    ByteOrder, Check, FlagTrailer, FrameLayout, LengthExtension, LengthRule, Pos, WordField,
};
use protocol_runtime::{Checksum, EncodeError, StreamDecoder};

/// `A5 flags size command [size16 when size is 255] payload xor [4 bytes when flags & 1]`.
static BOTH: FrameLayout<'static> = FrameLayout {
    sync: &[0xA5],
    sync_set: &[],
    header_len: 3,
    min_len: 5,
    max_len: 4 + 2 + 600 + 1 + 4,
    length: LengthRule::Conditional {
        field: WordField::le(2, 1),
        adjust: 5,
        extension: Some(LengthExtension {
            marker: 255,
            wide: WordField::le(4, 2),
            len: 2,
        }),
        trailer: Some(FlagTrailer {
            flag: WordField::le(1, 1).bits(0, 1),
            len: 4,
        }),
    },
    constants: &[],
    header_checks: &[],
    frame_checks: &[Check {
        checksum: Checksum::Xor8,
        from: Pos::Start(2),
        to: Pos::End(1),
        at: Pos::End(1),
        order: ByteOrder::Little,
    }],
    markers: &[],
    escape: None,
};

/// A sealed frame: `plen` payload bytes, with the flag trailer when `signed`.
fn frame(plen: usize, signed: bool, seed: u8) -> Vec<u8> {
    let short = 4 + plen + 1;
    let extra = BOTH.extension_for(short);
    let trailer = if signed { 4 } else { 0 };
    let mut f = vec![0u8; short + extra + trailer];
    f[1] = u8::from(signed);
    f[3] = seed;
    for (k, b) in f[4 + extra..4 + extra + plen].iter_mut().enumerate() {
        *b = (k as u8).wrapping_mul(31).wrapping_add(seed);
    }
    if signed {
        let n = f.len();
        f[n - 4..].copy_from_slice(&[0xDE, 0xAD, seed, 0xEF]);
    }
    BOTH.seal(&mut f).unwrap();
    f
}

#[test]
fn the_marker_form_is_used_exactly_when_the_count_needs_it() {
    for plen in [0, 1, 254, 255, 256, 600] {
        for signed in [false, true] {
            let f = frame(plen, signed, 7);
            assert_eq!(BOTH.probe(&f), Probe::Frame(f.len()), "{plen} {signed}");
            let jumbo = plen >= 255;
            assert_eq!(f[2] == 255, jumbo, "{plen}");
            assert_eq!(BOTH.extension_len(&f), if jumbo { 2 } else { 0 });
            assert_eq!(BOTH.flag_trailer_len(&f), if signed { 4 } else { 0 });
            if jumbo {
                assert_eq!(usize::from(u16::from_le_bytes([f[4], f[5]])), plen);
            }
        }
    }
}

/// `frame_len` looks at the header alone: it gives the length of a frame whose count is in the
/// header, and none for the marker form, whose wider count comes after it.
#[test]
fn the_length_from_the_header_alone_is_the_frames_without_a_wider_count() {
    for plen in [0, 1, 254, 255, 256, 600] {
        for signed in [false, true] {
            let f = frame(plen, signed, 3);
            let header = &f[..BOTH.header_span()];
            let want = (plen < 255).then_some(f.len());
            assert_eq!(BOTH.frame_len(header), want, "{plen} {signed}");
            assert_eq!(BOTH.frame_len(&header[..2]), None, "{plen} {signed}");
        }
    }
}

/// An encoder's payload moves behind the wider length in a buffer of exactly the frame's size
/// (without its flag trailer), which one byte less cannot hold; a payload whose count fits the
/// header stays where it is.
#[test]
fn a_payload_moves_behind_the_wider_length_in_a_buffer_of_its_size() {
    let plen = 300;
    let short = 4 + plen + 1;
    let extra = BOTH.extension_for(short);
    assert_eq!(extra, 2);
    let payload: Vec<u8> = (0..plen).map(|k| (k as u8).wrapping_mul(7)).collect();
    let mut buf = vec![0u8; short + extra];
    buf[4..4 + plen].copy_from_slice(&payload);
    assert_eq!(BOTH.place_payload(&mut buf, 4, plen, 1), Ok(4 + extra));
    assert_eq!(&buf[4 + extra..4 + extra + plen], &payload[..]);
    let mut tight = vec![0u8; short + extra - 1];
    assert_eq!(
        BOTH.place_payload(&mut tight, 4, plen, 1),
        Err(EncodeError::BufferTooSmall {
            needed: short + extra,
            available: short + extra - 1,
        })
    );
    assert_eq!(BOTH.place_payload(&mut tight, 4, 10, 1), Ok(4));
}

#[test]
fn every_prefix_of_a_frame_waits_and_never_rejects() {
    for (plen, signed) in [(3, true), (300, true), (300, false), (254, true)] {
        let f = frame(plen, signed, 1);
        for cut in 1..f.len() {
            match BOTH.probe(&f[..cut]) {
                Probe::Need(n) => assert!(n > cut && n <= f.len(), "{plen} {cut}: {n}"),
                other => panic!("{plen} {signed} {cut}: {other:?}"),
            }
        }
    }
}

#[test]
fn impossible_lengths_are_rejected_when_their_bytes_are_in() {
    let f = frame(300, false, 3);
    // A wider count below the marker, or above the largest frame.
    for wide in [0u16, 254, 606, 0xFFFF] {
        let mut bad = f[..6].to_vec();
        bad[4..6].copy_from_slice(&wide.to_le_bytes());
        assert_eq!(BOTH.probe(&bad), Probe::Reject(Reject::BadLength), "{wide}");
    }
    // A decoder whose buffer holds no marker-form frame refuses the marker with the header.
    let mut small = StreamDecoder::<_, 100>::new(&BOTH);
    let mut input = &f[..4];
    assert!(matches!(
        small.next_event(&mut input),
        Some(protocol_runtime::Event::Rejected {
            reason: Reject::BadLength,
            ..
        })
    ));
}

#[test]
fn the_check_resolves_against_the_frame_without_its_flag_trailer() {
    let f = frame(10, true, 9);
    // The flag trailer is not covered: other bytes there still verify.
    let mut other = f.clone();
    let n = other.len();
    other[n - 1] ^= 0xFF;
    assert_eq!(BOTH.probe(&other), Probe::Frame(n));
    // The flag is: cleared, the check fails (it is covered), or the length is shorter.
    let mut cleared = f.clone();
    cleared[1] = 0;
    assert_ne!(BOTH.probe(&cleared), Probe::Frame(n));
    let mut corrupt = f.clone();
    corrupt[n - 5] ^= 1;
    assert_eq!(BOTH.probe(&corrupt), Probe::Reject(Reject::BadChecksum));
}

#[test]
fn a_stream_of_mixed_forms_decodes_at_every_chunk_size() {
    let frames = [
        frame(0, false, 1),
        frame(300, true, 2),
        frame(12, true, 3),
        frame(255, false, 4),
    ];
    let mut bytes = vec![0x00, 0xA5];
    let mut expected = Vec::new();
    for f in &frames {
        expected.push((bytes.len() as u64, f.clone()));
        bytes.extend_from_slice(f);
    }
    // Under Miri, which interprets every byte fed (601 bytes at each of 601 chunk sizes),
    // every 61st chunk size and the whole stream.
    let step = if cfg!(miri) { 61 } else { 1 };
    for chunk in (1..=bytes.len()).step_by(step).chain([bytes.len()]) {
        let mut dec = StreamDecoder::<_, 1400>::new(&BOTH);
        let mut got = Vec::new();
        for part in bytes.chunks(chunk) {
            dec.feed(part, |f| got.push((f.offset, f.bytes.to_vec())));
        }
        assert_eq!(got, expected, "chunk {chunk}");
    }
}
