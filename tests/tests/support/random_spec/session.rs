//! The random spec's `[session]` table (`random_spec.rs` owns the rest of the spec): the
//! conversation rules of its first frame format, which change no byte on the wire.

use std::fmt::Write as _;

use super::{Rng, Spec};

impl Spec {
    /// A `[session]` table now and then: what a request expects (nothing, the same command,
    /// the first command, an acknowledgement where the format has them), its timeout, retries
    /// and backoff, the sequence field where the header has one, a handshake or a watchdog,
    /// and a command answered once by each id its request lists.
    /// It changes no byte: the front end validates it and generated code holds it.
    pub(super) fn emit_session(&mut self) {
        let mut side = self.side();
        if !side.one_in(5) {
            return;
        }
        self.feature("session");
        let mut answers = vec!["none", "reply", "C0"];
        if self.shape.ack {
            answers.push("ack");
        }
        let answer = *side.pick(&answers);
        writeln!(self.out, "[session]\nanswer = \"{answer}\"").unwrap();
        let timeout = side.range(1, 2000);
        let (retries, backoff) = (side.below(4), side.range(1, 8));
        writeln!(
            self.out,
            "timeout_ms = {timeout}\nretries = {retries}\nbackoff = {backoff}"
        )
        .unwrap();
        // The sequence field of the first format, the session's frame.
        let main = self.out.split("[frames.main]").nth(1).unwrap_or("");
        let main = main.split("\n[").next().unwrap_or("");
        let mut senders = main_values(main);
        if main.contains("{ field = \"seq\", type = \"u8\"") && side.one_in(2) {
            self.feature("session-sequence");
            writeln!(self.out, "sequence = \"seq\"").unwrap();
        }
        // A handshake expects an answer.
        if answer != "none" && side.one_in(3) {
            self.feature("session-handshake");
            writeln!(self.out, "handshake = \"C0\"").unwrap();
        } else if side.one_in(3) {
            self.feature("session-watchdog");
            let period = side.range(10, 5000);
            writeln!(
                self.out,
                "watchdog = {{ command = \"C0\", period_ms = {period} }}"
            )
            .unwrap();
        }
        self.out.push('\n');
        // The numbered field is the requester's, not the sender's id.
        if self.out.contains("\nsequence = \"seq\"") {
            senders.retain(|s| *s != "seq");
        }
        if answer != "none" && answer != "ack" {
            self.emit_answers(&mut side, senders);
        }
    }

    /// `answers` on a command whose request lists one-byte ids at a fixed place, answered by
    /// a header value of `senders` (one-byte values the sender sets): drawn after the rest of
    /// the session, so that a seed's other choices stay as they are.
    fn emit_answers(&mut self, side: &mut Rng, senders: Vec<&'static str>) {
        let listing: Vec<(String, String)> = self
            .commands_lines()
            .into_iter()
            .filter_map(|(command, payload)| {
                let p = self.payloads.iter().find(|p| p.name == payload)?;
                Some((command, p.ids.clone()?))
            })
            .collect();
        if listing.is_empty() || senders.is_empty() {
            return;
        }
        let (command, each) = side.pick(&listing).clone();
        let by = *side.pick(&senders);
        let line_start = format!("\n{command} = {{ id = ");
        let Some(at) = self.out.find(&line_start) else {
            return;
        };
        let end = at + 1 + self.out[at + 1..].find('\n').unwrap_or(0);
        let Some(close) = self.out[..end].rfind(" }") else {
            return;
        };
        self.feature("session-answers");
        self.out.insert_str(
            close,
            &format!(", answers = {{ each = \"{each}\", by = \"{by}\" }}"),
        );
    }

    /// Each command of `[commands]` with the struct its request carries.
    fn commands_lines(&self) -> Vec<(String, String)> {
        let table = self.out.split("\n[commands]\n").nth(1).unwrap_or("");
        let table = table.split("\n\n").next().unwrap_or("");
        table
            .lines()
            .filter_map(|line| {
                let (command, rest) = line.split_once(" = { id = ")?;
                let key = [", payload = \"", ", request = \""]
                    .iter()
                    .find_map(|k| rest.split_once(k))?;
                let payload = key.1.split('"').next()?;
                Some((command.to_string(), payload.to_string()))
            })
            .collect()
    }
}

/// The one-byte header values of the first format that the sender sets and no rule computes:
/// a sequence field that is no counter, a field after the payload that is no counter, a user
/// bit member.
fn main_values(main: &str) -> Vec<&'static str> {
    let mut out = Vec::new();
    if main.contains("{ field = \"seq\", type = \"u8\" }") {
        out.push("seq");
    }
    if main.contains("{ field = \"after\", type = \"u8\" }") {
        out.push("after");
    }
    if main.contains("{ name = \"fuser\", bits = ") {
        out.push("fuser");
    }
    out
}
