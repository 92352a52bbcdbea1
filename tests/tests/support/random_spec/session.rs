//! The random spec's `[session]` table (`random_spec.rs` owns the rest of the spec): the
//! conversation rules of its first frame format, which change no byte on the wire.

use std::fmt::Write as _;

use super::Spec;

impl Spec {
    /// A `[session]` table now and then: what a request expects (nothing, the same command,
    /// the first command, an acknowledgement where the format has them), its timeout, retries
    /// and backoff, the sequence field where the header has one, a handshake or a watchdog.
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
    }
}
