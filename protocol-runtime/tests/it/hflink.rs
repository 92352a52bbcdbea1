//! HFLink golden vectors and the golden stream, fed whole and in chunks of every size.
#![allow(clippy::unwrap_used)]

use crate::common;

use common::{HFLINK, HFLINK_GOLDEN, HFLINK_STREAM, Seen, check, hex};
use protocol_runtime::decoder::{Probe, Reject};
use protocol_runtime::{DecodeError, EncodeError, Frame, StreamDecoder};

#[test]
fn golden_frames_probe_and_parse_as_valid() {
    for golden in HFLINK_GOLDEN {
        let frame = hex(golden);
        assert_eq!(HFLINK.probe(&frame), Probe::Frame(frame.len()), "{golden}");
        assert_eq!(HFLINK.parse(&frame), Ok(&frame[..]));
        for cut in 0..frame.len() {
            let want = if cut < 6 { 6 } else { frame.len() };
            assert_eq!(
                HFLINK.probe(&frame[..cut]),
                Probe::Need(want),
                "{golden} cut at {cut}"
            );
            assert_eq!(
                HFLINK.parse(&frame[..cut]),
                Err(DecodeError::Truncated {
                    needed: want,
                    available: cut
                })
            );
        }
    }
}

#[test]
fn every_single_byte_corruption_is_rejected() {
    for golden in HFLINK_GOLDEN {
        let frame = hex(golden);
        for i in 0..frame.len() {
            // Not 0xFF: sum mod 255 cannot tell 0x00 from 0xFF.
            for flip in [0x01, 0x80, 0x55] {
                let mut bad = frame.clone();
                bad[i] ^= flip;
                let Probe::Reject(reason) = HFLINK.probe(&bad) else {
                    // A changed length may only ask for more bytes (or fewer, then fail).
                    assert!(i == 4 || i == 5, "{golden}: byte {i} ^ {flip:#x} accepted");
                    continue;
                };
                let expected = match i {
                    0 | 1 => Reject::BadHeader,
                    4 | 5 => reason,
                    _ => Reject::BadChecksum,
                };
                assert_eq!(reason, expected, "{golden}: byte {i} ^ {flip:#x}");
            }
        }
    }
}

#[test]
fn seal_writes_the_golden_frames() {
    for golden in HFLINK_GOLDEN {
        let frame = hex(golden);
        let mut built = frame.clone();
        // Keep sender, receiver, command and payload; clear what the layout computes.
        built[..2].fill(0);
        built[4..6].fill(0);
        *built.last_mut().unwrap() = 0;
        HFLINK.seal(&mut built).unwrap();
        assert_eq!(built, frame, "{golden}");
        assert!(HFLINK.is_valid_frame(&built));
    }
}

#[test]
fn seal_refuses_bad_sizes() {
    let mut short = [0u8; 7];
    assert_eq!(
        HFLINK.seal(&mut short),
        Err(EncodeError::BufferTooSmall {
            needed: 8,
            available: 7
        })
    );
    let mut long = [0u8; 128];
    assert_eq!(
        HFLINK.seal(&mut long),
        Err(EncodeError::PayloadTooLarge { len: 128, max: 127 })
    );
    let mut max = [0u8; 127];
    HFLINK.seal(&mut max).unwrap();
    assert_eq!(HFLINK.probe(&max), Probe::Frame(127));
}

const EXPECTED_FRAMES: [(u64, usize); 4] = [(4, 28), (40, 20), (62, 8), (81, 28)];

fn frames_of(seen: &[Seen]) -> Vec<(u64, usize)> {
    seen.iter()
        .filter_map(|e| match e {
            Seen::Frame { offset, bytes } => Some((*offset, bytes.len())),
            _ => None,
        })
        .collect()
}

/// The candidate at 70 claims 44 bytes and the stream ends 40 bytes later. The frame at 81
/// lies inside its claimed length: it comes out as soon as it is complete, the candidate being
/// taken for a truncated frame, whatever the chunking, without waiting for more input.
#[test]
fn golden_stream_yields_its_frames_for_every_chunk_size() {
    let stream = hex(HFLINK_STREAM);
    assert_eq!(stream.len(), 110);
    let whole = check::<128>(&HFLINK, &stream, &[stream.len()], false);
    assert_eq!(frames_of(&whole), EXPECTED_FRAMES);
    for size in 1..=stream.len() {
        for flush in [false, true] {
            let seen = check::<128>(&HFLINK, &stream, &[size], flush);
            assert_eq!(seen, whole, "chunks of {size}, flush {flush}");
        }
    }
    // With 4 more bytes the candidate at 70 is complete, and fails its checksum instead.
    let mut longer = stream.clone();
    longer.extend_from_slice(&[0; 4]);
    let seen = check::<128>(&HFLINK, &longer, &[longer.len()], false);
    assert_eq!(frames_of(&seen), EXPECTED_FRAMES);
    assert!(seen.contains(&Seen::Rejected {
        offset: 70,
        reason: Reject::BadChecksum
    }));
}

#[test]
fn golden_stream_events_report_rejections_with_offsets() {
    let stream = hex(HFLINK_STREAM);
    let seen = check::<128>(&HFLINK, &stream, &[5, 1, 9], true);
    let summary: Vec<String> = seen
        .iter()
        .map(|e| match e {
            Seen::Frame { offset, bytes } => format!("frame {offset} +{}", bytes.len()),
            Seen::Rejected { offset, reason } => format!("rejected {offset} {reason}"),
            Seen::Skipped { offset, len } => format!("skipped {offset} +{len}"),
        })
        .collect();
    assert_eq!(
        summary,
        [
            "skipped 0 +4",
            "frame 4 +28",
            "rejected 32 bad checksum",
            "skipped 33 +7",
            "frame 40 +20",
            "skipped 60 +2",
            "frame 62 +8",
            "rejected 70 truncated frame",
            "skipped 71 +10",
            "frame 81 +28",
            "skipped 109 +1",
        ]
    );
}

#[test]
fn frames_found_whole_in_the_input_borrow_it() {
    let stream = hex(HFLINK_STREAM);
    let mut decoder = StreamDecoder::<_, 128>::new(&HFLINK);
    let mut input = &stream[..];
    let range = stream.as_ptr_range();
    let mut frames = Vec::new();
    while let Some(Frame { bytes, offset, .. }) = decoder.decode(&mut input) {
        let at = offset as usize;
        assert_eq!(bytes, &stream[at..at + bytes.len()]);
        frames.push((offset, range.contains(&bytes.as_ptr())));
    }
    // The frame at 81 lies inside the pending candidate at 70, whose bytes were copied. (With
    // the `stage-input` feature, every byte goes through the buffer.)
    let in_place = !cfg!(feature = "stage-input");
    assert_eq!(
        frames,
        [(4, in_place), (40, in_place), (62, in_place), (81, false)]
    );
    assert_eq!(decoder.pending(), 0);
    assert_eq!(decoder.stats().truncated, 1);
}

#[test]
fn stats_account_for_every_byte() {
    let stream = hex(HFLINK_STREAM);
    let mut decoder = StreamDecoder::<_, 128>::new(&HFLINK);
    let mut fed = 0u64;
    for chunk in stream.chunks(3) {
        let mut frames = 0;
        decoder.feed(chunk, |_| frames += 1);
        fed += chunk.len() as u64;
        let s = *decoder.stats();
        assert_eq!(
            s.frame_bytes + s.skipped_bytes + decoder.pending() as u64,
            fed
        );
        assert_eq!(decoder.position(), fed);
    }
    while decoder.flush().is_some() {}
    let s = *decoder.stats();
    assert_eq!(
        (s.frames, s.frame_bytes, s.bad_checksum, s.truncated),
        (4, 84, 1, 1)
    );
    assert_eq!(s.skipped_bytes, 110 - 84);
    assert_eq!(decoder.pending(), 0);
    decoder.reset();
    assert_eq!(
        (*decoder.stats(), decoder.position(), decoder.pending()),
        (Default::default(), 0, 0)
    );
}

#[test]
fn impossible_lengths_are_rejected_before_their_bytes_arrive() {
    // len = 0x7F00: rejected with the header alone, and the next frame is found.
    let mut stream = hex("ffff11017f00");
    stream.extend(hex(HFLINK_GOLDEN[1]));
    let mut decoder = StreamDecoder::<_, 128>::new(&HFLINK);
    let mut input = &stream[..6];
    assert!(decoder.decode(&mut input).is_none());
    assert_eq!(decoder.stats().bad_length, 1);
    assert_eq!(
        decoder.pending(),
        0,
        "nothing is awaited for an impossible length"
    );
    let mut input = &stream[6..];
    assert_eq!(decoder.decode(&mut input).map(|f| f.offset), Some(6));
}

#[test]
fn a_truncated_frame_does_not_cost_the_next_one() {
    let valid = hex(HFLINK_GOLDEN[2]);
    for cut in 1..valid.len() {
        let mut stream = valid[..cut].to_vec();
        stream.extend(&valid);
        stream.extend(&valid);
        let seen = check::<128>(&HFLINK, &stream, &[1], false);
        let frames = frames_of(&seen);
        assert!(
            frames.contains(&(stream.len() as u64 - valid.len() as u64, valid.len())),
            "cut {cut}"
        );
    }
}

/// The one case where the chunking changes the frames: a valid frame whose payload holds a
/// complete valid frame, cut by a chunk boundary right after the inner one.
#[test]
fn an_inner_frame_complete_first_wins_over_its_pending_outer_frame() {
    let inner = hex(HFLINK_GOLDEN[1]);
    let mut outer = vec![0u8; 7 + 1 + inner.len() + 3];
    outer[2..4].copy_from_slice(&[0x11, 0x01]);
    outer[7..7 + inner.len()].copy_from_slice(&inner);
    common::HFLINK.seal(&mut outer).unwrap();
    let whole = check::<128>(&HFLINK, &outer, &[outer.len()], false);
    assert_eq!(
        whole,
        [Seen::Frame {
            offset: 0,
            bytes: outer.clone()
        }]
    );
    let cut = check::<128>(&HFLINK, &outer, &[7 + inner.len(), outer.len()], false);
    assert_eq!(
        cut,
        [
            Seen::Rejected {
                offset: 0,
                reason: Reject::Truncated
            },
            Seen::Skipped { offset: 1, len: 6 },
            Seen::Frame {
                offset: 7,
                bytes: inner
            },
            Seen::Skipped { offset: 15, len: 4 },
        ]
    );
}

/// Feeds `stream` in chunks of `sizes` (in order, the last one repeated) with `feed`; returns
/// the frames, and how many were out once `at` bytes had been fed.
fn feed_frames<const N: usize>(
    stream: &[u8],
    sizes: &[usize],
    at: usize,
) -> (Vec<(u64, Vec<u8>)>, usize) {
    let mut decoder = StreamDecoder::<_, N>::new(&HFLINK);
    let (mut frames, mut out_at, mut fed) = (Vec::new(), None, 0);
    let mut rest = stream;
    let mut i = 0;
    while !rest.is_empty() {
        let size = sizes[i.min(sizes.len() - 1)].clamp(1, rest.len());
        i += 1;
        let (chunk, tail) = rest.split_at(size);
        rest = tail;
        decoder.feed(chunk, |f: Frame<'_>| {
            frames.push((f.offset, f.bytes.to_vec()))
        });
        fed += size;
        if fed == at {
            out_at = Some(frames.len());
        }
    }
    (frames, out_at.unwrap())
}

/// The early-truncation rule wherever the inner frame lies in the longest outer frame (127
/// bytes: up to 118 offsets to search, two 64-byte blocks on hosts), with the outer frame
/// waiting over many chunks first: the inner frame comes out with the chunk that completes it,
/// through `feed` (the staged path, with the hosts' 2 KiB buffer and a small one) as through
/// `next_event` and the reference model.
#[test]
fn an_inner_frame_at_any_offset_of_a_long_waiting_frame_comes_out_when_complete() {
    let inner = hex(HFLINK_GOLDEN[1]);
    for k in 7..=127 - 1 - inner.len() {
        let mut outer = vec![0u8; 127];
        outer[2..4].copy_from_slice(&[0x11, 0x01]);
        outer[k..k + inner.len()].copy_from_slice(&inner);
        common::HFLINK.seal(&mut outer).unwrap();
        let end = k + inner.len();
        for c in [1, 3, 16, 64] {
            // Chunks of `c` bytes up to the inner frame's end, then the rest.
            let mut sizes = vec![c; end / c];
            if end % c > 0 {
                sizes.push(end % c);
            }
            sizes.push(outer.len());
            let expected = vec![(k as u64, inner.clone())];
            for (frames, out) in [
                feed_frames::<2048>(&outer, &sizes, end),
                feed_frames::<256>(&outer, &sizes, end),
            ] {
                assert_eq!(frames, expected, "inner at {k}, chunks of {c}");
                assert_eq!(out, 1, "inner at {k}, chunks of {c}: not out when complete");
            }
            let seen = check::<2048>(&HFLINK, &outer, &sizes, true);
            assert_eq!(
                frames_of(&seen),
                [(k as u64, inner.len())],
                "inner at {k}, chunks of {c}"
            );
            assert!(seen.contains(&Seen::Rejected {
                offset: 0,
                reason: Reject::Truncated
            }));
        }
    }
}
