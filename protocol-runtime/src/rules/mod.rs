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

use crate::layout::{FrameLayout, WordField};
use crate::stuffing::Stuffing;

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

mod decode;
mod encode;

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
    #[cfg_attr(not(protocol_opt0), inline(always))]
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

#[cfg(test)]
mod tests;
#[cfg(test)]
mod tests_headers;
#[cfg(test)]
mod tests_sent;
