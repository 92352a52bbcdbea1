//! `protocol_link`: the run-time codec of `protocol` specs as a Python package.
//!
//! A thin face over `protocol-dynamic`: [`spec::Spec`] loads a spec and decodes and encodes
//! its frames, [`stream::StreamDecoder`] finds them in a byte stream, [`message`] holds what a
//! decode gives Python, [`convert`] maps values to and from Python objects. The readers of
//! files, CAN logs, serial ports and asyncio streams, and the columnar export, are Python
//! (`protocol_link/*.py`), on top of these.

mod convert;
mod message;
mod spec;
mod stream;

use pyo3::create_exception;
use pyo3::exceptions::PyValueError;

create_exception!(
    protocol_link,
    SpecError,
    PyValueError,
    "A spec could not be read or has errors. `str(e)` is the report the `protocol` command prints (every error, located, with its line and a caret); `e.diagnostics` lists each error as a dict (severity, message, help, path, line, column, rendered)."
);
create_exception!(
    protocol_link,
    DecodeError,
    PyValueError,
    "No valid frame of a message of the spec: a framing or check error, an unknown command, a payload that does not fit its command."
);
create_exception!(
    protocol_link,
    EncodeError,
    PyValueError,
    "A message could not be encoded. `e.path` names the offending value (`payload.lat`, `header.seq`, `command`)."
);

/// The run-time codec of `protocol` specs.
#[pyo3::pymodule]
mod _native {
    #[pymodule_export]
    use super::message::{Event, Message, Record};
    #[pymodule_export]
    use super::spec::Spec;
    #[pymodule_export]
    use super::stream::StreamDecoder;
    #[pymodule_export]
    use super::{DecodeError, EncodeError, SpecError};
}
