//! The packet rules of a frame format as data: what lies between a frame the engine checked and
//! a typed packet. Which bytes are the payload (after the header and a wider length, before the
//! trailer and a flag trailer, unstuffed), whether the frame is an acknowledgement and where its
//! data is, the dispatch key, the direction the header tells, trailing zeros refilled and the
//! fields a format without extension fields carries; and back: a frame assembled from a body, a
//! payload writer and header values (the payload trimmed, stuffed and placed behind a wider
//! length, the acknowledgement flag and the key written, the frame sealed).
//!
//! As [`FrameLayout`] is for the frame rules, a [`PacketRules`] is one value that two backends
//! execute: generated code holds it as a `static` (its reads fold into the code one would write
//! for the one format), the run-time codec builds it from a spec. Neither writes a packet rule
//! of its own; what stays to each is the key-to-struct match (which command a key names, which
//! struct a command carries).
//!
//! It does not verify frames (the engine does, through [`FrameLayout`]) nor read or write
//! payload fields (the payload code does).

use crate::encoder::{MessagePayload, frame_room, payload_room};
use crate::error::{DecodeError, EncodeError};
use crate::layout::{FrameLayout, WordField};
use crate::stuffing::Stuffing;
use crate::wire::Writer;
use crate::zeros::{trimmed_len, zero_filled};

/// Runs `$body` with `$item` bound to each item of `$items`, in order. One or two items (a key
/// of one or two fields, two directions: the usual cases) are matched apart: with rules known
/// at compile time each item is then a constant the compiler folds, which a loop only gives
/// where the compiler unrolls it (not at `opt-level = "s"`, where a loop over the key kept a
/// word field reader for any position, size and byte order in firmware). The same reasoning
/// as the layout's `all_hold!`.
macro_rules! each {
    ($items:expr, |$item:ident| $body:block) => {
        match $items {
            [] => {}
            [one] => {
                let $item = one;
                $body
            }
            [one, two] => {
                {
                    let $item = one;
                    $body
                }
                {
                    let $item = two;
                    $body
                }
            }
            more => {
                for $item in more {
                    $body
                }
            }
        }
    };
}

/// Acknowledgements: frames whose one-bit header flag holds `equals` carry no command, and
/// their payload is data from `header_len` on (the dispatch fields are absent).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct AckRule {
    /// The flag.
    pub flag: WordField,
    /// The flag's value in an acknowledgement (the other value marks a command).
    pub equals: u64,
    /// Bytes of an acknowledgement's header.
    pub header_len: usize,
    /// True when an acknowledgement without data is its header alone, without trailer (the
    /// format's [`LengthRule::FieldOrBare`](crate::layout::LengthRule::FieldOrBare)).
    pub bare: bool,
}

/// How the header tells a direction: the first test that holds names it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum DirectionTest {
    /// A header value lies in `first ..= last` (an address range).
    InRange {
        /// The header value.
        field: WordField,
        /// Lowest value.
        first: u64,
        /// Highest value.
        last: u64,
    },
    /// A header value equals `value` (a flag).
    Equals {
        /// The header value.
        field: WordField,
        /// The value.
        value: u64,
    },
}

impl DirectionTest {
    /// The test that `field` lies in `first ..= last`.
    #[must_use]
    pub const fn in_range(field: WordField, first: u64, last: u64) -> Self {
        DirectionTest::InRange { field, first, last }
    }

    /// The test that `field` equals `value`.
    #[must_use]
    pub const fn equals(field: WordField, value: u64) -> Self {
        DirectionTest::Equals { field, value }
    }

    /// Whether the header of `frame` passes the test (`None` if the frame is too short for
    /// the field).
    #[inline(always)]
    fn holds(&self, frame: &[u8]) -> Option<bool> {
        match *self {
            DirectionTest::InRange { field, first, last } => {
                let v = field.read(frame)?;
                Some(first <= v && v <= last)
            }
            DirectionTest::Equals { field, value } => Some(field.read(frame)? == value),
        }
    }
}

/// The packet rules of a frame format.
#[derive(Debug, Clone, Copy)]
pub struct PacketRules<'a> {
    /// The frame rules: a wider length and a flag trailer are read and placed through it, and
    /// an assembled frame is sealed by it.
    pub layout: &'a FrameLayout<'a>,
    /// Bytes before the payload of a command frame.
    pub header_len: usize,
    /// Bytes after the payload (checks, markers), without a flag trailer.
    pub trailer_len: usize,
    /// Largest payload on the wire.
    pub max_payload: usize,
    /// The dispatch key's fields, in key order (for a CAN format, the whole identifier word);
    /// empty for a format whose frames carry one struct.
    pub key: &'a [WordField],
    /// Acknowledgements, if the format has them.
    pub ack: Option<AckRule>,
    /// The directions the header tells, in the order of the spec's directions; empty when the
    /// spec has none or the decoding side is given the direction.
    pub directions: &'a [DirectionTest],
    /// Byte stuffing of command and struct payloads (acknowledgement data is sent as it is), if
    /// any.
    pub stuffing: Option<Stuffing<'a>>,
    /// The sender drops a command payload's trailing zeros; the receiver refills them.
    pub truncate_zeros: bool,
}

/// What an assembled frame carries.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Body<'k> {
    /// A command's payload.
    Command {
        /// The key's values, one per key field.
        key: &'k [u64],
        /// The bytes of the payload the format carries (the fields before the extension
        /// fields, for a format without them); `None`: all it writes.
        carried: Option<usize>,
        /// The direction the message is of (an index into
        /// [`directions`](PacketRules::directions)): the header written must tell it.
        direction: Option<usize>,
    },
    /// An acknowledgement's data.
    Ack,
    /// One struct, from byte `start` (a format without key: the header's length; a direction
    /// that carries a struct in place of the key: where the key would be).
    Struct {
        /// Where the payload starts.
        start: usize,
    },
}

impl PacketRules<'_> {
    fn truncated(&self, frame: &[u8]) -> DecodeError {
        DecodeError::Truncated {
            needed: self.header_len,
            available: frame.len(),
        }
    }

    /// The largest acknowledgement data: what the largest frame holds after an
    /// acknowledgement's header and before the trailer.
    #[inline(always)]
    #[must_use]
    pub fn ack_max(&self) -> usize {
        let header = self.ack.map_or(self.header_len, |a| a.header_len);
        self.layout
            .max_len
            .saturating_sub(header)
            .saturating_sub(self.trailer_len)
    }

    /// The data of `frame` when it is an acknowledgement, `None` when it is not.
    ///
    /// # Errors
    ///
    /// [`DecodeError::Truncated`] if the frame is shorter than its header,
    /// [`DecodeError::PayloadLength`] if the data is longer than [`ack_max`](Self::ack_max).
    #[inline(always)]
    pub fn ack_data<'f>(&self, frame: &'f [u8]) -> Result<Option<&'f [u8]>, DecodeError> {
        let Some(ack) = self.ack else {
            return Ok(None);
        };
        if ack.flag.read(frame).ok_or(self.truncated(frame))? != ack.equals {
            return Ok(None);
        }
        // A bare header is the header alone: no trailer to leave out.
        let end = if ack.bare && frame.len() == ack.header_len {
            frame.len()
        } else {
            frame.len().saturating_sub(self.trailer_len)
        };
        let data = frame
            .get(ack.header_len..end)
            .ok_or(DecodeError::Truncated {
                needed: ack.header_len,
                available: frame.len(),
            })?;
        let max = self.ack_max();
        if data.len() > max {
            return Err(DecodeError::PayloadLength {
                expected: max,
                actual: data.len(),
            });
        }
        Ok(Some(data))
    }

    /// The value of key field `i` of `frame`.
    ///
    /// # Errors
    ///
    /// [`DecodeError::Truncated`] if the frame ends before the field (or the format has no
    /// field `i`).
    #[inline(always)]
    pub fn key_value(&self, frame: &[u8], i: usize) -> Result<u64, DecodeError> {
        self.key
            .get(i)
            .and_then(|f| f.read(frame))
            .ok_or(self.truncated(frame))
    }

    /// The key of `frame` as one number, its fields' values side by side (the first field in
    /// the high bits): what [`DecodeError::UnknownCommand`] reports.
    ///
    /// # Errors
    ///
    /// [`DecodeError::Truncated`] if the frame ends before a key field.
    #[inline(always)]
    pub fn key(&self, frame: &[u8]) -> Result<u64, DecodeError> {
        let mut key = 0u64;
        each!(self.key, |f| {
            let v = f.read(frame).ok_or(self.truncated(frame))?;
            key = key.checked_shl(u32::from(f.width)).unwrap_or(0) | v;
        });
        Ok(key)
    }

    /// The direction the header of `frame` tells: the index of the first test that holds.
    ///
    /// # Errors
    ///
    /// [`DecodeError::UnknownDirection`] if none holds (a frame too short for a tested field
    /// holds none; its header read says `Truncated` first).
    #[inline(always)]
    pub fn direction(&self, frame: &[u8]) -> Result<usize, DecodeError> {
        // Matched apart as `each!` does, for the same reason.
        let found = match self.directions {
            [] => None,
            [one] => (one.holds(frame) == Some(true)).then_some(0),
            [one, two] => {
                if one.holds(frame) == Some(true) {
                    Some(0)
                } else {
                    (two.holds(frame) == Some(true)).then_some(1)
                }
            }
            more => more.iter().position(|t| t.holds(frame) == Some(true)),
        };
        found.ok_or(DecodeError::UnknownDirection)
    }

    /// Whether the header of `frame` tells direction `d` ([`direction`](Self::direction) would
    /// say `d`): always, when the header tells no direction. For an encoder's check, without
    /// the decoder's errors.
    #[inline(always)]
    #[must_use]
    pub fn tells(&self, frame: &[u8], d: usize) -> bool {
        // Matched apart as `each!` does, for the same reason.
        match self.directions {
            [] => true,
            [one] => d == 0 && one.holds(frame) == Some(true),
            [one, two] => match d {
                0 => one.holds(frame) == Some(true),
                1 => one.holds(frame) == Some(false) && two.holds(frame) == Some(true),
                _ => false,
            },
            more => more.iter().position(|t| t.holds(frame) == Some(true)) == Some(d),
        }
    }

    /// The payload of a command frame: the bytes after the header (and a wider length) and
    /// before the trailer (and a flag trailer), unstuffed into `scratch` when the format stuffs
    /// its payloads.
    ///
    /// # Errors
    ///
    /// [`DecodeError::Truncated`] if the frame is shorter than its header and trailer, and the
    /// errors of [`Stuffing::unstuff`].
    #[inline(always)]
    pub fn payload<'f>(
        &self,
        frame: &'f [u8],
        scratch: &'f mut [u8],
    ) -> Result<&'f [u8], DecodeError> {
        let start = self
            .header_len
            .saturating_add(self.layout.extension_len(frame));
        self.payload_from(frame, start, scratch)
    }

    /// The payload of a frame from byte `start` (an acknowledgement's or a struct carried in
    /// place of the key) to the trailer, unstuffed as [`payload`](Self::payload) does.
    ///
    /// # Errors
    ///
    /// As [`payload`](Self::payload).
    #[inline(always)]
    pub fn payload_from<'f>(
        &self,
        frame: &'f [u8],
        start: usize,
        scratch: &'f mut [u8],
    ) -> Result<&'f [u8], DecodeError> {
        let trailer = self
            .trailer_len
            .saturating_add(self.layout.flag_trailer_len(frame));
        let sent = frame
            .get(start..frame.len().saturating_sub(trailer))
            .ok_or(DecodeError::Truncated {
                needed: start.saturating_add(trailer),
                available: frame.len(),
            })?;
        match self.stuffing {
            Some(s) => s.unstuff(sent, scratch),
            None => Ok(sent),
        }
    }

    /// A command payload as its struct of `size` bytes reads it: with `carried` (a format
    /// without extension fields carries exactly the `carried` bytes before them), exactly that
    /// many bytes, zero-filled to `size`; with trailing-zero truncation, zero-filled to `size`;
    /// else as it is. The fill is written into `scratch`.
    ///
    /// # Errors
    ///
    /// [`DecodeError::PayloadLength`] if the payload is not `carried` bytes long, and the
    /// errors of [`zero_filled`].
    #[inline(always)]
    pub fn filled<'p>(
        &self,
        payload: &'p [u8],
        size: usize,
        carried: Option<usize>,
        scratch: &'p mut [u8],
    ) -> Result<&'p [u8], DecodeError> {
        if let Some(carried) = carried {
            if payload.len() != carried {
                return Err(DecodeError::PayloadLength {
                    expected: carried,
                    actual: payload.len(),
                });
            }
            return zero_filled(payload, size, scratch);
        }
        if self.truncate_zeros {
            return zero_filled(payload, size, scratch);
        }
        Ok(payload)
    }
}

/// Encoding.
impl PacketRules<'_> {
    /// Where the payload of `body` starts, before a wider length moves it.
    #[inline(always)]
    #[must_use]
    pub fn start(&self, body: &Body<'_>) -> usize {
        match *body {
            Body::Command { .. } => self.header_len,
            Body::Ack => self.ack.map_or(self.header_len, |a| a.header_len),
            Body::Struct { start } => start,
        }
    }

    /// The stuffing of `body`'s payload: the format's, for a command's or a struct's payload;
    /// none for acknowledgement data, which [`ack_data`](Self::ack_data) gives as it is on the
    /// wire.
    #[inline(always)]
    fn stuffing_of(&self, body: &Body<'_>) -> Option<Stuffing<'_>> {
        self.stuffing.filter(|_| !matches!(body, Body::Ack))
    }

    /// True when a command's payload is written aside before it is placed in the frame (its
    /// size on the wire is known only once it is written: trailing zeros trimmed, bytes
    /// stuffed, or fields after the carried ones cut).
    #[inline(always)]
    #[must_use]
    pub fn writes_aside(&self, body: &Body<'_>) -> bool {
        let cut = matches!(
            body,
            Body::Command {
                carried: Some(_),
                ..
            }
        );
        let trimmed = self.truncate_zeros && matches!(body, Body::Command { .. });
        cut || trimmed || self.stuffing_of(body).is_some()
    }

    /// The bytes a written payload takes on the wire: cut to what the format carries, its
    /// trailing zeros trimmed, stuffed.
    #[inline(always)]
    #[must_use]
    pub fn wire_len(&self, body: &Body<'_>, written: &[u8]) -> usize {
        let sent = self.sent(body, written);
        let stuffed = match self.stuffing_of(body) {
            Some(s) => s.count(sent),
            None => 0,
        };
        sent.len().saturating_add(stuffed)
    }

    /// The bytes of a written payload that are sent, before stuffing.
    #[inline(always)]
    fn sent<'w>(&self, body: &Body<'_>, written: &'w [u8]) -> &'w [u8] {
        let written = match *body {
            Body::Command {
                carried: Some(c), ..
            } => written.get(..c).unwrap_or(written),
            _ => written,
        };
        if self.truncate_zeros && matches!(body, Body::Command { .. }) {
            return written.get(..trimmed_len(written)).unwrap_or(written);
        }
        written
    }

    /// The trailer's bytes in a frame of `body` whose payload takes `plen` bytes: none for a
    /// bare header (an acknowledgement without data), else the format's.
    #[inline(always)]
    fn trailer_for(&self, body: &Body<'_>, plen: usize) -> usize {
        let bare = self.ack.is_some_and(|a| a.bare);
        if bare && matches!(body, Body::Ack) && plen == 0 {
            0
        } else {
            self.trailer_len
        }
    }

    /// The length of the frame of `body` whose payload takes `plen` bytes on the wire, with
    /// `flag_trailer` bytes of flag trailer: what [`assemble`](Self::assemble) writes.
    #[inline(always)]
    #[must_use]
    pub fn frame_len(&self, body: &Body<'_>, plen: usize, flag_trailer: usize) -> usize {
        let short = self
            .start(body)
            .saturating_add(plen)
            .saturating_add(self.trailer_for(body, plen));
        short
            .saturating_add(self.layout.extension_for(short))
            .saturating_add(flag_trailer)
    }

    /// Assembles a frame of `body` into the start of `buf`: the payload `write` writes (in
    /// place, or into `aside` and then placed, as [`writes_aside`](Self::writes_aside) says),
    /// cut, trimmed, stuffed and moved behind a wider length; then the header values `header`
    /// writes (it also writes a flag trailer's flag and bytes), the acknowledgement flag and
    /// the key; then the frame is sealed. `len` gives the frame's length as the caller computes
    /// it ([`frame_len`](Self::frame_len)), asked only when the payload is written in place
    /// (the buffer is checked against it first); `flag_trailer` is the bytes of flag trailer
    /// the frame carries. Returns the frame's length.
    ///
    /// # Errors
    ///
    /// [`EncodeError::BufferTooSmall`] if `buf` (or `aside`) is too short;
    /// [`EncodeError::ValueOutOfRange`] if a key value or a header value does not fit its
    /// field, or the header written does not tell the message's direction; the errors of
    /// `write`, `header` and [`FrameLayout::seal`].
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub fn assemble(
        &self,
        buf: &mut [u8],
        aside: &mut [u8],
        body: &Body<'_>,
        len: impl FnOnce() -> usize,
        flag_trailer: usize,
        write: impl FnOnce(&mut Writer<'_>) -> Result<(), EncodeError>,
        header: impl FnOnce(&mut [u8]) -> Result<(), EncodeError>,
    ) -> Result<usize, EncodeError> {
        let start = self.start(body);
        let trailer_out = self.trailer_len.saturating_add(flag_trailer);
        let plen = if self.writes_aside(body) {
            self.place_aside(buf, aside, body, start, trailer_out, write)?
        } else {
            let mut w = Writer::new(self.room(buf, body, len(), flag_trailer)?);
            write(&mut w)?;
            w.position()
        };
        let (frame, total) = self.frame(buf, body, plen, flag_trailer)?;
        header(frame)?;
        self.seal(frame, body)?;
        Ok(total)
    }

    /// For an encoder that writes the payload of `body` in place (where
    /// [`writes_aside`](Self::writes_aside) is false): the room for it in `buf`, from where it
    /// starts to where the trailer and `flag_trailer` bytes of flag trailer must stay free,
    /// once `buf` is known to hold the frame's `len` bytes ([`frame_len`](Self::frame_len)).
    /// The three steps [`room`](Self::room), [`frame`](Self::frame) and [`seal`](Self::seal)
    /// are [`assemble`](Self::assemble) with the payload and the header written between them,
    /// in straight-line code.
    ///
    /// # Errors
    ///
    /// [`EncodeError::BufferTooSmall`] if `buf` is shorter than `len`.
    #[inline(always)]
    pub fn room<'b>(
        &self,
        buf: &'b mut [u8],
        body: &Body<'_>,
        len: usize,
        flag_trailer: usize,
    ) -> Result<&'b mut [u8], EncodeError> {
        let start = self.start(body);
        let available = buf.len();
        if available < len {
            return Err(EncodeError::BufferTooSmall {
                needed: len,
                available,
            });
        }
        // A bare header has no trailer: its (empty) room may end before the trailer would
        // start.
        let trailer_out = self.trailer_len.saturating_add(flag_trailer);
        let end = available.saturating_sub(trailer_out).max(start);
        buf.get_mut(start..end).ok_or(EncodeError::BufferTooSmall {
            needed: len,
            available,
        })
    }

    /// The frame of `body` whose payload, `plen` bytes on the wire, was placed at its start
    /// ([`start`](Self::start)): the payload moved behind a wider length where the frame needs
    /// one, and the frame's bytes in `buf` with its length, for the header values to be
    /// written into before [`seal`](Self::seal).
    ///
    /// # Errors
    ///
    /// [`EncodeError::BufferTooSmall`] if `buf` is shorter than the frame.
    #[inline(always)]
    pub fn frame<'b>(
        &self,
        buf: &'b mut [u8],
        body: &Body<'_>,
        plen: usize,
        flag_trailer: usize,
    ) -> Result<(&'b mut [u8], usize), EncodeError> {
        let start = self.start(body);
        let trailer = self.trailer_for(body, plen);
        // A wider length moves the payload behind it; most formats have none (this folds away).
        let short = start.saturating_add(plen).saturating_add(trailer);
        let start = if self.layout.extension_for(short) == 0 {
            start
        } else {
            self.layout.place_payload(buf, start, plen, trailer)?
        };
        let total = start
            .saturating_add(plen)
            .saturating_add(trailer)
            .saturating_add(flag_trailer);
        Ok((frame_room(buf, total)?, total))
    }

    /// Completes a frame of `body` whose header values are written: the acknowledgement flag
    /// and the key, the check that the header tells the message's direction, then the frame
    /// rules' seal (length, constants, checks).
    ///
    /// # Errors
    ///
    /// [`EncodeError::ValueOutOfRange`] if a key value does not fit its field or the header
    /// does not tell the message's direction; the errors of [`FrameLayout::seal`].
    #[inline(always)]
    pub fn seal(&self, frame: &mut [u8], body: &Body<'_>) -> Result<(), EncodeError> {
        self.write_body(frame, body)?;
        self.layout.seal(frame)
    }

    /// The length of the frame that carries `message` as `body`, with `flag_trailer` bytes of
    /// flag trailer: [`frame_len`](Self::frame_len) of the message's payload as it goes on the
    /// wire (written into `aside` and measured where the rules write aside; `aside` is unused
    /// otherwise and may be empty).
    #[inline(always)]
    pub fn message_len<M: MessagePayload>(
        &self,
        body: &Body<'_>,
        message: &M,
        aside: &mut [u8],
        flag_trailer: usize,
    ) -> usize {
        let plen = if self.writes_aside(body) {
            let mut w = Writer::new(aside);
            match message.write_payload(&mut w) {
                Ok(()) => self.wire_len(body, w.written()),
                // The encoder reports the error; the length is the message's own.
                Err(_) => message.payload_len(),
            }
        } else {
            message.payload_len()
        };
        self.frame_len(body, plen, flag_trailer)
    }

    /// Encodes `message` as `body` into the start of `buf`: [`assemble`](Self::assemble) with
    /// the message's payload and `header` writing the header values. Returns the frame's
    /// length.
    ///
    /// # Errors
    ///
    /// The errors of [`assemble`](Self::assemble).
    #[inline(always)]
    pub fn encode_message<M: MessagePayload>(
        &self,
        buf: &mut [u8],
        aside: &mut [u8],
        body: &Body<'_>,
        message: &M,
        flag_trailer: usize,
        header: impl FnOnce(&mut [u8]) -> Result<(), EncodeError>,
    ) -> Result<usize, EncodeError> {
        // `assemble`'s steps written out with the message's own calls rather than closures:
        // the compiler then keeps a fixed-size payload in registers and folds its checksum, as
        // it does for hand-written code (through closures it summed a stack copy, several
        // times slower).
        let plen = if self.writes_aside(body) {
            let start = self.start(body);
            let trailer_out = self.trailer_len.saturating_add(flag_trailer);
            self.place_aside(buf, aside, body, start, trailer_out, |w| {
                message.write_payload(w)
            })?
        } else {
            let len = self.message_len(body, message, &mut [], flag_trailer);
            let mut w = Writer::new(self.room(buf, body, len, flag_trailer)?);
            message.write_payload(&mut w)?;
            w.position()
        };
        let (frame, total) = self.frame(buf, body, plen, flag_trailer)?;
        header(frame)?;
        self.seal(frame, body)?;
        Ok(total)
    }

    /// Writes the payload into `aside`, then places what is sent of it at `start` of `buf`,
    /// stuffed; returns its bytes on the wire.
    #[inline(always)]
    fn place_aside(
        &self,
        buf: &mut [u8],
        aside: &mut [u8],
        body: &Body<'_>,
        start: usize,
        trailer_out: usize,
        write: impl FnOnce(&mut Writer<'_>) -> Result<(), EncodeError>,
    ) -> Result<usize, EncodeError> {
        let mut w = Writer::new(aside);
        write(&mut w)?;
        let sent = self.sent(body, w.written());
        let needed = start
            .saturating_add(self.wire_len(body, sent))
            .saturating_add(trailer_out);
        let available = buf.len();
        let room = payload_room(buf, needed, start, trailer_out)?;
        // `payload_room` found room for the stuffed payload, so for the sent bytes too.
        let kept = room
            .get_mut(..sent.len())
            .ok_or(EncodeError::BufferTooSmall { needed, available })?;
        kept.copy_from_slice(sent);
        match self.stuffing_of(body) {
            Some(s) => s.stuff_in_place(room, sent.len()),
            None => Ok(sent.len()),
        }
    }

    /// Writes the acknowledgement flag and the key of `body` into `frame`, and checks that
    /// the header tells the message's direction.
    #[inline(always)]
    fn write_body(&self, frame: &mut [u8], body: &Body<'_>) -> Result<(), EncodeError> {
        if let Some(ack) = self.ack {
            let value = if matches!(body, Body::Ack) {
                ack.equals
            } else {
                u64::from(ack.equals == 0)
            };
            write_field(frame, ack.flag, value)?;
        }
        if let Body::Command { key, direction, .. } = *body {
            // Matched apart as `each!` does, for the same reason.
            match (self.key, key) {
                ([f0], [v0, ..]) => write_field(frame, *f0, *v0)?,
                ([f0, f1], [v0, v1, ..]) => {
                    write_field(frame, *f0, *v0)?;
                    write_field(frame, *f1, *v1)?;
                }
                (fields, values) => {
                    if values.len() < fields.len() {
                        return Err(EncodeError::ValueOutOfRange);
                    }
                    for (field, value) in fields.iter().zip(values) {
                        write_field(frame, *field, *value)?;
                    }
                }
            }
            if let Some(d) = direction {
                if !self.tells(frame, d) {
                    return Err(EncodeError::ValueOutOfRange);
                }
            }
        }
        Ok(())
    }
}

#[inline(always)]
fn write_field(frame: &mut [u8], field: WordField, value: u64) -> Result<(), EncodeError> {
    field
        .write(frame, value)
        .ok_or(EncodeError::ValueOutOfRange)
}

#[cfg(test)]
mod tests;
