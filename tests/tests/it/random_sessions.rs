//! The sessions of random specs through generated code and the run-time codec: for every spec
//! of the batch (`random_specs.rs`, `tests/build.rs`) with a `[session]` table, the generated
//! `Requester` and `Responder` (over the module's `SESSION`) and the same machines over the
//! rules `protocol_dynamic` builds at run time are driven with the same events, and every output
//! must be the same: the result of each send and the frame it leaves to transmit (its sequence
//! number written, its checks sealed), what each frame is to either side, the answers the
//! responders seal, the retries and timeouts that the passing of time brings, the watchdog's
//! alarms, and the state between events (open requests, the next deadline, the handshake).
//!
//! The events are seeded by the spec's seed: random valid frames of the spec (the spec-driven
//! model) sent as requests, delivered to the responder or lost, answered with a frame of the
//! command the request expects (a request that several devices answer, a command's `answers`,
//! once per id it lists, each answer lost or not on its own), duplicated, bit-flipped, and time
//! advanced by random steps or to the next deadline. The output counts the requests of several
//! answers, the answers that left them open and those that ended incomplete.

use protocol_kit::session::{
    Due, Heard, Incoming, Outcome, Received, Requester, Resolution, Responder, SessionRef,
    SessionRules,
};

use crate::random_specs as batch;
use crate::support;

use support::model::model;
use support::{Rng, Source, Spec};

/// Requests open at once.
const SLOTS: usize = 4;
/// Sequence numbers the responder remembers.
const REMEMBERED: usize = 8;
/// Events per spec.
const STEPS: usize = 600;
/// Random valid frames per spec, the pool the events draw from.
const POOL: usize = 64;

/// What the comparison saw, summed over the batch.
#[derive(Debug, Default)]
struct Tally {
    events: usize,
    sent: usize,
    answered: usize,
    outcomes: usize,
    resends: usize,
    /// Requests sent that several devices answer (a command's `answers`).
    several: usize,
    /// Answers that left such a request open for the other devices' (`Received::Partial`).
    partial: usize,
    /// Such requests that ended with some devices silent (`Resolution::Incomplete`).
    incomplete: usize,
}

impl Tally {
    /// Counts an outcome: incomplete ones apart.
    fn outcome(&mut self, o: Outcome) {
        self.outcomes += 1;
        self.incomplete += usize::from(matches!(o.resolution, Resolution::Incomplete(_)));
    }

    /// Adds `t`'s counts.
    fn add(&mut self, t: &Tally) {
        self.events += t.events;
        self.sent += t.sent;
        self.answered += t.answered;
        self.outcomes += t.outcomes;
        self.resends += t.resends;
        self.several += t.several;
        self.partial += t.partial;
        self.incomplete += t.incomplete;
    }
}

/// A machine of each kind over each side's rules: `G` is generated code's `Session`, the other
/// the codec's rules.
struct Twins<'r, G: SessionRef, const FRAME: usize> {
    requester: (
        Requester<G, SLOTS, FRAME>,
        Requester<&'r SessionRules<'r>, SLOTS, FRAME>,
    ),
    responder: (
        Responder<G, REMEMBERED, FRAME>,
        Responder<&'r SessionRules<'r>, REMEMBERED, FRAME>,
    ),
    tally: Tally,
}

impl<'r, G: SessionRef, const FRAME: usize> Twins<'r, G, FRAME> {
    /// Sends `frame` from both requesters: the frame to transmit, when both send it.
    fn send(&mut self, now: u64, frame: &[u8]) -> Option<Vec<u8>> {
        let (mut a, mut b) = (frame.to_vec(), frame.to_vec());
        let ra = self.requester.0.send(now, &mut a);
        let rb = self.requester.1.send(now, &mut b);
        assert_eq!(ra, rb, "send at {now} of {}", support::hex(frame));
        assert_eq!(a, b, "the frame sent at {now}");
        self.tally.sent += usize::from(ra.is_ok());
        ra.ok().map(|_| a)
    }

    /// `frame` at both requesters.
    fn at_requester(&mut self, now: u64, frame: &[u8]) {
        let a = self.requester.0.on_frame(now, frame);
        let b = self.requester.1.on_frame(now, frame);
        assert_eq!(a, b, "at the requester at {now}: {}", support::hex(frame));
        match a {
            Received::Outcome(o) => self.tally.outcome(o),
            Received::Partial { .. } => self.tally.partial += 1,
            _ => {}
        }
    }

    /// `frame` at both responders: whether it is to be answered, and the answer to send again
    /// for a duplicate.
    fn at_responder(&mut self, now: u64, frame: &[u8]) -> (bool, Option<Vec<u8>>) {
        let a = self.responder.0.on_frame(now, frame);
        let b = self.responder.1.on_frame(now, frame);
        assert_eq!(a, b, "at the responder at {now}: {}", support::hex(frame));
        match a {
            Incoming::Deliver { answer } => (answer, None),
            Incoming::Duplicate(again) => (false, again.map(<[u8]>::to_vec)),
            _ => (false, None),
        }
    }

    /// Both responders seal `answer` for `request`: the answer to transmit.
    fn answer(&mut self, request: &[u8], answer: &[u8]) -> Option<Vec<u8>> {
        let (mut a, mut b) = (answer.to_vec(), answer.to_vec());
        let ra = self.responder.0.answer(request, &mut a);
        let rb = self.responder.1.answer(request, &mut b);
        assert_eq!(ra, rb, "answering {}", support::hex(request));
        assert_eq!(a, b, "the answer to {}", support::hex(request));
        self.tally.answered += usize::from(ra.is_ok());
        ra.ok().map(|()| a)
    }

    /// The passing of time at both sides: the frames the requesters send again.
    fn poll(&mut self, now: u64) -> Vec<Vec<u8>> {
        let mut resent = Vec::new();
        loop {
            let a = self.requester.0.poll(now);
            let b = self.requester.1.poll(now);
            assert_eq!(a, b, "the requesters' poll at {now}");
            match a {
                None => break,
                Some(Due::Resend { frame, .. }) => {
                    self.tally.resends += 1;
                    resent.push(frame.to_vec());
                }
                Some(Due::Outcome(o)) => self.tally.outcome(o),
            }
        }
        loop {
            let a = self.responder.0.poll(now);
            assert_eq!(
                a,
                self.responder.1.poll(now),
                "the responders' poll at {now}"
            );
            if a.is_none() {
                break;
            }
        }
        resent
    }

    /// The state both sides show between events.
    fn same_state(&self, now: u64) {
        let (a, b) = &self.requester;
        assert_eq!(
            (a.open(), a.next_deadline(), a.handshaken()),
            (b.open(), b.next_deadline(), b.handshaken()),
            "the requesters' state at {now}"
        );
        let (a, b) = &self.responder;
        assert_eq!(
            (a.next_deadline(), a.handshaken()),
            (b.next_deadline(), b.handshaken()),
            "the responders' state at {now}"
        );
    }
}

/// A frame of the pool that answers `request` as the rules say it expects, if the pool holds
/// one.
fn answer_for<'p>(
    rules: &SessionRules<'_>,
    request: &[u8],
    pool: &'p [Vec<u8>],
) -> Option<&'p [u8]> {
    let Ok(Heard::Command(key)) = rules.heard(request) else {
        return None;
    };
    let expected = rules.expects(key, request).answer;
    pool.iter()
        .find(|f| {
            rules
                .heard(f)
                .is_ok_and(|h| SessionRules::is_answer(expected, key, h))
        })
        .map(Vec::as_slice)
}

/// The answers to `request` made of `reply`: `reply` itself, or, for a request that several
/// devices answer, one per id it lists, that id written as the sender's (an id the field cannot
/// hold gets no answer, as a device the answer cannot name would stay silent).
fn answers_of_each(rules: &SessionRules<'_>, request: &[u8], reply: &[u8]) -> Vec<Vec<u8>> {
    let fanout = match rules.heard(request) {
        Ok(Heard::Command(key)) => rules.fanout(key),
        _ => None,
    };
    let Some(fanout) = fanout else {
        return vec![reply.to_vec()];
    };
    let ids = fanout.listed(rules.packet, request).unwrap_or_default();
    ids.iter()
        .filter_map(|id| {
            let mut frame = reply.to_vec();
            fanout.id.write(&mut frame, u64::from(id))?;
            Some(frame)
        })
        .collect()
}

/// Whether several devices answer `request`.
fn several(rules: &SessionRules<'_>, request: &[u8]) -> bool {
    matches!(rules.heard(request), Ok(Heard::Command(key)) if rules.fanout(key).is_some())
}

/// One event: a request and what the link does with it, or a frame out of turn.
fn event<G: SessionRef, const FRAME: usize>(
    twins: &mut Twins<'_, G, FRAME>,
    rules: &SessionRules<'_>,
    pool: &[Vec<u8>],
    rng: &mut Rng,
    now: u64,
    last: &mut Option<Vec<u8>>,
) {
    let pick = |rng: &mut Rng| pool[rng.below(pool.len() as u64) as usize].clone();
    match rng.below(10) {
        0..=5 => {
            let Some(sent) = twins.send(now, &pick(rng)) else {
                return;
            };
            *last = Some(sent.clone());
            twins.tally.several += usize::from(several(rules, &sent));
            if rng.one_in(5) {
                return; // lost on the way
            }
            let (answer, _) = twins.at_responder(now, &sent);
            let Some(reply) = answer.then(|| answer_for(rules, &sent, pool)).flatten() else {
                return;
            };
            for reply in answers_of_each(rules, &sent, reply) {
                if let Some(sealed) = twins.answer(&sent, &reply)
                    && !rng.one_in(5)
                {
                    twins.at_requester(now, &sealed);
                }
            }
        }
        6 | 7 => {
            let mut frame = pick(rng);
            if rng.one_in(3) {
                let bit = rng.below(frame.len() as u64 * 8) as usize;
                frame[bit / 8] ^= 1 << (bit % 8);
            }
            twins.at_requester(now, &frame);
        }
        8 => {
            twins.at_responder(now, &pick(rng));
        }
        _ => {
            // The last request again: a duplicate, its answer sent again.
            if let Some(frame) = last.clone()
                && let (_, Some(again)) = twins.at_responder(now, &frame)
            {
                twins.at_requester(now, &again);
            }
        }
    }
}

/// Drives the generated machines and the codec's (over `rules`) with the events of `seed`.
fn compare<S: Spec, G: SessionRef, const FRAME: usize>(
    seed: u64,
    generated: (Requester<G, SLOTS, FRAME>, Responder<G, REMEMBERED, FRAME>),
    rules: &SessionRules<'_>,
) -> Tally {
    let mut rng = Rng(seed ^ 0x5E55_1011);
    let m = model::<S>();
    let pool: Vec<Vec<u8>> = (0..POOL)
        .map(|_| {
            // The machines take frames as the decoder yields them: unescaped.
            let format = m.pick(&mut rng);
            support::unescaped(format.layout, &format.canonical_here(&mut rng))
        })
        .collect();
    let mut twins = Twins {
        requester: (generated.0, Requester::new(rules)),
        responder: (generated.1, Responder::new(rules)),
        tally: Tally::default(),
    };
    let (mut now, mut last) = (0u64, None);
    for _ in 0..STEPS {
        // To the next deadline of either side, past a request's whole life, or a short step.
        now = match rng.below(5) {
            0 => twins.requester.0.next_deadline().unwrap_or(now).max(now),
            1 => twins.responder.0.next_deadline().unwrap_or(now).max(now),
            2 => now + rng.below(rules.lifetime() + 1),
            _ => now + rng.below(20),
        };
        event(&mut twins, rules, &pool, &mut rng, now, &mut last);
        for frame in twins.poll(now) {
            if rng.one_in(2) {
                twins.at_responder(now, &frame);
            }
        }
        twins.same_state(now);
        twins.tally.events += 1;
    }
    twins.tally
}

#[test]
fn random_sessions_agree_in_generated_rust_and_the_run_time_codec() {
    let (mut specs, mut with_answers) = (0, 0);
    let mut total = Tally::default();
    macro_rules! one {
        ($name:ident, link) => {
            one!(@ $name, batch::$name::AnyPacket)
        };
        ($name:ident $(, $given:tt)*) => {
            one!(@ $name, batch::$name::Packet)
        };
        (@ $name:ident, $packet:ty) => {{
            let seed: u64 = stringify!($name)["rand_".len()..].parse().expect("a seed");
            let interpreter = protocol_dynamic::Interpreter::new(model::<$packet>().ir.clone());
            let generated = (
                batch::$name::Requester::<SLOTS>::new(batch::$name::Session),
                batch::$name::Responder::<REMEMBERED>::new(batch::$name::Session),
            );
            let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(move || {
                interpreter
                    .codec()
                    .with_session(|rules| compare::<$packet, _, _>(seed, generated, rules))
                    .expect("the codec reads the spec's session")
            }));
            match outcome {
                Ok(t) => {
                    eprintln!("seed {seed}: {t:?}");
                    specs += 1;
                    with_answers += usize::from(t.several > 0);
                    total.add(&t);
                }
                Err(panic) => {
                    eprintln!(
                        "seed {seed}: the session machines over generated code and the run-time \
                         codec disagree on:\n{}",
                        <$packet as Spec>::TEXT
                    );
                    std::panic::resume_unwind(panic);
                }
            }
        }};
    }
    for_each_random_session!(one);
    eprintln!(
        "random sessions: {specs} specs of the batch with a session, {with_answers} of them \
         with requests that several devices answer, {total:?}"
    );
    // `tests/build.rs` adds a later seed's spec when the batch has no session, and one when
    // none of its sessions has a request that several devices answer.
    assert!(specs > 0, "no random spec with a session was compared");
    assert!(
        total.several > 0,
        "no request that several devices answer was compared: {total:?}"
    );
    assert_eq!(total.events, specs * STEPS);
}
