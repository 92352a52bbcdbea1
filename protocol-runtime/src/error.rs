//! The errors of decoding and encoding: [`DecodeError`] and [`EncodeError`].
//!
//! This module owns the error types shared by the cursors ([`crate::wire`]), the frame engine
//! ([`crate::decoder`]), sealing ([`crate::encoder`]) and generated code. Why a frame was
//! rejected ([`Reject`]) lives with the engine that decides it.
//!
//! Every error is `Copy`, small, `#[non_exhaustive]`, and implements [`Display`] and
//! [`core::error::Error`], so it works the same on firmware and on a host. An error about a
//! value names where the value lies ([`Place`]: the command and the field, as `&'static str`s
//! generated code passes), so that `Display` says which field of which command is wrong
//! without allocating.
//!
//! [`Display`]: core::fmt::Display

use core::fmt;

use crate::decoder::Reject;

/// Why bytes could not be decoded into a value or a frame.
///
/// # Examples
///
/// ```
/// use protocol_runtime::{DecodeError, Reader};
///
/// let mut r = Reader::new(&[0x01]);
/// assert_eq!(r.u16_le(), Err(DecodeError::Truncated { needed: 2, available: 1 }));
/// ```
#[non_exhaustive]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum DecodeError {
    /// The input ended early: `needed` bytes (counted from the start of the input) were
    /// required, only `available` exist.
    Truncated {
        /// Bytes the read needed, counted from the start of the input.
        needed: usize,
        /// Bytes the input holds.
        available: usize,
    },
    /// The payload's size does not match the command's struct.
    PayloadLength {
        /// Size the struct takes on the wire.
        expected: usize,
        /// Size of the payload received.
        actual: usize,
    },
    /// No command has this dispatch key. A key of several fields is the fields concatenated,
    /// the first field in the high bits.
    UnknownCommand {
        /// The dispatch key.
        key: u64,
    },
    /// The header matches no direction rule (for example an address outside every range).
    UnknownDirection,
    /// A value is not one of its enum's variants.
    InvalidEnum {
        /// The value on the wire.
        value: u64,
        /// The field that holds it.
        place: Place,
    },
    /// The bytes are not a valid frame.
    Frame(Reject),
    /// A stuffed payload holds the forbidden pattern without the byte stuffing inserts after
    /// it.
    InvalidStuffing,
    /// A scaled value lies outside the range its field clamps encoded values to: it could not
    /// be encoded back to the same bytes.
    ValueOutOfRange {
        /// The field.
        place: Place,
    },
    /// A field that must have the size another field states does not (a repeated group's
    /// element that does not fit the declared data length).
    SizeMismatch {
        /// The field.
        place: Place,
    },
    /// A NUL-terminated text has no NUL within its field's most bytes (or before the payload
    /// ends).
    Unterminated {
        /// The field.
        place: Place,
    },
    /// A check inside the payload (a CRC over some of its fields) does not match the bytes it
    /// covers.
    PayloadCheck {
        /// The check.
        place: Place,
    },
}

/// Where in a message a value lies: the command's name and the field's path, as the spec
/// writes them (`SET_LED`, `LedState.mode`: the struct that declares the field, then its
/// name). Generated code fills them in as an error passes out of a field's code and then out
/// of a command's; a rule of the runtime called on its own leaves them empty ([`Place::NONE`]).
///
/// # Examples
///
/// ```
/// use protocol_runtime::DecodeError;
/// use protocol_runtime::error::Place;
///
/// let e = DecodeError::InvalidEnum { value: 9, place: Place::NONE };
/// assert_eq!(e.to_string(), "invalid enum value 0x9");
/// let e = e.in_field("LedState.mode").in_command("SET_LED");
/// assert_eq!(e.place(), Some(Place::new("SET_LED", "LedState.mode")));
/// assert_eq!(
///     e.to_string(),
///     "SET_LED: `LedState.mode` holds 0x9, which is no variant of its enum"
/// );
/// ```
///
/// Kept on hosts (64-bit pointers), and on every target with the `error-places` feature. A
/// microcontroller's firmware leaves them out by default ([`Place`] is then empty, its names
/// read as unknown): with them the name of every command and field is linked in for a message
/// a firmware rarely prints, and every error value is larger (the HFLink firmware of
/// `bash benches/footprint.sh`, 7,452 bytes of `.text`, takes 7,984 with them).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Place {
    /// The command's name in the spec; empty where unknown.
    #[cfg(any(target_pointer_width = "64", feature = "error-places"))]
    command: &'static str,
    /// The field's path (`Struct.field`); empty where unknown.
    #[cfg(any(target_pointer_width = "64", feature = "error-places"))]
    field: &'static str,
}

impl Place {
    /// Whether places are kept on the target this is built for (see [`Place`]).
    pub const KEPT: bool = cfg!(any(target_pointer_width = "64", feature = "error-places"));

    /// Nowhere known.
    pub const NONE: Place = Place::new("", "");

    /// The place in `command` (its name in the spec) and `field` (`Struct.field`); either
    /// empty where unknown. Both are dropped where places are not kept.
    #[inline]
    #[must_use]
    #[allow(unused_variables)]
    pub const fn new(command: &'static str, field: &'static str) -> Place {
        Place {
            #[cfg(any(target_pointer_width = "64", feature = "error-places"))]
            command,
            #[cfg(any(target_pointer_width = "64", feature = "error-places"))]
            field,
        }
    }

    /// The command's name in the spec; empty where unknown or not kept.
    #[inline]
    #[must_use]
    pub const fn command(&self) -> &'static str {
        #[cfg(any(target_pointer_width = "64", feature = "error-places"))]
        return self.command;
        #[cfg(not(any(target_pointer_width = "64", feature = "error-places")))]
        ""
    }

    /// The field's path (`Struct.field`); empty where unknown or not kept.
    #[inline]
    #[must_use]
    pub const fn field(&self) -> &'static str {
        #[cfg(any(target_pointer_width = "64", feature = "error-places"))]
        return self.field;
        #[cfg(not(any(target_pointer_width = "64", feature = "error-places")))]
        ""
    }

    /// The place with `field` as its field, unless it names one already: the innermost
    /// field's code names it first (a nested struct's field), and the path it gives is the
    /// more precise.
    #[inline]
    #[must_use]
    pub const fn in_field(self, field: &'static str) -> Place {
        if self.field().is_empty() {
            Place::new(self.command(), field)
        } else {
            self
        }
    }

    /// The place with `command` as its command, unless it names one already.
    #[inline]
    #[must_use]
    pub const fn in_command(self, command: &'static str) -> Place {
        if self.command().is_empty() {
            Place::new(command, self.field())
        } else {
            self
        }
    }

    /// `COMMAND: `field`` (either part alone where the other is unknown), before what is
    /// wrong; nothing when neither is known.
    fn write_prefix(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if !self.command().is_empty() {
            write!(f, "{}: ", self.command())?;
        }
        if !self.field().is_empty() {
            write!(f, "`{}`: ", self.field())?;
        }
        Ok(())
    }
}

impl DecodeError {
    /// The place of an error about a value; `None` for the other errors.
    #[must_use]
    pub const fn place(&self) -> Option<Place> {
        match *self {
            DecodeError::InvalidEnum { place, .. }
            | DecodeError::ValueOutOfRange { place }
            | DecodeError::SizeMismatch { place }
            | DecodeError::Unterminated { place }
            | DecodeError::PayloadCheck { place } => Some(place),
            _ => None,
        }
    }

    /// The same error with its place set to `place`; the other errors as they are.
    #[inline]
    const fn map_place(self, place: Place) -> Self {
        match self {
            DecodeError::InvalidEnum { value, .. } => DecodeError::InvalidEnum { value, place },
            DecodeError::ValueOutOfRange { .. } => DecodeError::ValueOutOfRange { place },
            DecodeError::SizeMismatch { .. } => DecodeError::SizeMismatch { place },
            DecodeError::Unterminated { .. } => DecodeError::Unterminated { place },
            DecodeError::PayloadCheck { .. } => DecodeError::PayloadCheck { place },
            other => other,
        }
    }

    /// The error located in `field` (a `Struct.field` path), unless it names a field already.
    #[inline]
    #[must_use]
    pub const fn in_field(self, field: &'static str) -> Self {
        // Nothing to name where places are not kept: the error as it is, without a match
        // that rebuilds it (which the optimiser does not always see through).
        if !Place::KEPT {
            return self;
        }
        match self.place() {
            Some(place) => self.map_place(place.in_field(field)),
            None => self,
        }
    }

    /// The error located in `command`, unless it names a command already.
    #[inline]
    #[must_use]
    pub const fn in_command(self, command: &'static str) -> Self {
        // Nothing to name where places are not kept: the error as it is, without a match
        // that rebuilds it (which the optimiser does not always see through).
        if !Place::KEPT {
            return self;
        }
        match self.place() {
            Some(place) => self.map_place(place.in_command(command)),
            None => self,
        }
    }

    /// The same error without its place ([`Place::NONE`]): what went wrong, not where, to
    /// compare with a decoder that names places otherwise.
    #[must_use]
    pub const fn without_place(self) -> Self {
        self.map_place(Place::NONE)
    }
}

impl fmt::Display for DecodeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            DecodeError::Truncated { needed, available } => {
                write!(
                    f,
                    "input truncated: {needed} bytes needed, {available} available"
                )
            }
            DecodeError::PayloadLength { expected, actual } => {
                write!(
                    f,
                    "payload length mismatch: expected {expected} bytes, got {actual}"
                )
            }
            DecodeError::UnknownCommand { key } => write!(f, "unknown command {key:#x}"),
            DecodeError::UnknownDirection => f.write_str("header matches no direction"),
            DecodeError::InvalidEnum { value, place } if place.field().is_empty() => {
                place.write_prefix(f)?;
                write!(f, "invalid enum value {value:#x}")
            }
            DecodeError::InvalidEnum { value, place } => {
                if !place.command().is_empty() {
                    write!(f, "{}: ", place.command())?;
                }
                write!(
                    f,
                    "`{}` holds {value:#x}, which is no variant of its enum",
                    place.field()
                )
            }
            DecodeError::InvalidStuffing => {
                write!(
                    f,
                    "stuffed payload: a forbidden pattern is not followed by its stuffing byte"
                )
            }
            DecodeError::ValueOutOfRange { place } => {
                place.write_prefix(f)?;
                write!(f, "a scaled value lies outside its field's range")
            }
            DecodeError::SizeMismatch { place } => {
                place.write_prefix(f)?;
                write!(
                    f,
                    "a field's size does not match the size another field states"
                )
            }
            DecodeError::Unterminated { place } => {
                place.write_prefix(f)?;
                f.write_str("a NUL-terminated text has no NUL within its most bytes")
            }
            DecodeError::PayloadCheck { place } => {
                place.write_prefix(f)?;
                f.write_str("a check inside the payload does not match the bytes it covers")
            }
            DecodeError::Frame(reason) => write!(f, "invalid frame: {reason}"),
        }
    }
}

impl core::error::Error for DecodeError {
    fn source(&self) -> Option<&(dyn core::error::Error + 'static)> {
        match self {
            DecodeError::Frame(reason) => Some(reason),
            _ => None,
        }
    }
}

impl From<Reject> for DecodeError {
    #[inline]
    fn from(reason: Reject) -> Self {
        DecodeError::Frame(reason)
    }
}

/// Why a value or a frame could not be encoded.
///
/// # Examples
///
/// ```
/// use protocol_runtime::{EncodeError, Writer};
///
/// let mut buf = [0u8; 1];
/// let mut w = Writer::new(&mut buf);
/// assert_eq!(w.put_u16_be(7), Err(EncodeError::BufferTooSmall { needed: 2, available: 1 }));
/// ```
#[non_exhaustive]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum EncodeError {
    /// The output buffer is too small: `needed` bytes (counted from its start) were required,
    /// it holds `available`.
    BufferTooSmall {
        /// Bytes the write needed, counted from the start of the buffer.
        needed: usize,
        /// Bytes the buffer holds.
        available: usize,
    },
    /// The payload makes the frame longer than the format allows.
    PayloadTooLarge {
        /// Length that was asked for.
        len: usize,
        /// Largest length allowed.
        max: usize,
    },
    /// A value does not fit its field (for example a length or a bitfield).
    ValueOutOfRange {
        /// The field.
        place: Place,
    },
}

impl EncodeError {
    /// The place of an error about a value; `None` for the other errors.
    #[must_use]
    pub const fn place(&self) -> Option<Place> {
        match *self {
            EncodeError::ValueOutOfRange { place } => Some(place),
            _ => None,
        }
    }

    /// The error located in `field` (a `Struct.field` path), unless it names a field already.
    ///
    /// ```
    /// use protocol_runtime::EncodeError;
    /// use protocol_runtime::error::Place;
    ///
    /// let e = EncodeError::ValueOutOfRange { place: Place::NONE };
    /// let e = e.in_field("Status.battery").in_command("STATUS");
    /// assert_eq!(e.to_string(), "STATUS: `Status.battery`: value does not fit its field");
    /// ```
    #[inline]
    #[must_use]
    pub const fn in_field(self, field: &'static str) -> Self {
        // Nothing to name where places are not kept: the error as it is, without a match
        // that rebuilds it (which the optimiser does not always see through).
        if !Place::KEPT {
            return self;
        }
        match self {
            EncodeError::ValueOutOfRange { place } => EncodeError::ValueOutOfRange {
                place: place.in_field(field),
            },
            other => other,
        }
    }

    /// The error located in `command`, unless it names a command already.
    #[inline]
    #[must_use]
    pub const fn in_command(self, command: &'static str) -> Self {
        // Nothing to name where places are not kept: the error as it is, without a match
        // that rebuilds it (which the optimiser does not always see through).
        if !Place::KEPT {
            return self;
        }
        match self {
            EncodeError::ValueOutOfRange { place } => EncodeError::ValueOutOfRange {
                place: place.in_command(command),
            },
            other => other,
        }
    }

    /// The same error without its place ([`Place::NONE`]).
    #[must_use]
    pub const fn without_place(self) -> Self {
        match self {
            EncodeError::ValueOutOfRange { .. } => {
                EncodeError::ValueOutOfRange { place: Place::NONE }
            }
            other => other,
        }
    }
}

impl fmt::Display for EncodeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            EncodeError::BufferTooSmall { needed, available } => {
                write!(
                    f,
                    "buffer too small: {needed} bytes needed, {available} available"
                )
            }
            EncodeError::PayloadTooLarge { len, max } => {
                write!(f, "payload too large: {len} bytes, at most {max} allowed")
            }
            EncodeError::ValueOutOfRange { place } => {
                place.write_prefix(f)?;
                f.write_str("value does not fit its field")
            }
        }
    }
}

impl core::error::Error for EncodeError {}

/// Reads a field with `read`; an error it gives names the field `field` (a `Struct.field`
/// path), unless a nested struct's field is named already. Generated code reads each field
/// through it, so the path costs nothing but on the error path.
///
/// # Errors
///
/// The error of `read`, located.
#[cfg_attr(not(protocol_opt0), inline(always))]
pub fn read_field<T>(
    field: &'static str,
    read: impl FnOnce() -> Result<T, DecodeError>,
) -> Result<T, DecodeError> {
    read().map_err(|e| e.in_field(field))
}

/// Writes a field with `write`; an error it gives names the field `field`, as
/// [`read_field`] does for reading.
///
/// # Errors
///
/// The error of `write`, located.
#[cfg_attr(not(protocol_opt0), inline(always))]
pub fn write_field<T>(
    field: &'static str,
    write: impl FnOnce() -> Result<T, EncodeError>,
) -> Result<T, EncodeError> {
    write().map_err(|e| e.in_field(field))
}

/// Reads a command's payload with `read`; an error it gives names the command `command`.
///
/// # Errors
///
/// The error of `read`, located.
#[cfg_attr(not(protocol_opt0), inline(always))]
pub fn read_command<T>(
    command: &'static str,
    read: impl FnOnce() -> Result<T, DecodeError>,
) -> Result<T, DecodeError> {
    read().map_err(|e| e.in_command(command))
}

/// The result of decoding a `T`.
pub type DecodeResult<T> = Result<T, DecodeError>;

/// The result of encoding: nothing, or why not.
pub type EncodeResult = Result<(), EncodeError>;
