//! The checked stream driver: feeds bytes to a spec's generated decoder in given chunk sizes and
//! asserts the engine's invariants after every call, so that every suite (properties, faults,
//! fuzzing) checks the same things:
//!
//! - the decoder never holds more than its buffer, and once a chunk is used up only the start
//!   of one candidate, shorter than a frame;
//! - it always makes progress: every event accounts for at least one byte, the events tile the
//!   stream without gap or overlap, and a call returns `None` only once its input is consumed;
//! - every byte is accounted for: `frame_bytes + skipped_bytes + pending == position == fed`;
//! - every frame it yields is the stream's bytes at its offset, and a valid frame of the layout;
//!
//! A format that escapes its frames between flags ([`FrameLayout::escape`]) yields them
//! unescaped, and an event there does not say how many bytes of the wire it took (a rejected
//! candidate runs to the next flag; two frames may share a flag, counted with the first). There
//! each frame must be the stream's bytes at its offset unescaped, the events' offsets never go
//! back, frames overlap by a shared flag at most, and `frame_bytes` is the frames' escaped
//! lengths less the shared flags; the identity of the counters holds as for every format.
//! - every frame decodes to a packet or an error, never a panic, and a packet re-encodes to
//!   bytes that decode to the same packet.

use protocol_kit::decoder::Probe;
use protocol_kit::{Event, FrameLayout, Reject, Stats};

use super::{Dec, Spec, hex};

/// What a checked run yielded.
#[derive(Debug, Clone, Default)]
pub struct Run {
    /// The frames, with their stream offsets.
    pub frames: Vec<(u64, Vec<u8>)>,
    /// The rejected candidates.
    pub rejected: Vec<(u64, Reject)>,
    /// The decoder's counters at the end.
    pub stats: Stats,
}

/// Feeds `stream` to a fresh decoder of `S` in chunks of the sizes `sizes` (cycled; zero sizes
/// are fed too, as empty chunks), flushes it, and checks every invariant on the way.
///
/// # Panics
/// On any broken invariant.
pub fn run<S: Spec>(stream: &[u8], sizes: &[usize]) -> Run {
    let mut decoder = S::decoder();
    let mut out = Run::default();
    let mut cursor = Cursor::default();
    let mut fed = 0usize;
    let mut sizes = Sizes::new(sizes);
    let mut rest = stream;
    while !rest.is_empty() {
        let n = sizes.next(rest.len());
        let (chunk, tail) = rest.split_at(n);
        rest = tail;
        fed += n;
        let mut input = chunk;
        // Every event accounts for at least one byte, so a call that makes no progress would
        // show up here as more events than bytes.
        let budget = n + decoder.pending() + 1;
        let mut events = 0;
        loop {
            let before = input.len();
            let Some(event) = decoder.next_event(&mut input) else {
                assert!(
                    input.is_empty(),
                    "{}: None with {} bytes unread",
                    S::NAME,
                    input.len()
                );
                break;
            };
            events += 1;
            assert!(
                events <= budget,
                "{}: no progress at offset {}",
                S::NAME,
                cursor.at
            );
            assert!(input.len() <= before);
            record::<S>(event, stream, &mut cursor, &mut out);
            check_counters::<S>(&decoder, (fed - input.len()) as u64, &cursor, false);
        }
        check_counters::<S>(&decoder, fed as u64, &cursor, true);
    }
    let budget = decoder.pending() + 1;
    let mut events = 0;
    while let Some(event) = decoder.flush_event() {
        events += 1;
        assert!(events <= budget, "{}: flush makes no progress", S::NAME);
        record::<S>(event, stream, &mut cursor, &mut out);
    }
    assert_eq!(
        decoder.pending(),
        0,
        "{}: flush leaves bytes pending",
        S::NAME
    );
    check_counters::<S>(&decoder, fed as u64, &cursor, true);
    if S::layout().escape.is_none() {
        assert_eq!(
            cursor.at,
            stream.len() as u64,
            "{}: events do not cover the stream",
            S::NAME
        );
    }
    let stats = decoder.stats();
    assert_eq!(stats.frames, out.frames.len() as u64);
    assert_eq!(stats.rejected(), out.rejected.len() as u64);
    out.stats = stats;
    out
}

/// The frames of `stream` through the APIs users call (`decode` in a loop, and `feed`, then
/// `flush`), in chunks of `sizes`: must be exactly the frames of [`run`]. The two decoders must
/// agree after every chunk: the same frames, stats, position and pending bytes (`feed` scans
/// runs of frames in a loop of its own).
pub fn frames<S: Spec>(stream: &[u8], sizes: &[usize]) -> Vec<(u64, Vec<u8>)> {
    let mut decoder = S::decoder();
    let mut fed = S::decoder();
    let mut out = Vec::new();
    let mut out_fed = Vec::new();
    let mut sizes = Sizes::new(sizes);
    let mut rest = stream;
    while !rest.is_empty() {
        let n = sizes.next(rest.len());
        let (mut chunk, tail) = rest.split_at(n);
        rest = tail;
        fed.feed(chunk, |frame| {
            out_fed.push((frame.offset, frame.bytes.to_vec()))
        });
        while let Some(frame) = decoder.decode(&mut chunk) {
            out.push((frame.offset, frame.bytes.to_vec()));
        }
        assert!(chunk.is_empty());
        assert!(decoder.pending() < wire_bound::<S>(S::MAX_FRAME_LEN));
        assert_eq!(out_fed, out, "{}: feed and decode differ", S::NAME);
        assert_eq!(
            fed.stats(),
            decoder.stats(),
            "{}: feed and decode count differently",
            S::NAME
        );
        assert_eq!(fed.pending(), decoder.pending(), "{}", S::NAME);
        assert_eq!(fed.position(), decoder.position(), "{}", S::NAME);
    }
    while let Some(frame) = decoder.flush() {
        out.push((frame.offset, frame.bytes.to_vec()));
    }
    while let Some(frame) = fed.flush() {
        out_fed.push((frame.offset, frame.bytes.to_vec()));
    }
    assert_eq!(
        out_fed,
        out,
        "{}: feed and decode differ after flush",
        S::NAME
    );
    assert_eq!(fed.stats(), decoder.stats(), "{}", S::NAME);
    out
}

/// Chunk sizes, cycled: zeros are fed as empty chunks, but sizes that are all zero (or none)
/// mean the whole rest, so that feeding always ends.
struct Sizes<'a> {
    sizes: &'a [usize],
    next: usize,
}

impl<'a> Sizes<'a> {
    fn new(sizes: &'a [usize]) -> Self {
        let sizes = if sizes.iter().any(|&s| s > 0) {
            sizes
        } else {
            &[]
        };
        Sizes { sizes, next: 0 }
    }

    fn next(&mut self, rest: usize) -> usize {
        let Some(&n) = self.sizes.get(self.next % self.sizes.len().max(1)) else {
            return rest;
        };
        self.next += 1;
        n.min(rest)
    }
}

/// Where the events have got to in the stream.
#[derive(Debug, Default)]
struct Cursor {
    /// The end of the last event (for an escaped format: the furthest offset an event
    /// reached).
    at: u64,
    /// For an escaped format: the end of the last frame on the wire, and the bytes the
    /// frames took on the wire, a shared flag counted once.
    frame_end: u64,
    frame_bytes: u64,
}

/// Checks one event against the stream and appends it to `out`.
fn record<S: Spec>(event: Event<'_>, stream: &[u8], cursor: &mut Cursor, out: &mut Run) {
    let escaped = S::layout().escape.is_some();
    let (offset, len) = match event {
        Event::Frame(frame) => {
            let len = frame.bytes.len();
            let at = frame.offset as usize;
            let wire = if escaped {
                escaped_frame::<S>(frame.bytes, stream, at, cursor)
            } else {
                stream.get(at..at + len).map(<[u8]>::to_vec)
            };
            assert_eq!(
                Some(frame.bytes),
                wire.as_deref(),
                "{}: frame at {at} is not the stream's bytes",
                S::NAME
            );
            let layouts = S::layouts();
            assert_eq!(
                frame.format,
                S::format_of(frame.bytes),
                "{}: a frame of one format said to be of another: {}",
                S::NAME,
                hex(frame.bytes)
            );
            assert_eq!(
                layouts[frame.format].probe(frame.bytes),
                Probe::Frame(len),
                "{}: yielded an invalid frame {}",
                S::NAME,
                hex(frame.bytes)
            );
            check_packet::<S>(frame.bytes);
            out.frames.push((frame.offset, frame.bytes.to_vec()));
            (frame.offset, len)
        }
        Event::Rejected { offset, reason } => {
            out.rejected.push((offset, reason));
            (offset, 1)
        }
        Event::Skipped { offset, len } => (offset, len),
    };
    assert!(len > 0, "{}: an event of no bytes at {offset}", S::NAME);
    if escaped {
        assert!(
            offset >= cursor.at,
            "{}: an event at {offset} goes back before {}",
            S::NAME,
            cursor.at
        );
        cursor.at = offset;
        return;
    }
    assert_eq!(
        offset,
        cursor.at,
        "{}: events leave a gap or overlap",
        S::NAME
    );
    cursor.at += len as u64;
}

/// For a format that escapes its frames: the stream's bytes at `at` unescaped, which a frame
/// yielded there must be (`None` if they are no escaped frame); records the frame's bytes on
/// the wire, which start no earlier than the flag that closed the frame before.
fn escaped_frame<S: Spec>(
    frame: &[u8],
    stream: &[u8],
    at: usize,
    cursor: &mut Cursor,
) -> Option<Vec<u8>> {
    let escape = S::layout().escape?;
    let mut out = vec![0u8; frame.len()];
    let n = escape.unescape(stream.get(at..)?, &mut out).ok()?;
    out.truncate(n);
    let wire = escape.escaped_len(&out) as u64;
    let shared = cursor.frame_end > 0 && at as u64 + 1 == cursor.frame_end;
    assert!(
        shared || at as u64 >= cursor.frame_end,
        "{}: the frame at {at} overlaps the frame before, which ends at {}",
        S::NAME,
        cursor.frame_end
    );
    cursor.frame_bytes += wire - u64::from(shared);
    cursor.frame_end = at as u64 + wire;
    Some(out)
}

/// `n` unescaped bytes as they may go on the wire: twice as many where the format escapes its
/// frames (`pending` counts the bytes on the wire of a candidate the buffer holds unescaped).
fn wire_bound<S: Spec>(n: usize) -> usize {
    match S::layout().escape {
        Some(_) => 2 * n,
        None => n,
    }
}

/// The buffer bound and the accounting identity. Between events the buffer may hold a staged
/// chunk beyond a frame; once the input is used up (`idle`), it holds only the start of one
/// candidate, shorter than a frame.
fn check_counters<S: Spec>(decoder: &S::Decoder, fed: u64, cursor: &Cursor, idle: bool) {
    let pending = decoder.pending();
    assert!(
        !idle || pending < wire_bound::<S>(S::MAX_FRAME_LEN),
        "{}: {pending} bytes pending",
        S::NAME
    );
    assert!(pending <= wire_bound::<S>(<S::Decoder as Dec>::CAPACITY));
    let s = decoder.stats();
    assert_eq!(
        decoder.position(),
        fed,
        "{}: position is not the bytes fed",
        S::NAME
    );
    assert_eq!(
        s.frame_bytes + s.skipped_bytes + pending as u64,
        fed,
        "{}: counters do not add up: {s:?}, pending {pending}",
        S::NAME
    );
    if S::layout().escape.is_some() {
        assert_eq!(
            s.frame_bytes,
            cursor.frame_bytes,
            "{}: frame_bytes is not the frames' bytes on the wire",
            S::NAME
        );
        return;
    }
    assert_eq!(
        cursor.at + pending as u64,
        fed,
        "{}: events and pending bytes differ from fed",
        S::NAME
    );
}

/// A valid frame decodes to a packet or an error (never a panic); a packet re-encodes into
/// bytes that are a valid frame and decode to the same packet.
pub fn check_packet<S: Spec>(frame: &[u8]) {
    let Ok(packet) = S::from_frame(frame) else {
        return;
    };
    let bytes = packet
        .to_vec()
        .unwrap_or_else(|e| panic!("{}: decoded {packet:?} does not encode: {e}", S::NAME));
    let again = S::decode(&bytes).expect("re-encoded frame decodes");
    assert_same_packet(&packet, &again, &bytes);
}

/// `a == b`, or, when a value does not equal itself (a NaN), that both encode to the same
/// bytes. `bytes` (what `b` was decoded from) names the case in the message.
pub fn assert_same_packet<S: Spec>(a: &S, b: &S, bytes: &[u8]) {
    #[allow(clippy::eq_op)]
    if a == a {
        assert_eq!(a, b, "{}: packet changed through {}", S::NAME, hex(bytes));
    } else {
        assert_eq!(
            a.to_vec(),
            b.to_vec(),
            "{}: packet changed through {}",
            S::NAME,
            hex(bytes)
        );
    }
}

/// Whether a frame of `frames` holds another complete valid frame strictly inside it: the one
/// case where the frames depend on how the input was cut (see the decoder's module docs).
/// `layouts` are the formats the decoder finds.
pub fn nested_frame(
    layouts: &[&FrameLayout<'_>],
    frames: &[(u64, Vec<u8>)],
) -> Option<(u64, usize)> {
    frames.iter().find_map(|(offset, bytes)| {
        (1..bytes.len()).find_map(|k| {
            layouts
                .iter()
                .any(|l| matches!(l.probe(&bytes[k..]), Probe::Frame(_)))
                .then_some((*offset, k))
        })
    })
}

/// The frames of `stream` fed whole and fed in `sizes` must be the same, but for the
/// documented nested-frame case. Returns whether the documented case applied.
pub fn assert_chunking_invariant<S: Spec>(stream: &[u8], sizes: &[usize]) -> bool {
    let whole = run::<S>(stream, &[stream.len().max(1)]);
    let chunked = run::<S>(stream, sizes);
    assert_eq!(
        frames::<S>(stream, sizes),
        chunked.frames,
        "{}: decode (or feed) and next_event differ",
        S::NAME
    );
    if whole.frames == chunked.frames {
        return false;
    }
    let nested = nested_frame(&S::layouts(), &whole.frames);
    assert!(
        nested.is_some(),
        "{}: chunks {sizes:?} change the frames of {}:\nwhole   {:?}\nchunked {:?}",
        S::NAME,
        hex(stream),
        whole.frames.iter().map(|f| f.0).collect::<Vec<_>>(),
        chunked.frames.iter().map(|f| f.0).collect::<Vec<_>>(),
    );
    true
}
