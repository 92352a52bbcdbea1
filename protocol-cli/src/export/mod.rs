//! Captures written for tools that read tables and logs: one CSV file per command
//! ([`csv`]), and an MCAP file with one channel per command ([`mcap`]) whose JSON schema is
//! derived from the spec ([`schema`]).
//!
//! The frames come from [`decode_capture`] (or [`each_frame`], one at a time), which runs a
//! [`Session`] in JSON mode, the one place that turns a decoded frame into the objects
//! `protocol decode --format json` prints: an export holds exactly what `decode` prints, field
//! for field. Events (rejected candidates, skipped bytes, unknown commands) are not frames and
//! are left out.

pub mod csv;
pub mod mcap;
pub mod schema;

use std::io;

use protocol_dynamic::Codec;
use serde_json::Value;

use crate::candump::CanRecord;
use crate::session::{Output, Session};

/// A capture to decode: raw bytes of a serial link, or the records of a CAN log.
#[derive(Debug, Clone, Copy)]
pub enum Capture<'a> {
    /// A byte stream, decoded by the stream engine; `link`: every command format of the
    /// link (as `decode` without `--frame`), else the one format given.
    Bytes {
        /// The bytes.
        data: &'a [u8],
        /// Decode with the link's decoder of several formats.
        link: bool,
    },
    /// The records of a CAN log, in order.
    Can(&'a [CanRecord]),
}

/// One decoded frame of a capture.
#[derive(Debug, Clone, PartialEq)]
pub struct Record {
    /// The frame's object, as `protocol decode --format json` prints it.
    pub value: Value,
    /// Receive time in nanoseconds since the Unix epoch, when the capture has times (a
    /// candump log's timestamps).
    pub time_ns: Option<u64>,
}

impl Record {
    /// The frame's offset: its first byte in a byte stream, its record's index in a CAN log.
    pub fn offset(&self) -> u64 {
        self.value
            .get("offset")
            .and_then(Value::as_u64)
            .unwrap_or(0)
    }

    /// What the frame's table or channel is named after: its command, else its frame format
    /// (a format without commands).
    pub fn key(&self) -> &str {
        ["command", "format"]
            .iter()
            .find_map(|k| self.value.get(*k).and_then(Value::as_str))
            .unwrap_or("frames")
    }
}

/// Decodes every frame of a capture with frame format `format` of `codec`, through the same
/// session as `protocol decode --format json`.
///
/// # Errors
/// Only an internal failure to read back a JSON line the session wrote.
pub fn decode_capture(
    codec: &Codec<'_>,
    format: usize,
    capture: Capture<'_>,
) -> io::Result<Vec<Record>> {
    let mut out = Vec::new();
    each_frame(codec, format, capture, &mut |r| out.push(r))?;
    Ok(out)
}

/// Decodes every frame of a capture as [`decode_capture`] does, handing each to `each` as soon
/// as it is decoded: a long capture is never held decoded whole.
///
/// # Errors
/// Only an internal failure to read back a JSON line the session wrote.
pub fn each_frame(
    codec: &Codec<'_>,
    format: usize,
    capture: Capture<'_>,
    each: &mut dyn FnMut(Record),
) -> io::Result<()> {
    let mut on_line = |line: &[u8]| -> io::Result<()> {
        let value: Value = serde_json::from_slice(line).map_err(io::Error::other)?;
        if value.get("event").is_some() {
            return Ok(());
        }
        let time_ns = match capture {
            Capture::Can(records) => value
                .get("offset")
                .and_then(Value::as_u64)
                .and_then(|i| records.get(usize::try_from(i).ok()?))
                .and_then(|r| r.time.as_deref())
                .and_then(time_ns),
            Capture::Bytes { .. } => None,
        };
        each(Record { value, time_ns });
        Ok(())
    };
    let sink = Lines {
        partial: Vec::new(),
        on_line: &mut on_line,
    };
    let mut session = Session::new(codec, format, Output::Json, sink);
    match capture {
        Capture::Bytes { data, link } => {
            let decoder = if link {
                codec.link_stream()
            } else {
                codec.stream(format)
            };
            let mut decoder = decoder.ok_or_else(|| {
                io::Error::other(format!(
                    "frame format #{format} cannot decode a byte stream"
                ))
            })?;
            session.fed(data.len());
            let mut rest = data;
            while let Some(item) = decoder.next_item(&mut rest) {
                session.item(item)?;
            }
            while let Some(item) = decoder.flush_item() {
                session.item(item)?;
            }
        }
        Capture::Can(records) => {
            for (index, record) in records.iter().enumerate() {
                session.can(index as u64, record)?;
            }
        }
    }
    session.flush()
}

/// The session's output: each complete line written is handed on, and only a line not yet
/// ended is kept.
struct Lines<'f> {
    partial: Vec<u8>,
    on_line: &'f mut dyn FnMut(&[u8]) -> io::Result<()>,
}

impl io::Write for Lines<'_> {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        self.partial.extend_from_slice(buf);
        let mut start = 0;
        while let Some(end) = self.partial[start..].iter().position(|b| *b == b'\n') {
            let line = &self.partial[start..start + end];
            if !line.is_empty() {
                (self.on_line)(line)?;
            }
            start += end + 1;
        }
        self.partial.drain(..start);
        Ok(buf.len())
    }

    fn flush(&mut self) -> io::Result<()> {
        if self.partial.is_empty() {
            Ok(())
        } else {
            Err(io::Error::other("a JSON line without its end"))
        }
    }
}

/// Nanoseconds of a decimal seconds timestamp (`1700000000.500000`), read exactly (no float).
///
/// ```
/// use protocol_cli::export::time_ns;
/// assert_eq!(time_ns("1700000000.5"), Some(1_700_000_000_500_000_000));
/// assert_eq!(time_ns("12"), Some(12_000_000_000));
/// assert_eq!(time_ns("x.5"), None);
/// ```
pub fn time_ns(text: &str) -> Option<u64> {
    let (secs, frac) = text.split_once('.').unwrap_or((text, ""));
    if frac.len() > 9 || !frac.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    let frac: String = frac.chars().chain(std::iter::repeat('0')).take(9).collect();
    secs.parse::<u64>()
        .ok()?
        .checked_mul(1_000_000_000)?
        .checked_add(frac.parse().ok()?)
}

/// The records grouped by [`Record::key`], groups in order of first appearance.
pub fn by_key(records: &[Record]) -> Vec<(&str, Vec<&Record>)> {
    let mut groups: Vec<(&str, Vec<&Record>)> = Vec::new();
    for r in records {
        match groups.iter_mut().find(|(k, _)| *k == r.key()) {
            Some((_, rs)) => rs.push(r),
            None => groups.push((r.key(), vec![r])),
        }
    }
    groups
}
