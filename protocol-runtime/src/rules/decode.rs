//! Decoding: a checked frame taken apart into its packet's parts.

use super::PacketRules;
use crate::decoder::frame_body;
use crate::error::DecodeError;
use crate::zeros::zero_filled;

impl PacketRules<'_> {
    fn truncated(&self, frame: &[u8]) -> DecodeError {
        DecodeError::Truncated {
            needed: self.header_len,
            available: frame.len(),
        }
    }

    /// The largest acknowledgement data: what the largest frame holds after an
    /// acknowledgement's header and before the trailer.
    #[cfg_attr(not(protocol_opt0), inline(always))]
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
    #[cfg_attr(not(protocol_opt0), inline(always))]
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
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub fn key_value(&self, frame: &[u8], i: usize) -> Result<u64, DecodeError> {
        // A match, not `Option::and_then`: a closure is a function of its own that the
        // optimiser may keep apart (at opt-level "s", once per firmware), and the field's
        // read only folds to a load where the static field is seen.
        match self.key.get(i) {
            Some(f) => f.read(frame).ok_or(self.truncated(frame)),
            None => Err(self.truncated(frame)),
        }
    }

    /// The key of `frame` as one number, its fields' values side by side (the first field in
    /// the high bits): what [`DecodeError::UnknownCommand`] reports.
    ///
    /// # Errors
    ///
    /// [`DecodeError::Truncated`] if the frame ends before a key field.
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub fn key(&self, frame: &[u8]) -> Result<u64, DecodeError> {
        let mut key = 0u64;
        each!(self.key, |f| {
            let v = f.read(frame).ok_or(self.truncated(frame))?;
            key = key.checked_shl(u32::from(f.width)).unwrap_or(0) | v;
        });
        Ok(key)
    }

    /// The direction the header of `frame` tells: the index of the first test that holds. A
    /// field after the payload is read back from the end of the body (the frame without its
    /// flag trailer).
    ///
    /// # Errors
    ///
    /// [`DecodeError::UnknownDirection`] if none holds (a frame too short for a tested field
    /// holds none; its header read says `Truncated` first).
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub fn direction(&self, frame: &[u8]) -> Result<usize, DecodeError> {
        let frame = frame_body(self.layout, frame);
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
    #[cfg_attr(not(protocol_opt0), inline(always))]
    #[must_use]
    pub fn tells(&self, frame: &[u8], d: usize) -> bool {
        let frame = frame_body(self.layout, frame);
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
    /// errors of [`Stuffing::unstuff`](crate::stuffing::Stuffing::unstuff).
    #[cfg_attr(not(protocol_opt0), inline(always))]
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
    #[cfg_attr(not(protocol_opt0), inline(always))]
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
    #[cfg_attr(not(protocol_opt0), inline(always))]
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
