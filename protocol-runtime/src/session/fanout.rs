//! A request answered by several frames, one per device it lists (Dynamixel 2.0: a SYNC_READ
//! or BULK_READ lists servo ids in its payload, and each listed servo answers with a status
//! packet of its own id): where the request lists the ids, which header value of an answer
//! names its sender, and the set of ids a request still waits for.
//!
//! Ids are one byte (the protocols in view address at most 253 devices on a bus), so the set
//! is a fixed 256-bit table: no heap, 32 bytes per open request, in the requesters of rules
//! that list such a command only ([`Awaiting`]). The listed ids are read from
//! the request's payload, unstuffed on the fly when the format stuffs payloads (Dynamixel
//! does), so that no scratch buffer is needed.

use crate::layout::WordField;
use crate::rules::PacketRules;

/// A command whose request is answered once by each id its payload lists.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Fanout {
    /// The request's command key.
    pub request: u64,
    /// Offset of the first listed id from the start of the request's (unstuffed) payload.
    pub first: usize,
    /// Bytes from one listed id to the next (the size of a repeated element), at least 1.
    pub stride: usize,
    /// The header value of an answer that holds the id of the device that sent it.
    pub id: WordField,
}

/// A set of one-byte ids.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct IdSet([u64; 4]);

impl IdSet {
    /// The set with no id.
    pub const EMPTY: IdSet = IdSet([0; 4]);

    /// Adds `id`.
    pub fn insert(&mut self, id: u8) {
        if let Some(w) = self.0.get_mut(usize::from(id >> 6)) {
            *w |= 1u64 << (id & 63);
        }
    }

    /// Removes `id`; true when it was in the set.
    pub fn remove(&mut self, id: u8) -> bool {
        let had = self.contains(id);
        if let Some(w) = self.0.get_mut(usize::from(id >> 6)) {
            *w &= !(1u64 << (id & 63));
        }
        had
    }

    /// True when `id` is in the set.
    #[must_use]
    pub fn contains(&self, id: u8) -> bool {
        self.0
            .get(usize::from(id >> 6))
            .is_some_and(|w| w & (1u64 << (id & 63)) != 0)
    }

    /// The number of ids.
    #[must_use]
    pub fn len(&self) -> usize {
        self.0.iter().map(|w| w.count_ones() as usize).sum()
    }

    /// True when the set holds no id.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.0.iter().all(|&w| w == 0)
    }

    /// True when an id is in both sets.
    #[must_use]
    pub fn meets(&self, other: &IdSet) -> bool {
        self.0.iter().zip(other.0).any(|(a, b)| a & b != 0)
    }

    /// The ids, in increasing order.
    pub fn iter(&self) -> impl Iterator<Item = u8> + '_ {
        (0..=u8::MAX).filter(|&id| self.contains(id))
    }
}

/// What a requester's slot keeps of a request answered once by each id it lists: the ids it
/// still waits for, and whether one has answered. A [`SessionRef`](super::SessionRef) names
/// it ([`SessionRef::Awaiting`](super::SessionRef::Awaiting)): [`Awaited`] when its rules list
/// a command of several answers, [`NoFanout`] otherwise, which holds nothing, so that a
/// requester of rules without one keeps no id set in its slots.
pub trait Awaiting: Copy + core::fmt::Debug + Send + Sync + 'static {
    /// Keeps `ids`, none answered yet; `None` when this keeps no ids.
    fn keep(ids: IdSet) -> Option<Self>;
    /// True while `id` is still to answer.
    fn awaits(&self, id: u8) -> bool;
    /// `id` answered: it is taken off the ids still to answer; returns how many remain.
    fn answered(&mut self, id: u8) -> usize;
    /// The ids still to answer once at least one has answered (the request is then
    /// incomplete, not unanswered).
    fn incomplete(&self) -> Option<IdSet>;
    /// The ids still to answer.
    fn waiting(&self) -> IdSet;
}

/// The ids a request of several answers still waits for, and whether one has answered.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Awaited {
    left: IdSet,
    heard: bool,
}

impl Awaiting for Awaited {
    fn keep(ids: IdSet) -> Option<Self> {
        Some(Self {
            left: ids,
            heard: false,
        })
    }

    fn awaits(&self, id: u8) -> bool {
        self.left.contains(id)
    }

    fn answered(&mut self, id: u8) -> usize {
        self.left.remove(id);
        self.heard = true;
        self.left.len()
    }

    fn incomplete(&self) -> Option<IdSet> {
        self.heard.then_some(self.left)
    }

    fn waiting(&self) -> IdSet {
        self.left
    }
}

/// Nothing: what a requester keeps of requests of several answers when its rules list no
/// such command. It has no value, so an `Option<NoFanout>` takes no byte.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum NoFanout {}

impl Awaiting for NoFanout {
    fn keep(_: IdSet) -> Option<Self> {
        None
    }

    fn awaits(&self, _: u8) -> bool {
        match *self {}
    }

    fn answered(&mut self, _: u8) -> usize {
        match *self {}
    }

    fn incomplete(&self) -> Option<IdSet> {
        match *self {}
    }

    fn waiting(&self) -> IdSet {
        match *self {}
    }
}

impl Fanout {
    /// The ids the request `frame` lists, read through `rules` (its payload unstuffed as it is
    /// read); `None` when the frame has no payload the rules can find.
    ///
    /// ```
    /// use protocol_runtime::layout::{FrameLayout, LengthRule, WordField};
    /// use protocol_runtime::session::Fanout;
    /// use protocol_runtime::stuffing::Stuffing;
    /// use protocol_runtime::PacketRules;
    ///
    /// // `AA cmd payload(6)`, with `AA` stuffed inside the payload as `AA 00`.
    /// static LAYOUT: FrameLayout<'static> = FrameLayout {
    ///     sync: &[0xAA], sync_set: &[], header_len: 2, min_len: 2, max_len: 16,
    ///     length: LengthRule::Fixed(8), constants: &[], header_checks: &[], frame_checks: &[],
    ///     markers: &[], escape: None,
    /// };
    /// static RULES: PacketRules<'static> = PacketRules {
    ///     layout: &LAYOUT, header_len: 2, trailer_len: 0, max_payload: 8,
    ///     key: &[WordField::le(1, 1)], ack: None, directions: &[],
    ///     stuffing: Some(Stuffing { after: &[0xAA], insert: 0x00 }), truncate_zeros: false,
    /// };
    /// // A two-byte address, then the ids 3, 0xAA (stuffed) and 7.
    /// let read = Fanout { request: 0x82, first: 2, stride: 1, id: WordField::le(2, 1) };
    /// let ids = read.listed(&RULES, &[0xAA, 0x82, 0x10, 0x00, 3, 0xAA, 0x00, 7]).unwrap();
    /// assert_eq!(ids.iter().collect::<Vec<_>>(), [3, 7, 0xAA]);
    /// ```
    #[must_use]
    pub fn listed(&self, rules: &PacketRules<'_>, frame: &[u8]) -> Option<IdSet> {
        let raw = PacketRules {
            stuffing: None,
            ..*rules
        }
        .payload(frame, &mut [])
        .ok()?;
        let stride = self.stride.max(1);
        let mut set = IdSet::EMPTY;
        for (i, b) in Unstuffed::new(raw, rules).enumerate() {
            let Some(from_first) = i.checked_sub(self.first) else {
                continue;
            };
            if from_first.checked_rem(stride) == Some(0) {
                set.insert(b);
            }
        }
        Some(set)
    }

    /// The id of the device that sent the answer `frame`, when it holds one that fits a byte.
    #[must_use]
    pub fn sender(&self, frame: &[u8]) -> Option<u8> {
        u8::try_from(self.id.read(frame)?).ok()
    }
}

/// The bytes of a stuffed payload with the inserted bytes left out, as
/// [`Stuffing::unstuff`](crate::stuffing::Stuffing::unstuff) copies them, one at a time: the
/// last bytes given are kept to find the pattern, so a pattern longer than that keeps nothing
/// out (no format stuffs after more than 8 bytes).
struct Unstuffed<'a> {
    raw: &'a [u8],
    at: usize,
    after: &'a [u8],
    insert: u8,
    last: [u8; 8],
    given: usize,
}

impl<'a> Unstuffed<'a> {
    fn new(raw: &'a [u8], rules: &PacketRules<'a>) -> Self {
        let (after, insert) = rules.stuffing.map_or((&[][..], 0), |s| (s.after, s.insert));
        Self {
            raw,
            at: 0,
            after,
            insert,
            last: [0; 8],
            given: 0,
        }
    }

    /// True when the bytes given last are the pattern.
    fn ends_pattern(&self) -> bool {
        let n = self.after.len();
        if n == 0 || n > self.last.len() || self.given < n {
            return false;
        }
        let tail = self.last.get(self.last.len().saturating_sub(n)..);
        tail == Some(self.after)
    }
}

impl Iterator for Unstuffed<'_> {
    type Item = u8;

    fn next(&mut self) -> Option<u8> {
        if self.ends_pattern() && self.raw.get(self.at) == Some(&self.insert) {
            self.at = self.at.saturating_add(1);
        }
        let b = *self.raw.get(self.at)?;
        self.at = self.at.saturating_add(1);
        self.last.rotate_left(1);
        if let Some(l) = self.last.last_mut() {
            *l = b;
        }
        self.given = self.given.saturating_add(1);
        Some(b)
    }
}
