//! The conversation at run time: the spec's [`SessionRules`], built from the same lowering as
//! generated code's `SESSION` static ([`lower_session`]) over the session format's packet
//! rules, for the runtime's session machines (`protocol_runtime::session::Requester` and
//! `Responder`) to run.

use protocol_runtime::session::SessionRules;
use protocol_spec::session::lower_session;

use crate::Codec;

impl Codec<'_> {
    /// `f` run on the spec's session rules, as generated code's `SESSION` holds them; `None`
    /// when the spec has no `[session]`. A closure, as [`with_rules`](Codec::with_rules): the
    /// rules borrow the packet rules, which borrow the format's layout, built on each call. The
    /// machines borrow the rules, so they live inside `f`.
    ///
    /// ```
    /// use protocol_dynamic::Interpreter;
    /// use protocol_runtime::session::{Requester, SendError};
    ///
    /// let interpreter =
    ///     Interpreter::load(concat!(env!("CARGO_MANIFEST_DIR"), "/../specs/hflink.toml"))?;
    /// let codec = interpreter.codec();
    /// let refused = codec.with_session(|rules| {
    ///     let mut requester = Requester::<_, 4, 128>::new(rules);
    ///     // READ_SYSTEM_INFO from 0x01 to 0x11, before the handshake.
    ///     let mut frame = [0xFF, 0xFF, 0x01, 0x11, 0x00, 0x01, 0x01, 0x14];
    ///     requester.send(0, &mut frame)
    /// });
    /// assert_eq!(refused, Some(Err(SendError::Handshake)));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn with_session<R>(&self, f: impl FnOnce(&SessionRules<'_>) -> R) -> Option<R> {
        let plan = lower_session(self.protocol())?;
        let echo = plan.echo_fields();
        let pairs = plan.runtime_pairs();
        let verdicts = plan.runtime_verdicts();
        let fanouts = plan.runtime_fanouts();
        self.with_rules(plan.frame, |packet| {
            f(&plan.rules(packet, &plan.exchanges, &echo, &pairs, &verdicts, &fanouts))
        })
    }
}
