//! Values an answer repeats from its request under another name, and possibly in its payload
//! (MAVLink: a COMMAND_ACK names the `command` of the COMMAND_LONG it answers, and addresses
//! the request's sender in its `target_system`): where each value sits, and reading it from a
//! frame through the packet rules. A payload value is read at its offset in the payload the
//! rules return; on a format that drops trailing zero bytes, a value past the bytes sent is 0.

use crate::layout::{Pos, WordField};
use crate::rules::PacketRules;

/// Where a value sits in a frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ValueAt {
    /// A header field.
    Header(WordField),
    /// A payload field, at its position from the payload's first byte (`Pos::Start`).
    Payload(WordField),
}

/// A value that an answer repeats from a request of one command.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Pair {
    /// The request's command key.
    pub request: u64,
    /// Where the request holds the value.
    pub from: ValueAt,
    /// Where its answer holds it.
    pub to: ValueAt,
}

impl ValueAt {
    /// The value in `frame`, read through `rules`; `None` when the frame does not hold it.
    ///
    /// ```
    /// use protocol_runtime::layout::{ByteOrder, Check, FrameLayout, LengthRule, Pos, WordField};
    /// use protocol_runtime::session::ValueAt;
    /// use protocol_runtime::{Checksum, PacketRules};
    ///
    /// // `AA cmd payload(2) sum8`.
    /// static LAYOUT: FrameLayout<'static> = FrameLayout {
    ///     sync: &[0xAA], sync_set: &[], header_len: 2, min_len: 5, max_len: 5,
    ///     length: LengthRule::Fixed(5), constants: &[], header_checks: &[],
    ///     frame_checks: &[Check { checksum: Checksum::Sum8, from: Pos::Start(0), to: Pos::End(1),
    ///                             at: Pos::End(1), order: ByteOrder::Little }],
    ///     markers: &[],
    ///     escape: None,
    /// };
    /// static RULES: PacketRules<'static> = PacketRules {
    ///     layout: &LAYOUT, header_len: 2, trailer_len: 1, max_payload: 2,
    ///     key: &[WordField::le(1, 1)], ack: None, directions: &[], stuffing: None,
    ///     truncate_zeros: false,
    /// };
    /// let frame = [0xAA, 7, 0x34, 0x12, 0x17];
    /// assert_eq!(ValueAt::Header(WordField::le(1, 1)).read(&RULES, &frame), Some(7));
    /// assert_eq!(ValueAt::Payload(WordField::le(0, 2)).read(&RULES, &frame), Some(0x1234));
    /// assert_eq!(ValueAt::Payload(WordField::le(1, 2)).read(&RULES, &frame), None);
    /// ```
    #[must_use]
    pub fn read(self, rules: &PacketRules<'_>, frame: &[u8]) -> Option<u64> {
        match self {
            ValueAt::Header(f) => f.read(frame),
            ValueAt::Payload(f) => {
                // Stuffed formats are refused by validation: their payload needs a scratch
                // buffer, and reads as absent here.
                let payload = rules.payload(frame, &mut []).ok()?;
                match f.read(payload) {
                    Some(v) => Some(v),
                    None if rules.truncate_zeros => read_zero_filled(f, payload),
                    None => None,
                }
            }
        }
    }
}

/// `f` read from `payload` as if the bytes past its end were zero (a truncated payload).
fn read_zero_filled(f: WordField, payload: &[u8]) -> Option<u64> {
    let Pos::Start(at) = f.at else { return None };
    let mut word = [0u8; 8];
    let size = usize::from(f.size).min(word.len());
    let have = payload.get(at..).unwrap_or(&[]);
    let n = have.len().min(size);
    word.get_mut(..n)?.copy_from_slice(have.get(..n)?);
    WordField {
        at: Pos::Start(0),
        ..f
    }
    .read(&word)
}
