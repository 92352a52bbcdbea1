//! Encoding: a frame assembled from a body, a payload and header values.

use super::{Body, PacketRules};
use crate::encoder::{MessagePayload, frame_room, payload_room};
use crate::error::EncodeError;
use crate::layout::{EveryKind, LayoutRef, WordField};
use crate::stuffing::Stuffing;
use crate::wire::Writer;
use crate::zeros::trimmed_len;

/// Encoding.
impl PacketRules<'_> {
    /// Where the payload of `body` starts, before a wider length moves it.
    #[cfg_attr(not(protocol_opt0), inline(always))]
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
    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn stuffing_of(&self, body: &Body<'_>) -> Option<Stuffing<'_>> {
        self.stuffing.filter(|_| !matches!(body, Body::Ack))
    }

    /// True when a command's payload is written aside before it is placed in the frame (its
    /// size on the wire is known only once it is written: trailing zeros trimmed, bytes
    /// stuffed, or fields after the carried ones cut).
    #[cfg_attr(not(protocol_opt0), inline(always))]
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
    #[cfg_attr(not(protocol_opt0), inline(always))]
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
    #[cfg_attr(not(protocol_opt0), inline(always))]
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
    #[cfg_attr(not(protocol_opt0), inline(always))]
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
    #[cfg_attr(not(protocol_opt0), inline(always))]
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
    /// `write`, `header` and [`FrameLayout::seal`](crate::layout::FrameLayout::seal).
    #[cfg_attr(not(protocol_opt0), inline(always))]
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
        self.escape(buf, total)
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
    #[cfg_attr(not(protocol_opt0), inline(always))]
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
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub fn frame<'b>(
        &self,
        buf: &'b mut [u8],
        body: &Body<'_>,
        plen: usize,
        flag_trailer: usize,
    ) -> Result<(&'b mut [u8], usize), EncodeError> {
        self.frame_of::<EveryKind>(buf, body, plen, flag_trailer)
    }

    /// [`frame`](Self::frame) on a link of layout type `L`: a wider length only where `L`
    /// declares lengths decided by header values ([`LayoutRef::HEADER_DECIDED`]).
    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn frame_of<'b, L: LayoutRef>(
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
        // The constant tested first and alone, so that an unoptimised build folds it.
        let start = if L::HEADER_DECIDED && self.layout.extension_for(short) != 0 {
            self.layout.place_payload(buf, start, plen, trailer)?
        } else {
            start
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
    /// does not tell the message's direction; the errors of [`FrameLayout::seal`](crate::layout::FrameLayout::seal).
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub fn seal(&self, frame: &mut [u8], body: &Body<'_>) -> Result<(), EncodeError> {
        self.seal_of::<EveryKind>(frame, body)
    }

    /// [`seal`](Self::seal) on a link of layout type `L` (`FrameLayout::seal_of`).
    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn seal_of<L: LayoutRef>(&self, frame: &mut [u8], body: &Body<'_>) -> Result<(), EncodeError> {
        self.write_body(frame, body)?;
        self.layout.seal_of::<L>(frame)
    }

    /// Escapes the sealed frame `buf[..len]` in place where the format escapes its frames
    /// ([`FrameLayout::escape`](crate::FrameLayout::escape)); returns its length on the wire.
    ///
    /// # Errors
    ///
    /// [`EncodeError::BufferTooSmall`] if `buf` has no room for the escaped frame.
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub fn escape(&self, buf: &mut [u8], len: usize) -> Result<usize, EncodeError> {
        self.escape_of::<EveryKind>(buf, len)
    }

    /// [`escape`](Self::escape) on a link of layout type `L`: nothing to escape where `L`
    /// declares no escaping ([`LayoutRef::ESCAPED`]).
    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn escape_of<L: LayoutRef>(&self, buf: &mut [u8], len: usize) -> Result<usize, EncodeError> {
        // A test of the constant alone, which an unoptimised build folds (not a match guard).
        if L::ESCAPED {
            return match self.layout.escape {
                Some(escape) => escape.escape_in_place(buf, len),
                None => Ok(len),
            };
        }
        match self.layout.escape {
            Some(_) => Err(EncodeError::ValueOutOfRange {
                place: crate::error::Place::NONE,
            }),
            None => Ok(len),
        }
    }

    /// The length of the frame that carries `message` as `body`, with `flag_trailer` bytes of
    /// flag trailer: [`frame_len`](Self::frame_len) of the message's payload as it goes on the
    /// wire (written into `aside` and measured where the rules write aside; `aside` is unused
    /// otherwise and may be empty).
    #[cfg_attr(not(protocol_opt0), inline(always))]
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
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub fn encode_message<M: MessagePayload>(
        &self,
        buf: &mut [u8],
        aside: &mut [u8],
        body: &Body<'_>,
        message: &M,
        flag_trailer: usize,
        header: impl FnOnce(&mut [u8]) -> Result<(), EncodeError>,
    ) -> Result<usize, EncodeError> {
        self.encode_message_of::<EveryKind, M>(buf, aside, body, message, flag_trailer, header)
    }

    /// [`encode_message`](Self::encode_message) on a link of layout type `L` (generated code
    /// names its own): only the rule kinds `L` declares are compiled (`LayoutRef::ESCAPED`,
    /// `HEADER_DECIDED`, `CRC_CHECKED`), which an unoptimised build does not find by itself.
    ///
    /// # Errors
    ///
    /// The errors of [`assemble`](Self::assemble); [`EncodeError::ValueOutOfRange`] for a
    /// layout of a kind `L` does not declare.
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub fn encode_message_of<L: LayoutRef, M: MessagePayload>(
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
        let (frame, total) = self.frame_of::<L>(buf, body, plen, flag_trailer)?;
        header(frame)?;
        self.seal_of::<L>(frame, body)?;
        self.escape_of::<L>(buf, total)
    }

    /// Writes the payload into `aside`, then places what is sent of it at `start` of `buf`,
    /// stuffed; returns its bytes on the wire.
    #[cfg_attr(not(protocol_opt0), inline(always))]
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
    #[cfg_attr(not(protocol_opt0), inline(always))]
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
                        return Err(EncodeError::ValueOutOfRange {
                            place: crate::error::Place::NONE,
                        });
                    }
                    for (field, value) in fields.iter().zip(values) {
                        write_field(frame, *field, *value)?;
                    }
                }
            }
            if let Some(d) = direction {
                if !self.tells(frame, d) {
                    return Err(EncodeError::ValueOutOfRange {
                        place: crate::error::Place::NONE,
                    });
                }
            }
        }
        Ok(())
    }
}

#[cfg_attr(not(protocol_opt0), inline(always))]
fn write_field(frame: &mut [u8], field: WordField, value: u64) -> Result<(), EncodeError> {
    field
        .write(frame, value)
        .ok_or(EncodeError::ValueOutOfRange {
            place: crate::error::Place::NONE,
        })
}
