//! What a decode gives Python: a [`Message`] (a frame and its decoded command), a [`Record`]
//! (a struct's fields, by attribute), and an [`Event`] (what a stream reports besides
//! messages: rejected candidates, skipped bytes, frames that hold no message of the spec).
//!
//! A message keeps the codec's [`Decoded`] value and converts a field to a Python object when
//! it is read, so decoding a stream costs one small object per frame; `to_dict()` converts it
//! all, in the shape of a line of `protocol decode --format json`.

use std::sync::Arc;

use protocol_dynamic::{Decoded, Fields, Value};
use pyo3::exceptions::{PyAttributeError, PyKeyError};
use pyo3::intern;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyList, PyString, PyTuple};

use crate::convert::{Shape, fields_to_dict, to_py};
use crate::spec::Linked;

/// The fields of a struct (a header, a payload, a nested struct), read by attribute
/// (`rec.lat`) or by key (`rec["lat"]`), in spec order.
#[pyclass(frozen, module = "protocol_link", mapping)]
pub struct Record {
    fields: Fields,
}

impl Record {
    /// A record of `fields`.
    pub fn new(fields: Fields) -> Self {
        Record { fields }
    }

    /// The fields.
    pub fn fields(&self) -> &Fields {
        &self.fields
    }
}

#[pymethods]
impl Record {
    fn __getattr__<'py>(&self, py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyAny>> {
        match self.fields.get(name) {
            Some(v) => to_py(py, v, Shape::Record),
            None => Err(PyAttributeError::new_err(format!(
                "no field `{name}` (fields: {})",
                self.fields.keys().collect::<Vec<_>>().join(", ")
            ))),
        }
    }

    fn __getitem__<'py>(&self, py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyAny>> {
        match self.fields.get(name) {
            Some(v) => to_py(py, v, Shape::Record),
            None => Err(PyKeyError::new_err(name.to_owned())),
        }
    }

    fn __contains__(&self, name: &str) -> bool {
        self.fields.get(name).is_some()
    }

    fn __len__(&self) -> usize {
        self.fields.len()
    }

    fn __iter__<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.keys(py)?.try_iter().map(Bound::into_any)
    }

    fn __dir__(&self) -> Vec<String> {
        self.fields.keys().map(str::to_owned).collect()
    }

    fn __eq__(&self, py: Python<'_>, other: &Bound<'_, PyAny>) -> PyResult<bool> {
        let mine = fields_to_dict(py, &self.fields)?;
        match other.cast::<Record>() {
            Ok(r) => mine.eq(fields_to_dict(py, r.get().fields())?),
            Err(_) => mine.eq(other),
        }
    }

    fn __repr__(&self, py: Python<'_>) -> PyResult<String> {
        let mut parts = Vec::new();
        for (k, v) in self.fields.iter() {
            parts.push(format!("{k}={}", to_py(py, v, Shape::Record)?.repr()?));
        }
        Ok(format!("Record({})", parts.join(", ")))
    }

    /// The field names, in spec order.
    fn keys<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        PyList::new(py, self.fields.keys())
    }

    /// The field values, in spec order.
    fn values<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let list = PyList::empty(py);
        for (_, v) in self.fields.iter() {
            list.append(to_py(py, v, Shape::Record)?)?;
        }
        Ok(list)
    }

    /// `(name, value)` pairs, in spec order.
    fn items<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let list = PyList::empty(py);
        for (k, v) in self.fields.iter() {
            list.append(PyTuple::new(
                py,
                [
                    PyString::new(py, k).into_any(),
                    to_py(py, v, Shape::Record)?,
                ],
            )?)?;
        }
        Ok(list)
    }

    /// The field's value, or `default` when there is no such field.
    #[pyo3(signature = (name, default=None))]
    fn get<'py>(
        &self,
        py: Python<'py>,
        name: &str,
        default: Option<Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        match self.fields.get(name) {
            Some(v) => to_py(py, v, Shape::Record),
            None => Ok(default.unwrap_or_else(|| py.None().into_bound(py))),
        }
    }

    /// The fields as a `dict`, nested structs as `dict`s.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        fields_to_dict(py, &self.fields)
    }
}

/// A frame and the message it carries.
///
/// `name` is the command (`None` for an acknowledgement or a frame format without commands),
/// `header` and `payload` its values; a payload field is also an attribute of the message
/// itself (`msg.lat` is `msg.payload.lat`), as in pymavlink and pyubx2.
#[pyclass(frozen, module = "protocol_link")]
pub struct Message {
    spec: Arc<Linked>,
    decoded: Decoded,
    offset: u64,
    raw: Vec<u8>,
}

impl Message {
    /// A message decoded from `raw`, found at `offset` of its stream.
    pub fn new(spec: Arc<Linked>, decoded: Decoded, offset: u64, raw: Vec<u8>) -> Self {
        Message {
            spec,
            decoded,
            offset,
            raw,
        }
    }

    fn payload_fields(&self) -> Option<&Fields> {
        self.decoded.payload.as_struct()
    }
}

#[pymethods]
impl Message {
    /// The command's name; `None` for an acknowledgement or a frame without command.
    #[getter]
    fn name(&self) -> Option<&str> {
        let p = self.spec.borrow_owner().protocol();
        self.decoded
            .command
            .and_then(|c| p.commands.get(c))
            .map(|c| c.name.as_str())
    }

    /// The name of the frame format it came in.
    #[getter]
    fn format(&self) -> &str {
        let p = self.spec.borrow_owner().protocol();
        p.frames
            .get(self.decoded.format)
            .map_or("", |f| f.name.as_str())
    }

    /// The dispatch key's value (a tuple for a key of several fields); `None` without command.
    #[getter]
    fn id<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        if self.decoded.command.is_none() {
            return Ok(py.None().into_bound(py));
        }
        match self.decoded.id.as_slice() {
            [one] => Ok(one.into_pyobject(py)?.into_any()),
            many => Ok(PyTuple::new(py, many)?.into_any()),
        }
    }

    /// The direction's name, for a spec with directions.
    #[getter]
    fn direction(&self) -> Option<&str> {
        let p = self.spec.borrow_owner().protocol();
        self.decoded
            .direction
            .and_then(|d| p.directions.get(d))
            .map(|d| d.name.as_str())
    }

    /// True for an acknowledgement (its payload is its data, as bytes).
    #[getter]
    fn ack(&self) -> bool {
        self.decoded.ack
    }

    /// The CAN identifier, for a frame of a CAN format.
    #[getter]
    fn can_id(&self) -> Option<u64> {
        self.decoded.can_id
    }

    /// Offset of the frame's first byte in its stream (the record's index in a CAN log).
    #[getter]
    fn offset(&self) -> u64 {
        self.offset
    }

    /// The frame's bytes as received (a CAN frame's data bytes).
    #[getter]
    fn raw<'py>(&self, py: Python<'py>) -> Bound<'py, PyBytes> {
        PyBytes::new(py, &self.raw)
    }

    /// The header's values the spec leaves to the sender (sequence, addresses, flags).
    #[getter]
    fn header(&self, py: Python<'_>) -> PyResult<Py<Record>> {
        Py::new(py, Record::new(self.decoded.header.clone()))
    }

    /// The payload: a [`Record`] of the command's fields, or `bytes` (an acknowledgement's
    /// data, the payload of a format without commands).
    #[getter]
    fn payload<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_py(py, &self.decoded.payload, Shape::Record)
    }

    fn __getattr__<'py>(&self, py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyAny>> {
        match self.payload_fields().and_then(|f| f.get(name)) {
            Some(v) => to_py(py, v, Shape::Record),
            None => Err(PyAttributeError::new_err(format!(
                "{} has no field `{name}`",
                self.name().unwrap_or("this frame")
            ))),
        }
    }

    fn __dir__(&self) -> Vec<String> {
        let own = [
            "name",
            "format",
            "id",
            "direction",
            "ack",
            "can_id",
            "offset",
            "raw",
            "header",
            "payload",
            "to_dict",
            "to_json",
        ];
        let fields = self.payload_fields().into_iter().flat_map(Fields::keys);
        own.into_iter().chain(fields).map(str::to_owned).collect()
    }

    fn __repr__(&self, py: Python<'_>) -> PyResult<String> {
        let header = Record::new(self.decoded.header.clone()).__repr__(py)?;
        let payload = to_py(py, &self.decoded.payload, Shape::Record)?.repr()?;
        Ok(format!(
            "Message(name={}, header={header}, payload={payload})",
            self.name()
                .map_or_else(|| "None".to_owned(), |n| format!("{n:?}"))
        ))
    }

    /// The message as a `dict` in the shape of a line of `protocol decode --format json`:
    /// `offset`, `length`, `format`, `command`, `id`, `header`, `payload`, `hex` (and
    /// `direction`, `ack`, `can_id` where they apply). Bytes stay `bytes` and non-finite
    /// floats stay `float`; `hex` is the frame's bytes as hex text.
    ///
    /// Built here rather than from the codec's frame value (as `to_json` is), which would copy
    /// every field first; the package's tests hold the two to the same lines.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let p = self.spec.borrow_owner().protocol();
        let d = PyDict::new(py);
        d.set_item(intern!(py, "offset"), self.offset)?;
        d.set_item(intern!(py, "length"), self.raw.len())?;
        d.set_item(intern!(py, "format"), self.format())?;
        // A direction no header field tells is part of the frame's value (encode reads it).
        if p.directions_given() {
            if let Some(dir) = self.direction() {
                d.set_item(intern!(py, "direction"), dir)?;
            }
        }
        if let Some(name) = self.name() {
            d.set_item(intern!(py, "command"), name)?;
            let id = match self.decoded.id.as_slice() {
                [one] => one.into_pyobject(py)?.into_any(),
                many => PyList::new(py, many)?.into_any(),
            };
            d.set_item(intern!(py, "id"), id)?;
        }
        if self.decoded.ack {
            d.set_item(intern!(py, "ack"), true)?;
        }
        if let Some(can_id) = self.decoded.can_id {
            d.set_item(intern!(py, "can_id"), can_id)?;
        }
        d.set_item(
            intern!(py, "header"),
            fields_to_dict(py, &self.decoded.header)?,
        )?;
        let payload = to_py(py, &self.decoded.payload, Shape::Dict)?;
        d.set_item(intern!(py, "payload"), payload)?;
        d.set_item(intern!(py, "hex"), hex_text(&self.raw))?;
        Ok(d)
    }

    /// The line `protocol decode --format json` prints for this frame.
    fn to_json(&self) -> PyResult<String> {
        serde_json::to_string(&self.frame_value())
            .map_err(|e| pyo3::exceptions::PyValueError::new_err(e.to_string()))
    }
}

/// Lowercase hex of some bytes.
fn hex_text(bytes: &[u8]) -> String {
    const DIGITS: &[u8; 16] = b"0123456789abcdef";
    // Two ASCII digits a byte, collected as bytes: no character is encoded one at a time.
    let digits: Vec<u8> = bytes
        .iter()
        .flat_map(|b| [DIGITS[usize::from(b >> 4)], DIGITS[usize::from(b & 0xF)]])
        .collect();
    String::from_utf8(digits).unwrap_or_default()
}

impl Message {
    fn frame_value(&self) -> Value {
        self.spec
            .borrow_dependent()
            .frame_value(&self.decoded, self.offset, &self.raw)
    }
}

/// What a stream reports besides messages, as `protocol decode --format json` prints it:
/// `kind` is `skipped`, a rejection (`bad_checksum`, `bad_length`, `bad_header`,
/// `bad_header_check`, `bad_trailer`, `truncated`) or a frame without message
/// (`unknown_command`, `unknown_direction`, `bad_payload`).
#[pyclass(frozen, module = "protocol_link", get_all)]
pub struct Event {
    /// What happened.
    pub kind: String,
    /// Offset of its first byte in the stream (the record's index in a CAN log).
    pub offset: u64,
    /// Bytes it covers.
    pub length: usize,
    /// Why a frame holds no message (`None` for skipped bytes and rejections).
    pub error: Option<String>,
    /// The frame's bytes, for a frame without message.
    pub raw: Option<Py<PyBytes>>,
    /// The command, when the frame's key names one.
    pub command: Option<String>,
    /// The dispatch key's value of an unknown command.
    pub id: Option<Py<PyAny>>,
    /// The CAN identifier, for a CAN record.
    pub can_id: Option<u64>,
}

#[pymethods]
impl Event {
    fn __repr__(&self) -> String {
        let error = self
            .error
            .as_ref()
            .map_or_else(String::new, |e| format!(", error={e:?}"));
        format!(
            "Event(kind={:?}, offset={}, length={}{error})",
            self.kind, self.offset, self.length
        )
    }

    /// The event as a `dict` in the shape of a line of `protocol decode --format json`
    /// (`offset`, `event`, `bytes`, then what applies of `can_id`, `id`, `command`, `error`,
    /// `hex`).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        d.set_item("offset", self.offset)?;
        d.set_item("event", &self.kind)?;
        d.set_item("bytes", self.length)?;
        if let Some(c) = self.can_id {
            d.set_item("can_id", c)?;
        }
        if let Some(id) = &self.id {
            d.set_item("id", id)?;
        }
        if let Some(c) = &self.command {
            d.set_item("command", c)?;
        }
        if let Some(e) = &self.error {
            d.set_item("error", e)?;
        }
        if let Some(raw) = &self.raw {
            d.set_item("hex", hex_text(raw.as_bytes(py)))?;
        }
        Ok(d)
    }
}
