//! Writing frames: sealing a frame written in place ([`FrameLayout::seal`]) and the
//! [`Payload`] trait that generated payload structs implement.
//!
//! This module owns the encoding rules of every frame format: which parts of a frame the
//! runtime computes (sync, length, constants, checks, markers) and in which order. The caller
//! (generated code, or the run-time codec) writes the user's header fields and the payload
//! straight into the output buffer, then seals it: no frame is built on the stack and copied.

use crate::decoder::Probe;
use crate::error::{DecodeError, EncodeError};
use crate::layout::{EveryKind, FrameLayout, LayoutRef, LengthRule, WordField, all_hold};
use crate::wire::{Reader, Writer};

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

/// A value with a fixed wire form: generated payload structs implement it (usually with
/// `#[derive(Payload)]`).
///
/// ```
/// use protocol_runtime::{DecodeError, EncodeError, Payload, Reader, Writer};
///
/// #[derive(Debug, PartialEq)]
/// struct Speed {
///     x: f32,
///     turn: i16,
/// }
///
/// impl Payload for Speed {
///     const SIZE: usize = 6;
///     fn write(&self, w: &mut Writer<'_>) -> Result<(), EncodeError> {
///         w.put_f32_le(self.x)?;
///         w.put_i16_be(self.turn)
///     }
///     fn read(r: &mut Reader<'_>) -> Result<Self, DecodeError> {
///         Ok(Speed { x: r.f32_le()?, turn: r.i16_be()? })
///     }
/// }
///
/// let mut buf = [0u8; 8];
/// let n = Speed { x: 0.5, turn: -3 }.to_bytes(&mut buf)?;
/// assert_eq!(n, Speed::SIZE);
/// assert_eq!(Speed::from_bytes(&buf[..n])?, Speed { x: 0.5, turn: -3 });
/// assert_eq!(
///     Speed::from_bytes(&buf),
///     Err(DecodeError::PayloadLength { expected: 6, actual: 8 })
/// );
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub trait Payload: Sized {
    /// Size on the wire in bytes; for a value that ends with variable bytes, the largest size.
    const SIZE: usize;

    /// Smallest size on the wire: [`SIZE`](Self::SIZE) unless the value ends with variable
    /// bytes.
    const MIN_SIZE: usize = Self::SIZE;

    /// Whether [`read`](Self::read) can fail only for want of bytes, and every value has
    /// exactly [`SIZE`](Self::SIZE) bytes (no enums, clamped values or variable parts, also in
    /// nested values). Then [`from_bytes`](Self::from_bytes) checks the length first, which
    /// gives the same error the reading would and lets the compiler drop every per-field
    /// bounds check (smaller firmware). Generated code sets it; `false` is always correct.
    #[doc(hidden)]
    const READ_NEEDS_ONLY_BYTES: bool = false;

    /// Size of this value on the wire.
    fn wire_len(&self) -> usize {
        Self::SIZE
    }

    /// Writes the value at the writer's position.
    ///
    /// # Errors
    ///
    /// [`EncodeError::BufferTooSmall`] if the buffer is too short;
    /// [`EncodeError::ValueOutOfRange`] if a field's value does not fit its wire form.
    fn write(&self, w: &mut Writer<'_>) -> Result<(), EncodeError>;

    /// Reads a value at the reader's position.
    ///
    /// # Errors
    ///
    /// [`DecodeError::Truncated`] if the input is too short;
    /// [`DecodeError::InvalidEnum`] if a field holds no variant of its enum.
    fn read(r: &mut Reader<'_>) -> Result<Self, DecodeError>;

    /// Decodes a value from exactly `bytes`.
    ///
    /// # Errors
    ///
    /// [`DecodeError::PayloadLength`] if `bytes` is shorter than the value (then `expected` is
    /// [`MIN_SIZE`](Self::MIN_SIZE)) or longer (then `expected` is the bytes read); the errors of
    /// [`read`](Self::read) otherwise.
    fn from_bytes(bytes: &[u8]) -> Result<Self, DecodeError> {
        if Self::READ_NEEDS_ONLY_BYTES && bytes.len() != Self::SIZE {
            // What reading would give: a truncation, or bytes left once `SIZE` are read.
            return Err(DecodeError::PayloadLength {
                expected: Self::SIZE,
                actual: bytes.len(),
            });
        }
        Self::read_exactly(bytes)
    }

    /// [`from_bytes`](Self::from_bytes) without the length checked first: field by field, then
    /// no byte may be left. (The tests check the shortcut against it.)
    ///
    /// # Errors
    ///
    /// As [`from_bytes`](Self::from_bytes).
    #[doc(hidden)]
    fn read_exactly(bytes: &[u8]) -> Result<Self, DecodeError> {
        // Matched, not `?` and `map_err`: unoptimised, each of those is a function of `core`
        // instantiated for every payload type, where the error is decided once, in
        // `whole_read_error`.
        let mut r = Reader::new(bytes);
        match Self::read(&mut r) {
            Ok(value) => match r.finish() {
                Ok(()) => Ok(value),
                Err(e) => Err(e),
            },
            Err(e) => Err(whole_read_error(e, Self::MIN_SIZE, bytes.len())),
        }
    }

    /// Encodes the value at the start of `buf` and returns the bytes written.
    ///
    /// # Errors
    ///
    /// The errors of [`write`](Self::write).
    fn to_bytes(&self, buf: &mut [u8]) -> Result<usize, EncodeError> {
        let mut w = Writer::new(buf);
        self.write(&mut w)?;
        Ok(w.position())
    }
}

/// The error of reading a whole payload of `actual` bytes whose read failed with `e`: a
/// truncation is a payload shorter than `min_size`, any other error stays as it is.
fn whole_read_error(e: DecodeError, min_size: usize, actual: usize) -> DecodeError {
    match e {
        DecodeError::Truncated { .. } => DecodeError::PayloadLength {
            expected: min_size,
            actual,
        },
        other => other,
    }
}

/// An operation on the payload of a message, whatever the payload's type. A generated message
/// enum opens itself in one place (`visit_payload`, one arm per variant) and hands the variant's
/// command (of type `C`) and payload to a visitor: [`CommandOf`] takes the command, [`WireLen`]
/// measures the payload, [`WritePayload`] writes it. Each call is monomorphised, so it compiles
/// to the same code as a match per operation.
pub trait PayloadVisitor<C> {
    /// What the operation gives.
    type Output;
    /// Applies the operation to the message of `command` carrying `payload`.
    fn visit<P: Payload>(self, command: C, payload: &P) -> Self::Output;
}

/// A generated message enum (`Message`, `Request`, `Response`): the one place that opens it,
/// [`visit_payload`](Self::visit_payload), and the payload's size and encoding through it.
///
/// Generated code implements it; a caller that measures or writes a payload by itself names it
/// (`use protocol_kit::MessagePayload;`). The message's command is an inherent method, `command()`,
/// of each generated enum.
pub trait MessagePayload {
    /// The command a message names: the spec's `Command`, or `Option<Command>` when some
    /// messages carry none (acknowledgements, a direction's struct in place of a command).
    type Command: CommandName;

    /// Hands the command and the payload to `v` (`&()` when the command carries none).
    fn visit_payload<V: PayloadVisitor<Self::Command>>(&self, v: V) -> V::Output;

    /// Bytes of the payload on the wire.
    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn payload_len(&self) -> usize {
        self.visit_payload(WireLen)
    }

    /// Writes the payload at the writer's position.
    ///
    /// # Errors
    ///
    /// [`EncodeError::BufferTooSmall`] if `w` has too little room,
    /// [`EncodeError::ValueOutOfRange`] if a field's value does not fit its wire form.
    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn write_payload(&self, w: &mut Writer<'_>) -> Result<(), EncodeError> {
        self.visit_payload(WritePayload(w))
    }
}

/// A command's name in the spec, for the place of an encode error ([`WritePayload`] names the
/// command of a payload that fails to write). Generated `Command` enums implement it.
pub trait CommandName {
    /// The name; empty for a message without command.
    fn command_name(&self) -> &'static str;
}

/// A message that may carry no command (an acknowledgement) has no name then.
///
/// ```
/// use protocol_runtime::encoder::CommandName;
///
/// struct Set;
/// impl CommandName for Set {
///     fn command_name(&self) -> &'static str {
///         "SET"
///     }
/// }
/// assert_eq!(Some(Set).command_name(), "SET");
/// assert_eq!(None::<Set>.command_name(), "");
/// ```
impl<C: CommandName> CommandName for Option<C> {
    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn command_name(&self) -> &'static str {
        self.as_ref().map_or("", CommandName::command_name)
    }
}

/// The message's command.
#[derive(Debug, Clone, Copy, Default)]
pub struct CommandOf;

impl<C> PayloadVisitor<C> for CommandOf {
    type Output = C;
    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn visit<P: Payload>(self, command: C, _: &P) -> C {
        command
    }
}

/// The payload's size on the wire ([`Payload::wire_len`]).
#[derive(Debug, Clone, Copy, Default)]
pub struct WireLen;

impl<C> PayloadVisitor<C> for WireLen {
    type Output = usize;
    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn visit<P: Payload>(self, _: C, payload: &P) -> usize {
        payload.wire_len()
    }
}

/// Writing the payload at the writer's position ([`Payload::write`]); an error names the
/// command, as a decode error does (the field's code has named the field).
#[derive(Debug)]
pub struct WritePayload<'w, 'b>(pub &'w mut Writer<'b>);

impl<C: CommandName> PayloadVisitor<C> for WritePayload<'_, '_> {
    type Output = Result<(), EncodeError>;
    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn visit<P: Payload>(self, command: C, payload: &P) -> Result<(), EncodeError> {
        // Matched, not `map_err`: unoptimised, a closure and a `map_err` per payload type.
        match payload.write(self.0) {
            Ok(()) => Ok(()),
            Err(e) => Err(e.in_command(command.command_name())),
        }
    }
}

/// The error of a command without payload that arrived with `bytes`.
///
/// ```
/// use protocol_runtime::{DecodeError, encoder::expected_empty};
/// assert_eq!(expected_empty(&[1]), DecodeError::PayloadLength { expected: 0, actual: 1 });
/// ```
#[cfg_attr(not(protocol_opt0), inline(always))]
pub fn expected_empty(bytes: &[u8]) -> DecodeError {
    DecodeError::PayloadLength {
        expected: 0,
        actual: bytes.len(),
    }
}

/// The command of a frame of an empty direction (MSP's error replies: the header and no
/// payload, whatever the command), read from its payload `bytes`, which must be empty.
///
/// # Errors
///
/// [`DecodeError::PayloadLength`] when `bytes` is not empty.
///
/// ```
/// use protocol_runtime::{DecodeError, encoder::read_empty};
/// assert_eq!(read_empty(7u8, &[]), Ok(7));
/// assert_eq!(read_empty(7u8, &[0]), Err(DecodeError::PayloadLength { expected: 0, actual: 1 }));
/// ```
#[cfg_attr(not(protocol_opt0), inline(always))]
pub fn read_empty<C>(command: C, bytes: &[u8]) -> Result<C, DecodeError> {
    if bytes.is_empty() {
        Ok(command)
    } else {
        Err(expected_empty(bytes))
    }
}

/// The payload read from exactly `bytes` ([`Payload::from_bytes`] as a function, so that a
/// message enum's `read_payload` arm infers the type from the variant it fills).
///
/// # Errors
///
/// The errors of [`Payload::from_bytes`].
#[cfg_attr(not(protocol_opt0), inline(always))]
pub fn read_payload<P: Payload>(bytes: &[u8]) -> Result<P, DecodeError> {
    P::from_bytes(bytes)
}

/// A payload struct that one command alone carries: its command, known from the type.
///
/// Generated code implements it for every such struct, so that a packet type decodes a frame
/// as one command's struct and encodes one (`Packet::from_frame_as::<Heartbeat>`,
/// `Packet::encode_as`): a program that handles a few commands of a large spec links the
/// readers and writers of those alone, where `Packet::from_frame` and `Packet::encode` match
/// every command and so link each one's.
pub trait CommandPayload: Payload {
    /// The spec's `Command`.
    type Command: CommandName + Copy;
    /// The command that carries this struct.
    const COMMAND: Self::Command;
}

/// One command's struct as a message ([`MessagePayload`]): its command from its type, so
/// that encoding it opens no `match` over the spec's commands.
#[derive(Debug, Clone, Copy)]
pub struct CommandMessage<'p, P>(pub &'p P);

impl<P: CommandPayload> MessagePayload for CommandMessage<'_, P> {
    type Command = P::Command;
    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn visit_payload<V: PayloadVisitor<P::Command>>(&self, v: V) -> V::Output {
        v.visit(P::COMMAND, self.0)
    }
}

/// Reads a header value of `frame` at `field`; a frame too short for it is
/// [`DecodeError::Truncated`], needing the `header_len` bytes every frame of its format has.
///
/// # Errors
///
/// [`DecodeError::Truncated`] if `frame` ends before the field.
#[cfg_attr(not(protocol_opt0), inline(always))]
pub fn header_value(frame: &[u8], field: WordField, header_len: usize) -> Result<u64, DecodeError> {
    field.read(frame).ok_or(DecodeError::Truncated {
        needed: header_len,
        available: frame.len(),
    })
}

/// The error of a frame whose dispatch key `key` names no command.
#[cfg_attr(not(protocol_opt0), inline(always))]
#[must_use]
pub const fn unknown_command(key: u64) -> DecodeError {
    DecodeError::UnknownCommand { key }
}

/// The payload of a checked frame: its bytes between the `header_len` bytes of its header and
/// the `trailer_len` bytes of its trailer.
///
/// # Errors
///
/// [`DecodeError::Truncated`] if `frame` is shorter than its header and trailer.
#[cfg_attr(not(protocol_opt0), inline(always))]
pub fn payload_of(
    frame: &[u8],
    header_len: usize,
    trailer_len: usize,
) -> Result<&[u8], DecodeError> {
    frame
        .get(header_len..frame.len().saturating_sub(trailer_len))
        .ok_or(DecodeError::Truncated {
            needed: header_len.saturating_add(trailer_len),
            available: frame.len(),
        })
}

/// Where an encoder writes a payload into `buf`: from `start` up to the `trailer_len` bytes the
/// trailer needs at the end, once `buf` is known to hold the `needed` bytes of the frame.
///
/// # Errors
///
/// [`EncodeError::BufferTooSmall`] if `buf` is shorter than `needed` or than `start` and the
/// trailer.
#[cfg_attr(not(protocol_opt0), inline(always))]
pub fn payload_room(
    buf: &mut [u8],
    needed: usize,
    start: usize,
    trailer_len: usize,
) -> Result<&mut [u8], EncodeError> {
    let available = buf.len();
    if available < needed {
        return Err(EncodeError::BufferTooSmall { needed, available });
    }
    buf.get_mut(start..available.saturating_sub(trailer_len))
        .ok_or(EncodeError::BufferTooSmall { needed, available })
}

/// The first `total` bytes of `buf`: the frame an encoder seals.
///
/// # Errors
///
/// [`EncodeError::BufferTooSmall`] if `buf` is shorter than `total`.
#[cfg_attr(not(protocol_opt0), inline(always))]
pub fn frame_room(buf: &mut [u8], total: usize) -> Result<&mut [u8], EncodeError> {
    let available = buf.len();
    buf.get_mut(..total).ok_or(EncodeError::BufferTooSmall {
        needed: total,
        available,
    })
}

/// Writes a header value into `frame` at `field`.
///
/// # Errors
///
/// [`EncodeError::ValueOutOfRange`] if the value does not fit the field or the field lies
/// outside the frame.
#[cfg_attr(not(protocol_opt0), inline(always))]
pub fn write_header(frame: &mut [u8], field: WordField, value: u64) -> Result<(), EncodeError> {
    field
        .write(frame, value)
        .ok_or(EncodeError::ValueOutOfRange {
            place: crate::error::Place::NONE,
        })
}

/// Refuses a header value of another direction's frames: a frame of a direction without that
/// field (Sensirion SHDLC's state byte, in a command) has no place for it, so it is `None`
/// there; a value would not decode back.
///
/// # Errors
///
/// [`EncodeError::ValueOutOfRange`] when `value` is `Some`.
///
/// # Examples
///
/// ```
/// use protocol_runtime::EncodeError;
/// use protocol_runtime::encoder::absent_header;
/// assert_eq!(absent_header::<u8>(None), Ok(()));
/// assert!(matches!(absent_header(Some(3u8)), Err(EncodeError::ValueOutOfRange { .. })));
/// ```
#[inline]
pub fn absent_header<T>(value: Option<T>) -> Result<(), EncodeError> {
    match value {
        None => Ok(()),
        Some(_) => Err(EncodeError::ValueOutOfRange {
            place: crate::error::Place::NONE,
        }),
    }
}

/// The value of a header field of one direction, in a frame of that direction: every such
/// frame has it, so a `None` would not decode back.
///
/// # Errors
///
/// [`EncodeError::ValueOutOfRange`] when `value` is `None`.
///
/// # Examples
///
/// ```
/// use protocol_runtime::EncodeError;
/// use protocol_runtime::encoder::present_header;
/// assert_eq!(present_header(Some(3u8)), Ok(3));
/// assert!(matches!(present_header::<u8>(None), Err(EncodeError::ValueOutOfRange { .. })));
/// ```
#[inline]
pub fn present_header<T>(value: Option<T>) -> Result<T, EncodeError> {
    value.ok_or(EncodeError::ValueOutOfRange {
        place: crate::error::Place::NONE,
    })
}

/// No payload: a command that carries nothing.
impl Payload for () {
    const SIZE: usize = 0;
    const READ_NEEDS_ONLY_BYTES: bool = true;

    #[inline]
    fn write(&self, _: &mut Writer<'_>) -> Result<(), EncodeError> {
        Ok(())
    }

    #[inline]
    fn read(_: &mut Reader<'_>) -> Result<Self, DecodeError> {
        Ok(())
    }
}

/// Raw bytes.
impl<const N: usize> Payload for [u8; N] {
    const SIZE: usize = N;
    const READ_NEEDS_ONLY_BYTES: bool = true;

    #[inline]
    fn write(&self, w: &mut Writer<'_>) -> Result<(), EncodeError> {
        w.put_array(*self)
    }

    #[inline]
    fn read(r: &mut Reader<'_>) -> Result<Self, DecodeError> {
        r.bytes()
    }
}
