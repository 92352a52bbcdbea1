//! A layout type that declares the rule kinds its format lacks (`LayoutRef::ESCAPED`,
//! `HEADER_DECIDED`, `SEVERAL_FORMATS` false, and `CRC_CHECKED` false for HFLink's sum, as
//! generated code declares them): the engine
//! leaves those paths out and decodes the same events as with the layout read at run time,
//! on random streams of frames and noise cut into chunks of every size.
#![allow(clippy::unwrap_used, clippy::indexing_slicing)]

use crate::common;

use common::{HFLINK, REFEREE, ROBORTS, Rng, Seen, push, random_frame};
use protocol_runtime::StreamDecoder;
use protocol_runtime::layout::{FrameLayout, LayoutRef};

/// A format known at compile time that uses none of the three kinds, and a CRC where `CRC`.
#[derive(Clone, Copy)]
struct Plain<const CRC: bool>(&'static FrameLayout<'static>);

impl<const CRC: bool> LayoutRef for Plain<CRC> {
    const ESCAPED: bool = false;
    const HEADER_DECIDED: bool = false;
    const SEVERAL_FORMATS: bool = false;
    const CRC_CHECKED: bool = CRC;

    fn layout(&self) -> &FrameLayout<'_> {
        self.0
    }
}

/// Every event of `layout`'s decoder on `stream` fed in chunks of `size`, then flushed.
fn events<L: LayoutRef>(layout: L, stream: &[u8], size: usize) -> Vec<Seen> {
    let mut decoder = StreamDecoder::<L, 512>::new(layout);
    let mut seen = Vec::new();
    for mut chunk in stream.chunks(size) {
        while let Some(event) = decoder.next_event(&mut chunk) {
            push(&mut seen, event);
        }
    }
    while let Some(event) = decoder.flush_event() {
        push(&mut seen, event);
    }
    seen
}

/// Frames of random lengths, some damaged, between runs of noise.
fn stream(rng: &mut Rng, layout: &FrameLayout<'_>) -> Vec<u8> {
    let mut out = Vec::new();
    for _ in 0..40 {
        let span = layout.min_len.max(layout.header_span());
        let len = span + rng.below(layout.max_len.min(64) - span + 1);
        let mut frame = random_frame(rng, layout, len);
        if rng.below(4) == 0 {
            let at = rng.below(frame.len());
            frame[at] ^= 0x5A;
        }
        out.extend_from_slice(&frame);
        let noise = rng.below(6);
        out.extend((0..noise).map(|_| rng.byte()));
    }
    out
}

#[test]
fn declared_kinds_decode_as_the_layout_read_at_run_time() {
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    for (name, layout, crc) in [
        ("hflink", &HFLINK, false),
        ("referee", &REFEREE, true),
        ("roborts", &ROBORTS, true),
    ] {
        let stream = stream(&mut rng, layout);
        let frames = |seen: &[Seen]| {
            seen.iter()
                .filter(|s| matches!(s, Seen::Frame { .. }))
                .count()
        };
        for size in [1, 2, 3, 7, 16, 64, stream.len()] {
            let want = events(layout, &stream, size);
            assert!(frames(&want) >= 20, "{name}: the stream holds frames");
            let declared = if crc {
                events(Plain::<true>(layout), &stream, size)
            } else {
                events(Plain::<false>(layout), &stream, size)
            };
            assert_eq!(declared, want, "{name}, chunks of {size}");
        }
    }
}
