//! A request's outcome told by a value of its answer (MAVLink: a COMMAND_ACK answers every
//! COMMAND_LONG, and its `result` says accepted, in progress, denied, failed, ...): where the
//! value sits, the values that mean success and those that mean the request is still being
//! carried out, and the judgement of an answer's frame. Every other value is a refusal that
//! carries the value: a value the spec does not list (a result a newer peer adds) is never
//! taken for success.

use super::pairs::ValueAt;
use crate::rules::PacketRules;

/// How the answer to a request of one command tells success from refusal.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Verdict<'a> {
    /// The request's command key.
    pub request: u64,
    /// Where its answer holds the value.
    pub at: ValueAt,
    /// The values that mean the request succeeded.
    pub accept: &'a [u64],
    /// The values that mean the request is being carried out: its answer is still to come.
    pub progress: &'a [u64],
}

/// What an answer's value says of its request.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Judged {
    /// A value of [`Verdict::accept`]: the request succeeded.
    Accepted,
    /// A value of [`Verdict::progress`]: the request is being carried out.
    Progress(u64),
    /// Any other value: the request is refused, with this value.
    Rejected(u64),
}

impl Verdict<'_> {
    /// What the answer `frame` says, read through `rules`; `None` when the frame does not
    /// hold the value (it is not an answer of this kind).
    ///
    /// ```
    /// use protocol_runtime::layout::{FrameLayout, LengthRule, Pos, WordField};
    /// use protocol_runtime::session::{Judged, ValueAt, Verdict};
    /// use protocol_runtime::PacketRules;
    ///
    /// // `AA cmd result`: the answer's result in its one payload byte.
    /// static LAYOUT: FrameLayout<'static> = FrameLayout {
    ///     sync: &[0xAA], sync_set: &[], header_len: 2, min_len: 3, max_len: 3,
    ///     length: LengthRule::Fixed(3), constants: &[], header_checks: &[], frame_checks: &[],
    ///     markers: &[], escape: None,
    /// };
    /// static RULES: PacketRules<'static> = PacketRules {
    ///     layout: &LAYOUT, header_len: 2, trailer_len: 0, max_payload: 1,
    ///     key: &[WordField::le(1, 1)], ack: None, directions: &[], stuffing: None,
    ///     truncate_zeros: false,
    /// };
    /// let verdict = Verdict {
    ///     request: 7, at: ValueAt::Payload(WordField::le(0, 1)), accept: &[0], progress: &[5],
    /// };
    /// assert_eq!(verdict.judge(&RULES, &[0xAA, 8, 0]), Some(Judged::Accepted));
    /// assert_eq!(verdict.judge(&RULES, &[0xAA, 8, 5]), Some(Judged::Progress(5)));
    /// assert_eq!(verdict.judge(&RULES, &[0xAA, 8, 4]), Some(Judged::Rejected(4)));
    /// assert_eq!(verdict.judge(&RULES, &[0xAA, 8]), None);
    /// ```
    #[must_use]
    pub fn judge(&self, rules: &PacketRules<'_>, frame: &[u8]) -> Option<Judged> {
        let v = self.at.read(rules, frame)?;
        Some(if self.accept.contains(&v) {
            Judged::Accepted
        } else if self.progress.contains(&v) {
            Judged::Progress(v)
        } else {
            Judged::Rejected(v)
        })
    }
}
