//! Frames whose parts depend on header values ([`LengthRule::Conditional`]): a wider length
//! that a marker value of the length field announces (MSP v1 jumbo frames), and bytes after
//! the checks that a header flag announces (the MAVLink 2 signature).
//!
//! This module owns how such a frame's total length, the length of its body (the frame without
//! the flag trailer, against which checks and markers resolve) and the place of its payload
//! follow from its header, for the engine ([`measure`]), for encoders
//! ([`FrameLayout::extension_for`]) and for the code that reads a payload
//! ([`FrameLayout::extension_len`], [`FrameLayout::flag_trailer_len`]).

use super::{Probe, Reject};
use crate::layout::{FlagTrailer, FrameLayout, LengthExtension, LengthRule, WordField};

/// Bytes of the flag trailer present in the frame whose header starts `header` (0 without
/// one, or when its flag is clear or lies past `header`).
#[cfg_attr(not(protocol_opt0), inline(always))]
fn trailer_len(trailer: Option<FlagTrailer>, header: &[u8]) -> usize {
    match trailer {
        Some(t) if t.flag.read(header).is_some_and(|flag| flag != 0) => t.len,
        _ => 0,
    }
}

/// One past the last byte of `field` (a [`Pos::Start`](crate::layout::Pos::Start) position).
#[cfg_attr(not(protocol_opt0), inline(always))]
fn end_of(field: WordField) -> usize {
    field
        .at
        .resolve(usize::MAX)
        .map_or(usize::MAX, |at| at.saturating_add(usize::from(field.size)))
}

/// The total length and the body length (without the flag trailer) of the candidate `bytes`
/// under [`LengthRule::Conditional`], or the engine's verdict when they are not known yet or
/// impossible: [`Probe::Need`] for the bytes of a wider length, [`Reject::BadLength`] as soon
/// as the bytes that decide it are in (a marker form whose smallest frame exceeds `limit` is
/// rejected before its wider length is awaited). `header` is the candidate's first
/// [`FrameLayout::header_span`] bytes, `bytes` all it has.
#[cfg_attr(not(protocol_opt0), inline(always))]
pub(super) fn measure(
    field: WordField,
    adjust: i64,
    extension: Option<LengthExtension>,
    trailer: Option<FlagTrailer>,
    header: &[u8],
    bytes: &[u8],
    limit: usize,
) -> Result<(usize, usize), Probe> {
    const BAD: Probe = Probe::Reject(Reject::BadLength);
    let count = field.read(header).ok_or(BAD)?;
    let (count, extra) = match extension {
        Some(e) if count == e.marker => {
            // The smallest frame of the marker form: a count of `marker`.
            let smallest = total_of(e.marker, adjust, e.len).ok_or(BAD)?;
            let needed = end_of(e.wide);
            if smallest > limit || needed > limit {
                return Err(BAD);
            }
            let wide = bytes.get(..needed).ok_or(Probe::Need(needed))?;
            let count = e.wide.read(wide).ok_or(BAD)?;
            if count < e.marker {
                return Err(BAD);
            }
            (count, e.len)
        }
        // Counts from the marker up are the marker form's.
        Some(e) if count > e.marker => return Err(BAD),
        _ => (count, 0),
    };
    let body = total_of(count, adjust, extra).ok_or(BAD)?;
    let total = body.checked_add(trailer_len(trailer, header)).ok_or(BAD)?;
    Ok((total, body))
}

/// `count + adjust + extra`, or `None` if negative or too large.
#[cfg_attr(not(protocol_opt0), inline(always))]
fn total_of(count: u64, adjust: i64, extra: usize) -> Option<usize> {
    let count = i64::try_from(count).ok()?;
    let total = usize::try_from(count.checked_add(adjust)?).ok()?;
    total.checked_add(extra)
}

impl FrameLayout<'_> {
    /// Bytes a wider length adds before the payload of `frame` (which starts with at least its
    /// header): the extension's bytes when its length field holds the marker, else 0.
    ///
    /// ```
    /// # use protocol_runtime::layout::*;
    /// // MSP v1: `$M` direction size command [size as u16le when size is 255] payload xor.
    /// let msp = FrameLayout {
    ///     sync: b"$M", sync_set: &[], header_len: 5, min_len: 6, max_len: 1000,
    ///     length: LengthRule::Conditional {
    ///         field: WordField::le(3, 1),
    ///         adjust: 6,
    ///         extension: Some(LengthExtension { marker: 255, wide: WordField::le(5, 2), len: 2 }),
    ///         trailer: None,
    ///     },
    ///     constants: &[], header_checks: &[], frame_checks: &[], markers: &[], escape: None,
    /// };
    /// assert_eq!(msp.extension_len(b"$M>\x03\x01"), 0);
    /// assert_eq!(msp.extension_len(b"$M>\xff\x74\x2c\x01"), 2);
    /// // The short form of a frame: 6 bytes of framing and the payload.
    /// assert_eq!(msp.extension_for(6 + 254), 0);
    /// assert_eq!(msp.extension_for(6 + 255), 2);
    /// ```
    #[cfg_attr(not(protocol_opt0), inline(always))]
    #[must_use]
    pub fn extension_len(&self, frame: &[u8]) -> usize {
        match self.length {
            LengthRule::Conditional {
                field,
                extension: Some(e),
                ..
            } if field.read(frame) == Some(e.marker) => e.len,
            _ => 0,
        }
    }

    /// Bytes of the flag trailer at the end of `frame` (which starts with at least its header):
    /// its length when its flag is set, else 0.
    #[cfg_attr(not(protocol_opt0), inline(always))]
    #[must_use]
    pub fn flag_trailer_len(&self, frame: &[u8]) -> usize {
        match self.length {
            LengthRule::Conditional { trailer, .. } => trailer_len(trailer, frame),
            _ => 0,
        }
    }

    /// For an encoder: the bytes a wider length adds before the payload of a frame of `len`
    /// bytes in its short form (without the wider length and a flag trailer): the extension's
    /// bytes when the count of the length field does not fit below the marker, else 0.
    #[cfg_attr(not(protocol_opt0), inline(always))]
    #[must_use]
    pub fn extension_for(&self, len: usize) -> usize {
        match self.length {
            LengthRule::Conditional {
                adjust,
                extension: Some(e),
                ..
            } => {
                let count = i64::try_from(len).map_or(i64::MAX, |l| l.saturating_sub(adjust));
                if u64::try_from(count).is_ok_and(|c| c >= e.marker) {
                    e.len
                } else {
                    0
                }
            }
            _ => 0,
        }
    }

    /// For an encoder that wrote a `plen`-byte payload at `start` of `buf`, with `trailer_len`
    /// bytes of trailer to follow: moves the payload behind the wider length when the frame
    /// needs one ([`extension_for`](Self::extension_for)). Returns where the payload starts.
    ///
    /// # Errors
    ///
    /// [`EncodeError::BufferTooSmall`](crate::EncodeError::BufferTooSmall) if `buf` has no
    /// room for the moved payload and the trailer.
    #[inline]
    pub fn place_payload(
        &self,
        buf: &mut [u8],
        start: usize,
        plen: usize,
        trailer_len: usize,
    ) -> Result<usize, crate::EncodeError> {
        let short = start.saturating_add(plen).saturating_add(trailer_len);
        let extra = self.extension_for(short);
        if extra == 0 {
            return Ok(start);
        }
        let needed = short.saturating_add(extra);
        if buf.len() < needed {
            return Err(crate::EncodeError::BufferTooSmall {
                needed,
                available: buf.len(),
            });
        }
        let end = start.saturating_add(plen);
        buf.copy_within(start..end, start.saturating_add(extra));
        Ok(start.saturating_add(extra))
    }

    /// The count written into the length field of a frame of `len` bytes under a conditional
    /// rule, and whether it goes into the wider field; `None` if no frame has that length.
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub(crate) fn conditional_count(
        adjust: i64,
        extension: Option<LengthExtension>,
        body: usize,
    ) -> Option<(u64, Option<LengthExtension>)> {
        let count = u64::try_from(i64::try_from(body).ok()?.checked_sub(adjust)?).ok()?;
        match extension {
            Some(e) if count >= e.marker => {
                let wide = count.checked_sub(e.len as u64)?;
                (wide >= e.marker).then_some((wide, Some(e)))
            }
            _ => Some((count, None)),
        }
    }

    /// The body length (without the flag trailer) of a frame of `len` bytes whose header is
    /// `header`.
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub(crate) fn body_len(&self, header: &[u8], len: usize) -> usize {
        len.saturating_sub(self.flag_trailer_len(header))
    }
}

/// The flag trailer of a checked `frame` of `layout`: its last `N` bytes when its flag is set
/// (and the trailer is `N` bytes long), else `None`.
///
/// ```
/// # use protocol_runtime::layout::*;
/// # use protocol_runtime::decoder::flag_trailer;
/// let signed = FrameLayout {
///     sync: &[0xFD], sync_set: &[], header_len: 3, min_len: 3, max_len: 300,
///     length: LengthRule::Conditional {
///         field: WordField::le(1, 1),
///         adjust: 3,
///         extension: None,
///         trailer: Some(FlagTrailer { flag: WordField::le(2, 1).bits(0, 1), len: 2 }),
///     },
///     constants: &[], header_checks: &[], frame_checks: &[], markers: &[], escape: None,
/// };
/// assert_eq!(flag_trailer::<2>(&signed, &[0xFD, 1, 1, 0xAA, 7, 8]), Some([7, 8]));
/// assert_eq!(flag_trailer::<2>(&signed, &[0xFD, 1, 0, 0xAA]), None);
/// ```
#[cfg_attr(not(protocol_opt0), inline(always))]
#[must_use]
pub fn flag_trailer<const N: usize>(layout: &FrameLayout<'_>, frame: &[u8]) -> Option<[u8; N]> {
    if layout.flag_trailer_len(frame) != N {
        return None;
    }
    frame.last_chunk::<N>().copied()
}

/// The body of a checked `frame` of `layout`: the frame without its flag trailer, where the
/// header values after the payload lie at their distance from the end (as the checks and
/// trailers do). Without a flag trailer, or with its flag clear, the whole frame.
///
/// ```
/// # use protocol_runtime::layout::*;
/// # use protocol_runtime::decoder::frame_body;
/// let signed = FrameLayout {
///     sync: &[0xFD], sync_set: &[], header_len: 3, min_len: 4, max_len: 300,
///     length: LengthRule::Conditional {
///         field: WordField::le(1, 1),
///         adjust: 4,
///         extension: None,
///         trailer: Some(FlagTrailer { flag: WordField::le(2, 1).bits(0, 1), len: 2 }),
///     },
///     constants: &[], header_checks: &[], frame_checks: &[], markers: &[], escape: None,
/// };
/// // A field after the one payload byte, then the two flagged bytes.
/// assert_eq!(frame_body(&signed, &[0xFD, 1, 1, 0xAA, 0x33, 7, 8]), &[0xFD, 1, 1, 0xAA, 0x33]);
/// assert_eq!(frame_body(&signed, &[0xFD, 1, 0, 0xAA, 0x33]), &[0xFD, 1, 0, 0xAA, 0x33]);
/// ```
#[inline(always)]
#[must_use]
pub fn frame_body<'f>(layout: &FrameLayout<'_>, frame: &'f [u8]) -> &'f [u8] {
    let len = layout.body_len(frame, frame.len());
    frame.get(..len).unwrap_or(frame)
}

/// [`frame_body`] of a frame being assembled, whose flag is written.
#[inline(always)]
#[must_use]
pub fn frame_body_mut<'f>(layout: &FrameLayout<'_>, frame: &'f mut [u8]) -> &'f mut [u8] {
    let len = layout.body_len(frame, frame.len());
    if len < frame.len() {
        frame.split_at_mut(len).0
    } else {
        frame
    }
}

/// Writes the flag trailer `bytes`, if any, into the last `N` bytes of `frame` (the caller
/// sets its flag and counts the bytes in the frame's length).
///
/// # Errors
///
/// [`EncodeError::BufferTooSmall`](crate::EncodeError::BufferTooSmall) if `frame` is shorter
/// than `N` bytes.
#[cfg_attr(not(protocol_opt0), inline(always))]
pub fn write_flag_trailer<const N: usize>(
    frame: &mut [u8],
    bytes: Option<&[u8; N]>,
) -> Result<(), crate::EncodeError> {
    let Some(bytes) = bytes else {
        return Ok(());
    };
    let available = frame.len();
    let at = available
        .checked_sub(N)
        .ok_or(crate::EncodeError::BufferTooSmall {
            needed: N,
            available,
        })?;
    if let Some(dst) = frame.get_mut(at..) {
        dst.copy_from_slice(bytes);
    }
    Ok(())
}
