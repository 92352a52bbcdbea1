//! Values between the run-time codec's [`Value`] and Python objects.
//!
//! This module owns the Python face of the value model: integers are `int`, floats `float` (an
//! `f32` as the shortest decimal that reads back as the same bits, the number `protocol decode`
//! prints), enum variants `str`, bytes `bytes`, arrays `list`, absent optional fields `None`.
//! A struct is a [`Record`] (attribute access) when a message is read, and a `dict` in
//! `to_dict()`. It does not decide how a value is encoded: a Python object becomes the
//! [`Value`] that the codec's own checks accept or refuse, naming the field.

use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};
use std::sync::Mutex;

use protocol_dynamic::{Fields, Value};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyBytes, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};

use crate::message::Record;
use pyo3::type_object::PyTypeInfo;

/// How a struct becomes a Python object.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Shape {
    /// A [`Record`], its fields converted as they are read.
    Record,
    /// A `dict`, all the way down.
    Dict,
}

/// An `f32` as the `f64` of the decimal `protocol decode` prints for it: `serde_json`'s
/// shortest text that reads back as the same `f32` (`0.1f32` is `0.1`, not
/// `0.10000000149011612`; of two shortest texts, the one JSON prints). Non-finite values stay
/// what they are.
fn f32_as_f64(x: f32) -> f64 {
    if !x.is_finite() {
        return f64::from(x);
    }
    serde_json::to_string(&x)
        .ok()
        .and_then(|t| t.parse().ok())
        .unwrap_or(f64::from(x))
}

/// The Python object of a value.
pub fn to_py<'py>(py: Python<'py>, value: &Value, shape: Shape) -> PyResult<Bound<'py, PyAny>> {
    Ok(match value {
        Value::Null => py.None().into_bound(py),
        Value::Bool(b) => PyBool::new(py, *b).to_owned().into_any(),
        Value::UInt(u) => u.into_pyobject(py)?.into_any(),
        Value::Int(i) => i.into_pyobject(py)?.into_any(),
        Value::F32(x) => PyFloat::new(py, f32_as_f64(*x)).into_any(),
        Value::F64(x) => PyFloat::new(py, *x).into_any(),
        Value::String(s) => PyString::new(py, s).into_any(),
        Value::Bytes(b) => PyBytes::new(py, b).into_any(),
        Value::Array(items) => {
            let list = PyList::empty(py);
            for item in items {
                list.append(to_py(py, item, shape)?)?;
            }
            list.into_any()
        }
        Value::Struct(fields) => match shape {
            Shape::Record => Bound::new(py, Record::new(fields.clone()))?.into_any(),
            Shape::Dict => fields_to_dict(py, fields)?.into_any(),
        },
    })
}

/// A `dict` of a struct's fields, in spec order, nested structs as `dict`s.
pub fn fields_to_dict<'py>(py: Python<'py>, fields: &Fields) -> PyResult<Bound<'py, PyDict>> {
    let dict = PyDict::new(py);
    for (k, v) in fields.iter() {
        dict.set_item(key(py, k), to_py(py, v, Shape::Dict)?)?;
    }
    Ok(dict)
}

/// Field names kept as Python strings, at most this many: a process that loads spec after spec
/// keeps the names of the first ones and makes the others' anew.
const KEYS_KEPT: usize = 1 << 16;

/// FNV-1a: field names are short, and SipHash costs more than the lookup it serves.
struct Fnv(u64);

impl Default for Fnv {
    fn default() -> Self {
        Fnv(0xcbf2_9ce4_8422_2325)
    }
}

impl Hasher for Fnv {
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = (self.0 ^ u64::from(b)).wrapping_mul(0x100_0000_01b3);
        }
    }

    fn finish(&self) -> u64 {
        self.0
    }
}

type KeyMap = HashMap<Box<str>, Py<PyString>, BuildHasherDefault<Fnv>>;

/// A field name as an interned Python `str`, made once for the process: the dicts of a
/// stream's messages take the same names again and again, and making, hashing and interning
/// each anew is about 40% of what `to_dict()` costs.
fn key<'py>(py: Python<'py>, name: &str) -> Bound<'py, PyString> {
    static KEYS: Mutex<Option<KeyMap>> = Mutex::new(None);
    // Taken with the GIL held; nothing done under the lock releases the GIL.
    let Ok(mut keys) = KEYS.lock() else {
        return PyString::intern(py, name);
    };
    let keys = keys.get_or_insert_with(KeyMap::default);
    if let Some(k) = keys.get(name) {
        return k.bind(py).clone();
    }
    let k = PyString::intern(py, name);
    if keys.len() < KEYS_KEPT {
        keys.insert(name.into(), k.clone().unbind());
    }
    k
}

/// The value of a Python object: `None`, `bool`, `int`, `float`, `str`, `bytes` (and
/// `bytearray`, `memoryview`), a sequence, a mapping or a [`Record`]; anything with `__index__`
/// or `__float__` (NumPy scalars) as a number.
///
/// # Errors
/// `TypeError` for an object of another type, or an integer beyond 64 bits, naming `path`.
pub fn from_py(obj: &Bound<'_, PyAny>, path: &str) -> PyResult<Value> {
    if obj.is_none() {
        return Ok(Value::Null);
    }
    if let Ok(b) = obj.cast::<PyBool>() {
        return Ok(Value::Bool(b.is_true()));
    }
    if obj.is_instance_of::<PyInt>() {
        return int_value(obj, path);
    }
    if let Ok(f) = obj.cast::<PyFloat>() {
        return Ok(Value::F64(f.value()));
    }
    if let Ok(s) = obj.cast::<PyString>() {
        return Ok(Value::String(s.extract::<String>()?));
    }
    if let Ok(b) = obj.cast::<PyBytes>() {
        return Ok(Value::Bytes(b.as_bytes().to_vec()));
    }
    if let Ok(r) = obj.cast::<Record>() {
        return Ok(Value::Struct(r.get().fields().clone()));
    }
    if let Ok(d) = obj.cast::<PyDict>() {
        return dict_value(d, path);
    }
    if obj.is_instance_of::<PyList>() || obj.is_instance_of::<PyTuple>() {
        return sequence_value(obj, path);
    }
    other_value(obj, path)
}

/// An `int` as the value the codec range-checks: unsigned when it is not negative.
fn int_value(obj: &Bound<'_, PyAny>, path: &str) -> PyResult<Value> {
    if let Ok(u) = obj.extract::<u64>() {
        return Ok(Value::UInt(u));
    }
    if let Ok(i) = obj.extract::<i64>() {
        return Ok(Value::Int(i));
    }
    Err(PyTypeError::new_err(format!(
        "`{path}`: {obj} does not fit 64 bits"
    )))
}

fn dict_value(d: &Bound<'_, PyDict>, path: &str) -> PyResult<Value> {
    let mut fields = Fields::new();
    for (k, v) in d.iter() {
        let key: String = k.str()?.extract()?;
        let inner = join(path, &key);
        fields.insert(key, from_py(&v, &inner)?);
    }
    Ok(Value::Struct(fields))
}

fn sequence_value(obj: &Bound<'_, PyAny>, path: &str) -> PyResult<Value> {
    let mut items = Vec::new();
    for (i, item) in obj.try_iter()?.enumerate() {
        items.push(from_py(&item?, &format!("{path}[{i}]"))?);
    }
    Ok(Value::Array(items))
}

/// `bytearray`, `memoryview`, mappings, other sequences and numbers of other libraries.
fn other_value(obj: &Bound<'_, PyAny>, path: &str) -> PyResult<Value> {
    let py = obj.py();
    if obj.is_instance(&py.get_type::<pyo3::types::PyByteArray>())?
        || obj.is_instance(&py.get_type::<pyo3::types::PyMemoryView>())?
    {
        let bytes = PyBytes::type_object(py).call1((obj,))?;
        return from_py(&bytes, path);
    }
    if obj.hasattr("__index__")? {
        return int_value(&obj.call_method0("__index__")?, path);
    }
    if obj.hasattr("__float__")? {
        return Ok(Value::F64(obj.call_method0("__float__")?.extract()?));
    }
    if obj.hasattr("keys")? {
        let dict = PyDict::type_object(py).call1((obj,))?;
        return dict_value(dict.cast()?, path);
    }
    if obj.hasattr("__iter__")? {
        return sequence_value(obj, path);
    }
    Err(PyTypeError::new_err(format!(
        "`{path}`: cannot encode a value of type {}",
        obj.get_type().name()?
    )))
}

/// `path.key`, or `key` at the top.
fn join(path: &str, key: &str) -> String {
    if path.is_empty() {
        key.to_owned()
    } else {
        format!("{path}.{key}")
    }
}
