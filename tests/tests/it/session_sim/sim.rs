//! One simulated conversation: a requester and a responder (the runtime's session machines,
//! over a spec's generated `Session`), an application on each side, a lossy [`Link`] and a
//! clock advanced one millisecond at a time. Every call into a machine runs under the counting
//! allocator. The run records what the invariants are checked against.

use std::collections::HashMap;

use protocol_kit::session::{
    Due, Incoming, Received, Requester, Resolution, Responder, SessionRef, Ticket,
};

use super::link::{DOWN, Fault, Faults, Link, UP};

/// The bytes a slot holds: the largest request or answer the peers build.
pub const FRAME: usize = 64;
/// The requester's open requests and the responder's remembered ones.
pub const SLOTS: usize = 4;

/// The application of a spec's two sides, built on its generated code.
pub trait Peer {
    /// The spec's generated `Session`: the machines read its rules as constants, as a
    /// firmware's do.
    type Session: SessionRef;
    /// The spec's generated `Session`.
    fn session() -> Self::Session;
    /// A request the host's application sends: `kind` picks the command, `mode` a header
    /// value (RoboRTS's session id).
    fn request(kind: u8, mode: u8) -> Vec<u8>;
    /// The handshake request, when the spec has one.
    fn handshake() -> Option<Vec<u8>>;
    /// The device's answer to a delivered request, as its application builds it.
    fn answer(request: &[u8]) -> Vec<u8>;
    /// The answers to a delivered request, in the order the devices send them: one, the
    /// [`answer`](Self::answer), but where each device the request lists answers.
    fn answers(request: &[u8]) -> Vec<Vec<u8>> {
        vec![Self::answer(request)]
    }
    /// An answer the device sends before [`answer`](Self::answer), saying the request is
    /// being carried out (a `result` value of `progress`); none by default.
    fn progress(_request: &[u8]) -> Option<Vec<u8>> {
        None
    }
    /// Whether generated code takes `frame` as a checked frame of the spec and decodes it
    /// (what a real receiver's stream decoder and `Packet::from_frame` would do).
    fn decodes(frame: &[u8]) -> bool;
}

/// What one run saw.
#[derive(Debug, Default, Clone)]
pub struct Tally {
    /// Requests that got a ticket (they expect an answer).
    pub requests: u64,
    /// Requests sent expecting nothing.
    pub fire_and_forget: u64,
    pub answered: u64,
    pub refused: u64,
    /// Requests refused by their answer's result value.
    pub rejected_by_value: u64,
    pub timed_out: u64,
    /// Requests of several answers that timed out with some of them.
    pub incomplete: u64,
    /// Answers to a request of several answers that left it open for the others.
    pub partial: u64,
    /// Answers of one device to one request handed to the application twice (must be 0).
    pub answers_twice: u64,
    /// Answers to a request of several answers from a device it does not list (must be 0).
    pub unlisted: u64,
    /// Answers that said a request is in progress.
    pub progress: u64,
    /// Retries of a request after an answer said it is in progress (must be 0).
    pub resent_after_progress: u64,
    /// Tickets with no outcome, or more than one (must be 0).
    pub outcome_errors: u64,
    /// Answers whose sequence number is not their request's (must be 0).
    pub mismatched: u64,
    /// Transmissions of a request beyond 1 + its retries (must be 0).
    pub over_retried: u64,
    pub resends: u64,
    /// Requests delivered to the device's application.
    pub delivered: u64,
    /// Numbered requests delivered a second time (must be 0).
    pub duplicates_delivered: u64,
    /// Duplicates the responder answered again without delivering them.
    pub duplicates_answered: u64,
    /// Requests delivered before the handshake was (must be 0).
    pub before_handshake: u64,
    /// Requests the responder took as older than its window (neither delivered nor answered).
    pub stale: u64,
    pub unsolicited: u64,
    /// Frames the receiving side rejected (corrupt).
    pub rejected: u64,
    /// Allocations inside the machines' calls (must be 0).
    pub allocations: u64,
    pub max_open: usize,
    pub faults: Faults,
}

#[derive(Debug, Default)]
struct Log {
    seq: Option<u64>,
    sends: u32,
    retries: u8,
    progressed: bool,
    outcomes: Vec<Resolution>,
    /// The devices whose answers were handed over, for a request of several answers.
    from: Vec<u8>,
    listed: Option<(protocol_kit::session::Fanout, Vec<u8>)>,
}

/// Runs `plan` (requests as `(gap in ms, kind, mode)`) over a link with `schedule`.
pub fn run<P: Peer>(plan: &[(u64, u8, u8)], schedule: Vec<Fault>) -> Tally {
    let rules = P::session();
    let mut req = Requester::<_, SLOTS, FRAME>::new(rules);
    let mut res = Responder::<_, SLOTS, FRAME>::new(rules);
    let mut link = Link::new(schedule);
    let mut t = Tally::default();
    let mut logs: HashMap<Ticket, Log> = HashMap::new();
    let mut seen: HashMap<u64, u32> = HashMap::new();
    let mut pending: Vec<(u64, u8, u8)> = Vec::new();
    let mut at = 0;
    for &(gap, kind, mode) in plan {
        at += gap;
        pending.push((at, kind, mode));
    }
    pending.reverse();
    let mut handshake: Option<Ticket> = None;
    let mut now = 0u64;
    // Long enough for every request to live its lifetime twice over (an answer that says it
    // is in progress restarts a wait), one after the other.
    let lifetime = rules.session().lifetime().saturating_mul(2);
    let end = at + 20_000u64.max(lifetime.saturating_mul(plan.len() as u64));
    while now < end {
        if !req.handshaken()
            && handshake.is_none()
            && let Some(mut frame) = P::handshake()
        {
            handshake = send::<P>(&mut t, &mut req, &mut link, &mut logs, now, &mut frame)
                .ok()
                .flatten();
        }
        while let Some(&(due, kind, mode)) = pending.last() {
            if due > now {
                break;
            }
            let mut frame = P::request(kind, mode);
            if send::<P>(&mut t, &mut req, &mut link, &mut logs, now, &mut frame).is_err() {
                // No room, or before the handshake: the application tries again later.
                if let Some(last) = pending.last_mut() {
                    last.0 = now + 7;
                }
                break;
            }
            pending.pop();
        }
        serve::<P>(&mut t, &mut res, &mut link, &mut seen, now);
        hear::<P>(&mut t, &mut req, &mut link, &mut logs, &mut handshake, now);
        tick(&mut t, &mut req, &mut link, &mut logs, &mut handshake, now);
        let mut alarm = None;
        t.allocations += allocation_counter::measure(|| alarm = res.poll(now)).count_total;
        t.max_open = t.max_open.max(req.open());
        if pending.is_empty() && req.open() == 0 && link.quiet() && req.handshaken() {
            break;
        }
        now += 1;
    }
    for log in logs.values() {
        t.outcome_errors += u64::from(log.outcomes.len() != 1);
        t.over_retried += u64::from(log.sends > 1 + u32::from(log.retries));
    }
    t.faults = link.faults;
    t
}

/// The host's application sends `frame` through the requester.
fn send<P: Peer>(
    t: &mut Tally,
    req: &mut Requester<P::Session, SLOTS, FRAME>,
    link: &mut Link,
    logs: &mut HashMap<Ticket, Log>,
    now: u64,
    frame: &mut [u8],
) -> Result<Option<Ticket>, protocol_kit::session::SendError> {
    let mut sent = None;
    t.allocations += allocation_counter::measure(|| sent = Some(req.send(now, frame))).count_total;
    let ticket = sent.expect("ran")?;
    link.send(DOWN, now, frame);
    let session = P::session();
    let rules = session.session();
    match ticket {
        Some(ticket) => {
            t.requests += 1;
            let key = rules.heard(frame).ok();
            let e = key.map(|h| match h {
                protocol_kit::session::Heard::Command(k) => rules.expects(k, frame),
                protocol_kit::session::Heard::Ack => rules.default,
            });
            logs.insert(
                ticket,
                Log {
                    seq: rules.sequence.and_then(|f| f.read(frame)),
                    sends: 1,
                    retries: e.map_or(0, |e| e.retries),
                    progressed: false,
                    outcomes: Vec::new(),
                    from: Vec::new(),
                    listed: rules
                        .heard(frame)
                        .ok()
                        .and_then(|h| match h {
                            protocol_kit::session::Heard::Command(k) => rules.fanout(k),
                            protocol_kit::session::Heard::Ack => None,
                        })
                        .and_then(|f| Some((*f, f.listed(rules.packet, frame)?.iter().collect()))),
                },
            );
        }
        None => t.fire_and_forget += 1,
    }
    Ok(ticket)
}

/// The device: frames that arrived go through the responder; its application answers.
fn serve<P: Peer>(
    t: &mut Tally,
    res: &mut Responder<P::Session, SLOTS, FRAME>,
    link: &mut Link,
    seen: &mut HashMap<u64, u32>,
    now: u64,
) {
    let session = P::session();
    let rules = session.session();
    for frame in link.arrived(DOWN, now) {
        if !P::decodes(&frame) {
            t.rejected += 1;
            continue;
        }
        let mut again = [0u8; FRAME];
        let mut what = None;
        t.allocations += allocation_counter::measure(|| {
            what = Some(match res.on_frame(now, &frame) {
                Incoming::Duplicate(Some(b)) => {
                    again[..b.len()].copy_from_slice(b);
                    Err(Some(b.len()))
                }
                Incoming::Duplicate(None) => Err(None),
                other => Ok(format_incoming(&other)),
            })
        })
        .count_total;
        match what.expect("ran") {
            Err(resend) => {
                t.duplicates_answered += u64::from(resend.is_some());
                if let Some(n) = resend {
                    link.send(UP, now, &again[..n]);
                }
            }
            Ok(Verdict::Deliver(answer)) => {
                t.delivered += 1;
                if !res.handshaken() {
                    t.before_handshake += 1;
                }
                if let Some(seq) = rules.sequence.and_then(|f| f.read(&frame)) {
                    let n = seen.entry(seq).or_default();
                    *n += 1;
                    t.duplicates_delivered += u64::from(*n > 1);
                }
                if answer && let Some(mut first) = P::progress(&frame) {
                    let mut ok = None;
                    t.allocations += allocation_counter::measure(|| {
                        ok = Some(res.answer(&frame, &mut first));
                    })
                    .count_total;
                    ok.expect("ran")
                        .expect("the answer takes the request's values");
                    link.send(UP, now, &first);
                }
                let replies = if answer {
                    P::answers(&frame)
                } else {
                    Default::default()
                };
                for mut reply in replies {
                    let mut ok = None;
                    t.allocations += allocation_counter::measure(|| {
                        ok = Some(res.answer(&frame, &mut reply));
                    })
                    .count_total;
                    ok.expect("ran")
                        .expect("the answer takes the request's values");
                    link.send(UP, now, &reply);
                }
            }
            Ok(Verdict::Stale) => t.stale += 1,
            Ok(Verdict::Other) => {}
        }
    }
}

enum Verdict {
    Deliver(bool),
    Stale,
    Other,
}

fn format_incoming(i: &Incoming<'_>) -> Verdict {
    match i {
        Incoming::Deliver { answer } => Verdict::Deliver(*answer),
        Incoming::Stale => Verdict::Stale,
        _ => Verdict::Other,
    }
}

/// The host: frames that arrived go through the requester.
fn hear<P: Peer>(
    t: &mut Tally,
    req: &mut Requester<P::Session, SLOTS, FRAME>,
    link: &mut Link,
    logs: &mut HashMap<Ticket, Log>,
    handshake: &mut Option<Ticket>,
    now: u64,
) {
    let session = P::session();
    let rules = session.session();
    for frame in link.arrived(UP, now) {
        if !P::decodes(&frame) {
            t.rejected += 1;
            continue;
        }
        let mut got = None;
        t.allocations +=
            allocation_counter::measure(|| got = Some(req.on_frame(now, &frame))).count_total;
        match got.expect("ran") {
            Received::Outcome(o) => {
                let log = logs
                    .get_mut(&o.ticket)
                    .expect("a ticket the requester gave");
                if o.resolution == Resolution::Answered
                    && log.seq != rules.sequence.and_then(|f| f.read(&frame))
                {
                    t.mismatched += 1;
                }
                if o.resolution == Resolution::Answered {
                    handed_over(t, log, &frame);
                }
                record(t, log, o.resolution);
                if *handshake == Some(o.ticket) && o.resolution != Resolution::Answered {
                    *handshake = None;
                }
            }
            Received::Progress { ticket, .. } => {
                t.progress += 1;
                logs.get_mut(&ticket).expect("open").progressed = true;
            }
            Received::Partial { ticket, .. } => {
                t.partial += 1;
                let log = logs.get_mut(&ticket).expect("open");
                assert!(
                    log.outcomes.is_empty(),
                    "a partial answer after the outcome"
                );
                handed_over(t, log, &frame);
            }
            Received::Unsolicited => t.unsolicited += 1,
            Received::Unreadable(e) => panic!("a checked frame is readable: {e:?}"),
        }
    }
}

/// Time advances: retries go out, requests time out.
fn tick<S: SessionRef>(
    t: &mut Tally,
    req: &mut Requester<S, SLOTS, FRAME>,
    link: &mut Link,
    logs: &mut HashMap<Ticket, Log>,
    handshake: &mut Option<Ticket>,
    now: u64,
) {
    loop {
        let mut buf = [0u8; FRAME];
        let mut due = None;
        t.allocations += allocation_counter::measure(|| {
            due = Some(match req.poll(now) {
                Some(Due::Resend { ticket, frame }) => {
                    buf[..frame.len()].copy_from_slice(frame);
                    Some(Ok((ticket, frame.len())))
                }
                Some(Due::Outcome(o)) => Some(Err(o)),
                None => None,
            })
        })
        .count_total;
        match due.expect("ran") {
            None => break,
            Some(Ok((ticket, n))) => {
                t.resends += 1;
                let log = logs.get_mut(&ticket).expect("open");
                log.sends += 1;
                t.resent_after_progress += u64::from(log.progressed);
                link.send(DOWN, now, &buf[..n]);
            }
            Some(Err(o)) => {
                record(t, logs.get_mut(&o.ticket).expect("open"), o.resolution);
                if *handshake == Some(o.ticket) {
                    *handshake = None;
                }
            }
        }
    }
}

fn record(t: &mut Tally, log: &mut Log, r: Resolution) {
    log.outcomes.push(r);
    match r {
        Resolution::Answered => t.answered += 1,
        Resolution::Refused => t.refused += 1,
        Resolution::Rejected(_) => t.rejected_by_value += 1,
        Resolution::TimedOut => t.timed_out += 1,
        Resolution::Incomplete(_) => t.incomplete += 1,
    }
}

/// An answer to a request of several answers handed to the application: counted against its
/// sender's id.
fn handed_over(t: &mut Tally, log: &mut Log, frame: &[u8]) {
    let Some((fanout, listed)) = &log.listed else {
        return;
    };
    let Some(id) = fanout.sender(frame) else {
        t.unlisted += 1;
        return;
    };
    t.unlisted += u64::from(!listed.contains(&id));
    t.answers_twice += u64::from(log.from.contains(&id));
    log.from.push(id);
}
