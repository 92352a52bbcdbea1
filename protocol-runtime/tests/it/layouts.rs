//! The other frame shapes: a header CRC (referee), a 10-bit length sharing a word with a
//! constant version (RoboRTS), and a trailer marker.
#![allow(clippy::unwrap_used)]

use crate::common;

use common::{
    CRSF, CRSF_GOLDEN, REFEREE, REFEREE_GOLDEN, ROBORTS, Rng, SET_THEN_SYNC, TRAILER, check, hex,
    random_frame,
};
use protocol_runtime::decoder::{Probe, Reject};
use protocol_runtime::layout::{FrameLayout, LengthRule};
use protocol_runtime::{EncodeError, StreamDecoder};

#[test]
fn referee_golden_frame() {
    let frame = hex(REFEREE_GOLDEN);
    assert_eq!(REFEREE.probe(&frame), Probe::Frame(12));
    let mut built = frame.clone();
    built[0] = 0;
    built[1..3].fill(0);
    built[4] = 0;
    built[10..].fill(0);
    REFEREE.seal(&mut built).unwrap();
    assert_eq!(built, frame);
}

#[test]
fn referee_header_check_is_verified_before_the_length_is_trusted() {
    let frame = hex(REFEREE_GOLDEN);
    let mut bad = frame.clone();
    bad[4] ^= 1;
    assert_eq!(
        REFEREE.probe(&bad[..5]),
        Probe::Reject(Reject::BadHeaderCheck)
    );
    // A corrupt length is caught by the header CRC, not awaited.
    let mut long = frame.clone();
    long[1] = 0x40;
    assert_eq!(
        REFEREE.probe(&long[..5]),
        Probe::Reject(Reject::BadHeaderCheck)
    );
    let mut body = frame.clone();
    body[7] ^= 0x10;
    assert_eq!(REFEREE.probe(&body), Probe::Reject(Reject::BadChecksum));
    let mut stream = bad.clone();
    stream.extend(&body);
    stream.extend(&frame);
    let seen = check::<64>(&REFEREE, &stream, &[1, 2, 3], true);
    assert!(seen.contains(&common::Seen::Frame {
        offset: 24,
        bytes: frame.clone()
    }));
}

#[test]
fn roborts_ten_bit_length_and_version_bits() {
    let mut frame = vec![0u8; 20];
    frame[3] = 0x02; // sender
    frame[12..16].copy_from_slice(&[1, 2, 3, 4]);
    ROBORTS.seal(&mut frame).unwrap();
    assert_eq!(frame[0], 0xAA);
    assert_eq!(
        u16::from_le_bytes([frame[1], frame[2]]),
        20,
        "length 20, version 0"
    );
    assert_eq!(ROBORTS.probe(&frame), Probe::Frame(20));

    // Version bits set: the constant fails.
    let mut v1 = frame.clone();
    v1[2] |= 0x04;
    assert_eq!(ROBORTS.probe(&v1), Probe::Reject(Reject::BadHeader));
    // A 10-bit length above max_len (300) but with a valid header: rejected on the header.
    let mut long = frame.clone();
    long[1..3].copy_from_slice(&(1000u16).to_le_bytes());
    ROBORTS.header_checks[0].store(&mut long[..12]).unwrap();
    assert_eq!(ROBORTS.probe(&long[..12]), Probe::Reject(Reject::BadLength));
    // A length above 10 bits cannot be sealed.
    let mut huge = vec![0u8; 1024];
    let wide = FrameLayout {
        max_len: 2000,
        ..ROBORTS
    };
    assert_eq!(
        wide.seal(&mut huge),
        Err(EncodeError::ValueOutOfRange {
            place: protocol_runtime::error::Place::NONE
        })
    );
    // The CRC32 covers the data.
    let mut data = frame.clone();
    data[13] ^= 0x80;
    assert_eq!(ROBORTS.probe(&data), Probe::Reject(Reject::BadChecksum));
}

#[test]
fn roborts_streams_match_the_reference() {
    let mut rng = Rng(0xDEAD_BEEF_1234_5678);
    let mut stream = Vec::new();
    for i in 0..40 {
        let len = 16 + rng.below(100);
        let mut frame = random_frame(&mut rng, &ROBORTS, len);
        if i % 5 == 3 {
            let at = rng.below(len);
            frame[at] ^= 1 << rng.below(8);
        }
        if i % 7 == 2 {
            frame.truncate(rng.below(len));
        }
        stream.extend(&frame);
    }
    let whole = check::<300>(&ROBORTS, &stream, &[stream.len()], false);
    let frames = |seen: &[common::Seen]| {
        seen.iter()
            .filter(|e| matches!(e, common::Seen::Frame { .. }))
            .cloned()
            .collect::<Vec<_>>()
    };
    for sizes in [&[1][..], &[7, 1, 300], &[64]] {
        for flush in [false, true] {
            let seen = check::<300>(&ROBORTS, &stream, sizes, flush);
            assert_eq!(frames(&seen), frames(&whole), "{sizes:?}");
        }
    }
}

#[test]
fn trailer_marker_is_checked_after_the_checksum() {
    let mut frame = vec![0u8; 9];
    frame[2..6].copy_from_slice(&[1, 2, 3, 5]);
    TRAILER.seal(&mut frame).unwrap();
    assert_eq!(
        frame,
        [0x5A, 4, 1, 2, 3, 5, 0x5A ^ 4 ^ 1 ^ 2 ^ 3 ^ 5, 0x1F, 0x2F]
    );
    assert_eq!(TRAILER.probe(&frame), Probe::Frame(9));
    let mut bad = frame.clone();
    bad[8] = 0x30;
    assert_eq!(TRAILER.probe(&bad), Probe::Reject(Reject::BadTrailer));
    let mut both = bad.clone();
    both[6] ^= 1;
    assert_eq!(TRAILER.probe(&both), Probe::Reject(Reject::BadChecksum));

    let mut stream = bad.clone();
    stream.extend(&frame);
    let seen = check::<64>(&TRAILER, &stream, &[2], false);
    assert_eq!(
        seen[0],
        common::Seen::Rejected {
            offset: 0,
            reason: Reject::BadTrailer
        }
    );
    assert!(seen.contains(&common::Seen::Frame {
        offset: 9,
        bytes: frame
    }));
}

#[test]
fn fixed_length_layouts() {
    let fixed = FrameLayout {
        length: LengthRule::Fixed(9),
        min_len: 9,
        max_len: 9,
        ..TRAILER
    };
    let mut frame = [0u8; 9];
    fixed.seal(&mut frame).unwrap();
    assert_eq!(fixed.probe(&frame), Probe::Frame(9));
    assert_eq!(fixed.frame_len(&frame[..2]), Some(9));
    let loose = FrameLayout {
        max_len: 10,
        ..fixed
    };
    let mut ten = [0u8; 10];
    assert_eq!(
        loose.seal(&mut ten),
        Err(EncodeError::ValueOutOfRange {
            place: protocol_runtime::error::Place::NONE
        })
    );
}

#[test]
fn frame_len_edge_cases() {
    let negative = FrameLayout {
        length: match TRAILER.length {
            LengthRule::Field { field, .. } => LengthRule::Field { field, adjust: -10 },
            fixed => fixed,
        },
        ..TRAILER
    };
    assert_eq!(negative.frame_len(&[0x5A, 3]), None);
    assert_eq!(negative.probe(&[0x5A, 3]), Probe::Reject(Reject::BadLength));
    assert_eq!(negative.frame_len(&[0x5A, 12]), Some(2));
    let overflow = FrameLayout {
        length: match TRAILER.length {
            LengthRule::Field { field, .. } => LengthRule::Field {
                field,
                adjust: i64::MAX,
            },
            fixed => fixed,
        },
        ..TRAILER
    };
    assert_eq!(overflow.frame_len(&[0x5A, 3]), None);
    let mut decoder = StreamDecoder::<_, 64>::new(&overflow);
    let mut input = &[0x5A, 3, 0x5A][..];
    assert!(decoder.decode(&mut input).is_none());
    assert_eq!(decoder.stats().bad_length, 1);
}

#[test]
fn a_sync_from_a_set_is_found_with_every_value_and_no_other() {
    let frame = hex(CRSF_GOLDEN);
    assert_eq!(CRSF.probe(&frame), Probe::Frame(6));
    for lead in 0..=0xFFu8 {
        let mut copy = frame.clone();
        copy[0] = lead;
        let expected = if CRSF.sync_set.contains(&lead) {
            Probe::Frame(6)
        } else {
            Probe::Reject(Reject::BadHeader)
        };
        assert_eq!(CRSF.probe(&copy), expected, "{lead:#04x}");
        // The decoder finds the frame after one garbage byte, whatever its first byte.
        let mut stream = vec![0x11];
        stream.extend_from_slice(&copy);
        let mut decoder = StreamDecoder::<_, 64>::new(&CRSF);
        let mut input = &stream[..];
        let found = decoder
            .decode(&mut input)
            .map(|f| (f.offset, f.bytes.to_vec()));
        let expected = CRSF.sync_set.contains(&lead).then(|| (1, copy.clone()));
        assert_eq!(found, expected, "{lead:#04x}");
    }
}

#[test]
fn sealing_keeps_the_value_of_the_set_and_refuses_another() {
    let frame = hex(CRSF_GOLDEN);
    for &lead in CRSF.sync_set {
        let mut built = frame.clone();
        built[0] = lead;
        built[1] = 0;
        built[5] = 0;
        CRSF.seal(&mut built).unwrap();
        assert_eq!(built[0], lead);
        assert_eq!(&built[1..], &frame[1..]);
    }
    let mut built = frame.clone();
    built[0] = 0xC9;
    assert_eq!(
        CRSF.seal(&mut built),
        Err(EncodeError::ValueOutOfRange {
            place: protocol_runtime::error::Place::NONE
        })
    );
}

#[test]
fn a_set_value_followed_by_sync_bytes() {
    let mut rng = Rng(7);
    let frame = random_frame(&mut rng, &SET_THEN_SYNC, 9);
    assert!(SET_THEN_SYNC.sync_set.contains(&frame[0]));
    assert_eq!(frame[1], 0x5A);
    let mut wrong = frame.clone();
    wrong[1] = 0x5B;
    assert_eq!(
        SET_THEN_SYNC.probe(&wrong),
        Probe::Reject(Reject::BadHeader)
    );
    // A set value alone is a prefix of a sync: the header is awaited.
    assert_eq!(SET_THEN_SYNC.probe(&frame[..1]), Probe::Need(3));
    let seen = check::<64>(
        &SET_THEN_SYNC,
        &[&[0xA1, 0x00][..], &frame].concat(),
        &[1],
        true,
    );
    assert!(seen.contains(&common::Seen::Frame {
        offset: 2,
        bytes: frame.clone()
    }));
}
