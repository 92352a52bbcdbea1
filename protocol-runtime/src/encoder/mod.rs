//! Writing frames: sealing a frame written in place ([`FrameLayout::seal`]) and the
//! [`Payload`] trait that generated payload structs implement.
//!
//! This module owns the encoding rules of every frame format: which parts of a frame the
//! runtime computes (sync, length, constants, checks, markers) and in which order. The caller
//! (generated code, or the run-time codec) writes the user's header fields and the payload
//! straight into the output buffer, then seals it: no frame is built on the stack and copied.

use crate::decoder::Probe;
use crate::error::EncodeError;
use crate::layout::{EveryKind, FrameLayout, LayoutRef, LengthRule, WordField, all_hold};

mod header;
mod payload;

pub use header::*;
pub use payload::*;

/// The error of a frame whose computed parts do not fit it.
const OUT_OF_RANGE: EncodeError = EncodeError::ValueOutOfRange {
    place: crate::error::Place::NONE,
};

impl FrameLayout<'_> {
    /// Fills in the computed parts of `frame`, whose user header fields and payload are already
    /// written: the sync bytes (with a sync set, the first byte is a header value the caller
    /// wrote, which must be one of the set), the length field (from `frame.len()` by the length rule), the
    /// constants, the header checks, the markers, then the frame checks in order.
    ///
    /// Header items resolve their positions against the header, as when decoding.
    ///
    /// # Errors
    ///
    /// - [`EncodeError::BufferTooSmall`] if `frame` is shorter than `min_len` (or the header),
    /// - [`EncodeError::PayloadTooLarge`] if it is longer than `max_len`,
    /// - [`EncodeError::ValueOutOfRange`] if the first byte is not one of a non-empty sync set,
    ///   the length does not fit its field, the rule is
    ///   [`LengthRule::Fixed`] and the length differs, a constant does not fit its field, or an
    ///   item lies outside the frame (an inconsistent layout).
    ///
    /// ```
    /// use protocol_runtime::layout::{ByteOrder, Check, LengthRule, Pos, WordField};
    /// use protocol_runtime::{Checksum, FrameLayout};
    ///
    /// let hflink = FrameLayout {
    ///     sync: &[0xFF, 0xFF],
    ///     sync_set: &[],
    ///     header_len: 6,
    ///     min_len: 8,
    ///     max_len: 127,
    ///     length: LengthRule::Field {
    ///         field: WordField { at: Pos::Start(4), size: 2, order: ByteOrder::Big, shift: 0, width: 16 },
    ///         adjust: 7,
    ///     },
    ///     constants: &[],
    ///     header_checks: &[],
    ///     frame_checks: &[Check {
    ///         checksum: Checksum::SumMod255,
    ///         from: Pos::Start(0),
    ///         to: Pos::End(1),
    ///         at: Pos::End(1),
    ///         order: ByteOrder::Big,
    ///     }],
    ///     markers: &[],
    ///     escape: None,
    /// };
    /// let mut frame = [0u8; 8];
    /// frame[2] = 0x11; // sender
    /// frame[3] = 0x01; // receiver
    /// frame[6] = 0x00; // command
    /// hflink.seal(&mut frame)?;
    /// assert_eq!(frame, [0xFF, 0xFF, 0x11, 0x01, 0x00, 0x01, 0x00, 0x13]);
    /// assert_eq!(hflink.parse(&frame), Ok(&frame[..]));
    /// # Ok::<(), protocol_runtime::EncodeError>(())
    /// ```
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub fn seal(&self, frame: &mut [u8]) -> Result<(), EncodeError> {
        self.seal_of::<EveryKind>(frame)
    }

    /// [`seal`](Self::seal) on a link of layout type `L`, which compiles only the rule kinds
    /// `L` declares ([`LayoutRef::HEADER_DECIDED`], [`LayoutRef::CRC_CHECKED`]); a layout of
    /// another kind is [`EncodeError::ValueOutOfRange`].
    ///
    /// # Errors
    ///
    /// As [`seal`](Self::seal).
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub(crate) fn seal_of<L: LayoutRef>(&self, frame: &mut [u8]) -> Result<(), EncodeError> {
        let len = frame.len();
        let span = self.header_span();
        let bare = self.length.bare_len() == Some(len) && len >= span;
        let min = self.min_len.max(span);
        if len < min && !bare {
            return Err(EncodeError::BufferTooSmall {
                needed: min,
                available: len,
            });
        }
        if len > self.max_len {
            return Err(EncodeError::PayloadTooLarge {
                len,
                max: self.max_len,
            });
        }
        // `let ... else` rather than `ok_or` and `?` here and below: unoptimised, each of those
        // is a function of `core` per type, linked into every firmware that encodes.
        let Some(header) = frame.get_mut(..span) else {
            return Err(OUT_OF_RANGE);
        };
        // With a sync set, the first byte is a header value the caller wrote: one of the set.
        let lead = match (self.sync_set, header.first()) {
            ([], _) => 0usize,
            (set, Some(first)) if set.contains(first) => 1,
            _ => return Err(OUT_OF_RANGE),
        };
        let Some(sync) = header.get_mut(lead..lead.wrapping_add(self.sync.len())) else {
            return Err(OUT_OF_RANGE);
        };
        sync.copy_from_slice(self.sync);
        match self.length {
            LengthRule::Fixed(fixed) if fixed == len => {}
            LengthRule::Fixed(_) => return Err(OUT_OF_RANGE),
            LengthRule::Field { field, adjust } | LengthRule::FieldOrBare { field, adjust, .. } => {
                // The field holds the length less `adjust`.
                let value = match i64::try_from(len) {
                    Ok(len) => len.checked_sub(adjust),
                    Err(_) => None,
                };
                let written = match value {
                    Some(value) => match u64::try_from(value) {
                        Ok(value) => field.write(header, value),
                        Err(_) => None,
                    },
                    None => None,
                };
                if written.is_none() {
                    return Err(OUT_OF_RANGE);
                }
            }
            LengthRule::Conditional { .. } => {}
        }
        // Each item handled apart (`all_hold`), so that a constant layout folds at any
        // optimisation level.
        let written = all_hold!(self.constants, |c| c.field.write(header, c.value).is_some())
            && all_hold!(self.header_checks, |c| c.store_of::<L>(header).is_some());
        if !written {
            return Err(OUT_OF_RANGE);
        }
        if bare {
            return Ok(());
        }
        let frame = match self.length {
            LengthRule::Conditional {
                field,
                adjust,
                extension,
                ..
            } => {
                if L::HEADER_DECIDED {
                    match self.seal_conditional(frame, field, adjust, extension) {
                        Some(body) => body,
                        None => return Err(OUT_OF_RANGE),
                    }
                } else {
                    return Err(OUT_OF_RANGE);
                }
            }
            _ => frame,
        };
        let written = all_hold!(self.markers, |m| m.write(frame).is_some())
            && all_hold!(self.frame_checks, |c| c.store_of::<L>(frame).is_some());
        if !written {
            return Err(OUT_OF_RANGE);
        }
        Ok(())
    }

    /// [`seal`](Self::seal)'s length for [`LengthRule::Conditional`]: the count (in the wider
    /// field, with the marker in the length field, when it does not fit below the marker),
    /// from the frame's length without the flag trailer, whose flag the caller set. Returns
    /// the frame's body, which the checks and markers resolve against; `None` when the count
    /// does not fit its field.
    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn seal_conditional<'f>(
        &self,
        frame: &'f mut [u8],
        field: WordField,
        adjust: i64,
        extension: Option<crate::layout::LengthExtension>,
    ) -> Option<&'f mut [u8]> {
        let body = self.body_len(frame, frame.len());
        let (count, wide) = Self::conditional_count(adjust, extension, body)?;
        match wide {
            Some(e) => {
                field.write(frame, e.marker)?;
                e.wide.write(frame, count)?;
            }
            None => field.write(frame, count)?,
        }
        frame.get_mut(..body)
    }

    /// Whether `frame` is exactly one valid frame (a debugging aid for encoders).
    pub fn is_valid_frame(&self, frame: &[u8]) -> bool {
        self.probe(frame) == Probe::Frame(frame.len())
    }
}
