//! The conversation of the IR (`[session]`): the frame format it reads, the values an answer
//! repeats, and what each command's request expects. Every name is resolved to an index.

/// The answer a request expects.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AnswerKind {
    /// None: sent once and forgotten.
    None,
    /// The same command, sent back.
    Reply,
    /// The format's acknowledgement.
    Ack,
    /// Another command (index into [`Protocol::commands`](super::Protocol::commands)).
    Command(usize),
    /// The response direction's struct, carried in place of a command.
    Message,
}

/// What a command's request expects.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Exchange {
    /// The command (index into [`Protocol::commands`](super::Protocol::commands)).
    pub command: usize,
    /// The answer.
    pub answer: AnswerKind,
    /// Milliseconds before the first retry (or the timeout).
    pub timeout_ms: u32,
    /// Times the request is sent again.
    pub retries: u8,
    /// Each retry waits this many times longer than the one before.
    pub backoff: u8,
}

/// A command that must keep arriving.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Watchdog {
    /// The command (index into [`Protocol::commands`](super::Protocol::commands)).
    pub command: usize,
    /// Longest gap between two of its frames, in milliseconds.
    pub period_ms: u32,
    /// Documentation.
    pub doc: String,
}

/// A command sent at a fixed rate.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Periodic {
    /// The command (index into [`Protocol::commands`](super::Protocol::commands)).
    pub command: usize,
    /// Milliseconds between two of its frames.
    pub period_ms: u32,
    /// Which side sends it.
    pub sender: protocol_runtime::session::Sender,
    /// Documentation.
    pub doc: String,
}

/// A header value whose value says whether a request expects an answer.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Modes {
    /// The header value (index into the session frame's values).
    pub value: usize,
    /// Values of a request that expects no answer.
    pub none: Option<(u64, u64)>,
    /// Values of a request that expects its answer, sent once.
    pub once: Option<(u64, u64)>,
}

/// Where a value an answer repeats from its request sits.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PairValue {
    /// A header value (index into the session frame's values).
    Header(usize),
    /// A fixed-position integer field of the command's payload struct.
    Payload {
        /// The field's offset in the payload.
        offset: usize,
        /// The field's wire type and byte order.
        scalar: super::Scalar,
    },
}

/// A value the answer to a command's request repeats from it under another name (a command's
/// `match`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Pair {
    /// The request's command (index into [`Protocol::commands`](super::Protocol::commands)).
    pub command: usize,
    /// Where the request holds the value.
    pub from: PairValue,
    /// Where the answer holds it.
    pub to: PairValue,
    /// The two fields' names, as the spec writes them (request's, answer's).
    pub names: (String, String),
}

/// The value of the answer to a command's request that says whether it succeeded (a
/// command's `result`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Verdict {
    /// The request's command (index into [`Protocol::commands`](super::Protocol::commands)).
    pub command: usize,
    /// Where the answer holds the value.
    pub value: PairValue,
    /// The field's name, as the spec writes it.
    pub field: String,
    /// The values that mean success; every other value refuses the request.
    pub accept: Vec<u64>,
    /// The values that mean the request is being carried out.
    pub progress: Vec<u64>,
}

/// A command whose request is answered once by each id it lists (a command's `answers`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Fanout {
    /// The request's command (index into [`Protocol::commands`](super::Protocol::commands)).
    pub command: usize,
    /// Offset of the first listed id in the request's payload.
    pub first: usize,
    /// Bytes from one listed id to the next.
    pub stride: usize,
    /// The answer's header value that names its sender (index into the session frame's
    /// values).
    pub by: usize,
    /// The two names, as the spec writes them (`each`, `by`).
    pub names: (String, String),
}

/// The conversation of the link.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Session {
    /// The frame format whose frames it reads (index into
    /// [`Protocol::frames`](super::Protocol::frames)).
    pub frame: usize,
    /// Documentation.
    pub doc: String,
    /// The header value the requester numbers (index into the frame's values).
    pub sequence: Option<usize>,
    /// Further header values an answer repeats.
    pub echo: Vec<usize>,
    /// The address values `(sender, receiver)` an answer swaps.
    pub swap: Option<(usize, usize)>,
    /// The command that refuses a request.
    pub nack: Option<usize>,
    /// The command whose answered request precedes every other.
    pub handshake: Option<usize>,
    /// A command that must keep arriving.
    pub watchdog: Option<Watchdog>,
    /// A header value that says whether a request expects an answer.
    pub modes: Option<Modes>,
    /// What a request expects unless its command says otherwise (`command` is not read).
    pub default: Exchange,
    /// What each command's request expects, in command order.
    pub exchanges: Vec<Exchange>,
    /// The values answers repeat under other names, in command order, then `match` order.
    pub pairs: Vec<Pair>,
    /// The commands whose answers tell success by a value, in command order.
    pub verdicts: Vec<Verdict>,
    /// The commands sent at a fixed rate, in spec order.
    pub periodic: Vec<Periodic>,
    /// The commands whose requests are answered once by each id they list, in command order.
    pub fanouts: Vec<Fanout>,
}
