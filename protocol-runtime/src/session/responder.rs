//! The responder: the side that receives requests, delivers each once and answers it. It
//! remembers the requests of the last while (a fixed table) with their answers, so that a
//! request received again (a retry whose answer was lost, a duplicate of the link) is answered
//! again without being delivered twice; it gates requests on the handshake and watches the
//! command that must keep arriving.

use super::{Answer, Heard, Ids, SessionRules};
use crate::error::{DecodeError, EncodeError};

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
    /// A request the table has no room to remember: not delivered (as if lost; the requester
    /// retries it).
    Busy,
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
    at: u64,
    /// The answer's bytes, `None` until it is sent (or when it does not fit `FRAME`).
    answer: Option<usize>,
    frame: [u8; FRAME],
}

/// The responder's state machine: it remembers up to `SLOTS` requests with answers of at most
/// `FRAME` bytes each, for twice the longest a request lives ([`SessionRules::lifetime`]).
#[derive(Debug, Clone)]
pub struct Responder<'r, const SLOTS: usize, const FRAME: usize> {
    rules: &'r SessionRules<'r>,
    seen: [Option<Seen<FRAME>>; SLOTS],
    handshaken: bool,
    /// When the watchdog's command last arrived, and whether its lapse is reported.
    fed: Option<(u64, bool)>,
}

impl<'r, const SLOTS: usize, const FRAME: usize> Responder<'r, SLOTS, FRAME> {
    /// A responder that has seen nothing; before its handshake when the rules have one.
    #[must_use]
    pub fn new(rules: &'r SessionRules<'r>) -> Self {
        Self {
            rules,
            seen: [None; SLOTS],
            handshaken: rules.handshake.is_none(),
            fed: None,
        }
    }

    /// True once the handshake arrived (always, without a handshake).
    #[must_use]
    pub fn handshaken(&self) -> bool {
        self.handshaken
    }

    /// How long a request is remembered: twice the longest it lives, so that a retry or a
    /// duplicate the link delays by less than a request's lifetime is recognised.
    fn hold(&self) -> u64 {
        self.rules.lifetime().saturating_mul(2)
    }

    /// A checked frame arrived at `now`.
    pub fn on_frame(&mut self, now: u64, frame: &[u8]) -> Incoming<'_> {
        let key = match self.rules.heard(frame) {
            Ok(Heard::Command(key)) => key,
            Ok(Heard::Ack) => return Incoming::Ack,
            Err(e) => return Incoming::Unreadable(e),
        };
        if self.rules.watchdog.is_some_and(|w| w.key == key) {
            self.fed = Some((now, false));
        }
        if !self.handshaken {
            if Some(key) != self.rules.handshake {
                return Incoming::BeforeHandshake;
            }
            self.handshaken = true;
        }
        let answer = self.rules.expects(key, frame).answer != Answer::None;
        if self.rules.sequence.is_none() {
            return Incoming::Deliver { answer };
        }
        let ids = self.rules.ids(key, frame);
        let hold = self.hold();
        let mut free = None;
        let mut found = None;
        for (i, s) in self.seen.iter_mut().enumerate() {
            if s.is_some_and(|s| now.saturating_sub(s.at) > hold) {
                *s = None;
            }
            match s {
                Some(s) if s.ids == ids => found = Some(i),
                None => free = free.or(Some(i)),
                Some(_) => {}
            }
        }
        if let Some(i) = found {
            let sent = self.seen.get(i).copied().flatten().and_then(|s| s.answer);
            let bytes = self.seen.get(i).and_then(|s| s.as_ref());
            return Incoming::Duplicate(sent.and_then(|n| bytes.and_then(|s| s.frame.get(..n))));
        }
        let Some(slot) = free.and_then(|i| self.seen.get_mut(i)) else {
            return Incoming::Busy;
        };
        *slot = Some(Seen {
            ids,
            at: now,
            answer: None,
            frame: [0; FRAME],
        });
        Incoming::Deliver { answer }
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
        let key = match self.rules.heard(request).map_err(AnswerError::Request)? {
            Heard::Command(key) => key,
            Heard::Ack => return Err(AnswerError::Request(DecodeError::UnknownDirection)),
        };
        let ids = self.rules.ids(key, request);
        self.rules
            .write_repeats(&ids, answer)
            .ok_or(AnswerError::Encode(EncodeError::ValueOutOfRange))?;
        self.rules
            .packet
            .layout
            .seal(answer)
            .map_err(AnswerError::Encode)?;
        if self.rules.sequence.is_none() {
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
        let w = self.rules.watchdog?;
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
