//! The lowering of the conversation ([`ir::Session`]) to the runtime's [`SessionRules`],
//! once: each command's key as the session's frame format reads it, the word fields of the
//! values the machines read and write. The expansion prints the plan as the `SESSION` static;
//! the run-time codec builds the same value from it. The C printer does not print it: a
//! session is behaviour, not bytes, and the C peer does not run the machines.

use protocol_runtime::layout::{Pos, WordField};
use protocol_runtime::rules::PacketRules;
use protocol_runtime::session::{
    Answer, Exchange, Fanout, Modes, Pair, Periodic, SessionRules, ValueAt, Verdict, Watchdog,
};

use crate::ir::{self, AnswerKind, PacketKind, PairValue, Protocol};
use crate::layout::word_field;
use crate::rules::Field;

/// The conversation, lowered, with the header values its word fields read.
#[derive(Debug, Clone, PartialEq)]
pub struct SessionPlan {
    /// The frame format (index into [`Protocol::frames`]).
    pub frame: usize,
    /// What a request of a command not in `exchanges` expects.
    pub default: Exchange,
    /// The commands whose requests expect otherwise than the default, in command order (a
    /// command the format has no key for is left out).
    pub exchanges: Vec<Exchange>,
    /// The sequence number's field.
    pub sequence: Option<Field>,
    /// The fields an answer repeats.
    pub echo: Vec<Field>,
    /// The address fields an answer swaps.
    pub swap: Option<(Field, Field)>,
    /// The NACK command's key.
    pub nack: Option<u64>,
    /// The directions whose frames refuse the request of their command (indices into the
    /// session frame's direction tests, which follow [`Protocol::directions`]): the empty ones.
    pub refusals: Vec<usize>,
    /// The handshake command's key.
    pub handshake: Option<u64>,
    /// The watchdog.
    pub watchdog: Option<Watchdog>,
    /// The modes, with their field.
    pub modes: Option<(Field, Modes)>,
    /// The values answers repeat under other names (a command the format has no key for is
    /// left out).
    pub pairs: Vec<PairPlan>,
    /// The commands whose answers tell success by a value (a command the format has no key
    /// for is left out).
    pub verdicts: Vec<VerdictPlan>,
    /// The commands sent at a fixed rate (a command the format has no key for is left out).
    pub periodic: Vec<Periodic>,
    /// The commands answered once by each id they list, with the answer's header value that
    /// names its sender (a command the format has no key for is left out).
    pub fanouts: Vec<FanoutPlan>,
}

/// A command whose request is answered once by each id it lists.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FanoutPlan {
    /// The request's command key.
    pub request: u64,
    /// Offset of the first listed id in the request's payload.
    pub first: usize,
    /// Bytes from one listed id to the next.
    pub stride: usize,
    /// The answer's header value that names its sender.
    pub by: Field,
}

impl FanoutPlan {
    /// The runtime's value.
    pub fn runtime(&self) -> Fanout {
        Fanout {
            request: self.request,
            first: self.first,
            stride: self.stride,
            id: self.by.field,
        }
    }
}

/// How the answer to a request of one command tells success from refusal.
#[derive(Debug, Clone, PartialEq)]
pub struct VerdictPlan {
    /// The request's command key.
    pub request: u64,
    /// Where the answer holds the value.
    pub at: PlanValue,
    /// The values that mean success.
    pub accept: Vec<u64>,
    /// The values that mean the request is in progress.
    pub progress: Vec<u64>,
}

/// Where a value of a [`PairPlan`] sits: a header value (printed by its `wire` const), or a
/// payload field.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PlanValue {
    /// A header value.
    Header(Field),
    /// A payload field, from the payload's first byte.
    Payload(WordField),
}

/// A value the answer to a request of one command repeats from it under another name.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PairPlan {
    /// The request's command key.
    pub request: u64,
    /// Where the request holds it.
    pub from: PlanValue,
    /// Where the answer holds it.
    pub to: PlanValue,
}

impl PlanValue {
    /// The runtime's value.
    pub fn at(self) -> ValueAt {
        match self {
            PlanValue::Header(f) => ValueAt::Header(f.field),
            PlanValue::Payload(w) => ValueAt::Payload(w),
        }
    }
}

/// The key of command `ci` as frame format `f` reads it ([`PacketRules::key`]): its CAN id
/// on a CAN format after the first, else its id's values side by side, the first in the high bits.
pub fn command_key(p: &Protocol, f: &ir::Frame, ci: usize) -> Option<u64> {
    let c = p.commands.get(ci)?;
    if f.packet == PacketKind::Can {
        return c.can_id;
    }
    let mut key = 0u64;
    for (&vi, &v) in f.dispatch.iter().zip(&c.id) {
        let width = f.values.get(vi)?.width;
        key = key.checked_shl(width).unwrap_or(0) | v;
    }
    Some(key)
}

/// Lowers the session of `p`, if it has one.
pub fn lower_session(p: &Protocol) -> Option<SessionPlan> {
    let s = p.session.as_ref()?;
    let f = p.frames.get(s.frame)?;
    let key = |ci: usize| command_key(p, f, ci);
    let field = |vi: usize| Field {
        value: vi,
        field: word_field(&f.values[vi]),
    };
    let lower = |e: &ir::Exchange, k: u64| {
        Some(Exchange {
            key: k,
            answer: match e.answer {
                AnswerKind::None => Answer::None,
                AnswerKind::Reply => Answer::Reply,
                AnswerKind::Ack => Answer::Ack,
                AnswerKind::Command(c) => Answer::Command(key(c)?),
                AnswerKind::Message => Answer::Message,
            },
            timeout: e.timeout_ms,
            retries: e.retries,
            backoff: e.backoff,
        })
    };
    let value = |v: PairValue| match v {
        PairValue::Header(vi) => PlanValue::Header(field(vi)),
        PairValue::Payload { offset, scalar } => PlanValue::Payload(WordField::whole(
            Pos::Start(offset),
            u8::try_from(scalar.prim.size()).unwrap_or(8),
            scalar.endian,
        )),
    };
    let pairs = s
        .pairs
        .iter()
        .filter_map(|pr| {
            Some(PairPlan {
                request: key(pr.command)?,
                from: value(pr.from),
                to: value(pr.to),
            })
        })
        .collect();
    let verdicts = s
        .verdicts
        .iter()
        .filter_map(|v| {
            Some(VerdictPlan {
                request: key(v.command)?,
                at: value(v.value),
                accept: v.accept.clone(),
                progress: v.progress.clone(),
            })
        })
        .collect();
    let fanouts = s
        .fanouts
        .iter()
        .filter_map(|fo| {
            Some(FanoutPlan {
                request: key(fo.command)?,
                first: fo.first,
                stride: fo.stride,
                by: field(fo.by),
            })
        })
        .collect();
    let default = lower(&s.default, 0)?;
    let exchanges = s
        .exchanges
        .iter()
        .filter_map(|e| lower(e, key(e.command)?))
        .filter(|e| Exchange { key: 0, ..*e } != default)
        .collect();
    Some(SessionPlan {
        frame: s.frame,
        default,
        exchanges,
        sequence: s.sequence.map(field),
        echo: s.echo.iter().map(|&v| field(v)).collect(),
        swap: s.swap.map(|(a, b)| (field(a), field(b))),
        nack: s.nack.and_then(key),
        refusals: p
            .directions
            .iter()
            .enumerate()
            .filter(|(_, d)| d.empty)
            .map(|(i, _)| i)
            .collect(),
        handshake: s.handshake.and_then(key),
        watchdog: s.watchdog.as_ref().and_then(|w| {
            Some(Watchdog {
                key: key(w.command)?,
                period: w.period_ms,
            })
        }),
        modes: s.modes.map(|m| {
            (
                field(m.value),
                Modes {
                    field: field(m.value).field,
                    none: m.none,
                    once: m.once,
                },
            )
        }),
        pairs,
        verdicts,
        fanouts,
        periodic: s
            .periodic
            .iter()
            .filter_map(|p| {
                Some(Periodic {
                    key: key(p.command)?,
                    period: p.period_ms,
                    sender: p.sender,
                })
            })
            .collect(),
    })
}

impl SessionPlan {
    /// The rules, over `packet` (the session frame's packet rules), with the exchange, echo,
    /// pair, verdict and fanout slices built from this plan.
    pub fn rules<'a>(
        &'a self,
        packet: &'a PacketRules<'a>,
        exchanges: &'a [Exchange],
        echo: &'a [WordField],
        pairs: &'a [Pair],
        verdicts: &'a [Verdict<'a>],
        fanouts: &'a [Fanout],
    ) -> SessionRules<'a> {
        SessionRules {
            packet,
            default: self.default,
            exchanges,
            sequence: self.sequence.map(|f| f.field),
            echo,
            swap: self.swap.map(|(a, b)| (a.field, b.field)),
            pairs,
            nack: self.nack,
            refusals: &self.refusals,
            handshake: self.handshake,
            watchdog: self.watchdog,
            modes: self.modes.map(|(_, m)| m),
            verdicts,
            periodic: &self.periodic,
            fanouts,
        }
    }

    /// The fanouts, as the runtime reads them.
    pub fn runtime_fanouts(&self) -> Vec<Fanout> {
        self.fanouts.iter().map(FanoutPlan::runtime).collect()
    }

    /// The verdicts, as the runtime reads them (borrowing this plan's values).
    pub fn runtime_verdicts(&self) -> Vec<Verdict<'_>> {
        self.verdicts
            .iter()
            .map(|v| Verdict {
                request: v.request,
                at: v.at.at(),
                accept: &v.accept,
                progress: &v.progress,
            })
            .collect()
    }

    /// The echo fields' word fields.
    pub fn echo_fields(&self) -> Vec<WordField> {
        self.echo.iter().map(|f| f.field).collect()
    }

    /// The pairs, as the runtime reads them.
    pub fn runtime_pairs(&self) -> Vec<Pair> {
        self.pairs
            .iter()
            .map(|p| Pair {
                request: p.request,
                from: p.from.at(),
                to: p.to.at(),
            })
            .collect()
    }
}
