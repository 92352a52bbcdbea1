//! A decoding session of `protocol decode`: turns the items of a decoded stream (and CAN log
//! records) into output lines, JSON Lines or table, and counts what it saw for `--stats`.
//!
//! Unknown commands and bad frames are events like any other: they are printed and counted,
//! and the decode goes on. The byte accounting of a serial stream is the engine's
//! ([`protocol_runtime::Stats`]); this module adds what only an interpreter knows (commands,
//! payload errors).

use std::io::{self, Write};
use std::time::Duration;

use protocol_dynamic::registers::RegisterValues;
use protocol_dynamic::{Codec, Conversation, DecodeIssue, Decoded, Item, hex};
use protocol_runtime::{CanFrame, DecodeError, Reject, Stats};
use serde_json::{Map, Value};

use crate::candump::CanRecord;
use crate::counter::Counters;
use crate::table::{Widths, event_line, frame_line};

/// How frames and events are printed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Output {
    /// One aligned line per frame or event.
    Table,
    /// One JSON object per line.
    Json,
}

/// What a session counted.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Counts {
    /// Frames decoded into messages, and their bytes, per command (spec order).
    pub per_command: Vec<(u64, u64)>,
    /// Frames of a format without commands.
    pub raw_frames: u64,
    /// Frames decoded (messages and raw frames).
    pub frames: u64,
    /// Bytes of the decoded frames.
    pub frame_bytes: u64,
    /// Payload bytes of the decoded frames.
    pub payload_bytes: u64,
    /// Valid frames with an id no command has.
    pub unknown_command: u64,
    /// Valid frames whose header matches no direction.
    pub unknown_direction: u64,
    /// Valid frames whose payload does not fit their command (size, enum value).
    pub bad_payload: u64,
    /// CAN frames rejected, by reason (serial rejections are in the engine's stats).
    pub can_rejected: Vec<(String, u64)>,
    /// CAN records that are not data frames (remote requests, CAN FD).
    pub can_skipped: u64,
    /// Bytes received (serial), or data bytes of the CAN records.
    pub input_bytes: u64,
    /// Bytes of the `skipped` events (serial).
    pub skipped_event_bytes: u64,
    /// Rejected candidates (serial): each an event of 1 byte.
    pub rejected: u64,
    /// Lost and reordered frames, from the spec's frame counters.
    pub counters: Counters,
    /// Answers paired with their requests, and requests never answered (`--session`).
    pub conversation: Option<(u64, u64)>,
}

/// The JSON name of a rejection.
pub fn reject_name(reason: Reject) -> &'static str {
    match reason {
        Reject::BadHeader => "bad_header",
        Reject::BadHeaderCheck => "bad_header_check",
        Reject::BadLength => "bad_length",
        Reject::BadChecksum => "bad_checksum",
        Reject::BadTrailer => "bad_trailer",
        Reject::BadEscape => "bad_escape",
        Reject::Truncated => "truncated",
        _ => "rejected",
    }
}

/// A decoding session writing to `out`.
pub struct Session<'c, 'a, W: Write> {
    codec: &'c Codec<'a>,
    format: usize,
    output: Output,
    widths: Widths,
    out: W,
    /// The receive time of the items being handled (live inputs), since the Unix epoch.
    received: Option<Duration>,
    /// The conversation followed through the frames (`--session`).
    conversation: Option<Conversation>,
    /// What was counted so far.
    pub counts: Counts,
}

impl<'c, 'a, W: Write> Session<'c, 'a, W> {
    /// A session decoding frames of format `format` of `codec`'s protocol.
    pub fn new(codec: &'c Codec<'a>, format: usize, output: Output, out: W) -> Self {
        let p = codec.protocol();
        Session {
            codec,
            format,
            output,
            widths: Widths::of(p),
            out,
            received: None,
            conversation: None,
            counts: Counts {
                per_command: vec![(0, 0); p.commands.len()],
                ..Counts::default()
            },
        }
    }

    /// Follows the spec's conversation through the frames ([`Conversation`]): each frame
    /// line gets its `frame` number, an answer the request it `answers` and its `rtt_ms`.
    pub fn follow_conversation(&mut self) {
        self.conversation = Some(Conversation::new());
    }

    /// Closes the conversation (the input ended): the requests still open count unanswered.
    pub fn finish(&mut self) {
        if let Some(c) = self.conversation.as_mut() {
            let unanswered = c.finish();
            self.counts.conversation = Some((c.answered(), unanswered));
        }
    }

    /// Handles one item of a decoded stream ([`protocol_dynamic::Stream`]).
    ///
    /// # Errors
    /// When the output cannot be written.
    pub fn item(&mut self, item: Item<'_>) -> io::Result<()> {
        match item {
            Item::Frame {
                offset,
                bytes,
                decoded,
            } => match self.conversation.as_mut() {
                Some(c) => {
                    let format = decoded.as_ref().map_or(self.format, |d| d.format);
                    let at = self.received.map(|d| d.as_millis() as u64);
                    let heard = c.hear(self.codec, format, bytes, at, decoded);
                    let mut extra = Map::new();
                    extra.insert("frame".into(), Value::from(heard.index));
                    if let Some(a) = heard.answers {
                        extra.insert("answers".into(), Value::from(a.request));
                        if let Some(rtt) = a.round_trip {
                            extra.insert("rtt_ms".into(), Value::from(rtt));
                        }
                        // An in-progress answer, or one of several: more are to come.
                        if a.open {
                            extra.insert("request_open".into(), Value::Bool(true));
                        }
                        // An error reply (a frame of an empty direction): the request's refusal.
                        if a.refused {
                            extra.insert("refused".into(), Value::Bool(true));
                        }
                    }
                    registers_fields(&mut extra, heard.registers);
                    self.decoded(offset, bytes, heard.decoded, extra)
                }
                None => self.decoded(offset, bytes, decoded, Map::new()),
            },
            Item::Rejected { offset, reason } => {
                self.counts.rejected += 1;
                self.emit(offset, reject_name(reason), 1, Map::new())
            }
            Item::Skipped { offset, len } => {
                self.counts.skipped_event_bytes += len as u64;
                self.emit(offset, "skipped", len, Map::new())
            }
        }
    }

    /// Stamps the items handled from now on with their receive time (since the Unix epoch):
    /// a live input's frames and events carry it, as `time` (seconds) in JSON and in front of
    /// a table line. `None` for a file, whose bytes have no time.
    pub fn received(&mut self, at: Option<Duration>) {
        self.received = at;
    }

    /// Counts bytes fed to the engine (for the link efficiency).
    pub fn fed(&mut self, bytes: usize) {
        self.counts.input_bytes += bytes as u64;
    }

    /// Handles one record of a CAN log (`index`: its position in the log, from 0).
    ///
    /// # Errors
    /// When the output cannot be written.
    pub fn can(&mut self, index: u64, record: &CanRecord) -> io::Result<()> {
        self.counts.input_bytes += record.data.len() as u64;
        let mut extra = Map::new();
        extra.insert("can_id".into(), Value::from(record.id));
        if record.remote || record.fd {
            self.counts.can_skipped += 1;
            let kind = if record.remote {
                "remote request"
            } else {
                "CAN FD frame"
            };
            extra.insert(
                "error".into(),
                Value::from(format!("{kind}: not a classic data frame")),
            );
            return self.emit(index, "skipped", record.data.len(), extra);
        }
        let frame = match CanFrame::new(record.id, &record.data) {
            Ok(f) => CanFrame {
                extended: record.extended,
                ..f
            },
            Err(_) => return self.can_reject(index, record, Reject::BadLength, extra),
        };
        match self.codec.decode_can(self.format, &frame) {
            Err(DecodeIssue::Frame(DecodeError::Frame(reason))) => {
                self.can_reject(index, record, reason, extra)
            }
            result => self.decoded(index, &record.data, result, extra),
        }
    }

    fn can_reject(
        &mut self,
        index: u64,
        record: &CanRecord,
        reason: Reject,
        extra: Map<String, Value>,
    ) -> io::Result<()> {
        let name = reject_name(reason);
        match self.counts.can_rejected.iter_mut().find(|(n, _)| n == name) {
            Some((_, n)) => *n += 1,
            None => self.counts.can_rejected.push((name.to_string(), 1)),
        }
        self.emit(index, name, record.data.len(), extra)
    }

    fn decoded(
        &mut self,
        offset: u64,
        shown: &[u8],
        result: Result<Decoded, DecodeIssue>,
        mut extra: Map<String, Value>,
    ) -> io::Result<()> {
        let p = self.codec.protocol();
        let d = match result {
            Ok(d) => d,
            Err(issue) => {
                let event = match &issue {
                    DecodeIssue::UnknownCommand { id, .. } => {
                        self.counts.unknown_command += 1;
                        let id = match id.as_slice() {
                            [one] => Value::from(*one),
                            many => Value::from(many.to_vec()),
                        };
                        extra.insert("id".into(), id);
                        "unknown_command"
                    }
                    DecodeIssue::UnknownDirection { command } => {
                        self.counts.unknown_direction += 1;
                        extra.insert("command".into(), Value::from(command.clone()));
                        "unknown_direction"
                    }
                    DecodeIssue::DirectionNotGiven { .. } => {
                        self.counts.unknown_direction += 1;
                        "unknown_direction"
                    }
                    DecodeIssue::PayloadLength { command, .. }
                    | DecodeIssue::InvalidEnum { command, .. } => {
                        self.counts.bad_payload += 1;
                        extra.insert("command".into(), Value::from(command.clone()));
                        "bad_payload"
                    }
                    DecodeIssue::Frame(_) => {
                        self.counts.bad_payload += 1;
                        "bad_payload"
                    }
                };
                extra.insert("error".into(), Value::from(issue.to_string()));
                extra.insert("hex".into(), Value::from(hex(shown)));
                return self.emit(offset, event, shown.len(), extra);
            }
        };
        self.counts.frames += 1;
        self.counts.frame_bytes += shown.len() as u64;
        self.counts.counters.observe(p, &d);
        let f = &p.frames[d.format];
        self.counts.payload_bytes +=
            shown.len().saturating_sub(f.header_len + f.trailer_len) as u64;
        match d.command.and_then(|ci| self.counts.per_command.get_mut(ci)) {
            Some((n, bytes)) => {
                *n += 1;
                *bytes += shown.len() as u64;
            }
            None => self.counts.raw_frames += 1,
        }
        let line = match self.output {
            Output::Json => {
                let value = self.codec.frame_value(&d, offset, shown);
                // A decoded CAN frame's value names its identifier already.
                if value.as_struct().is_some_and(|o| o.get("can_id").is_some()) {
                    extra.remove("can_id");
                }
                let line = match self.received {
                    None => serde_json::to_string(&value),
                    Some(at) => serde_json::to_value(&value).map(|v| match v {
                        Value::Object(o) => Value::Object(with_time(o, at)).to_string(),
                        other => other.to_string(),
                    }),
                }
                .map_err(io::Error::other)?;
                with_fields(line, extra)
            }
            Output::Table => {
                let mut line = frame_line(p, self.widths, &d, offset, shown.len());
                line.push_str(&conversation_note(&extra));
                line
            }
        };
        self.write_line(&line)
    }

    fn emit(
        &mut self,
        offset: u64,
        event: &str,
        bytes: usize,
        extra: Map<String, Value>,
    ) -> io::Result<()> {
        let line = match self.output {
            Output::Json => {
                let mut o = Map::new();
                o.insert("offset".into(), Value::from(offset));
                o.insert("event".into(), Value::from(event));
                o.insert("bytes".into(), Value::from(bytes));
                o.extend(extra);
                match self.received {
                    Some(at) => Value::Object(with_time(o, at)).to_string(),
                    None => Value::Object(o).to_string(),
                }
            }
            Output::Table => {
                let mut what = event.replace('_', " ");
                for key in ["command", "can_id", "id", "error"] {
                    if let Some(v) = extra.get(key) {
                        let text = match (key, v.as_u64()) {
                            ("can_id" | "id", Some(n)) => format!("{n:#x}"),
                            _ => v.as_str().map_or_else(|| v.to_string(), str::to_string),
                        };
                        what.push_str(&format!("  {key}={text}"));
                    }
                }
                event_line(offset, bytes, &what)
            }
        };
        self.write_line(&line)
    }

    /// Writes one output line; a table line of a live input starts with its receive time
    /// (UTC, to the microsecond).
    fn write_line(&mut self, line: &str) -> io::Result<()> {
        match (self.output, self.received) {
            (Output::Table, Some(at)) => writeln!(self.out, "{}  {line}", time_of_day(at)),
            _ => writeln!(self.out, "{line}"),
        }
    }

    /// Flushes the output.
    ///
    /// # Errors
    /// When the output cannot be written.
    pub fn flush(&mut self) -> io::Result<()> {
        self.out.flush()
    }

    /// The `--stats` summary. `engine`: the stream engine's stats (serial input).
    pub fn summary(&self, engine: Option<&Stats>) -> String {
        let p = self.codec.protocol();
        let c = &self.counts;
        let total = engine
            .map_or(c.input_bytes, |e| e.frame_bytes + e.skipped_bytes)
            .max(c.input_bytes);
        let width = p
            .commands
            .iter()
            .map(|x| x.name.len())
            .max()
            .unwrap_or(0)
            .max(7);
        let mut s = format!(
            "frames decoded: {} ({} of {} bytes)\n  {:<width$}  {:>7}  {:>9}\n",
            c.frames, c.frame_bytes, total, "command", "frames", "bytes"
        );
        for (cmd, (n, bytes)) in p.commands.iter().zip(&c.per_command) {
            if *n > 0 {
                s.push_str(&format!("  {:<width$}  {n:>7}  {bytes:>9}\n", cmd.name));
            }
        }
        if c.raw_frames > 0 {
            s.push_str(&format!(
                "  {:<width$}  {:>7}\n",
                "(no command)", c.raw_frames
            ));
        }
        s.push_str(&format!(
            "unknown commands: {}, unknown directions: {}, bad payloads: {}\n",
            c.unknown_command, c.unknown_direction, c.bad_payload
        ));
        match engine {
            Some(e) => {
                s.push_str(&format!(
                    "checksum failures: {} (frame checks {}, header checks {})\n",
                    e.bad_checksum + e.bad_header_check,
                    e.bad_checksum,
                    e.bad_header_check
                ));
                s.push_str(&format!("length rejections: {}\n", e.bad_length));
                s.push_str(&format!(
                    "other rejections: bad header {}, bad trailer {}, truncated {}\n",
                    e.bad_header, e.bad_trailer, e.truncated
                ));
                // The engine's count holds the first byte of every rejected candidate too; the
                // line says so, and splits it as the events do.
                s.push_str(&format!(
                    "bytes skipped: {} ({}): {} in skipped events, {} the first bytes of rejected candidates\n",
                    e.skipped_bytes,
                    percent(e.skipped_bytes, total),
                    c.skipped_event_bytes,
                    c.rejected
                ));
            }
            None => {
                let rejected: Vec<String> = c
                    .can_rejected
                    .iter()
                    .map(|(name, n)| format!("{} {n}", name.replace('_', " ")))
                    .collect();
                s.push_str(&format!(
                    "CAN frames rejected: {}; not data frames: {}\n",
                    if rejected.is_empty() {
                        "none".into()
                    } else {
                        rejected.join(", ")
                    },
                    c.can_skipped
                ));
            }
        }
        if let Some((answered, unanswered)) = c.conversation {
            s.push_str(&format!(
                "conversation: {answered} answers paired with their requests, {unanswered} requests unanswered\n"
            ));
        }
        if let Some(counters) = c.counters.summary() {
            s.push_str(&format!("frame counter: {counters}\n"));
        }
        s.push_str(&format!(
            "link efficiency: {} (bytes in decoded frames); payload {}\n",
            percent(c.frame_bytes, total),
            percent(c.payload_bytes, total)
        ));
        s
    }
}

/// A JSON object's text with `extra`'s fields appended, the object's own text kept as it is
/// (its floats printed at their own precision).
fn with_fields(mut line: String, extra: Map<String, Value>) -> String {
    if extra.is_empty() || !line.ends_with('}') {
        return line;
    }
    line.pop();
    for (k, v) in extra {
        line.push_str(&format!(",{}:{v}", Value::from(k)));
    }
    line.push('}');
    line
}

/// A frame's register values as `registers` (an object, in address order) and what is not a
/// whole register as `registers_note`.
fn registers_fields(extra: &mut Map<String, Value>, registers: Option<RegisterValues>) {
    let Some(r) = registers else {
        return;
    };
    // Through text, so that an `f32` keeps its shortest decimal (`12.6`).
    let object = serde_json::to_string(&protocol_dynamic::Value::Struct(r.values))
        .ok()
        .and_then(|t| serde_json::from_str::<Value>(&t).ok());
    if let Some(object) = object {
        extra.insert("registers".into(), object);
    }
    if let Some(note) = r.note {
        extra.insert("registers_note".into(), Value::from(note));
    }
}

/// The end of a table line of the conversation: the frame's number, the request an answer
/// answers with its round-trip time, and the registers the frame holds.
fn conversation_note(extra: &Map<String, Value>) -> String {
    let mut note = String::new();
    if let Some(n) = extra.get("frame") {
        note.push_str(&format!("  #{n}"));
    }
    if let Some(r) = extra.get("answers") {
        let verb = if extra.contains_key("refused") {
            "refuses"
        } else {
            "answers"
        };
        note.push_str(&format!("  {verb} #{r}"));
        if let Some(t) = extra.get("rtt_ms") {
            note.push_str(&format!(" after {t} ms"));
        }
        if extra.contains_key("request_open") {
            note.push_str(" (more to come)");
        }
    }
    if let Some(Value::Object(r)) = extra.get("registers") {
        let values: Vec<String> = r.iter().map(|(k, v)| format!("{k}={v}")).collect();
        note.push_str(&format!("  [{}]", values.join(" ")));
    }
    if let Some(Value::String(n)) = extra.get("registers_note") {
        note.push_str(&format!(" ({n})"));
    }
    note
}

/// A frame or event object with `time` (seconds since the Unix epoch, to the microsecond)
/// after its `offset`.
fn with_time(object: Map<String, Value>, at: Duration) -> Map<String, Value> {
    let seconds = at.as_micros() as f64 / 1e6;
    let mut out = Map::new();
    for (k, v) in object {
        let after_offset = k == "offset";
        out.insert(k, v);
        if after_offset {
            out.insert("time".into(), Value::from(seconds));
        }
    }
    out
}

/// The UTC time of day of a time since the Unix epoch: `HH:MM:SS.ffffff`.
///
/// ```
/// # use std::time::Duration;
/// use protocol_cli::session::time_of_day;
/// assert_eq!(time_of_day(Duration::from_micros(1_700_000_000_123_456)), "22:13:20.123456");
/// ```
pub fn time_of_day(at: Duration) -> String {
    let secs = at.as_secs() % 86_400;
    format!(
        "{:02}:{:02}:{:02}.{:06}",
        secs / 3600,
        secs / 60 % 60,
        secs % 60,
        at.subsec_micros()
    )
}

fn percent(part: u64, total: u64) -> String {
    if total == 0 {
        "0.0%".into()
    } else {
        format!("{:.1}%", part as f64 * 100.0 / total as f64)
    }
}
