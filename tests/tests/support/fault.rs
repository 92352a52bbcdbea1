//! The fault injector: long streams of valid frames of a spec, with seeded faults applied to
//! some frames and garbage between others, and a record of where every frame sent ended up and
//! whether a fault touched it.
//!
//! Faults that touch a frame: single and burst bit flips, dropped bytes, inserted bytes,
//! inserted sync words, truncation, a length field set to extreme or random values (with the
//! header checks left stale, or recomputed so that the header looks valid), and a corrupt header
//! in front of a payload that holds a valid-looking header. Faults between frames (no frame
//! touched): garbage, and sync words followed by part of a header. Frames whose payload holds
//! the sync word and a valid-looking header are also sent untouched: they must arrive.

use protocol_kit::FrameLayout;

use super::model::{Model, length_field, sync_word};
use super::payload::Ctx;
use super::{Rng, Source};

/// What was done to a frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Kind {
    /// Sent as built.
    Clean,
    /// Sent as built; its payload holds the sync word and a valid-looking header.
    FakeHeaderInside,
    /// One bit flipped.
    BitFlip,
    /// A burst of 2 to 32 bits, first and last flipped, the others at random.
    Burst,
    /// One to three bytes dropped.
    Drop,
    /// One to three random bytes inserted inside.
    Insert,
    /// The sync word inserted inside.
    SyncInside,
    /// Cut short: only a prefix was sent.
    Truncate,
    /// The length field set to another value (extremes included); header checks left stale.
    LengthStale,
    /// The length field set to another value, header checks recomputed: a valid-looking header
    /// that lies about the length.
    LengthForged,
    /// A payload with a valid-looking header inside, behind a corrupt outer header: the decoder
    /// resumes inside the payload and meets the fake header.
    FakeHeaderExposed,
}

impl Kind {
    /// Whether the fault changes the frame's bytes.
    pub fn touches(self) -> bool {
        !matches!(self, Kind::Clean | Kind::FakeHeaderInside)
    }
}

/// A frame as it appears in the stream.
#[derive(Debug, Clone)]
pub struct Sent {
    /// Offset of its first byte in the stream.
    pub offset: usize,
    /// Its bytes in the stream (the faulty bytes when touched).
    pub bytes: Vec<u8>,
    /// The frame before the fault.
    pub original: Vec<u8>,
    /// What was done to it.
    pub kind: Kind,
}

/// A stream and what it is made of.
#[derive(Debug, Clone, Default)]
pub struct FaultStream {
    /// The bytes.
    pub bytes: Vec<u8>,
    /// Every frame sent, in order.
    pub sent: Vec<Sent>,
    /// Runs of garbage inserted between frames.
    pub garbage_runs: usize,
    /// Sync words (with part of a header) inserted between frames.
    pub sync_runs: usize,
}

/// Builds a stream of `frames` frames of `model`, touching about one in `touch_one_in`.
/// On a link of several formats, each frame (and each run between frames) is of a format picked
/// at random.
pub fn build(link: &Model, rng: &mut Rng, frames: usize, touch_one_in: u64) -> FaultStream {
    let mut out = FaultStream::default();
    for _ in 0..frames {
        if rng.one_in(8) {
            between(link.pick(rng), rng, &mut out);
        }
        let model = link.pick(rng);
        let layout = model.layout;
        let fake = if rng.one_in(6) {
            fake_header_frame(model, rng)
        } else {
            None
        };
        let (mut frame, mut kind) = match fake {
            Some(frame) => (frame, Kind::FakeHeaderInside),
            None => (model.canonical_here(rng), Kind::Clean),
        };
        let original = frame.clone();
        if rng.one_in(touch_one_in) {
            kind = if kind == Kind::FakeHeaderInside {
                corrupt_header(layout, rng, &mut frame);
                Kind::FakeHeaderExposed
            } else {
                touch(layout, rng, &mut frame)
            };
        }
        if !frame.is_empty() {
            out.sent.push(Sent {
                offset: out.bytes.len(),
                bytes: frame.clone(),
                original,
                kind,
            });
            out.bytes.extend_from_slice(&frame);
        }
    }
    out
}

/// Garbage, or a sync word with part of a header, between two frames (of `model`'s format).
fn between(model: &Model, rng: &mut Rng, out: &mut FaultStream) {
    let sync = sync_word(model.layout, rng.below(256) as usize);
    if rng.one_in(2) {
        let n = rng.range(1, 16) as usize;
        for _ in 0..n {
            let b = if rng.one_in(3) {
                sync[rng.below(sync.len() as u64) as usize]
            } else {
                rng.byte()
            };
            out.bytes.push(b);
        }
        out.garbage_runs += 1;
    } else {
        let header = model.canonical_here(rng);
        let n = rng.range(sync.len() as u64, model.layout.header_span() as u64) as usize;
        out.bytes.extend_from_slice(&header[..n.min(header.len())]);
        out.sync_runs += 1;
    }
}

/// Applies a random fault that changes the frame's bytes.
fn touch(layout: &FrameLayout<'_>, rng: &mut Rng, frame: &mut Vec<u8>) -> Kind {
    let len = frame.len();
    match rng.below(9) {
        0 => {
            let bit = rng.below(8 * len as u64) as usize;
            frame[bit / 8] ^= 1 << (bit % 8);
            Kind::BitFlip
        }
        1 => {
            let total = 8 * len as u64;
            let start = rng.below(total - 1);
            let span = rng.range(2, 32.min(total - start));
            for i in 0..span {
                if i == 0 || i == span - 1 || rng.one_in(2) {
                    let bit = (start + i) as usize;
                    frame[bit / 8] ^= 1 << (bit % 8);
                }
            }
            Kind::Burst
        }
        2 => {
            for _ in 0..rng.range(1, 3).min(len as u64 - 1) {
                let at = rng.below(frame.len() as u64) as usize;
                frame.remove(at);
            }
            Kind::Drop
        }
        3 => {
            for _ in 0..rng.range(1, 3) {
                let at = rng.range(1, frame.len() as u64 - 1) as usize;
                frame.insert(at, rng.byte());
            }
            Kind::Insert
        }
        4 => {
            let at = rng.range(1, len as u64 - 1) as usize;
            frame.splice(at..at, sync_word(layout, rng.below(256) as usize));
            Kind::SyncInside
        }
        5 | 6 if length_field(layout).is_some() => {
            let forged = rng.one_in(2);
            set_length(layout, rng, frame, forged, false);
            if forged {
                Kind::LengthForged
            } else {
                Kind::LengthStale
            }
        }
        _ => {
            frame.truncate(rng.range(1, len as u64 - 1) as usize);
            Kind::Truncate
        }
    }
}

/// Sets the length field to another value: 0, the field's maximum, just outside and at the
/// format's bounds, or random; or, `in_bounds`, to another length the format allows (if there
/// is one). With `forged`, the header checks are recomputed.
fn set_length(
    layout: &FrameLayout<'_>,
    rng: &mut Rng,
    frame: &mut [u8],
    forged: bool,
    in_bounds: bool,
) {
    let (field, adjust) = length_field(layout).expect("a length field");
    let current = field.read(frame).expect("length field");
    let value_for = |total: usize| u64::try_from(total as i64 - adjust).ok();
    let lo = layout.min_len.max(layout.header_span());
    let pick = |rng: &mut Rng| {
        if in_bounds {
            return value_for(rng.range(lo as u64, layout.max_len as u64) as usize);
        }
        match rng.below(8) {
            0 => Some(0),
            1 => Some(field.max_value()),
            2 => value_for(layout.min_len).and_then(|v| v.checked_sub(1)),
            3 => value_for(layout.min_len),
            4 => value_for(layout.max_len),
            5 => value_for(layout.max_len + 1),
            6 => Some(current ^ 1),
            _ => Some(rng.next_u64() & field.max_value()),
        }
    };
    if in_bounds && lo >= layout.max_len {
        return;
    }
    let value = loop {
        if let Some(v) = pick(rng).filter(|&v| v != current && v <= field.max_value()) {
            break v;
        }
    };
    field.write(frame, value).expect("length fits");
    if forged {
        let header = &mut frame[..layout.header_span()];
        for check in layout.header_checks {
            check.store(header).expect("header check");
        }
    }
}

/// Flips a bit in the sync bytes or the header, so that the decoder rejects the frame's start
/// and resumes inside it.
fn corrupt_header(layout: &FrameLayout<'_>, rng: &mut Rng, frame: &mut [u8]) {
    let span = layout.header_span().min(frame.len());
    let bit = rng.below(8 * span as u64) as usize;
    frame[bit / 8] ^= 1 << (bit % 8);
}

/// A valid frame whose payload holds the sync word and a valid-looking header (header checks
/// right, a length in the format's bounds), or `None` if no payload came out long enough.
fn fake_header_frame(model: &Model, rng: &mut Rng) -> Option<Vec<u8>> {
    let span = model.layout.header_span();
    let fits: Vec<_> = model
        .choices
        .iter()
        .filter(|c| model.payload_len(**c) >= span)
        .collect();
    let choice = **fits.get(rng.below(fits.len() as u64) as usize)?;
    let mut payload = Vec::new();
    let room = model.frame().payload_max;
    model.canonical_struct(
        rng,
        choice.payload?,
        room,
        &mut Ctx::default(),
        &mut payload,
    );
    if payload.len() < span {
        return None;
    }
    let mut inner = model.canonical_here(rng);
    if length_field(model.layout).is_some() {
        set_length(model.layout, rng, &mut inner, true, true);
    }
    let at = rng.below((payload.len() - span + 1) as u64) as usize;
    payload[at..at + span].copy_from_slice(&inner[..span]);
    model.try_build(rng, choice, &payload).ok()
}
