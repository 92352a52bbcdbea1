//! Decoding and encoding never allocate: every spec's stream decoder, `Packet::from_frame` and
//! `Packet::encode` run under a counting global allocator (`allocation-counter`, which counts
//! the calling thread's allocations, so the test harness's own threads do not interfere) on
//! streams with every kind of fault, and the count must be zero.
//!
//! The counting allocator is the global allocator of the whole test binary (`main.rs` says why
//! the other tests can share it).
//!
//! The packets to encode are those of the frames sent, read as a decoder yields them
//! (unescaped, on a format that escapes its frames).

use crate::support;

use support::fault::build;
use support::model::model;
use support::{Dec, Rng, Spec};

/// The allocator counts: an allocation inside `measure` is seen (so zero below means zero).
#[test]
fn the_counter_counts() {
    let info = allocation_counter::measure(|| {
        std::hint::black_box(vec![1u8; 16]);
    });
    assert_eq!(info.count_total, 1);
}

fn no_alloc<S: Spec>() {
    let m = model::<S>();
    let stream = build(m, &mut Rng(11), 300, 3);
    let chunks: Vec<&[u8]> = stream.bytes.chunks(37).collect();
    let packets: Vec<S> = stream
        .sent
        .iter()
        .filter_map(|s| {
            S::from_frame(&support::unescaped(
                m.format_for(&s.original).layout,
                &s.original,
            ))
            .ok()
        })
        .collect();
    assert!(!packets.is_empty());
    let mut buf = vec![0u8; S::wire_max_len()];
    let mut decoder = S::decoder();

    let mut frames = 0usize;
    let mut decoded = 0usize;
    let info = allocation_counter::measure(|| {
        for chunk in &chunks {
            let mut input = *chunk;
            while let Some(frame) = decoder.decode(&mut input) {
                frames += 1;
                decoded += usize::from(S::from_frame(frame.bytes).is_ok());
            }
        }
        while let Some(frame) = decoder.flush() {
            frames += 1;
            decoded += usize::from(S::from_frame(frame.bytes).is_ok());
        }
    });
    assert_eq!(
        info.count_total,
        0,
        "{}: decoding allocated {info:?}",
        S::NAME
    );
    // The same stream through `feed`, which scans in its own loops.
    let mut fed_decoder = S::decoder();
    let mut fed_frames = 0usize;
    let info = allocation_counter::measure(|| {
        for chunk in &chunks {
            fed_decoder.feed(chunk, |_| fed_frames += 1);
        }
        while fed_decoder.flush().is_some() {
            fed_frames += 1;
        }
    });
    assert_eq!(info.count_total, 0, "{}: feed allocated {info:?}", S::NAME);
    assert_eq!(fed_frames, frames, "{}: feed and decode differ", S::NAME);
    assert!(frames > 0 && decoded > 0, "{}: nothing decoded", S::NAME);

    let mut written = 0usize;
    let info = allocation_counter::measure(|| {
        for packet in &packets {
            written += packet.encode(&mut buf).unwrap_or(0);
        }
    });
    assert_eq!(
        info.count_total,
        0,
        "{}: encoding allocated {info:?}",
        S::NAME
    );
    assert!(written > 0, "{}: nothing encoded", S::NAME);
}

macro_rules! no_alloc_suite {
    ($name:ident, $path:literal $(, $given:tt)*) => {
        #[test]
        fn $name() {
            no_alloc::<support::packet!($name $(, $given)*)>();
        }
    };
}

support::for_each_spec!(no_alloc_suite);
