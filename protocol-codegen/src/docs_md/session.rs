//! The conversation section of the Markdown reference (`[session]`): the rules as a table,
//! each command's exchange with the handler method that receives it, and a sequence diagram
//! (Mermaid) of each kind of exchange the spec has.

use std::fmt::Write as _;

use crate::ir::{AnswerKind, Exchange, Frame, Protocol, Session, Verdict};

/// What an answer is, in words.
fn answer_text(p: &Protocol, a: AnswerKind) -> String {
    match a {
        AnswerKind::None => "none".to_string(),
        AnswerKind::Reply => "the same command back".to_string(),
        AnswerKind::Ack => "an acknowledgement".to_string(),
        AnswerKind::Command(c) => format!("`{}`", p.commands[c].name),
        AnswerKind::Message => "the response's struct (no command)".to_string(),
    }
}

/// Values, in words: `0`, `0 or 5`.
fn listed(values: &[u64]) -> String {
    let v: Vec<String> = values.iter().map(u64::to_string).collect();
    v.join(" or ")
}

/// What a verdict says, in words.
fn verdict_text(v: &Verdict) -> String {
    let mut text = format!("`{}` {}: success", v.field, listed(&v.accept));
    if !v.progress.is_empty() {
        text.push_str(&format!(
            "; {}: in progress (waits again, not sent again)",
            listed(&v.progress)
        ));
    }
    text.push_str("; any other value: refused, with the value");
    text
}

/// The waits of an exchange, in words.
fn waits(e: &Exchange) -> String {
    if e.answer == AnswerKind::None {
        return "-".to_string();
    }
    let mut wait = u64::from(e.timeout_ms);
    let mut all = vec![wait.to_string()];
    for _ in 0..e.retries {
        wait = wait.saturating_mul(u64::from(e.backoff));
        all.push(wait.to_string());
    }
    format!("{} ms", all.join(", "))
}

fn name(f: &Frame, v: usize) -> String {
    format!("`{}`", f.values[v].name)
}

/// How an answer is matched to its request, in words; `own` is the header value an answer
/// sets for itself (the answering device's id, for a request of several answers).
fn matched(p: &Protocol, s: &Session, f: &Frame, own: Option<usize>) -> String {
    let kind = match s.default.answer {
        AnswerKind::None => "its kind (command)".to_string(),
        AnswerKind::Reply => "its command (the request's)".to_string(),
        AnswerKind::Ack => "its acknowledgement flag".to_string(),
        AnswerKind::Command(c) => format!("its command (`{}`)", p.commands[c].name),
        AnswerKind::Message => "its place after the request (it carries no command)".to_string(),
    };
    let mut parts = vec![kind];
    if let Some(q) = s.sequence {
        parts.push(format!("{} repeated", name(f, q)));
    }
    parts.extend(s.echo.iter().map(|&v| match own {
        Some(o) if o == v => format!("its own {}", name(f, v)),
        _ => format!("{} repeated", name(f, v)),
    }));
    if let Some((a, b)) = s.swap {
        parts.push(format!("{} and {} swapped", name(f, a), name(f, b)));
    }
    if let Some(n) = s.nack {
        parts.push(format!("`{}` refuses", p.commands[n].name));
    }
    parts.join("; ")
}

/// The rules, one row each.
fn rules(p: &Protocol, s: &Session, f: &Frame, out: &mut String) {
    let _ = writeln!(out, "| rule | value |\n|---|---|");
    let _ = writeln!(out, "| frame format | `{}` |", f.name);
    let d = &s.default;
    let _ = writeln!(out, "| a request expects | {} |", answer_text(p, d.answer));
    let _ = writeln!(
        out,
        "| an answer is matched by | {} |",
        matched(p, s, f, None)
    );
    let _ = writeln!(
        out,
        "| waits before each retry, then the timeout | {} |",
        waits(d)
    );
    let dup = match s.sequence {
        Some(q) => format!("answered again, not delivered twice (by {})", name(f, q)),
        None => "delivered again (no sequence number)".to_string(),
    };
    let _ = writeln!(out, "| a request received twice | {dup} |");
    for d in p.directions.iter().filter(|d| d.empty) {
        let _ = writeln!(
            out,
            "| a request is refused by | a frame of direction `{}` that carries its command ({}) |",
            d.name,
            super::cell(&d.doc)
        );
    }
    if let Some(h) = s.handshake {
        let _ = writeln!(
            out,
            "| handshake | `{}`, answered before any other request |",
            p.commands[h].name
        );
    }
    if let Some(m) = s.modes {
        let range =
            |r: Option<(u64, u64)>, what: &str| r.map(|(a, b)| format!("{a} to {b}: {what}"));
        let modes: Vec<String> = [
            range(m.none, "no answer"),
            range(m.once, "answered, not retried"),
        ]
        .into_iter()
        .flatten()
        .collect();
        let _ = writeln!(
            out,
            "| modes ({}) | {}; other values: as the command says |",
            name(f, m.value),
            modes.join("; ")
        );
    }
    for pd in &s.periodic {
        let who = match pd.sender {
            protocol_runtime::session::Sender::Requester => "the requester",
            protocol_runtime::session::Sender::Responder => "the responder",
            protocol_runtime::session::Sender::Both => "each side",
        };
        let _ = writeln!(
            out,
            "| periodic | `{}` every {} ms, sent by {who}. {} |",
            p.commands[pd.command].name,
            pd.period_ms,
            super::cell(&pd.doc)
        );
    }
    if let Some(w) = &s.watchdog {
        let _ = writeln!(
            out,
            "| watchdog | `{}` at least every {} ms. {} |",
            p.commands[w.command].name,
            w.period_ms,
            super::cell(&w.doc)
        );
    }
    out.push('\n');
}

/// Each command's conversation: what its request expects, the values its answer repeats under
/// other names, and the method of the generated handler that receives it.
fn per_command(p: &Protocol, s: &Session, f: &Frame, out: &mut String) {
    let trait_name = if p.directions.is_empty() {
        "Handler".to_string()
    } else {
        p.directions
            .first()
            .map_or_else(String::new, |d| format!("{}Handler", d.rust_name))
    };
    let _ = writeln!(
        out,
        "Each command's request, as the responder's `{trait_name}` receives it (its method \
         returns the answer as a `session::Reply` when one is expected; `dispatch` encodes it):\n"
    );
    let _ = writeln!(
        out,
        "| command | handler method | expects | waits | the answer repeats |\n|---|---|---|---|---|"
    );
    for e in &s.exchanges {
        let c = &p.commands[e.command];
        let repeats: Vec<String> = s
            .pairs
            .iter()
            .filter(|pr| pr.command == e.command)
            .map(|pr| format!("`{}` as `{}`", pr.names.0, pr.names.1))
            .collect();
        let repeats = if e.answer == AnswerKind::None {
            "-".to_string()
        } else if repeats.is_empty() {
            let own = s.fanouts.iter().find(|fo| fo.command == e.command);
            matched(p, s, f, own.map(|fo| fo.by))
        } else {
            repeats.join(", ")
        };
        let mut expects = answer_text(p, e.answer);
        if let Some(v) = s.verdicts.iter().find(|v| v.command == e.command) {
            expects.push_str(&format!(" ({})", verdict_text(v)));
        }
        if let Some(fo) = s.fanouts.iter().find(|fo| fo.command == e.command) {
            expects.push_str(&format!(
                ", one from each id `{}` lists (its `{}`)",
                fo.names.0, fo.names.1
            ));
        }
        let _ = writeln!(
            out,
            "| `{}` | `{}` | {} | {} | {} |",
            c.name,
            c.name.to_ascii_lowercase(),
            expects,
            waits(e),
            repeats
        );
    }
    out.push('\n');
}

/// A sequence diagram of an exchange.
fn diagram(p: &Protocol, s: &Session, f: &Frame, e: &Exchange, out: &mut String) {
    let seq = s
        .sequence
        .map(|q| format!(" ({} n)", f.values[q].name))
        .unwrap_or_default();
    let _ = writeln!(out, "```mermaid\nsequenceDiagram");
    let _ = writeln!(
        out,
        "    participant R as requester\n    participant S as responder"
    );
    if let Some(h) = s.handshake {
        let answer = match s.exchanges.get(h).map_or(e.answer, |x| x.answer) {
            AnswerKind::Reply => p.commands[h].name.clone(),
            other => answer_text(p, other).replace('`', ""),
        };
        let _ = writeln!(
            out,
            "    R->>S: {}\n    S-->>R: {answer}",
            p.commands[h].name
        );
    }
    let _ = writeln!(out, "    R->>S: request{seq}");
    let answer = answer_text(p, e.answer).replace('`', "");
    let refusal = p.directions.iter().find(|d| d.empty);
    match (s.verdicts.iter().find(|v| v.command == e.command), refusal) {
        (Some(v), _) => verdict_lines(v, &answer, &seq, out),
        (None, Some(d)) => {
            let _ = writeln!(out, "    alt answered\n        S-->>R: {answer}{seq}");
            let _ = writeln!(
                out,
                "    else refused\n        S-->>R: {} (the request's command, no payload){seq}\n    end",
                d.name
            );
        }
        (None, None) => {
            let _ = writeln!(out, "    S-->>R: {answer}{seq}");
        }
    }
    let note = if e.retries == 0 {
        format!("no answer in {}: timed out", waits(e))
    } else {
        format!(
            "no answer: sent again after each wait but the last ({}), then timed out",
            waits(e)
        )
    };
    let _ = writeln!(out, "    Note over R: {note}");
    let _ = writeln!(out, "```\n");
}

/// The answers of an exchange whose answer says success by a value: progress, then the end.
fn verdict_lines(v: &Verdict, answer: &str, seq: &str, out: &mut String) {
    if let Some(p) = v.progress.first() {
        let _ = writeln!(out, "    S-->>R: {answer}{seq}, {} = {p}", v.field);
        let _ = writeln!(
            out,
            "    Note over R: in progress: waits again, not sent again"
        );
    }
    let ok = v.accept.first().copied().unwrap_or(0);
    let _ = writeln!(out, "    S-->>R: {answer}{seq}, {} = {ok}", v.field);
    let _ = writeln!(
        out,
        "    Note over R: {} {}: answered; any other value: refused, with the value",
        v.field,
        listed(&v.accept)
    );
}

/// The `## Conversation` section, when the spec has a session.
pub(super) fn session(p: &Protocol, out: &mut String) {
    let Some(s) = &p.session else {
        return;
    };
    let Some(f) = p.frames.get(s.frame) else {
        return;
    };
    let _ = writeln!(out, "## Conversation\n");
    if !s.doc.is_empty() {
        let _ = writeln!(out, "{}\n", s.doc);
    }
    rules(p, s, f, out);
    per_command(p, s, f, out);
    if s.default.answer != AnswerKind::None {
        diagram(p, s, f, &s.default, out);
    } else if let Some(e) = s.exchanges.iter().find(|e| e.answer != AnswerKind::None) {
        diagram(p, s, f, e, out);
    }
    if let Some(fo) = s.fanouts.first() {
        fanout_diagram(p, s, fo, out);
    }
}

/// A sequence diagram of a request answered once by each id it lists: two devices answer,
/// a third does not, and the request times out naming it.
fn fanout_diagram(p: &Protocol, s: &Session, fo: &crate::ir::Fanout, out: &mut String) {
    let Some(e) = s.exchanges.iter().find(|e| e.command == fo.command) else {
        return;
    };
    let (each, by) = &fo.names;
    let answer = answer_text(p, e.answer).replace('`', "");
    let _ = writeln!(
        out,
        "`{}` is answered once by each id its `{each}` lists; each answer waits {} anew, and \
         the request resolves when every listed id answered, or times out naming those that \
         did not (sent again whole after each wait but the last):\n",
        p.commands[fo.command].name,
        waits(e)
    );
    let _ = writeln!(out, "```mermaid\nsequenceDiagram");
    let _ = writeln!(
        out,
        "    participant R as requester\n    participant A as {by} 1\n    participant B as {by} 2\n    participant C as {by} 3"
    );
    let _ = writeln!(
        out,
        "    R->>A: {} ({each}: 1, 2, 3)",
        p.commands[fo.command].name
    );
    let _ = writeln!(
        out,
        "    A-->>R: {answer} ({by} 1)\n    B-->>R: {answer} ({by} 2)"
    );
    let _ = writeln!(
        out,
        "    Note over R: {by} 3 did not answer: incomplete, missing [3]"
    );
    let _ = writeln!(out, "```\n");
}
