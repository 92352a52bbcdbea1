//! The requester: the side that sends requests and waits for their answers. Every request
//! that expects an answer holds a slot of a fixed table until it resolves to exactly one
//! [`Resolution`]: its answer, a refusal (the spec's NACK, or an answer whose result value is
//! not a success) or a timeout after its retries (with the ids still to answer, for a request
//! answered once by each id it lists).
//!
//! Such a request is sent again whole when its wait lapses with ids still to answer: the
//! requester writes only the header values it owns and never rewrites a payload, so it cannot
//! list only the missing ids; an answer from an id that has answered already is then
//! `Unsolicited`, and costs the bus that answer's time only.

use super::ambiguity::Awaits;
use super::{Answer, Awaiting, Heard, Ids, Judged, SessionRef, SessionRules};
use crate::error::{DecodeError, EncodeError, Place};

/// A request that expects an answer, as [`Requester::send`] numbers it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Ticket(pub u32);

/// How a request ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Resolution {
    /// Its answer arrived (the frame passed to [`Requester::on_frame`]).
    Answered,
    /// The spec's NACK command answered it, or a frame of an empty direction that carries
    /// its command (MSP's error reply, `!`).
    Refused,
    /// Its answer arrived, and the answer's result value (the command's `result`) is not one
    /// that means success: a NACK that carries the value.
    Rejected(u64),
    /// No answer came within its timeout and retries.
    TimedOut,
    /// A request answered once by each id it lists ([`Fanout`](super::Fanout)) timed out after its retries
    /// with some of its answers: the ids that did not answer.
    Incomplete(super::IdSet),
}

/// A request's one outcome.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Outcome {
    /// The request.
    pub ticket: Ticket,
    /// How it ended.
    pub resolution: Resolution,
}

/// Why a request cannot be sent.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum SendError {
    /// The spec's handshake must be answered before this request.
    Handshake,
    /// Every slot holds an open request.
    Full,
    /// An open request is numbered `SLOTS` or more before this one: sending it would move
    /// the responder's window of remembered numbers past that request (it waits until the old
    /// one resolves).
    Window,
    /// A request is open that one frame could answer as well as this one (the same command to
    /// the same peer; a READ to a servo that an open SYNC_READ lists, or the other way
    /// round), and without a sequence number their answers could not be told apart (it waits
    /// until the open one resolves).
    Ambiguous,
    /// The frame is longer than a slot holds.
    TooLong,
    /// The request lists the ids that answer it, and the requester's
    /// [`SessionRef::Awaiting`] keeps no ids ([`NoFanout`](super::NoFanout)): its rules are
    /// not those it was sized for.
    Several,
    /// The frame is not a request (too short for its key, or an acknowledgement).
    NotARequest(DecodeError),
    /// The sequence number does not fit the frame, or sealing it failed.
    Encode(EncodeError),
}

/// What a frame that arrived at the requester is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Received {
    /// It resolves an open request (answer or refusal): the request's one outcome.
    Outcome(Outcome),
    /// It answers an open request with a result value that means the request is being
    /// carried out: the request stays open, is not sent again, and waits its current wait
    /// anew for the answer that ends it.
    Progress {
        /// The request.
        ticket: Ticket,
        /// The answer's result value.
        value: u64,
    },
    /// It answers an open request that lists several answerers ([`Fanout`](super::Fanout)), and answerers
    /// are still to come: the request stays open, and waits its current wait anew for the
    /// next. The last answer resolves it ([`Received::Outcome`]).
    Partial {
        /// The request.
        ticket: Ticket,
        /// The id of the device that answered.
        id: u8,
        /// How many listed ids are still to answer.
        waiting: usize,
    },
    /// It answers no open request: an unsolicited message (or an answer that came after its
    /// request resolved), for the application to handle as it does any message.
    Unsolicited,
    /// It cannot be read as a frame of the format.
    Unreadable(DecodeError),
}

/// What the passing of time asks for.
#[derive(Debug, PartialEq, Eq)]
pub enum Due<'a> {
    /// Send a request's frame again: a retry.
    Resend {
        /// The request.
        ticket: Ticket,
        /// Its frame, as first sent.
        frame: &'a [u8],
    },
    /// A request timed out after its retries.
    Outcome(Outcome),
}

#[derive(Debug, Clone, Copy)]
struct Open<W> {
    ticket: Ticket,
    ids: Ids,
    answer: Answer,
    deadline: u64,
    wait: u64,
    retries_left: u8,
    backoff: u8,
    /// The ids still to answer a request of several answers, and whether one has answered.
    fanout: Option<W>,
}

/// A slot of the table: an open request and the bytes of its frame, for retries.
#[derive(Debug, Clone, Copy)]
struct Slot<W, const FRAME: usize> {
    open: Option<Open<W>>,
    frame: [u8; FRAME],
    len: usize,
}

/// The requester's state machine: at most `SLOTS` open requests of frames of at most `FRAME`
/// bytes.
///
/// `S` is where it finds its rules ([`SessionRef`]): a generated module's `Session` (its
/// `Requester` alias names this type with it), or a `&SessionRules` built at run time, as here.
///
/// ```
/// use protocol_runtime::session::{Answer, Exchange, Requester, Received, Resolution, SessionRules};
/// use protocol_runtime::layout::{ByteOrder, Check, FrameLayout, LengthRule, Pos, WordField};
/// use protocol_runtime::{Checksum, PacketRules};
///
/// // `AA seq cmd payload sum8`: every frame is 4 bytes.
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
///     default: Exchange { key: 0, answer: Answer::Reply, timeout: 50, retries: 1, backoff: 2 },
///     exchanges: &[],
///     sequence: Some(WordField::le(1, 1)), echo: &[], swap: None, pairs: &[], nack: None,
///     refusals: &[],
///     handshake: None, watchdog: None, modes: None, verdicts: &[],
///     periodic: &[], fanouts: &[],
/// };
///
/// let mut requester = Requester::<_, 4, 4>::new(&SESSION);
/// let mut frame = [0xAA, 0, 7, 0];
/// let ticket = requester.send(0, &mut frame)?.expect("an answer is expected");
/// assert_eq!(frame, [0xAA, 0, 7, 0xB1]); // numbered 0 and sealed
///
/// // No answer within 50 ms: the request is sent again, then waits 100 ms.
/// assert!(matches!(requester.poll(50), Some(protocol_runtime::session::Due::Resend { .. })));
/// let answer = [0xAA, 0, 7, 0xB1];
/// let Received::Outcome(outcome) = requester.on_frame(60, &answer) else { panic!() };
/// assert_eq!((outcome.ticket, outcome.resolution), (ticket, Resolution::Answered));
/// assert_eq!(requester.on_frame(61, &answer), Received::Unsolicited); // a late duplicate
/// # Ok::<(), protocol_runtime::session::SendError>(())
/// ```
#[derive(Debug, Clone)]
pub struct Requester<S: SessionRef, const SLOTS: usize, const FRAME: usize> {
    rules: S,
    slots: [Slot<S::Awaiting, FRAME>; SLOTS],
    next_seq: u64,
    next_ticket: u32,
    handshaken: bool,
}

impl<S: SessionRef, const SLOTS: usize, const FRAME: usize> Requester<S, SLOTS, FRAME> {
    /// A requester with no open request; before its handshake when the rules have one.
    #[must_use]
    pub fn new(rules: S) -> Self {
        Self {
            rules,
            slots: [Slot {
                open: None,
                frame: [0; FRAME],
                len: 0,
            }; SLOTS],
            next_seq: 0,
            next_ticket: 0,
            handshaken: rules.session().handshake.is_none(),
        }
    }

    /// True once the handshake is answered (always, without a handshake).
    #[must_use]
    pub fn handshaken(&self) -> bool {
        self.handshaken
    }

    /// The number of open requests.
    #[must_use]
    pub fn open(&self) -> usize {
        self.slots.iter().filter(|s| s.open.is_some()).count()
    }

    /// True when the open request `ticket` is answered once by each id it lists
    /// ([`Fanout`](super::Fanout)).
    #[must_use]
    pub fn several(&self, ticket: Ticket) -> bool {
        self.slots
            .iter()
            .filter_map(|s| s.open)
            .any(|o| o.ticket == ticket && o.fanout.is_some())
    }

    /// The earliest instant at which [`poll`](Self::poll) has something to do.
    #[must_use]
    pub fn next_deadline(&self) -> Option<u64> {
        self.slots
            .iter()
            .filter_map(|s| s.open.map(|o| o.deadline))
            .min()
    }

    /// The application sends the request `frame` (assembled by its encoder) at `now`: the
    /// requester writes the next sequence number into it and seals it; the caller transmits
    /// the frame as it then is. Returns the request's ticket when it expects an answer (the
    /// ticket's one [`Outcome`] comes from [`on_frame`](Self::on_frame) or
    /// [`poll`](Self::poll)), `None` when it expects none.
    ///
    /// # Errors
    ///
    /// [`SendError`]; nothing is sent and no sequence number is used.
    pub fn send(&mut self, now: u64, frame: &mut [u8]) -> Result<Option<Ticket>, SendError> {
        let owner = self.rules;
        let rules = owner.session();
        let key = match rules.heard(frame).map_err(SendError::NotARequest)? {
            Heard::Command(key) if !rules.refuses(frame) => key,
            _ => return Err(SendError::NotARequest(DecodeError::UnknownDirection)),
        };
        if !self.handshaken && Some(key) != rules.handshake {
            return Err(SendError::Handshake);
        }
        let e = rules.expects(key, frame);
        if e.answer == Answer::None {
            self.check_window()?;
            self.number(frame)?;
            return Ok(None);
        }
        if frame.len() > FRAME {
            return Err(SendError::TooLong);
        }
        let fanout = match rules
            .fanout(key)
            .and_then(|f| f.listed(rules.packet, frame))
        {
            Some(ids) => Some(S::Awaiting::keep(ids).ok_or(SendError::Several)?),
            None => None,
        };
        let ids = rules.ids(key, frame);
        let index = self.free_slot(Awaits {
            ids: &ids,
            answer: e.answer,
            several: fanout.map(|w| w.waiting()),
        })?;
        self.check_window()?;
        self.number(frame)?;
        let ticket = Ticket(self.next_ticket);
        self.next_ticket = self.next_ticket.wrapping_add(1);
        let slot = self.slots.get_mut(index).ok_or(SendError::Full)?;
        let stored = slot
            .frame
            .get_mut(..frame.len())
            .ok_or(SendError::TooLong)?;
        stored.copy_from_slice(frame);
        slot.len = frame.len();
        let wait = u64::from(e.timeout);
        slot.open = Some(Open {
            ticket,
            // Read again: numbering wrote the sequence number.
            ids: rules.ids(key, frame),
            answer: e.answer,
            deadline: now.saturating_add(wait),
            wait,
            retries_left: e.retries,
            backoff: e.backoff.max(1),
            fanout,
        });
        Ok(Some(ticket))
    }

    /// A free slot for the request `new`; without a sequence number, none while a request is
    /// open that one frame could answer as well as `new` (a request of the same command to
    /// the same peer; a READ to a servo that an open SYNC_READ lists).
    fn free_slot(&self, new: Awaits<'_>) -> Result<usize, SendError> {
        let rules = self.rules.session();
        if rules.sequence.is_none() {
            let shared = self.slots.iter().filter_map(|s| s.open).any(|o| {
                let open = Awaits {
                    ids: &o.ids,
                    answer: o.answer,
                    several: o.fanout.map(|w| w.waiting()),
                };
                rules.share_answer(open, new)
            });
            if shared {
                return Err(SendError::Ambiguous);
            }
        }
        self.slots
            .iter()
            .position(|s| s.open.is_none())
            .ok_or(SendError::Full)
    }

    /// Rule: no open request is `SLOTS` or more numbers before the next one.
    fn check_window(&self) -> Result<(), SendError> {
        let Some(f) = self.rules.session().sequence else {
            return Ok(());
        };
        let next = self.next_seq & f.max_value();
        let wide = self
            .slots
            .iter()
            .filter_map(|s| s.open)
            .any(|o| (next.wrapping_sub(o.ids.seq) & f.max_value()) >= SLOTS as u64);
        if wide { Err(SendError::Window) } else { Ok(()) }
    }

    /// Writes the next sequence number into `frame` and seals it.
    fn number(&mut self, frame: &mut [u8]) -> Result<(), SendError> {
        let owner = self.rules;
        let rules = owner.session();
        if let Some(f) = rules.sequence {
            let seq = self.next_seq & f.max_value();
            f.write(frame, seq)
                .ok_or(SendError::Encode(EncodeError::ValueOutOfRange {
                    place: Place::NONE,
                }))?;
            self.next_seq = seq.wrapping_add(1) & f.max_value();
        }
        rules.packet.layout.seal(frame).map_err(SendError::Encode)
    }

    /// A checked frame arrived at `now`: the outcome of the open request it answers or refuses
    /// (the oldest, should several match), a progress answer, or an unsolicited message.
    pub fn on_frame(&mut self, now: u64, frame: &[u8]) -> Received {
        let owner = self.rules;
        let rules = owner.session();
        let heard = match rules.heard(frame) {
            Ok(h) => h,
            Err(e) => return Received::Unreadable(e),
        };
        let Some((i, judged, ticket)) = self.matching(heard, frame) else {
            return Received::Unsolicited;
        };
        let Some(slot) = self.slots.get_mut(i) else {
            return Received::Unsolicited;
        };
        if judged == Some(Judged::Accepted)
            && let Some(part) = Self::one_of_several(rules, slot, now, frame)
        {
            return part;
        }
        let resolution = match judged {
            Some(Judged::Progress(value)) => {
                if let Some(o) = slot.open.as_mut() {
                    o.retries_left = 0;
                    o.deadline = now.saturating_add(o.wait);
                }
                return Received::Progress { ticket, value };
            }
            Some(Judged::Rejected(value)) => Resolution::Rejected(value),
            Some(Judged::Accepted) => Resolution::Answered,
            None => Resolution::Refused,
        };
        if let Some(o) = slot.open.take()
            && Some(o.ids.key) == rules.handshake
            && resolution == Resolution::Answered
        {
            self.handshaken = true;
        }
        Received::Outcome(Outcome { ticket, resolution })
    }

    /// Rule: an answer to a request of several answers takes its sender off the ids the
    /// request waits for; while some remain, the request waits its wait anew for the next
    /// (`Partial`); the last lets the answer resolve it (`None`).
    fn one_of_several(
        rules: &SessionRules<'_>,
        slot: &mut Slot<S::Awaiting, FRAME>,
        now: u64,
        frame: &[u8],
    ) -> Option<Received> {
        let o = slot.open.as_mut()?;
        let id = rules.fanout(o.ids.key)?.sender(frame)?;
        let waiting = o.fanout.as_mut()?.answered(id);
        if waiting == 0 {
            return None;
        }
        o.deadline = now.saturating_add(o.wait);
        Some(Received::Partial {
            ticket: o.ticket,
            id,
            waiting,
        })
    }

    /// Whether `frame` comes from an id that the open request `o` still waits for (always,
    /// for a request of one answer).
    fn awaited(rules: &SessionRules<'_>, o: &Open<S::Awaiting>, frame: &[u8]) -> bool {
        let Some(waiting) = o.fanout else {
            return true;
        };
        rules
            .fanout(o.ids.key)
            .and_then(|f| f.sender(frame))
            .is_some_and(|id| waiting.awaits(id))
    }

    /// The open request `frame` answers or refuses (the oldest, should several match): its
    /// slot, what the answer says (`Some`: an answer, judged by the command's result value
    /// when it has one; `None`: the NACK, or a frame of a refusing direction that carries the
    /// request's command) and its ticket.
    fn matching(&self, heard: Heard, frame: &[u8]) -> Option<(usize, Option<Judged>, Ticket)> {
        let rules = self.rules.session();
        let refusal = rules.refuses(frame);
        let refuses = matches!(heard, Heard::Command(k) if Some(k) == rules.nack);
        let mut found: Option<(usize, Option<Judged>, Ticket)> = None;
        for (i, s) in self.slots.iter().enumerate() {
            let Some(o) = s
                .open
                .filter(|o| rules.repeats(&o.ids, frame) && Self::awaited(rules, o, frame))
            else {
                continue;
            };
            let judged = if refusal {
                // An error reply refuses the request it repeats the command of, whatever that
                // request expects; it is never an answer.
                if heard != Heard::Command(o.ids.key) {
                    continue;
                }
                None
            } else if SessionRules::is_answer(o.answer, o.ids.key, heard) {
                match rules.verdict(o.ids.key) {
                    // An answer without the value is not of the kind the request expects.
                    Some(v) => match v.judge(rules.packet, frame) {
                        Some(j) => Some(j),
                        None => continue,
                    },
                    None => Some(Judged::Accepted),
                }
            } else if refuses {
                None
            } else {
                continue;
            };
            if found.is_none_or(|(_, _, t)| o.ticket < t) {
                found = Some((i, judged, o.ticket));
            }
        }
        found
    }

    /// Time advanced to `now`: a retry to send, or a request that timed out; `None` when
    /// nothing is due. Call it until it returns `None`.
    pub fn poll(&mut self, now: u64) -> Option<Due<'_>> {
        let (i, _) = self
            .slots
            .iter()
            .enumerate()
            .filter_map(|(i, s)| s.open.map(|o| (i, o.deadline)))
            .filter(|&(_, d)| d <= now)
            .min_by_key(|&(_, d)| d)?;
        let slot = self.slots.get_mut(i)?;
        let mut o = slot.open?;
        if o.retries_left == 0 {
            slot.open = None;
            let resolution = match o.fanout.and_then(|w| w.incomplete()) {
                Some(waiting) => Resolution::Incomplete(waiting),
                None => Resolution::TimedOut,
            };
            return Some(Due::Outcome(Outcome {
                ticket: o.ticket,
                resolution,
            }));
        }
        o.retries_left = o.retries_left.saturating_sub(1);
        o.wait = o.wait.saturating_mul(u64::from(o.backoff));
        o.deadline = now.saturating_add(o.wait);
        slot.open = Some(o);
        let frame = slot.frame.get(..slot.len)?;
        Some(Due::Resend {
            ticket: o.ticket,
            frame,
        })
    }
}
