//! The spec as written, `[session]`: who answers whom on the link (the answer a request
//! expects, how it is matched, timeouts, retries, a handshake, a watchdog, sequence numbers).
//! Part of the serde model ([`super::model`]); nothing is interpreted here.

#[cfg(feature = "schema")]
use schemars::JsonSchema;
use serde::Deserialize;
use toml::Spanned;

use super::model::{SInt, SStr};

/// `[session]`: the conversation of the link's commands.
#[derive(Debug, Deserialize)]
#[cfg_attr(feature = "schema", derive(JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct SessionDef {
    /// The frame format whose frames the conversation reads (default: the first format).
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub frame: Option<SStr>,
    /// The answer a request expects by default: `"none"`, `"reply"` (the same command back),
    /// `"ack"` (the format's acknowledgement) or the name of the command that answers.
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub answer: Option<SStr>,
    /// A command that answers any open request as a refusal (a NACK).
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub nack: Option<SStr>,
    /// The header field the requester numbers and an answer repeats; the responder suppresses
    /// duplicates by it.
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub sequence: Option<SStr>,
    /// Further header fields an answer repeats from its request (a session id).
    #[serde(rename = "match")]
    #[cfg_attr(feature = "schema", schemars(with = "Option<Vec<String>>"))]
    pub match_fields: Option<Spanned<Vec<SStr>>>,
    /// Two address fields, `[sender, receiver]`, that an answer swaps.
    #[cfg_attr(feature = "schema", schemars(with = "Option<Vec<String>>"))]
    pub addresses: Option<Spanned<Vec<SStr>>>,
    /// Milliseconds a request waits for its answer before it is sent again (default 100).
    #[cfg_attr(feature = "schema", schemars(with = "Option<i64>"))]
    pub timeout_ms: Option<SInt>,
    /// Times a request is sent again before it times out (default 0).
    #[cfg_attr(feature = "schema", schemars(with = "Option<i64>"))]
    pub retries: Option<SInt>,
    /// Each retry waits this many times longer than the one before (1 to 8, default 1).
    #[cfg_attr(feature = "schema", schemars(with = "Option<i64>"))]
    pub backoff: Option<SInt>,
    /// A command whose answered request must precede every other request.
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub handshake: Option<SStr>,
    /// A command that must keep arriving.
    #[cfg_attr(feature = "schema", schemars(with = "Option<WatchdogDef>"))]
    pub watchdog: Option<Spanned<WatchdogDef>>,
    /// A header field whose value says, per request, whether an answer is expected.
    #[cfg_attr(feature = "schema", schemars(with = "Option<ModesDef>"))]
    pub modes: Option<Spanned<ModesDef>>,
    /// Commands sent at a fixed rate.
    #[cfg_attr(feature = "schema", schemars(with = "Option<Vec<PeriodicDef>>"))]
    pub periodic: Option<Spanned<Vec<Spanned<PeriodicDef>>>>,
    /// Documentation.
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub doc: Option<SStr>,
}

/// `watchdog = { command = "NAME", period_ms = 500 }`.
#[derive(Debug, Deserialize)]
#[cfg_attr(feature = "schema", derive(JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct WatchdogDef {
    /// The command that must keep arriving.
    #[cfg_attr(feature = "schema", schemars(with = "String"))]
    pub command: SStr,
    /// Longest gap, in milliseconds, between two of its frames.
    #[cfg_attr(feature = "schema", schemars(with = "i64"))]
    pub period_ms: SInt,
    /// Documentation (what the receiver does when it expires).
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub doc: Option<SStr>,
}

/// `modes = { field = "session_id", none = [0, 0], once = [1, 1] }`.
#[derive(Debug, Deserialize)]
#[cfg_attr(feature = "schema", derive(JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct ModesDef {
    /// The header field.
    #[cfg_attr(feature = "schema", schemars(with = "String"))]
    pub field: SStr,
    /// Values `[first, last]` of a request that expects no answer.
    #[cfg_attr(feature = "schema", schemars(with = "Option<Vec<i64>>"))]
    pub none: Option<Spanned<Vec<SInt>>>,
    /// Values `[first, last]` of a request that expects an answer but is sent once.
    #[cfg_attr(feature = "schema", schemars(with = "Option<Vec<i64>>"))]
    pub once: Option<Spanned<Vec<SInt>>>,
}

/// A command's `result = { field = "result", accept = [0], progress = [5] }`: the value of its
/// answer that says whether the request succeeded.
#[derive(Debug, Deserialize)]
#[cfg_attr(feature = "schema", derive(JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct ResultDef {
    /// The answer's field: a header field the sender sets, or an integer field of the
    /// answer's payload at a fixed position.
    #[cfg_attr(feature = "schema", schemars(with = "String"))]
    pub field: SStr,
    /// The values that mean success; every other value refuses the request.
    #[cfg_attr(feature = "schema", schemars(with = "Vec<i64>"))]
    pub accept: Spanned<Vec<SInt>>,
    /// The values that mean the request is being carried out: it waits on, not sent again.
    #[cfg_attr(feature = "schema", schemars(with = "Option<Vec<i64>>"))]
    pub progress: Option<Spanned<Vec<SInt>>>,
}

/// `periodic = [{ command = "HEARTBEAT", period_ms = 1000, sender = "both" }]`.
#[derive(Debug, Deserialize)]
#[cfg_attr(feature = "schema", derive(JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct PeriodicDef {
    /// The command sent at the rate.
    #[cfg_attr(feature = "schema", schemars(with = "String"))]
    pub command: SStr,
    /// Milliseconds between two of its frames.
    #[cfg_attr(feature = "schema", schemars(with = "i64"))]
    pub period_ms: SInt,
    /// Which side sends it: `"requester"`, `"responder"` or `"both"` (default).
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub sender: Option<SStr>,
    /// Documentation.
    #[cfg_attr(feature = "schema", schemars(with = "Option<String>"))]
    pub doc: Option<SStr>,
}

/// A command's `answers = { each = "ids", by = "id" }`: its request is answered once by each
/// id it lists.
#[derive(Debug, Deserialize)]
#[cfg_attr(feature = "schema", derive(JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct AnswersDef {
    /// Where the request lists the ids: a repeated `u8` field of its payload (`ids`), or a
    /// `u8` field of its repeated elements (`servos.id`).
    #[cfg_attr(feature = "schema", schemars(with = "String"))]
    pub each: SStr,
    /// The header field of an answer that holds the id of the device that sent it.
    #[cfg_attr(feature = "schema", schemars(with = "String"))]
    pub by: SStr,
}
