//! The `SESSION` static of a spec with `[session]`: its conversation, as
//! [`lower_session`] plans it, printed as the runtime's `SessionRules` value over the session
//! frame's `RULES`, with `Session`, the zero-sized type that hands it to the machines as a
//! constant, and the `Requester` and `Responder` aliases of the machines over it. The machines
//! (`session::Requester`, `session::Responder`) run it; this module prints it.

use proc_macro2::TokenStream;
use quote::{format_ident, quote};

use super::rules::{field, rules_static};
use crate::codegen::frame::word_field_lit;
use crate::ir::{Frame, Protocol};
use crate::session::{PairPlan, PlanValue, SessionPlan, VerdictPlan, lower_session};
use protocol_runtime::session::{Answer, Exchange, Sender};

fn opt_key(rt: &TokenStream, k: Option<u64>) -> TokenStream {
    match k {
        Some(k) => {
            let k = key_lit(k);
            quote!(#rt::Some(#k))
        }
        None => quote!(#rt::None),
    }
}

fn range(rt: &TokenStream, r: Option<(u64, u64)>) -> TokenStream {
    match r {
        Some((a, b)) => quote!(#rt::Some((#a, #b))),
        None => quote!(#rt::None),
    }
}

/// A command's key in hex, as the spec writes ids (`0x0302` is `[0x03, 0x02]`).
fn key_lit(k: u64) -> TokenStream {
    let lit = proc_macro2::Literal::u64_suffixed(k);
    format!("0x{k:X}_u64")
        .parse()
        .unwrap_or_else(|_| quote!(#lit))
}

fn exchange(rt: &TokenStream, e: &Exchange) -> TokenStream {
    let s = quote!(#rt::session);
    let answer = match e.answer {
        Answer::None => quote!(#s::Answer::None),
        Answer::Reply => quote!(#s::Answer::Reply),
        Answer::Ack => quote!(#s::Answer::Ack),
        Answer::Command(k) => {
            let k = key_lit(k);
            quote!(#s::Answer::Command(#k))
        }
        Answer::Message => quote!(#s::Answer::Message),
    };
    let key = key_lit(e.key);
    let (timeout, retries, backoff) = (e.timeout, e.retries, e.backoff);
    quote!(#s::Exchange { key: #key, answer: #answer, timeout: #timeout, retries: #retries, backoff: #backoff })
}

/// Where a value sits, as a `session::ValueAt`.
fn value_at(f: &Frame, rt: &TokenStream, v: PlanValue) -> TokenStream {
    let s = quote!(#rt::session);
    match v {
        PlanValue::Header(k) => {
            let k = field(f, &k, rt);
            quote!(#s::ValueAt::Header(#k))
        }
        PlanValue::Payload(w) => {
            let w = word_field_lit(rt, w);
            quote!(#s::ValueAt::Payload(#w))
        }
    }
}

/// A pair: where the request holds a value and where its answer does.
fn pair(f: &Frame, rt: &TokenStream, p: &PairPlan) -> TokenStream {
    let s = quote!(#rt::session);
    let (request, from, to) = (
        key_lit(p.request),
        value_at(f, rt, p.from),
        value_at(f, rt, p.to),
    );
    quote!(#s::Pair { request: #request, from: #from, to: #to })
}

/// A verdict: where the answer holds its result, and the values of success and progress.
fn verdict(f: &Frame, rt: &TokenStream, v: &VerdictPlan) -> TokenStream {
    let s = quote!(#rt::session);
    let (request, at) = (key_lit(v.request), value_at(f, rt, v.at));
    let (accept, progress) = (&v.accept, &v.progress);
    quote!(#s::Verdict { request: #request, at: #at, accept: &[#(#accept),*], progress: &[#(#progress),*] })
}

/// The `SESSION` static, when the spec has a session.
pub(super) fn emit_session(p: &Protocol, rt: &TokenStream) -> TokenStream {
    let Some(plan): Option<SessionPlan> = lower_session(p) else {
        return quote!();
    };
    let Some(f) = p.frames.get(plan.frame) else {
        return quote!();
    };
    let s = quote!(#rt::session);
    let rules = rules_static(f);
    let default = exchange(rt, &plan.default);
    let exchanges = plan.exchanges.iter().map(|e| exchange(rt, e));
    let sequence = match plan.sequence {
        Some(k) => {
            let k = field(f, &k, rt);
            quote!(#rt::Some(#k))
        }
        None => quote!(#rt::None),
    };
    let echo = plan.echo.iter().map(|k| field(f, k, rt));
    let swap = match plan.swap {
        Some((a, b)) => {
            let (a, b) = (field(f, &a, rt), field(f, &b, rt));
            quote!(#rt::Some((#a, #b)))
        }
        None => quote!(#rt::None),
    };
    let pairs = plan.pairs.iter().map(|p| pair(f, rt, p));
    let verdicts = plan.verdicts.iter().map(|v| verdict(f, rt, v));
    let fanouts = plan.fanouts.iter().map(|fo| {
        let request = key_lit(fo.request);
        let first = proc_macro2::Literal::usize_unsuffixed(fo.first);
        let stride = proc_macro2::Literal::usize_unsuffixed(fo.stride);
        let id = field(f, &fo.by, rt);
        quote!(#s::Fanout { request: #request, first: #first, stride: #stride, id: #id })
    });
    let periodic = plan.periodic.iter().map(|p| {
        let (key, period) = (key_lit(p.key), p.period);
        let sender = match p.sender {
            Sender::Requester => quote!(#s::Sender::Requester),
            Sender::Responder => quote!(#s::Sender::Responder),
            Sender::Both => quote!(#s::Sender::Both),
        };
        quote!(#s::Periodic { key: #key, period: #period, sender: #sender })
    });
    let nack = opt_key(rt, plan.nack);
    let refusals = plan
        .refusals
        .iter()
        .map(|&d| proc_macro2::Literal::usize_unsuffixed(d));
    let handshake = opt_key(rt, plan.handshake);
    let watchdog = match plan.watchdog {
        Some(w) => {
            let (key, period) = (key_lit(w.key), w.period);
            quote!(#rt::Some(#s::Watchdog { key: #key, period: #period }))
        }
        None => quote!(#rt::None),
    };
    let modes = match plan.modes {
        Some((k, m)) => {
            let k = field(f, &k, rt);
            let (none, once) = (range(rt, m.none), range(rt, m.once));
            quote!(#rt::Some(#s::Modes { field: #k, none: #none, once: #once }))
        }
        None => quote!(#rt::None),
    };
    let name = format_ident!("SESSION");
    let doc = format!(
        " The conversation of the `{}` frame format: the answer each request expects, how it \
         is matched, timeouts and retries. [`Requester`] and [`Responder`] run it.",
        f.name
    );
    let machines = emit_machines(f, &s, !plan.fanouts.is_empty());
    let scheduler = emit_scheduler(&plan, &s);
    quote! {
        #[doc = #doc]
        pub static #name: #s::SessionRules<'static> = #s::SessionRules {
            packet: &#rules,
            default: #default,
            exchanges: &[#(#exchanges),*],
            sequence: #sequence,
            echo: &[#(#echo),*],
            swap: #swap,
            pairs: &[#(#pairs),*],
            nack: #nack,
            refusals: &[#(#refusals),*],
            handshake: #handshake,
            watchdog: #watchdog,
            modes: #modes,
            verdicts: &[#(#verdicts),*],
            periodic: &[#(#periodic),*],
            fanouts: &[#(#fanouts),*],
        };
        #machines
        #scheduler
    }
}

/// `Scheduler`, the periodic commands' scheduler over [`SESSION`] with a slot per periodic
/// command, when the spec has any.
fn emit_scheduler(plan: &SessionPlan, s: &TokenStream) -> TokenStream {
    let n = plan.periodic.len();
    if n == 0 {
        return quote!();
    }
    let doc = format!(
        " The scheduler of the {n} periodic command{} of [`SESSION`]: \
         `Scheduler::new(Session, session::Sender::Requester, now)`, then `poll(now)` says \
         which is due.",
        if n == 1 { "" } else { "s" }
    );
    quote! {
        #[doc = #doc]
        pub type Scheduler = #s::Scheduler<Session, #n>;
    }
}

/// `Session` and the machines over it: the machines read [`SESSION`] as a constant, so a
/// firmware links the checks of this frame format alone.
fn emit_machines(f: &Frame, s: &TokenStream, several: bool) -> TokenStream {
    let max = format_ident!("{}", f.names.sizes.max_frame_len);
    let session_doc = " [`SESSION`] as a type: the session machines read the conversation as a \
         compile-time constant and compile to code for this spec's alone (its frame format's \
         checks, none other).";
    let requester_doc = format!(
        " The requester of [`SESSION`]: at most `SLOTS` open requests, each kept to send again \
         (a frame of at most `FRAME` bytes, by default [`{max}`]). `Requester::<4>::new(Session)`."
    );
    let responder_doc = format!(
        " The responder of [`SESSION`]: it remembers the last `SLOTS` sequence numbers with \
         their answers of at most `FRAME` bytes (by default [`{max}`]). \
         `Responder::<8>::new(Session)`."
    );
    // A requester's slot keeps the ids a request still waits for only where a command is
    // answered once by each id it lists.
    let awaiting = if several {
        quote!(#s::Awaited)
    } else {
        quote!(#s::NoFanout)
    };
    quote! {
        #[doc = #session_doc]
        #[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash)]
        pub struct Session;
        impl #s::SessionRef for Session {
            type Awaiting = #awaiting;
            #[inline(always)]
            fn session(&self) -> &#s::SessionRules<'_> {
                &SESSION
            }
        }
        #[doc = #requester_doc]
        pub type Requester<const SLOTS: usize, const FRAME: usize = #max> = #s::Requester<Session, SLOTS, FRAME>;
        #[doc = #responder_doc]
        pub type Responder<const SLOTS: usize, const FRAME: usize = #max> = #s::Responder<Session, SLOTS, FRAME>;
    }
}
