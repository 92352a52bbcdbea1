//! The conversation of a link as data, and the sans-IO state machines that hold it: which
//! answer a request expects (the same command back, the format's acknowledgement, another
//! command, or none), how an answer is matched to its request (the command, a sequence number
//! and further header values it repeats, the addresses it swaps), timeouts, retries and their
//! backoff, a handshake that must precede other requests, a command that must keep arriving
//! (a watchdog), commands sent at a fixed rate, and duplicate suppression by sequence number.
//!
//! As [`PacketRules`] is for packets, a [`SessionRules`] is one value that generated code holds
//! as a `static` (`SESSION`, handed out as the zero-sized type `Session`) and the run-time
//! codec builds from a spec. The machines, [`Requester`] and [`Responder`], execute it over
//! frames the engine has checked, reaching it through a [`SessionRef`]: they read
//! the key, the acknowledgement flag and header values through the packet rules and the word
//! fields of the session rules, write the values they assign (the sequence number, the values
//! an answer repeats) into a frame and seal it through the frame rules. They hold no I/O and no
//! clock: time is passed in as a monotonic instant in milliseconds, and each step returns what
//! to transmit and what to deliver. Their tables are fixed arrays sized by const generics: no
//! heap.
//!
//! This module does not decode payloads (the packet code does) nor read the wire.

use crate::error::DecodeError;
use crate::layout::WordField;
use crate::rules::PacketRules;

mod ambiguity;
#[cfg(feature = "tokio")]
pub mod client;
mod fanout;
#[cfg(feature = "embedded-io-async")]
pub mod io_async;
mod observer;
mod pairs;
mod reply;
mod requester;
mod responder;
mod scheduler;
mod verdict;

pub use fanout::{Awaited, Awaiting, Fanout, IdSet, NoFanout};
pub use observer::{Observer, Paired};
pub use pairs::{Pair, ValueAt};
pub use reply::Reply;
pub use requester::{Due, Outcome, Received, Requester, Resolution, SendError, Ticket};
pub use responder::{Alarm, AnswerError, Incoming, Responder};
pub use scheduler::{Periodic, Scheduler, Sender};
pub use verdict::{Judged, Verdict};

/// The answer a request expects.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Answer {
    /// None: the request is sent once and forgotten.
    None,
    /// The same command, sent back (HFLink: a READ's reply, a SET's empty acknowledgement).
    Reply,
    /// The format's acknowledgement (a frame whose ack flag is set).
    Ack,
    /// Another command, by its key (Dynamixel: a STATUS packet).
    Command(u64),
    /// A frame of the answer direction that carries one struct in place of a command
    /// (Dynamixel 1.0's status packet, whose error byte sits where an instruction does): any
    /// frame that repeats what the request says answers it.
    Message,
}

/// What a request of one command expects.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Exchange {
    /// The command's key, as [`PacketRules::key`] reads it.
    pub key: u64,
    /// The answer it expects.
    pub answer: Answer,
    /// Milliseconds to wait for the answer before the first retry (or the timeout).
    pub timeout: u32,
    /// Times the request is sent again before it times out.
    pub retries: u8,
    /// Each retry waits this many times longer than the one before (1: a fixed wait).
    pub backoff: u8,
}

impl Exchange {
    /// The longest a request lives: its first wait and every retry's, in milliseconds.
    #[must_use]
    pub fn lifetime(&self) -> u64 {
        let mut wait = u64::from(self.timeout);
        let mut total = wait;
        for _ in 0..self.retries {
            wait = wait.saturating_mul(u64::from(self.backoff.max(1)));
            total = total.saturating_add(wait);
        }
        total
    }
}

/// A command that must keep arriving: the receiver reports when `period` milliseconds pass
/// without one.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Watchdog {
    /// The command's key.
    pub key: u64,
    /// Longest gap between two of its frames, in milliseconds.
    pub period: u32,
}

/// A header value that says, per request, whether it expects an answer (RoboRTS's session id:
/// 0 none, 1 an answer without retries, 2 to 31 an answer with retries).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Modes {
    /// The header value.
    pub field: WordField,
    /// Values `first ..= last` of a request that expects no answer.
    pub none: Option<(u64, u64)>,
    /// Values `first ..= last` of a request that expects its answer but is sent once.
    pub once: Option<(u64, u64)>,
}

impl Modes {
    /// True when a request whose header value is `value` expects no answer.
    #[must_use]
    pub fn silent(&self, value: u64) -> bool {
        self.none.is_some_and(|(a, b)| a <= value && value <= b)
    }
}

/// The conversation of a frame format.
#[derive(Debug, Clone, Copy)]
pub struct SessionRules<'a> {
    /// The packet rules the frames are read through (key, acknowledgement flag) and sealed by.
    pub packet: &'a PacketRules<'a>,
    /// What a request of a command that [`exchanges`](Self::exchanges) does not list expects
    /// (its `key` is not read).
    pub default: Exchange,
    /// The commands whose requests expect otherwise than the default, in spec order.
    pub exchanges: &'a [Exchange],
    /// The header value the requester numbers and an answer repeats; the responder suppresses
    /// duplicates by it.
    pub sequence: Option<WordField>,
    /// Further header values an answer repeats from its request (at most
    /// [`MAX_ECHO`](Self::MAX_ECHO)).
    pub echo: &'a [WordField],
    /// The address values `(sender, receiver)` an answer swaps.
    pub swap: Option<(WordField, WordField)>,
    /// Values the answer to a request of one command repeats from it under other names (at
    /// most [`MAX_PAIRS`](Self::MAX_PAIRS) per command), in spec order.
    pub pairs: &'a [Pair],
    /// The key of a command that answers an open request as a refusal.
    pub nack: Option<u64>,
    /// The directions (indices into the packet rules'
    /// [`directions`](PacketRules::directions)) whose frames refuse the open request of the
    /// command they carry: the spec's empty directions (MSP's error replies, `!`, which repeat
    /// the refused command's id with no payload). Such a frame is never an answer.
    pub refusals: &'a [usize],
    /// The key of a command whose answered request precedes every other request.
    pub handshake: Option<u64>,
    /// A command that must keep arriving.
    pub watchdog: Option<Watchdog>,
    /// A header value that says whether a request expects an answer.
    pub modes: Option<Modes>,
    /// The commands whose answers tell success from refusal by a value (at most one per
    /// command), in spec order.
    pub verdicts: &'a [Verdict<'a>],
    /// The commands sent at a fixed rate, in spec order ([`Scheduler`]).
    pub periodic: &'a [Periodic],
    /// The commands whose requests are answered once by each id they list, in spec order.
    pub fanouts: &'a [Fanout],
}

/// Where a session machine finds its [`SessionRules`]: a reference to rules built at run time
/// (the run-time codec), or a zero-sized type whose [`session`](Self::session) returns a
/// `static` (generated code's `Session`).
///
/// Why a trait and not always a reference, as for
/// [`LayoutRef`](crate::layout::LayoutRef): a machine reads the rules on
/// every frame (the key, the sequence number, the values an answer repeats) and seals frames
/// through their layout. Through a reference held in a field those reads stay reads, and every
/// checksum the runtime knows is linked to seal a frame; through a zero-sized type they are
/// reads of a constant, which the compiler folds: a firmware links the checks its spec uses.
///
/// ```
/// use protocol_runtime::layout::{FrameLayout, LengthRule, WordField};
/// use protocol_runtime::session::{Answer, Exchange, SessionRef, SessionRules};
/// use protocol_runtime::PacketRules;
///
/// static LAYOUT: FrameLayout<'static> = FrameLayout {
///     sync: &[0xAA], sync_set: &[], header_len: 2, min_len: 2, max_len: 2,
///     length: LengthRule::Fixed(2), constants: &[], header_checks: &[], frame_checks: &[],
///     markers: &[],
///     escape: None,
/// };
/// static RULES: PacketRules<'static> = PacketRules {
///     layout: &LAYOUT, header_len: 2, trailer_len: 0, max_payload: 0,
///     key: &[WordField::le(1, 1)], ack: None, directions: &[], stuffing: None,
///     truncate_zeros: false,
/// };
/// static SESSION: SessionRules<'static> = SessionRules {
///     packet: &RULES,
///     default: Exchange { key: 0, answer: Answer::Reply, timeout: 50, retries: 0, backoff: 1 },
///     exchanges: &[], sequence: None, echo: &[], swap: None, pairs: &[], nack: None,
///     refusals: &[], handshake: None, watchdog: None, modes: None, verdicts: &[],
///     periodic: &[], fanouts: &[],
/// };
///
/// #[derive(Clone, Copy)]
/// struct Session;
/// impl SessionRef for Session {
///     // No command of these rules is answered by several frames: the requester's slots keep
///     // no id set.
///     type Awaiting = protocol_runtime::session::NoFanout;
///     #[inline(always)]
///     fn session(&self) -> &SessionRules<'_> {
///         &SESSION
///     }
/// }
/// assert_eq!(Session.session().lifetime(), (&SESSION).session().lifetime());
/// ```
///
/// The same choice sizes the requester: [`Awaiting`](Self::Awaiting) is what each of its slots
/// keeps of a request answered by several frames, an id set where the rules list such a
/// command and nothing where they do not. Generated code picks it from the spec; rules built at
/// run time may list any, so a reference keeps the set.
pub trait SessionRef: Copy {
    /// What a requester's slot keeps of a request answered once by each id it lists:
    /// [`Awaited`] when [`fanouts`](SessionRules::fanouts) may list a command, [`NoFanout`]
    /// when it lists none (a requester refuses such a request with
    /// [`SendError::Several`]).
    type Awaiting: Awaiting;

    /// The conversation.
    fn session(&self) -> &SessionRules<'_>;
}

impl<'s> SessionRef for &'s SessionRules<'s> {
    type Awaiting = Awaited;

    #[inline(always)]
    fn session(&self) -> &SessionRules<'_> {
        self
    }
}

/// The frame format of a session's frames, as the engine finds it: a constant when the
/// session is one.
#[cfg(any(feature = "tokio", feature = "embedded-io-async"))]
#[derive(Debug, Clone, Copy)]
pub(crate) struct SessionLayout<S>(pub S);

#[cfg(any(feature = "tokio", feature = "embedded-io-async"))]
impl<S: SessionRef> crate::layout::LayoutRef for SessionLayout<S> {
    #[inline(always)]
    fn layout(&self) -> &crate::layout::FrameLayout<'_> {
        self.0.session().packet.layout
    }
}

/// What a checked frame is, as the conversation reads it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Heard {
    /// An acknowledgement.
    Ack,
    /// A command, by its key.
    Command(u64),
}

/// The values that identify a request: its key, sequence number, repeated and address values.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) struct Ids {
    pub key: u64,
    pub seq: u64,
    pub values: [u64; SessionRules::MAX_ECHO],
    pub from: u64,
    pub to: u64,
    pub paired: [u64; SessionRules::MAX_PAIRS],
}

impl SessionRules<'_> {
    /// The most header values an answer repeats besides the sequence number.
    pub const MAX_ECHO: usize = 2;

    /// The most values an answer repeats from a request of one command under other names.
    pub const MAX_PAIRS: usize = 6;

    /// What `frame` is: an acknowledgement, or a command and its key.
    ///
    /// # Errors
    ///
    /// The errors of [`PacketRules::ack_data`] and [`PacketRules::key`].
    pub fn heard(&self, frame: &[u8]) -> Result<Heard, DecodeError> {
        if self.packet.ack_data(frame)?.is_some() {
            return Ok(Heard::Ack);
        }
        Ok(Heard::Command(self.packet.key(frame)?))
    }

    /// Whether `frame` is of a direction that refuses the request of its command
    /// ([`refusals`](Self::refusals)); false when the rules list none.
    #[must_use]
    pub fn refuses(&self, frame: &[u8]) -> bool {
        !self.refusals.is_empty()
            && self
                .packet
                .direction(frame)
                .is_ok_and(|d| self.refusals.contains(&d))
    }

    /// What a request of command `key` expects: its exchange, or the default.
    #[must_use]
    pub fn exchange(&self, key: u64) -> Exchange {
        self.exchanges
            .iter()
            .find(|e| e.key == key)
            .copied()
            .unwrap_or(Exchange {
                key,
                ..self.default
            })
    }

    /// What the request `frame` of command `key` expects, its modes applied. A request that
    /// lists the ids that answer it ([`fanouts`](Self::fanouts)) expects them whatever its
    /// modes value says (a SYNC_READ goes to the broadcast id, which otherwise expects no
    /// answer), and nothing when it lists none.
    #[must_use]
    pub fn expects(&self, key: u64, frame: &[u8]) -> Exchange {
        let mut e = self.exchange(key);
        if let Some(f) = self.fanout(key) {
            if f.listed(self.packet, frame)
                .is_none_or(|ids| ids.is_empty())
            {
                e.answer = Answer::None;
            }
            return e;
        }
        if let Some(m) = self.modes
            && let Some(v) = m.field.read(frame)
        {
            if m.silent(v) {
                e.answer = Answer::None;
            } else if m.once.is_some_and(|(a, b)| a <= v && v <= b) {
                e.retries = 0;
            }
        }
        e
    }

    /// Whether a frame heard as `heard` is the answer `answer` that a request of command `key`
    /// expects (the values it repeats of the request are checked apart).
    #[must_use]
    pub fn is_answer(answer: Answer, key: u64, heard: Heard) -> bool {
        match (answer, heard) {
            (Answer::Reply, Heard::Command(k)) => k == key,
            (Answer::Ack, Heard::Ack) => true,
            (Answer::Command(c), Heard::Command(k)) => k == c,
            (Answer::Message, Heard::Command(_)) => true,
            _ => false,
        }
    }

    /// The longest any request lives (its waits and retries), in milliseconds.
    #[must_use]
    pub fn lifetime(&self) -> u64 {
        self.exchanges
            .iter()
            .map(Exchange::lifetime)
            .fold(self.default.lifetime(), u64::max)
    }

    /// The values that identify the request `frame` of command `key` (those of its fields the
    /// frame holds; a value it lacks reads as 0).
    pub(crate) fn ids(&self, key: u64, frame: &[u8]) -> Ids {
        let read = |f: Option<WordField>| f.and_then(|f| f.read(frame)).unwrap_or(0);
        let mut ids = Ids {
            key,
            seq: read(self.sequence),
            from: read(self.swap.map(|s| s.0)),
            to: read(self.swap.map(|s| s.1)),
            ..Ids::default()
        };
        for (slot, f) in ids.values.iter_mut().zip(self.echo) {
            *slot = f.read(frame).unwrap_or(0);
        }
        for (slot, p) in ids.paired.iter_mut().zip(self.pairs_of(key)) {
            *slot = p.from.read(self.packet, frame).unwrap_or(0);
        }
        ids
    }

    /// How the answer to a request of command `key` tells success from refusal, if it does.
    #[must_use]
    pub fn verdict(&self, key: u64) -> Option<&Verdict<'_>> {
        self.verdicts.iter().find(|v| v.request == key)
    }

    /// How the ids that answer a request of command `key` are listed, when several answer it.
    #[must_use]
    pub fn fanout(&self, key: u64) -> Option<&Fanout> {
        self.fanouts.iter().find(|f| f.request == key)
    }

    /// The pairs of requests of command `key`.
    fn pairs_of(&self, key: u64) -> impl Iterator<Item = &Pair> {
        self.pairs.iter().filter(move |p| p.request == key)
    }

    /// The header value that each answer to a request of command `key` sets for itself (the
    /// id of the device that answers a request of several answers), which it does not repeat
    /// from the request.
    pub(crate) fn own_value(&self, key: u64) -> Option<WordField> {
        self.fanout(key).map(|f| f.id)
    }

    /// Whether `frame` repeats what its request `ids` told (the sequence number, the echoed
    /// values) and swaps its addresses; a value the answer sets for itself is not compared.
    pub(crate) fn repeats(&self, ids: &Ids, frame: &[u8]) -> bool {
        let own = self.own_value(ids.key);
        let is = |f: Option<WordField>, v: u64| {
            f.is_none_or(|f| Some(f) == own || f.read(frame) == Some(v))
        };
        is(self.sequence, ids.seq)
            && self
                .echo
                .iter()
                .zip(ids.values)
                .all(|(&f, v)| is(Some(f), v))
            && is(self.swap.map(|s| s.0), ids.to)
            && is(self.swap.map(|s| s.1), ids.from)
            && self
                .pairs_of(ids.key)
                .zip(ids.paired)
                .all(|(p, v)| p.to.read(self.packet, frame) == Some(v))
    }

    /// Writes into the answer `frame` what it repeats from its request `ids` (the sequence
    /// number, the echoed values, the swapped addresses); `None` if a value does not fit. The
    /// values of [`pairs`](Self::pairs) are the application's to set: they may lie in the
    /// payload, which is sealed in the frame; so is a value the answer sets for itself (the
    /// answering device's id, for a request of several answers).
    pub(crate) fn write_repeats(&self, ids: &Ids, frame: &mut [u8]) -> Option<()> {
        let own = self.own_value(ids.key);
        let mut put = |f: Option<WordField>, v: u64| match f {
            Some(f) if Some(f) != own => f.write(frame, v),
            _ => Some(()),
        };
        put(self.sequence, ids.seq)?;
        for (&f, v) in self.echo.iter().zip(ids.values) {
            put(Some(f), v)?;
        }
        if let Some((from, to)) = self.swap {
            put(Some(from), ids.to)?;
            put(Some(to), ids.from)?;
        }
        Some(())
    }
}

#[cfg(test)]
mod tests;
#[cfg(test)]
mod tests_fanout;
#[cfg(test)]
mod tests_refusal;
