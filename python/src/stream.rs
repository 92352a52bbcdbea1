//! [`StreamDecoder`]: bytes in chunks of any size in, messages and events out, on the runtime's
//! stream engine (the one generated decoders and `protocol decode` run).
//!
//! This module owns the Python face of a stream: what an item becomes (a [`Message`] or an
//! [`Event`], in the vocabulary of `protocol decode --format json`) and the counts `stats()`
//! returns. Finding, verifying and decoding frames is the run-time codec's.

use std::sync::Arc;

use protocol_dynamic::{DecodeIssue, Item, Stream};
use protocol_runtime::Reject;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyList};

use crate::message::{Event, Message};
use crate::spec::Linked;

self_cell::self_cell!(
    /// A stream engine and the codec it borrows.
    struct Engine {
        owner: Arc<Linked>,
        #[not_covariant]
        dependent: Stream,
    }
);

/// The name of a rejection in `protocol decode --format json` (`event`).
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

/// An event without a frame: skipped bytes, a rejected candidate.
pub fn reject_event(offset: u64, kind: &str, length: usize, can_id: Option<u64>) -> Event {
    Event {
        kind: kind.to_owned(),
        offset,
        length,
        error: None,
        raw: None,
        command: None,
        id: None,
        can_id,
    }
}

/// The event of a frame that passed the engine's checks and holds no message of the spec, as
/// `protocol decode` reports it.
pub fn issue_event(
    py: Python<'_>,
    offset: u64,
    raw: &[u8],
    issue: &DecodeIssue,
    can_id: Option<u64>,
) -> PyResult<Event> {
    let mut e = reject_event(offset, "bad_payload", raw.len(), can_id);
    match issue {
        DecodeIssue::UnknownCommand { id, .. } => {
            e.kind = "unknown_command".to_owned();
            e.id = Some(match id.as_slice() {
                [one] => one.into_pyobject(py)?.into_any().unbind(),
                many => PyList::new(py, many)?.into_any().unbind(),
            });
        }
        DecodeIssue::UnknownDirection { command } => {
            e.kind = "unknown_direction".to_owned();
            e.command = Some(command.clone());
        }
        DecodeIssue::DirectionNotGiven { .. } => e.kind = "unknown_direction".to_owned(),
        DecodeIssue::PayloadLength { command, .. } | DecodeIssue::InvalidEnum { command, .. } => {
            e.command = Some(command.clone());
        }
        DecodeIssue::Frame(_) => {}
    }
    e.error = Some(issue.to_string());
    e.raw = Some(PyBytes::new(py, raw).unbind());
    Ok(e)
}

/// What a stream counted besides the engine's counts.
#[derive(Default)]
struct Counts {
    input_bytes: u64,
    per_command: Vec<u64>,
    raw_frames: u64,
    unknown_command: u64,
    unknown_direction: u64,
    bad_payload: u64,
}

/// A stream decoder: `feed(data)` takes bytes as they come, in chunks of any size, and returns
/// what they complete: a `Message` for each frame of a message, an `Event` for each rejected
/// candidate, run of skipped bytes and frame without message. `flush()` ends the stream;
/// `stats()` gives the counts so far. Made by `Spec.stream()`.
#[pyclass(module = "protocol_link")]
pub struct StreamDecoder {
    engine: Engine,
    counts: Counts,
}

impl StreamDecoder {
    /// A decoder of frame format `format`, else of the link's command formats.
    pub fn new(linked: Arc<Linked>, format: Option<usize>) -> PyResult<Self> {
        let commands = linked.borrow_owner().protocol().commands.len();
        let engine = Engine::try_new(linked, |l| {
            let codec = l.borrow_dependent();
            let p = codec.protocol();
            let stream = match format {
                Some(f) => codec.stream(f),
                None if !p.link.is_empty() => codec.link_stream(),
                None => p
                    .frames
                    .iter()
                    .position(|f| matches!(f.transport, protocol_spec::ir::Transport::Serial))
                    .and_then(|f| codec.stream(f)),
            };
            stream.ok_or_else(|| PyValueError::new_err("the spec has no serial frame format"))
        })?;
        Ok(StreamDecoder {
            engine,
            counts: Counts {
                per_command: vec![0; commands],
                ..Counts::default()
            },
        })
    }
}

/// A stream item as a Python object, counted.
fn convert(
    py: Python<'_>,
    c: &mut Counts,
    linked: &Arc<Linked>,
    item: Item<'_>,
) -> PyResult<Py<PyAny>> {
    Ok(match item {
        Item::Frame {
            offset,
            bytes,
            decoded: Ok(d),
        } => {
            match d.command.and_then(|ci| c.per_command.get_mut(ci)) {
                Some(n) => *n += 1,
                None => c.raw_frames += 1,
            }
            Py::new(py, Message::new(linked.clone(), d, offset, bytes.to_vec()))?.into_any()
        }
        Item::Frame {
            offset,
            bytes,
            decoded: Err(issue),
        } => {
            match issue {
                DecodeIssue::UnknownCommand { .. } => c.unknown_command += 1,
                DecodeIssue::UnknownDirection { .. } | DecodeIssue::DirectionNotGiven { .. } => {
                    c.unknown_direction += 1;
                }
                _ => c.bad_payload += 1,
            }
            Py::new(py, issue_event(py, offset, bytes, &issue, None)?)?.into_any()
        }
        Item::Rejected { offset, reason } => {
            Py::new(py, reject_event(offset, reject_name(reason), 1, None))?.into_any()
        }
        Item::Skipped { offset, len } => {
            Py::new(py, reject_event(offset, "skipped", len, None))?.into_any()
        }
    })
}

#[pymethods]
impl StreamDecoder {
    /// Takes the next bytes of the stream; returns the messages and events they complete, in
    /// stream order.
    fn feed<'py>(&mut self, py: Python<'py>, data: &[u8]) -> PyResult<Bound<'py, PyList>> {
        self.counts.input_bytes += data.len() as u64;
        let out = PyList::empty(py);
        let counts = &mut self.counts;
        let mut input = data;
        self.engine.with_dependent_mut(|linked, stream| {
            while let Some(item) = stream.next_item(&mut input) {
                out.append(convert(py, counts, linked, item)?)?;
            }
            Ok(out)
        })
    }

    /// Ends the stream: the messages and events left in the engine's buffer (a frame cut off
    /// by the end of the input is `truncated`).
    fn flush<'py>(&mut self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let out = PyList::empty(py);
        let counts = &mut self.counts;
        self.engine.with_dependent_mut(|linked, stream| {
            while let Some(item) = stream.flush_item() {
                out.append(convert(py, counts, linked, item)?)?;
            }
            Ok(out)
        })
    }

    /// The counts so far, as a `dict`: the engine's (`frames`, `frame_bytes`, `skipped_bytes`,
    /// `bad_header`, `bad_header_check`, `bad_length`, `bad_checksum`, `bad_trailer`,
    /// `truncated`, `rejected`), the bytes fed (`input_bytes`), and the decoder's
    /// (`per_command`: frames per command name, `raw_frames`, `unknown_command`,
    /// `unknown_direction`, `bad_payload`).
    fn stats<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        let linked = self.engine.borrow_owner();
        self.engine.with_dependent(|_, stream| -> PyResult<()> {
            let s = stream.stats();
            for (k, v) in [
                ("frames", s.frames),
                ("frame_bytes", s.frame_bytes),
                ("skipped_bytes", s.skipped_bytes),
                ("bad_header", s.bad_header),
                ("bad_header_check", s.bad_header_check),
                ("bad_length", s.bad_length),
                ("bad_checksum", s.bad_checksum),
                ("bad_trailer", s.bad_trailer),
                ("truncated", s.truncated),
                ("rejected", s.rejected()),
            ] {
                d.set_item(k, v)?;
            }
            Ok(())
        })?;
        let c = &self.counts;
        d.set_item("input_bytes", c.input_bytes)?;
        let per = PyDict::new(py);
        let p = linked.borrow_owner().protocol();
        for (cmd, n) in p.commands.iter().zip(&c.per_command) {
            if *n > 0 {
                per.set_item(&cmd.name, n)?;
            }
        }
        d.set_item("per_command", per)?;
        d.set_item("raw_frames", c.raw_frames)?;
        d.set_item("unknown_command", c.unknown_command)?;
        d.set_item("unknown_direction", c.unknown_direction)?;
        d.set_item("bad_payload", c.bad_payload)?;
        Ok(d)
    }

    /// The largest frame the engine's buffer holds.
    #[getter]
    fn capacity(&self) -> usize {
        self.engine.with_dependent(|_, s| s.capacity())
    }

    fn __repr__(&self) -> String {
        let frames = self.engine.with_dependent(|_, s| s.stats().frames);
        format!("StreamDecoder(frames={frames})")
    }
}
