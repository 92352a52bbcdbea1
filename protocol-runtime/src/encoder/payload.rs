//! The [`Payload`] trait that generated payload structs implement, and the visitors through
//! which a generated message enum reads, measures and writes its variant's payload.

use crate::error::{DecodeError, EncodeError};
use crate::wire::{Reader, Writer};

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
