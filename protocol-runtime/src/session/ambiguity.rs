//! Whether one frame could answer two requests: the rule by which a requester without a
//! sequence number refuses a request whose answers it could not tell from an open one's
//! ([`SendError::Ambiguous`](super::SendError::Ambiguous)). A frame answers both when it is of
//! the kind both expect and repeats what both told: each value the two answers repeat in one
//! place is the same, except the sender's id of a request answered once by each id it lists,
//! which then is one the other request waits for (Dynamixel: a READ to servo 3 and a SYNC_READ
//! listing 3; a status from 3 could answer either, and which one it answers would depend on
//! the order they were sent in, not on what the status carries).

use super::{Answer, IdSet, Ids, SessionRules, ValueAt};
use crate::layout::WordField;

/// A request as far as telling its answers apart goes.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Awaits<'a> {
    /// The values that identify it.
    pub ids: &'a Ids,
    /// The answer it expects.
    pub answer: Answer,
    /// The ids still to answer, for a request answered once by each id it lists.
    pub several: Option<IdSet>,
}

impl SessionRules<'_> {
    /// True when one frame could answer both `a` and `b`.
    pub(crate) fn share_answer(&self, a: Awaits<'_>, b: Awaits<'_>) -> bool {
        Self::same_kind(a, b)
            && self.same_repeats(a, b)
            && self.same_pairs(a, b)
            && self.same_sender(a, b)
    }

    /// Rule: both expect frames of one kind (a reply is its command back; a `message` is any
    /// command).
    fn same_kind(a: Awaits<'_>, b: Awaits<'_>) -> bool {
        let kind = |w: Awaits<'_>| match w.answer {
            Answer::Reply => Answer::Command(w.ids.key),
            other => other,
        };
        match (kind(a), kind(b)) {
            (Answer::Message, Answer::Command(_)) | (Answer::Command(_), Answer::Message) => true,
            (x, y) => x == y,
        }
    }

    /// The header values an answer to the request `ids` repeats, where it holds them.
    fn repeated(&self, ids: &Ids) -> impl Iterator<Item = (WordField, u64)> {
        let swap = self
            .swap
            .into_iter()
            .flat_map(move |(from, to)| [(from, ids.to), (to, ids.from)]);
        self.sequence
            .map(|f| (f, ids.seq))
            .into_iter()
            .chain(self.echo.iter().copied().zip(ids.values))
            .chain(swap)
    }

    /// Rule: each header value both answers repeat is the same, but the sender's id of a
    /// request of several answers.
    fn same_repeats(&self, a: Awaits<'_>, b: Awaits<'_>) -> bool {
        let own = [self.own_value(a.ids.key), self.own_value(b.ids.key)];
        self.repeated(a.ids)
            .zip(self.repeated(b.ids))
            .all(|((f, va), (_, vb))| own.contains(&Some(f)) || va == vb)
    }

    /// Rule: a value both answers repeat in one place under other names (a pair of each
    /// request's command) is the same.
    fn same_pairs(&self, a: Awaits<'_>, b: Awaits<'_>) -> bool {
        let told = |w: Awaits<'_>| -> [Option<(ValueAt, u64)>; SessionRules::MAX_PAIRS] {
            let mut told = [None; SessionRules::MAX_PAIRS];
            for (slot, (p, v)) in told
                .iter_mut()
                .zip(self.pairs_of(w.ids.key).zip(w.ids.paired))
            {
                *slot = Some((p.to, v));
            }
            told
        };
        let (ta, tb) = (told(a), told(b));
        ta.iter()
            .flatten()
            .all(|(at, va)| tb.iter().flatten().all(|(bt, vb)| at != bt || va == vb))
    }

    /// Rule: an answer to a request of several answers comes from an id it waits for; one
    /// that answers the other request too holds the id that one repeats, or waits for.
    fn same_sender(&self, a: Awaits<'_>, b: Awaits<'_>) -> bool {
        match (a.several, b.several) {
            (None, None) => true,
            (Some(x), Some(y)) => x.meets(&y),
            (Some(set), None) => self
                .sender_told(a.ids.key, b.ids)
                .is_none_or(|id| u8::try_from(id).is_ok_and(|id| set.contains(id))),
            (None, Some(set)) => self
                .sender_told(b.ids.key, a.ids)
                .is_none_or(|id| u8::try_from(id).is_ok_and(|id| set.contains(id))),
        }
    }

    /// The value an answer to the request `ids` repeats in the field where an answer to a
    /// request of `several` holds its sender's id, when it repeats one there.
    fn sender_told(&self, several: u64, ids: &Ids) -> Option<u64> {
        let by = self.fanout(several)?.id;
        self.repeated(ids).find(|&(f, _)| f == by).map(|(_, v)| v)
    }
}
