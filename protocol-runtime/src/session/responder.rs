//! The responder: the side that receives requests, delivers each once and answers it. With a
//! sequence number it remembers a window of the last `SLOTS` numbers (a fixed table) with
//! their answers, so that a request received again (a retry whose answer was lost, a duplicate
//! of the link) is answered again without being delivered twice, and a request older than the
//! window is neither delivered nor answered; it gates requests on the handshake and watches
//! the command that must keep arriving.
//!
//! The window is what makes the guarantee exact with fixed memory: the requester never has a
//! request open that is `SLOTS` numbers behind the one it sends ([`Requester::send`] refuses
//! with [`SendError::Window`]), so a responder with at least the requester's slots remembers
//! every request that can still be retried.
//!
//! [`Requester::send`]: super::Requester::send
//! [`SendError::Window`]: super::SendError::Window

use super::{Answer, Heard, Ids, SessionRef};
use crate::error::{DecodeError, EncodeError, Place};

/// What a frame that arrived at the responder is.
#[derive(Debug, PartialEq, Eq)]
pub enum Incoming<'a> {
    /// A new request: deliver it to the application. With `answer`, the application answers
    /// it through [`Responder::answer`].
    Deliver {
        /// The request expects an answer.
        answer: bool,
    },
    /// A request received before: not delivered again. Its answer, when one was sent, is to
    /// be sent again.
    Duplicate(Option<&'a [u8]>),
    /// A request before the handshake: not delivered (the application may answer it with the
    /// spec's NACK).
    BeforeHandshake,
    /// A request numbered before the window: its requester has resolved it already, so it is
    /// neither delivered nor answered (a duplicate the link delayed).
    Stale,
    /// Not a request: an acknowledgement.
    Ack,
    /// It cannot be read as a frame of the format.
    Unreadable(DecodeError),
}

/// What the passing of time reports.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Alarm {
    /// The watchdog's command stopped arriving: `period` passed since the last one.
    WatchdogExpired,
}

/// Why an answer cannot be sent.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum AnswerError {
    /// The request cannot be read as a frame of the format.
    Request(DecodeError),
    /// A repeated value does not fit the answer, or sealing it failed.
    Encode(EncodeError),
}

/// A remembered request and its answer.
#[derive(Debug, Clone, Copy)]
struct Seen<const FRAME: usize> {
    ids: Ids,
    /// The answer's bytes, `None` until it is sent (or when it does not fit `FRAME`).
    answer: Option<usize>,
    frame: [u8; FRAME],
}

/// The responder's state machine: it remembers the last `SLOTS` sequence numbers with answers
/// of at most `FRAME` bytes each. Give it at least as many slots as its requester has.
///
/// `S` is where it finds its rules ([`SessionRef`]): a generated module's `Session` (its
/// `Responder` alias names this type with it), or a `&SessionRules` built at run time.
#[derive(Debug, Clone)]
pub struct Responder<S, const SLOTS: usize, const FRAME: usize> {
    rules: S,
    /// Slot `seq % SLOTS` holds the request numbered `seq`, while it is in the window.
    seen: [Option<Seen<FRAME>>; SLOTS],
    /// The highest sequence number received.
    newest: Option<u64>,
    handshaken: bool,
    /// When the watchdog's command last arrived, and whether its lapse is reported.
    fed: Option<(u64, bool)>,
}

impl<S: SessionRef, const SLOTS: usize, const FRAME: usize> Responder<S, SLOTS, FRAME> {
    /// A responder that has seen nothing; before its handshake when the rules have one.
    #[must_use]
    pub fn new(rules: S) -> Self {
        Self {
            rules,
            seen: [None; SLOTS],
            newest: None,
            handshaken: rules.session().handshake.is_none(),
            fed: None,
        }
    }

    /// True once the handshake arrived (always, without a handshake).
    #[must_use]
    pub fn handshaken(&self) -> bool {
        self.handshaken
    }

    /// Forgets every request and the handshake: the peer restarted (its numbering starts
    /// again). A handshake that arrives does the same.
    pub fn reset(&mut self) {
        self.seen = [None; SLOTS];
        self.newest = None;
        self.handshaken = self.rules.session().handshake.is_none();
    }

    /// A checked frame arrived at `now`.
    pub fn on_frame(&mut self, now: u64, frame: &[u8]) -> Incoming<'_> {
        let owner = self.rules;
        let rules = owner.session();
        let key = match rules.heard(frame) {
            Ok(Heard::Command(key)) => key,
            Ok(Heard::Ack) => return Incoming::Ack,
            Err(e) => return Incoming::Unreadable(e),
        };
        if rules.watchdog.is_some_and(|w| w.key == key) {
            self.fed = Some((now, false));
        }
        let ids = rules.ids(key, frame);
        if Some(key) == rules.handshake && !self.is_duplicate(&ids) {
            // A new handshake starts a new conversation: the peer's numbering starts again.
            self.reset();
            self.handshaken = true;
        }
        if !self.handshaken {
            return Incoming::BeforeHandshake;
        }
        let answer = rules.expects(key, frame).answer != Answer::None;
        let Some(seq) = rules.sequence else {
            return Incoming::Deliver { answer };
        };
        let behind = self.behind(seq.max_value(), ids.seq);
        if behind >= SLOTS as u64 {
            return Incoming::Stale;
        }
        let index = self.index(ids.seq);
        let held = self.seen.get(index).copied().flatten();
        if let Some(s) = held.filter(|s| s.ids == ids) {
            let slot = self.seen.get(index).and_then(|s| s.as_ref());
            let sent = s.answer.and_then(|n| slot.and_then(|s| s.frame.get(..n)));
            return Incoming::Duplicate(sent);
        }
        if behind == 0 {
            self.newest = Some(ids.seq);
        }
        if let Some(slot) = self.seen.get_mut(index) {
            *slot = Some(Seen {
                ids,
                answer: None,
                frame: [0; FRAME],
            });
        }
        Incoming::Deliver { answer }
    }

    /// How far `seq` is behind the newest number (0: it is the newest or newer), in a numbering
    /// modulo `max + 1` where a number up to half the range ahead is newer.
    fn behind(&self, max: u64, seq: u64) -> u64 {
        let Some(newest) = self.newest else {
            return 0;
        };
        let back = newest.wrapping_sub(seq) & max;
        if back > max / 2 { 0 } else { back }
    }

    /// The slot of sequence number `seq`.
    fn index(&self, seq: u64) -> usize {
        seq.checked_rem(SLOTS as u64)
            .and_then(|i| usize::try_from(i).ok())
            .unwrap_or(0)
    }

    /// True when a request of these values is remembered.
    fn is_duplicate(&self, ids: &Ids) -> bool {
        self.rules.session().sequence.is_some() && self.seen.iter().flatten().any(|s| s.ids == *ids)
    }

    /// The application answers `request` with `answer` (assembled by its encoder, as the
    /// spec's answer or NACK): the responder writes into it what it repeats from the request
    /// (the sequence number, echoed values, swapped addresses), seals it, and remembers it to
    /// answer the request's duplicates. The caller transmits `answer` as it then is.
    ///
    /// # Errors
    ///
    /// [`AnswerError`]; the answer is then not remembered.
    pub fn answer(&mut self, request: &[u8], answer: &mut [u8]) -> Result<(), AnswerError> {
        let owner = self.rules;
        let rules = owner.session();
        let key = match rules.heard(request).map_err(AnswerError::Request)? {
            Heard::Command(key) => key,
            Heard::Ack => return Err(AnswerError::Request(DecodeError::UnknownDirection)),
        };
        let ids = rules.ids(key, request);
        rules
            .write_repeats(&ids, answer)
            .ok_or(AnswerError::Encode(EncodeError::ValueOutOfRange {
                place: Place::NONE,
            }))?;
        rules
            .packet
            .layout
            .seal(answer)
            .map_err(AnswerError::Encode)?;
        if rules.sequence.is_none() {
            return Ok(());
        }
        let seen = self.seen.iter_mut().flatten().find(|s| s.ids == ids);
        if let Some(s) = seen
            && let Some(stored) = s.frame.get_mut(..answer.len())
        {
            stored.copy_from_slice(answer);
            s.answer = Some(answer.len());
        }
        Ok(())
    }

    /// The instant at which the watchdog expires, while it is armed (its command arrived and
    /// its lapse is not yet reported).
    #[must_use]
    pub fn next_deadline(&self) -> Option<u64> {
        let w = self.rules.session().watchdog?;
        match self.fed {
            Some((at, false)) => Some(at.saturating_add(u64::from(w.period))),
            _ => None,
        }
    }

    /// Time advanced to `now`: the watchdog's expiry, reported once per lapse (the next
    /// frame of its command arms it again).
    pub fn poll(&mut self, now: u64) -> Option<Alarm> {
        let due = self.next_deadline()?;
        if now < due {
            return None;
        }
        if let Some((_, reported)) = self.fed.as_mut() {
            *reported = true;
        }
        Some(Alarm::WatchdogExpired)
    }
}
