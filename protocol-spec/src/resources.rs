//! What a spec's decoders take: each frame format's largest frame, and the buffer and state of
//! a generated decoder of it, in bytes, on hosts and on targets without 64-bit pointers
//! ([`needs`]); the bound above which a spec is warned ([`BUFFER_BOUND`], the rule is
//! `lint`'s); where a frame's payload is declared, for messages that must quote the spec
//! ([`payload_origin`]).
//!
//! The sizes are the runtime's own rules ([`decoder_buffer_len_for`], [`decoder_state_len`]),
//! so what `protocol check` and the docs state is what generated code allocates.

use std::ops::Range;

use protocol_runtime::decoder::{decoder_buffer_len_for, decoder_state_len};

use crate::ir::{Frame, Protocol, Transport};
use crate::source::SpecSource;
use crate::spec::model::{FrameDef, SpecFile};

/// The largest decoder buffer a spec gets without a warning, in bytes, on a target without
/// 64-bit pointers: 64 KiB. `docs/spec-format.md` ("How much memory a decoder takes") gives
/// the reasons.
pub const BUFFER_BOUND: usize = 64 * 1024;

/// What a generated decoder of one frame format takes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Needs {
    /// The largest frame, in bytes.
    pub max_frame: usize,
    /// The decoder's buffer on a host (64-bit pointers).
    pub host_buffer: usize,
    /// The decoder's state besides its buffer on a host.
    pub host_state: usize,
    /// The decoder's buffer on a target without 64-bit pointers; `usize::MAX` when it does not
    /// fit a `usize` ([`fits_pointer_width`] tells where it fits).
    pub small_buffer: usize,
    /// The decoder's state on a target with 32-bit pointers.
    pub small_state: usize,
    /// Whether the frames come in a byte stream, read by a stream decoder; a CAN frame arrives
    /// whole and is decoded where it lies, so the buffer and state figures do not apply.
    pub stream: bool,
}

/// What a generated decoder of frame format `f` takes.
pub fn needs(f: &Frame) -> Needs {
    let max_frame = f.max_len();
    Needs {
        max_frame,
        host_buffer: decoder_buffer_len_for(max_frame, true),
        host_state: decoder_state_len(8),
        small_buffer: decoder_buffer_len_for(max_frame, false),
        small_state: decoder_state_len(4),
        stream: f.transport == Transport::Serial,
    }
}

impl Needs {
    /// Whether the buffer exceeds [`BUFFER_BOUND`] on a target without 64-bit pointers.
    pub fn above_bound(&self) -> bool {
        self.stream && self.small_buffer > BUFFER_BOUND
    }

    /// One line for a reader: `largest frame N bytes; decoder buffer H bytes (64-bit hosts)
    /// or M bytes (32-bit microcontrollers), plus S or S' bytes of state`.
    pub fn summary(&self) -> String {
        if !self.stream {
            return format!(
                "largest frame {} bytes; CAN frames arrive whole: no stream decoder, no buffer",
                self.max_frame
            );
        }
        format!(
            "largest frame {} bytes; decoder buffer {} bytes (64-bit hosts) or {} bytes (32-bit \
             microcontrollers), plus {} or {} bytes of state",
            self.max_frame,
            self.host_buffer,
            shown(self.small_buffer),
            self.host_state,
            self.small_state,
        )
    }
}

/// A size in bytes, or "impossibly large" for one that does not fit a `usize`.
fn shown(bytes: usize) -> String {
    if bytes == usize::MAX {
        "impossibly large".to_owned()
    } else {
        bytes.to_string()
    }
}

/// Whether a decoder buffer of `bytes` can exist on a target with `bits`-bit pointers: no
/// object there is larger than `isize::MAX` of that target.
pub fn fits_pointer_width(bytes: usize, bits: u32) -> bool {
    let largest = (1u128 << (bits - 1)) - 1;
    (bytes as u128) <= largest && bytes != usize::MAX
}

/// The span of the payload element of frame format `def` (its whole layout when it has none).
pub fn payload_span(def: &FrameDef) -> Range<usize> {
    def.layout
        .get_ref()
        .iter()
        .find(|e| e.get_ref().payload.is_some())
        .map_or_else(|| def.layout.span(), |e| e.span())
}

/// `PATH:LINE:COL` of `span` in `source`, then the line as written, trimmed, in backquotes.
pub fn payload_origin(source: &SpecSource, span: Range<usize>) -> String {
    let (line, col) = source.line_col(span.start);
    format!(
        "{}:{line}:{col}: `{}`",
        source.path,
        source.line_text(line).trim()
    )
}

/// Sets every frame's [`Frame::payload_origin`] from the spec it was lowered from.
pub(crate) fn locate_payloads(spec: &SpecFile, source: &SpecSource, p: &mut Protocol) {
    for f in &mut p.frames {
        if let Some((_, def)) = spec.frames.iter().find(|(n, _)| *n.get_ref() == f.name) {
            f.payload_origin = payload_origin(source, payload_span(def.get_ref()));
        }
    }
    // A direction's own layout of the first format declares its payload where the format does.
    if let Some(first) = p.frames.first().map(|f| f.payload_origin.clone()) {
        for f in p.directions.iter_mut().filter_map(|d| d.frame.as_mut()) {
            f.payload_origin.clone_from(&first);
        }
    }
}
