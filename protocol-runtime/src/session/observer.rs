//! The observer: a third party on a half-duplex wire (a capture of both ends) that follows the
//! conversation without taking part. It remembers the requests that expect an answer, in a
//! fixed table, and pairs each answer with the request it answers by the rules the requester
//! uses ([`SessionRules::is_answer`] and what the answer repeats), so that a decoder can read a
//! frame that follows a request as that request's answer (Dynamixel 1.0's status packets share
//! the instruction packets' layout) and report which request each answer answers, its
//! round-trip time, and the requests that were never answered.
//!
//! An answer that does not end its request is paired and leaves it open: one whose result
//! value says the request is in progress (MAVLink's COMMAND_ACK `IN_PROGRESS`; the final ACK
//! that follows answers the same request), and each answer but the last of a request
//! answered once by each id it lists (a SYNC_READ's statuses).
//!
//! An answer that carries no command ([`Answer::Message`]) can be told from a request only by
//! its place: it answers the request right before it (on a half-duplex bus a device answers
//! before the wire is used again), never an older one.
//!
//! The observer holds no rules: each call takes them (a [`SessionRef`]: a generated module's
//! `Session`, or a `&SessionRules`), so a caller that builds its rules on each call (the
//! run-time codec) keeps one observer for a whole capture. What it keeps per request of
//! several answers is the rules' [`SessionRef::Awaiting`], as a requester's slot does: an id
//! set where the rules may list such a command ([`Awaited`], the default), nothing where they
//! list none ([`NoFanout`](super::NoFanout)).

use super::{Answer, Awaited, Awaiting, Ids, Judged, SessionRef, SessionRules};

/// An answer, paired with the request it answers.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Paired {
    /// The request's frame number, as passed to [`Observer::request`].
    pub request: u64,
    /// Milliseconds from the request to its answer, when both have a time.
    pub round_trip: Option<u64>,
    /// The request waits on for another answer: this one says it is in progress, or ids it
    /// lists are still to answer.
    pub open: bool,
    /// The frame refuses the request: it is of a refusing direction
    /// ([`SessionRules::refusals`]: MSP's error reply) and carries the request's command.
    pub refused: bool,
}

/// A request seen, waiting for its answer.
#[derive(Debug, Clone, Copy)]
struct Watched<A> {
    index: u64,
    at: Option<u64>,
    ids: Ids,
    answer: Answer,
    /// How long the requester waits for it, its retries included.
    lifetime: u64,
    /// When it last heard an answer that left it open (its wait starts anew then).
    heard: Option<u64>,
    /// The ids still to answer, for a request answered once by each id it lists.
    waiting: Option<A>,
}

/// Follows a conversation on a wire: at most `OPEN` requests wait for their answer at once (an
/// older one is counted unanswered to make room). `A` is what it keeps of a request answered
/// once by each id it lists: the [`SessionRef::Awaiting`] of the rules it is given.
///
/// ```
/// use protocol_runtime::layout::{ByteOrder, Check, FrameLayout, LengthRule, Pos, WordField};
/// use protocol_runtime::session::{Answer, Exchange, Observer, Paired, SessionRules};
/// use protocol_runtime::{Checksum, PacketRules};
///
/// // `AA id cmd sum8`: a request and its answer look alike; the answer repeats the id.
/// static LAYOUT: FrameLayout<'static> = FrameLayout {
///     sync: &[0xAA], sync_set: &[], header_len: 3, min_len: 4, max_len: 4,
///     length: LengthRule::Fixed(4), constants: &[], header_checks: &[],
///     frame_checks: &[Check { checksum: Checksum::Sum8, from: Pos::Start(0), to: Pos::End(1),
///                             at: Pos::End(1), order: ByteOrder::Little }],
///     markers: &[],
///     escape: None,
/// };
/// static RULES: PacketRules<'static> = PacketRules {
///     layout: &LAYOUT, header_len: 3, trailer_len: 1, max_payload: 0,
///     key: &[WordField::le(2, 1)], ack: None, directions: &[], stuffing: None,
///     truncate_zeros: false,
/// };
/// static SESSION: SessionRules<'static> = SessionRules {
///     packet: &RULES,
///     default: Exchange { key: 0, answer: Answer::Reply, timeout: 50, retries: 0, backoff: 1 },
///     exchanges: &[],
///     sequence: None, echo: &[WordField::le(1, 1)], swap: None, pairs: &[], nack: None,
///     refusals: &[],
///     handshake: None, watchdog: None, modes: None, verdicts: &[],
///     periodic: &[], fanouts: &[],
/// };
///
/// let mut wire = Observer::<4>::new();
/// assert!(wire.request(&SESSION, 0, Some(1000), &[0xAA, 1, 7, 0xB2]));
/// assert!(wire.awaiting());
/// // An answer from another id answers nothing; the one from id 1 answers frame 0.
/// assert_eq!(wire.answer(&SESSION, Some(1010), &[0xAA, 2, 7, 0xB3]), None);
/// let paired = wire.answer(&SESSION, Some(1012), &[0xAA, 1, 7, 0xB2]);
/// assert_eq!(paired, Some(Paired { request: 0, round_trip: Some(12), open: false, refused: false }));
/// assert!(wire.request(&SESSION, 2, Some(2000), &[0xAA, 1, 7, 0xB2]));
/// assert_eq!((wire.answered(), wire.finish()), (1, 1));
/// ```
#[derive(Debug, Clone)]
pub struct Observer<const OPEN: usize, A: Awaiting = Awaited> {
    open: [Option<Watched<A>>; OPEN],
    /// The frame number of the last frame heard, when it was a request that waits.
    latest: Option<u64>,
    answered: u64,
    unanswered: u64,
}

impl<const OPEN: usize, A: Awaiting> Default for Observer<OPEN, A> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const OPEN: usize, A: Awaiting> Observer<OPEN, A> {
    /// An observer that has seen nothing.
    #[must_use]
    pub const fn new() -> Self {
        Self {
            open: [None; OPEN],
            latest: None,
            answered: 0,
            unanswered: 0,
        }
    }

    /// True while a request waits for its answer: a decoder reads the next frame as an answer
    /// first.
    #[must_use]
    pub fn awaiting(&self) -> bool {
        self.open.iter().any(Option::is_some)
    }

    /// Answers paired so far.
    #[must_use]
    pub fn answered(&self) -> u64 {
        self.answered
    }

    /// Requests counted unanswered so far: sent again, expired, or pushed out of the table.
    #[must_use]
    pub fn unanswered(&self) -> u64 {
        self.unanswered
    }

    /// The frame `frame`, number `index`, seen at `at` (milliseconds, when known), read as a
    /// request (any frame that is not an answer): remembered when it expects an answer (the
    /// return value). The same request
    /// seen again (a retry) replaces the one before, which counts unanswered; so does the
    /// oldest request when the table is full, and any request whose requester has given up by
    /// `at`.
    pub fn request<S: SessionRef<Awaiting = A>>(
        &mut self,
        rules: S,
        index: u64,
        at: Option<u64>,
        frame: &[u8],
    ) -> bool {
        let rules = rules.session();
        self.expire(at);
        self.latest = None;
        let Ok(super::Heard::Command(key)) = rules.heard(frame) else {
            return false;
        };
        if rules.refuses(frame) {
            return false;
        }
        let e = rules.expects(key, frame);
        if e.answer == Answer::None {
            return false;
        }
        let ids = rules.ids(key, frame);
        let watched = Watched {
            index,
            at,
            ids,
            answer: e.answer,
            lifetime: e.lifetime(),
            heard: None,
            waiting: rules
                .fanout(key)
                .and_then(|f| f.listed(rules.packet, frame))
                .and_then(A::keep),
        };
        let again = self
            .open
            .iter()
            .position(|o| o.is_some_and(|o| o.ids == ids));
        let free = self.open.iter().position(Option::is_none);
        let oldest = self
            .open
            .iter()
            .enumerate()
            .filter_map(|(i, o)| o.map(|o| (i, o.index)))
            .min_by_key(|&(_, n)| n)
            .map(|(i, _)| i);
        let Some(slot) = again.or(free).or(oldest).and_then(|i| self.open.get_mut(i)) else {
            return false;
        };
        if slot.is_some() {
            self.unanswered = self.unanswered.saturating_add(1);
        }
        *slot = Some(watched);
        self.latest = Some(index);
        true
    }

    /// The frame `frame`, seen at `at`, read as an answer: the open request it answers (the
    /// oldest, should several match), which is then closed unless the answer leaves it open
    /// ([`Paired::open`]); `None` when it answers none.
    pub fn answer<S: SessionRef<Awaiting = A>>(
        &mut self,
        rules: S,
        at: Option<u64>,
        frame: &[u8],
    ) -> Option<Paired> {
        let rules = rules.session();
        self.expire(at);
        let heard = rules.heard(frame).ok()?;
        let refused = rules.refuses(frame);
        let nack = matches!(heard, super::Heard::Command(k) if Some(k) == rules.nack);
        let (i, w) = self
            .open
            .iter()
            .enumerate()
            .filter_map(|(i, o)| o.map(|o| (i, o)))
            .filter(|(_, o)| Self::ends(o, heard, refused, nack))
            .filter(|(_, o)| o.answer != Answer::Message || self.latest == Some(o.index))
            .filter(|(_, o)| rules.repeats(&o.ids, frame))
            .filter(|(_, o)| Self::awaited(rules, o, frame))
            .min_by_key(|(_, o)| o.index)?;
        // The NACK command refuses a request unless it is that request's own answer (HFLink's
        // handshake answers itself and refuses every other request).
        let refused = refused || (nack && !SessionRules::is_answer(w.answer, w.ids.key, heard));
        let open = if refused {
            None
        } else {
            Self::leaves_open(rules, w, frame).map(|o| Watched {
                heard: at.or(o.heard),
                ..o
            })
        };
        if let Some(slot) = self.open.get_mut(i) {
            *slot = open;
        }
        self.latest = None;
        self.answered = self.answered.saturating_add(1);
        Some(Paired {
            request: w.index,
            round_trip: at.zip(w.at).map(|(a, r)| a.saturating_sub(r)),
            open: open.is_some(),
            refused,
        })
    }

    /// Rule, as the requester's: a frame heard as `heard` ends the request `w` when it is the
    /// answer `w` expects, the spec's NACK command (`nack`), or a frame of a refusing direction
    /// (`refused`) that carries `w`'s command.
    fn ends(w: &Watched<A>, heard: super::Heard, refused: bool, nack: bool) -> bool {
        if refused {
            heard == super::Heard::Command(w.ids.key)
        } else {
            nack || SessionRules::is_answer(w.answer, w.ids.key, heard)
        }
    }

    /// Whether `frame` comes from an id the request `w` still waits for (always, for a
    /// request of one answer).
    fn awaited(rules: &SessionRules<'_>, w: &Watched<A>, frame: &[u8]) -> bool {
        let Some(waiting) = w.waiting else {
            return true;
        };
        rules
            .fanout(w.ids.key)
            .and_then(|f| f.sender(frame))
            .is_some_and(|id| waiting.awaits(id))
    }

    /// Rule, as the requester's: the request after its answer `frame`, when it waits on (the
    /// answer says it is in progress, or listed ids are still to answer); `None` when the
    /// answer ends it.
    fn leaves_open(
        rules: &SessionRules<'_>,
        mut w: Watched<A>,
        frame: &[u8],
    ) -> Option<Watched<A>> {
        let judged = rules
            .verdict(w.ids.key)
            .and_then(|v| v.judge(rules.packet, frame));
        if matches!(judged, Some(Judged::Progress(_))) {
            return Some(w);
        }
        let id = rules.fanout(w.ids.key).and_then(|f| f.sender(frame));
        let waiting = w.waiting.as_mut()?;
        (waiting.answered(id?) > 0).then_some(w)
    }

    /// Closes every open request (the capture ended): returns how many requests went
    /// unanswered in all.
    pub fn finish(&mut self) -> u64 {
        let open = self.open.iter().filter(|o| o.is_some()).count() as u64;
        self.open = [None; OPEN];
        self.unanswered = self.unanswered.saturating_add(open);
        self.unanswered
    }

    /// Requests whose requester has given up by `now` (their lifetime passed) count
    /// unanswered.
    fn expire(&mut self, now: Option<u64>) {
        let Some(now) = now else { return };
        for slot in &mut self.open {
            let gone = slot.is_some_and(|w| {
                w.heard
                    .or(w.at)
                    .is_some_and(|at| now > at.saturating_add(w.lifetime))
            });
            if gone {
                *slot = None;
                self.unanswered = self.unanswered.saturating_add(1);
            }
        }
    }
}
