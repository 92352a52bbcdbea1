//! [`Spec`]: a loaded spec and its codec, the entry point of the Python package.
//!
//! This module owns loading (errors become `SpecError` with the rendered diagnostics),
//! decoding one frame, and encoding one message (errors become `EncodeError` naming the
//! field). Finding frames in a stream is [`crate::stream`]'s.

use std::sync::Arc;

use protocol_dynamic::{Codec, DecodeIssue, Fields, Interpreter, LoadError, Value};
use protocol_runtime::{CanFrame, DecodeError as RuntimeDecodeError};
use protocol_spec::diag::{Diagnostic, render_all};
use protocol_spec::ir::Transport;
use protocol_spec::source::SpecSource;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyList};

use crate::convert::from_py;
use crate::message::Message;
use crate::stream::{StreamDecoder, issue_event, reject_event};
use crate::{DecodeError, EncodeError, SpecError};

self_cell::self_cell!(
    /// An interpreter and the codec borrowed from it, in one value Python can hold.
    pub struct Linked {
        owner: Interpreter,
        #[covariant]
        dependent: Codec,
    }
);

/// A protocol spec, loaded and checked: decodes and encodes its frames.
///
/// `Spec.load("specs/mavlink.toml")` reads a file, `Spec.from_str(text)` a string; both raise
/// `SpecError` with every error of the spec, located and rendered as the `protocol!` macro and
/// the `protocol` command print them. `direction` names the side of a spec whose directions no
/// header field tells (`given = true`, as Dynamixel 1.0's `instruction` and `status`).
#[pyclass(frozen, module = "protocol_link")]
pub struct Spec {
    pub(crate) linked: Arc<Linked>,
    path: String,
}

fn spec_error(py: Python<'_>, e: LoadError) -> PyErr {
    let err = SpecError::new_err(e.to_string());
    if let LoadError::Spec {
        source,
        diagnostics,
    } = &e
    {
        let attrs = diagnostic_list(py, source, diagnostics).and_then(|list| {
            let value = err.value(py);
            value.setattr("diagnostics", list)?;
            value.setattr("rendered", render_all(diagnostics, source))
        });
        if let Err(inner) = attrs {
            return inner;
        }
    }
    err
}

/// Each diagnostic as a `dict`: `severity`, `message`, `help`, `path`, `line`, `column` (from 1)
/// and `rendered` (its `--> path:line:col` block).
fn diagnostic_list<'py>(
    py: Python<'py>,
    source: &SpecSource,
    diagnostics: &[Diagnostic],
) -> PyResult<Bound<'py, PyList>> {
    let list = PyList::empty(py);
    for d in diagnostics {
        let (line, column) = source.line_col(d.span.start);
        let item = PyDict::new(py);
        item.set_item("severity", d.severity.as_str())?;
        item.set_item("message", &d.message)?;
        item.set_item("help", d.help.as_deref())?;
        item.set_item("path", &source.path)?;
        item.set_item("line", line)?;
        item.set_item("column", column)?;
        item.set_item("rendered", d.render(source))?;
        list.append(item)?;
    }
    Ok(list)
}

impl Spec {
    fn new(interp: Interpreter, path: String, direction: Option<&str>) -> PyResult<Self> {
        let directions: Vec<String> = interp
            .protocol()
            .directions
            .iter()
            .map(|d| d.name.clone())
            .collect();
        let index = match direction {
            None => None,
            Some(name) => Some(directions.iter().position(|d| d == name).ok_or_else(|| {
                PyValueError::new_err(format!(
                    "spec has no direction `{name}` (it has: {})",
                    directions.join(", ")
                ))
            })?),
        };
        let linked = Linked::new(interp, |i| i.codec().with_direction(index));
        Ok(Spec {
            linked: Arc::new(linked),
            path,
        })
    }

    fn codec(&self) -> &Codec<'_> {
        self.linked.borrow_dependent()
    }

    fn format_arg(&self, format: Option<&str>) -> PyResult<Option<usize>> {
        let Some(name) = format else { return Ok(None) };
        self.codec().format_index(name).map(Some).ok_or_else(|| {
            PyValueError::new_err(format!(
                "spec has no frame format `{name}` (it has: {})",
                self.format_names().join(", ")
            ))
        })
    }

    fn format_names(&self) -> Vec<String> {
        let p = self.codec().protocol();
        p.frames.iter().map(|f| f.name.clone()).collect()
    }

    /// The serial formats a frame is tried against: the one named, else every command format
    /// of the link, else every serial format.
    fn serial_formats(&self, format: Option<usize>) -> Vec<usize> {
        let p = self.codec().protocol();
        if let Some(f) = format {
            return vec![f];
        }
        let serial = |i: &usize| matches!(p.frames[*i].transport, Transport::Serial);
        if p.link.is_empty() {
            (0..p.frames.len()).filter(serial).collect()
        } else {
            p.link.iter().copied().filter(serial).collect()
        }
    }

    fn message(
        &self,
        py: Python<'_>,
        d: protocol_dynamic::Decoded,
        raw: &[u8],
    ) -> PyResult<Py<Message>> {
        Py::new(py, Message::new(self.linked.clone(), d, 0, raw.to_vec()))
    }
}

fn decode_error(issue: &DecodeIssue) -> PyErr {
    DecodeError::new_err(issue.to_string())
}

#[pymethods]
impl Spec {
    /// Reads, loads and checks the spec at `path`.
    #[staticmethod]
    #[pyo3(signature = (path, *, direction=None))]
    fn load(py: Python<'_>, path: std::path::PathBuf, direction: Option<&str>) -> PyResult<Self> {
        let interp = py
            .detach(|| Interpreter::load(&path))
            .map_err(|e| spec_error(py, e))?;
        Spec::new(interp, path.display().to_string(), direction)
    }

    /// Loads and checks a spec's text; `name` is the path its diagnostics show.
    #[staticmethod]
    #[pyo3(signature = (text, name="<string>", *, direction=None))]
    fn from_str(py: Python<'_>, text: &str, name: &str, direction: Option<&str>) -> PyResult<Self> {
        let interp = Interpreter::from_text(name, text).map_err(|e| spec_error(py, e))?;
        Spec::new(interp, name.to_owned(), direction)
    }

    /// The spec with another direction given (see the class documentation).
    #[pyo3(signature = (direction))]
    fn with_direction(&self, direction: Option<&str>) -> PyResult<Self> {
        let protocol = self.codec().protocol().clone();
        Spec::new(Interpreter::new(protocol), self.path.clone(), direction)
    }

    /// The protocol's name.
    #[getter]
    fn name(&self) -> &str {
        &self.codec().protocol().name
    }

    /// The path (or name) the spec was loaded from.
    #[getter]
    fn path(&self) -> &str {
        &self.path
    }

    /// The command names, in spec order.
    #[getter]
    fn commands(&self) -> Vec<String> {
        let p = self.codec().protocol();
        p.commands.iter().map(|c| c.name.clone()).collect()
    }

    /// The frame format names, in spec order.
    #[getter]
    fn formats(&self) -> Vec<String> {
        self.format_names()
    }

    /// The direction names (empty for a spec without directions).
    #[getter]
    fn directions(&self) -> Vec<String> {
        let p = self.codec().protocol();
        p.directions.iter().map(|d| d.name.clone()).collect()
    }

    /// The direction given to this spec's codec, if any.
    #[getter]
    fn direction(&self) -> Option<String> {
        let c = self.codec();
        c.direction()
            .and_then(|d| c.protocol().directions.get(d))
            .map(|d| d.name.clone())
    }

    /// Decodes the one frame that starts `frame` (verifying its framing and checks). Without
    /// `format`, the frame is tried against every serial format of the link (MAVLink 1 and 2)
    /// or of the spec, in spec order.
    ///
    /// Raises `DecodeError` when no valid frame of a message starts there.
    #[pyo3(signature = (frame, *, format=None))]
    fn decode(&self, py: Python<'_>, frame: &[u8], format: Option<&str>) -> PyResult<Py<Message>> {
        let format = self.format_arg(format)?;
        let mut first_err = None;
        for fi in self.serial_formats(format) {
            match self.codec().parse(fi, frame) {
                Ok(d) => {
                    let len = self
                        .codec()
                        .layout(fi)
                        .and_then(|l| l.parse(frame).ok())
                        .map_or(frame.len(), <[u8]>::len);
                    return self.message(py, d, &frame[..len]);
                }
                // A sync of another format: try the next one, report the first other error.
                Err(DecodeIssue::Frame(RuntimeDecodeError::Frame(
                    protocol_runtime::Reject::BadHeader,
                ))) => {
                    first_err.get_or_insert(DecodeIssue::Frame(RuntimeDecodeError::Frame(
                        protocol_runtime::Reject::BadHeader,
                    )));
                }
                Err(e) => return Err(decode_error(&e)),
            }
        }
        Err(first_err.map_or_else(
            || DecodeError::new_err("the spec has no serial frame format"),
            |e| decode_error(&e),
        ))
    }

    /// Decodes a CAN frame (`can_id`, its data bytes) of the spec's CAN format (or of
    /// `format`); `extended` is the identifier's kind (by default, the format's).
    ///
    /// Raises `DecodeError` when it holds no message of the spec.
    #[pyo3(signature = (can_id, data, *, extended=None, format=None))]
    fn decode_can(
        &self,
        py: Python<'_>,
        can_id: u32,
        data: &[u8],
        extended: Option<bool>,
        format: Option<&str>,
    ) -> PyResult<Py<Message>> {
        let fi = self.can_format(format)?;
        let frame = self.can_frame(fi, can_id, data, extended)?;
        match self.codec().decode_can(fi, &frame) {
            Ok(d) => self.message(py, d, data),
            Err(e) => Err(decode_error(&e)),
        }
    }

    /// Encodes a message: `name` is the command, its payload fields given as a `dict`
    /// (`fields`) or as keywords, the header's values as `header`. Values the spec computes
    /// (lengths, ids, checks) are computed. Returns the frame's bytes (a CAN format's virtual
    /// frame: see `encode_can`).
    ///
    /// Raises `EncodeError` naming the first missing, ill-typed or out-of-range field
    /// (`payload.lat`, `header.seq`); its `path` attribute holds the name.
    #[pyo3(signature = (name, fields=None, /, *, header=None, format=None, direction=None, **kwargs))]
    #[allow(clippy::too_many_arguments)]
    fn encode<'py>(
        &self,
        py: Python<'py>,
        name: &str,
        fields: Option<&Bound<'py, PyAny>>,
        header: Option<&Bound<'py, PyAny>>,
        format: Option<&str>,
        direction: Option<&str>,
        kwargs: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<Bound<'py, PyBytes>> {
        let object = frame_object(name, fields, header, format, direction, kwargs)?;
        let encoded = self.codec().encode(&object).map_err(|e| {
            let err = EncodeError::new_err(e.to_string());
            let _ = err.value(py).setattr("path", &e.path);
            err
        })?;
        Ok(PyBytes::new(py, &encoded.bytes))
    }

    /// As `encode`, for a CAN format: returns `(can_id, data, extended)`.
    #[pyo3(signature = (name, fields=None, /, *, header=None, format=None, direction=None, **kwargs))]
    #[allow(clippy::too_many_arguments)]
    fn encode_can<'py>(
        &self,
        py: Python<'py>,
        name: &str,
        fields: Option<&Bound<'py, PyAny>>,
        header: Option<&Bound<'py, PyAny>>,
        format: Option<&str>,
        direction: Option<&str>,
        kwargs: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<(u32, Bound<'py, PyBytes>, bool)> {
        let format = match format {
            Some(f) => Some(f.to_owned()),
            None => self
                .first_can_format()
                .map(|i| self.format_names()[i].clone()),
        };
        let object = frame_object(name, fields, header, format.as_deref(), direction, kwargs)?;
        let encoded = self
            .codec()
            .encode(&object)
            .map_err(|e| EncodeError::new_err(e.to_string()))?;
        let can = encoded
            .can
            .ok_or_else(|| EncodeError::new_err("the frame format is not a CAN format"))?;
        Ok((can.id, PyBytes::new(py, can.data()), can.extended))
    }

    /// A stream decoder of this spec (see `StreamDecoder`): of `format`, else of every command
    /// format of the link, else of the first serial format.
    #[pyo3(signature = (*, format=None))]
    fn stream(&self, format: Option<&str>) -> PyResult<StreamDecoder> {
        let format = self.format_arg(format)?;
        StreamDecoder::new(self.linked.clone(), format)
    }

    /// One record of a CAN log as `protocol decode --candump` reports it: the `Message` it
    /// holds, or an `Event` (`bad_length`, a rejection, `unknown_command`, `skipped` for a remote
    /// request or a CAN FD frame). `offset` is the record's index in the log.
    #[pyo3(signature = (can_id, data, *, extended=None, offset=0, remote=false, fd=false, format=None))]
    #[allow(clippy::too_many_arguments)]
    fn read_can(
        &self,
        py: Python<'_>,
        can_id: u32,
        data: &[u8],
        extended: Option<bool>,
        offset: u64,
        remote: bool,
        fd: bool,
        format: Option<&str>,
    ) -> PyResult<Py<PyAny>> {
        let id = Some(u64::from(can_id));
        if remote || fd {
            let kind = if remote {
                "remote request"
            } else {
                "CAN FD frame"
            };
            let mut e = reject_event(offset, "skipped", data.len(), id);
            e.error = Some(format!("{kind}: not a classic data frame"));
            return Ok(Py::new(py, e)?.into_any());
        }
        let fi = self.can_format(format)?;
        let Ok(frame) = self.can_frame(fi, can_id, data, extended) else {
            let e = reject_event(offset, "bad_length", data.len(), id);
            return Ok(Py::new(py, e)?.into_any());
        };
        match self.codec().decode_can(fi, &frame) {
            Ok(d) => Ok(Py::new(
                py,
                Message::new(self.linked.clone(), d, offset, data.to_vec()),
            )?
            .into_any()),
            Err(DecodeIssue::Frame(RuntimeDecodeError::Frame(reason))) => {
                let e = reject_event(offset, crate::stream::reject_name(reason), data.len(), id);
                Ok(Py::new(py, e)?.into_any())
            }
            Err(issue) => Ok(Py::new(py, issue_event(py, offset, data, &issue, id)?)?.into_any()),
        }
    }

    fn __repr__(&self) -> String {
        format!("Spec({:?}, name={:?})", self.path, self.name())
    }
}

impl Spec {
    fn first_can_format(&self) -> Option<usize> {
        let p = self.codec().protocol();
        p.frames
            .iter()
            .position(|f| matches!(f.transport, Transport::Can { .. }))
    }

    /// The CAN format named, else the spec's first.
    fn can_format(&self, format: Option<&str>) -> PyResult<usize> {
        match self.format_arg(format)? {
            Some(f) => Ok(f),
            None => self
                .first_can_format()
                .ok_or_else(|| PyValueError::new_err("the spec has no CAN frame format")),
        }
    }

    /// The frame of a received identifier and data, for CAN format `fi`: the identifier's
    /// kind as given, else the format's.
    fn can_frame(
        &self,
        fi: usize,
        can_id: u32,
        data: &[u8],
        extended: Option<bool>,
    ) -> PyResult<CanFrame> {
        let p = self.codec().protocol();
        let ext = extended.unwrap_or(matches!(
            p.frames[fi].transport,
            Transport::Can { extended: true }
        ));
        let frame = CanFrame::new(can_id, data)
            .map_err(|e| DecodeError::new_err(format!("not a CAN frame: {e}")))?;
        Ok(CanFrame {
            extended: ext,
            ..frame
        })
    }
}

/// The frame object the codec encodes: `command`, `header`, `payload`, `format`, `direction`.
fn frame_object(
    name: &str,
    fields: Option<&Bound<'_, PyAny>>,
    header: Option<&Bound<'_, PyAny>>,
    format: Option<&str>,
    direction: Option<&str>,
    kwargs: Option<&Bound<'_, PyDict>>,
) -> PyResult<Value> {
    let mut payload = match fields.map(|f| from_py(f, "payload")).transpose()? {
        None | Some(Value::Null) => Fields::new(),
        Some(Value::Struct(f)) => f,
        Some(_) => return Err(EncodeError::new_err("`payload`: expected a dict of fields")),
    };
    if let Some(kw) = kwargs {
        for (k, v) in kw.iter() {
            let key: String = k.extract()?;
            let value = from_py(&v, &format!("payload.{key}"))?;
            payload.insert(key, value);
        }
    }
    let mut object = Fields::new();
    object.insert("command", Value::from(name));
    if let Some(h) = header {
        object.insert("header", from_py(h, "header")?);
    }
    object.insert("payload", Value::Struct(payload));
    if let Some(f) = format {
        object.insert("format", Value::from(f));
    }
    if let Some(d) = direction {
        object.insert("direction", Value::from(d));
    }
    Ok(Value::Struct(object))
}
