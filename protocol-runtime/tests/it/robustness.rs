//! Properties of the stream engine on random input: it never panics, always makes progress,
//! accounts for every byte, never holds more than its buffer, and yields exactly what the
//! whole-stream reference yields, for every chunking and every buffer size.
#![allow(clippy::unwrap_used)]

use crate::common;

use common::{Rng, Seen, check, layouts, random_frame, run};
use protocol_runtime::StreamDecoder;
use protocol_runtime::layout::{FrameLayout, LengthRule};

/// `n`, or under Miri, which interprets every step (a thousand times slower or more), a
/// fiftieth of it: the same properties on shorter streams.
const fn scaled(n: usize) -> usize {
    if cfg!(miri) { n.div_ceil(50) } else { n }
}

/// Random bytes where sync bytes and small values are frequent, so that many candidates get
/// deep into the checks.
fn hostile_garbage(rng: &mut Rng, layout: &FrameLayout<'_>, len: usize) -> Vec<u8> {
    (0..len)
        .map(|_| match rng.below(4) {
            0 => {
                let sync = if layout.sync_set.is_empty() {
                    layout.sync
                } else {
                    layout.sync_set
                };
                sync.get(rng.below(sync.len().max(1))).copied().unwrap_or(0)
            }
            1 => rng.below(16) as u8,
            _ => rng.byte(),
        })
        .collect()
}

/// Valid frames, corrupted frames, truncated frames and garbage, mixed.
fn mixed_stream(rng: &mut Rng, layout: &FrameLayout<'_>, frames: usize) -> Vec<u8> {
    let mut stream = Vec::new();
    let min = layout.min_len.max(layout.header_span());
    for _ in 0..frames {
        if rng.below(4) == 0 {
            let n = rng.below(12);
            stream.extend(hostile_garbage(rng, layout, n));
        }
        let len = min + rng.below(layout.max_len.min(160) - min + 1);
        let mut frame = random_frame(rng, layout, len);
        match rng.below(8) {
            0 => {
                let at = rng.below(len);
                frame[at] ^= 1 << rng.below(8);
            }
            1 => frame.truncate(rng.below(len)),
            _ => {}
        }
        stream.extend(frame);
    }
    stream
}

/// Chunk size patterns: single bytes, small primes, a random mix, the whole stream.
fn chunkings(rng: &mut Rng, total: usize) -> Vec<Vec<usize>> {
    let random: Vec<usize> = (0..64).map(|_| 1 + rng.below(70)).collect();
    vec![vec![1], vec![2, 3, 5], vec![13], random, vec![total.max(1)]]
}

fn frames(seen: &[Seen]) -> Vec<Seen> {
    seen.iter()
        .filter(|e| matches!(e, Seen::Frame { .. }))
        .cloned()
        .collect()
}

#[test]
fn mixed_streams_match_the_reference_for_every_chunking() {
    let mut rng = Rng(0x0123_4567_89AB_CDEF);
    for (name, layout) in layouts() {
        for round in 0..scaled(6) {
            let stream = mixed_stream(&mut rng, layout, scaled(60).max(10));
            let whole = check::<512>(layout, &stream, &[stream.len()], false);
            for flush in [false, true] {
                for sizes in chunkings(&mut rng, stream.len()) {
                    let seen = check::<512>(layout, &stream, &sizes, flush);
                    // No valid frame hides inside another in these streams: the frames do not
                    // depend on the chunking (only why a truncated frame was dropped may).
                    assert_eq!(
                        frames(&seen),
                        frames(&whole),
                        "{name} round {round} {sizes:?}"
                    );
                }
            }
        }
    }
}

#[test]
fn decode_yields_the_frames_that_next_event_reports() {
    let mut rng = Rng(0x5151_5151_0000_0001);
    // Chunk sizes from one byte (every candidate waits, the early-truncation search runs at
    // every byte) to larger than the stream.
    for (name, layout) in layouts() {
        for size in [1, 2, 3, 7, 17, 64, 200, 5000] {
            feed_matches_next_event(&mut rng, name, layout, size);
        }
    }
}

fn feed_matches_next_event(rng: &mut Rng, name: &str, layout: &FrameLayout<'_>, size: usize) {
    let stream = mixed_stream(rng, layout, scaled(80).max(10));
    let events: Vec<Seen> = run::<256>(layout, &stream, &[size], true)
        .into_iter()
        .filter(|e| matches!(e, Seen::Frame { .. }))
        .collect();
    let mut decoder = StreamDecoder::<_, 256>::new(layout);
    let mut frames = Vec::new();
    for chunk in stream.chunks(size) {
        decoder.feed(chunk, |f| {
            frames.push(Seen::Frame {
                offset: f.offset,
                bytes: f.bytes.to_vec(),
            })
        });
    }
    while let Some(f) = decoder.flush() {
        frames.push(Seen::Frame {
            offset: f.offset,
            bytes: f.bytes.to_vec(),
        });
    }
    assert_eq!(frames, events, "{name}, chunks of {size}");
}

/// Runs the engine with a buffer of `N` bytes: it behaves as if `max_len` were `min(max_len, N)`.
fn small_buffer<const N: usize>(rng: &mut Rng) {
    for (name, layout) in layouts() {
        let stream = mixed_stream(rng, layout, scaled(40).max(5));
        for flush in [false, true] {
            for sizes in [vec![1], vec![3, 11], vec![stream.len()]] {
                if N >= layout.sync_len() {
                    check::<N>(layout, &stream, &sizes, flush);
                } else {
                    // The sync does not fit: nothing can be decoded, and a sync prefix cut by
                    // a chunk boundary cannot be held to see whether it completes.
                    let seen = run::<N>(layout, &stream, &sizes, flush);
                    assert!(frames(&seen).is_empty(), "{name}");
                }
            }
        }
    }
}

#[test]
fn buffers_smaller_than_max_len_never_panic_and_reject_long_frames() {
    let mut rng = Rng(0xB0B0_CAFE_0000_0042);
    small_buffer::<0>(&mut rng);
    small_buffer::<1>(&mut rng);
    small_buffer::<2>(&mut rng);
    small_buffer::<5>(&mut rng);
    small_buffer::<8>(&mut rng);
    small_buffer::<12>(&mut rng);
    small_buffer::<20>(&mut rng);
    small_buffer::<64>(&mut rng);
    small_buffer::<127>(&mut rng);
}

#[test]
fn random_garbage_never_panics_and_always_progresses() {
    let mut rng = Rng(0x7777_0000_1111_2222);
    for (_, layout) in layouts() {
        for hostile in [false, true] {
            let len = scaled(50_000);
            let stream = if hostile {
                hostile_garbage(&mut rng, layout, len)
            } else {
                let mut s = vec![0u8; len];
                rng.fill(&mut s);
                s
            };
            let sizes: Vec<usize> = (0..97).map(|_| 1 + rng.below(200)).collect();
            check::<128>(layout, &stream, &sizes, true);
            check::<16>(layout, &stream, &sizes, true);
            check::<128>(layout, &stream[..scaled(5000)], &[1], false);
        }
    }
}

#[test]
fn degenerate_layouts_still_progress() {
    let mut rng = Rng(0x1234_4321_5678_8765);
    let mut stream = vec![0u8; 3000];
    rng.fill(&mut stream);
    let base = common::TRAILER;
    let no_sync_fixed = FrameLayout {
        sync: &[],
        sync_set: &[],
        header_len: 0,
        min_len: 0,
        length: LengthRule::Fixed(3),
        markers: &[],
        escape: None,
        frame_checks: &[],
        ..base
    };
    let empty_frames = FrameLayout {
        length: LengthRule::Fixed(0),
        ..no_sync_fixed
    };
    let header_beyond_max = FrameLayout {
        header_len: 80,
        ..base
    };
    let long_sync = FrameLayout {
        sync: &[1, 2, 3, 4, 5, 6, 7, 8, 9, 10],
        sync_set: &[],
        ..base
    };
    for layout in [no_sync_fixed, empty_frames, header_beyond_max, long_sync] {
        for flush in [false, true] {
            check::<64>(&layout, &stream, &[1, 7, 64], flush);
            if layout.sync.len() <= 4 {
                check::<4>(&layout, &stream, &[5], flush);
            } else {
                run::<4>(&layout, &stream, &[5], flush);
            }
        }
    }
    let frames = run::<64>(&no_sync_fixed, &stream, &[10], false);
    assert_eq!(frames.len(), 1000);
}
