//! Periodic messages, the sending side: commands a side sends at a fixed rate (MAVLink's
//! HEARTBEAT at 1 Hz, a base's velocity command that its watchdog expects). The [`Scheduler`]
//! tells the application, for the instant passed in, which of them is due; the application
//! builds and sends each (its values are the application's). `no_std`, no heap: one deadline
//! per periodic command, in a table sized by the spec.
//!
//! The receiving side's check (a command that must keep arriving) is the responder's watchdog.

use super::SessionRef;

/// Which side of the link sends a periodic command.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Sender {
    /// The side that sends requests (the host, the ground station).
    Requester,
    /// The side that answers them (the device).
    Responder,
    /// Both sides.
    Both,
}

impl Sender {
    /// Whether `side` (a requester or a responder, not `Both`) sends such a command.
    #[must_use]
    pub fn includes(self, side: Sender) -> bool {
        self == Sender::Both || self == side
    }
}

/// A command sent every `period` milliseconds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Periodic {
    /// The command's key.
    pub key: u64,
    /// Milliseconds between two of its frames.
    pub period: u32,
    /// Which side sends it.
    pub sender: Sender,
}

/// When each periodic command of one side is next due: at most `N` of them (the spec's
/// count; a generated module's `Scheduler` alias names it).
///
/// Each command is due first at the instant the scheduler starts, then every period after the
/// instant it was last due: a late [`poll`](Self::poll) does not shift the rate, and a poll
/// later than a whole period sends once and resumes the rate from the instant passed in (no
/// burst of missed frames).
///
/// ```
/// use protocol_runtime::layout::{FrameLayout, LengthRule, WordField};
/// use protocol_runtime::session::{Answer, Exchange, Periodic, Scheduler, Sender, SessionRules};
/// use protocol_runtime::PacketRules;
///
/// static LAYOUT: FrameLayout<'static> = FrameLayout {
///     sync: &[0xAA], sync_set: &[], header_len: 2, min_len: 2, max_len: 2,
///     length: LengthRule::Fixed(2), constants: &[], header_checks: &[], frame_checks: &[],
///     markers: &[], escape: None,
/// };
/// static RULES: PacketRules<'static> = PacketRules {
///     layout: &LAYOUT, header_len: 2, trailer_len: 0, max_payload: 0,
///     key: &[WordField::le(1, 1)], ack: None, directions: &[], stuffing: None,
///     truncate_zeros: false,
/// };
/// static SESSION: SessionRules<'static> = SessionRules {
///     packet: &RULES,
///     default: Exchange { key: 0, answer: Answer::None, timeout: 50, retries: 0, backoff: 1 },
///     exchanges: &[], sequence: None, echo: &[], swap: None, pairs: &[], nack: None,
///     refusals: &[],
///     handshake: None, watchdog: None, modes: None, verdicts: &[],
///     periodic: &[
///         Periodic { key: 0, period: 1000, sender: Sender::Both },
///         Periodic { key: 5, period: 20, sender: Sender::Requester },
///     ],
///     fanouts: &[],
/// };
///
/// let mut host = Scheduler::<_, 2>::new(&SESSION, Sender::Requester, 0);
/// assert_eq!(host.poll(0), Some(0)); // both are due at the start
/// assert_eq!(host.poll(0), Some(5));
/// assert_eq!((host.poll(0), host.next_deadline()), (None, Some(20)));
/// assert_eq!(host.poll(25), Some(5)); // late: the next one is still due at 40
/// assert_eq!(host.next_deadline(), Some(40));
///
/// // The device sends the heartbeat alone.
/// let mut device = Scheduler::<_, 2>::new(&SESSION, Sender::Responder, 0);
/// assert_eq!((device.poll(0), device.poll(0)), (Some(0), None));
/// assert_eq!(device.next_deadline(), Some(1000));
/// ```
#[derive(Debug, Clone)]
pub struct Scheduler<S, const N: usize> {
    rules: S,
    /// Per periodic command of the rules (the first `N`): when it is next due, `None` for one
    /// the other side sends.
    due: [Option<u64>; N],
}

impl<S: SessionRef, const N: usize> Scheduler<S, N> {
    /// The scheduler of `side` (`Sender::Requester` or `Sender::Responder`), started at
    /// `now`: every periodic command that side sends is due at once.
    #[must_use]
    pub fn new(rules: S, side: Sender, now: u64) -> Self {
        let mut due = [None; N];
        for (slot, p) in due.iter_mut().zip(rules.session().periodic) {
            if p.sender.includes(side) {
                *slot = Some(now);
            }
        }
        Self { rules, due }
    }

    /// The earliest instant at which [`poll`](Self::poll) has a command to send.
    #[must_use]
    pub fn next_deadline(&self) -> Option<u64> {
        self.due.iter().flatten().copied().min()
    }

    /// Time advanced to `now`: the key of a periodic command due (the earliest, in spec order
    /// at a tie), scheduled again a period later; `None` when none is due. Call it until it
    /// returns `None`, and send a frame of each command it returns.
    pub fn poll(&mut self, now: u64) -> Option<u64> {
        let owner = self.rules;
        let periodic = owner.session().periodic;
        let (i, at) = self
            .due
            .iter()
            .enumerate()
            .filter_map(|(i, d)| d.map(|d| (i, d)))
            .filter(|&(_, d)| d <= now)
            .min_by_key(|&(i, d)| (d, i))?;
        let p = periodic.get(i)?;
        let next = at.saturating_add(u64::from(p.period.max(1)));
        let slot = self.due.get_mut(i)?;
        *slot = Some(if next <= now {
            now.saturating_add(u64::from(p.period.max(1)))
        } else {
            next
        });
        Some(p.key)
    }

    /// The application sent command `key` at `now` on its own (a velocity command the user
    /// just changed): its next periodic frame is due a period after `now`.
    pub fn sent(&mut self, now: u64, key: u64) {
        let owner = self.rules;
        let periodic = owner.session().periodic;
        for (slot, p) in self.due.iter_mut().zip(periodic) {
            if p.key == key && slot.is_some() {
                *slot = Some(now.saturating_add(u64::from(p.period.max(1))));
            }
        }
    }
}
