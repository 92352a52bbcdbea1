//! The typed handlers: per side of the link, a trait with one method per command that side
//! receives (`Handler` without directions; `RequestHandler` and `ResponseHandler` with them),
//! and the `dispatch` function that hands a decoded `Packet` to its method and turns the
//! method's `session::Reply` into the answer packet. What a request expects comes from the IR's
//! session (`ir::Session::exchanges`); this module prints it and decides nothing.
//!
//! Only the requests of a spec (every message without directions; the first direction's with
//! them) answer: the other direction's messages are answers and unsolicited reports, and their
//! methods return nothing.

use proc_macro2::{Ident, TokenStream};
use quote::{format_ident, quote};

use super::packet::Items;
use crate::codegen::docs::doc_attrs;
use crate::codegen::ident;
use crate::ir::{AnswerKind, DirectionRule, Frame, Protocol};

/// One side's trait and dispatch function.
struct Side {
    /// The trait (`Handler`, `RequestHandler`, ...).
    handler: Ident,
    /// The dispatch function (`dispatch`, `dispatch_request`, ...).
    dispatch: Ident,
    /// The direction whose messages this side receives, if the spec has directions.
    direction: Option<usize>,
    /// Its messages are requests, which may expect answers.
    requests: bool,
}

/// What a request's method returns and how its answer is built.
struct Answer {
    /// The answer's payload type (`()` for an empty answer or an acknowledgement).
    ty: TokenStream,
    /// The answer's `Message`, from `a` (the payload) when it has one.
    message: TokenStream,
    /// The pattern of the method's `Reply::Answer`: `a`, or `()` for an empty answer.
    pattern: TokenStream,
    /// Prose for the method's rustdoc.
    doc: String,
}

/// The handler traits and dispatch functions of format `f` (the first, whose `Message` they
/// take).
pub(super) fn emit_handlers(p: &Protocol, f: &Frame, rt: &TokenStream) -> TokenStream {
    let sides: Vec<Side> = if p.directions.is_empty() {
        vec![Side {
            handler: format_ident!("Handler"),
            dispatch: format_ident!("dispatch"),
            direction: None,
            requests: true,
        }]
    } else {
        // An empty direction carries no payload to hand to a method: its frames (a command
        // refused) reach no handler.
        p.directions
            .iter()
            .enumerate()
            .filter(|(_, d)| !d.empty)
            .map(|(di, d)| Side {
                handler: format_ident!("{}Handler", d.rust_name),
                dispatch: format_ident!("dispatch_{}", d.name),
                direction: Some(di),
                requests: di == 0,
            })
            .collect()
    };
    sides.iter().map(|s| emit_side(p, f, s, rt)).collect()
}

/// The `Message` of command `ci` in direction `di` holding `arg` (`Message::X(arg)`, or
/// `Message::Request(Request::X(arg))`; no argument for an empty payload).
fn message(p: &Protocol, di: Option<usize>, ci: usize, arg: Option<&TokenStream>) -> TokenStream {
    let v = ident(&p.commands[ci].rust_name);
    let inner = match arg {
        Some(a) => quote!(#v(#a)),
        None => quote!(#v),
    };
    match di.and_then(|di| p.directions.get(di)) {
        Some(d) => {
            let dv = format_ident!("{}", d.rust_name);
            quote!(Message::#dv(#dv::#inner))
        }
        None => quote!(Message::#inner),
    }
}

/// True when command `ci` carries a payload in direction `di`.
fn carries(p: &Protocol, di: Option<usize>, ci: usize) -> bool {
    p.commands[ci]
        .payloads
        .get(di.unwrap_or(0))
        .copied()
        .flatten()
        .is_some()
}

/// The payload type of command `ci` in direction `di`, `()` when empty.
fn payload_type(p: &Protocol, di: Option<usize>, ci: usize) -> TokenStream {
    match p.commands[ci]
        .payloads
        .get(di.unwrap_or(0))
        .copied()
        .flatten()
    {
        Some(si) => {
            let s = ident(&p.structs[si].name);
            quote!(#s)
        }
        None => quote!(()),
    }
}

/// The direction answers travel in: the second with directions.
fn answer_direction(p: &Protocol) -> Option<usize> {
    (!p.directions.is_empty()).then_some(1)
}

/// The answer the request of command `ci` expects, `None` when it expects none.
fn answer(p: &Protocol, ci: usize, rt: &TokenStream) -> Option<Answer> {
    let s = p.session.as_ref()?;
    let e = s.exchanges.get(ci)?;
    let by = match e.answer {
        AnswerKind::None => return None,
        AnswerKind::Ack => {
            return Some(Answer {
                ty: quote!(()),
                message: quote!(Message::Ack(#rt::Bytes::new())),
                pattern: quote!(()),
                doc: "It expects an acknowledgement: `Reply::ACK` sends it.".into(),
            });
        }
        AnswerKind::Reply | AnswerKind::Message => ci,
        AnswerKind::Command(k) => k,
    };
    let ad = answer_direction(p);
    // An answer direction that carries one struct in place of a command.
    if let Some((si, _)) = ad.and_then(|d| p.directions.get(d)).and_then(|d| d.message) {
        let (s, dv) = (&p.structs[si].name, &p.directions[1].rust_name);
        let (sid, dvid) = (ident(s), format_ident!("{dv}"));
        return Some(Answer {
            ty: quote!(#sid),
            message: quote!(Message::#dvid(a)),
            pattern: quote!(a),
            doc: format!("It expects an answer: a `{s}`."),
        });
    }
    let name = &p.commands[by].name;
    Some(if carries(p, ad, by) {
        Answer {
            ty: payload_type(p, ad, by),
            message: message(p, ad, by, Some(&quote!(a))),
            pattern: quote!(a),
            doc: format!(
                "It expects an answer, `{name}`, carrying what the method returns.{}{}",
                verdict_doc(s, ci),
                fanout_doc(s, ci)
            ),
        }
    } else {
        Answer {
            ty: quote!(()),
            message: message(p, ad, by, None),
            pattern: quote!(()),
            doc: format!("It expects an empty answer, `{name}`: `Reply::ACK` sends it."),
        }
    })
}

/// What the answer's result value tells the requester, when the command has a `result`.
/// For a request answered once by each id it lists: who answers, and with which id.
fn fanout_doc(s: &crate::ir::Session, ci: usize) -> String {
    let Some(fo) = s.fanouts.iter().find(|fo| fo.command == ci) else {
        return String::new();
    };
    let (each, by) = &fo.names;
    format!(
        " Each device that `{each}` lists answers once, in the answer's header its own `{by}` \
         (set it before encoding the answer); a device not listed returns `Reply::Refuse`."
    )
}

fn verdict_doc(s: &crate::ir::Session, ci: usize) -> String {
    let Some(v) = s.verdicts.iter().find(|v| v.command == ci) else {
        return String::new();
    };
    let list = |vs: &[u64]| {
        vs.iter()
            .map(u64::to_string)
            .collect::<Vec<_>>()
            .join(" or ")
    };
    let progress = if v.progress.is_empty() {
        String::new()
    } else {
        format!(
            " {} says it is in progress (the requester waits again),",
            list(&v.progress)
        )
    };
    format!(
        " Its `{}` tells the requester the outcome: {} accepts the request,{progress} any \
         other value refuses it with that value.",
        v.field,
        list(&v.accept)
    )
}

/// What a refusal sends: the error reply of the request's command where the spec has an
/// empty direction (MSP's `!`: the refusal the requester reads), else the spec's `nack`
/// command when it carries no payload in the answer's direction.
fn refusal(p: &Protocol, rt: &TokenStream) -> TokenStream {
    if let Some(e) = p.directions.iter().find(|d| d.empty) {
        let dv = format_ident!("{}", e.rust_name);
        return quote!(#rt::Some(Message::#dv(packet.message.command())));
    }
    let ad = answer_direction(p);
    let struct_answers = ad
        .and_then(|d| p.directions.get(d))
        .is_some_and(|d| d.message.is_some());
    let empty_nack = p
        .session
        .as_ref()
        .and_then(|s| s.nack)
        .filter(|_| !struct_answers)
        .filter(|&n| !carries(p, ad, n))
        .map(|n| message(p, ad, n, None));
    match empty_nack {
        Some(nack) => quote!(#rt::Some(#nack)),
        None => quote!(#rt::None),
    }
}

/// One side: its trait, with a method per message, and its dispatch function.
fn emit_side(p: &Protocol, f: &Frame, side: &Side, rt: &TokenStream) -> TokenStream {
    let header = Items::of(f).header;
    let answers = arms_answer(side, p);
    // What an arm without an answer evaluates to.
    let nothing = if answers {
        quote!(#rt::None)
    } else {
        quote!({})
    };
    // A call to a method that returns nothing, as an arm's expression.
    let call = |call: TokenStream| {
        if answers {
            quote!({ #call; #rt::None })
        } else {
            quote!(#call,)
        }
    };
    let reply = quote!(#rt::session::Reply);
    let mut methods = Vec::new();
    let mut arms = Vec::new();
    let di = side.direction;
    let message_struct = di
        .and_then(|d| p.directions.get(d))
        .and_then(|d| d.message.map(|(si, _)| (d, si)));
    if let Some((d, si)) = message_struct {
        let (m, s, dv) = (
            ident(&d.name),
            ident(&p.structs[si].name),
            format_ident!("{}", d.rust_name),
        );
        let doc = doc_attrs(&format!("A {}: {}", d.name, d.doc));
        methods.push(quote! {
            #doc
            fn #m(&mut self, header: &#header, payload: &#s) {
                let _ = (header, payload);
            }
        });
        let c = call(quote!(handler.#m(header, p)));
        arms.push(quote!(Message::#dv(p) => #c));
    } else {
        for (ci, c) in p.commands.iter().enumerate() {
            let m = ident(&c.name.to_ascii_lowercase());
            let full = carries(p, di, ci);
            let answer = if side.requests {
                answer(p, ci, rt)
            } else {
                None
            };
            let (param, arg, pat) = if full {
                let t = payload_type(p, di, ci);
                (
                    quote!(, payload: &#t),
                    quote!(, p),
                    message(p, di, ci, Some(&quote!(p))),
                )
            } else {
                (quote!(), quote!(), message(p, di, ci, None))
            };
            let unused = if full {
                quote!(let _ = (header, payload);)
            } else {
                quote!(let _ = header;)
            };
            let mut doc = if c.doc.is_empty() {
                format!("`{}`.", c.name)
            } else {
                format!("`{}`: {}", c.name, c.doc)
            };
            match answer {
                Some(a) => {
                    doc.push_str(&format!("\n\n{} The default refuses the request.", a.doc));
                    let (ty, message, pattern) = (a.ty, a.message, a.pattern);
                    let doc = doc_attrs(&doc);
                    methods.push(quote! {
                        #doc
                        fn #m(&mut self, header: &#header #param) -> #reply<#ty> {
                            #unused
                            #reply::Refuse
                        }
                    });
                    arms.push(quote! {
                        #pat => match handler.#m(header #arg) {
                            #reply::Answer(#pattern) => #rt::Some(#message),
                            #reply::Refuse => refusal,
                        }
                    });
                }
                None => {
                    let doc = doc_attrs(&doc);
                    methods.push(quote! {
                        #doc
                        fn #m(&mut self, header: &#header #param) { #unused }
                    });
                    let c = call(quote!(handler.#m(header #arg)));
                    arms.push(quote!(#pat => #c));
                }
            }
        }
    }
    arms.extend(other_arms(p, f, di, &nothing));
    emit_items(p, f, side, &methods, &arms, answers, rt)
}

/// The arms of the messages a side does not handle: the other directions', acknowledgements.
fn other_arms(
    p: &Protocol,
    f: &Frame,
    di: Option<usize>,
    nothing: &TokenStream,
) -> Vec<TokenStream> {
    let mut arms = Vec::new();
    for (oi, d) in p.directions.iter().enumerate() {
        if Some(oi) != di {
            let dv = format_ident!("{}", d.rust_name);
            arms.push(quote!(Message::#dv(_) => #nothing,));
        }
    }
    if di.is_none() && f.ack.is_some() {
        arms.push(quote!(Message::Ack(_) => #nothing,));
    }
    arms
}

/// True when some message of the side may be answered.
fn arms_answer(side: &Side, p: &Protocol) -> bool {
    side.requests
        && p.session
            .as_ref()
            .is_some_and(|s| s.exchanges.iter().any(|e| e.answer != AnswerKind::None))
}

/// The trait and the dispatch function around their methods and arms.
fn emit_items(
    p: &Protocol,
    f: &Frame,
    side: &Side,
    methods: &[TokenStream],
    arms: &[TokenStream],
    answers: bool,
    rt: &TokenStream,
) -> TokenStream {
    let items = Items::of(f);
    let packet = &items.packet;
    let (handler, dispatch) = (&side.handler, &side.dispatch);
    let (what, about) = match side.direction.and_then(|d| p.directions.get(d)) {
        Some(d) => (format!("the {} messages", d.name), format!("\n\n{}", d.doc)),
        None => ("the messages".to_string(), String::new()),
    };
    let answering = if answers {
        format!(
            "\n\nA method whose request expects an answer (the spec's `[session]`) returns it \
             as a `session::Reply`: the typed answer, or `Refuse`. With a `session::Responder`, \
             call [`{dispatch}`] for each frame it delivers and pass the encoded answer to \
             `Responder::answer`, which makes it repeat what the request says (sequence number, \
             matched fields) and answers the request's duplicates with it."
        )
    } else {
        String::new()
    };
    let trait_doc = doc_attrs(&format!(
        "Handles {what} this end of the link receives: one method per message, each with a \
         default, so that an implementation writes only the ones it handles. \
         [`{dispatch}`] calls them (the runtime crate's documentation, *A handler*, shows one).\
         {about}{answering}"
    ));
    let fn_doc = if answers {
        doc_attrs(&format!(
            "Hands `packet` to its [`{handler}`] method and returns the answer to encode and \
             send (`None`: nothing to send). The answer's header is the request's, {}.",
            swap_doc(p, f)
        ))
    } else {
        doc_attrs(&format!("Hands `packet` to its [`{handler}`] method."))
    };
    let setup = answers.then(|| {
        let refuse = refusal(p, rt);
        quote!(let refusal: #rt::Option<Message> = #refuse;)
    });
    let function = if answers {
        let silent = silent_check(p, f, rt);
        let swap = swap_stmts(p, f);
        let direction = direction_stmts(p, f);
        quote! {
            pub fn #dispatch<H: #handler + ?Sized>(handler: &mut H, packet: &#packet) -> #rt::Option<#packet> {
                let header = &packet.header;
                #setup
                let answer = match &packet.message { #(#arms)* };
                #silent
                let mut to = packet.header;
                #swap
                #direction
                answer.map(|message| #packet { header: to, message })
            }
        }
    } else {
        quote! {
            pub fn #dispatch<H: #handler + ?Sized>(handler: &mut H, packet: &#packet) {
                let header = &packet.header;
                match &packet.message { #(#arms)* }
            }
        }
    };
    quote! {
        #trait_doc
        pub trait #handler {
            #(#methods)*
        }
        #fn_doc
        #function
    }
}

/// The header fields an answer swaps and the direction field it sets, in prose.
fn swap_doc(p: &Protocol, f: &Frame) -> String {
    let swapped = p
        .session
        .as_ref()
        .and_then(|s| s.swap)
        .map(|(a, b)| format!("`{}` and `{}` swapped", f.values[a].name, f.values[b].name));
    let told = p.directions.first().and_then(|d| match d.rule.in_frame(f) {
        DirectionRule::Equals { value, .. } if !direction_stmts(p, f).is_empty() => f
            .values
            .get(value)
            .map(|v| format!("`{}` set to the answer's direction", v.name)),
        _ => None,
    });
    match (swapped, told) {
        (Some(a), Some(b)) => format!("{a}, {b}"),
        (Some(a), None) | (None, Some(a)) => a,
        (None, None) => "unchanged".to_string(),
    }
}

/// Swapping the answer header's address fields.
fn swap_stmts(p: &Protocol, f: &Frame) -> TokenStream {
    match p.session.as_ref().and_then(|s| s.swap) {
        Some((a, b)) => {
            let (a, b) = (ident(&f.values[a].name), ident(&f.values[b].name));
            quote! {
                to.#a = packet.header.#b;
                to.#b = packet.header.#a;
            }
        }
        None => quote!(),
    }
}

/// Setting the answer header's direction field to the answer's direction, where the header
/// tells every direction by a value of one field (MSP's `<`, `>` and `!`): the request's
/// value tells the request's direction, under which the encoder refuses an answer.
fn direction_stmts(p: &Protocol, f: &Frame) -> TokenStream {
    let mut field = None;
    let mut arms = Vec::new();
    for d in &p.directions {
        let DirectionRule::Equals { value, equals } = d.rule.in_frame(f) else {
            return quote!();
        };
        if field.is_some_and(|v| v != value) {
            return quote!();
        }
        field = Some(value);
        let dv = format_ident!("{}", d.rust_name);
        // In hex, as specs write these values (`0x3C`).
        let equals = format!("{equals:#04X}")
            .replace("0X", "0x")
            .parse::<proc_macro2::Literal>()
            .unwrap_or_else(|_| proc_macro2::Literal::u64_unsuffixed(equals));
        arms.push(quote!(Message::#dv(_) => #equals,));
    }
    let Some(v) = field.and_then(|v| f.values.get(v)) else {
        return quote!();
    };
    let name = ident(&v.name);
    quote! {
        if let Some(m) = &answer {
            to.#name = match m { #(#arms)* };
        }
    }
}

/// With `modes`: a request whose mode says it expects no answer gets none, except a request
/// that lists the ids that answer it (a SYNC_READ goes to the broadcast id; the application
/// sets its own id in the answer's header).
fn silent_check(p: &Protocol, f: &Frame, rt: &TokenStream) -> TokenStream {
    let Some(s) = p.session.as_ref() else {
        return quote!();
    };
    match s.modes {
        Some(m) => {
            let id = ident(&f.values[m.value].name);
            let listed = s.fanouts.iter().filter_map(|fo| {
                let v = format_ident!("{}", p.commands.get(fo.command)?.rust_name);
                Some(quote!(Command::#v))
            });
            let listing = if s.fanouts.is_empty() {
                quote!()
            } else {
                quote!(&&!matches!(packet.message.command(), #(#listed)|*))
            };
            quote! {
                if SESSION.modes.is_some_and(|m| m.silent(packet.header.#id as u64)) #listing {
                    return #rt::None;
                }
            }
        }
        None => quote!(),
    }
}
